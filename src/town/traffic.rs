//! Traffic over time in closed form. Vehicles ride the closed routes of
//! `routes` (block loops turning right at every corner, the ring turning
//! left around the town and going straight through its T junctions) as
//! rigid trains: slot n of route r sits at arc length o_n + v_r·G(t), where
//! G is one town-wide stop-and-go clock (drive T_go, stand T_stop). The pose
//! of every object at frame K is a pure function of (desc, seed, K).
//!
//! No overlap, by construction: routes share no road surface (each lane
//! belongs to one route and corners stay in their own corridor), and slots
//! of one route keep a fixed arc spacing ≥ the longest allowed body plus a
//! gap. Stops: a block loop is square, so with v_r·T_go = a quarter of its
//! perimeter every slot stands at the same side position at every stop;
//! slots are placed so one per side stands at the stop line, the others
//! queue behind it, and slots whose stop position would lie in the
//! departing junction or crosswalk stay empty. Crosswalks on interior roads
//! are therefore clear while everything stands (pedestrians cross then).

use super::desc::TownDesc;
use super::layout::{Layout, Rect};
use super::materials::PAINTS;
use super::rng::{tag, Rng};
use super::routes::{routes, Route, RouteKind, Turns};
use super::vehicles::{BodyKind, BODIES, BODY_WEIGHTS};
use super::walkers;

/// Stop line distance before the junction edge (as painted), metres.
const STOP_LINE_AT_M: f64 = 4.2;
/// Gap between consecutive bodies on a route, metres.
const GAP_M: f64 = 6.0;

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
    /// Shirt material name.
    pub shirt: &'static str,
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

/// The town-wide stop-and-go clock and the slot layout it implies.
#[derive(Clone, Debug, PartialEq)]
pub struct Schedule {
    /// Driving time per cycle, seconds.
    pub go_s: f64,
    /// Standing time per cycle, seconds (long enough to cross a road).
    pub stop_s: f64,
    /// Cruising speed of the ring and the innermost block lanes, m/s.
    pub speed_mps: f64,
    /// Corner geometry and the bodies that fit it.
    pub turns: Turns,
    /// Longest allowed body, metres.
    pub max_len_m: f64,
}

impl Schedule {
    /// The schedule of a validated town.
    pub fn new(desc: &TownDesc) -> Self {
        let l = Layout::new(desc);
        let turns = Turns::new(l.lane_w_m);
        let max_len_m = turns
            .bodies
            .iter()
            .map(|b| b.footprint_m()[0])
            .fold(0.0, f64::max);
        let speed_mps = desc.speed_kmh / 3.6;
        let quarter = block_quarter_m(&l, &turns, 0);
        let crossing = (l.road_w_m + 1.6) / walkers::WALK_MPS;
        Schedule {
            go_s: quarter / speed_mps,
            stop_s: if l.sidewalks { crossing + 2.0 } else { 4.0 },
            speed_mps,
            turns,
            max_len_m,
        }
    }

    /// Cycle length T_go + T_stop, seconds.
    pub fn cycle_s(&self) -> f64 {
        self.go_s + self.stop_s
    }

    /// Driving time G(t) elapsed by time `t`, seconds (stands still during
    /// the last `stop_s` of every cycle).
    pub fn driven_s(&self, t: f64) -> f64 {
        let n = (t / self.cycle_s()).floor();
        let tau = t - n * self.cycle_s();
        n * self.go_s + tau.min(self.go_s)
    }

    /// Whether everything stands still at time `t`.
    pub fn standing(&self, t: f64) -> bool {
        t.rem_euclid(self.cycle_s()) >= self.go_s
    }

    /// Speed of `route`, m/s: block loops drive a quarter loop per cycle.
    pub fn route_speed_mps(&self, route: &Route) -> f64 {
        match route.kind {
            RouteKind::Block { .. } => route.length_m() / 4.0 / self.go_s,
            RouteKind::Ring => self.speed_mps,
        }
    }
}

/// A quarter of the perimeter of a block loop on lane `k`, metres.
fn block_quarter_m(l: &Layout, turns: &Turns, k: u32) -> f64 {
    let e = (k as f64 + 0.5) * l.lane_w_m;
    let side = l.pitch_m - 2.0 * e - 2.0 * turns.radius_m;
    side + std::f64::consts::FRAC_PI_2 * turns.radius_m
}

