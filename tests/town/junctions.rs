//! Background traffic at junctions over long horizons (thousands of
//! frames, several towns): no two footprints on one level overlap (the
//! ego's included), no vehicle passes a stop line while its lamp is red,
//! vehicles turn left and right and go straight, cyclists ride the kerb
//! lane at their own speed with vehicles following them, brake lamps are
//! lit exactly when a vehicle slows or stands, indicators blink before the
//! turn they announce, and pedestrians are on a crossing's carriageway
//! only while every approach stands red.

use std::collections::BTreeMap;

use parallax::town::layout::Layout;
use parallax::town::signals::{axis_lamp, signals_at, Lamp};
use parallax::town::traffic::{cyclist_speed_mps, Plan, VehiclePose, ROUNDS_PER_STAND};
use parallax::town::vehicles::BodyKind;
use parallax::town::walkers::WALK_MPS;
use parallax::town::{frame_at, TownFrame};

use crate::common::towns::{level_frame, town};
use crate::traffic::quads_overlap;

const SEED: u64 = 11;

/// Frames 0..n in the level grid's plane (an organic town's carried back
/// by W⁻¹), where junction centres and stop lines lie on the grid; W is a
/// bijection, so footprints apart there stay apart in the bent world.
fn frames(name: &str, n: u64) -> Vec<TownFrame> {
    let desc = town(name);
    (0..n)
        .map(|k| level_frame(&desc, SEED, frame_at(&desc, SEED, k)))
        .collect()
}

/// Heading quadrant (0 east … 3 south) when within 2° of one, else None.
fn quadrant(h: f64) -> Option<i64> {
    let q = (h / 90.0).round();
    ((h - q * 90.0).abs() < 2.0).then_some((q as i64).rem_euclid(4))
}

/// (along, lateral) of `v`'s front relative to a junction centre `c` for
/// traffic heading `u`: lateral > 0 on that traffic's right.
fn front_rel(v: &VehiclePose, c: [f64; 2], u: [f64; 2]) -> (f64, f64) {
    let half = v.body.footprint_m()[0] / 2.0;
    let h = v.heading_deg.to_radians();
    let p = [
        v.position[0] + half * h.cos(),
        v.position[1] + half * h.sin(),
    ];
    let r = [p[0] - c[0], p[1] - c[1]];
    (r[0] * u[0] + r[1] * u[1], r[0] * u[1] - r[1] * u[0])
}

#[test]
fn traffic_turns_obeys_per_direction_signals_and_never_collides_over_long_horizons() {
    let mut total_turns = [0usize; 2];
    let mut inner_turns = [0usize; 2];
    for (name, n) in [
        ("town02", 3000),
        ("town03", 2400),
        ("town05", 1800),
        ("town06", 1800),
    ] {
        let desc = town(name);
        let l = Layout::new(&desc);
        let hw = l.road_w_m / 2.0;
        let line = -(hw + 4.2);
        let fs = frames(name, n);
        let mut last_q: BTreeMap<u32, i64> = BTreeMap::new();
        let (mut left, mut right, mut passed) = (0usize, 0usize, 0usize);
        for (k, f) in fs.iter().enumerate() {
            let all: Vec<&VehiclePose> = std::iter::once(&f.ego).chain(&f.vehicles).collect();
            for (i, a) in all.iter().enumerate() {
                let ca = a.corners();
                for b in &all[i + 1..] {
                    assert!(
                        !(a.same_level(b) && quads_overlap(&ca, &b.corners())),
                        "{name} frame {k}: vehicles {} ({:?}) and {} ({:?}) overlap",
                        a.id,
                        a.body,
                        b.id,
                        b.body
                    );
                }
            }
            for v in &f.vehicles {
                let Some(q) = quadrant(v.heading_deg) else {
                    continue;
                };
                if let Some(p) = last_q.insert(v.id, q) {
                    // At an interior junction, where going straight is legal
                    // too (town corners and edges force turns).
                    let ij = [v.position[0], v.position[1]].map(|c| (c / l.pitch_m).round());
                    let inner =
                        ij[0] >= 1.0 && ij[0] < l.nx as f64 && ij[1] >= 1.0 && ij[1] < l.ny as f64;
                    match (q - p).rem_euclid(4) {
                        1 => {
                            left += 1;
                            inner_turns[0] += inner as usize;
                        }
                        3 => {
                            right += 1;
                            inner_turns[1] += inner as usize;
                        }
                        _ => {}
                    }
                }
            }
            let Some(next) = fs.get(k + 1) else { continue };
            let ahead: BTreeMap<u32, &VehiclePose> =
                next.vehicles.iter().map(|v| (v.id, v)).collect();
            for sig in signals_at(&desc, f.frame) {
                let (c, u) = (sig.site.centre(&l), sig.site.dir());
                for v in &f.vehicles {
                    if quadrant(v.heading_deg) != Some(sig.site.dir_index() as i64) {
                        continue;
                    }
                    let Some(w) = ahead.get(&v.id) else { continue };
                    let ((a, lat), (b, _)) = (front_rel(v, c, u), front_rel(w, c, u));
                    if lat > 0.0 && lat < hw && a <= line + 0.01 && b > line + 0.01 {
                        assert_ne!(
                            sig.lamp,
                            Lamp::Red,
                            "{name} frame {}: vehicle {} passed a red light at {:?}",
                            f.frame,
                            v.id,
                            sig.site.junction
                        );
                        passed += 1;
                    }
                }
            }
        }
        println!("{name}: {left} left turns, {right} right turns, {passed} stop lines passed");
        assert!(
            left >= 5 && right >= 5,
            "{name}: {left} left, {right} right turns"
        );
        if !parallax::town::signals::signal_sites(&l).is_empty() {
            assert!(passed >= 20, "{name}: only {passed} stop lines passed");
        }
        total_turns[0] += left;
        total_turns[1] += right;
    }
    println!("turns: {total_turns:?}, at interior junctions {inner_turns:?}");
    assert!(
        inner_turns.iter().all(|&n| n >= 10),
        "turns at interior junctions: {inner_turns:?}"
    );
}

