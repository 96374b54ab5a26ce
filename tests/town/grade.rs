//! Town04 on grades (`road_grade_m`): the ground-elevation field stays under
//! the 6 % cap yet gives every route grades a driver sees; rays cast down
//! under every route point and every vehicle hit road or paint at the
//! field's height (the vehicle's z) within a few centimetres; vehicles and
//! the ego pitch and roll with the field's gradient so all four wheels
//! touch the road; buildings never float; the hills sit on the field;
//! level towns build exactly as before the field existed (hashes pinned
//! from the commit before it, checked equal by OBJ export).

use glam::{DMat3, DVec3, Vec3};
use parallax::accel::{Accel, Backend, Ray};
use parallax::render::recipe::BuiltScene;
use parallax::scene::desc::ShapeDesc;
use parallax::scene::semantic::class_id;
use parallax::scene::{build_scene, build_scene_with, Instancing, LoadedScene, Scene};
use parallax::town::grade::{body_rotation_deg, Grade, MAX_GRADE};
use parallax::town::layout::Layout;
use parallax::town::routes::{routes, Turns};
use parallax::town::terrain::{Terrain, GROUND_Z, TERRAIN_NAME};
use parallax::town::{
    frame_at, geometry_hash, load_town_frame, parse_town_str, CameraConfig, StaticTown, TownDesc,
};

use crate::common;
use common::towns::{town, town_file};

const SEED: u64 = 3;

/// Town04 and its field.
fn graded() -> (TownDesc, Grade) {
    let desc = town("town04");
    let g = Grade::new(&desc, SEED).expect("town04 is graded");
    (desc, g)
}

/// The static frame of a town (no vehicles or pedestrians).
fn static_frame(desc: &TownDesc, name: &str) -> LoadedScene {
    let mut loaded =
        load_town_frame(desc, SEED, 0, CameraConfig::Normal, &town_file(name)).expect("town loads");
    loaded.desc.objects.retain(|o| {
        !matches!(
            o.semantic.as_deref(),
            Some("car" | "bus" | "truck" | "motorcycle" | "bicycle" | "rider" | "pedestrian")
        )
    });
    loaded
}

/// The static scene of a town frame, built around `origin`.
fn static_scene(desc: &TownDesc, name: &str, origin: DVec3) -> Scene {
    build_scene(&static_frame(desc, name), origin).unwrap()
}

#[test]
fn grade_stays_under_the_cap_and_every_route_climbs_a_few_percent() {
    let (desc, g) = graded();
    assert!(g.max_grade() <= MAX_GRADE, "{}", g.max_grade());
    let l = Layout::new(&desc);
    let b = l.bounds();
    let mut steepest: f64 = 0.0;
    for i in 0..=200 {
        for j in 0..=100 {
            let x = b.min[0] + (b.max[0] - b.min[0]) * i as f64 / 200.0;
            let y = b.min[1] + (b.max[1] - b.min[1]) * j as f64 / 100.0;
            let [gx, gy] = g.gradient(x, y);
            steepest = steepest.max(gx.hypot(gy));
        }
    }
    assert!(steepest <= MAX_GRADE, "{steepest}");
    // Along the routes, metre by metre: rise per metre driven.
    let all = routes(&l, &Turns::new(l.lane_w_m));
    for r in &all {
        let n = r.length_m().floor() as usize;
        let z = |s: f64| {
            let (p, _) = r.pose(s);
            g.height_m(p[0], p[1])
        };
        let worst = (0..n)
            .map(|k| (z(k as f64 + 1.0) - z(k as f64)).abs())
            .fold(0.0, f64::max);
        assert!(worst <= MAX_GRADE, "{:?} lane {}: {worst}", r.kind, r.lane);
        assert!(worst > 0.01, "{:?} lane {}: only {worst}", r.kind, r.lane);
        // The loops really go up and down: metres of relief along each.
        let zs: Vec<f64> = (0..n).step_by(5).map(|k| z(k as f64)).collect();
        let relief =
            zs.iter().fold(f64::MIN, |a, &b| a.max(b)) - zs.iter().fold(f64::MAX, |a, &b| a.min(b));
        assert!(relief > 1.5, "{:?}: relief {relief} m", r.kind);
    }
    // A grade a driver sees somewhere: ≥ 3 % on some route.
    let best = all
        .iter()
        .flat_map(|r| {
            (0..r.length_m() as usize).map(move |k| {
                let (p, h) = r.pose(k as f64);
                let [gx, gy] = g.gradient(p[0], p[1]);
                (gx * h.cos() + gy * h.sin()).abs()
            })
        })
        .fold(0.0, f64::max);
    assert!(best > 0.03, "steepest route grade {best}");
}

