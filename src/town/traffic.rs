//! Traffic over time in closed form, and the ego's drives (`ego`: a
//! seeded route over the whole grid, simulated from the drive's start,
//! with the background vehicles in its way removed; docs/drives.md).
//! Vehicles ride the closed routes of `routes` (block loops turning right
//! at every corner or round the roundabout, the ring turning left around
//! the town and going straight through its T junctions). Every vehicle
//! of route r follows the same speed profile s(τ) (`profile`: slower in
//! curves, accelerating out) at its own time offset c_n: s_n(t) = s(ρ_r·G(t) + c_n), where G is one
//! town-wide stop-and-go clock (ramp up, drive, ramp down, stand) and ρ_r
//! ≤ 1 scales the route so it advances exactly 1/m_r lap per cycle; the
//! ring (on the outer roads, without crossers) ignores the clock. The
//! pose of every object at frame K is a pure function of (desc, seed, K).
//! Each route carries the bodies its corners fit; in multi-lane towns the
//! ring's long-vehicle route runs a bus line (every third slot a bus or
//! truck), spaced for the longest body on it.
//!
//! No overlap, by construction: routes share no road surface (each lane
//! belongs to one route, corners stay in their own corridor, roundabout
//! turns in their own quarter of the ring), and time offsets of one route
//! differ by Δc, chosen so the arc spacing min over τ of s(τ+Δc) − s(τ) is
//! at least the longest allowed body plus a gap. Stops: the offsets are
//! shifted by whole Δc each cycle, so the stand positions of a block loop
//! repeat every m_r cycles; the lead slot stands at the first stop line,
//! and slots that would stand in a junction, crosswalk or the roundabout at
//! any of their m_r stands stay empty. Crosswalks on interior roads are
//! therefore clear while everything stands (pedestrians cross then).

pub mod coverage;
mod ego;
mod profile;

use std::sync::Arc;

use super::desc::TownDesc;
use super::grade::Grade;
use super::layout::{Layout, Rect};
use super::overpass::Overpass;
use super::rng::{tag, Rng};
use super::routes::{routes, Route, RouteKind, Turns};
use super::vehicles::{BodyKind, BODIES, BODY_WEIGHTS};
use super::walkers;

pub use ego::{drive_start_frame, start_link, CHUNK_FRAMES, DRIVE_WINDOW_FRAMES};
pub use profile::{Limits, SpeedProfile};

/// Gap kept between consecutive bodies of a route at the closest, metres.
const MIN_GAP_M: f64 = 3.0;
/// Gap between consecutive bodies on a straight at full speed, at least, metres.
const CRUISE_GAP_M: f64 = 6.0;
/// On long-vehicle routes, slots n ≡ 0 (mod this) hold a bus or truck.
const LINE_EVERY: usize = 3;
/// Height difference beyond which two vehicles are on different levels,
/// metres: taller than every body (the bus roof, 3.1 m) and less than the
/// overpass's `TOP_M`.
pub const LEVEL_GAP_M: f64 = 4.0;
/// Lateral acceleration bound in curves, m/s².
pub const A_LAT_MPS2: f64 = 3.0;
/// Longitudinal acceleration and braking bound, m/s².
pub const A_LON_MPS2: f64 = 3.0;

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
    /// Index into `routes()`.
    pub route: usize,
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

/// The town-wide stop-and-go clock.
#[derive(Clone, Debug, PartialEq)]
pub struct Schedule {
    /// Driving time per cycle at full clock rate, seconds.
    pub go_s: f64,
    /// Duration of each of the two clock ramps (start, stop), seconds.
    pub ramp_s: f64,
    /// Standing time per cycle, seconds (long enough to cross a road).
    pub stop_s: f64,
    /// Speed limit, m/s.
    pub speed_mps: f64,
    /// Corner geometry of the block loops and the bodies that fit it.
    pub turns: Turns,
    /// Longest body on the block loops, metres.
    pub max_len_m: f64,
}

impl Schedule {
    /// Cycle length, seconds: ramp up and drive (go_s), ramp down (ramp_s), stand.
    pub fn cycle_s(&self) -> f64 {
        self.go_s + self.ramp_s + self.stop_s
    }

    /// Time from the start of a cycle until everything stands, seconds.
    pub fn moving_s(&self) -> f64 {
        self.go_s + self.ramp_s
    }

    /// Clock time G(t) elapsed by time `t`, seconds: the rate ramps
    /// linearly 0 → 1 over `ramp_s`, holds, ramps 1 → 0, then stands, so
    /// each cycle adds exactly `go_s`.
    pub fn driven_s(&self, t: f64) -> f64 {
        let n = (t / self.cycle_s()).floor();
        let tau = t - n * self.cycle_s();
        let r = self.ramp_s;
        let g = if tau < r {
            tau * tau / (2.0 * r)
        } else if tau < self.go_s {
            tau - r / 2.0
        } else if tau < self.go_s + r {
            let u = self.go_s + r - tau;
            self.go_s - u * u / (2.0 * r)
        } else {
            self.go_s
        };
        n * self.go_s + g
    }

