//! The underpass (`underpass = true`) in a 4 × 4 grid test town of 90 m
//! blocks with four-lane avenues: vertical rays find the x-road on the
//! deck, the deck's underside and the sunken road at the profile's height;
//! a ray straight down from a car in the cut hits its asphalt at the
//! camera's height; the crossing has no signals, crosswalks or junction
//! moves; over 600 frames vehicles never overlap on one level, stay on
//! the road, ride the profile in the cut and go straight through, and no
//! pedestrian walks over the cut; some drive of the ego goes under.

use glam::{DVec3, Vec3};
use parallax::accel::{Accel, Ray};
use parallax::render::recipe::BuiltScene;
use parallax::scene::semantic::class_id;
use parallax::town::layout::Layout;
use parallax::town::signals::signal_sites;
use parallax::town::traffic::ego_pose;
use parallax::town::underpass::{Underpass, DECK_M, DEPTH_M};
use parallax::town::{frame_at, parse_town_str, TownDesc};

use crate::common::towns::{static_town_scene, surfaces_below, town_file};
use crate::traffic::{on_road, overlaps};

const SEED: u64 = 3;

/// The test town: a level grid with the underpass at junction (1, 2).
fn test_town() -> TownDesc {
    let text = r#"
name = "underpass_test"
extent_m = [360.0, 360.0]
block_size_m = 90.0
lanes_per_direction = 2
lane_width_m = 3.5
sidewalk_width_m = 4.0
building_density = 0.8
floors = [2, 4]
vegetation_density = 0.3
terrain = "grass"
traffic_density = 0.6
speed_kmh = 40.0
sun_elevation_deg = 45.0
sun_azimuth_deg = 160.0
underpass = true
"#;
    parse_town_str(text, "underpass_test.toml".as_ref()).unwrap()
}

#[test]
fn rays_find_the_deck_over_the_sunken_road_on_its_profile() {
    let desc = test_town();
    let l = Layout::new(&desc);
    let u = Underpass::of(&l).expect("the test town has an underpass");
    assert_eq!(u.ij, (1, 2));
    let origin = DVec3::new(u.x_m, u.y_m, 0.0);
    let built = static_town_scene(&desc, SEED, &town_file("town03"), origin);
    let (road, bridge, mark) = (
        class_id("road").unwrap(),
        class_id("bridge").unwrap(),
        class_id("road_line").unwrap(),
    );
    let column = |x: f64, y: f64, from: f64| surfaces_below(&built, origin, (x, y, from));
    // On the deck, over every lane of both roads: the x-road at grade,
    // the deck's underside, then the sunken road DEPTH_M down.
    for k in 0..4 {
        let y = u.y_m - 7.0 + (k as f64 + 0.5) * 3.5;
        for dx in [-5.25, -1.75, 1.75, 5.25] {
            let c = column(u.x_m + dx, y, 30.0);
            assert!(c.len() >= 3, "({dx}, {y}): {c:?}");
            assert!(c[0].0 == road || c[0].0 == mark, "{c:?}");
            assert!(c[0].1.abs() < 0.01, "{c:?}");
            assert_eq!(c[1].0, bridge, "{c:?}");
            assert!((c[1].1 + DECK_M).abs() < 1e-4, "{c:?}");
            assert_eq!(c[2].0, road, "{c:?}");
            assert!((c[2].1 + DEPTH_M).abs() < 1e-4, "{c:?}");
        }
    }
    // Along the cut, below grade (street trees and lamp arms overhang
    // it): asphalt (or paint) at the profile, no ground quad over it.
    let mut y = u.edges.0 + 0.25;
    let mut deepest: f64 = 0.0;
    while y < u.edges.1 {
        if y < u.deck.0 || y > u.deck.1 {
            for dx in [-5.0, -3.0, 3.0, 5.0] {
                let c = column(u.x_m + dx, y, 0.1);
                let want = u.profile(y).0;
                assert!(c[0].0 == road || c[0].0 == mark, "{y}: {c:?}");
                let paint = if c[0].0 == mark { 0.0081 } else { 0.0 };
                assert!((c[0].1 - want - paint).abs() < 5e-4, "{y}: {c:?} vs {want}");
                deepest = deepest.min(c[0].1);
            }
        }
        y += 1.0;
    }
    assert!(deepest < -DEPTH_M + 0.01, "{deepest}");
    // A camera 1.5 m above a car's footprint in the cut, looking straight
    // down between the lane lines: its depth is the camera height.
    for y in [u.ends.0 + 30.0, u.deck.0 - 0.5, u.ends.1 - 5.0] {
        let z = u.profile(y).0;
        let c = column(u.x_m + 5.25, y, z + 1.5);
        assert_eq!(c[0].0, road, "{y}: {c:?}");
        assert!((c[0].1 - z).abs() < 5e-4, "{y}: {c:?} vs {z}");
    }
    // The ground quad is cut open over the cut: nothing above the road
    // between the walls, and the walls beside it.
    let wall = class_id("wall").unwrap();
    let dy = u.ends.0 + 33.0;
    let c = column(u.x_m + u.half_w_m - 0.01, dy, 0.0);
    assert!((c[0].1 - u.profile(dy).0).abs() < 1e-3, "{c:?}");
    let side = built
        .accel
        .intersect(&Ray::new(
            (DVec3::new(u.x_m, dy, u.profile(dy).0 + 1.0) - origin).as_vec3(),
            Vec3::X,
        ))
        .expect("the east wall");
    assert_eq!(built.scene.hit_labels(&side).0, wall);
    assert!((side.t as f64 - u.half_w_m).abs() < 1e-4, "{}", side.t);
}