#[test]
fn pedestrians_cross_the_carriageway_only_while_every_approach_stands_red() {
    for name in ["town02", "town03", "town10"] {
        let desc = town(name);
        let l = Layout::new(&desc);
        let sched = Plan::new(&desc).schedule.clone();
        let hw = l.road_w_m / 2.0;
        let mut on_road = 0;
        for f in frames(name, 1500) {
            let t = f.time_s;
            for p in &f.pedestrians {
                let (x, y) = (p.position[0], p.position[1]);
                let near = |v: f64| (v - (v / l.pitch_m).round() * l.pitch_m).abs();
                if near(x) >= hw && near(y) >= hw {
                    continue; // not on a carriageway
                }
                on_road += 1;
                // The stand by the schedule's numbers (time 0 starts one):
                // τ seconds into it, a crosser who set off from the kerb as
                // it began is at most WALK_MPS · τ into the carriageway.
                let window = sched.green_s + sched.amber_s + sched.all_red_s;
                let cycle = 2.0 * ROUNDS_PER_STAND as f64 * window + sched.stop_s;
                let tau = t.rem_euclid(cycle);
                assert!(
                    tau < sched.stop_s,
                    "{name} frame {}: on the road {tau} s into the cycle",
                    f.frame
                );
                let h = p.heading_deg.to_radians();
                let across_x = h.cos().abs() > 0.5;
                let (v, u) = if across_x { (x, h.cos()) } else { (y, h.sin()) };
                let into = hw + (v - (v / l.pitch_m).round() * l.pitch_m) * u.signum();
                assert!(
                    into <= WALK_MPS * tau + 1e-6,
                    "{name} frame {}: pedestrian {} {into} m into the road {tau} s into the stand",
                    f.frame,
                    p.id
                );
                for dir in 0..4 {
                    assert_eq!(
                        axis_lamp(&sched, dir, t),
                        Lamp::Red,
                        "{name} frame {}: pedestrian {} on the road at ({x:.1}, {y:.1})",
                        f.frame,
                        p.id
                    );
                }
                assert!(sched.standing(t));
            }
        }
        assert!(
            on_road > 100,
            "{name}: only {on_road} pedestrian frames on a crossing"
        );
    }
}

/// Per vehicle id, its poses in consecutive frames `k` (None where absent).
fn tracks(fs: &[TownFrame]) -> BTreeMap<u32, Vec<Option<VehiclePose>>> {
    let mut out: BTreeMap<u32, Vec<Option<VehiclePose>>> = BTreeMap::new();
    for (k, f) in fs.iter().enumerate() {
        for v in &f.vehicles {
            out.entry(v.id).or_insert_with(|| vec![None; fs.len()])[k] = Some(v.clone());
        }
    }
    out
}

fn dist(a: &VehiclePose, b: &VehiclePose) -> f64 {
    (a.position[0] - b.position[0]).hypot(a.position[1] - b.position[1])
}

