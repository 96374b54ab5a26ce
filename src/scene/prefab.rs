//! Prefab graph checks: cycles among instances (rejected with the cycle
//! spelled out) and the triangle estimate, multiplying repeat counts and
//! prefab contents before anything is tessellated.

use std::collections::BTreeMap;
use std::path::Path;

use super::desc::{ObjectDesc, SceneDesc, ShapeDesc};
use super::load::{SceneError, SceneErrorKind};
use super::mesh::{cylinder_triangles, ellipsoid_triangles, keep_nondegenerate};
use super::transform::repeat_count;

/// Rejects prefabs that instance themselves, directly or through others.
/// Precondition: every instanced prefab name exists.
pub fn check_cycles(desc: &SceneDesc, file: &Path) -> Result<(), SceneError> {
    // 0 = unvisited, 1 = on the stack, 2 = done.
    let mut state = vec![0u8; desc.prefabs.len()];
    let mut stack = Vec::new();
    for p in 0..desc.prefabs.len() {
        visit(desc, p, &mut state, &mut stack, file)?;
    }
    Ok(())
}

fn index(desc: &SceneDesc, name: &str) -> Option<usize> {
    desc.prefabs.iter().position(|p| p.name == name)
}

fn visit(
    desc: &SceneDesc,
    p: usize,
    state: &mut [u8],
    stack: &mut Vec<usize>,
    file: &Path,
) -> Result<(), SceneError> {
    match state[p] {
        2 => return Ok(()),
        1 => {
            let start = stack.iter().position(|&q| q == p).unwrap_or(0);
            let names: Vec<&str> = stack[start..]
                .iter()
                .chain([&p])
                .map(|&q| desc.prefabs[q].name.as_str())
                .collect();
            return Err(SceneError::at(
                file,
                SceneErrorKind::Invalid,
                format!("prefab[{p}]"),
                format!("prefab cycle: {}", names.join(" → ")),
            ));
        }
        _ => {}
    }
    state[p] = 1;
    stack.push(p);
    for o in &desc.prefabs[p].objects {
        if let ShapeDesc::Instance { prefab, .. } = &o.shape {
            if let Some(q) = index(desc, prefab) {
                visit(desc, q, state, stack, file)?;
            }
        }
    }
    stack.pop();
    state[p] = 2;
    Ok(())
}

/// Triangles (spheres count one) the objects build into, saturating.
/// `obj_triangles` gives each OBJ file's count; inline meshes count their
/// non-degenerate triangles. Precondition: no cycles.
pub fn estimate_triangles(
    desc: &SceneDesc,
    objects: &[ObjectDesc],
    obj_triangles: &BTreeMap<String, u64>,
) -> u64 {
    let mut memo = vec![None; desc.prefabs.len()];
    estimate(desc, objects, obj_triangles, &mut memo)
}

fn estimate(
    desc: &SceneDesc,
    objects: &[ObjectDesc],
    objs: &BTreeMap<String, u64>,
    memo: &mut Vec<Option<u64>>,
) -> u64 {
    let mut sum = 0u64;
    for o in objects {
        let one = match &o.shape {
            ShapeDesc::Quad { .. } => 2,
            ShapeDesc::Box { .. } => 12,
            ShapeDesc::Sphere { .. } => 1,
            ShapeDesc::Cylinder {
                segments, capped, ..
            } => cylinder_triangles(*segments, *capped),
            ShapeDesc::Ellipsoid {
                segments, rings, ..
            } => ellipsoid_triangles(*segments, *rings),
            ShapeDesc::Obj { file } => objs.get(file).copied().unwrap_or(0),
            // Exact: the data is in hand (0 when an index is out of range,
            // which validation reports).
            ShapeDesc::Mesh {
                positions,
                triangles,
                ..
            } => keep_nondegenerate(positions, triangles).map_or(0, |(t, _)| t.len() as u64),
            ShapeDesc::Instance { prefab, .. } => match index(desc, prefab) {
                // Memoised per prefab: a deep DAG of instances stays linear.
                Some(p) => match memo[p] {
                    Some(n) => n,
                    None => {
                        let n = estimate(desc, &desc.prefabs[p].objects, objs, memo);
                        memo[p] = Some(n);
                        n
                    }
                },
                None => 0,
            },
        };
        sum = sum.saturating_add(one.saturating_mul(repeat_count(&o.repeat)));
    }
    sum
}
