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

#[test]
fn lofted_bodies_are_closed_outward_solids_of_a_plausible_volume() {
    for kind in BODIES {
        let Some(s) = spec::spec_of(kind) else {
            continue;
        };
        let f = |x: f64, th: f64| s.lower(x, th);
        let hl = s.hl();
        let m = loft::grid(
            &f,
            (-hl, hl, 200),
            (0.0, std::f64::consts::TAU, 64),
            0.0,
            true,
        );
        let v = loft::volume(&m);
        // Between a third and all of the box from the floor to the waist.
        let bound = s.length * s.width * (s.belt_z - s.floor_z);
        assert!(v > bound / 3.0 && v < bound, "{kind:?}: {v} m³ of {bound}");
        // The glass house sits on the lower body: its sills inside it.
        for x in [s.rear_x + 0.2, (s.rear_x + s.ws_x) / 2.0, s.ws_x - 0.2] {
            let [_, y, z] = s.glass(x, 0.0, 0.0);
            assert!(y <= s.lower_half_width_at(x, z) + 1e-9, "{kind:?} at {x}");
            assert!(
                s.roof_z(x) > z && s.roof_z(x) <= s.height + 1e-9,
                "{kind:?} at {x}"
            );
        }
    }
}

#[test]
fn riders_sit_on_two_wheelers_only_hands_ahead_of_hips_feet_below() {
    for kind in BODIES {
        match kind.seat() {
            None => assert!(!matches!(kind, BodyKind::Motorcycle | BodyKind::Bicycle)),
            Some([hip, grip, peg]) => {
                let [len, w] = kind.footprint_m();
                for p in [hip, grip, peg] {
                    assert!(p[0].abs() < len / 2.0 && p[1].abs() < w / 2.0 && p[2] > 0.0);
                }
                assert!(grip[0] > hip[0] + 0.3 && grip[1] > 0.1, "{kind:?}");
                assert!(peg[2] < hip[2] - 0.4 && peg[1] > 0.0, "{kind:?}");
                assert_eq!(hip[1], 0.0);
            }
        }
    }
}

#[test]
fn headlights_are_two_spots_per_car_one_per_two_wheeler_ahead_and_along_the_heading() {
    use crate::scene::desc::LightDesc;
    use crate::town::parts::{class, instance};
    use crate::weather::Weather;
    let objects = vec![
        instance(
            "sedan",
            [10.0, 5.0, 0.0],
            90.0,
            &[("car_paint", "paint_red")],
            class("car"),
        ),
        instance("sedan_parts", [10.0, 5.0, 0.0], 90.0, &[], class("car")),
        instance("bicycle", [0.0, 0.0, 0.0], 0.0, &[], class("bicycle")),
    ];
    let spots = headlights(&objects);
    assert_eq!(spots.len(), 3);
    for l in &spots[..2] {
        let LightDesc::Spot {
            position,
            direction,
            ..
        } = l
        else {
            panic!("spot lights");
        };
        // Heading 90°: forward is +y; the lamps stand ahead of the centre,
        // either side of it, low, and aim along +y, slightly down.
        assert!(
            position[1] > 5.0 + 2.0 && (position[0] - 10.0).abs() > 0.4,
            "{position:?}"
        );
        assert!(position[2] > 0.3 && position[2] < 0.9);
        assert!(direction[1] > 0.99 && direction[2] < 0.0 && direction[0].abs() < 1e-9);
    }
    let weathers: Vec<Weather> = Weather::ALL
        .into_iter()
        .filter(|&w| needs_headlights(w))
        .collect();
    assert_eq!(weathers, [Weather::Night, Weather::Sunset]);
}

#[test]
fn paints_are_drawn_like_real_traffic() {
    use crate::town::materials::{draw_paint, PAINTS};
    let n = 100_000;
    let mut count = std::collections::HashMap::new();
    for k in 0..n {
        *count
            .entry(draw_paint((k as f64 + 0.5) / n as f64))
            .or_insert(0usize) += 1;
    }
    let share = |p: &str| *count.get(p).unwrap_or(&0) as f64 / n as f64;
    let neutral: f64 = ["paint_white", "paint_black", "paint_grey", "paint_silver"]
        .iter()
        .map(|p| share(p))
        .sum();
    assert!((0.75..0.85).contains(&neutral), "{neutral}");
    assert!(share("paint_white") > share("paint_black"));
    assert!(share("paint_blue") + share("paint_red") > 0.1);
    assert!(PAINTS.iter().all(|p| share(p) > 0.005), "{count:?}");
}

#[test]
fn a_dome_is_the_outward_half_of_its_ellipsoid() {
    use crate::scene::mesh::{ellipsoid, ellipsoid_triangles};
    for outward in [1.0, -1.0] {
        let d = lamps::dome([0.05, 0.15, 0.055], 8, 4, outward);
        let full = ellipsoid([0.05, 0.15, 0.055], 8, 4);
        assert_eq!(d.triangles.len() as u64 * 2, ellipsoid_triangles(8, 4));
        assert_eq!(d.positions.len(), d.normals.len());
        // Every vertex on the outward side or on the rim, and the pole
        // kept; every triangle faces outward on the whole.
        assert!(d.positions.iter().all(|p| p.x * outward > -1e-12));
        let pole = full
            .positions
            .iter()
            .map(|p| p.x * outward)
            .fold(0.0, f64::max);
        assert!(d.positions.iter().any(|p| p.x * outward == pole));
        let facing: f64 = d
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| d.positions[i as usize]);
                (b - a).cross(c - a).x * outward
            })
            .sum();
        assert!(facing > 0.0, "{facing}");
    }
}

#[test]
fn car_lamp_lenses_face_out_of_the_body_only() {
    // A lens's inner half would sit in the body, emitting into it.
    for kind in BODIES {
        if spec::spec_of(kind).is_none() {
            continue;
        }
        let prefabs = vehicle_prefabs();
        let p = prefabs
            .iter()
            .find(|p| p.name == kind.lamps_prefab())
            .unwrap();
        for (mat, pos, tris) in meshes(&p.objects) {
            let outward = match mat {
                "headlight_emit" => 1.0,
                "taillight_emit" | "lamp_red" => -1.0,
                _ => continue,
            };
            for t in tris {
                let [a, b, c] = t.map(|i| glam::DVec3::from(pos[i as usize]));
                let n = (b - a).cross(c - a);
                assert!(n.x * outward > 0.0, "{kind:?} {mat}: {n:?}");
            }
        }
    }
}
