//! The background vehicles as a deterministic simulation, per chunk.
//!
//! Chunk k (frames k · `CHUNK_FRAMES` onward) of drive N starts from its
//! own seeded state (`spawn`: vehicles on every road, seeded per seed,
//! drive and chunk) `WARM_UP_FRAMES` before its first frame and is
//! simulated only up to its end, so frame K costs one chunk whatever K
//! is; at a chunk's first frame the traffic
//! starts anew with other ids (`ID_SPAN` apart in consecutive chunks).
//! The vehicles walk junction to junction (`DrivePath::background`), one
//! step per frame: each takes the highest speed that lets it brake (at
//! `A_LON_MPS2`) for the curves ahead (lateral ≤ `A_LAT_MPS2`), for the
//! first footprint within reach of its path ahead (keeping
//! `FOLLOW_GAP_M`; the ego's convoy's, known in advance, count), and for the stop
//! line of a junction it may not enter (`junction`); it accelerates at
//! `A_LON_MPS2` up to its limit (cyclists ride at `cyclist_speed_mps`, and
//! whoever is behind them follows). Steps use the state at the start of
//! the step, in id order; a driver passing a stop line claims the
//! junction at once, so later drivers of the same step see it inside.
//! A first pass brakes onto the current positions of what is ahead,
//! which only moves on along its own path, so every gap stays open; a
//! second pass lets a follower count on its leader's first-pass motion
//! and braking distance (`follow_cap`), which keeps the gap open too and
//! lets platoons run close to the limit; last, a move into another
//! footprint is held (`keep_out`). The junction rules keep crossing paths
//! apart. Lamps per frame: brake
//! lamps while decelerating or standing, the indicator of a turn blinking
//! from `SIGNAL_AHEAD_M` before its stop line until the turn is done.
//!
//! A chunk's frames are memoised per (town, seed, drive, chunk), the few
//! latest kept: a pure function of those, the same bytes whichever frame
//! asked first, alone, in sequence or on any thread.

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

use super::junction::{self, JState};
use super::recent::Recent;
use super::{closed, ego, Plan, VehicleLamps, VehiclePose, A_LAT_MPS2, A_LON_MPS2, LEVEL_GAP_M};
use crate::town::desc::TownDesc;
use crate::town::layout::Layout;
use crate::town::overpass::Overpass;
use crate::town::routes::drive::{DrivePath, Move};
use crate::town::routes::Segment;
use crate::town::underpass;
use crate::town::vehicles::BodyKind;

/// `VehiclePose::route` of a simulated vehicle.
pub const SIM_ROUTE: usize = usize::MAX - 1;
/// Gap kept behind the vehicle ahead when standing, metres.
pub const FOLLOW_GAP_M: f64 = 2.5;
/// Spacing of the path samples that look for vehicles ahead, metres.
const SAMPLE_M: f64 = 1.0;
/// Cell size of the per-step spatial index, metres.
const CELL_M: f64 = 16.0;
/// Chunks whose simulation is kept.
const KEEP_CHUNKS: usize = 3;
/// Offset between the ids of consecutive chunks' vehicles: a vehicle
/// starting anew never takes the id of one that was just there.
pub const ID_SPAN: u32 = 10_000;
/// Frames simulated before a chunk's first frame from its seeded start.
pub const WARM_UP_FRAMES: u64 = 200;
/// Indicator blink rate, Hz.
pub const BLINK_HZ: f64 = 1.5;
/// How far before a turn's stop line the indicator starts, metres.
pub const SIGNAL_AHEAD_M: f64 = 35.0;
/// A leader this fast inside a junction leaves room behind it, m/s.
pub const MOVING_LEADER_MPS: f64 = 3.0;

/// Cyclists' speed under the town's limit `limit_mps`, m/s.
pub fn cyclist_speed_mps(limit_mps: f64) -> f64 {
    limit_mps.min(5.5)
}

/// One background vehicle.
#[derive(Clone, Debug)]
pub(super) struct Agent {
    /// Stable id, ≥ 1.
    pub id: u32,
    /// Body type.
    pub body: BodyKind,
    /// Paint material.
    pub paint: &'static str,
    /// Its walk.
    pub path: DrivePath,
    /// Arc length of its centre, metres.
    pub s: f64,
    /// Speed, m/s (NaN before the first step: it starts at the speed the
    /// first step allows).
    pub v: f64,
    /// Its speed limit, m/s.
    pub v_max: f64,
}