#[test]
fn brake_lamps_follow_the_speed_and_indicators_announce_the_turn() {
    let desc = town("town03");
    let fs = frames("town03", 1200);
    let (mut lit_checked, mut dark_checked, mut announced) = (0, 0, 0);
    for (id, t) in tracks(&fs) {
        for k in 1..t.len() - 1 {
            let (Some(a), Some(b), Some(c)) = (&t[k - 1], &t[k], &t[k + 1]) else {
                continue;
            };
            // Speeds before and after frame k, from the positions.
            let (v0, v1) = (dist(a, b) * desc.fps, dist(b, c) * desc.fps);
            if v1 < v0 - 0.05 || (v0 < 0.01 && v1 < 0.01) {
                assert!(
                    b.lamps.brake,
                    "vehicle {id} frame {k}: {v0} → {v1} m/s, brake dark"
                );
                lit_checked += 1;
            } else if v1 > v0 + 0.01 && v0 > 0.1 {
                assert!(
                    !b.lamps.brake,
                    "vehicle {id} frame {k}: {v0} → {v1} m/s, brake lit"
                );
                dark_checked += 1;
            }
        }
        // Every indicator lit is followed by that turn, before any other.
        for k in 0..t.len() {
            let Some(b) = &t[k] else { continue };
            if !(b.lamps.left || b.lamps.right) {
                continue;
            }
            assert!(
                !(b.lamps.left && b.lamps.right),
                "vehicle {id}: both indicators"
            );
            let Some(q0) = quadrant(b.heading_deg) else {
                continue;
            };
            let next = t[k..]
                .iter()
                .flatten()
                .filter_map(|v| quadrant(v.heading_deg))
                .find(|&q| q != q0);
            if let Some(q) = next {
                let want = if b.lamps.left { 1 } else { 3 };
                assert_eq!((q - q0).rem_euclid(4), want, "vehicle {id} frame {k}");
                announced += 1;
            }
        }
    }
    assert!(
        lit_checked > 1000 && dark_checked > 1000,
        "{lit_checked} {dark_checked}"
    );
    assert!(
        announced > 100,
        "only {announced} indicator frames followed by their turn"
    );
}

#[test]
fn cyclists_ride_the_kerb_lane_at_their_own_speed_and_are_followed() {
    let mut followed = 0;
    for name in ["town02", "town03", "town10"] {
        let desc = town(name);
        let l = Layout::new(&desc);
        let limit = cyclist_speed_mps(desc.speed_kmh / 3.6);
        assert!(limit < desc.speed_kmh / 3.6);
        let fs = frames(name, 600);
        let tr = tracks(&fs);
        let (mut bikes, mut on_kerb) = (0, [0usize; 2]);
        for (k, f) in fs.iter().enumerate().skip(1) {
            for b in f.vehicles.iter().filter(|v| v.body == BodyKind::Bicycle) {
                bikes += 1;
                assert!(b.body.footprint_m()[0] < 2.0, "a bicycle's own length");
                if let Some(Some(p)) = tr[&b.id].get(k - 1) {
                    let v = dist(p, b) * desc.fps;
                    assert!(
                        v <= limit + 1e-6,
                        "{name} frame {k}: bicycle {} at {v} m/s",
                        b.id
                    );
                }
                // On a straight: its lateral offset is the kerb lane's centre.
                let exact = (b.heading_deg / 90.0 - (b.heading_deg / 90.0).round()).abs() < 1e-9;
                if let Some(q) = quadrant(b.heading_deg).filter(|_| exact) {
                    let across = if q % 2 == 0 {
                        b.position[1]
                    } else {
                        b.position[0]
                    };
                    let off = (across - (across / l.pitch_m).round() * l.pitch_m).abs();
                    let kerb = (l.lanes as f64 - 0.5) * l.lane_w_m;
                    if off < l.road_w_m / 2.0 {
                        // On a lane centre; the kerb lane's unless a town
                        // corner left it no move (then it changed lanes).
                        let lane = off / l.lane_w_m - 0.5;
                        assert!(
                            (lane - lane.round()).abs() < 1e-6,
                            "{name}: bicycle {} at {off} m",
                            b.id
                        );
                        on_kerb[usize::from((off - kerb).abs() < 1e-6)] += 1;
                    }
                }
                // A vehicle close behind it in its lane keeps its pace.
                let h = b.heading_deg.to_radians();
                for v in &f.vehicles {
                    let d = [b.position[0] - v.position[0], b.position[1] - v.position[1]];
                    let along = d[0] * h.cos() + d[1] * h.sin();
                    let lat = (d[1] * h.cos() - d[0] * h.sin()).abs();
                    let gap = along - (b.body.footprint_m()[0] + v.body.footprint_m()[0]) / 2.0;
                    // Heading its way (not crossing behind it at a junction).
                    let dh = (v.heading_deg - b.heading_deg).rem_euclid(360.0);
                    let its_way = dh.min(360.0 - dh) < 30.0;
                    if v.id == b.id || lat > 0.3 || !its_way || !(1.0..4.0).contains(&gap) {
                        continue;
                    }
                    if let Some(Some(p)) = tr[&v.id].get(k - 1) {
                        let speed = dist(p, v) * desc.fps;
                        if speed > 1.0 {
                            assert!(
                                speed <= limit + 0.2,
                                "{name} frame {k}: {} passes through",
                                v.id
                            );
                            followed += 1;
                        }
                    }
                }
            }
        }
        assert!(bikes > 0, "{name}: no bicycle");
        assert!(
            on_kerb[1] >= 9 * on_kerb[0],
            "{name}: {on_kerb:?} frames off / on the kerb lane"
        );
    }
    assert!(
        followed > 20,
        "only {followed} frames of a vehicle following a cyclist"
    );
}
