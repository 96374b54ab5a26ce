//! The ego's drive: a 1-D simulation along its `DrivePath` against the
//! signals, the road and its convoy's leaders only (`convoy`), so its
//! state at any frame depends on no traffic history; the background
//! vehicles in the convoy's way are removed.
//!
//! Drive N starts its traffic clock at town frame N · `DRIVE_WINDOW_FRAMES`
//! (its own time window) and its path on a link spread over the network by
//! N (`start_link`). Each step (1 / fps) the ego takes the highest speed
//! that lets it brake (at `A_LON_MPS2`) for the curves ahead (lateral
//! acceleration ≤ `A_LAT_MPS2`) and for the stop line of a junction it may
//! not enter; it accelerates at `A_LON_MPS2` up to the speed limit. It
//! enters a junction that obeys the clock only when it can clear the
//! junction's keep-clear zone before its lamp turns red (so the lamp
//! never shows red as it passes the line); the roundabout and a divided
//! highway's through lanes have no lamps. The leaders ahead of it on the
//! same path move by the same rules, front to back, and each member
//! behind one also keeps the speed from which it could stop
//! `CONVOY_GAP_M` behind the one ahead (`sim::follow_cap`) and enters a
//! junction only with room beyond it. The motion costs a few
//! microseconds a frame and is memoised per (town, seed, drive): the same
//! numbers whichever frame asked first.
//!
//! The background vehicles (`sim`, simulated per chunk of `CHUNK_FRAMES`)
//! see the convoy's footprints as obstacles and queue behind them; every
//! one whose footprint still comes within `MARGIN_M` of a member's in
//! some frame of the chunk is removed for the whole chunk, and so are the
//! pedestrians within reach of a member. Removing vehicles moves none of
//! the others, so no footprint ever overlaps. Frame K costs the chunk
//! holding K, whatever K is.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, Mutex, OnceLock};

use super::convoy::{Drive, Member, CONVOY_GAP_M};
use super::junction::{clear_time_s, CLEAR_RESERVE_S};
use super::recent::Recent;
use super::sim::{follow_cap, MOVING_LEADER_MPS};
use super::{others, Plan, VehiclePose, A_LAT_MPS2, A_LON_MPS2};
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

/// Town frames per simulated chunk of background traffic (one dataset
/// sequence of 59 frames at stride 10 fits).
pub const CHUNK_FRAMES: u64 = 600;
/// Town frames between the traffic clocks of consecutive drives.
pub const DRIVE_WINDOW_FRAMES: u64 = 6007;
/// Clearance kept between a convoy member's footprint and any
/// background one, metres.
pub const MARGIN_M: f64 = 0.5;
/// Chunks whose removals are kept.
const KEEP_CHUNKS: usize = 4;

/// The ego in one frame of a drive.
#[derive(Clone, Debug)]
pub struct EgoFrame {
    /// Its pose on the level grid (z = 0; the caller sets it on the ground).
    pub pose: VehiclePose,
    /// Its leaders' level poses, front to back.
    pub leaders: Vec<VehiclePose>,
    /// Ids of the background vehicles removed in this frame's chunk.
    pub removed: Arc<BTreeSet<u32>>,
    /// Ids of the pedestrians removed in this frame's chunk.
    pub removed_pedestrians: Arc<BTreeSet<u32>>,
}

/// The town frame where drive `drive`'s traffic clock starts.
pub fn drive_start_frame(drive: u64) -> u64 {
    drive.wrapping_mul(DRIVE_WINDOW_FRAMES)
}

