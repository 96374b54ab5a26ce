//! Where a drive's background vehicles start: along the straight of every
//! directed link, in its inner and outer lanes (the only lanes whose moves
//! need no lane change), spaced by their bodies plus a 2.2 s headway at
//! the speed limit (so no platoon starts compressed: braking to where the
//! one ahead is, as `sim` does, a follower starts above 0.7 × the limit),
//! each place
//! filled with a chance from the town's traffic density (higher the
//! further apart the places are). Bicycles start
//! only in the outer (kerb-side) lane, and not in highway towns (limit
//! above 60 km/h); with several lanes buses and
//! trucks start only in the inner lane (its left turns are the widest),
//! and only cars elsewhere. Seeded per (seed, drive, chunk, link, lane).

use super::sim::{Agent, FOLLOW_GAP_M};
use super::{cyclist_speed_mps, weighted_body, Plan};
use crate::town::layout::Layout;
use crate::town::materials::draw_paint;
use crate::town::rng::{tag, Rng};
use crate::town::roundabout::arm_start_m;
use crate::town::routes::drive::{links, DrivePath};
use crate::town::routes::Turns;
use crate::town::vehicles::BodyKind;

/// Share of the places that hold a vehicle, per unit of traffic density.
const FILL_PER_DENSITY: f64 = 0.5;
/// Distance kept from a junction's edge (or a curve's end), metres.
const EDGE_M: f64 = 8.0;
/// Fastest speed limit of towns with bicycles (not on highways), m/s.
const BICYCLE_ROADS_MPS: f64 = 60.0 / 3.6;
/// Gap between the bodies of a lane at the start, at least, metres.
const GAP_M: f64 = 6.0;
/// Time headway between the bodies of a lane at the start, seconds: a
/// follower braking to where its leader is starts at ≥ 0.7 × the limit.
const HEADWAY_S: f64 = 2.2;

/// The background vehicles of chunk `chunk` of drive `drive` at its
/// start, ids from 1.
pub(super) fn spawn(
    seed: u64,
    drive: u64,
    chunk: u64,
    density: f64,
    l: &Layout,
    plan: &Plan,
) -> Vec<Agent> {
    let turns = &plan.schedule.turns;
    let hw = l.road_w_m / 2.0;
    // Where a link's straight begins past junction (i, j), metres.
    let edge = |j: (usize, usize)| {
        if l.loop_corner_at(j.0, j.1) {
            l.loop_radius_m + EDGE_M
        } else if l.roundabout == Some(j) {
            arm_start_m(l) + 12.0
        } else {
            hw + EDGE_M
        }
    };
    let dirs = [[1i64, 0], [0, 1], [-1, 0], [0, -1]];
    let lanes: Vec<u32> = if l.lanes > 1 {
        vec![0, l.lanes - 1]
    } else {
        vec![0]
    };
    let cars: Vec<BodyKind> = turns
        .bodies
        .iter()
        .copied()
        .filter(|b| b.seat().is_none())
        .collect();
    // Long bodies only where their wide right turn at a town's corner fits.
    let wide = Turns::merged(l.lane_w_m, l.lanes);
    let long: Vec<BodyKind> = [BodyKind::Bus, BodyKind::Truck]
        .into_iter()
        .filter(|b| wide.bodies.contains(b))
        .collect();
    // A following distance at the limit (`HEADWAY_S` plus the standing
    // gap `sim` keeps, at least `GAP_M`), places filled more often the
    // further apart they are.
    let v = plan.schedule.speed_mps;
    let gap_m = (v * HEADWAY_S + FOLLOW_GAP_M).max(GAP_M);
    let fill = (density * FILL_PER_DENSITY * gap_m / GAP_M).min(1.0);
    let mut out = Vec::new();
    for (k, (from, d)) in links(l).into_iter().enumerate() {
        let to = (
            (from.0 as i64 + dirs[d][0]) as usize,
            (from.1 as i64 + dirs[d][1]) as usize,
        );
        let (a0, a1) = (edge(from), l.pitch_m - edge(to));
        for &lane in &lanes {
            let mut r = Rng::new(&[seed, tag::TRAFFIC, drive, chunk, k as u64, lane as u64]);
            let mut allowed: Vec<BodyKind> = cars.clone();
            if lane + 1 == l.lanes {
                allowed.extend(turns.bodies.iter().filter(|b| b.seat().is_some()));
                if plan.schedule.speed_mps > BICYCLE_ROADS_MPS {
                    allowed.retain(|b| *b != BodyKind::Bicycle);
                }
            } else if l.lanes > 1 {
                allowed.extend(turns.bodies.iter().filter(|b| b.seat().is_some()));
                allowed.retain(|b| *b != BodyKind::Bicycle);
                allowed.extend(&long);
            }
            let mut at = a0 + r.f64() * GAP_M;
            loop {
                let body = weighted_body(&mut r, &allowed);
                let len = body.footprint_m()[0];
                if at + len > a1 {
                    break;
                }
                if !r.chance(fill) {
                    at += len + gap_m;
                    continue;
                }
                let paint = draw_paint(r.f64());
                let moves = Rng::new(&[
                    seed,
                    tag::TRAFFIC,
                    drive,
                    chunk,
                    k as u64,
                    lane as u64,
                    out.len() as u64,
                ]);
                let centre = at + len / 2.0;
                let v_max = match body {
                    BodyKind::Bicycle => cyclist_speed_mps(plan.schedule.speed_mps),
                    _ => plan.schedule.speed_mps,
                };
                out.push(Agent {
                    id: out.len() as u32 + 1,
                    body,
                    paint,
                    path: DrivePath::background(
                        l,
                        turns,
                        k,
                        lane,
                        centre,
                        moves,
                        long.contains(&body),
                    ),
                    s: 0.0,
                    v: f64::NAN,
                    v_max,
                });
                at += len + gap_m + r.f64() * GAP_M;
            }
        }
    }
    out
}
