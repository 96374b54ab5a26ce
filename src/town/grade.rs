//! Road grades: a smooth, seeded ground-elevation field under the whole town
//! (`road_grade_m`, `road_grade_wavelength_m`), so roads climb and fall
//! as a driver sees them on a highway.
//!
//! h(x, y) = A/2 · [sin(k·u + φ₀) + sin(k·v + φ₁)], k = 2π/λ, with (u, v)
//! the world (x, y) turned by a seeded angle θ. Its gradient is
//! A·k/2 · (cos(k·u + φ₀), cos(k·v + φ₁)) in the turned frame, so the
//! steepest grade anywhere is at most A·k/√2 (`max_grade`), which the
//! description keeps ≤ `MAX_GRADE`. World frame z up, metres. Everything
//! standing on the ground follows h (`drape`); vehicles take z from h and
//! pitch and roll from ∇h (`Grade::pose`).

use glam::DVec3;

use super::desc::TownDesc;
use super::rng::Rng;

/// Steepest grade the field may reach (6 %, a steep highway).
pub const MAX_GRADE: f64 = 0.06;
/// Rng stream tag of the grade field (distinct from `rng::tag` and terrain).
const GRADE_TAG: u64 = 0x06ad_e5ee;

/// The ground-elevation field of one (town, seed); evaluate with `height_m`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grade {
    /// Amplitude A, metres (h ∈ [−A, A]).
    amplitude_m: f64,
    /// Wave number k = 2π/λ, rad/m.
    k: f64,
    /// (cos θ, sin θ) of the turned frame.
    dir: [f64; 2],
    /// Phases φ₀, φ₁, radians.
    phase: [f64; 2],
}

/// Bound on the steepest grade of a field of amplitude `amplitude_m` and
/// wavelength `wavelength_m`: A·k/√2 (dimensionless rise per run).
pub fn max_grade(amplitude_m: f64, wavelength_m: f64) -> f64 {
    amplitude_m * std::f64::consts::TAU / wavelength_m / std::f64::consts::SQRT_2
}

/// A vehicle's placement on the ground: height, nose-up pitch and
/// left-side-up roll, so its local z is the surface normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GroundPose {
    /// Ground height at the footprint centre, metres.
    pub z_m: f64,
    /// Nose-up pitch, degrees (atan of the grade along the heading).
    pub pitch_deg: f64,
    /// Roll, degrees, > 0 when the left side is higher.
    pub roll_deg: f64,
}

impl Grade {
    /// The field of a (validated) town and seed; `None` when the town is
    /// level (`road_grade_m = 0`).
    pub fn new(desc: &TownDesc, seed: u64) -> Option<Self> {
        if desc.road_grade_m <= 0.0 {
            return None;
        }
        let mut r = Rng::new(&[seed, GRADE_TAG]);
        let theta = r.range(0.0, std::f64::consts::TAU);
        Some(Grade {
            amplitude_m: desc.road_grade_m,
            k: std::f64::consts::TAU / desc.road_grade_wavelength_m,
            dir: [theta.cos(), theta.sin()],
            phase: [
                r.range(0.0, std::f64::consts::TAU),
                r.range(0.0, std::f64::consts::TAU),
            ],
        })
    }

    /// The steepest grade this field can reach (`max_grade`).
    pub fn max_grade(&self) -> f64 {
        self.amplitude_m * self.k / std::f64::consts::SQRT_2
    }

    /// Arguments k·u + φ₀ and k·v + φ₁ at world (x, y).
    fn args(&self, x: f64, y: f64) -> [f64; 2] {
        let [c, s] = self.dir;
        let (u, v) = (c * x + s * y, -s * x + c * y);
        [self.k * u + self.phase[0], self.k * v + self.phase[1]]
    }

    /// Ground height at world (x, y), metres, in [−A, A].
    pub fn height_m(&self, x: f64, y: f64) -> f64 {
        let [a, b] = self.args(x, y);
        self.amplitude_m / 2.0 * (a.sin() + b.sin())
    }

    /// ∇h at world (x, y): (∂h/∂x, ∂h/∂y), dimensionless.
    pub fn gradient(&self, x: f64, y: f64) -> [f64; 2] {
        let [a, b] = self.args(x, y);
        let f = self.amplitude_m * self.k / 2.0;
        let (du, dv) = (f * a.cos(), f * b.cos());
        // Back from the turned frame: ∂/∂x = c·∂/∂u − s·∂/∂v, etc.
        let [c, s] = self.dir;
        [c * du - s * dv, s * du + c * dv]
    }

