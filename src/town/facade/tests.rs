//! Unit tests of the façade generator: styles, bay geometry (inside the
//! bay, glass recess), ground-floor plans, determinism and reachability.

use std::collections::BTreeSet;

use super::bay::{self, SKIN_M};
use super::front::{self, GroundBay};
use super::ornament;
use super::*;
use crate::scene::desc::ShapeDesc;

fn town(name: &str) -> TownDesc {
    crate::town::source::load_named_town(name, None)
        .unwrap()
        .desc
}

const ID: Label = Label {
    class: "building",
    instance: 1001,
};

/// Axis-aligned bounds of a box or quad part with its repeats (through
/// the merge into a mesh, which places every corner).
fn bounds(o: &ObjectDesc) -> ([f64; 3], [f64; 3]) {
    let merged = merge::merge_boxes(vec![o.clone()]);
    let ShapeDesc::Mesh { positions, .. } = &merged[0].shape else {
        panic!("not a box, quad or mesh: {o:?}");
    };
    assert!(o.transform == Default::default() || !matches!(o.shape, ShapeDesc::Mesh { .. }));
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

#[test]
fn ten_styles_differ_in_name_and_proportions() {
    let names: BTreeSet<&str> = STYLES.iter().map(|s| s.name).collect();
    assert_eq!(names.len(), 10);
    for (i, a) in STYLES.iter().enumerate() {
        for b in &STYLES[i + 1..] {
            let pa = (a.floor_m, a.bay_m, a.window_m, a.sill_m, a.ground);
            let pb = (b.floor_m, b.bay_m, b.window_m, b.sill_m, b.ground);
            assert_ne!(pa, pb, "{} and {}", a.name, b.name);
        }
        // A window fits its bay with a pier either side, and its floor.
        assert!(a.window_m[0] < a.bay_m, "{}", a.name);
        assert!(a.sill_m + a.window_m[1] < a.floor_m, "{}", a.name);
        assert!((0.1..=0.25).contains(&a.recess_m), "{}", a.name);
    }
}

#[test]
fn every_style_is_reachable_and_suits_its_floor_count() {
    let mut seen = BTreeSet::new();
    for name in ["town01", "town02", "town03", "town07", "town10"] {
        let desc = town(name);
        let mut r = Rng::new(&[5, 1]);
        for _ in 0..400 {
            let tower = r.chance(desc.tower_fraction);
            let [lo, hi] = if tower {
                desc.tower_floors
            } else {
                desc.floors
            };
            let floors = r.int(lo, hi);
            let s = style::choose(&desc, floors, tower, &mut r);
            assert!(
                (s.floors[0]..=s.floors[1]).contains(&floors),
                "{name} {floors} {}",
                s.name
            );
            seen.insert(s.name);
        }
    }
    assert_eq!(seen.len(), 10, "{seen:?}");
    // Characters differ: rural town07 never gets an office, town10's towers mostly do.
    let (rural, city) = (town("town07"), town("town10"));
    let mut r = Rng::new(&[9]);
    assert!((0..300).all(|_| style::choose(&rural, 2, false, &mut r).name != "glass_office"));
    let offices = (0..300)
        .filter(|_| style::choose(&city, 20, true, &mut r).name == "glass_office")
        .count();
    assert!(offices > 150, "{offices}");
}

#[test]
fn window_bay_parts_stay_inside_their_bay_and_the_glass_is_recessed() {
    for s in &STYLES {
        for v in 0..bay::VARIANTS {
            let parts = bay::window_bay(s, v);
            let o = bay::window_opening(s);
            for p in &parts {
                let (lo, hi) = bounds(p);
                let eps = 1e-9;
                assert!(
                    lo[0] >= -s.bay_m / 2.0 - eps && hi[0] <= s.bay_m / 2.0 + eps,
                    "{} {p:?}",
                    s.name
                );
                assert!(
                    lo[2] >= -0.07 && hi[2] <= s.floor_m + eps,
                    "{} {p:?}",
                    s.name
                );
                assert!(
                    lo[1] >= -0.06 - eps && hi[1] <= SKIN_M + eps,
                    "{} {p:?}",
                    s.name
                );
            }
            let glass: Vec<_> = parts
                .iter()
                .filter(|p| p.material.as_deref() == Some("facade_glass"))
                .collect();
            assert_eq!(glass.len(), 1);
            let (lo, hi) = bounds(glass[0]);
            // The glass's front face stands exactly recess_m behind the wall.
            assert_eq!(lo[1], s.recess_m, "{}", s.name);
            assert!((hi[0] - lo[0] - s.window_m[0]).abs() < 1e-12);
            assert!((lo[2] - o.z0).abs() < 1e-12 && (hi[2] - o.z1).abs() < 1e-12);
            // Nothing stands between the wall plane and the glass inside the
            // opening (the reveal is clear): no box there, and the rings
            // (wall, frame) have no vertex inside the frame's hole.
            for p in &parts {
                if let ShapeDesc::Mesh { positions, .. } = &p.shape {
                    for q in positions {
                        let hole = q[0].abs() < o.half_w - 0.06 - 1e-9
                            && q[2] > o.z0 + 0.06 + 1e-9
                            && q[2] < o.z1 - 0.06 - 1e-9;
                        assert!(!hole, "{} ring vertex {q:?} in the opening", s.name);
                    }
                    continue;
                }
                let (plo, phi) = bounds(p);
                let inside = plo[0] < -o.half_w + 0.1 && phi[0] > o.half_w - 0.1;
                let in_front = plo[1] < s.recess_m - 0.04 - 1e-9;
                let mid = plo[2] < (o.z0 + o.z1) / 2.0 && phi[2] > (o.z0 + o.z1) / 2.0;
                assert!(
                    !(inside && in_front && mid),
                    "{} blocks the glass: {p:?}",
                    s.name
                );
            }
        }
    }
}

#[test]
fn the_lit_panel_hangs_just_below_the_unlit_one_inside_the_room() {
    for s in &STYLES {
        let light = bounds(&bay::room_light(s)[0]);
        let parts = bay::window_bay(s, 0);
        let off = parts
            .iter()
            .find(|p| p.material.as_deref() == Some("facade_lamp_off"))
            .map(bounds)
            .unwrap();
        assert!(
            light.1[2] < off.0[2] && off.0[2] - light.1[2] < 0.005,
            "{}",
            s.name
        );
        assert_eq!(light.0[2], light.1[2]);
        assert!(light.0[0] > off.0[0] && light.1[0] < off.1[0]);
        assert!(light.0[1] > bay::front_depth(s.recess_m) && light.1[1] < SKIN_M);
        // Both face down: the lit one is a single quad.
        assert!(matches!(
            bay::room_light(s)[0].shape,
            ShapeDesc::Quad { .. }
        ));
    }
}

#[test]
fn columns_tile_the_wall_with_solid_ends() {
    for s in &STYLES {
        for len in [0.5, 3.0, 10.0, 17.3, 40.0] {
            let (cols, end) = columns(s, len);
            assert!((cols as f64 * s.bay_m + 2.0 * end - len).abs() < 1e-9);
            assert!(end >= END_MIN_M - 1e-12 || cols == 0, "{} {len}", s.name);
            assert!(
                end < END_MIN_M + s.bay_m,
                "{} {len}: one more column fits",
                s.name
            );
        }
    }
}

#[test]
fn shop_units_partition_the_front_with_one_door_each_and_a_sign_that_fits() {
    let shops: Vec<&Style> = STYLES
        .iter()
        .filter(|s| s.ground == Ground::Shops)
        .collect();
    assert!(shops.len() >= 3);
    let mut r = Rng::new(&[11]);
    for s in shops {
        for cols in 1..12 {
            let (plan, units) = front::ground_plan(s, cols, &mut r);
            assert_eq!(plan.len(), cols as usize);
            let mut next = 0;
            for u in &units {
                assert_eq!(u.first, next, "{cols}: {units:?}");
                next += u.cols;
                let bays = &plan[u.first as usize..(u.first + u.cols) as usize];
                let doors = bays.iter().filter(|b| **b == GroundBay::Door).count();
                assert_eq!(doors, 1, "{bays:?}");
                assert!(bays
                    .iter()
                    .all(|b| matches!(b, GroundBay::Door | GroundBay::Shop)));
                if let Some(k) = u.name {
                    assert!(front::sign_width(k) <= u.cols as f64 * s.bay_m - 0.3);
                }
            }
            assert_eq!(next, cols);
        }
    }
    // Residential: exactly one door, in the middle, windows elsewhere.
    let (plan, units) = front::ground_plan(&STYLES[0], 5, &mut r);
    assert!(units.is_empty());
    assert_eq!(plan[2], GroundBay::Door);
    assert!(
        plan.iter()
            .filter(|b| matches!(b, GroundBay::Window(_)))
            .count()
            == 4
    );
}

#[test]
fn sign_letters_sit_on_the_board_face() {
    for k in 0..front::SHOP_NAMES.len() {
        let parts = front::sign(k);
        let (lo, hi) = bounds(&parts[0]);
        let ShapeDesc::Mesh { positions, .. } = &parts[1].shape else {
            panic!()
        };
        assert!(!positions.is_empty());
        for p in positions {
            assert!(
                p[0] > lo[0] && p[0] < hi[0] && p[2] > lo[2] && p[2] < hi[2],
                "{p:?}"
            );
            assert!(
                p[1] <= lo[1] + 1e-12 && p[1] >= lo[1] - 0.03 - 1e-12,
                "{p:?}"
            );
        }
    }
}

#[test]
fn balcony_railing_is_fence_bars_at_their_spacing() {
    for s in STYLES.iter().filter(|s| s.balcony > 0.0) {
        assert_eq!(
            ornament::balcony(s)[0].semantic.as_deref(),
            Some("building")
        );
        let parts = ornament::railing(s);
        assert!(parts.iter().all(|p| p.semantic.as_deref() == Some("fence")));
        let front_bars = &parts[2];
        assert_eq!(
            front_bars.repeat[0].offset,
            [ornament::BAR_STEP_M, 0.0, 0.0]
        );
        let (lo, hi) = bounds(front_bars);
        let hw = s.bay_m / 2.0 - 0.2;
        assert!(lo[0] >= -hw && hi[0] <= hw + 1e-9 && hi[0] > hw - ornament::BAR_STEP_M);
    }
}

fn build(seed: u64, desc: &TownDesc, floors: u32) -> (Vec<ObjectDesc>, &'static str) {
    let plot = Rect {
        min: [0.0, 0.0],
        max: [21.0, 14.0],
    };
    let mut r = Rng::new(&[seed]);
    let mut out = Vec::new();
    let s = building(desc, &plot, true, floors, false, &mut r, ID, &mut out);
    (out, s.name)
}

#[test]
fn a_building_is_deterministic_per_seed_and_labelled_as_one() {
    let desc = town("town03");
    let (a, _) = build(3, &desc, 5);
    assert_eq!(a, build(3, &desc, 5).0);
    assert_ne!(a, build(4, &desc, 5).0);
    for o in &a {
        assert_eq!(o.instance, Some(1001), "{o:?}");
        // Balcony railings are `fence`, everything else `building`.
        let railing =
            matches!(&o.shape, ShapeDesc::Instance { prefab, .. } if prefab.ends_with("railing"));
        let want = if railing { "fence" } else { "building" };
        assert_eq!(o.semantic.as_deref(), Some(want), "{o:?}");
    }
}

#[test]
fn shopfronts_and_doors_never_share_a_column() {
    let desc = town("town03");
    for seed in 0..40 {
        let (out, _) = build(seed, &desc, 3);
        let mut ground = BTreeSet::new();
        for o in &out {
            let ShapeDesc::Instance { prefab, .. } = &o.shape else {
                continue;
            };
            let t = o.transform.translate.unwrap();
            let ground_bay = [
                "_shop",
                "_door",
                "_roller",
                "_window_0",
                "_window_1",
                "_window_2",
            ]
            .iter()
            .any(|k| prefab.ends_with(k));
            if t[2] == 0.0 && o.repeat.is_empty() && ground_bay {
                // One bay per position along the front (x in mm).
                assert!(
                    ground.insert((t[0] * 1000.0).round() as i64,),
                    "seed {seed}: two bays at {t:?}"
                );
            }
        }
    }
}

#[test]
fn every_prefab_material_is_a_facade_or_town_material() {
    let desc = town("town01");
    let names: BTreeSet<String> = crate::town::materials::town_materials(&desc)
        .into_iter()
        .map(|m| m.name)
        .collect();
    let prefabs = facade_prefabs();
    let pnames: BTreeSet<&str> = prefabs.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(pnames.len(), prefabs.len());
    for p in &prefabs {
        for o in &p.objects {
            let m = o.material.as_deref().unwrap();
            assert!(names.contains(m), "{}: {m}", p.name);
        }
    }
    for s in &STYLES {
        assert!(s.walls.iter().all(|w| names.contains(*w)), "{}", s.name);
    }
}

#[test]
#[ignore]
fn print_prefab_triangles() {
    for p in facade_prefabs() {
        let n: usize = p
            .objects
            .iter()
            .map(|o| match &o.shape {
                ShapeDesc::Mesh { triangles, .. } => triangles.len(),
                _ => 0,
            })
            .sum();
        println!("{} {} objs {n} tris", p.name, p.objects.len());
    }
}

/// Triangles of one object's own shape (instances: 0), times its repeats.
fn own_triangles(o: &ObjectDesc) -> u64 {
    let n = match &o.shape {
        ShapeDesc::Box { .. } => 12,
        ShapeDesc::Quad { .. } => 2,
        ShapeDesc::Mesh { triangles, .. } => triangles.len() as u64,
        ShapeDesc::Cylinder {
            segments, capped, ..
        } => crate::scene::mesh::cylinder_triangles(*segments, *capped),
        ShapeDesc::Ellipsoid {
            segments, rings, ..
        } => crate::scene::mesh::ellipsoid_triangles(*segments, *rings),
        _ => 0,
    };
    n * crate::scene::transform::repeat_count(&o.repeat)
}

#[test]
#[ignore]
fn print_town_facade_triangles() {
    let prefabs = facade_prefabs();
    let tris = |name: &str| -> u64 {
        prefabs
            .iter()
            .find(|p| p.name == name)
            .map_or(0, |p| p.objects.iter().map(own_triangles).sum())
    };
    let stored: u64 = prefabs.iter().map(|p| tris(&p.name)).sum();
    for name in ["town03", "town10", "town02"] {
        let desc = town(name);
        let scene = crate::town::town_scene(&desc, 0, 0, crate::town::CameraConfig::Normal);
        let (mut unique, mut placed, mut placements) = (0u64, 0u64, 0u64);
        for o in &scene.objects {
            if o.semantic.as_deref() != Some("building") && o.semantic.as_deref() != Some("fence") {
                continue;
            }
            match &o.shape {
                ShapeDesc::Instance { prefab, .. } if prefab.starts_with("facade_") => {
                    let n = crate::scene::transform::repeat_count(&o.repeat);
                    placements += n;
                    placed += n * tris(prefab);
                }
                _ => unique += own_triangles(o),
            }
        }
        println!("{name}: building unique {unique} tris, facade prefab placements {placements} = {placed} tris flattened; facade prefabs stored once {stored} tris ({} prefabs)", prefabs.len());
    }
}

/// Writes a street close-up of a shop-row building (for looking at).
#[test]
#[ignore]
fn write_close_up_scene() {
    let desc = town("town03");
    let plot = Rect {
        min: [0.0, 0.0],
        max: [21.0, 14.0],
    };
    let mut out = Vec::new();
    for seed in 0.. {
        out.clear();
        let mut r = Rng::new(&[seed]);
        let s = building(&desc, &plot, true, 3, false, &mut r, ID, &mut out);
        if s.name == "shop_row" && out.iter().any(|o| matches!(&o.shape, ShapeDesc::Instance { prefab, .. } if prefab.contains("sign"))) {
            break;
        }
    }
    out.push(crate::town::parts::ground_quad(
        [-30.0, -30.0],
        [50.0, 30.0],
        0.0,
        "sidewalk",
        crate::town::parts::class("sidewalk"),
    ));
    let mut scene = crate::town::town_scene(&desc, 0, 0, crate::town::CameraConfig::Normal);
    scene.objects = out;
    scene.camera.position = [6.0, -9.0, 1.7];
    scene.camera.yaw_deg = 90.0;
    scene.camera.pitch_deg = -20.0;
    std::fs::write("/tmp/h4/close.toml", crate::scene::serialize_scene(&scene)).unwrap();
}
