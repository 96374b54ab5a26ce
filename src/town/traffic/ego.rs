//! The ego's drive: a 1-D simulation along its `DrivePath` against the
//! closed-form traffic, memoised per (town, seed, drive).
//!
//! Drive N starts its traffic clock at town frame N · `DRIVE_WINDOW_FRAMES`
//! (its own time window) and its path on a link spread over the network by
//! N (`start_link`). Each step (1 / fps) the ego takes the highest speed
//! that lets it brake (at `A_LON_MPS2`) for the curves ahead (lateral
//! acceleration ≤ `A_LAT_MPS2`), for the stop line of a junction it may not
//! enter, and for the first vehicle in its way (a path sample within
//! reach of a footprint), keeping `FOLLOW_GAP_M`; it accelerates at
//! `A_LON_MPS2` up to the speed limit. It enters a junction that obeys the
//! clock only when it can clear the junction's keep-clear zone before the
//! town next stands, and nothing stands in its way beyond (so its lamp, red
//! while the town stands, never shows red as it passes the stop line).
//!
//! Background vehicles do not react to the ego: the drive is simulated in
//! chunks of `CHUNK_FRAMES`; after a chunk, every vehicle whose footprint
//! comes within `MARGIN_M` of the ego's in some frame of the chunk is
//! removed for the whole chunk, and the chunk is simulated again without
//! them, a few rounds; the last round's conflicts are removed too, so no
//! footprint ever overlaps. A vehicle that holds the ego standing behind
//! it for longer than a whole signal cycle (one that waits at a junction
//! it cannot clear for a long time) is removed for the chunk likewise, so
//! the ego never stands longer than a red light and its queue. Pedestrians within reach of the ego are removed
//! likewise. Frame K of a drive costs the chunks up to K / `CHUNK_FRAMES`
//! once (a dataset sequence fits in the first).

use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, Mutex, OnceLock};

use super::junction::{clear_time_s, CLEAR_RESERVE_S};
use super::sim::{BLINK_HZ, MOVING_LEADER_MPS, SIGNAL_AHEAD_M};
use super::{others, Plan, VehicleLamps, VehiclePose, A_LAT_MPS2, A_LON_MPS2, LEVEL_GAP_M};
use crate::town::desc::TownDesc;
use crate::town::layout::Layout;
use crate::town::materials::PAINTS;
use crate::town::overpass::Overpass;
use crate::town::rng::{tag, Rng};
use crate::town::routes::drive::{links, Crossing, DrivePath, Move};
use crate::town::routes::Segment;
use crate::town::signals::until_red_s;
use crate::town::vehicles::BodyKind;
use crate::town::walkers;

/// Town frames per simulated chunk (one dataset sequence of 59 frames at
/// stride 10 fits).
pub const CHUNK_FRAMES: u64 = 600;
/// Town frames between the traffic clocks of consecutive drives.
pub const DRIVE_WINDOW_FRAMES: u64 = 6007;
/// Clearance kept between the ego's footprint and any other, metres.
pub const MARGIN_M: f64 = 0.5;
/// Gap the ego keeps behind the vehicle ahead when standing, metres.
const FOLLOW_GAP_M: f64 = 2.5;
/// Spacing of the path samples that look for vehicles ahead, metres.
const SAMPLE_M: f64 = 0.5;
/// Re-simulations of a chunk without the vehicles in the ego's way.
const ROUNDS: usize = 12;
/// Below this speed the ego stands, m/s.
const STAND_MPS: f64 = 0.05;

/// The ego in one frame of a drive.
#[derive(Clone, Debug)]
pub struct EgoFrame {
    /// Its pose on the level grid (z = 0; the caller sets it on the ground).
    pub pose: VehiclePose,
    /// Speed over the last frame, m/s.
    pub speed_mps: f64,
    /// Ids of the background vehicles removed in this frame's chunk.
    pub removed: Arc<BTreeSet<u32>>,
    /// Ids of the pedestrians removed in this frame's chunk.
    pub removed_pedestrians: Arc<BTreeSet<u32>>,
}