impl Agent {
    fn half(&self) -> f64 {
        self.body.footprint_m()[0] / 2.0
    }

    pub fn pose(&self) -> VehiclePose {
        let (p, h) = self.path.pose(self.s);
        let (z, pitch_deg) = underpass::level_pose(self.path.layout(), p, h);
        VehiclePose {
            id: self.id,
            body: self.body,
            paint: self.paint,
            position: [p[0], p[1], z],
            heading_deg: ego::heading_deg(h),
            pitch_deg,
            roll_deg: 0.0,
            route: SIM_ROUTE,
            lamps: VehicleLamps::default(),
        }
    }
}

/// One frame's vehicles.
type Frame = Arc<Vec<VehiclePose>>;

/// The latest chunks' frames, per (description, seed, drive, chunk).
static SIMS: Recent<(String, u64, u64, u64), Arc<Vec<Frame>>> = Recent::new(KEEP_CHUNKS);

/// The background vehicles of `frame` of drive `drive` (level grid).
pub fn vehicles_at(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> Frame {
    let chunk = frame / ego::CHUNK_FRAMES;
    let key = (format!("{desc:?}"), seed, drive, chunk);
    let frames = SIMS
        .slot(key)
        .lock()
        .expect("sim chunk")
        .get_or_insert_with(|| Arc::new(simulate(desc, seed, drive, chunk)))
        .clone();
    frames[(frame % ego::CHUNK_FRAMES) as usize].clone()
}

/// Every frame of chunk `chunk` of drive `drive`, from its seeded start.
fn simulate(desc: &TownDesc, seed: u64, drive: u64, chunk: u64) -> Vec<Frame> {
    let l = Layout::new(desc);
    let plan = Plan::new(desc);
    let mut agents = super::spawn::spawn(seed, drive, chunk, desc.traffic_density, &l, &plan);
    let base = (chunk % 2) as u32 * ID_SPAN;
    for a in &mut agents {
        assert!(a.id < ID_SPAN, "more than {ID_SPAN} background vehicles");
        a.id += base;
    }
    let first = chunk * ego::CHUNK_FRAMES;
    let frames = first..first + ego::CHUNK_FRAMES;
    let cx = Ctx::new(desc, seed, drive);
    // The warm-up: queues form at red lights and platoons spread out
    // before the chunk's first frame (with the convoy where it has driven).
    let from = first.saturating_sub(WARM_UP_FRAMES);
    let convoys = ego::level_poses(desc, seed, drive, from..first);
    for k in 0..WARM_UP_FRAMES {
        let me = (first + k)
            .checked_sub(WARM_UP_FRAMES)
            .map(|f| convoys[(f - from) as usize].clone())
            .unwrap_or_default();
        cx.step(
            &mut agents,
            first as i64 + k as i64 - WARM_UP_FRAMES as i64,
            me,
        );
    }
    let convoys = ego::level_poses(desc, seed, drive, frames.clone());
    frames
        .zip(convoys)
        .map(|(f, me)| Arc::new(cx.step(&mut agents, f as i64, me)))
        .collect()
}

/// What the simulation needs besides the agents.
struct Ctx<'a> {
    desc: &'a TownDesc,
    seed: u64,
    drive: u64,
    plan: Arc<Plan>,
    overpass: Option<Overpass>,
    dt: f64,
}

/// The per-step index of footprints: cell → indices into the step's poses.
struct Grid(HashMap<(i64, i64), Vec<usize>>);

impl Grid {
    fn new(poses: &[VehiclePose]) -> Self {
        let mut g: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (i, v) in poses.iter().enumerate() {
            for c in cells(&v.footprint()) {
                g.entry(c).or_default().push(i);
            }
        }
        Grid(g)
    }

    /// Indices of the footprints in cells meeting `r` (sorted, unique).
    fn near(&self, r: &crate::town::layout::Rect) -> Vec<usize> {
        let mut out: Vec<usize> = cells(r)
            .filter_map(|c| self.0.get(&c))
            .flatten()
            .copied()
            .collect();
        out.sort_unstable();
        out.dedup();
        out
    }
}

fn cells(r: &crate::town::layout::Rect) -> impl Iterator<Item = (i64, i64)> {
    let c = |v: f64| (v / CELL_M).floor() as i64;
    let (x0, x1, y0, y1) = (c(r.min[0]), c(r.max[0]), c(r.min[1]), c(r.max[1]));
    (x0..=x1).flat_map(move |x| (y0..=y1).map(move |y| (x, y)))
}

