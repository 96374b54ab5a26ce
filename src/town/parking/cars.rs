//! The parked cars: each bay holds a car with probability
//! `parking_density`, drawn from the traffic's body mix (the cars whose
//! footprint fits the bay) and paint mix, parked parallel with the
//! traffic on its side, near its kerb, with small seeded offsets and a
//! slight turn. Static objects: the grown vehicle prefabs as instances
//! (panels in the drawn paint, parts, a registration and the lamps with
//! their emitters swapped for unlit lenses), one instance id per car.

use crate::scene::desc::ObjectDesc;

use super::super::materials::draw_paint;
use super::super::organic::Warp;
use super::super::parts::{instance, Label};
use super::super::rng::Rng;
use super::super::vehicles::{plates::PLATE_VARIANTS, BodyKind, BODIES, BODY_WEIGHTS};
use super::{Bay, BAY_LEN_M};

/// Stream word of the parked cars (apart from `rng::tag`'s).
const PARKED: u64 = 0x5041_524b;
/// Largest turn off the kerb line, degrees.
const MAX_TURN_DEG: f64 = 0.8;
/// Gap between a car's footprint and the bay's kerb, metres.
const KERB_GAP_M: (f64, f64) = (0.03, 0.25);
/// Gap kept at each bay end, metres.
const END_GAP_M: f64 = 0.2;
/// The lamps' emitters, and the unlit lenses a parked car shows instead
/// (clear glass over the head-lamp reflector, red tail-lamp lenses).
const UNLIT: [(&str, &str); 2] = [
    ("headlight_emit", "car_glass"),
    ("taillight_emit", "lamp_red"),
];

/// One parked car: its body type, paint and pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParkedCar {
    /// Body type.
    pub body: BodyKind,
    /// Paint material.
    pub paint: &'static str,
    /// Footprint centre on the ground, world metres.
    pub at: [f64; 3],
    /// Heading, degrees.
    pub heading_deg: f64,
}

impl ParkedCar {
    /// The footprint's four corners in plan, world metres.
    pub fn corners(&self) -> [[f64; 2]; 4] {
        let [len, w] = self.body.footprint_m();
        let (s, c) = self.heading_deg.to_radians().sin_cos();
        [(1.0, 1.0), (1.0, -1.0), (-1.0, -1.0), (-1.0, 1.0)].map(|(a, b)| {
            let (x, y) = (a * len / 2.0, b * w / 2.0);
            [self.at[0] + c * x - s * y, self.at[1] + s * x + c * y]
        })
    }
}

/// Half extents (along, across) of a footprint `[len, w]` turned by up to
/// `MAX_TURN_DEG`.
fn turned_half([len, w]: [f64; 2]) -> (f64, f64) {
    let (s, c) = MAX_TURN_DEG.to_radians().sin_cos();
    ((c * len + s * w) / 2.0, (s * len + c * w) / 2.0)
}

/// The body types a bay `depth` deep takes (four-wheeled cars whose
/// turned footprint fits with the smallest kerb gap), with their weights.
pub fn fitting(depth: f64) -> Vec<(BodyKind, f64)> {
    BODIES
        .iter()
        .zip(BODY_WEIGHTS)
        .filter(|(b, _)| b.class() == "car" && b.seat().is_none())
        .filter(|(b, _)| {
            let (h_along, h_across) = turned_half(b.footprint_m());
            2.0 * h_across + KERB_GAP_M.0 <= depth && 2.0 * h_along + 2.0 * END_GAP_M <= BAY_LEN_M
        })
        .map(|(&b, w)| (b, w))
        .collect()
}

/// The car parked in `bay` (bay number `k` of the town) under `seed` with
/// fill `density`, if any.
pub fn parked_in(bay: &Bay, k: usize, seed: u64, density: f64) -> Option<ParkedCar> {
    let mut r = Rng::new(&[seed, PARKED, k as u64]);
    if !r.chance(density) {
        return None;
    }
    let kinds = fitting(bay.depth);
    let total: f64 = kinds.iter().map(|(_, w)| w).sum();
    let mut u = r.f64() * total;
    let mut body = kinds.last()?.0;
    for &(b, w) in &kinds {
        if u < w {
            body = b;
            break;
        }
        u -= w;
    }
    let paint = draw_paint(r.f64());
    let (h_along, h_across) = turned_half(body.footprint_m());
    let slack_along = (BAY_LEN_M / 2.0 - END_GAP_M - h_along).max(0.0);
    let along = 0.5 * (bay.along.0 + bay.along.1) + r.range(-slack_along, slack_along);
    let gap_hi = KERB_GAP_M.1.min(bay.depth - 2.0 * h_across);
    let gap = r.range(KERB_GAP_M.0, gap_hi.max(KERB_GAP_M.0));
    let off = bay.hw + bay.depth - gap - h_across;
    let turn = r.range(-MAX_TURN_DEG, MAX_TURN_DEG);
    let [x, y] = bay.world(along, off);
    Some(ParkedCar {
        body,
        paint,
        at: [x, y, 0.0],
        heading_deg: bay.heading_deg() + turn,
    })
}

/// Every parked car of the `bays` (numbered in order) under `seed`.
pub fn cars_in(bays: &[Bay], seed: u64, density: f64) -> Vec<ParkedCar> {
    bays.iter()
        .enumerate()
        .filter_map(|(k, b)| parked_in(b, k, seed, density))
        .collect()
}

/// The parked cars of `bays` as static instances, instance ids from
/// `first_id` up to (not including) `end_id` (cars past it are left out);
/// in an organic town moved by its `warp` as the vehicles are (to W(p),
/// the heading turned by W's Jacobian, so the car follows its kerb).
pub fn parked_cars(
    bays: &[Bay],
    seed: u64,
    density: f64,
    (first_id, end_id): (u32, u32),
    warp: Option<&Warp>,
) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    for (car, id) in cars_in(bays, seed, density).iter().zip(first_id..end_id) {
        let l = Label {
            class: car.body.class(),
            instance: id as u16,
        };
        let (mut at, mut h) = (car.at, car.heading_deg);
        if let Some(w) = warp {
            h = w.heading_deg([at[0], at[1]], h);
            [at[0], at[1]] = w.map([at[0], at[1]]);
        }
        out.push(instance(
            car.body.prefab(),
            at,
            h,
            &[("car_paint", car.paint)],
            l,
        ));
        out.push(instance(&car.body.parts_prefab(), at, h, &[], l));
        out.push(instance(&car.body.lamps_prefab(), at, h, &UNLIT, l));
        if let Some(plate) = car.body.plate_prefab(id % PLATE_VARIANTS) {
            out.push(instance(&plate, at, h, &[], l));
        }
    }
    out
}