#[test]
fn rays_down_hit_the_road_at_the_field_height_under_routes_and_vehicles() {
    let (desc, g) = graded();
    let l = Layout::new(&desc);
    let origin = DVec3::new(500.0, 250.0, 0.0);
    let static_town = static_frame(&desc, "town04");
    let BuiltScene { scene, accel, .. } =
        BuiltScene::build(&static_town, origin, Backend::default_backend()).unwrap();
    let (road, mark) = (class_id("road").unwrap(), class_id("road_line").unwrap());
    // (class id, world z) of the first surface below (x, y), from 1.5 m
    // above the field (under the street lights' arms).
    let down = |x: f64, y: f64| {
        let top = g.height_m(x, y) + 1.5;
        let o = DVec3::new(x, y, top) - origin;
        let hit = accel
            .intersect(&Ray::new(o.as_vec3(), Vec3::NEG_Z))
            .expect("the ground is everywhere");
        (scene.hit_labels(&hit).0, top - hit.t as f64)
    };
    let mut checked = 0;
    for r in routes(&l, &Turns::new(l.lane_w_m)) {
        let mut s = 0.0;
        while s < r.length_m() {
            let (p, _) = r.pose(s);
            let (class, z) = down(p[0], p[1]);
            let h = g.height_m(p[0], p[1]);
            assert!(class == road || class == mark, "{p:?}: class {class}");
            // Paint is 8 mm thick; the surface chords the field within mm.
            assert!((z - h).abs() < 0.03, "{p:?}: road at {z}, field {h}");
            checked += 1;
            s += 2.5;
        }
    }
    assert!(checked > 2000, "{checked} route points");
    let mut vehicles = 0;
    for frame in (0..300).step_by(15) {
        let f = frame_at(&desc, SEED, frame);
        for v in std::iter::once(&f.ego).chain(&f.vehicles) {
            let [x, y, z] = v.position;
            assert_eq!(z, g.height_m(x, y), "frame {frame} vehicle {}", v.id);
            let (class, hit_z) = down(x, y);
            assert!(
                class == road || class == mark,
                "vehicle {} over class {class}",
                v.id
            );
            assert!(
                (hit_z - z).abs() < 0.03,
                "vehicle {} at z {z}, road {hit_z}",
                v.id
            );
            vehicles += 1;
        }
    }
    assert!(vehicles > 100, "{vehicles} vehicles");
}

#[test]
fn vehicles_pitch_with_the_gradient_and_their_wheels_touch_the_road() {
    let (desc, g) = graded();
    let (mut tilted, mut n) = (0, 0);
    for frame in 0..300 {
        let f = frame_at(&desc, SEED, frame);
        for v in std::iter::once(&f.ego).chain(&f.vehicles) {
            let [x, y, z] = v.position;
            let [gx, gy] = g.gradient(x, y);
            let h = v.heading_deg.to_radians();
            let along = gx * h.cos() + gy * h.sin();
            assert!((v.pitch_deg - along.atan().to_degrees()).abs() < 1e-9);
            let r = body_rotation_deg(v.heading_deg, v.pitch_deg, v.roll_deg).map(f64::to_radians);
            let m = DMat3::from_rotation_z(r[2])
                * DMat3::from_rotation_y(r[1])
                * DMat3::from_rotation_x(r[0]);
            // The body's up axis is the ground normal there.
            assert!((m.z_axis - g.normal(x, y)).length() < 1e-9);
            // Every footprint corner (where the wheels stand) on the field.
            let [len, w] = v.body.footprint_m();
            for (a, b) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                let c = DVec3::new(x, y, z) + m * DVec3::new(a * len / 2.0, b * w / 2.0, 0.0);
                let gap = c.z - g.height_m(c.x, c.y);
                assert!(
                    gap.abs() < 0.05,
                    "vehicle {} corner {gap} m off the road",
                    v.id
                );
            }
            tilted += (v.pitch_deg.abs() > 1.0) as usize;
            n += 1;
        }
    }
    assert!(tilted * 5 > n, "only {tilted} of {n} poses pitched over 1°");
    // The ego's cameras ride the tilted body (rig_desc).
    let f = frame_at(&desc, SEED, 0);
    let rd = parallax::town::rig_desc(CameraConfig::Normal, &f.ego);
    assert!((rd.pitch_deg + f.ego.pitch_deg).abs() < 0.2, "{rd:?}");
    assert!(rd.position[2] - f.ego.position[2] > 1.6);
}

#[test]
fn buildings_never_float_and_the_hills_sit_on_the_field() {
    let (desc, g) = graded();
    let origin = DVec3::new(500.0, 250.0, 0.0);
    let scene = static_scene(&desc, "town04", origin);
    let building = class_id("building").unwrap();
    let mut lowest: std::collections::BTreeMap<u16, Vec<DVec3>> = Default::default();
    for m in scene.flattened_meshes().filter(|m| m.semantic == building) {
        let e = lowest.entry(m.instance).or_default();
        e.extend(m.p_render.iter().map(|&p| p + origin));
    }
    assert!(lowest.len() >= 5, "{} buildings", lowest.len());
    for (id, pts) in &lowest {
        let base = pts.iter().map(|p| p.z).fold(f64::INFINITY, f64::min);
        for p in pts.iter().filter(|p| p.z < base + 1e-6) {
            // The ground is at or above the base under every bottom corner.
            let h = g.height_m(p.x, p.y);
            assert!(h >= base - 0.021, "building {id}: base {base}, ground {h}");
        }
    }
    let terrain = Terrain::new(&desc, &Layout::new(&desc), SEED).expect("town04 has hills");
    let meshes = StaticTown::new(&desc, SEED).meshes();
    let hills = meshes
        .iter()
        .find(|o| o.name.as_deref() == Some(TERRAIN_NAME))
        .expect("the hills mesh");
    let ShapeDesc::Mesh { positions, .. } = &hills.shape else {
        panic!("hills are a mesh")
    };
    let mut raised = 0;
    for w in positions.iter().step_by(37) {
        let want = terrain.height_m(w[0], w[1]) + GROUND_Z + g.height_m(w[0], w[1]);
        assert!((w[2] - want).abs() < 1e-9, "{w:?} vs {want}");
        raised += (terrain.height_m(w[0], w[1]) > 1.0) as usize;
    }
    assert!(raised > 100, "{raised} hill vertices");
}