impl<'a> Ctx<'a> {
    fn new(desc: &'a TownDesc, seed: u64, drive: u64) -> Self {
        let l = Layout::new(desc);
        Ctx {
            desc,
            seed,
            drive,
            plan: Plan::new(desc),
            overpass: Overpass::new(desc, &l),
            dt: 1.0 / desc.fps,
        }
    }

    /// The poses of frame `f` (from the drive's start; < 0 in the first
    /// chunk's warm-up), then one step on (`me`: the ego's convoy's poses
    /// in frame `f`, obstacles, once the drive has started).
    fn step(&self, agents: &mut [Agent], f: i64, me: Vec<VehiclePose>) -> Vec<VehiclePose> {
        let t = (ego::drive_start_frame(self.drive) as f64 + f as f64) / self.desc.fps;
        let n = agents.len();
        for a in agents.iter_mut() {
            let ahead = a.v_max * a.v_max / (2.0 * A_LON_MPS2) + 150.0;
            a.path.reach(a.s + ahead);
        }
        let mut poses: Vec<VehiclePose> = agents.iter().map(Agent::pose).collect();
        // The overpass's vehicles on this level are obstacles too.
        let closed = closed(self.desc, self.seed, &self.plan, self.overpass.as_ref(), t);
        let mut all = poses.clone();
        all.extend(
            closed
                .into_iter()
                .filter(|v| v.position[2].abs() < LEVEL_GAP_M),
        );
        all.extend(me);
        let grid = Grid::new(&all);
        let states: Vec<Option<JState>> = agents
            .iter()
            .map(|a| {
                // Far enough for a merging street driver's look.
                let within = (a.v_max * a.v_max / (2.0 * A_LON_MPS2) + 60.0).max(12.0 * a.v_max);
                JState::of(&a.path, a.s, a.half(), a.v.max(0.0), a.v_max, within)
            })
            .collect();
        let mut at_junction: BTreeMap<(usize, usize), Vec<usize>> = BTreeMap::new();
        for (i, st) in states.iter().enumerate() {
            if let Some(st) = st {
                at_junction.entry(st.c.junction).or_default().push(i);
            }
        }
        let mut claimed = vec![false; n];
        let mut next = vec![0.0; n];
        let mut caps = Vec::with_capacity(n);
        for i in 0..n {
            let c = self.allowed(agents, i, &all, &grid, &states, &at_junction, &claimed, t);
            let a = &mut agents[i];
            if a.v.is_nan() {
                a.v = c.cap;
            }
            let v = (a.v + A_LON_MPS2 * self.dt).min(c.cap).max(0.0);
            if let Some(st) = &states[i] {
                if !st.inside() && v * self.dt > st.d_stop + 0.01 {
                    claimed[i] = true;
                }
            }
            next[i] = v;
            caps.push(c);
        }
        // Second pass: a follower counts on its leader's own motion and
        // braking distance (the leader's first-pass speed, which the
        // second pass only raises), never passing a stop line it did not
        // claim in the first.
        let first = next.clone();
        for (i, c) in caps.iter().enumerate() {
            // Only a leader ahead in one lane, beyond twice the standstill
            // gap (closer, the follower brakes to where it is and keeps
            // the pace of a slow one, a cyclist's).
            let Some((g, j)) = c.lead.filter(|&(g, j)| j < n && g > FOLLOW_GAP_M) else {
                continue;
            };
            let a = &agents[i];
            let (_, h) = a.path.pose(a.s + g + a.half() + FOLLOW_GAP_M);
            let along = (h - all[j].heading_deg.to_radians()).cos();
            if along < ALIGNED_COS {
                continue;
            }
            let cap = c.other.min(follow_cap(g, first[j] * along, self.dt));
            let v = (a.v + A_LON_MPS2 * self.dt).min(cap).max(0.0);
            let crosses =
                states[i].is_some_and(|st| !st.inside() && v * self.dt > st.d_stop + 0.01);
            if v > next[i] && (claimed[i] || !crosses) {
                next[i] = v;
            }
        }
        keep_out(agents, &all, &grid, &mut next, self.dt);
        let blink = (t * BLINK_HZ).fract() < 0.5;
        for (i, a) in agents.iter_mut().enumerate() {
            let p = &mut poses[i];
            p.lamps.brake = next[i] < a.v - 1e-3 || (a.v < 0.05 && next[i] < 0.05);
            if let Some(st) = states[i].filter(|st| st.d_stop < SIGNAL_AHEAD_M && blink) {
                p.lamps.left = st.c.turn == Move::Left;
                p.lamps.right = st.c.turn == Move::Right;
            }
            a.v = next[i];
            a.s += a.v * self.dt;
        }
        poses
    }

