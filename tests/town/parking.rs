//! Parked cars in lay-bys (`parking_density`) in the towns that have them:
//! every parked car lies inside a bay, so off every driving lane; no two
//! overlap; nothing else stands in a bay (sidewalk and kerb slabs cut
//! back, furniture and trees kept out); bays stay off junction corners,
//! crosswalks and stop lines; walkers never step into a bay; a parked car
//! is one static instance id below the moving vehicles' with unlit lamps
//! and no head-lights; all of it a pure function of the seed.

use std::collections::BTreeMap;

use parallax::scene::desc::{ObjectDesc, ShapeDesc};
use parallax::town::layout::{Layout, Rect};
use parallax::town::parking::{footprint, Bay};
use parallax::town::people::{person_prefab, phase_index};
use parallax::town::vehicles::headlights;
use parallax::town::{
    frame_at, StaticTown, TownDesc, FURNITURE_ID_BASE, PEDESTRIAN_ID_BASE, VEHICLE_ID_BASE,
};

use crate::common;
use common::towns::town;

const SEED: u64 = 3;
/// The towns with lay-bys.
const PARKING_TOWNS: [&str; 2] = ["town10", "town05"];

fn objects_and_bays(desc: &TownDesc, seed: u64) -> (Vec<ObjectDesc>, Vec<Bay>) {
    StaticTown::new(desc, seed).objects_and_bays()
}

/// The parked cars' body instances (the prefab holding the paint).
pub(crate) fn parked_bodies(objects: &[ObjectDesc]) -> Vec<&ObjectDesc> {
    objects
        .iter()
        .filter(|o| o.semantic.as_deref() == Some("car"))
        .filter(|o| match &o.shape {
            ShapeDesc::Instance { material_map, .. } => material_map.contains_key("car_paint"),
            _ => false,
        })
        .collect()
}

/// Plan corners of a placed car body (its prefab's footprint about the
/// instance origin, turned by the heading).
pub(crate) fn corners(o: &ObjectDesc) -> [[f64; 2]; 4] {
    let ShapeDesc::Instance { prefab, .. } = &o.shape else {
        panic!("an instance");
    };
    let kind = parallax::town::vehicles::BODIES
        .into_iter()
        .find(|b| b.prefab() == prefab)
        .expect("a vehicle body");
    let [len, w] = kind.footprint_m();
    let t = o.transform.translate.unwrap();
    let h = o.transform.rotate_deg.map_or(0.0, |r| r[2]).to_radians();
    let (s, c) = h.sin_cos();
    [(1.0, 1.0), (1.0, -1.0), (-1.0, -1.0), (-1.0, 1.0)].map(|(a, b)| {
        let (x, y) = (a * len / 2.0, b * w / 2.0);
        [t[0] + c * x - s * y, t[1] + s * x + c * y]
    })
}

fn inside(r: &Rect, q: [f64; 2]) -> bool {
    (0..2).all(|k| q[k] >= r.min[k] - 1e-9 && q[k] <= r.max[k] + 1e-9)
}

/// Whether two convex quads overlap (separating axes of both).
pub(crate) fn quads_overlap(a: &[[f64; 2]; 4], b: &[[f64; 2]; 4]) -> bool {
    for poly in [a, b] {
        for k in 0..4 {
            let (p, q) = (poly[k], poly[(k + 1) % 4]);
            let n = [q[1] - p[1], p[0] - q[0]];
            let proj = |s: &[[f64; 2]; 4]| {
                s.iter()
                    .map(|v| v[0] * n[0] + v[1] * n[1])
                    .fold((f64::MAX, f64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)))
            };
            let ((a0, a1), (b0, b1)) = (proj(a), proj(b));
            if a1 <= b0 || b1 <= a0 {
                return false;
            }
        }
    }
    true
}

