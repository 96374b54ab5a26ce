//! Pedestrians in closed form: walkers circle blocks on the sidewalks, and
//! crossers circle an interior junction, crossing one of its four
//! crosswalks in every standing phase of the traffic clock (when every
//! crosswalk on an interior road is clear, see `traffic`) and walking round
//! the sidewalk corner to the next crosswalk while traffic drives.
//!
//! A crosswalk lies 0.5–3.5 m from the junction edge; crossers walk its
//! middle line, 2 m out, from 0.8 m onto one sidewalk to 0.8 m onto the other.

use super::desc::TownDesc;
use super::layout::Layout;
use super::people::{Person, VARIANTS};
use super::rng::{tag, Rng};
use super::traffic::{PedestrianPose, Schedule};

/// Walking speed, m/s.
pub const WALK_MPS: f64 = 1.3;
/// Pedestrian slots per block loop.
const WALK_SLOTS: u64 = 24;
/// First id of crossers (walkers count up from 0).
const CROSSER_ID_BASE: u32 = 5000;
/// Crosswalk centre line, metres from the junction edge.
const CROSS_AT_M: f64 = 2.0;
/// How far onto the sidewalk a crossing starts and ends, metres.
const ONTO_WALK_M: f64 = 0.8;

/// Walk-cycle phase of variant `variant` after walking `walked_m` metres.
fn phase(variant: u32, walked_m: f64) -> f64 {
    (walked_m / Person::variant(variant).body.stride_m()).rem_euclid(1.0)
}

/// Every pedestrian at time `t` (none on country roads without sidewalks).
pub fn pedestrians(
    desc: &TownDesc,
    l: &Layout,
    sched: &Schedule,
    seed: u64,
    t: f64,
) -> Vec<PedestrianPose> {
    let mut out = Vec::new();
    if !l.sidewalks {
        return out;
    }
    walkers(desc, l, seed, t, &mut out);
    crossers(desc, l, sched, seed, t, &mut out);
    out
}

fn walkers(desc: &TownDesc, l: &Layout, seed: u64, t: f64, out: &mut Vec<PedestrianPose>) {
    let inset = l.road_w_m / 2.0 + l.sidewalk_m / 2.0 + 0.1;
    let side = l.pitch_m - 2.0 * inset;
    let perimeter = 4.0 * side;
    let share = (desc.traffic_density * 0.35).min(1.0);
    for j in 0..l.ny {
        for i in 0..l.nx {
            if l.block_touches_roundabout(i, j) {
                continue; // their loop would cut across the ring
            }
            let (x0, y0) = (i as f64 * l.pitch_m + inset, j as f64 * l.pitch_m + inset);
            for slot in 0..WALK_SLOTS {
                let mut r = Rng::new(&[seed, tag::PEDESTRIAN, i as u64, j as u64, slot]);
                if !r.chance(share) {
                    continue;
                }
                let dir = if r.chance(0.5) { 1.0 } else { -1.0 };
                let variant = r.index(VARIANTS as usize) as u32;
                let s0 = slot as f64 * perimeter / WALK_SLOTS as f64;
                // Opposite walkers use the two halves of the sidewalk: the
                // block's loop grown (or shrunk) by `lane` on every side,
                // so its corners join (no jump turning a corner).
                let lane = dir * 0.45;
                let (x0, y0, side) = (x0 - lane, y0 - lane, side + 2.0 * lane);
                let s = (s0 * side / (perimeter / 4.0) + dir * WALK_MPS * t).rem_euclid(4.0 * side);
                // Side and distance along it from one floor, so they agree
                // at the corners (`s % side` and `s / side` can round apart
                // there: a jump of a whole side).
                let k = (s / side).floor();
                let (side_k, u) = (k as u32 % 4, (s - k * side).clamp(0.0, side));
                let (x, y, h) = match side_k {
                    0 => (x0 + u, y0, 0.0),
                    1 => (x0 + side, y0 + u, 90.0),
                    2 => (x0 + side - u, y0 + side, 180.0),
                    _ => (x0, y0 + side - u, 270.0),
                };
                let heading_deg = if dir > 0.0 { h } else { (h + 180.0) % 360.0 };
                let id = ((j * l.nx + i) as u64 * WALK_SLOTS + slot) as u32;
                out.push(PedestrianPose {
                    id: id.min(CROSSER_ID_BASE - 1),
                    variant,
                    // Always walking: the cycle runs with the distance.
                    phase: Some(phase(variant, s0 + WALK_MPS * t)),
                    position: [x, y, l.walk_z()],
                    heading_deg,
                });
            }
        }
    }
}