    /// The highest speed (m/s) agent `i` may take for the next step,
    /// braking to where the first footprint in its way is now.
    #[allow(clippy::too_many_arguments)]
    fn allowed(
        &self,
        agents: &[Agent],
        i: usize,
        all: &[VehiclePose],
        grid: &Grid,
        states: &[Option<JState>],
        at_junction: &BTreeMap<(usize, usize), Vec<usize>>,
        claimed: &[bool],
        t: f64,
    ) -> Caps {
        let a = &agents[i];
        let half = a.half();
        let v = if a.v.is_nan() { a.v_max } else { a.v };
        let vn = v + A_LON_MPS2 * self.dt;
        let look = vn * vn / (2.0 * A_LON_MPS2) + vn * self.dt + half + FOLLOW_GAP_M + 8.0;
        let stop = |d: f64| {
            let d = d.max(0.0);
            (2.0 * A_LON_MPS2 * d).sqrt().min(d / self.dt)
        };
        let mut cap = a.v_max;
        for (s0, seg) in a.path.pieces(a.s, a.s + look) {
            if let Segment::Arc { radius_m, .. } = *seg {
                let vc = (A_LAT_MPS2 * radius_m).sqrt();
                let d = (s0 - a.s).max(0.0);
                cap = cap.min((vc * vc + 2.0 * A_LON_MPS2 * d).sqrt());
            }
        }
        let st = states[i].filter(|st| !st.inside() && st.d_stop < look);
        let need = match &st {
            Some(st) => look.max(st.c.clear_m - a.s + 3.0 * half + FOLLOW_GAP_M + 1.0),
            None => look,
        };
        let ahead = first_in_way(a, i, need, all, grid);
        let lead = ahead
            .filter(|(d, _)| *d < look)
            .map(|(d, j)| (d - half - FOLLOW_GAP_M, j));
        if let Some(st) = st {
            let beyond = st.c.clear_m - a.s + 3.0 * half + FOLLOW_GAP_M;
            let free = ahead.is_none_or(|(d, j)| {
                d > beyond || (j < agents.len() && agents[j].v > MOVING_LEADER_MPS)
            });
            let clear_s = junction::clear_time_s(
                &a.path,
                st.c.stop_m,
                st.c.clear_m + half - st.c.stop_m + st.d_stop.max(0.0),
                v,
                a.v_max,
            );
            let others = at_junction[&st.c.junction].iter().filter(|&&j| j != i);
            let blocked = others.into_iter().any(|&j| {
                let o = states[j].as_ref().expect("listed");
                junction::blocks(
                    &self.plan.schedule,
                    &st,
                    o,
                    o.inside() || claimed[j],
                    clear_s,
                    t,
                )
            });
            if !free || blocked || !junction::can_clear(&self.plan.schedule, &st, clear_s, t) {
                cap = cap.min(stop(st.d_stop));
            }
        }
        Caps {
            cap: lead.map_or(cap, |(g, _)| cap.min(stop(g))),
            other: cap,
            lead,
        }
    }
}

/// An agent's speed caps for one step, m/s.
struct Caps {
    /// Everything counted, the first footprint in its way standing still.
    cap: f64,
    /// Everything but that footprint.
    other: f64,
    /// The gap to that footprint (metres beyond the standstill gap, < 0
    /// inside it) and its index.
    lead: Option<(f64, usize)>,
}

/// Highest speed for one step `dt` behind a leader `g` metres beyond the
/// standstill gap moving on at `u` along the way: it stays behind where
/// the leader will be, and could stop behind it were the leader to brake
/// at `A_LON_MPS2` from then on (g + u·dt + u²/2b ≥ v·dt + v²/2b).
pub(super) fn follow_cap(g: f64, u: f64, dt: f64) -> f64 {
    let (b, room) = (A_LON_MPS2, g.max(0.0) + u.max(0.0) * dt);
    let u = u.max(0.0);
    (room / dt).min(-b * dt + ((b * dt).powi(2) + 2.0 * b * room + u * u).sqrt())
}

