//! Participating media: grey extinction with an RGB single-scattering albedo
//! and a Henyey–Greenstein phase. Densities: homogeneous, and exponential
//! height fog σ_t(z) = σ0·exp(−(z − z0)/H) (Tungsten's `ExponentialMedium`),
//! both optionally bounded to a horizontal slab z ∈ [z_min, z_max].
//!
//! Transmittance and free-flight sampling are closed form for both (the
//! optical depth along a ray is an exponential integral that inverts with a
//! logarithm), so the sampled pdf is exact: pdf(t) = σ_t(t)·Tr(t) for a
//! collision, Tr(t_max) for passing through (pbrt-v4 §11.2; one routine for
//! every medium as `SampleT_maj`). Positions are render space (metres, z up);
//! directions unit; arithmetic inside is f64.

mod equiangular;
mod phase;
mod rain;

pub use equiangular::Equiangular;
pub use phase::{hg, HenyeyGreenstein, PhaseSample};
pub use rain::{
    atlas_fall_speed, marshall_palmer_count, marshall_palmer_lambda, Rain, Streak, StreakHit,
    MAX_DROP_DIAMETER_MM,
};

use glam::{DVec3, Vec3};

/// Koschmieder's constant: ln(1/0.02), the 2 % contrast threshold.
pub const KOSCHMIEDER: f64 = 3.912;

/// Extinction (1/m) giving meteorological visibility `visibility_m` (m > 0):
/// σ_t = 3.912 / V (Koschmieder 1924).
pub fn sigma_t_from_visibility(visibility_m: f64) -> f64 {
    KOSCHMIEDER / visibility_m
}

/// How extinction varies in space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Density {
    /// Constant extinction `sigma_t` (1/m).
    Homogeneous {
        /// Extinction coefficient, 1/m, ≥ 0.
        sigma_t: f64,
    },
    /// σ_t(z) = `sigma0`·exp(−(z − `z0`)/`height_scale`).
    HeightExp {
        /// Extinction at height `z0`, 1/m, ≥ 0.
        sigma0: f64,
        /// Reference height (render-space z, metres).
        z0: f64,
        /// Scale height H, metres, > 0.
        height_scale: f64,
    },
}

/// A medium filling the slab z ∈ [`z_min`, `z_max`] of render space.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Medium {
    /// Extinction field.
    pub density: Density,
    /// Single-scattering albedo σ_s/σ_t per RGB channel, in [0, 1].
    pub albedo: Vec3,
    /// Phase function.
    pub phase: HenyeyGreenstein,
    /// Lower bound of the medium (render-space z, may be −∞).
    pub z_min: f64,
    /// Upper bound of the medium (render-space z, may be +∞).
    pub z_max: f64,
}

/// Result of free-flight sampling along a ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DistanceSample {
    /// Collision distance (metres) when `scattered`, else the segment end.
    pub t: f32,
    /// Whether a collision happened before the segment end.
    pub scattered: bool,
    /// Probability density per metre of the collision at `t` (σ_t·Tr), or the
    /// probability of passing (Tr of the whole segment).
    pub pdf: f32,
    /// Extinction at the collision (1/m), 0 when passing.
    pub sigma_t: f32,
}

/// A ray's stretch o + t·d, t ∈ [0, t_max], of a medium: its part inside
/// the slab and its optical depth, worked out once for both its
/// transmittance and free-flight sampling on it (the same bits as
/// `Medium::tr` and `Medium::sample_distance` each give alone; a segment
/// of a volumetric path wants both, and each costs two or three `exp`).
#[derive(Clone, Copy, Debug)]
pub struct Span {
    o: DVec3,
    d: DVec3,
    t_max: f32,
    /// The part inside the slab, [t_a, t_b] (None: none).
    clip: Option<(f64, f64)>,
    /// Extinction at t_a (exponential height fog; unused otherwise).
    sigma_a: f64,
    /// Optical depth over [0, t_max].
    tau: f64,
}

impl Span {
    /// Optical depth over the stretch.
    pub fn optical_depth(&self) -> f64 {
        self.tau
    }

    /// Transmittance exp(−τ) over the stretch.
    pub fn tr(&self) -> f32 {
        (-self.tau).exp() as f32
    }
}

/// (1 − e^{−x})/x, stable near 0.
fn phi(x: f64) -> f64 {
    if x.abs() < 1e-8 {
        1.0 - 0.5 * x
    } else {
        -(-x).exp_m1() / x
    }
}

impl Medium {
    /// Extinction at `p` (1/m); 0 outside the slab.
    pub fn sigma_t(&self, p: Vec3) -> f64 {
        let z = p.z as f64;
        if z < self.z_min || z > self.z_max {
            return 0.0;
        }
        self.sigma_at_z(z)
    }