#[test]
fn the_crossing_has_no_signals_and_traffic_passes_on_two_levels() {
    let desc = test_town();
    let l = Layout::new(&desc);
    let u = Underpass::of(&l).unwrap();
    let roads = l.road_rects();
    assert!(signal_sites(&l)
        .iter()
        .all(|s| (s.centre(&l)[0] - u.x_m).hypot(s.centre(&l)[1] - u.y_m) > 30.0));
    let (mut sunk, mut deepest, mut pairs, mut on_deck) = (0, 0.0f64, 0, 0);
    let hw = u.half_w_m;
    for frame in 0..600 {
        let f = frame_at(&desc, SEED, frame);
        let all: Vec<_> = std::iter::once(&f.ego).chain(&f.vehicles).collect();
        assert!(
            overlaps(&all).is_empty(),
            "frame {frame}: {:?}",
            overlaps(&all)
        );
        for v in &all {
            assert!(
                on_road(&l, &roads, None, v),
                "frame {frame}: {} {:?} at {:?} heading {}",
                v.id,
                v.body,
                v.position,
                v.heading_deg
            );
            let [x, y, z] = v.position;
            let h = v.heading_deg.to_radians();
            let along_y = h.sin().abs() > 0.5;
            if u.over_cut([x, y]) && along_y {
                let (want, slope) = u.profile(y);
                assert_eq!(z, want, "frame {frame}: {:?}", v.position);
                let pitch = (slope * h.sin()).atan().to_degrees();
                assert!((v.pitch_deg - pitch).abs() < 1e-12);
                sunk += 1;
                deepest = deepest.min(z);
            } else {
                assert_eq!(z, 0.0, "frame {frame}: {:?} {}", v.position, v.heading_deg);
                on_deck += ((y - u.y_m).abs() < hw && (x - u.x_m).abs() < hw) as usize;
            }
            // Nobody turns at the crossing: straight along x or y.
            if (x - u.x_m).abs() < hw && (y - u.y_m).abs() < hw {
                let q = v.heading_deg.rem_euclid(90.0);
                assert!(
                    !(1e-9..=90.0 - 1e-9).contains(&q),
                    "frame {frame}: {}",
                    v.heading_deg
                );
            }
            for w in &all {
                if w.id < v.id && v.footprint().overlaps(&w.footprint()) && !v.same_level(w) {
                    pairs += 1;
                }
            }
        }
        for p in &f.pedestrians {
            let q = [p.position[0], p.position[1]];
            let near = (q[0] - u.x_m).abs() < hw + 0.3 && q[1] > u.ends.0 && q[1] < u.ends.1;
            assert!(!near, "frame {frame}: pedestrian {} at {q:?}", p.id);
        }
    }
    eprintln!("{sunk} poses in the cut, deepest {deepest}, {on_deck} on the deck, {pairs} over-under pairs");
    assert!(sunk > 200 && deepest <= -DEPTH_M + 1e-9, "{sunk} {deepest}");
    assert!(on_deck > 20, "{on_deck}");
}