/// Traffic time of frame `frame` (from the drive's start) of drive
/// `drive`, seconds.
fn drive_time_s(desc: &TownDesc, drive: u64, frame: u64) -> f64 {
    (drive_start_frame(drive) + frame) as f64 / desc.fps
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

/// Every drive moved so far, per (description, seed, drive).
type Drives = Mutex<BTreeMap<(String, u64, u64), Arc<Mutex<Drive>>>>;
static DRIVES: OnceLock<Drives> = OnceLock::new();

/// What one chunk removes: vehicle ids and pedestrian ids.
type Removal = (Arc<BTreeSet<u32>>, Arc<BTreeSet<u32>>);
static REMOVALS: Recent<(String, u64, u64, u64), Removal> = Recent::new(KEEP_CHUNKS);

/// The drive's motion, moved on to frame `upto` at least, locked.
fn motion(desc: &TownDesc, seed: u64, drive: u64, upto: u64) -> Arc<Mutex<Drive>> {
    let key = (format!("{desc:?}"), seed, drive);
    let entry = {
        let mut c = DRIVES
            .get_or_init(Default::default)
            .lock()
            .expect("drive cache");
        c.entry(key)
            .or_insert_with(|| Arc::new(Mutex::new(Ctx::new(desc, seed, drive).start())))
            .clone()
    };
    {
        let mut d = entry.lock().expect("drive");
        if d.ego().s.len() as u64 <= upto {
            let cx = Ctx::new(desc, seed, drive);
            while d.ego().s.len() as u64 <= upto {
                cx.step(&mut d);
            }
        }
    }
    entry
}

/// The ego of `frame` (counted from the drive's start) of drive `drive`,
/// without the removals: its level pose with lamps, and its speed.
pub fn ego_motion(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> (VehiclePose, f64) {
    let entry = motion(desc, seed, drive, frame + 1);
    let d = entry.lock().expect("drive");
    let t = drive_time_s(desc, drive, frame);
    let ego = d.members.len() - 1;
    (d.pose(ego, frame as usize, t), d.ego().v[frame as usize])
}

/// One convoy member in one frame: its place along the drive's path.
#[derive(Clone, Debug, PartialEq)]
pub struct ConvoyMember {
    /// Its vehicle id (0: the ego; leaders from `LEADER_ID_BASE + 1`).
    pub id: u32,
    /// Arc length of its centre along the drive's path, metres.
    pub s_m: f64,
    /// Speed, m/s.
    pub speed_mps: f64,
    /// Half its body length, metres.
    pub half_length_m: f64,
    /// Its pose on the level grid, lamps lit as in the frame.
    pub pose: VehiclePose,
}

/// The convoy of `frame` of drive `drive`, front to back, the ego last.
pub fn convoy_at(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> Vec<ConvoyMember> {
    let entry = motion(desc, seed, drive, frame + 1);
    let d = entry.lock().expect("drive");
    let n = frame as usize;
    let t = drive_time_s(desc, drive, frame);
    d.members
        .iter()
        .enumerate()
        .map(|(i, m)| ConvoyMember {
            id: m.id,
            s_m: m.s[n],
            speed_mps: m.v[n],
            half_length_m: m.half(),
            pose: d.pose(i, n, t),
        })
        .collect()
}

/// The convoy's level poses (leaders front to back, the ego last) over
/// frames `range` of drive `drive`, one list per frame.
pub(super) fn level_poses(
    desc: &TownDesc,
    seed: u64,
    drive: u64,
    range: std::ops::Range<u64>,
) -> Vec<Vec<VehiclePose>> {
    let entry = motion(desc, seed, drive, range.end);
    let d = entry.lock().expect("drive");
    range
        .map(|f| {
            let t = drive_time_s(desc, drive, f);
            (0..d.members.len())
                .map(|i| d.pose(i, f as usize, t))
                .collect()
        })
        .collect()
}

/// The ego of `frame` (counted from the drive's start) of drive `drive`,
/// with what its chunk removes from its way.
pub fn ego_at(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> EgoFrame {
    let mut leaders = level_poses(desc, seed, drive, frame..frame + 1).remove(0);
    let pose = leaders.pop().expect("the ego");
    let chunk = frame / CHUNK_FRAMES;
    let key = (format!("{desc:?}"), seed, drive, chunk);
    let entry = REMOVALS.slot(key);
    let mut r = entry.lock().expect("removal");
    let (removed, removed_pedestrians) = r
        .get_or_insert_with(|| Ctx::new(desc, seed, drive).removal(chunk))
        .clone();
    EgoFrame {
        pose,
        leaders,
        removed,
        removed_pedestrians,
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

    /// The drive before its first frame: its path and convoy.
    fn start(&self) -> Drive {
        let l = &self.layout;
        let start = start_link(links(l).len(), self.seed, self.drive);
        let rng = Rng::new(&[self.seed, tag::EGO, self.drive, 1]);
        let turns = &self.plan.schedule.turns;
        let path = DrivePath::new(l, turns, start, rng);
        let ego = Member {
            id: 0,
            body: self.body,
            paint: self.paint,
            start_m: 0.0,
            s: Vec::new(),
            v: Vec::new(),
        };
        Drive::new(path, ego, &turns.bodies, self.seed, self.drive)
    }

    /// Traffic time of the drive's frame `f`, seconds.
    fn time(&self, f: u64) -> f64 {
        drive_time_s(self.desc, self.drive, f)
    }

    /// Appends the next frame's (s, v) to every member, front to back:
    /// each starts at the speed its first frame allows. A member behind
    /// another brakes for where that one's rear is at the step's start
    /// and for its speed after the step (`follow_cap`), so its front ends
    /// the step at least `CONVOY_GAP_M` behind that rear.
    fn step(&self, d: &mut Drive) {
        let frames = d.ego().s.len() as u64;
        let t = self.time(frames.saturating_sub(1));
        // The rear (arc length) of the member ahead and its next speed.
        let mut ahead: Option<(f64, f64)> = None;
        for m in d.members.iter_mut() {
            let half = m.half();
            let (s, v) = match (m.s.last(), m.v.last()) {
                (Some(&s), Some(&v)) => (s, Some(v)),
                _ => (m.start_m, None),
            };
            let mut cap = self.allowed(&mut d.path, half, s, v.unwrap_or(0.0), t, ahead);
            if let Some((rear, u)) = ahead {
                cap = cap.min(follow_cap(rear - s - half - CONVOY_GAP_M, u, self.dt));
            }
            let (s1, v1) = match v {
                Some(v) => {
                    let v = (v + A_LON_MPS2 * self.dt).min(cap).max(0.0);
                    (s + v * self.dt, v)
                }
                None => (s, cap),
            };
            ahead = Some((s - half, v1));
            m.s.push(s1);
            m.v.push(v1);
        }
    }

    /// The highest speed (m/s) a member `half` metres long from centre to
    /// front at arc length `s`, speed `v`, time `t` may take for the next
    /// step, without the follower cap; `ahead`: the rear (arc length) of
    /// the member ahead and its next speed. A junction is entered only
    /// when the one ahead is moving or has left room beyond it.
    fn allowed(
        &self,
        path: &mut DrivePath,
        half: f64,
        s: f64,
        v: f64,
        t: f64,
        ahead: Option<(f64, f64)>,
    ) -> f64 {
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
        let front = s + half;
        let next = path
            .crossings
            .iter()
            .find(|c| c.stop_m >= front - 0.05 && c.stop_m < s + look);
        if let Some(c) = next {
            let room = ahead.is_none_or(|(rear, u)| {
                u > MOVING_LEADER_MPS || rear >= c.clear_m + 2.0 * half + CONVOY_GAP_M
            });
            let clear = c.roundabout
                || c.major == Some(true)
                || self.can_clear(path, c, c.clear_m + half - s, v, t);
            if !(clear && room) {
                cap = cap.min(stop(c.stop_m - front));
            }
        }
        cap
    }

    /// Whether the ego, `d` metres from clearing the zone of crossing `c`
    /// at speed `v` at time `t`, clears it before its approach turns red.
    fn can_clear(&self, path: &DrivePath, c: &Crossing, d: f64, v: f64, t: f64) -> bool {
        let left = until_red_s(&self.plan.schedule, c.dir, t);
        clear_time_s(path, c.stop_m, d, v, self.v_max) + CLEAR_RESERVE_S <= left
    }

    /// The vehicles and pedestrians chunk `k` removes: those within
    /// `MARGIN_M` of a convoy member's footprint in some frame of it.
    fn removal(&self, k: u64) -> Removal {
        let frames = k * CHUNK_FRAMES..(k + 1) * CHUNK_FRAMES;
        let convoys = level_poses(self.desc, self.seed, self.drive, frames.clone());
        let mut vehicles = BTreeSet::new();
        let mut pedestrians = BTreeSet::new();
        let sched = &self.plan.schedule;
        for (f, convoy) in frames.zip(&convoys) {
            let op = self.overpass.as_ref();
            let near = |p: &[f64; 3], q: &[f64; 3], r: f64| (p[0] - q[0]).hypot(p[1] - q[1]) < r;
            let others = others(self.desc, self.seed, &self.plan, op, self.drive, f);
            for m in convoy {
                let grown = grown_corners(m, MARGIN_M);
                for c in &others {
                    if near(&m.position, &c.position, 30.0)
                        && m.same_level(c)
                        && quads_overlap(&grown, &c.corners())
                    {
                        vehicles.insert(c.id);
                    }
                }
            }
            if !self.layout.sidewalks {
                continue;
            }
            let t = self.time(f);
            for w in walkers::pedestrians(self.desc, &self.layout, sched, self.seed, t) {
                let q = [w.position[0], w.position[1]];
                if convoy.iter().any(|m| {
                    near(&m.position, &w.position, 10.0) && rect_distance(m, q) < 0.25 + MARGIN_M
                }) {
                    pedestrians.insert(w.id);
                }
            }
        }
        (Arc::new(vehicles), Arc::new(pedestrians))
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
pub(super) fn quads_overlap(a: &[[f64; 2]; 4], b: &[[f64; 2]; 4]) -> bool {
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
    let entry = motion(desc, seed, drive, frame);
    let d = entry.lock().expect("drive");
    let s = d.ego().s[frame as usize];
    d.path
        .crossings
        .iter()
        .filter(|x| x.clear_m <= s && x.turn != Move::Straight)
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A drive's convoy moves the same whether its path was grown far
    /// ahead first or only as the members reach it, and the memoised
    /// drive asked for a late frame first agrees with both.
    #[test]
    fn convoy_motion_does_not_depend_on_how_far_the_path_was_grown() {
        let desc = crate::town::source::load_named_town("town03", None)
            .unwrap()
            .desc;
        let frames = 1500;
        for drive in 0..6 {
            let cx = Ctx::new(&desc, 5, drive);
            let mut lazy = cx.start();
            let mut grown = cx.start();
            grown.path.reach(40_000.0);
            for _ in 0..frames {
                cx.step(&mut lazy);
                cx.step(&mut grown);
            }
            let late = convoy_at(&desc, 5, drive, frames as u64 - 1);
            assert_eq!(late.len(), lazy.members.len());
            for ((a, b), c) in lazy.members.iter().zip(&grown.members).zip(&late) {
                assert_eq!((&a.s, &a.v), (&b.s, &b.v), "drive {drive} member {}", a.id);
                assert_eq!((a.s[frames - 1], a.v[frames - 1]), (c.s_m, c.speed_mps));
            }
        }
    }
}