/// The last check of a step: in id order, a vehicle whose move would
/// take its footprint into another's (where that one stands after its
/// own move if already checked, else where it stands now) stays where it
/// is, which the vehicles already checked kept clear of. (The overpass's
/// vehicles and the convoy replayed in a warm-up do not brake and are left
/// to the removals.) It catches what
/// the look along the path cannot see: a body drifting in from beside
/// (a lane change alongside). Returns how many were held.
fn keep_out(
    agents: &[Agent],
    all: &[VehiclePose],
    grid: &Grid,
    next: &mut [f64],
    dt: f64,
) -> usize {
    let mut at: Vec<[[f64; 2]; 4]> = all.iter().map(VehiclePose::corners).collect();
    let mut held = 0;
    for (i, a) in agents.iter().enumerate() {
        if next[i] <= 0.0 {
            continue;
        }
        let mut moved = a.clone();
        moved.s += next[i] * dt;
        let q = moved.pose();
        let mut r = q.footprint();
        // Those already checked moved by at most a step at the fastest.
        let pad = 40.0 * dt;
        r.min = r.min.map(|c| c - pad);
        r.max = r.max.map(|c| c + pad);
        let c = q.corners();
        let hit = grid.near(&r).into_iter().any(|j| {
            j != i && j < agents.len() && q.same_level(&all[j]) && ego::quads_overlap(&c, &at[j])
        });
        if hit {
            next[i] = 0.0;
            held += 1;
        } else {
            at[i] = c;
        }
    }
    held
}

/// Cosine above which a leader heads along the follower's way where it
/// meets it (2°: one lane, not a follower changing lanes behind it nor a
/// junction turn).
const ALIGNED_COS: f64 = 0.999_39;

/// A footprint's centre, heading (cos, sin), half length and width, and
/// height (`VehiclePose::position`'s z).
type FootprintFrame = ([f64; 2], [f64; 2], [f64; 2], f64);

/// Distance along agent `i`'s path from its centre to the first sample
/// within reach of another footprint, up to `look` metres, and whose.
fn first_in_way(
    a: &Agent,
    i: usize,
    look: f64,
    all: &[VehiclePose],
    grid: &Grid,
) -> Option<(f64, usize)> {
    let reach = a.body.footprint_m()[1] / 2.0 + 0.3;
    let n = (look / SAMPLE_M).ceil() as usize;
    let poses: Vec<([f64; 2], f64)> = (0..=n)
        .map(|k| a.path.pose(a.s + k as f64 * SAMPLE_M))
        .collect();
    let samples: Vec<[f64; 2]> = poses.iter().map(|q| q.0).collect();
    // Heights along the way: a footprint on another level (the deck over
    // the underpass's cut) is not in it.
    let under = underpass::Underpass::of(a.path.layout());
    let heights: Vec<f64> = poses
        .iter()
        .map(|&(p, h)| under.map_or(0.0, |u| u.pose(p, h).0))
        .collect();
    let pad = reach + 1.0;
    let fold =
        |f: fn(f64, f64) -> f64, c: usize, init: f64| samples.iter().map(|p| p[c]).fold(init, f);
    let r = crate::town::layout::Rect {
        min: [
            fold(f64::min, 0, f64::INFINITY) - pad,
            fold(f64::min, 1, f64::INFINITY) - pad,
        ],
        max: [
            fold(f64::max, 0, f64::NEG_INFINITY) + pad,
            fold(f64::max, 1, f64::NEG_INFINITY) + pad,
        ],
    };
    let near: Vec<usize> = grid.near(&r).into_iter().filter(|&j| j != i).collect();
    if near.is_empty() {
        return None;
    }
    // Each footprint's frame once (`ego::rect_distance`, squared).
    let frames: Vec<FootprintFrame> = near
        .iter()
        .map(|&j| {
            let [len, wid] = all[j].body.footprint_m();
            let (sin, cos) = all[j].heading_deg.to_radians().sin_cos();
            let c = [all[j].position[0], all[j].position[1]];
            (c, [cos, sin], [len / 2.0, wid / 2.0], all[j].position[2])
        })
        .collect();
    let reach2 = reach * reach;
    samples.iter().enumerate().find_map(|(k, p)| {
        frames
            .iter()
            .position(|(c, [cos, sin], [hl, hw], z)| {
                if (z - heights[k]).abs() >= LEVEL_GAP_M {
                    return false;
                }
                let d = [p[0] - c[0], p[1] - c[1]];
                let a = ((d[0] * cos + d[1] * sin).abs() - hl).max(0.0);
                let b = ((-d[0] * sin + d[1] * cos).abs() - hw).max(0.0);
                a * a + b * b < reach2
            })
            .map(|n| (k as f64 * SAMPLE_M, near[n]))
    })
}