#[test]
fn parked_cars_lie_in_bays_off_the_lanes_and_apart() {
    for name in PARKING_TOWNS {
        let desc = town(name);
        let l = Layout::new(&desc);
        let (objects, bays) = objects_and_bays(&desc, SEED);
        let cars = parked_bodies(&objects);
        let fill = cars.len() as f64 / bays.len() as f64;
        assert!(bays.len() > 100, "{name}: {} bays", bays.len());
        assert!(
            (fill - desc.parking_density).abs() < 0.1,
            "{name}: {} cars in {} bays",
            cars.len(),
            bays.len()
        );
        let roads = l.road_rects();
        for b in &bays {
            assert!(
                !roads.iter().any(|r| r.overlaps(&b.rect())),
                "{name}: bay {b:?} on a road"
            );
        }
        let quads: Vec<_> = cars.iter().map(|o| corners(o)).collect();
        for (o, q) in cars.iter().zip(&quads) {
            let home = bays
                .iter()
                .filter(|b| q.iter().all(|&p| inside(&b.rect(), p)));
            assert_eq!(
                home.count(),
                1,
                "{name}: car at {:?}",
                o.transform.translate
            );
        }
        for i in 0..quads.len() {
            for j in i + 1..quads.len() {
                assert!(
                    !quads_overlap(&quads[i], &quads[j]),
                    "{name}: cars {i}, {j}"
                );
            }
        }
    }
}

#[test]
fn nothing_else_stands_in_a_bay_and_bays_keep_off_junctions() {
    for name in PARKING_TOWNS {
        let desc = town(name);
        let l = Layout::new(&desc);
        let (objects, bays) = objects_and_bays(&desc, SEED);
        let (p, hw, sw) = (l.pitch_m, l.road_w_m / 2.0, l.sidewalk_m);
        for b in &bays {
            // The junction square with its corners, crosswalks (0.5–3.5 m
            // out) and stop lines (4 m) lies within hw + sw of its centre.
            let k = (b.along.0 / p).floor();
            assert!(
                b.along.0 >= k * p + hw + sw && b.along.1 <= (k + 1.0) * p - hw - sw,
                "{name}: bay {b:?} in a junction area"
            );
        }
        for o in &objects {
            let mine = matches!(
                (o.semantic.as_deref(), o.material.as_deref()),
                (Some("road"), _) | (Some("road_line"), _) | (Some("terrain"), Some("ground"))
            );
            let parked = o
                .instance
                .is_some_and(|i| parked_id(i) && o.semantic.as_deref() == Some("car"));
            if mine || parked {
                continue;
            }
            let Some(f) = footprint(o) else { continue };
            // Instances are points here: grow them by a post's radius.
            // (Boxes shrunk by 1 µm: a kerb touching a bay is not in it.)
            let f = match o.shape {
                ShapeDesc::Instance { .. } => Rect::centered(f.center(), [0.3, 0.3]),
                _ => Rect {
                    min: f.min.map(|v| v + 1e-6),
                    max: f.max.map(|v| v - 1e-6),
                },
            };
            for b in &bays {
                assert!(
                    !b.rect().overlaps(&f),
                    "{name}: {:?} {:?} at {:?} in bay {b:?}",
                    o.semantic,
                    o.material,
                    o.transform.translate
                );
            }
        }
    }
}

/// Whether instance id `i` is in the static range above the furniture.
fn parked_id(i: u16) -> bool {
    (FURNITURE_ID_BASE..VEHICLE_ID_BASE).contains(&u32::from(i))
}