    fn sigma_at_z(&self, z: f64) -> f64 {
        match self.density {
            Density::Homogeneous { sigma_t } => sigma_t,
            Density::HeightExp {
                sigma0,
                z0,
                height_scale,
            } => sigma0 * (-(z - z0) / height_scale).exp(),
        }
    }

    /// Ray parameter interval [t_a, t_b] ⊂ [0, t_max] inside the slab (None if empty).
    pub fn clip(&self, o: Vec3, d: Vec3, t_max: f32) -> Option<(f64, f64)> {
        let (oz, dz) = (o.z as f64, d.z as f64);
        let (mut a, mut b) = (0.0f64, t_max as f64);
        if dz == 0.0 {
            if oz < self.z_min || oz > self.z_max {
                return None;
            }
        } else {
            let t0 = (self.z_min - oz) / dz;
            let t1 = (self.z_max - oz) / dz;
            let (lo, hi) = if t0 < t1 { (t0, t1) } else { (t1, t0) };
            a = a.max(lo);
            b = b.min(hi);
        }
        (a < b).then_some((a, b))
    }

    /// Optical depth τ over [t_a, t_b] of a ray inside the slab:
    /// heights exponential ⇒ τ = σ(z_a)·L·(1 − e^{−x})/x with x = d_z·L/H;
    /// with the extinction at t_a (exponential height fog; σ_t otherwise).
    fn tau_clipped(&self, o: DVec3, d: DVec3, t_a: f64, t_b: f64) -> (f64, f64) {
        let len = t_b - t_a;
        match self.density {
            Density::Homogeneous { sigma_t } => {
                if sigma_t == 0.0 {
                    (0.0, sigma_t)
                } else {
                    (sigma_t * len, sigma_t)
                }
            }
            Density::HeightExp { height_scale, .. } => {
                let s_a = self.sigma_at_z(o.z + d.z * t_a);
                if s_a == 0.0 {
                    return (0.0, s_a);
                }
                if len.is_infinite() {
                    // Upward rays see a finite column, level and downward ones do not.
                    let tau = if d.z > 0.0 {
                        s_a * height_scale / d.z
                    } else {
                        f64::INFINITY
                    };
                    return (tau, s_a);
                }
                (s_a * len * phi(d.z * len / height_scale), s_a)
            }
        }
    }

    /// The stretch o + t·d, t ∈ [0, t_max] (t_max may be +∞), of the medium.
    pub fn span(&self, o: Vec3, d: Vec3, t_max: f32) -> Span {
        let (o64, d64) = (o.as_dvec3(), d.as_dvec3());
        let clip = self.clip(o, d, t_max);
        let (tau, sigma_a) = match clip {
            Some((a, b)) => self.tau_clipped(o64, d64, a, b),
            None => (0.0, 0.0),
        };
        Span {
            o: o64,
            d: d64,
            t_max,
            clip,
            sigma_a,
            tau,
        }
    }

    /// Optical depth along o + t·d, t ∈ [0, t_max] (t_max may be +∞).
    pub fn optical_depth(&self, o: Vec3, d: Vec3, t_max: f32) -> f64 {
        self.span(o, d, t_max).optical_depth()
    }

    /// Transmittance exp(−τ) along o + t·d, t ∈ [0, t_max].
    pub fn tr(&self, o: Vec3, d: Vec3, t_max: f32) -> f32 {
        self.span(o, d, t_max).tr()
    }

    /// Whether the medium scatters at all (any albedo channel > 0).
    pub fn scatters(&self) -> bool {
        self.albedo.max_element() > 0.0
    }

    /// Free-flight sampling on [0, t_max]: a collision at τ(t) = −ln(1 − u),
    /// by inverting the optical depth in closed form.
    pub fn sample_distance(&self, o: Vec3, d: Vec3, t_max: f32, u: f32) -> DistanceSample {
        self.sample_distance_on(&self.span(o, d, t_max), u)
    }

    /// [`Medium::sample_distance`] on the stretch `span` of this medium.
    pub fn sample_distance_on(&self, span: &Span, u: f32) -> DistanceSample {
        let pass = |tau: f64| DistanceSample {
            t: span.t_max,
            scattered: false,
            pdf: (-tau).exp() as f32,
            sigma_t: 0.0,
        };
        let Some((a, b)) = span.clip else {
            return pass(0.0);
        };
        let (o64, d64) = (span.o, span.d);
        let target = -(-(u as f64)).ln_1p();
        let total = span.tau;
        if target >= total {
            return pass(total);
        }
        let s = match self.density {
            Density::Homogeneous { sigma_t } => target / sigma_t,
            Density::HeightExp { height_scale, .. } => {
                // τ(s) = σ_a·(H/d_z)(1 − e^{−d_z s/H})  ⇒  s = −(H/d_z)·ln(1 − τ d_z/(σ_a H)).
                let s_a = span.sigma_a;
                let x = target * d64.z / (s_a * height_scale);
                if x.abs() < 1e-9 {
                    target / s_a * (1.0 + 0.5 * x)
                } else {
                    -(height_scale / d64.z) * (-x).ln_1p()
                }
            }
        };
        let t = (a + s).min(b);
        let sigma_t = self.sigma_at_z(o64.z + d64.z * t);
        DistanceSample {
            t: t as f32,
            scattered: true,
            // pdf(t) = σ_t(t)·Tr(0, t) and τ(0, t) = target by construction.
            pdf: (sigma_t * (-target).exp()) as f32,
            sigma_t: sigma_t as f32,
        }
    }

