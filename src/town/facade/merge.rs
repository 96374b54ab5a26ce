//! Merges a prefab's boxes and quads into one inline mesh per (material, class,
//! instance id): a bay of twenty boxes becomes a handful of meshes with
//! the same triangles, so a town of many placed bays holds far fewer
//! geometries. Other shapes pass through unchanged, in order after the
//! merged meshes.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::scene::desc::{ObjectDesc, ShapeDesc};
use crate::scene::mesh::{cuboid, quad, LocalMesh};
use crate::scene::transform::{parent_from_local, repeat_offsets};

/// `objects` with every box and quad (any transform, any repeats) merged into one
/// mesh object per (material, semantic, instance), first-seen order.
pub fn merge_boxes(objects: Vec<ObjectDesc>) -> Vec<ObjectDesc> {
    type Key = (Option<String>, Option<String>, Option<u16>);
    let mut order: Vec<Key> = Vec::new();
    let mut meshes: BTreeMap<Key, LocalMesh> = BTreeMap::new();
    let mut rest = Vec::new();
    for o in objects {
        let block = match o.shape {
            ShapeDesc::Box { size } => cuboid(size),
            ShapeDesc::Quad { size } => quad(size),
            _ => {
                rest.push(o);
                continue;
            }
        };
        let key = (o.material.clone(), o.semantic.clone(), o.instance);
        if !meshes.contains_key(&key) {
            order.push(key.clone());
        }
        let mesh = meshes.entry(key).or_default();
        let local = parent_from_local(&o.transform);
        for offset in repeat_offsets(&o.repeat) {
            let base = mesh.positions.len() as u32;
            let moved = block
                .positions
                .iter()
                .map(|p| local.transform_point3(*p) + offset);
            mesh.positions.extend(moved.collect::<Vec<DVec3>>());
            mesh.triangles
                .extend(block.triangles.iter().map(|t| t.map(|i| i + base)));
        }
    }
    let mut out: Vec<ObjectDesc> = order
        .into_iter()
        .map(|key| {
            let mesh = meshes.remove(&key).unwrap_or_default();
            ObjectDesc {
                name: None,
                material: key.0,
                semantic: key.1,
                instance: key.2,
                transform: Default::default(),
                repeat: Vec::new(),
                shape: mesh.into_shape(),
            }
        })
        .collect();
    out.extend(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::town::parts::{class, cuboid as box_at, cylinder, repeated};

    #[test]
    fn merged_boxes_keep_every_corner_and_group_by_material() {
        let b = class("building");
        let mut turned = box_at([1.0, 2.0, 3.0], [5.0, 0.0, 0.0], 90.0, "a", b);
        turned.transform.rotate_deg = Some([0.0, 0.0, 90.0]);
        let objects = vec![
            repeated(
                box_at([1.0, 1.0, 1.0], [0.0, 0.0, 0.5], 0.0, "a", b),
                &[(3, [2.0, 0.0, 0.0])],
            ),
            cylinder(0.1, 1.0, 8, [0.0; 3], "a", b),
            box_at([1.0, 1.0, 1.0], [0.0, 9.0, 0.5], 0.0, "b", b),
            turned,
        ];
        let out = merge_boxes(objects);
        assert_eq!(out.len(), 3);
        assert!(matches!(out[2].shape, ShapeDesc::Cylinder { .. }));
        let ShapeDesc::Mesh {
            positions,
            triangles,
            ..
        } = &out[0].shape
        else {
            panic!()
        };
        assert_eq!(out[0].material.as_deref(), Some("a"));
        // Three repeats and the turned box: 4 × 12 triangles.
        assert_eq!(triangles.len(), 48);
        let has = |p: [f64; 3]| {
            positions
                .iter()
                .any(|q| (0..3).all(|k| (q[k] - p[k]).abs() < 1e-12))
        };
        assert!(has([4.5, 0.5, 1.0]) && has([-0.5, -0.5, 0.0]));
        // The turned box: 1 × 2 × 3 about (5, 0, 0), x and y swapped.
        assert!(has([6.0, 0.5, 1.5]) && has([4.0, -0.5, -1.5]));
        assert!(!has([5.5, 1.0, 1.5]));
    }
}
