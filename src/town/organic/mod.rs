//! Organic towns (`road_style = "organic"`): the grid town is generated as
//! usual, then bent by a smooth, seeded planar warp W so its streets curve.
//!
//! W is two shears: first every point moves along y by a(x), then along x
//! by b(y′) of its new y′:
//!
//!   y′ = y + a(x),  x′ = x + b(y′),
//!
//! with a and b each a sum of two seeded sines (wavelengths 190–520 m). An
//! x-road (a line y = c) becomes the curve y′ = c + a(x); a y-road bends
//! by b. The Jacobian J = [[1 + a′b′, b′], [a′, 1]] has det J = 1 (areas
//! keep), W is a bijection with a closed-form inverse, and with |a′|, |b′| ≤
//! s = `MAX_SHEAR` every street keeps its width within −3.3 % … +1.1 %
//! (width × length is kept and a unit step along a road stretches by
//! |J·t| ∈ [1/√(1 + s²), √((1 + s²)² + s²)]), lengths along streets change
//! by the same factors and headings turn by at most atan(s / (1 − s²)) ≈ 8.7°. A
//! street's curvature is about |a″| or |b″| ≤ Σ amplitude · k² (a radius
//! ≥ 300 m). Off the street directions J is a rotation times a stretch of
//! at most ≈ 1 + s (1.16, where both shears peak together, along the
//! diagonals): rigid bodies (buildings, furniture) turn by J's rotation. World frame z up, metres;
//! the warp is planar (z never changes), so it commutes with the grade
//! (`drape`), which is applied after it.
//!
//! Static objects bend in `bend`; vehicle and pedestrian poses (and with
//! the ego the camera rig) go through `Warp::vehicle` / `Warp::pedestrian`
//! in `traffic::frame_at`.

pub mod bend;

use super::desc::{RoadStyle, TownDesc};
use super::rng::Rng;
use super::traffic::{PedestrianPose, TownFrame, VehiclePose};

/// Largest shear |a′|, |b′| of the warp (dimensionless).
pub const MAX_SHEAR: f64 = 0.15;
/// Rng stream tag of the warp (distinct from `rng::tag`, grade and terrain).
const WARP_TAG: u64 = 0x0e6a_171c;
/// Share of `MAX_SHEAR` given to the long wave of each shear (the rest
/// to the short one).
const LONG_SHARE: f64 = 0.65;

/// One sine A·sin(k·t + φ).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Wave {
    amp_m: f64,
    k: f64,
    phase: f64,
}

/// A sum of sines with its value and slope.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Shear([Wave; 2]);

impl Shear {
    fn seeded(r: &mut Rng) -> Shear {
        let mut wave = |lo: f64, hi: f64, slope: f64| {
            let k = std::f64::consts::TAU / r.range(lo, hi);
            Wave {
                amp_m: slope / k,
                k,
                phase: r.range(0.0, std::f64::consts::TAU),
            }
        };
        Shear([
            wave(380.0, 520.0, LONG_SHARE * MAX_SHEAR),
            wave(190.0, 260.0, (1.0 - LONG_SHARE) * MAX_SHEAR),
        ])
    }
    fn value(&self, t: f64) -> f64 {
        self.0
            .iter()
            .map(|w| w.amp_m * (w.k * t + w.phase).sin())
            .sum()
    }
    fn slope(&self, t: f64) -> f64 {
        self.0
            .iter()
            .map(|w| w.amp_m * w.k * (w.k * t + w.phase).cos())
            .sum()
    }
    /// Bound on |slope|: Σ A·k.
    fn max_slope(&self) -> f64 {
        self.0.iter().map(|w| w.amp_m * w.k).sum()
    }
    /// Bound on |second derivative|: Σ A·k².
    fn max_bend(&self) -> f64 {
        self.0.iter().map(|w| w.amp_m * w.k * w.k).sum()
    }
}

/// The warp of one organic (town, seed); see the module header.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Warp {
    /// a(x): the shift along y.
    a: Shear,
    /// b(y′): the shift along x.
    b: Shear,
}

impl Warp {
    /// The warp of a town and seed; `None` unless `road_style = "organic"`.
    pub fn new(desc: &TownDesc, seed: u64) -> Option<Warp> {
        if desc.road_style != RoadStyle::Organic {
            return None;
        }
        let mut r = Rng::new(&[seed, WARP_TAG]);
        Some(Warp {
            a: Shear::seeded(&mut r),
            b: Shear::seeded(&mut r),
        })
    }

    /// W(x, y), metres.
    pub fn map(&self, p: [f64; 2]) -> [f64; 2] {
        let y = p[1] + self.a.value(p[0]);
        [p[0] + self.b.value(y), y]
    }