/// The town frame where drive `drive`'s traffic clock starts.
pub fn drive_start_frame(drive: u64) -> u64 {
    drive.wrapping_mul(DRIVE_WINDOW_FRAMES)
}

/// The index into `links` where drive `drive` starts: a seeded offset
/// plus `drive` times a stride near 0.618 · n coprime with n, so
/// consecutive drives start far apart and n drives start on n links.
pub fn start_link(n: usize, seed: u64, drive: u64) -> usize {
    let gcd = |mut a: usize, mut b: usize| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let mut stride = ((n as f64 * 0.618) as usize).max(1);
    while gcd(stride, n) != 1 {
        stride += 1;
    }
    let offset = Rng::new(&[seed, tag::EGO]).index(n);
    ((offset as u64 + (drive % n as u64) * stride as u64) % n as u64) as usize
}

struct Chunk {
    s: Vec<f64>,
    v: Vec<f64>,
    end: (f64, f64),
    removed: Arc<BTreeSet<u32>>,
    pedestrians: Arc<BTreeSet<u32>>,
}

struct Drive {
    path: DrivePath,
    body: BodyKind,
    paint: &'static str,
    chunks: Vec<Chunk>,
}

/// Every drive simulated so far, per (description, seed, drive).
type Drives = Mutex<BTreeMap<(String, u64, u64), Arc<Mutex<Drive>>>>;
static DRIVES: OnceLock<Drives> = OnceLock::new();

/// The ego of `frame` (counted from the drive's start) of drive `drive`.
pub fn ego_at(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> EgoFrame {
    let key = (format!("{desc:?}"), seed, drive);
    // The simulation's context, built only when a drive or chunk is new.
    let mut ctx = None;
    let entry = {
        let mut c = DRIVES
            .get_or_init(Default::default)
            .lock()
            .expect("drive cache");
        c.entry(key)
            .or_insert_with(|| {
                let cx = ctx.get_or_insert_with(|| Ctx::new(desc, seed, drive));
                let l = &cx.layout;
                let n = links(l).len();
                let start = start_link(n, seed, drive);
                let rng = Rng::new(&[seed, tag::EGO, drive, 1]);
                let path = DrivePath::new(l, &cx.plan.schedule.turns, start, rng);
                Arc::new(Mutex::new(Drive {
                    path,
                    body: cx.body,
                    paint: cx.paint,
                    chunks: Vec::new(),
                }))
            })
            .clone()
    };
    let mut d = entry.lock().expect("drive");
    let c = (frame / CHUNK_FRAMES) as usize;
    while d.chunks.len() <= c {
        let cx = ctx.get_or_insert_with(|| Ctx::new(desc, seed, drive));
        let k = d.chunks.len() as u64;
        let start = d.chunks.last().map(|c| c.end);
        let stood = standing_frames(&d.chunks);
        let Drive { path, chunks, .. } = &mut *d;
        chunks.push(cx.chunk(path, k, start, stood));
    }
    let ch = &d.chunks[c];
    let n = (frame % CHUNK_FRAMES) as usize;
    let (p, h) = d.path.pose(ch.s[n]);
    let mut pose = level_pose(p, h, d.body, d.paint);
    // Lamps as the background vehicles' (`sim`): the next frame's speed
    // is the step's decision.
    let (v, next) = (ch.v[n], ch.v.get(n + 1).copied().unwrap_or(ch.end.1));
    pose.lamps.brake = next < v - 1e-3 || (v < 0.05 && next < 0.05);
    let half = d.body.footprint_m()[0] / 2.0;
    let t = (drive_start_frame(drive) + frame) as f64 / desc.fps;
    let c = d.path.crossings.iter().find(|c| c.clear_m + half > ch.s[n]);
    if let Some(c) = c.filter(|c| c.stop_m - ch.s[n] - half < SIGNAL_AHEAD_M) {
        let lit = (t * BLINK_HZ).fract() < 0.5;
        pose.lamps.left = lit && c.turn == Move::Left;
        pose.lamps.right = lit && c.turn == Move::Right;
    }
    EgoFrame {
        pose,
        speed_mps: ch.v[n],
        removed: ch.removed.clone(),
        removed_pedestrians: ch.pedestrians.clone(),
    }
}

/// Frames the ego has stood at the end of `chunks` (counted back over
/// whole chunks it stood through).
fn standing_frames(chunks: &[Chunk]) -> usize {
    let mut n = 0;
    for c in chunks.iter().rev() {
        let tail = c.v.iter().rev().take_while(|&&v| v < STAND_MPS).count();
        n += tail;
        if tail < c.v.len() {
            break;
        }
    }
    n
}

/// The ego's pose at (x, y) heading `h` radians, on the level grid.
fn level_pose(p: [f64; 2], h: f64, body: BodyKind, paint: &'static str) -> VehiclePose {
    VehiclePose {
        id: 0,
        body,
        paint,
        position: [p[0], p[1], 0.0],
        heading_deg: heading_deg(h),
        pitch_deg: 0.0,
        roll_deg: 0.0,
        route: usize::MAX,
        lamps: VehicleLamps::default(),
    }
}

/// What one drive's simulation needs.
struct Ctx<'a> {
    desc: &'a TownDesc,
    seed: u64,
    drive: u64,
    plan: Arc<Plan>,
    layout: Layout,
    overpass: Option<Overpass>,
    body: BodyKind,
    /// The ego's paint, one per drive.
    paint: &'static str,
    v_max: f64,
    dt: f64,
}

