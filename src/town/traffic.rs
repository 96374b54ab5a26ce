//! Traffic over time: the ego's drives (`ego`: a seeded route over the
//! whole grid, moved against the signals and the road, with the
//! background vehicles in its way removed; docs/drives.md) and the
//! background vehicles (`sim`: seeded junction walks on every road,
//! simulated per drive in chunks that each start from their own seeded
//! state, that turn at junctions under per-direction signal phases and
//! keep their distance), plus the overpass's closed loop in closed form.
//! The signal phases (`Schedule`, shown by `signals`) are the same at
//! every junction: the east–west approaches' green, amber and all-red,
//! then the north–south approaches', then a stand in which every
//! approach shows red and pedestrians cross (`walkers`).
//!
//! The overpass route (`routes`, `overpass`) keeps its closed form: every
//! vehicle of it follows one speed profile s(τ) (`profile`) at its own
//! time offset, spaced so that the closest spacing stays at least the
//! longest body plus a gap; it meets no junction.

mod convoy;
pub mod coverage;
mod ego;
mod junction;
mod profile;
mod recent;
mod sim;
mod spawn;

use std::sync::Arc;

use super::desc::TownDesc;
use super::grade::Grade;
use super::layout::{Layout, Rect};
use super::overpass::Overpass;
use super::rng::{tag, Rng};
use super::routes::{Route, Turns};
use super::vehicles::{BodyKind, BODIES, BODY_WEIGHTS};
use super::walkers;

pub use convoy::{CONVOY_GAP_M, CONVOY_ROUTE, LEADER_ID_BASE};
pub use ego::{
    convoy_at, drive_start_frame, start_link, ConvoyMember, CHUNK_FRAMES, DRIVE_WINDOW_FRAMES,
};
pub use profile::{Limits, SpeedProfile};
pub use sim::{cyclist_speed_mps, SIM_ROUTE};

/// Gap kept between consecutive bodies of a route at the closest, metres.
const MIN_GAP_M: f64 = 3.0;
/// Gap between consecutive bodies on a straight at full speed, at least, metres.
const CRUISE_GAP_M: f64 = 6.0;
/// Height difference beyond which two vehicles are on different levels,
/// metres: taller than every body (the bus roof, 3.1 m) and less than the
/// overpass's `TOP_M`.
pub const LEVEL_GAP_M: f64 = 4.0;
/// Lateral acceleration bound in curves, m/s².
pub const A_LAT_MPS2: f64 = 3.0;
/// Longitudinal acceleration and braking bound, m/s².
pub const A_LON_MPS2: f64 = 3.0;

/// Which of a vehicle's signal lamps are lit in one frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct VehicleLamps {
    /// Brake lamps: decelerating or standing.
    pub brake: bool,
    /// Left indicator (blinking: lit in this frame).
    pub left: bool,
    /// Right indicator (blinking: lit in this frame).
    pub right: bool,
}

/// Pose of one vehicle in one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct VehiclePose {
    /// Stable id across frames (route and slot), < 25 000.
    pub id: u32,
    /// Body type.
    pub body: BodyKind,
    /// Paint material name.
    pub paint: &'static str,
    /// Centre of the footprint on the ground, world metres.
    pub position: [f64; 3],
    /// Heading, degrees counter-clockwise from +x, in [0, 360).
    pub heading_deg: f64,
    /// Nose-up pitch on a grade, degrees (0 on level ground).
    pub pitch_deg: f64,
    /// Roll on a cross-slope, degrees, > 0 with the left side higher.
    pub roll_deg: f64,
    /// Index into `Plan::routes` (the overpass), or `SIM_ROUTE` for a
    /// simulated background vehicle, `CONVOY_ROUTE` for one of the ego's
    /// leaders (`usize::MAX` for the ego).
    pub route: usize,
    /// Its lit signal lamps.
    pub lamps: VehicleLamps,
}

