//! Checks that depend on instancing, run on the flattened object tree:
//! every material name resolves after the enclosing `material_map`s, every
//! `material_map` key is used, and spheres stay spheres under enclosing
//! transforms. Reports which materials are in use (for the "no light" check).

use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::Path;

use super::desc::{MaterialDesc, SceneDesc, ShapeDesc};
use super::load::{SceneError, SceneErrorKind};
use super::obj::ObjAsset;
use super::walk::walk;

type MapRef = *const BTreeMap<String, String>;

/// Resolves every material reference of the placed objects against `table`
/// (the scene's materials in index order); returns which entries are used.
pub fn check_references(
    desc: &SceneDesc,
    objs: &BTreeMap<String, ObjAsset>,
    table: &[&MaterialDesc],
    file: &Path,
) -> Result<Vec<bool>, SceneError> {
    let err = |key: String, msg: String| SceneError::at(file, SceneErrorKind::Invalid, key, msg);
    let index: HashMap<&str, usize> = table
        .iter()
        .enumerate()
        .map(|(i, m)| (m.name.as_str(), i))
        .collect();
    let mut used = vec![false; table.len()];
    // Maps that enclose at least one object, and the (map, key) pairs applied.
    let mut seen: HashSet<MapRef> = HashSet::new();
    let mut applied: HashSet<(MapRef, String)> = HashSet::new();
    walk(desc, false, &mut |placed| {
        seen.extend(placed.maps.iter().map(|&m| m as MapRef));
        let mut resolve = |name: &str, key: String| -> Result<usize, SceneError> {
            // Innermost map first, as `Placed::map_material`.
            let mut mapped = name.to_string();
            for &map in placed.maps.iter().rev() {
                if let Some(to) = map.get(&mapped) {
                    applied.insert((map as MapRef, mapped.clone()));
                    mapped = to.clone();
                }
            }
            index.get(mapped.as_str()).copied().ok_or_else(|| {
                let shown = if mapped == name {
                    format!("\"{name}\"")
                } else {
                    format!("\"{mapped}\" (mapped from \"{name}\")")
                };
                err(key, format!("unknown material {shown}"))
            })
        };
        let mkey = format!("{}.material{}", placed.key, placed.via);
        match (&placed.object.shape, &placed.object.material) {
            (_, Some(m)) => used[resolve(m, mkey)?] = true,
            (ShapeDesc::Obj { file: f }, None) => {
                let asset = &objs[f];
                for g in &asset.groups {
                    let Some(mi) = g.material else {
                        let msg = format!("OBJ {f} has faces without `usemtl`; set `material`");
                        return Err(err(mkey, msg));
                    };
                    used[resolve(&asset.materials[mi].name, mkey.clone())?] = true;
                }
            }
            _ => {}
        }
        if let ShapeDesc::Sphere { .. } = placed.object.shape {
            // Columns of the linear part must be orthogonal with equal lengths.
            let m = placed.world_from_local.matrix3;
            let (a, b, c) = (m.x_axis, m.y_axis, m.z_axis);
            let s = a.length();
            let tol = 1e-9 * s;
            let similar = (b.length() - s).abs() <= tol
                && (c.length() - s).abs() <= tol
                && a.dot(b).abs() <= tol * s
                && a.dot(c).abs() <= tol * s
                && b.dot(c).abs() <= tol * s;
            if !similar {
                let msg = "a sphere's enclosing transforms must scale uniformly".to_string();
                return Err(err(format!("{}{}", placed.key, placed.via), msg));
            }
        }
        Ok(())
    })?;
    check_maps_used(desc, &seen, &applied, file)?;
    Ok(used)
}

/// A `material_map` key that renames nothing is almost always a typo.
fn check_maps_used(
    desc: &SceneDesc,
    seen: &HashSet<MapRef>,
    applied: &HashSet<(MapRef, String)>,
    file: &Path,
) -> Result<(), SceneError> {
    for (key, o) in super::validate::all_objects(desc) {
        let ShapeDesc::Instance {
            prefab,
            material_map,
        } = &o.shape
        else {
            continue;
        };
        let map = material_map as MapRef;
        if !seen.contains(&map) {
            continue; // inside a prefab that is never placed
        }
        if let Some(from) = material_map
            .keys()
            .find(|k| !applied.contains(&(map, (*k).clone())))
        {
            return Err(SceneError::at(
                file,
                SceneErrorKind::Invalid,
                format!("{key}.material_map.{from}"),
                format!("no object of prefab \"{prefab}\" uses material \"{from}\""),
            ));
        }
    }
    Ok(())
}
