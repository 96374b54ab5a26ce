//! Town06's overpass (`overpass = true`): a vertical ray where it crosses
//! the south highway hits the overpass road on the deck, then the deck's
//! underside ≥ 4.5 m above the highway, then the highway, and its road is
//! open to the sky along its whole route; its traffic rides
//! the height profile over 300 frames, is on the deck wherever it is above
//! another road, never meets another route at grade (no junction, no turn
//! into the highway) and vehicles on the two levels do not count as
//! overlapping; bad `overpass` keys are rejected.

use glam::DVec3;
use parallax::accel::Backend;
use parallax::render::recipe::BuiltScene;
use parallax::scene::semantic::class_id;
use parallax::town::layout::{Layout, Rect};
use parallax::town::overpass::{Overpass, CLEARANCE_M, TOP_M};
use parallax::town::routes::RouteKind;
use parallax::town::traffic::{ego_pose, Plan};
use parallax::town::{
    drive_frame_at, frame_at, load_town_drive_frame, parse_town_str, CameraConfig, TownDesc,
};

use crate::common;
use common::towns::{gt_frame, static_town_scene, surfaces_below, town, town_file};

const SEED: u64 = 5;

#[test]
fn vertical_ray_at_the_crossing_hits_deck_then_highway_with_clearance() {
    let desc = town("town06");
    let l = Layout::new(&desc);
    let o = Overpass::new(&desc, &l).expect("town06 has an overpass");
    let origin = DVec3::new(o.x_m, 0.0, 0.0);
    let built = static_town_scene(&desc, SEED, &town_file("town06"), origin);
    let (road, bridge) = (class_id("road").unwrap(), class_id("bridge").unwrap());
    // Every surface along a ray down from 30 m at (x, y): (class, z).
    let column = |x: f64, y: f64| surfaces_below(&built, origin, (x, y, 30.0));
    let hw = l.road_w_m / 2.0;
    let mut lanes = 0;
    // Over every highway lane centre, at the road's centre and off it.
    for k in 0..l.lanes * 2 {
        let y = -hw + (k as f64 + 0.5) * l.lane_w_m;
        for dx in [-1.75, 0.5, 1.75] {
            let c = column(o.x_m + dx, y);
            assert!(c.len() >= 3, "({dx}, {y}): {c:?}");
            // The overpass road (or its paint) on top of the deck …
            assert!((c[0].1 - TOP_M).abs() < 0.01, "({dx}, {y}): {c:?}");
            // … then the underside, then the highway at grade.
            assert_eq!(c[1].0, bridge, "({dx}, {y}): {c:?}");
            assert!((c[1].1 - CLEARANCE_M).abs() < 1e-4, "{c:?}");
            assert_eq!(c[2].0, road, "({dx}, {y}): {c:?}");
            assert!(c[2].1.abs() < 1e-4, "{c:?}");
            assert!(c[1].1 - c[2].1 >= 4.5);
            lanes += 1;
        }
    }
    assert_eq!(lanes, 18);
    // The slip road south of the highway passes under the deck too.
    let ramp_y = -(hw + 25.0 + 2.0);
    let c = column(o.x_m, ramp_y);
    let ramp_at_grade = c.iter().any(|&(k, z)| k == road && z.abs() < 1e-4);
    assert!((c[0].1 - TOP_M).abs() < 0.01 && ramp_at_grade, "{c:?}");
    // Open to the sky along its whole route: the first surface below 30 m
    // is its asphalt or paint, at the profile's height.
    let mark = class_id("road_line").unwrap();
    let r = o.route();
    let mut s = 0.0;
    while s < r.length_m() {
        let (p, _) = r.pose(s);
        let c = column(p[0], p[1]);
        let want = o.profile(p[1]).0;
        assert!(c[0].0 == road || c[0].0 == mark, "{p:?}: {c:?}");
        assert!((c[0].1 - want).abs() < 0.01, "{p:?}: {c:?} vs {want}");
        s += 3.0;
    }
    // At the loops the overpass road is at grade, beside nothing.
    for ctr in o.loop_centres() {
        let c = column(ctr[0], ctr[1]);
        assert_eq!((c[0].0, c[0].1.abs() < 1e-4), (road, true), "{c:?}");
    }
}