impl<'a> Ctx<'a> {
    fn new(desc: &'a TownDesc, seed: u64, drive: u64) -> Self {
        let plan = Plan::new(desc);
        let layout = Layout::new(desc);
        let overpass = Overpass::new(desc, &layout);
        let bodies = &plan.schedule.turns.bodies;
        let body = if bodies.contains(&BodyKind::Sedan) {
            BodyKind::Sedan
        } else {
            bodies[0]
        };
        let paint = PAINTS[Rng::new(&[seed, tag::EGO, drive, 2]).index(PAINTS.len())];
        Ctx {
            desc,
            seed,
            drive,
            v_max: plan.schedule.speed_mps,
            plan,
            layout,
            overpass,
            body,
            paint,
            dt: 1.0 / desc.fps,
        }
    }

    /// The ego's pose at (x, y) heading `h` radians, on the level grid.
    fn pose(&self, p: [f64; 2], h: f64) -> VehiclePose {
        level_pose(p, h, self.body, self.paint)
    }

    /// Traffic time of the drive's frame `f`, seconds.
    fn time(&self, f: u64) -> f64 {
        (drive_start_frame(self.drive) + f) as f64 / self.desc.fps
    }

    /// Simulates chunk `k` from `start` (s, v), removing the vehicles and
    /// pedestrians in the ego's way.
    /// `stood`: frames the ego has stood at the chunk's start.
    fn chunk(
        &self,
        path: &mut DrivePath,
        k: u64,
        start: Option<(f64, f64)>,
        stood: usize,
    ) -> Chunk {
        let frames: Vec<u64> = (k * CHUNK_FRAMES..(k + 1) * CHUNK_FRAMES).collect();
        let traffic: Vec<Vec<VehiclePose>> = frames
            .iter()
            .map(|&f| {
                let op = self.overpass.as_ref();
                others(self.desc, self.seed, &self.plan, op, self.drive, f)
            })
            .collect();
        let mut removed = BTreeSet::new();
        let mut run = self.simulate(path, &frames, &traffic, &removed, start);
        for round in 0..=ROUNDS {
            let hits = self.conflicts(path, &traffic, &run.0);
            let before = removed.len();
            removed.extend(hits);
            removed.extend(self.holder(stood, &run.1, &run.3));
            if removed.len() == before || round == ROUNDS {
                break;
            }
            run = self.simulate(path, &frames, &traffic, &removed, start);
        }
        let pedestrians = self.pedestrians_in_way(path, &frames, &run.0);
        let (s, v, end, _) = run;
        Chunk {
            s,
            v,
            end,
            removed: Arc::new(removed),
            pedestrians: Arc::new(pedestrians),
        }
    }