#[test]
fn level_towns_hash_as_before_the_grade_existed() {
    // Static geometry with frame 0's traffic, seed 3; the values equalled
    // the commit before `road_grade_m` (OBJ exports compared byte for byte)
    // until issue 21 rebuilt the static world (grown trees, hedges and verges,
    // the façade generator, street furniture); re-pinned then, with CARLA's
    // class ids (railings are `fence`, a class the pre-CARLA table lacked);
    // re-pinned when issue 22 sent the ego on drives over the network (frame
    // 0's ego and the vehicles in its way moved) and made vehicles lofted
    // meshes (new body types, weights and paint mix), with articulated
    // people and riders on the two-wheelers; town04 re-pinned when highway
    // roadside trees left the hard shoulder for the verge behind the rails;
    // town02 re-pinned when its outskirts (buildings beyond the outer roads,
    // trees past the stubs) were added.
    // re-pinned when background vehicles became a simulation per chunk
    // from a seeded start with a warm-up (other vehicles and places at
    // frame 0, brake and indicator lenses in the lamps prefab,
    // two-wheelers' real footprints) and the ego moved against the
    // signals only; re-pinned after merging main's outskirts (town02) and
    // when followers came to count on their leader's braking distance
    // (frame 0's traffic after the warm-up moved); re-pinned when the ego
    // got a convoy of leaders on its route and the pickup an open bed;
    // re-pinned when vehicle lamp lenses became outer domes and cobra
    // lamp panels lost their top face; re-pinned when signal lenses lost
    // their back cap, and when those faces' unused vertices went.
    const PINNED: [(&str, u64); 3] = [
        ("town02", 0xf505_f2d8_4c74_8441),
        ("town07", 0xebd3_3874_9d82_32fd),
        ("town04", 0xf12e_3774_5b7d_ca3c),
    ];
    let mut got = Vec::new();
    for (name, _) in PINNED {
        let mut desc = town(name);
        // Town04 with its key at 0: the town as it was; town07 as a grid,
        // unbent (its organic warp is tested in `organic`).
        desc.road_grade_m = 0.0;
        desc.road_style = parallax::town::desc::RoadStyle::Grid;
        // Town02 as before its parking lanes (the pin holds with the key at 0).
        crate::common::towns::without_parking_lanes(&mut desc);
        assert!(Grade::new(&desc, SEED).is_none());
        let loaded =
            load_town_frame(&desc, SEED, 0, CameraConfig::Normal, &town_file(name)).unwrap();
        // Flattened: instancing reorders meshes and rounds their vertices
        // through the instance transform.
        let scene = build_scene_with(&loaded, DVec3::ZERO, Instancing::Flat).unwrap();
        got.push((name, geometry_hash(&scene)));
    }
    // All three compared at once, so a re-pin sees every new value.
    let hex: Vec<String> = got.iter().map(|(n, h)| format!("{n}: {h:#x}")).collect();
    assert_eq!(got, PINNED, "{hex:?}");
}

#[test]
fn bad_grade_keys_are_rejected_naming_the_key() {
    let text = std::fs::read_to_string(town_file("town04")).unwrap();
    let edit = |key: &str, value: &str| -> String {
        text.lines()
            .map(|line| match line.starts_with(&format!("{key} =")) {
                true => format!("{key} = {value}\n"),
                false => format!("{line}\n"),
            })
            .collect()
    };
    let parse = |t: &str| parse_town_str(t, "t.toml".as_ref());
    // A = 12 m over 800 m: 12 · 2π / 800 / √2 = 6.66 % > 6 %.
    for (key, bad) in [
        ("road_grade_m", "12.0"),
        ("road_grade_m", "-1.0"),
        ("road_grade_wavelength_m", "100.0"),
        ("road_grade_wavelength_m", "500.0"),
    ] {
        let e = parse(&edit(key, bad)).unwrap_err();
        assert!(e.contains(key), "{key} = {bad}: {e}");
    }
    // 10.8 m over 800 m is exactly at the cap: 5.998 %.
    parse(&edit("road_grade_m", "10.8")).unwrap();
    parse(&edit("road_grade_m", "0.0")).unwrap();
    let e = parse(&format!("{text}river = true\n")).unwrap_err();
    assert!(e.contains("road_grade_m"), "{e}");
}
