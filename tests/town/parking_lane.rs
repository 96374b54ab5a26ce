//! Parking lanes (`parking_lane_m`) in town01, town02 and town03: the key's
//! validation; every parked car (mirrors included) lies in a parking strip,
//! off the driving lanes and the junction areas (town03's bent cars carried
//! back through W⁻¹); rays across a road find asphalt from the centreline
//! to the kerb at the strip's outer edge, then the sidewalk; over 600
//! frames no moving vehicle touches a parked car.

use parallax::scene::desc::semantic::class_id;
use parallax::town::layout::Layout;
use parallax::town::organic::Warp;
use parallax::town::parking::cars::cars_in;
use parallax::town::roundabout::arm_start_m;
use parallax::town::underpass::Underpass;
use parallax::town::{frame_at, parse_town_str, StaticTown, TownDesc};

use crate::common::towns::{level_frame, static_town_scene, surfaces_below, town, town_file};
use crate::parking::{corners, parked_bodies, quads_overlap};

const SEED: u64 = 3;
/// The towns with parking lanes.
const LANE_TOWNS: [&str; 3] = ["town01", "town02", "town03"];
/// Far edge of a junction's stop line beyond its edge (`routes`), metres.
const STOP_LINE_END_M: f64 = 4.2;
/// Far edge of a roundabout arm's crosswalk beyond the arm start, metres.
const RING_CROSSWALK_END_M: f64 = 9.5;