    /// (s, v) per frame of the chunk, the state after it, and per frame
    /// the vehicle the ego sees first in its way.
    #[allow(clippy::type_complexity)]
    fn simulate(
        &self,
        path: &mut DrivePath,
        frames: &[u64],
        traffic: &[Vec<VehiclePose>],
        removed: &BTreeSet<u32>,
        start: Option<(f64, f64)>,
    ) -> (Vec<f64>, Vec<f64>, (f64, f64), Vec<Option<u32>>) {
        let mut s_out = Vec::with_capacity(frames.len());
        let mut v_out = Vec::with_capacity(frames.len());
        let mut ahead_out = Vec::with_capacity(frames.len());
        // The drive starts at the speed its first frame allows.
        let (mut s, mut v) = start.unwrap_or((0.0, f64::NAN));
        for (k, (&f, cars)) in frames.iter().zip(traffic).enumerate() {
            let next = traffic.get(k + 1).map(Vec::as_slice);
            let t = self.time(f);
            let (cap, ahead) = self.allowed(path, s, v.max(0.0), t, (cars, next), removed);
            if v.is_nan() {
                v = cap;
            }
            s_out.push(s);
            v_out.push(v);
            ahead_out.push(ahead);
            v = (v + A_LON_MPS2 * self.dt).min(cap).max(0.0);
            s += v * self.dt;
        }
        (s_out, v_out, (s, v), ahead_out)
    }

    /// The first vehicle in the ego's way once the ego (standing for
    /// `stood` frames before the chunk, speeds `v` per frame, vehicles
    /// ahead `ahead`) has stood for a whole signal cycle: longer than any
    /// red light and its queue take.
    fn holder(&self, mut stood: usize, v: &[f64], ahead: &[Option<u32>]) -> Option<u32> {
        let patience = (self.plan.schedule.cycle_s() / self.dt).ceil() as usize;
        for (&v, &a) in v.iter().zip(ahead) {
            stood = if v < STAND_MPS { stood + 1 } else { 0 };
            if stood >= patience && a.is_some() {
                return a;
            }
        }
        None
    }