    /// Density per metre that `sample_distance` collides at `t` < t_max.
    pub fn distance_pdf(&self, o: Vec3, d: Vec3, t: f32) -> f32 {
        let p = o + d * t;
        (self.sigma_t(p) * (-self.optical_depth(o, d, t)).exp()) as f32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fog() -> Medium {
        Medium {
            density: Density::HeightExp {
                sigma0: 0.05,
                z0: 1.0,
                height_scale: 20.0,
            },
            albedo: Vec3::splat(0.99),
            phase: HenyeyGreenstein { g: 0.85 },
            z_min: f64::NEG_INFINITY,
            z_max: f64::INFINITY,
        }
    }

    #[test]
    fn koschmieder_visibility_gives_two_percent_contrast() {
        let s = sigma_t_from_visibility(100.0);
        assert!(((-s * 100.0).exp() - 0.02).abs() < 1e-4);
    }

    #[test]
    fn height_fog_upward_infinite_column_is_sigma_h_over_dz() {
        let m = fog();
        let d = Vec3::new(0.6, 0.0, 0.8);
        let tau = m.optical_depth(Vec3::new(0.0, 0.0, 1.0), d, f32::INFINITY);
        assert!((tau - 0.05 * 20.0 / 0.8).abs() < 1e-6, "{tau}");
    }

    #[test]
    fn a_span_gives_the_closed_form_tr_and_draws_that_invert_it() {
        // Height fog from z = 1 (σ = 0.05) up a 10 m stretch at d_z = 0.8:
        // τ = 0.05·(H/d_z)·(1 − e^{−d_z·L/H}). A draw on the span with u
        // collides where the optical depth from the origin is −ln(1 − u),
        // with density σ_t(t)·(1 − u); past τ it passes with pdf Tr.
        let m = fog();
        let (o, d, len) = (Vec3::new(0.0, 0.0, 1.0), Vec3::new(0.6, 0.0, 0.8), 10.0);
        let span = m.span(o, d, len);
        let tau = 0.05 * (20.0 / 0.8) * (1.0 - (-0.8f64 * 10.0 / 20.0).exp());
        assert!(
            (span.optical_depth() - tau).abs() < 1e-6 * tau,
            "{}",
            span.optical_depth()
        );
        assert_eq!(span.tr().to_bits(), m.tr(o, d, len).to_bits());
        assert!((span.tr() as f64 - (-tau).exp()).abs() < 1e-6);
        let mut collided = 0;
        for k in 0..64 {
            let u = (k as f32 + 0.5) / 64.0;
            let ds = m.sample_distance_on(&span, u);
            let target = -(1.0 - u as f64).ln();
            if target >= tau {
                assert!(!ds.scattered && ds.t == len, "u {u}: {ds:?}");
                assert!((ds.pdf - span.tr()).abs() < 1e-6, "u {u}: {ds:?}");
                continue;
            }
            collided += 1;
            assert!(ds.scattered, "u {u}");
            let reached = m.optical_depth(o, d, ds.t);
            assert!(
                (reached - target).abs() < 1e-5,
                "u {u}: τ {reached} vs {target}"
            );
            let want = m.sigma_t(o + d * ds.t) * (1.0 - u as f64);
            assert!(
                (ds.pdf as f64 - want).abs() < 1e-5 * want,
                "u {u}: {ds:?} vs {want}"
            );
        }
        assert!(collided > 10 && collided < 64, "{collided}");
    }

    #[test]
    fn slab_clip_limits_homogeneous_depth() {
        let m = Medium {
            density: Density::Homogeneous { sigma_t: 0.5 },
            z_min: 0.0,
            z_max: 2.0,
            ..fog()
        };
        let d = Vec3::new(0.0, 0.6, 0.8);
        let tau = m.optical_depth(Vec3::new(0.0, 0.0, -1.0), d, f32::INFINITY);
        assert!((tau - 0.5 * 2.0 / 0.8).abs() < 1e-6, "{tau}");
    }
}