    /// Whether everything stands still at time `t`.
    pub fn standing(&self, t: f64) -> bool {
        t.rem_euclid(self.cycle_s()) >= self.moving_s()
    }
}

/// How the vehicles of one route move.
#[derive(Clone, Debug, PartialEq)]
pub struct RoutePlan {
    /// The route.
    pub route: Route,
    /// Its speed profile.
    pub profile: SpeedProfile,
    /// Route time per unit of clock time (≤ 1).
    pub rate: f64,
    /// Stops per lap m (block loops), or 0 (the ring stands anywhere).
    pub stands: usize,
    /// Slot time offsets c_n (seconds of route time) and whether each may
    /// hold a vehicle.
    pub slots: Vec<(f64, bool)>,
}

/// The schedule and every route's plan of a town.
#[derive(Clone, Debug, PartialEq)]
pub struct Plan {
    /// The clock.
    pub schedule: Schedule,
    /// One plan per route, in `routes()` order.
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
        let mut all = routes(&l, &turns);
        all.extend(Overpass::new(desc, &l).map(|o| o.route()));
        let profiles: Vec<SpeedProfile> = all.iter().map(|r| SpeedProfile::new(r, lim)).collect();
        // A quarter lap of the slowest block loop per cycle (a plain
        // lane-0 loop, or one round the roundabout, a little longer).
        let go_s = all
            .iter()
            .zip(&profiles)
            .filter(|(r, _)| matches!(r.kind, RouteKind::Block { .. }))
            .map(|(_, p)| p.lap_s() / 4.0)
            .fold(0.0, f64::max);
        let go_s = if go_s > 0.0 {
            go_s
        } else {
            profiles.iter().map(|p| p.lap_s() / 4.0).fold(0.0, f64::max)
        };
        let crossing = (l.road_w_m + 1.6) / walkers::WALK_MPS;
        let schedule = Schedule {
            go_s,
            ramp_s: (speed_mps / A_LON_MPS2).min(go_s / 4.0),
            stop_s: if l.sidewalks { crossing + 2.0 } else { 4.0 },
            speed_mps,
            turns,
            max_len_m,
        };
        let routes = all
            .into_iter()
            .zip(profiles)
            .map(|(route, profile)| route_plan(&schedule, route, profile))
            .collect();
        Plan { schedule, routes }
    }
}