    /// The highest speed (m/s) the ego at arc length `s`, speed `v`, time
    /// `t` may take for the next step, and the vehicle first in its way;
    /// `cars`: the vehicles of this frame and of the next (if known).
    fn allowed(
        &self,
        path: &mut DrivePath,
        s: f64,
        v: f64,
        t: f64,
        (cars, later): (&[VehiclePose], Option<&[VehiclePose]>),
        removed: &BTreeSet<u32>,
    ) -> (f64, Option<u32>) {
        let half = self.body.footprint_m()[0] / 2.0;
        let look = self.v_max * self.v_max / (2.0 * A_LON_MPS2) + 2.0 * half + 20.0;
        path.reach(s + look + 1.0);
        // Stopping within d metres, also within one step.
        let stop = |d: f64| {
            let d = d.max(0.0);
            (2.0 * A_LON_MPS2 * d).sqrt().min(d / self.dt)
        };
        let mut cap = self.v_max;
        for (s0, seg) in path.pieces(s, s + look) {
            if let Segment::Arc { radius_m, .. } = *seg {
                let vc = (A_LAT_MPS2 * radius_m).sqrt();
                let d = (s0 - s).max(0.0);
                cap = cap.min((vc * vc + 2.0 * A_LON_MPS2 * d).sqrt());
            }
        }
        let ahead = self.first_in_way(path, s, look, cars, removed);
        if let Some((d, _)) = ahead {
            cap = cap.min(stop(d - half - FOLLOW_GAP_M));
        }
        let front = s + half;
        let next = path
            .crossings
            .iter()
            .find(|c| c.stop_m >= front - 0.05 && c.stop_m < s + look);
        if let Some(c) = next {
            // Room beyond the junction, or a leader moving on (as `sim`).
            let moving = |id: u32| {
                let at = |vs: &[VehiclePose]| vs.iter().find(|c| c.id == id).map(|c| c.position);
                match (at(cars), later.and_then(at)) {
                    (Some(a), Some(b)) => {
                        (b[0] - a[0]).hypot(b[1] - a[1]) / self.dt > MOVING_LEADER_MPS
                    }
                    _ => false,
                }
            };
            let free_beyond = ahead
                .is_none_or(|(d, id)| d > c.clear_m - s + 3.0 * half + FOLLOW_GAP_M || moving(id));
            let clear = c.roundabout
                || c.major == Some(true)
                || self.can_clear(path, c, c.clear_m + half - s, v, t);
            if !(free_beyond && clear) {
                cap = cap.min(stop(c.stop_m - front));
            }
        }
        (cap, ahead.map(|(_, id)| id))
    }

    /// Whether the ego, `d` metres from clearing the zone of crossing `c`
    /// at speed `v` at time `t`, clears it before its approach turns red.
    fn can_clear(&self, path: &DrivePath, c: &Crossing, d: f64, v: f64, t: f64) -> bool {
        let left = until_red_s(&self.plan.schedule, c.dir, t);
        clear_time_s(path, c.stop_m, d, v, self.v_max) + CLEAR_RESERVE_S <= left
    }

    /// Distance along the path from the ego's centre (at `s`) to the first
    /// sample within reach of a vehicle's footprint, up to `look` metres,
    /// and that vehicle's id.
    fn first_in_way(
        &self,
        path: &DrivePath,
        s: f64,
        look: f64,
        cars: &[VehiclePose],
        removed: &BTreeSet<u32>,
    ) -> Option<(f64, u32)> {
        let (me, _) = path.pose(s);
        let reach = self.body.footprint_m()[1] / 2.0 + 0.3;
        let near: Vec<&VehiclePose> = cars
            .iter()
            .filter(|c| !removed.contains(&c.id) && c.position[2].abs() < LEVEL_GAP_M)
            .filter(|c| (c.position[0] - me[0]).hypot(c.position[1] - me[1]) < look + 15.0)
            .collect();
        if near.is_empty() {
            return None;
        }
        let n = (look / SAMPLE_M) as usize;
        (0..=n).map(|k| k as f64 * SAMPLE_M).find_map(|d| {
            let (p, _) = path.pose(s + d);
            near.iter()
                .find(|c| rect_distance(c, p) < reach)
                .map(|c| (d, c.id))
        })
    }

    /// Ids of the vehicles whose footprint comes within `MARGIN_M` of the
    /// ego's in some frame.
    fn conflicts(&self, path: &DrivePath, traffic: &[Vec<VehiclePose>], s: &[f64]) -> Vec<u32> {
        let mut out = Vec::new();
        for (cars, &si) in traffic.iter().zip(s) {
            let (p, h) = path.pose(si);
            let ego = self.pose(p, h);
            let grown = grown_corners(&ego, MARGIN_M);
            for c in cars {
                let close = (c.position[0] - p[0]).hypot(c.position[1] - p[1]) < 30.0;
                if close && c.position[2].abs() < LEVEL_GAP_M && quads_overlap(&grown, &c.corners())
                {
                    out.push(c.id);
                }
            }
        }
        out
    }