impl VehiclePose {
    /// The four corners of the footprint rectangle (x, y), counter-clockwise.
    pub fn corners(&self) -> [[f64; 2]; 4] {
        let [len, w] = self.body.footprint_m();
        let h = self.heading_deg.to_radians();
        let (f, s) = ([h.cos(), h.sin()], [-h.sin(), h.cos()]);
        let [x, y] = [self.position[0], self.position[1]];
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(a, b)| {
            let (a, b) = (a * len / 2.0, b * w / 2.0);
            [x + a * f[0] + b * s[0], y + a * f[1] + b * s[1]]
        })
    }

    /// Whether two vehicles are on the same level (their bodies could
    /// touch): heights less than `LEVEL_GAP_M` apart. A vehicle on the
    /// overpass deck and one on the road below are not.
    pub fn same_level(&self, other: &VehiclePose) -> bool {
        (self.position[2] - other.position[2]).abs() < LEVEL_GAP_M
    }

    /// The axis-aligned bounds of the footprint.
    pub fn footprint(&self) -> Rect {
        let c = self.corners();
        let xs = c.map(|p| p[0]);
        let ys = c.map(|p| p[1]);
        let min = |v: [f64; 4]| v.iter().copied().fold(f64::INFINITY, f64::min);
        let max = |v: [f64; 4]| v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        Rect {
            min: [min(xs), min(ys)],
            max: [max(xs), max(ys)],
        }
    }
}

/// Pose of one pedestrian in one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PedestrianPose {
    /// Stable id across frames.
    pub id: u32,
    /// Look (body and outfit) of the person, `people::VARIANTS` of them.
    pub variant: u32,
    /// Walk-cycle phase (distance walked / stride, cycles), or `None`
    /// standing still.
    pub phase: Option<f64>,
    /// Position of the feet, world metres.
    pub position: [f64; 3],
    /// Heading, degrees counter-clockwise from +x.
    pub heading_deg: f64,
}

/// Every dynamic object of one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct TownFrame {
    /// Frame index.
    pub frame: u64,
    /// Time since frame 0, seconds.
    pub time_s: f64,
    /// The ego vehicle (carrying the cameras).
    pub ego: VehiclePose,
    /// Every other vehicle.
    pub vehicles: Vec<VehiclePose>,
    /// Every pedestrian.
    pub pedestrians: Vec<PedestrianPose>,
}

/// The signal phases, the same at every junction. One cycle, from time 0:
/// every approach stands red while pedestrians cross (`stop_s`); then,
/// `ROUNDS_PER_STAND` times, the x-axis approaches (heading east or west)
/// show green, amber, then red through an all-red gap, and the y-axis
/// approaches the same. Cycle positions count from the first x-axis green
/// (`cycle_time_s`).
#[derive(Clone, Debug, PartialEq)]
pub struct Schedule {
    /// Green time of each axis, seconds.
    pub green_s: f64,
    /// Amber time of each axis, seconds (long enough to stop from the
    /// speed limit at `A_LON_MPS2`, at least 3 s).
    pub amber_s: f64,
    /// All-red gap after each axis's amber, seconds.
    pub all_red_s: f64,
    /// Standing time per cycle, seconds (long enough to cross a road).
    pub stop_s: f64,
    /// Speed limit, m/s.
    pub speed_mps: f64,
    /// Right-turn geometry and the bodies that fit it.
    pub turns: Turns,
    /// Longest body that fits the turns, metres.
    pub max_len_m: f64,
}

impl Schedule {
    /// One axis's share of the cycle: green, amber and all-red, seconds.
    pub fn window_s(&self) -> f64 {
        self.green_s + self.amber_s + self.all_red_s
    }

    /// Cycle length, seconds.
    pub fn cycle_s(&self) -> f64 {
        self.moving_s() + self.stop_s
    }

    /// Time from the start of a cycle until the pedestrians' stand, seconds.
    pub fn moving_s(&self) -> f64 {
        2.0 * ROUNDS_PER_STAND as f64 * self.window_s()
    }