/// The four crossings of junction (x, y), counter-clockwise from the east
/// arm: (start, end) on the sidewalks.
fn crossings(l: &Layout, x: f64, y: f64) -> [([f64; 2], [f64; 2]); 4] {
    let hw = l.road_w_m / 2.0;
    let (a, b) = (hw + CROSS_AT_M, hw + ONTO_WALK_M);
    [
        ([x + a, y - b], [x + a, y + b]),
        ([x + b, y + a], [x - b, y + a]),
        ([x - a, y + b], [x - a, y - b]),
        ([x - b, y - a], [x + b, y - a]),
    ]
}

/// Metres a crosser has walked by time `t`: every cycle adds the corner
/// (while traffic drives) and the crossing (while it stands), each cut short
/// where the phase ends first; the four corners and crossings of a junction
/// are the same lengths.
fn crosser_walked(l: &Layout, sched: &Schedule, t: f64) -> f64 {
    let t = sched.cycle_time_s(t);
    let [(a, b), (_, d)] = [crossings(l, 0.0, 0.0)[0], crossings(l, 0.0, 0.0)[3]];
    let dist = |p: [f64; 2], q: [f64; 2]| (q[0] - p[0]).hypot(q[1] - p[1]);
    let (cross, corner) = (dist(a, b), dist(d, a));
    let (cycle, moving) = (sched.cycle_s(), sched.moving_s());
    let n = (t / cycle).floor();
    let tau = t - n * cycle;
    let per_cycle = corner.min(WALK_MPS * moving) + cross.min(WALK_MPS * (cycle - moving));
    let this_cycle = if tau < moving {
        corner.min(WALK_MPS * tau)
    } else {
        corner.min(WALK_MPS * moving) + cross.min(WALK_MPS * (tau - moving))
    };
    n * per_cycle + this_cycle
}

fn lerp(p: [f64; 2], q: [f64; 2], u: f64) -> [f64; 2] {
    [p[0] + (q[0] - p[0]) * u, p[1] + (q[1] - p[1]) * u]
}