    /// Ids of the pedestrians within reach (their 0.5 m square grown by
    /// `MARGIN_M`) of the ego's footprint in some frame.
    fn pedestrians_in_way(&self, path: &DrivePath, frames: &[u64], s: &[f64]) -> BTreeSet<u32> {
        let mut out = BTreeSet::new();
        if !self.layout.sidewalks {
            return out;
        }
        let sched = &self.plan.schedule;
        for (&f, &si) in frames.iter().zip(s) {
            let (p, h) = path.pose(si);
            let ego = self.pose(p, h);
            let t = self.time(f);
            for w in walkers::pedestrians(self.desc, &self.layout, sched, self.seed, t) {
                let q = [w.position[0], w.position[1]];
                if (q[0] - p[0]).hypot(q[1] - p[1]) < 10.0
                    && rect_distance(&ego, q) < 0.25 + MARGIN_M
                {
                    out.insert(w.id);
                }
            }
        }
        out
    }
}

/// Heading `h` radians as degrees in [0, 360) (a heading a hair below 0
/// or 2π rounds to 0, not 360).
pub(super) fn heading_deg(h: f64) -> f64 {
    let d = h.to_degrees().rem_euclid(360.0);
    if d >= 360.0 {
        0.0
    } else {
        d
    }
}

/// Distance from `p` to the footprint rectangle of `v` (0 inside).
pub(super) fn rect_distance(v: &VehiclePose, p: [f64; 2]) -> f64 {
    let [len, wid] = v.body.footprint_m();
    let h = v.heading_deg.to_radians();
    let d = [p[0] - v.position[0], p[1] - v.position[1]];
    let a = (d[0] * h.cos() + d[1] * h.sin()).abs() - len / 2.0;
    let b = (-d[0] * h.sin() + d[1] * h.cos()).abs() - wid / 2.0;
    a.max(0.0).hypot(b.max(0.0))
}

/// The footprint's corners grown by `m` on every side.
fn grown_corners(v: &VehiclePose, m: f64) -> [[f64; 2]; 4] {
    let [len, wid] = v.body.footprint_m();
    let h = v.heading_deg.to_radians();
    let (f, s) = ([h.cos(), h.sin()], [-h.sin(), h.cos()]);
    let (a, b) = (len / 2.0 + m, wid / 2.0 + m);
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(u, w)| {
        [
            v.position[0] + u * a * f[0] + w * b * s[0],
            v.position[1] + u * a * f[1] + w * b * s[1],
        ]
    })
}

/// Separating-axis test of two convex quads (touching does not count).
fn quads_overlap(a: &[[f64; 2]; 4], b: &[[f64; 2]; 4]) -> bool {
    [a, b].iter().all(|poly| {
        (0..4).all(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % 4]);
            let n = [q[1] - p[1], p[0] - q[0]];
            let proj = |v: &[[f64; 2]; 4]| {
                v.iter()
                    .map(|c| c[0] * n[0] + c[1] * n[1])
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                        (lo.min(x), hi.max(x))
                    })
            };
            let ((a0, a1), (b0, b1)) = (proj(a), proj(b));
            a1 > b0 && b1 > a0
        })
    })
}

/// Junction turns (left or right, roundabout exits included) the ego has
/// completed by `frame` of drive `drive`.
pub fn turns_by(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> usize {
    // Simulates (and caches) the drive up to the frame first.
    let _ = ego_at(desc, seed, drive, frame);
    let cache = DRIVES.get().expect("drive cache");
    let d = cache.lock().expect("drive cache")[&(format!("{desc:?}"), seed, drive)].clone();
    let d = d.lock().expect("drive");
    let c = &d.chunks[(frame / CHUNK_FRAMES) as usize];
    let s = c.s[(frame % CHUNK_FRAMES) as usize];
    d.path
        .crossings
        .iter()
        .filter(|x| x.clear_m <= s && x.turn != crate::town::routes::drive::Move::Straight)
        .count()
}
