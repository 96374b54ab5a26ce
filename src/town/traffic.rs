//! Traffic over time in closed form: every lane is a periodic track (its
//! road's length L, a whole number of slot spacings d) carrying vehicles at
//! fixed arc-length spacing d, all moving at one speed v, so the pose of every
//! vehicle at frame K is a pure function of (desc, seed, K).
//!
//! Junctions are shared in alternating time windows: with junctions at
//! multiples of the block pitch P = m·d, a vehicle on an x-lane is near a
//! junction centre when (φ_x + v·t) mod d is within h of 0, a vehicle on a
//! y-lane when (φ_x + d/2 + v·t) mod d is; the two distances to the nearest
//! multiple of d sum to d/2, so with h = W/2 + L_max/2 + margin ≤ d/4 they are
//! never both near one (`TownDesc::min_block_size_m` guarantees it). Lanes do
//! not overlap side by side (a lane is wider than any body), so no two
//! vehicles ever overlap. Vehicles leave at one town edge and re-enter at the
//! other (y-lane vehicles are hidden while their body is past the outer road).
//! Pedestrians walk loops around blocks on the sidewalks, also in closed form.

use super::desc::{TownDesc, JUNCTION_MARGIN_M, MAX_VEHICLE_LENGTH_M};
use super::layout::{Layout, Rect};
use super::materials::PAINTS;
use super::rng::{tag, Rng};
use super::roads::Axis;
use super::vehicles::{BodyKind, BODIES, BODY_WEIGHTS};

/// One lane: a periodic track along a road.
#[derive(Clone, Debug, PartialEq)]
pub struct Lane {
    /// Road axis.
    pub axis: Axis,
    /// Road index (j for x-roads, i for y-roads).
    pub road: usize,
    /// Travel direction along the axis, ±1.
    pub dir: f64,
    /// Lane number counted from the centreline, 0-based.
    pub k: u32,
    /// Lane centre in world coordinates across the road (y for x-lanes, x for y-lanes).
    pub center: f64,
    /// Period of the track (the road's grid length), metres.
    pub length_m: f64,
}

/// Pose of one vehicle in one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct VehiclePose {
    /// Stable id across frames (lane and slot), < 30 000.
    pub id: u32,
    /// Body type.
    pub body: BodyKind,
    /// Paint material name.
    pub paint: &'static str,
    /// Centre of the footprint on the ground, world metres.
    pub position: [f64; 3],
    /// Heading, degrees counter-clockwise from +x (0, 90, 180 or 270).
    pub heading_deg: f64,
    /// Index into `lanes()`.
    pub lane: usize,
}