fn crossers(
    desc: &TownDesc,
    l: &Layout,
    sched: &Schedule,
    seed: u64,
    t: f64,
    out: &mut Vec<PedestrianPose>,
) {
    let hw = l.road_w_m / 2.0;
    let cycle = sched.cycle_s();
    let n = (sched.cycle_time_s(t) / cycle).floor();
    let tau = sched.cycle_time_s(t) - n * cycle;
    let mut id = CROSSER_ID_BASE;
    for j in 1..l.ny {
        for i in 1..l.nx {
            if l.roundabout == Some((i, j)) || l.underpass == Some((i, j)) {
                id += 2;
                continue;
            }
            let (x, y) = (i as f64 * l.pitch_m, j as f64 * l.pitch_m);
            let walks = crossings(l, x, y);
            for slot in 0..2u64 {
                id += 1;
                let mut r = Rng::new(&[seed, tag::CROSSER, i as u64, j as u64, slot]);
                if !r.chance((desc.traffic_density * 1.5).min(1.0)) {
                    continue;
                }
                let variant = r.index(VARIANTS as usize) as u32;
                let first = r.int(0, 3) as i64 + 2 * slot as i64;
                // Crossing c happens in the standing phase of cycle n.
                let c = (n as i64 + first).rem_euclid(4) as usize;
                let (p, heading, u) = if tau >= sched.moving_s() {
                    let (a, b) = walks[c];
                    let len = ((b[0] - a[0]).powi(2) + (b[1] - a[1]).powi(2)).sqrt();
                    let u = (WALK_MPS * (tau - sched.moving_s()) / len).min(1.0);
                    (lerp(a, b, u), (b[1] - a[1]).atan2(b[0] - a[0]), u)
                } else {
                    // Round the corner from the previous crossing's end.
                    let prev = (c + 3) % 4;
                    let (from, to) = (walks[prev].1, walks[c].0);
                    let len = ((to[0] - from[0]).powi(2) + (to[1] - from[1]).powi(2)).sqrt();
                    let u = (WALK_MPS * tau / len).min(1.0);
                    (
                        lerp(from, to, u),
                        (to[1] - from[1]).atan2(to[0] - from[0]),
                        u,
                    )
                };
                // Waiting at the kerb (end of a leg) they stand.
                let walking = u < 1.0;
                let walked = crosser_walked(l, sched, t);
                let on_road = (p[0] - x).abs() < hw || (p[1] - y).abs() < hw;
                let z = if on_road { 0.008 } else { l.walk_z() };
                out.push(PedestrianPose {
                    id,
                    variant,
                    phase: walking.then(|| phase(variant, walked)),
                    position: [p[0], p[1], z],
                    heading_deg: heading.to_degrees().rem_euclid(360.0),
                });
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;
    use crate::town::{frame_at, load_named_town};

    /// Town03 at 100 frames per second: one frame is 1.3 cm of walking.
    fn town03() -> TownDesc {
        let mut desc = load_named_town("town03", None).expect("built in").desc;
        desc.fps = 100.0;
        desc
    }

    #[test]
    fn the_walk_cycle_advances_with_the_distance_walked_and_stops_standing() {
        // A grid town: an organic town's warp (town03) stretches the
        // level walk by up to 3 %.
        let mut desc = load_named_town("town05", None).expect("built in").desc;
        desc.fps = 100.0;
        let (mut walking, mut standing, mut checked) = (0, 0, 0);
        for k in [0u64, 777, 2020, 4321, 9000] {
            let f0 = frame_at(&desc, 0, k).pedestrians;
            let mut count: BTreeMap<u32, u32> = BTreeMap::new();
            for p in &f0 {
                *count.entry(p.id).or_default() += 1;
            }
            let a: BTreeMap<u32, PedestrianPose> = f0.into_iter().map(|p| (p.id, p)).collect();
            for q in frame_at(&desc, 0, k + 1).pedestrians {
                if count[&q.id] > 1 {
                    eprintln!("id {} shared by {} pedestrians", q.id, count[&q.id]);
                    continue;
                }
                let p = &a[&q.id];
                assert_eq!(p.variant, q.variant, "a person keeps their look");
                let moved = (q.position[0] - p.position[0]).hypot(q.position[1] - p.position[1]);
                match (p.phase, q.phase) {
                    (Some(f0), Some(f1)) => {
                        walking += 1;
                        let stride = Person::variant(p.variant).body.stride_m();
                        let walked = (f1 - f0).rem_euclid(1.0) * stride;
                        // Never more phase than distance; equal on a
                        // straight (a corner's chord is shorter).
                        assert!(
                            walked <= WALK_MPS / desc.fps + 1e-9,
                            "{walked} m in a frame"
                        );
                        assert!(
                            moved <= walked + 1e-9,
                            "frame {k}: {p:?} → {q:?} moved {moved} m but walked {walked} m"
                        );
                        if (moved - walked).abs() < 1e-9 {
                            checked += 1;
                        }
                    }
                    (None, None) => {
                        standing += 1;
                        assert!(moved < 1e-12, "a standing person moved {moved} m");
                    }
                    _ => {}
                }
            }
        }
        assert!(
            walking > 200 && standing > 0,
            "{walking} walking, {standing} standing"
        );
        assert!(checked * 10 > walking * 9, "{checked} of {walking} exact");
    }

    #[test]
    fn crossers_walk_the_sum_of_their_legs_continuously() {
        let desc = town03();
        let l = Layout::new(&desc);
        let sched = super::super::traffic::Plan::new(&desc).schedule.clone();
        let cycle = sched.cycle_s();
        // Continuous: no jump at the phase boundaries or cycle ends (on
        // the cycle's clock, `Schedule::cycle_time_s`, which leads t by
        // `moving_s`).
        let m = sched.moving_s();
        for t in [m, cycle, 3.0 * cycle + m].map(|u| u - m) {
            let d = crosser_walked(&l, &sched, t + 1e-7) - crosser_walked(&l, &sched, t - 1e-7);
            assert!(
                (0.0..=2.0 * WALK_MPS * 1e-7 + 1e-12).contains(&d),
                "jump {d} at {t}"
            );
        }
        // Per cycle: one corner (a diagonal) and one crossing (the road
        // plus 0.8 m onto each sidewalk), each cut short by its phase.
        let hw = l.road_w_m / 2.0;
        let cross = 2.0 * (hw + ONTO_WALK_M);
        let corner = std::f64::consts::SQRT_2 * (CROSS_AT_M - ONTO_WALK_M);
        let per =
            (crosser_walked(&l, &sched, 6.0 * cycle) - crosser_walked(&l, &sched, cycle)) / 5.0;
        let want = corner.min(WALK_MPS * sched.moving_s())
            + cross.min(WALK_MPS * (cycle - sched.moving_s()));
        assert!((per - want).abs() < 1e-9, "{per} vs {want}");
    }
}