#[test]
fn some_ego_drive_goes_through_the_underpass() {
    let desc = test_town();
    let found = (0..16u64).find_map(|drive| {
        (0..600u64)
            .step_by(5)
            .find(|&f| ego_pose(&desc, SEED, drive, f).0.position[2] < -5.0)
            .map(|f| (drive, f))
    });
    eprintln!("ego under the deck at (drive, frame) {found:?}");
    assert!(found.is_some());
}

/// Town03 (organic) bends the underpass with its streets: a ray down at
/// W(p) for level points p between the walls finds the sunken road at
/// the profile's height of p (the warp keeps z), and on the deck the
/// x-road above the deck's underside above the road; its traffic rides
/// the profile through the bent cut.
#[test]
fn town03_bends_the_underpass_with_its_streets() {
    use parallax::town::organic::Warp;
    let desc = crate::common::towns::town("town03");
    assert!(desc.underpass);
    let l = Layout::new(&desc);
    let u = Underpass::of(&l).expect("town03 has an underpass");
    let w = Warp::new(&desc, SEED).expect("town03 is organic");
    let c = w.map([u.x_m, u.y_m]);
    let origin = DVec3::new(c[0], c[1], 0.0);
    let BuiltScene { scene, accel, .. } =
        static_town_scene(&desc, SEED, &town_file("town03"), origin);
    let (road, bridge, mark) = (
        class_id("road").unwrap(),
        class_id("bridge").unwrap(),
        class_id("road_line").unwrap(),
    );
    let first = |p: [f64; 2], from: f64| {
        let q = w.map(p);
        let hit = accel
            .intersect(&Ray::new(
                (DVec3::new(q[0], q[1], from) - origin).as_vec3(),
                Vec3::NEG_Z,
            ))
            .expect("a surface below");
        (scene.hit_labels(&hit).0, from - hit.t as f64)
    };
    let mut y = u.edges.0 + 0.3;
    let mut checked = 0;
    while y < u.edges.1 {
        if y < u.deck.0 - 0.2 || y > u.deck.1 + 0.2 {
            for dx in [-5.0, -3.0, 0.9, 3.0, 5.0] {
                let (k, z) = first([u.x_m + dx, y], 0.1);
                let want = u.profile(y).0;
                assert!(k == road || k == mark, "{y}: {k} at {z}");
                assert!((z - want).abs() < 0.012, "{dx}, {y}: {z} vs {want}");
                checked += 1;
            }
        } else if (y - u.y_m).abs() < u.half_w_m - 0.5 {
            let (k, z) = first([u.x_m + 3.0, y], 0.1);
            assert!(
                (k == road || k == mark) && z.abs() < 0.01,
                "{y}: {k} at {z}"
            );
            let (k, z) = first([u.x_m + 3.0, y], -0.1);
            assert_eq!(k, bridge, "{y}: {k} at {z}");
            assert!((z + DECK_M).abs() < 1e-3, "{y}: {z}");
            let (k, z) = first([u.x_m + 3.0, y], -1.0);
            assert_eq!(k, road, "{y}: {k} at {z}");
            assert!((z + DEPTH_M).abs() < 1e-3, "{y}: {z}");
        }
        y += 0.7;
    }
    assert!(checked > 500, "{checked}");
    // Traffic: the level grid's poses (W⁻¹) ride the profile in the cut.
    let mut sunk = 0;
    for frame in (0..600).step_by(3) {
        let f = w.unwarp_frame(&frame_at(&desc, SEED, frame));
        for v in std::iter::once(&f.ego).chain(&f.vehicles) {
            let [x, y, z] = v.position;
            if u.over_cut([x, y]) && v.heading_deg.to_radians().sin().abs() > 0.5 {
                assert!(
                    (z - u.profile(y).0).abs() < 1e-9,
                    "frame {frame}: {:?}",
                    v.position
                );
                sunk += 1;
            }
        }
    }
    assert!(sunk > 20, "{sunk}");
}