impl VehiclePose {
    /// The footprint rectangle on the ground (bodies are axis-aligned).
    pub fn footprint(&self) -> Rect {
        let [len, w] = self.body.footprint_m();
        let along_x = (self.heading_deg / 90.0).round() as i64 % 2 == 0;
        let size = if along_x { [len, w] } else { [w, len] };
        Rect::centered([self.position[0], self.position[1]], size)
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
    /// Every other visible vehicle.
    pub vehicles: Vec<VehiclePose>,
    /// Every pedestrian.
    pub pedestrians: Vec<PedestrianPose>,
}

/// Timing constants shared by every lane of a town.
#[derive(Clone, Debug, PartialEq)]
pub struct Schedule {
    /// Slot spacing d, metres (P / d is a whole number).
    pub spacing_m: f64,
    /// Speed v, m/s.
    pub speed_mps: f64,
    /// Phase of x-lanes φ_x, metres; y-lanes use φ_x + d/2.
    pub phase_x_m: f64,
}

impl Schedule {
    /// The schedule of a validated town.
    pub fn new(desc: &TownDesc) -> Self {
        let p = desc.block_size_m;
        let per_block = (p / desc.min_block_size_m()).floor().max(1.0);
        let spacing_m = p / per_block;
        Schedule {
            spacing_m,
            speed_mps: desc.speed_kmh / 3.6,
            phase_x_m: spacing_m / 4.0,
        }
    }
    /// Half-width of the junction window h, metres.
    pub fn window_m(desc: &TownDesc) -> f64 {
        desc.road_width_m() / 2.0 + MAX_VEHICLE_LENGTH_M / 2.0 + JUNCTION_MARGIN_M
    }
}

/// Every lane of the town: x-roads first (by road, direction, lane), then y-roads.
pub fn lanes(l: &Layout) -> Vec<Lane> {
    let mut out = Vec::new();
    for (axis, roads, length_m) in [(Axis::X, l.ny, l.len_x()), (Axis::Y, l.nx, l.len_y())] {
        for road in 0..=roads {
            let c = road as f64 * l.pitch_m;
            for dir in [1.0, -1.0] {
                for k in 0..l.lanes {
                    // Right-hand traffic: the lane lies right of its direction.
                    let right = match axis {
                        Axis::X => -dir,
                        Axis::Y => dir,
                    };
                    let center = c + right * (k as f64 + 0.5) * l.lane_w_m;
                    out.push(Lane {
                        axis,
                        road,
                        dir,
                        k,
                        center,
                        length_m,
                    });
                }
            }
        }
    }
    out
}

/// Where the ego drives: (lane index, slot).
pub fn ego_slot(desc: &TownDesc, seed: u64) -> (usize, u64) {
    let l = Layout::new(desc);
    let lanes = lanes(&l);
    let mut r = Rng::new(&[seed, tag::EGO]);
    // An x-road away from the town edge when there is one.
    let road = if l.ny >= 2 {
        r.int(1, l.ny as u32 - 1) as usize
    } else {
        0
    };
    let dir = if r.chance(0.5) { 1.0 } else { -1.0 };
    let k = r.int(0, l.lanes - 1);
    let lane = lanes
        .iter()
        .position(|ln| ln.axis == Axis::X && ln.road == road && ln.dir == dir && ln.k == k)
        .expect("the ego lane exists");
    let slots = (l.len_x() / Schedule::new(desc).spacing_m).round() as u64;
    (lane, r.next_u64() % slots)
}

fn weighted_body(r: &mut Rng) -> BodyKind {
    let total: f64 = BODY_WEIGHTS.iter().sum();
    let mut u = r.f64() * total;
    for (b, w) in BODIES.iter().zip(BODY_WEIGHTS) {
        if u < w {
            return *b;
        }
        u -= w;
    }
    BODIES[0]
}

/// Every object's pose at `frame` (time frame / fps), in closed form.
pub fn frame_at(desc: &TownDesc, seed: u64, frame: u64) -> TownFrame {
    let l = Layout::new(desc);
    let sched = Schedule::new(desc);
    let t = frame as f64 / desc.fps;
    let (ego_lane, ego_slot_k) = ego_slot(desc, seed);
    let hw = l.road_w_m / 2.0;
    let mut ego = None;
    let mut vehicles = Vec::new();
    let mut next_id = 1u32;
    for (li, lane) in lanes(&l).iter().enumerate() {
        let slots = (lane.length_m / sched.spacing_m).round() as u64;
        let phase = match lane.axis {
            Axis::X => sched.phase_x_m,
            Axis::Y => sched.phase_x_m + sched.spacing_m / 2.0,
        };
        for slot in 0..slots {
            let id = next_id;
            next_id += 1;
            let is_ego = li == ego_lane && slot == ego_slot_k;
            let mut r = Rng::new(&[seed, tag::SLOT, li as u64, slot]);
            let occupied = r.chance(desc.traffic_density);
            if !(occupied || is_ego) {
                continue;
            }
            let body = if is_ego {
                BodyKind::Sedan
            } else {
                weighted_body(&mut r)
            };
            let paint = PAINTS[r.index(PAINTS.len())];
            // Arc position: slot offset plus distance travelled, wrapped.
            let s = phase + sched.speed_mps * t + slot as f64 * sched.spacing_m;
            let along = (lane.dir * s).rem_euclid(lane.length_m);
            let len = body.footprint_m()[0];
            if lane.axis == Axis::Y
                && (along - len / 2.0 < -hw || along + len / 2.0 > lane.length_m + hw)
            {
                continue; // past the outer x-road: off the map until it wraps
            }
            let (position, heading_deg) = match lane.axis {
                Axis::X => (
                    [along, lane.center, 0.0],
                    if lane.dir > 0.0 { 0.0 } else { 180.0 },
                ),
                Axis::Y => (
                    [lane.center, along, 0.0],
                    if lane.dir > 0.0 { 90.0 } else { 270.0 },
                ),
            };
            let pose = VehiclePose {
                id,
                body,
                paint,
                position,
                heading_deg,
                lane: li,
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
        pedestrians: pedestrians(desc, &l, seed, t),
    }
}

/// Walking speed, m/s.
const WALK_MPS: f64 = 1.3;
/// Pedestrian slots per block loop.
const WALK_SLOTS: u64 = 24;
const SHIRTS: &[&str] = &[
    "cloth_blue",
    "cloth_red",
    "cloth_dark",
    "paint_white",
    "paint_yellow",
];

fn pedestrians(desc: &TownDesc, l: &Layout, seed: u64, t: f64) -> Vec<PedestrianPose> {
    let mut out = Vec::new();
    if !l.sidewalks {
        return out;
    }
    let inset = l.road_w_m / 2.0 + l.sidewalk_m / 2.0 + 0.1;
    let side = l.pitch_m - 2.0 * inset;
    let perimeter = 4.0 * side;
    let share = (desc.traffic_density * 0.35).min(1.0);
    for j in 0..l.ny {
        for i in 0..l.nx {
            let (x0, y0) = (i as f64 * l.pitch_m + inset, j as f64 * l.pitch_m + inset);
            for slot in 0..WALK_SLOTS {
                let mut r = Rng::new(&[seed, tag::PEDESTRIAN, i as u64, j as u64, slot]);
                if !r.chance(share) {
                    continue;
                }
                let dir = if r.chance(0.5) { 1.0 } else { -1.0 };
                let shirt = SHIRTS[r.index(SHIRTS.len())];
                let s0 = slot as f64 * perimeter / WALK_SLOTS as f64;
                // Opposite walkers use the two halves of the sidewalk.
                let lane = dir * 0.45;
                let s = (s0 + dir * WALK_MPS * t).rem_euclid(perimeter);
                let (side_k, u) = ((s / side).floor() as u32 % 4, s % side);
                let (x, y, h) = match side_k {
                    0 => (x0 + u, y0 - lane, 0.0),
                    1 => (x0 + side + lane, y0 + u, 90.0),
                    2 => (x0 + side - u, y0 + side + lane, 180.0),
                    _ => (x0 - lane, y0 + side - u, 270.0),
                };
                let heading_deg = if dir > 0.0 { h } else { (h + 180.0) % 360.0 };
                let id = ((j * l.nx + i) as u64 * WALK_SLOTS + slot) as u32;
                out.push(PedestrianPose {
                    id,
                    shirt,
                    position: [x, y, 0.14],
                    heading_deg,
                });
            }
        }
    }
    out
}