#[test]
fn walkers_never_step_into_a_bay() {
    // Each look's widest reach about its walking line, every phase.
    let mut half: BTreeMap<u32, [f64; 2]> = BTreeMap::new();
    let desc = town("town10");
    let (_, bays) = objects_and_bays(&desc, SEED);
    let zones: Vec<Rect> = bays
        .iter()
        .map(|b| b.strip(b.along, (b.hw, b.hw + b.depth + 0.15)))
        .collect();
    let mut walkers = 0;
    for frame in (0..600).step_by(37) {
        for w in frame_at(&desc, SEED, frame).pedestrians {
            let reach = *half
                .entry(w.variant * 100 + w.phase.map_or(99, phase_index))
                .or_insert_with(|| {
                    let p = person_prefab(w.variant, w.phase.map(phase_index));
                    let mut m = [0.0f64; 2];
                    for o in &p.objects {
                        if let ShapeDesc::Mesh { positions, .. } = &o.shape {
                            for q in positions {
                                m = [m[0].max(q[0].abs()), m[1].max(q[1].abs())];
                            }
                        }
                    }
                    m
                });
            let h = w.heading_deg.to_radians();
            let (s, c) = h.sin_cos();
            let ext = [
                (c * reach[0]).abs() + (s * reach[1]).abs(),
                (s * reach[0]).abs() + (c * reach[1]).abs(),
            ];
            let body = Rect::centered([w.position[0], w.position[1]], [2.0 * ext[0], 2.0 * ext[1]]);
            walkers += 1;
            for z in &zones {
                assert!(
                    !z.overlaps(&body),
                    "walker {} at {:?} heading {} (reach {reach:?}) in {z:?}",
                    w.variant,
                    w.position,
                    w.heading_deg
                );
            }
        }
    }
    assert!(walkers > 500, "{walkers} walkers checked");
}

#[test]
fn a_parked_car_is_one_static_id_with_unlit_lamps_and_no_headlights() {
    let desc = town("town10");
    let (objects, _) = objects_and_bays(&desc, SEED);
    let furniture_max = objects
        .iter()
        .filter(|o| o.semantic.as_deref() != Some("car"))
        .filter_map(|o| o.instance)
        .filter(|&i| parked_id(i))
        .max()
        .unwrap();
    let mut ids: BTreeMap<u16, Vec<&ObjectDesc>> = BTreeMap::new();
    for o in objects
        .iter()
        .filter(|o| o.semantic.as_deref() == Some("car"))
    {
        let i = o.instance.expect("a parked car has an id");
        assert!(parked_id(i) && i > furniture_max, "id {i}");
        assert!(u32::from(i) < PEDESTRIAN_ID_BASE);
        ids.entry(i).or_default().push(o);
    }
    assert_eq!(ids.len(), parked_bodies(&objects).len());
    for parts in ids.values() {
        // Panels, parts, lamps and a registration, at one pose.
        assert_eq!(parts.len(), 4);
        assert!(parts.iter().all(|p| p.transform == parts[0].transform));
        let lamps = parts
            .iter()
            .find_map(|p| match &p.shape {
                ShapeDesc::Instance {
                    prefab,
                    material_map,
                } if prefab.ends_with("_lamps") => Some(material_map),
                _ => None,
            })
            .expect("a lamps instance");
        for emitter in ["headlight_emit", "taillight_emit"] {
            let to = lamps.get(emitter).expect("mapped");
            assert!(
                !to.ends_with("_emit") && !to.ends_with("_lit"),
                "{emitter} → {to}"
            );
        }
    }
    assert!(headlights(&objects).is_empty(), "parked cars light up");
}

#[test]
fn parking_is_a_pure_function_of_the_seed() {
    let desc = town("town05");
    let (a, ba) = objects_and_bays(&desc, SEED);
    let (b, bb) = objects_and_bays(&desc, SEED);
    assert_eq!(ba, bb);
    assert_eq!(a, b);
    let (c, _) = objects_and_bays(&desc, SEED + 1);
    let poses = |o: &[ObjectDesc]| -> Vec<_> {
        parked_bodies(o)
            .iter()
            .map(|o| o.transform.clone())
            .collect()
    };
    assert_ne!(poses(&a), poses(&c));
    // Without the key: no bays, no parked cars, the sidewalks whole.
    let plain = TownDesc {
        parking_density: 0.0,
        ..desc.clone()
    };
    let (o, bays) = objects_and_bays(&plain, SEED);
    assert!(bays.is_empty() && parked_bodies(&o).is_empty());
}
