//! Vehicle prefabs: every part inside the footprint and above the ground,
//! closed outward bodies, lamps facing out, triangle budgets per model.

use super::*;
use crate::scene::desc::{ObjectDesc, ShapeDesc};

fn meshes(objects: &[ObjectDesc]) -> impl Iterator<Item = (&str, &Vec<[f64; 3]>, &Vec<[u32; 3]>)> {
    objects.iter().map(|o| match &o.shape {
        ShapeDesc::Mesh {
            positions,
            triangles,
            ..
        } => (o.material.as_deref().unwrap_or(""), positions, triangles),
        other => panic!("a vehicle prefab is meshes, not {other:?}"),
    })
}

#[test]
fn every_part_stays_inside_the_footprint_and_above_the_ground() {
    let mut bad = Vec::new();
    for p in vehicle_prefabs() {
        let kind = BODIES
            .iter()
            .find(|b| p.name.starts_with(b.prefab()))
            .unwrap();
        let [len, w] = kind.footprint_m();
        for (mat, pos, _) in meshes(&p.objects) {
            for q in pos {
                let inside =
                    q[0].abs() <= len / 2.0 + 1e-9 && q[1].abs() <= w / 2.0 + 1e-9 && q[2] >= -1e-9;
                if !inside {
                    bad.push(format!(
                        "{}: {mat} vertex {q:?} outside {len} × {w}",
                        p.name
                    ));
                    break;
                }
            }
        }
    }
    assert!(bad.is_empty(), "{bad:#?}");
}