#[test]
fn overpass_traffic_rides_its_profile_and_never_meets_the_highway_at_grade() {
    let desc = town("town06");
    let l = Layout::new(&desc);
    let o = Overpass::new(&desc, &l).unwrap();
    let plan = Plan::new(&desc);
    let route = plan
        .routes
        .iter()
        .position(|p| p.route.kind == RouteKind::Overpass)
        .expect("the overpass has a route");
    assert!(plan.routes[route].route.keep_clear_m.is_empty());
    let roads = l.road_rects();
    let on_other_road = |p: [f64; 2]| {
        roads
            .iter()
            .any(|r| r.contains(&Rect::centered(p, [0.0, 0.0]), 0.0))
    };
    let (mut on_deck, mut riders, mut pairs) = (0, 0, 0);
    for frame in 0..300 {
        let f = frame_at(&desc, SEED, frame);
        let all: Vec<_> = std::iter::once(&f.ego).chain(&f.vehicles).collect();
        for v in &all {
            let [x, y, z] = v.position;
            if v.route == route {
                riders += 1;
                assert!(o.on_surface([x, y]), "{:?}", v.position);
                assert_eq!(z, o.profile(y).0);
                // Over another road only on the deck, at full height.
                for c in v.corners() {
                    if on_other_road(c) {
                        assert_eq!(z, TOP_M, "frame {frame}: {:?}", v.position);
                        on_deck += 1;
                    }
                }
                continue;
            }
            // Nobody else drives on the overpass or turns off under it.
            assert!(z == 0.0, "{:?}", v.position);
            if (x - o.x_m).abs() < 15.0 && y.abs() < 15.0 {
                let h = v.heading_deg.rem_euclid(180.0);
                assert!(
                    h.abs() < 1e-9 || (h - 180.0).abs() < 1e-9,
                    "{}",
                    v.heading_deg
                );
            }
            for w in all.iter().filter(|w| w.route == route) {
                if v.footprint().overlaps(&w.footprint()) {
                    assert!(!v.same_level(w), "frame {frame}: {} and {}", v.id, w.id);
                    pairs += 1;
                }
            }
        }
    }
    assert!(riders > 300, "{riders} overpass poses");
    assert!(on_deck > 0, "nobody crossed the deck");
    eprintln!("{pairs} over-under pairs in 300 frames");
    // One pair built on purpose: a car on the deck right above a car on the
    // highway overlaps in plan but not in space.
    let r = &plan.routes[route].route;
    let s = -o.ends.0; // north along the east lane to y = 0
    let (p, h) = r.pose(s);
    assert!(p[1].abs() < 1e-9 && (p[0] - o.x_m - 1.75).abs() < 1e-9);
    let f = frame_at(&desc, SEED, 0);
    let mut up = f.vehicles[0].clone();
    (up.position, up.heading_deg, up.route) = ([p[0], p[1], TOP_M], h.to_degrees(), route);
    let mut down = f.vehicles[0].clone();
    down.position = [o.x_m, -1.875, 0.0];
    down.heading_deg = 0.0;
    assert!(up.footprint().overlaps(&down.footprint()));
    assert!(!up.same_level(&down) && up.same_level(&up));
}

#[test]
fn bad_overpass_keys_are_rejected_naming_the_key() {
    let text = std::fs::read_to_string(town_file("town06")).unwrap();
    let without = text.replace("ramps = true", "ramps = false");
    let e = parse_town_str(&without, "t.toml".as_ref()).unwrap_err();
    assert!(e.contains("overpass"), "{e}");
    let graded = format!("{text}road_grade_m = 2.0\n");
    let e = parse_town_str(&graded, "t.toml".as_ref()).unwrap_err();
    assert!(e.contains("overpass"), "{e}");
    let e = parse_town_str(
        &text.replace("overpass = true", "overpass = 1"),
        "t.toml".as_ref(),
    )
    .unwrap_err();
    assert!(e.contains("overpass"), "{e}");
}

/// Frames where the ego drives towards the overpass on the highway below
/// it, within 200 m (a view of the bridge); printed for the notes.
#[test]
fn ego_sees_the_overpass_in_some_frames() {
    let desc = town("town06");
    let l = Layout::new(&desc);
    let o = Overpass::new(&desc, &l).unwrap();
    let seen = sightings(&desc, &l, &o, 12);
    eprintln!("ego sees the overpass at (drive, frame, metres ahead): {seen:?}");
    assert!(!seen.is_empty());
}

/// (drive, frame, metres to the bridge ahead, whether east of it) where the
/// ego of SEED's first `drives`, over a dataset sequence each, drives on
/// the highway towards the overpass 20 to 120 m ahead.
fn sightings(desc: &TownDesc, l: &Layout, o: &Overpass, drives: u64) -> Vec<(u64, u64, f64, bool)> {
    let mut seen = Vec::new();
    for drive in 0..drives {
        for frame in (0..590).step_by(10) {
            let (e, _) = ego_pose(desc, SEED, drive, frame);
            let h = e.heading_deg.to_radians();
            let ahead = (o.x_m - e.position[0]) * h.cos() + (0.0 - e.position[1]) * h.sin();
            let side = (-(o.x_m - e.position[0]) * h.sin() + (0.0 - e.position[1]) * h.cos()).abs();
            let on_highway = e.position[1].abs() < l.road_w_m / 2.0;
            if on_highway && (20.0..120.0).contains(&ahead) && side < 30.0 {
                seen.push((drive, frame, ahead, e.position[0] > o.x_m));
            }
        }
    }
    seen
}

