//! The convoy of a drive: a seeded number of lead vehicles driving the
//! ego's own `DrivePath` ahead of it, and the ego last. Every member is
//! moved like the ego (`ego::Ctx::step`), front to back, and follows the
//! one ahead, keeping `CONVOY_GAP_M` behind its rear, so the ego queues
//! behind them at red lights. The leaders are drawn per (seed, drive)
//! (`Rng::new(&[seed, tag::EGO, drive, LEADER_DRAW])`): their count
//! (`LEADER_PMF`), bodies (the town's cars by `BODY_WEIGHTS`), paints and
//! the gaps between them at frame 0. Their ids are `LEADER_ID_BASE + k`
//! (k = 1 right ahead of the ego), clear of the background's (< 20,000)
//! and of the overpass's.

use super::sim::{BLINK_HZ, SIGNAL_AHEAD_M};
use super::{weighted_body, VehicleLamps, VehiclePose};
use crate::town::materials::draw_paint;
use crate::town::rng::{tag, Rng};
use crate::town::routes::drive::{Crossing, DrivePath, Move};
use crate::town::vehicles::BodyKind;

/// Gap each convoy member keeps behind the rear of the one ahead, metres.
pub const CONVOY_GAP_M: f64 = 2.5;
/// First id of the leaders (the ego is 0, the background below 20,000,
/// the overpass's from 20,001).
pub const LEADER_ID_BASE: u32 = 24_000;
/// `VehiclePose::route` of a leader.
pub const CONVOY_ROUTE: usize = usize::MAX - 2;
/// Chance of 0, 1, 2 and 3 leaders.
const LEADER_PMF: [f64; 4] = [0.15, 0.35, 0.3, 0.2];
/// Index after `tag::EGO` and the drive of the leaders' draws (1 draws
/// the path, 2 the ego's paint).
const LEADER_DRAW: u64 = 3;
/// Gap between two members at frame 0 beyond `CONVOY_GAP_M`: at least
/// this, plus up to `START_SPREAD_M`, metres.
const START_EXTRA_M: f64 = 4.0;
const START_SPREAD_M: f64 = 16.0;
/// Distance a leader starts clear of a junction's zone, metres.
const START_CLEAR_M: f64 = 1.0;

/// One convoy member's motion: (s, v) per frame from the drive's start.
pub(super) struct Member {
    pub id: u32,
    pub body: BodyKind,
    pub paint: &'static str,
    /// Arc length of its centre at frame 0, metres.
    pub start_m: f64,
    pub s: Vec<f64>,
    pub v: Vec<f64>,
}

impl Member {
    pub fn half(&self) -> f64 {
        self.body.footprint_m()[0] / 2.0
    }
}

/// One drive's motion: the path every member drives and the members,
/// front to back, the ego last.
pub(super) struct Drive {
    pub path: DrivePath,
    pub members: Vec<Member>,
}

impl Drive {
    /// The drive with its leaders drawn and placed ahead of the ego
    /// (`ego` at arc length 0): each `CONVOY_GAP_M` plus a seeded extra
    /// ahead of the one behind, moved on past any junction zone it would
    /// start in (nobody starts inside a junction).
    pub fn new(
        mut path: DrivePath,
        ego: Member,
        bodies: &[BodyKind],
        seed: u64,
        drive: u64,
    ) -> Self {
        let mut r = Rng::new(&[seed, tag::EGO, drive, LEADER_DRAW]);
        let mut u = r.f64();
        let n = LEADER_PMF
            .iter()
            .position(|&p| {
                u -= p;
                u < 0.0
            })
            .unwrap_or(LEADER_PMF.len() - 1);
        // Cars only: the ego's path turns right from the kerb lane, which
        // buses and trucks do not fit, and a bicycle would hold the ego
        // to its pace for the whole drive.
        let cars: Vec<BodyKind> = bodies
            .iter()
            .copied()
            .filter(|b| !matches!(b, BodyKind::Bus | BodyKind::Truck | BodyKind::Bicycle))
            .collect();
        let mut members = vec![ego];
        for k in 1..=n {
            let body = weighted_body(&mut r, &cars);
            let paint = draw_paint(r.f64());
            let gap = CONVOY_GAP_M + START_EXTRA_M + r.f64() * START_SPREAD_M;
            let behind = members.last().expect("the ego");
            let half = body.footprint_m()[0] / 2.0;
            let mut s = behind.start_m + behind.half() + gap + half;
            loop {
                path.reach(s + half + START_CLEAR_M + 1.0);
                // (A leader just moved past a crossing ends there: within
                // rounding of its clear point, which must not hold it.)
                let inside = |c: &&Crossing| {
                    s + half > c.stop_m - START_CLEAR_M
                        && s - half < c.clear_m + START_CLEAR_M - 1e-9
                };
                match path.crossings.iter().find(inside) {
                    Some(c) => s = c.clear_m + START_CLEAR_M + half,
                    None => break,
                }
            }
            members.push(Member {
                id: LEADER_ID_BASE + k as u32,
                body,
                paint,
                start_m: s,
                s: Vec::new(),
                v: Vec::new(),
            });
        }
        members.reverse();
        Drive { path, members }
    }

    /// The ego, the last member.
    pub fn ego(&self) -> &Member {
        self.members.last().expect("the ego")
    }

    /// Member `i`'s level pose in frame `n` at traffic time `t` (seconds)
    /// with its lamps, as the background vehicles' (`sim`): brake lamps
    /// while the next frame's speed (the step's decision, so frame n + 1
    /// must be moved) is lower or it stands; the indicator of its next
    /// turn from `SIGNAL_AHEAD_M` before the stop line until it is done.
    pub fn pose(&self, i: usize, n: usize, t: f64) -> VehiclePose {
        let m = &self.members[i];
        let (s, v, next) = (m.s[n], m.v[n], m.v[n + 1]);
        let (p, h) = self.path.pose(s);
        let (z, pitch_deg) = crate::town::underpass::level_pose(self.path.layout(), p, h);
        let mut lamps = VehicleLamps {
            brake: next < v - 1e-3 || (v < 0.05 && next < 0.05),
            ..Default::default()
        };
        let half = m.half();
        let c = self.path.crossings.iter().find(|c| c.clear_m + half > s);
        if let Some(c) = c.filter(|c| c.stop_m - s - half < SIGNAL_AHEAD_M) {
            let lit = (t * BLINK_HZ).fract() < 0.5;
            lamps.left = lit && c.turn == Move::Left;
            lamps.right = lit && c.turn == Move::Right;
        }
        VehiclePose {
            id: m.id,
            body: m.body,
            paint: m.paint,
            position: [p[0], p[1], z],
            heading_deg: super::ego::heading_deg(h),
            pitch_deg,
            roll_deg: 0.0,
            route: if m.id == 0 { usize::MAX } else { CONVOY_ROUTE },
            lamps,
        }
    }
}