    /// Unit surface normal at world (x, y).
    pub fn normal(&self, x: f64, y: f64) -> DVec3 {
        let [gx, gy] = self.gradient(x, y);
        DVec3::new(-gx, -gy, 1.0).normalize()
    }

    /// Placement of a body at (x, y) heading `heading_deg` (from +x): with
    /// g_f, g_s the grades along the heading and to its left, pitch =
    /// atan(g_f) and roll = asin(g_s / √(1 + g_f² + g_s²)), which makes
    /// Rz(heading)·Ry(−pitch)·Rx(roll) carry local z onto the normal.
    pub fn pose(&self, x: f64, y: f64, heading_deg: f64) -> GroundPose {
        let [gx, gy] = self.gradient(x, y);
        let h = heading_deg.to_radians();
        let (gf, gs) = (gx * h.cos() + gy * h.sin(), -gx * h.sin() + gy * h.cos());
        let n = (1.0 + gf * gf + gs * gs).sqrt();
        GroundPose {
            z_m: self.height_m(x, y),
            pitch_deg: gf.atan().to_degrees(),
            roll_deg: (gs / n).asin().to_degrees(),
        }
    }
}

/// `rotate_deg` of a body with heading, nose-up pitch and roll (degrees)
/// in the scene's Rz·Ry·Rx order (`scene::transform`).
pub fn body_rotation_deg(heading_deg: f64, pitch_deg: f64, roll_deg: f64) -> [f64; 3] {
    [roll_deg, -pitch_deg, heading_deg]
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DMat3;

    fn field() -> Grade {
        Grade {
            amplitude_m: 8.0,
            k: std::f64::consts::TAU / 800.0,
            dir: [0.6, 0.8],
            phase: [0.3, 1.9],
        }
    }

    #[test]
    fn gradient_matches_central_differences_and_stays_under_the_bound() {
        let g = field();
        let mut steepest: f64 = 0.0;
        for i in 0..40 {
            for j in 0..40 {
                let (x, y) = (i as f64 * 37.0 - 300.0, j as f64 * 23.0 - 100.0);
                let e = 1e-3;
                let dx = (g.height_m(x + e, y) - g.height_m(x - e, y)) / (2.0 * e);
                let dy = (g.height_m(x, y + e) - g.height_m(x, y - e)) / (2.0 * e);
                let [gx, gy] = g.gradient(x, y);
                assert!((dx - gx).abs() < 1e-8 && (dy - gy).abs() < 1e-8);
                steepest = steepest.max(gx.hypot(gy));
                assert!(g.height_m(x, y).abs() <= 8.0);
            }
        }
        assert!(steepest <= g.max_grade() + 1e-12);
        // A dense scan gets close to the bound A·k/√2 ≈ 4.44 %.
        assert!(steepest > 0.9 * g.max_grade(), "{steepest}");
        assert!((max_grade(8.0, 800.0) - g.max_grade()).abs() < 1e-15);
    }

    #[test]
    fn pose_carries_local_z_onto_the_normal_and_x_along_the_slope() {
        let g = field();
        for (x, y, head) in [
            (10.0, 20.0, 0.0),
            (-140.0, 333.0, 37.0),
            (512.0, 3.0, 250.0),
        ] {
            let p = g.pose(x, y, head);
            let [rx, ry, rz] =
                body_rotation_deg(head, p.pitch_deg, p.roll_deg).map(f64::to_radians);
            let m = DMat3::from_rotation_z(rz)
                * DMat3::from_rotation_y(ry)
                * DMat3::from_rotation_x(rx);
            assert!((m.z_axis - g.normal(x, y)).length() < 1e-12, "{x} {y}");
            // The forward axis climbs at the grade along the heading.
            let f = m.x_axis;
            let [gx, gy] = g.gradient(x, y);
            let h = head.to_radians();
            let along = gx * h.cos() + gy * h.sin();
            assert!((f.z / f.truncate().length() - along).abs() < 1e-12);
            assert!((p.z_m - g.height_m(x, y)).abs() == 0.0);
        }
    }
}