    /// Time `t` on the cycle's clock, seconds: 0 where the x-axis's green
    /// starts, so time 0 lies in the stand before it.
    pub fn cycle_time_s(&self, t: f64) -> f64 {
        t + self.moving_s()
    }

    /// Whether every approach stands red for the pedestrians at time `t`.
    pub fn standing(&self, t: f64) -> bool {
        self.cycle_time_s(t).rem_euclid(self.cycle_s()) >= self.moving_s()
    }

    /// Time since the start of the latest green of the axis of direction
    /// `dir` (0 east, 1 north, 2 west, 3 south) at `t`, seconds (beyond
    /// green + amber: red; infinite during the stand).
    pub fn axis_time_s(&self, dir: usize, t: f64) -> f64 {
        let tau = self.cycle_time_s(t).rem_euclid(self.cycle_s());
        if tau >= self.moving_s() {
            return f64::INFINITY;
        }
        let w = self.window_s();
        (tau - (dir % 2) as f64 * w).rem_euclid(2.0 * w)
    }
}

/// How the vehicles of one closed route move.
#[derive(Clone, Debug, PartialEq)]
pub struct RoutePlan {
    /// The route.
    pub route: Route,
    /// Its speed profile.
    pub profile: SpeedProfile,
    /// Slot time offsets c_n (seconds of route time).
    pub slots: Vec<f64>,
}

/// The schedule and the closed routes (the overpass's) of a town.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The signal phases.
    pub schedule: Schedule,
    /// The closed routes: the overpass's loop, if the town has one.
    pub routes: Vec<RoutePlan>,
}

impl Plan {
    /// The plan of a validated town (cached per description).
    pub fn new(desc: &TownDesc) -> Arc<Plan> {
        use std::collections::BTreeMap;
        use std::sync::{Mutex, OnceLock};
        static CACHE: OnceLock<Mutex<BTreeMap<String, Arc<Plan>>>> = OnceLock::new();
        let key = format!("{desc:?}");
        let cache = CACHE.get_or_init(|| Mutex::new(BTreeMap::new()));
        if let Some(p) = cache.lock().expect("plan cache").get(&key) {
            return p.clone();
        }
        let p = Arc::new(Self::build(desc));
        cache.lock().expect("plan cache").insert(key, p.clone());
        p
    }

    fn build(desc: &TownDesc) -> Plan {
        let l = Layout::new(desc);
        let turns = Turns::new(l.lane_w_m);
        let max_len_m = turns
            .bodies
            .iter()
            .map(|b| b.footprint_m()[0])
            .fold(0.0, f64::max);
        let speed_mps = desc.speed_kmh / 3.6;
        let lim = Limits {
            v_max_mps: speed_mps,
            a_lat_mps2: A_LAT_MPS2,
            a_lon_mps2: A_LON_MPS2,
        };
        let crossing = (l.road_w_m + 1.6) / walkers::WALK_MPS;
        let schedule = Schedule {
            green_s: GREEN_S,
            amber_s: (speed_mps / (2.0 * A_LON_MPS2)).max(3.0),
            all_red_s: ALL_RED_S,
            stop_s: if l.sidewalks { crossing + 2.0 } else { 4.0 },
            speed_mps,
            turns,
            max_len_m,
        };
        let routes = Overpass::new(desc, &l)
            .map(|o| o.route())
            .into_iter()
            .map(|route| {
                let profile = SpeedProfile::new(&route, lim);
                route_plan(route, profile)
            })
            .collect();
        Plan { schedule, routes }
    }
}

/// Green time of each axis, seconds.
const GREEN_S: f64 = 10.0;
/// Rounds of both axes' windows between two pedestrian stands.
pub const ROUNDS_PER_STAND: usize = 2;
/// All-red gap after each amber, seconds.
const ALL_RED_S: f64 = 1.5;