/// Slot arc offsets of `route` with, for block loops, whether each slot may
/// hold a vehicle (its stop position lies on the straight between the
/// departing crosswalk and the stop line).
pub fn slots(l: &Layout, s: &Schedule, route: &Route) -> Vec<(f64, bool)> {
    let len = route.length_m();
    let min_spacing = s.max_len_m + GAP_M;
    match route.kind {
        RouteKind::Ring => {
            let n = (len / min_spacing).floor().max(1.0) as usize;
            (0..n).map(|k| (k as f64 * len / n as f64, true)).collect()
        }
        RouteKind::Block { .. } => {
            let quarter = len / 4.0;
            let per_side = (quarter / min_spacing).floor().max(1.0) as usize;
            let spacing = quarter / per_side as f64;
            let r = route.radius_m;
            let e = (route.lane as f64 + 0.5) * l.lane_w_m;
            let hw = l.road_w_m / 2.0;
            let side = route.side_m()[0];
            // Side coordinates: 0 at the end of the previous corner arc.
            let stop = side + r - (hw - e) - STOP_LINE_AT_M - s.max_len_m / 2.0;
            let clear = (hw - e) - r + 3.5 + 0.5 + s.max_len_m / 2.0;
            (0..4 * per_side)
                .map(|k| {
                    let back = (k % per_side) as f64 * spacing;
                    let offset = stop - back + (k / per_side) as f64 * quarter;
                    (offset.rem_euclid(len), stop - back >= clear)
                })
                .collect()
        }
    }
}

/// Where the ego drives: (route index, slot index).
pub fn ego_slot(desc: &TownDesc, seed: u64) -> (usize, usize) {
    let l = Layout::new(desc);
    let s = Schedule::new(desc);
    let all = routes(&l, &s.turns);
    let mut r = Rng::new(&[seed, tag::EGO]);
    // A block away from the town edge when there is one.
    let pick = |n: usize, r: &mut Rng| {
        if n >= 3 {
            r.int(1, n as u32 - 2) as usize
        } else {
            0
        }
    };
    let mut ij = (pick(l.nx, &mut r), pick(l.ny, &mut r));
    if l.block_touches_roundabout(ij.0, ij.1) {
        // Blocks at the roundabout have no loops: any other block.
        let free: Vec<(usize, usize)> = (0..l.ny)
            .flat_map(|j| (0..l.nx).map(move |i| (i, j)))
            .filter(|&(i, j)| !l.block_touches_roundabout(i, j))
            .collect();
        ij = free[r.index(free.len())];
    }
    let (i, j) = ij;
    let k = r.int(0, l.lanes - 1);
    let route = all
        .iter()
        .position(|ro| ro.kind == RouteKind::Block { i, j } && ro.lane == k)
        .expect("the ego route exists");
    let open: Vec<usize> = slots(&l, &s, &all[route])
        .iter()
        .enumerate()
        .filter(|(_, (_, ok))| *ok)
        .map(|(n, _)| n)
        .collect();
    (route, open[r.index(open.len())])
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

/// Every object's pose at `frame` (time frame / fps), in closed form.
pub fn frame_at(desc: &TownDesc, seed: u64, frame: u64) -> TownFrame {
    let l = Layout::new(desc);
    let sched = Schedule::new(desc);
    let t = frame as f64 / desc.fps;
    let driven = sched.driven_s(t);
    let (ego_route, ego_slot_n) = ego_slot(desc, seed);
    let ego_body = if sched.turns.bodies.contains(&BodyKind::Sedan) {
        BodyKind::Sedan
    } else {
        sched.turns.bodies[0]
    };
    let mut ego = None;
    let mut vehicles = Vec::new();
    let mut next_id = 1u32;
    for (ri, route) in routes(&l, &sched.turns).iter().enumerate() {
        let travelled = sched.route_speed_mps(route) * driven;
        for (n, (offset, open)) in slots(&l, &sched, route).into_iter().enumerate() {
            let id = next_id;
            next_id += 1;
            let is_ego = ri == ego_route && n == ego_slot_n;
            let mut r = Rng::new(&[seed, tag::SLOT, ri as u64, n as u64]);
            let occupied = open && r.chance(desc.traffic_density);
            if !(occupied || is_ego) {
                continue;
            }
            let body = if is_ego {
                ego_body
            } else {
                weighted_body(&mut r, &sched.turns.bodies)
            };
            let paint = PAINTS[r.index(PAINTS.len())];
            // Shorter bodies ride forward in their slot, so every front
            // stands at the stop line (gaps stay ≥ GAP_M: see `slots`).
            let shift = (sched.max_len_m - body.footprint_m()[0]) / 2.0;
            let (p, heading) = route.pose(offset + shift + travelled);
            let pose = VehiclePose {
                id,
                body,
                paint,
                position: [p[0], p[1], 0.0],
                heading_deg: heading.to_degrees(),
                route: ri,
            };
            if is_ego {
                ego = Some(pose);
            } else {
                vehicles.push(pose);
            }
        }
    }
    TownFrame {
        frame,
        time_s: t,
        ego: ego.expect("the ego slot is always occupied"),
        vehicles,
        pedestrians: walkers::pedestrians(desc, &l, &sched, seed, t),
    }
}