fn with(name: &str, key_value: &str) -> Result<TownDesc, String> {
    let text = std::fs::read_to_string(town_file(name)).unwrap();
    // The key replaced, or added before the traffic density.
    let text: String = text
        .lines()
        .filter(|l| !l.starts_with(key_value.split(' ').next().unwrap()))
        .map(|l| {
            if l.starts_with("traffic_density") {
                format!("{key_value}\n{l}\n")
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    parse_town_str(&text, format!("{name}.toml").as_ref())
}

#[test]
fn parking_lane_m_is_refused_out_of_range_without_sidewalks_and_beside_laybys() {
    for bad in ["1.5", "2.1", "2.7", "-2.2", "nan"] {
        let e = with("town02", &format!("parking_lane_m = {bad}")).unwrap_err();
        assert!(
            e.starts_with("town02.toml: parking_lane_m: must be 0 or in [2.15, 2.6], got"),
            "{e}"
        );
    }
    for ok in ["2.15", "2.6"] {
        with("town01", &format!("parking_lane_m = {ok}")).unwrap();
    }
    // Highway towns, country roads (no sidewalks).
    for name in ["town04", "town06", "town07"] {
        let e = with(name, "parking_lane_m = 2.2").unwrap_err();
        assert!(
            e.starts_with(&format!(
                "{name}.toml: parking_lane_m: a parking lane needs"
            )),
            "{e}"
        );
    }
    // Wide sidewalks take lay-bys: one or the other.
    for name in ["town05", "town10"] {
        let e = with(name, "parking_lane_m = 2.2").unwrap_err();
        assert!(
            e.contains("parking_lane_m: a town has a parking lane or lay-bys, not both"),
            "{e}"
        );
    }
    // The command line exits 2 naming the key.
    let dir = std::env::temp_dir().join(format!("parallax_lane_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(town_file("town01")).unwrap();
    let file = dir.join("town01.toml");
    std::fs::write(
        &file,
        text.replace("parking_lane_m = 2.2", "parking_lane_m = 3.0"),
    )
    .unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_parallax"))
        .args(["town", file.to_str().unwrap(), "--seed", "0"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("parking_lane_m: must be 0 or in"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A level-grid point's road: (centreline offset u, distance along from
/// the nearest grid node, that node) on the x-road or y-road nearest it.
fn road_coords(l: &Layout, q: [f64; 2]) -> (f64, f64, (usize, usize)) {
    let p = l.pitch_m;
    let near = |v: f64, n: usize| ((v / p).round().clamp(0.0, n as f64)) as usize;
    let (i, j) = (near(q[0], l.nx), near(q[1], l.ny));
    let (ux, uy) = (q[1] - j as f64 * p, q[0] - i as f64 * p);
    if ux.abs() <= uy.abs() {
        (ux, uy.abs(), (i, j))
    } else {
        (uy, ux.abs(), (i, j))
    }
}

#[test]
fn parked_cars_stand_in_the_strips_off_the_lanes_and_junctions() {
    for name in LANE_TOWNS {
        let desc = town(name);
        let l = Layout::new(&desc);
        let warp = Warp::new(&desc, SEED);
        let u = Underpass::of(&l);
        let (objects, bays) = StaticTown::new(&desc, SEED).objects_and_bays();
        let cars = parked_bodies(&objects);
        let fill = cars.len() as f64 / bays.len() as f64;
        assert!(bays.len() > 150, "{name}: {} bays", bays.len());
        assert!((fill - desc.parking_density).abs() < 0.1, "{name}: {fill}");
        let (hw, drive) = (l.road_w_m / 2.0, l.drive_hw());
        assert!((hw - drive - desc.parking_lane_m).abs() < 1e-12);
        // A bent car stands rigidly at W(centre), turned with its kerb (W's
        // Jacobian), so its corners leave the bent strip by W's stretch
        // (≤ 3.3 % of the ≤ 2.6 m half diagonal): towards the kerb only,
        // the lanes are kept exactly.
        let kerb_tol = if warp.is_some() { 0.09 } else { 1e-9 };
        let mut worst_gap = f64::INFINITY;
        for o in &cars {
            for q in corners(o) {
                let q = warp.as_ref().map_or(q, |w| w.unmap(q));
                let (off, along, node) = road_coords(&l, q);
                let at = format!("{name}: car at {:?}, corner {q:?}", o.transform.translate);
                assert!(
                    off.abs() >= drive && off.abs() <= hw + kerb_tol,
                    "{at}: {off}"
                );
                worst_gap = worst_gap.min(off.abs() - drive);
                let clear = if l.roundabout == Some(node) {
                    arm_start_m(&l) + RING_CROSSWALK_END_M
                } else {
                    hw + STOP_LINE_END_M
                };
                assert!(along >= clear, "{at}: {along} m from junction {node:?}");
                let pt = parallax::town::layout::Rect::centered(q, [0.0, 0.0]);
                assert!(!l.near_roundabout(&pt), "{at}");
                assert!(!l.river_band().is_some_and(|b| b.overlaps(&pt)), "{at}");
                assert!(!u.is_some_and(|u| u.beside(&pt)), "{at}: over the cut");
            }
        }
        eprintln!(
            "{name}: {} cars in {} bays, nearest the lane {worst_gap:.3} m",
            cars.len(),
            bays.len()
        );
        // The cars' own placement (level plan) matches the objects'.
        assert_eq!(cars_in(&bays, SEED, desc.parking_density).len(), cars.len());
    }
}

#[test]
fn the_kerb_stands_at_the_strips_outer_edge() {
    let (road, line, walk, soil) = (
        class_id("road").unwrap(),
        class_id("road_line").unwrap(),
        class_id("sidewalk").unwrap(),
        class_id("terrain").unwrap(),
    );
    for name in ["town02", "town03"] {
        let desc = town(name);
        let l = Layout::new(&desc);
        let warp = Warp::new(&desc, SEED);
        // The kerb from the description: the lanes, then the strip.
        let lanes = desc.lanes_per_direction as f64 * desc.lane_width_m;
        let (p, hw, sw) = (l.pitch_m, lanes + desc.parking_lane_m, l.sidewalk_m);
        let origin = glam::DVec3::new(1.5 * p, p, 0.0);
        let built = static_town_scene(&desc, SEED, &town_file(name), origin);
        let (mut checked, mut skipped, mut walks) = (0, 0, 0);
        // Across x-road 1 mid-block at three places, both sides.
        for x in [1.35 * p, 1.5 * p, 1.65 * p] {
            for k in -200..=200 {
                let u = k as f64 * (hw + sw) / 200.0;
                let a = u.abs();
                // Off the kerb's face (bent chords stay within 5 cm).
                if (a - hw).abs() < 0.05 || a > hw + sw - 0.05 {
                    continue;
                }
                let q = [x, p + u];
                let q = warp.as_ref().map_or(q, |w| w.map(q));
                let hits = surfaces_below(&built, origin, (q[0], q[1], 40.0));
                // Through furniture or a canopy: not the ground's story.
                if hits.iter().any(|h| h.1 > 0.2) {
                    skipped += 1;
                    continue;
                }
                let (c, z) = hits[0];
                checked += 1;
                if a < hw {
                    assert!(c == road || c == line, "{name}: u {u}: class {c}");
                    assert!(z.abs() < 0.01, "{name}: u {u}: z {z}");
                } else if c == walk {
                    assert!((0.13..0.16).contains(&z), "{name}: u {u}: z {z}");
                    walks += 1;
                } else {
                    // A street tree's pit (soil) in the walk.
                    assert!(
                        c == soil && z > -0.05 && z < 0.16,
                        "{name}: u {u}: class {c} at {z}"
                    );
                }
            }
        }
        // (Town02's many street trees hide about a quarter of the rays.)
        assert!(
            checked > 2 * skipped && checked > 800,
            "{name}: {checked} / {skipped}"
        );
        eprintln!("{name}: {checked} rays checked ({walks} on the sidewalk), {skipped} through furniture or trees");
        assert!(walks > 100, "{name}: {walks} rays on the sidewalk");
    }
}

#[test]
fn no_moving_vehicle_touches_a_parked_car_over_600_frames() {
    for name in LANE_TOWNS {
        let desc = town(name);
        let (_, bays) = StaticTown::new(&desc, SEED).objects_and_bays();
        let parked: Vec<[[f64; 2]; 4]> = cars_in(&bays, SEED, desc.parking_density)
            .iter()
            .map(|c| c.corners())
            .collect();
        let mut near = 0;
        for frame in 0..600 {
            let f = level_frame(&desc, SEED, frame_at(&desc, SEED, frame));
            for v in std::iter::once(&f.ego).chain(&f.vehicles) {
                let c = v.corners();
                for q in &parked {
                    let (dx, dy) = (q[0][0] - c[0][0], q[0][1] - c[0][1]);
                    near += (dx.hypot(dy) < 8.0) as usize;
                    assert!(
                        !quads_overlap(&c, q),
                        "{name} frame {frame}: {} {:?} at {:?} heading {} touches a parked car {q:?}",
                        v.id,
                        v.body,
                        v.position,
                        v.heading_deg
                    );
                }
            }
        }
        eprintln!("{name}: {near} vehicle poses within 8 m of a parked car");
        assert!(near > 1000, "{name}: {near}");
    }
}