/// Slots of a closed route: the most vehicles whose closest spacing stays
/// ≥ the longest body plus `MIN_GAP_M` (and ≥ `CRUISE_GAP_M` on average).
fn route_plan(route: Route, profile: SpeedProfile) -> RoutePlan {
    let lap = profile.lap_s();
    let len = route.length_m();
    let max_len_m = route.max_len_m();
    let need = max_len_m + MIN_GAP_M;
    let fits = |n: usize| n == 1 || profile.min_spacing_m(lap / n as f64) >= need;
    let most = (len / (max_len_m + CRUISE_GAP_M)).floor().max(1.0) as usize;
    let n = (1..=most).rev().find(|&n| fits(n)).unwrap_or(1);
    let slots = (0..n).map(|k| k as f64 * lap / n as f64).collect();
    RoutePlan {
        route,
        profile,
        slots,
    }
}

fn weighted_body(r: &mut Rng, allowed: &[BodyKind]) -> BodyKind {
    let weight = |b: &BodyKind| {
        BODIES
            .iter()
            .position(|x| x == b)
            .map_or(0.0, |n| BODY_WEIGHTS[n])
    };
    let total: f64 = allowed.iter().map(weight).sum();
    let mut u = r.f64() * total;
    for b in allowed {
        if u < weight(b) {
            return *b;
        }
        u -= weight(b);
    }
    allowed[0]
}

/// Every object's pose at `frame` of drive 0 (`drive_frame_at`).
pub fn frame_at(desc: &TownDesc, seed: u64, frame: u64) -> TownFrame {
    drive_frame_at(desc, seed, 0, frame)
}