/// The ground truth of a frame looking at the bridge (of seed 5's
/// `sightings`, the one nearest 50 m before it: the ego on the highway,
/// driving towards it) in
/// every configuration: every
/// structure pixel whose depth puts it at the bridge lies exactly on one of
/// its planes (the deck's underside, its east face, parapets, a pier or
/// abutment face), the underside among them for cameras below the deck.
#[test]
fn ground_truth_on_the_bridge_lies_on_its_planes() {
    use parallax::integrator::RenderCamera;
    use parallax::town::overpass::{HALF_WIDTH_M, PARAPET_M};
    use parallax::town::CONFIGS;
    let desc = town("town06");
    let l = Layout::new(&desc);
    let o = Overpass::new(&desc, &l).unwrap();
    let (drive, frame, _, _) = sightings(&desc, &l, &o, 12)
        .into_iter()
        .min_by(|a, b| (a.2 - 50.0).abs().total_cmp(&(b.2 - 50.0).abs()))
        .expect("a frame looking at the bridge");
    let seed = SEED;
    let loaded = load_town_drive_frame(
        &desc,
        seed,
        drive,
        frame,
        CameraConfig::Normal,
        &town_file("town06"),
    )
    .expect("town06 loads");
    let origin = DVec3::from(loaded.desc.camera.position);
    let BuiltScene { scene, accel, .. } =
        BuiltScene::build(&loaded, origin, Backend::default_backend()).unwrap();
    let bridge = class_id("bridge").unwrap();
    let ego = drive_frame_at(&desc, seed, drive, frame).ego;
    let east = o.x_m + HALF_WIDTH_M + PARAPET_M.0;
    let west = o.x_m - HALF_WIDTH_M - PARAPET_M.0;
    for config in [CONFIGS[0], CONFIGS[3], CONFIGS[4]] {
        let (rig, out) = gt_frame(
            &scene,
            &accel,
            config,
            &ego,
            (320, 180),
            &[54.0],
            (seed, frame),
        );
        let cam = RenderCamera::new(&rig.left, scene.origin_world);
        let (mut on_bridge, mut under) = (0, 0);
        for j in 0..180u32 {
            for i in 0..320u32 {
                let k = (j * 320 + i) as usize;
                let z = out.left.depth_z[k];
                if !z.is_finite() || out.left.semantic[k] != bridge {
                    continue;
                }
                let (u, v) = (i as f64 + 0.5, j as f64 + 0.5);
                let p = cam.center + cam.dir(u, v) * z + scene.origin_world;
                // The deck's span and its end faces: past them the approaches'
                // parapets slope down with the ramps.
                if (p.x - o.x_m).abs() > 8.0 || p.y < o.deck.0 - 0.01 || p.y > o.deck.1 + 0.01 {
                    continue;
                }
                let tol = 1e-5 * z;
                // Every plane of the structure's faces (the parapets' outer faces
                // on both sides: the drive may pass west of the bridge).
                let under_z = TOP_M - parallax::town::overpass::DECK_M;
                let (xo, yp) = (o.x_m, o.pier_y_m);
                let zs = [under_z, under_z - 0.8, TOP_M + PARAPET_M.1];
                let xs = [
                    east,
                    west,
                    xo + HALF_WIDTH_M,
                    xo - HALF_WIDTH_M,
                    xo + 3.1,
                    xo - 1.9,
                ];
                let ys = [o.deck.0, o.deck.1, yp - 0.6, yp + 0.6, yp - 0.7, yp + 0.7];
                let faces: Vec<f64> = zs
                    .iter()
                    .map(|&c| (p.z - c).abs())
                    .chain(xs.iter().map(|&c| (p.x - c).abs()))
                    .chain(ys.iter().map(|&c| (p.y - c).abs()))
                    .collect();
                let best = faces.iter().copied().fold(f64::INFINITY, f64::min);
                assert!(
                    best <= tol,
                    "{config} ({i},{j}): {p:?} off the bridge's planes by {best}"
                );
                on_bridge += 1;
                under += ((p.z - under_z).abs() <= tol) as usize;
            }
        }
        assert!(on_bridge > 100, "{config}: only {on_bridge} bridge pixels");
        // Cameras below the deck see its underside (10 m up, they see its top).
        if rig.left.center_world.z < CLEARANCE_M {
            assert!(under > 10, "{config}: only {under} underside pixels");
        }
    }
}