    /// W⁻¹(x′, y′), exact: y′ is kept by the second shear.
    pub fn unmap(&self, q: [f64; 2]) -> [f64; 2] {
        let x = q[0] - self.b.value(q[1]);
        [x, q[1] - self.a.value(x)]
    }

    /// The Jacobian of W at (x, y), rows (∂x′, ∂y′) over columns (∂x, ∂y).
    pub fn jacobian(&self, p: [f64; 2]) -> [[f64; 2]; 2] {
        let da = self.a.slope(p[0]);
        let db = self.b.slope(p[1] + self.a.value(p[0]));
        [[1.0 + da * db, db], [da, 1.0]]
    }

    /// Largest |a′|, |b′| of this warp (≤ `MAX_SHEAR`).
    pub fn max_shear(&self) -> f64 {
        self.a.max_slope().max(self.b.max_slope())
    }

    /// Bound on |a″| and |b″|, 1/m: a bent street's curvature to first
    /// order in the shear.
    pub fn max_bend(&self) -> f64 {
        self.a.max_bend().max(self.b.max_bend())
    }

    /// Where W takes the direction `heading_deg` (from +x) at `p`, degrees.
    pub fn heading_deg(&self, p: [f64; 2], heading_deg: f64) -> f64 {
        let [[j00, j01], [j10, j11]] = self.jacobian(p);
        let (s, c) = heading_deg.to_radians().sin_cos();
        let t = [j00 * c + j01 * s, j10 * c + j11 * s];
        heading_deg + turn_deg(heading_deg, t[1].atan2(t[0]).to_degrees())
    }

    /// The rotation of W's polar decomposition at `p` (J = R·S, S
    /// symmetric positive), degrees: how a rigid object there turns.
    pub fn rotation_deg(&self, p: [f64; 2]) -> f64 {
        let [[j00, j01], [j10, j11]] = self.jacobian(p);
        (j10 - j01).atan2(j00 + j11).to_degrees()
    }

    /// A vehicle pose moved to W(p), its heading turned with the road.
    pub fn vehicle(&self, mut v: VehiclePose) -> VehiclePose {
        let p = [v.position[0], v.position[1]];
        v.heading_deg = self.heading_deg(p, v.heading_deg);
        [v.position[0], v.position[1]] = self.map(p);
        v
    }

    /// A pedestrian pose moved to W(p), its heading turned with the street.
    pub fn pedestrian(&self, mut w: PedestrianPose) -> PedestrianPose {
        let p = [w.position[0], w.position[1]];
        w.heading_deg = self.heading_deg(p, w.heading_deg);
        [w.position[0], w.position[1]] = self.map(p);
        w
    }

    /// A frame's poses carried back into the level grid's plane (W⁻¹, for
    /// checks against the `Layout`); headings turn back through J⁻¹.
    pub fn unwarp_frame(&self, f: &TownFrame) -> TownFrame {
        let back = |mut v: VehiclePose| {
            let p = self.unmap([v.position[0], v.position[1]]);
            v.heading_deg = self.heading_back_deg(p, v.heading_deg);
            [v.position[0], v.position[1]] = p;
            v
        };
        TownFrame {
            ego: back(f.ego.clone()),
            vehicles: f.vehicles.iter().cloned().map(back).collect(),
            pedestrians: f
                .pedestrians
                .iter()
                .cloned()
                .map(|mut w| {
                    let p = self.unmap([w.position[0], w.position[1]]);
                    w.heading_deg = self.heading_back_deg(p, w.heading_deg);
                    [w.position[0], w.position[1]] = p;
                    w
                })
                .collect(),
            ..f.clone()
        }
    }

    /// The heading at level point `p` that W turns into `heading_deg`
    /// (J⁻¹ = [[1, −b′], [−a′, 1 + a′b′]] since det J = 1).
    fn heading_back_deg(&self, p: [f64; 2], heading_deg: f64) -> f64 {
        let [[j00, j01], [j10, j11]] = self.jacobian(p);
        let (s, c) = heading_deg.to_radians().sin_cos();
        let t = [j11 * c - j01 * s, -j10 * c + j00 * s];
        heading_deg + turn_deg(heading_deg, t[1].atan2(t[0]).to_degrees())
    }
}

/// The signed turn from `from_deg` to the direction `to_deg`, in (−180, 180]
/// (keeps headings continuous: a warped heading stays within 9° of the
/// level one).
fn turn_deg(from_deg: f64, to_deg: f64) -> f64 {
    let d = (to_deg - from_deg).rem_euclid(360.0);
    if d > 180.0 {
        d - 360.0
    } else {
        d
    }
}

#[cfg(test)]
mod tests;