/// Slots of one route: the most vehicles whose closest spacing stays ≥
/// the longest body plus `MIN_GAP_M` (and ≥ `CRUISE_GAP_M` on average).
fn route_plan(s: &Schedule, route: Route, profile: SpeedProfile) -> RoutePlan {
    let lap = profile.lap_s();
    let len = route.length_m();
    let max_len_m = route.max_len_m();
    let need = max_len_m + MIN_GAP_M;
    let fits = |n: usize| n == 1 || profile.min_spacing_m(lap / n as f64) >= need;
    let most = (len / (max_len_m + CRUISE_GAP_M)).floor().max(1.0) as usize;
    if matches!(route.kind, RouteKind::Ring | RouteKind::Overpass) {
        let n = (1..=most).rev().find(|&n| fits(n)).unwrap_or(1);
        let slots = (0..n).map(|k| (k as f64 * lap / n as f64, true)).collect();
        return RoutePlan {
            route,
            profile,
            rate: 1.0,
            stands: 0,
            slots,
        };
    }
    let m = (lap / s.go_s - 1e-9).ceil().max(1.0) as usize;
    let per = (1..=(most / m).max(1))
        .rev()
        .find(|&p| fits(m * p))
        .unwrap_or(1);
    let n = m * per;
    let dc = lap / n as f64;
    let half = max_len_m / 2.0;
    let lead = profile.time_at((route.keep_clear_m[0][0] - half).rem_euclid(len));
    let slots = (0..n)
        .map(|k| {
            let c = lead - k as f64 * dc;
            let open = (0..m).all(|q| {
                let at = profile.arc_at((c + q as f64 * lap / m as f64).rem_euclid(lap));
                route.may_stand(at, half)
            });
            (c.rem_euclid(lap), open)
        })
        .collect();
    RoutePlan {
        route,
        profile,
        rate: lap / m as f64 / s.go_s,
        stands: m,
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

/// Every object's pose at `frame` of drive `drive`: the background traffic
/// and pedestrians in closed form at the drive's traffic time (town frame
/// `ego::drive_start_frame(drive)` + `frame`, which `TownFrame::frame`
/// holds), without those the drive removes from its way, and the ego
/// (`ego::ego_at`). Computed in the level grid, then set on the ground.
pub fn drive_frame_at(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> TownFrame {
    let l = Layout::new(desc);
    let plan = Plan::new(desc);
    let clock = ego::drive_start_frame(drive) + frame;
    let t = clock as f64 / desc.fps;
    let me = ego::ego_at(desc, seed, drive, frame);
    let grade = Grade::new(desc, seed);
    let warp = super::organic::Warp::new(desc, seed);
    let overpass = Overpass::new(desc, &l);
    let vehicles = background(desc, seed, &plan, overpass.as_ref(), t)
        .into_iter()
        .filter(|v| !me.removed.contains(&v.id))
        .map(|v| match (&overpass, plan.routes[v.route].route.kind) {
            (Some(_), RouteKind::Overpass) => v,
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

/// The ego's pose (set on the ground) and speed (m/s) at `frame` of drive
/// `drive`: what `parallax town --trajectory` prints.
pub fn ego_pose(desc: &TownDesc, seed: u64, drive: u64, frame: u64) -> (VehiclePose, f64) {
    let me = ego::ego_at(desc, seed, drive, frame);
    let grade = Grade::new(desc, seed);
    let warp = super::organic::Warp::new(desc, seed);
    let pose = on_ground(bent(warp.as_ref(), me.pose), grade.as_ref());
    (pose, me.speed_mps)
}

/// Every background vehicle at time `t` in closed form: level grid
/// positions, z and pitch set on the overpass only.
fn background(
    desc: &TownDesc,
    seed: u64,
    plan: &Plan,
    overpass: Option<&Overpass>,
    t: f64,
) -> Vec<VehiclePose> {
    let driven = plan.schedule.driven_s(t);
    let mut vehicles = Vec::new();
    let mut next_id = 1u32;
    for (ri, rp) in plan.routes.iter().enumerate() {
        // The ring never stands (it meets no crosswalk that pedestrians
        // use): its vehicles drive on while the block loops wait.
        let tau = match rp.route.kind {
            RouteKind::Ring | RouteKind::Overpass => t,
            RouteKind::Block { .. } => rp.rate * driven,
        };
        for (n, &(offset, open)) in rp.slots.iter().enumerate() {
            let id = next_id;
            next_id += 1;
            let mut r = Rng::new(&[seed, tag::SLOT, ri as u64, n as u64]);
            let Some(body) = slot_body(desc, rp, (n, open), &mut r, None) else {
                continue;
            };
            let paint = super::materials::draw_paint(r.f64());
            let (p, heading) = slot_pose(rp, tau + offset, body);
            let pose = VehiclePose {
                id,
                body,
                paint,
                position: [p[0], p[1], 0.0],
                heading_deg: heading.to_degrees(),
                pitch_deg: 0.0,
                roll_deg: 0.0,
                route: ri,
            };
            vehicles.push(match (overpass, rp.route.kind) {
                (Some(o), RouteKind::Overpass) => on_overpass(pose, o),
                _ => pose,
            });
        }
    }
    vehicles
}

/// The body in slot `n` (`open`: not kept free) of route plan `rp`, drawn
/// from the slot's stream `r`, or None when the slot stays empty; `ego`:
/// the ego's body when this is the ego's slot (always occupied). A bus
/// line: every third slot of a long-vehicle route always holds a bus or
/// truck; the others fill at the traffic density.
fn slot_body(
    desc: &TownDesc,
    rp: &RoutePlan,
    (n, open): (usize, bool),
    r: &mut Rng,
    ego: Option<BodyKind>,
) -> Option<BodyKind> {
    let line = n % LINE_EVERY == 0 && rp.route.bodies.contains(&BodyKind::Bus);
    let occupied = open && (r.chance(desc.traffic_density) || line);
    if !(occupied || ego.is_some()) {
        return None;
    }
    Some(match ego {
        Some(b) => b,
        None if line => weighted_body(r, &[BodyKind::Bus, BodyKind::Truck]),
        None => weighted_body(r, &rp.route.bodies),
    })
}

/// Position and heading of `body` in the slot at schedule position `at`
/// of route plan `rp`. Shorter bodies ride forward in their slot, so every
/// front stands at the stop line (gaps stay ≥ MIN_GAP_M: see `Plan`); the
/// ring never stands, so its bodies ride their slot centres (up to 3.75 m
/// ahead, a car would enter corners too fast).
fn slot_pose(rp: &RoutePlan, at: f64, body: BodyKind) -> ([f64; 2], f64) {
    let shift = match rp.route.kind {
        RouteKind::Ring | RouteKind::Overpass => 0.0,
        RouteKind::Block { .. } => (rp.route.max_len_m() - body.footprint_m()[0]) / 2.0,
    };
    rp.route.pose(rp.profile.arc_at(at) + shift)
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
