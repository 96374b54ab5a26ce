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
use parallax::town::traffic::{Plan, VehiclePose};
use parallax::town::{frame_at, TownFrame};

use crate::common::towns::town;
use crate::traffic::quads_overlap;

const SEED: u64 = 11;

fn frames(name: &str, n: u64) -> Vec<TownFrame> {
    let desc = town(name);
    (0..n).map(|k| frame_at(&desc, SEED, k)).collect()
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
    let p = [v.position[0] + half * h.cos(), v.position[1] + half * h.sin()];
    let r = [p[0] - c[0], p[1] - c[1]];
    (r[0] * u[0] + r[1] * u[1], r[0] * u[1] - r[1] * u[0])
}

#[test]
fn traffic_turns_obeys_per_direction_signals_and_never_collides_over_long_horizons() {
    let mut total_turns = [0usize; 2];
    for (name, n) in [("town02", 3000), ("town03", 2400), ("town05", 1800), ("town06", 1800)] {
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
                let Some(q) = quadrant(v.heading_deg) else { continue };
                if let Some(p) = last_q.insert(v.id, q) {
                    match (q - p).rem_euclid(4) {
                        1 => left += 1,
                        3 => right += 1,
                        _ => {}
                    }
                }
            }
            let Some(next) = fs.get(k + 1) else { continue };
            let ahead: BTreeMap<u32, &VehiclePose> = next.vehicles.iter().map(|v| (v.id, v)).collect();
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
        assert!(left >= 5 && right >= 5, "{name}: {left} left, {right} right turns");
        if !parallax::town::signals::signal_sites(&l).is_empty() {
            assert!(passed >= 20, "{name}: only {passed} stop lines passed");
        }
        total_turns[0] += left;
        total_turns[1] += right;
    }
    println!("turns: {total_turns:?}");
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
        assert!(on_road > 100, "{name}: only {on_road} pedestrian frames on a crossing");
    }
}