/// Every object's pose at `frame` of drive `drive`: the background
/// vehicles (`sim`), and the overpass's and the pedestrians in closed
/// form, at the drive's traffic time (town frame
/// `ego::drive_start_frame(drive) + frame`, which `TownFrame::frame`
/// holds), without those the drive removes from its way, then the ego's
/// leaders, and the ego (`ego::ego_at`). Computed in the level grid, then set on the ground.
pub fn drive_frame_at(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> TownFrame {
    let l = Layout::new(desc);
    let plan = Plan::new(desc);
    let clock = ego::drive_start_frame(drive) + frame;
    let t = clock as f64 / desc.fps;
    let me = ego::ego_at(desc, seed, drive, frame);
    let grade = Grade::new(desc, seed);
    let warp = super::organic::Warp::new(desc, seed);
    let overpass = Overpass::new(desc, &l);
    let vehicles = others(desc, seed, &plan, overpass.as_ref(), drive, frame)
        .into_iter()
        .filter(|v| !me.removed.contains(&v.id))
        .chain(me.leaders)
        .map(|v| match (&overpass, v.route < plan.routes.len()) {
            (Some(_), true) => v,
            // Organic towns bend the level pose first (a planar warp).
            _ => on_ground(bent(warp.as_ref(), v), grade.as_ref()),
        })
        .collect();
    let mut pedestrians = walkers::pedestrians(desc, &l, &plan.schedule, seed, t);
    pedestrians.retain(|p| !me.removed_pedestrians.contains(&p.id));
    if let Some(w) = &warp {
        pedestrians = pedestrians.into_iter().map(|p| w.pedestrian(p)).collect();
    }
    if let Some(g) = &grade {
        for p in &mut pedestrians {
            p.position[2] += g.height_m(p.position[0], p.position[1]);
        }
    }
    TownFrame {
        frame: clock,
        time_s: t,
        ego: on_ground(bent(warp.as_ref(), me.pose), grade.as_ref()),
        vehicles,
        pedestrians,
    }
}

/// The ego's pose (set on the ground) and speed (m/s over the last frame,
/// in the world) at `frame` of drive `drive`: what `parallax town
/// --trajectory` prints.
pub fn ego_pose(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> (VehiclePose, f64) {
    let (pose, level_speed) = ego::ego_motion(desc, seed, drive, frame);
    let grade = Grade::new(desc, seed);
    let warp = super::organic::Warp::new(desc, seed);
    let world = |p: VehiclePose| on_ground(bent(warp.as_ref(), p), grade.as_ref());
    // The drive moves on the level grid; the warp and the grade stretch
    // the last frame's step (frame 0: the next one) by its chords' ratio.
    let level = |k| ego::ego_motion(desc, seed, drive, k).0;
    let (a, b) = if frame > 0 {
        (level(frame - 1), pose.clone())
    } else {
        (pose.clone(), level(1))
    };
    let level_chord = distance(&a, &b);
    let stretch = if level_chord > 1e-9 {
        distance(&world(a), &world(b)) / level_chord
    } else {
        1.0
    };
    (world(pose), level_speed * stretch)
}

fn distance(a: &VehiclePose, b: &VehiclePose) -> f64 {
    (0..3)
        .map(|i| (a.position[i] - b.position[i]).powi(2))
        .sum::<f64>()
        .sqrt()
}

/// Every vehicle but the ego at `frame` of drive `drive`, level grid
/// poses (z and pitch set on the overpass only): the simulated ones, then
/// the overpass's.
fn others(
    desc: &TownDesc,
    seed: u64,
    plan: &Plan,
    overpass: Option<&Overpass>,
    drive: u64,
    frame: u64,
) -> Vec<VehiclePose> {
    let t = (ego::drive_start_frame(drive) + frame) as f64 / desc.fps;
    let mut out = sim::vehicles_at(desc, seed, drive, frame).to_vec();
    out.extend(closed(desc, seed, plan, overpass, t));
    out
}

/// First id of the closed routes' vehicles (the simulated ones count up
/// from 1).
const CLOSED_ID_BASE: u32 = 20_000;

/// The closed routes' vehicles at time `t`, in closed form.
fn closed(
    desc: &TownDesc,
    seed: u64,
    plan: &Plan,
    overpass: Option<&Overpass>,
    t: f64,
) -> Vec<VehiclePose> {
    let mut vehicles = Vec::new();
    let mut id = CLOSED_ID_BASE;
    for (ri, rp) in plan.routes.iter().enumerate() {
        for (n, &offset) in rp.slots.iter().enumerate() {
            id += 1;
            assert!(
                id <= convoy::LEADER_ID_BASE,
                "closed route ids reach the leaders'"
            );
            let mut r = Rng::new(&[seed, tag::SLOT, ri as u64, n as u64]);
            if !r.chance(desc.traffic_density) {
                continue;
            }
            let body = weighted_body(&mut r, &rp.route.bodies);
            let paint = super::materials::draw_paint(r.f64());
            let (p, heading) = rp.route.pose(rp.profile.arc_at(t + offset));
            let pose = VehiclePose {
                id,
                body,
                paint,
                position: [p[0], p[1], 0.0],
                heading_deg: heading.to_degrees(),
                pitch_deg: 0.0,
                roll_deg: 0.0,
                route: ri,
                lamps: VehicleLamps::default(),
            };
            vehicles.push(match overpass {
                Some(o) => on_overpass(pose, o),
                None => pose,
            });
        }
    }
    vehicles
}

/// The pose on the overpass road: z and pitch from its height profile.
fn on_overpass(mut v: VehiclePose, o: &Overpass) -> VehiclePose {
    let (z, pitch) = o.pose([v.position[0], v.position[1]], v.heading_deg);
    v.position[2] = z;
    v.pitch_deg = pitch;
    v
}

/// The level pose bent by an organic town's warp (unchanged without one).
fn bent(warp: Option<&super::organic::Warp>, v: VehiclePose) -> VehiclePose {
    match warp {
        Some(w) => w.vehicle(v),
        None => v,
    }
}

/// The pose set on the ground field: z from h at the footprint centre,
/// pitch and roll from ∇h (unchanged on level ground).
fn on_ground(mut v: VehiclePose, grade: Option<&Grade>) -> VehiclePose {
    if let Some(g) = grade {
        let p = g.pose(v.position[0], v.position[1], v.heading_deg);
        v.position[2] += p.z_m;
        (v.pitch_deg, v.roll_deg) = (p.pitch_deg, p.roll_deg);
    }
    v
}

#[cfg(test)]
mod tests;
