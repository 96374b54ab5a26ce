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

/// Triangles of every prefab of a model (panels, parts, one plate).
fn triangles_of(kind: BodyKind) -> [usize; 3] {
    let prefabs = vehicle_prefabs();
    let count = |name: &str| -> usize {
        let p = prefabs.iter().find(|p| p.name == name).unwrap();
        meshes(&p.objects).map(|(_, _, t)| t.len()).sum()
    };
    let plate = kind.plate_prefab(0).map_or(0, |p| count(&p));
    let lamps = count(&kind.lamps_prefab());
    assert!(
        lamps <= 800,
        "{kind:?}: {lamps} emitter triangles, kept flat per vehicle"
    );
    [
        count(kind.prefab()),
        count(&kind.parts_prefab()) + lamps,
        plate,
    ]
}

#[test]
fn a_grown_car_has_at_least_20000_triangles_and_no_model_too_many() {
    for kind in BODIES {
        let [paint, parts, plate] = triangles_of(kind);
        eprintln!("{kind:?}: {paint} painted + {parts} parts + {plate} plate");
        let total = paint + parts + plate;
        if !matches!(kind, BodyKind::Motorcycle | BodyKind::Bicycle) {
            assert!(total >= 20_000, "{kind:?}: {total} triangles");
        }
        // Painted panels repeat per paint (a prototype each): keep them lean.
        assert!(
            paint <= 16_000 && total <= 60_000,
            "{kind:?}: {paint}, {total}"
        );
    }
}

