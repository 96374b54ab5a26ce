//! Wet surfaces and puddles at shading time (`[wetness]`, weathers humid and
//! storm). Shading only: geometry, depth and disparity never change.
//!
//! Exposed up-facing surfaces (normal facing the viewer with z > 0.7) of the
//! classes road, lane marking, sidewalk and terrain become a darkened base
//! under a water film (`Bsdf::Coated`, η = 1.33). The darkening is Lekner &
//! Dorf 1988 ("Why some things are darker when wet", Appl. Opt. 27(7)):
//! light scattered by the wet substrate is returned to it by internal
//! reflection at the water–air interface (diffuse internal reflectance
//! R_i = 1 − (1 − R̄_e)/n²), so A_wet = A (1 − R_i) / (1 − A R_i): dark
//! surfaces darken most, a white one not at all. Puddles: where a smooth,
//! world-space (x, y) noise exceeds its (1 − puddle_cover) quantile, road and
//! sidewalk become smooth water over the soaked base, and the GT mask's mirror
//! bit is set. The mask is a function of world position only, so every view of
//! a frame (and every frame) agrees.

use glam::{DVec3, Vec3};
use shaders_cpu::bsdf::fresnel::fr_dielectric;
use shaders_cpu::bsdf::{Bsdf, CoatBase, Facet};

use super::{mask_bits, Material};
use crate::geometry::SurfaceInteraction;
use crate::sampler::hash_words;
use crate::scene::desc::semantic;
use crate::scene::desc::WetnessDesc;

/// Index of refraction of water.
pub const WATER_IOR: f32 = 1.33;
/// Surfaces whose viewer-facing normal has z above this count as exposed.
pub const UP_FACING_Z: f32 = 0.7;
/// Semantic ids that get wet: road, road line, sidewalk, terrain.
const WET_CLASSES: [u8; 4] = [
    semantic::ROAD,
    semantic::ROAD_LINE,
    semantic::SIDEWALK,
    semantic::TERRAIN,
];
/// Semantic ids that can hold puddles: road, sidewalk.
const PUDDLE_CLASSES: [u8; 2] = [semantic::ROAD, semantic::SIDEWALK];
/// Stream tag of the puddle noise.
const PUDDLE_TAG: u64 = 0x7075_6464_6c65;

/// The built wetness of one frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wetness {
    /// Wetness in [0, 1].
    pub wetness: f32,
    /// Target fraction of road/sidewalk under puddles, [0, 1].
    pub puddle_cover: f32,
    /// Puddle feature size, metres.
    pub scale_m: f64,
    /// Seed of the puddle noise.
    pub seed: u64,
    /// Noise level above which a point is a puddle (+inf: no puddles).
    pub threshold: f32,
    /// World position of render-space origin (the frame's render origin).
    pub origin_world: DVec3,
    /// Diffuse internal reflectance R_i of the water–air interface.
    pub r_internal: f32,
}

impl Wetness {
    /// Builds the frame's wetness; render positions are `p_world − origin_world`.
    pub fn new(desc: &WetnessDesc, origin_world: DVec3) -> Self {
        let mut w = Wetness {
            wetness: desc.wetness as f32,
            puddle_cover: desc.puddle_cover as f32,
            scale_m: desc.puddle_scale_m,
            seed: desc.seed,
            threshold: f32::INFINITY,
            origin_world,
            r_internal: internal_reflectance(WATER_IOR),
        };
        w.threshold = w.noise_quantile(1.0 - desc.puddle_cover);
        w
    }

    /// Smooth noise in [0, 1] at world (x, y): two octaves of value noise
    /// with quintic interpolation (Perlin 2002), features ~`scale_m` wide.
    pub fn puddle_noise(&self, x_world: f64, y_world: f64) -> f32 {
        let (x, y) = (x_world / self.scale_m, y_world / self.scale_m);
        let a = value_noise(self.seed, 0, x, y);
        let b = value_noise(self.seed, 1, 2.3 * x + 17.1, 2.3 * y - 5.7);
        (0.65 * a + 0.35 * b) as f32
    }

    /// Whether world (x, y) lies in a puddle (road and sidewalk only).
    pub fn is_puddle_world(&self, x_world: f64, y_world: f64) -> bool {
        self.puddle_cover > 0.0 && self.puddle_noise(x_world, y_world) >= self.threshold
    }

    /// The noise level exceeded by a fraction 1 − q of the plane, estimated
    /// once from a fixed 96×96 lattice of points spread over ~40 features.
    fn noise_quantile(&self, q: f64) -> f32 {
        if q >= 1.0 {
            return f32::INFINITY;
        }
        let n = 96;
        let step = 0.43 * self.scale_m;
        let mut v: Vec<f32> = (0..n * n)
            .map(|k| self.puddle_noise((k % n) as f64 * step, (k / n) as f64 * step))
            .collect();
        v.sort_by(f32::total_cmp);
        if q <= 0.0 {
            return f32::NEG_INFINITY;
        }
        v[((q * v.len() as f64) as usize).min(v.len() - 1)]
    }

    /// Lekner–Dorf wet albedo, blended with the dry one by `wetness`.
    pub fn wet_albedo(&self, albedo: Vec3, wetness: f32) -> Vec3 {
        let ri = self.r_internal;
        let soaked = albedo * (1.0 - ri) / (Vec3::ONE - albedo * ri);
        albedo.lerp(soaked, wetness)
    }

    /// GGX alpha of the water film: rough when damp, near-smooth when soaked
    /// (perceptual roughness 0.6 → 0.1).
    pub fn film_alpha(&self) -> f32 {
        let r = 0.6 - 0.5 * self.wetness;
        r * r
    }
}

/// R_i = 1 − (1 − R̄_e)/n², with R̄_e = ∫ 2 F(μ) μ dμ the cosine-weighted
/// external reflectance (Lekner & Dorf 1988, eq. 2; midpoint rule).
pub fn internal_reflectance(eta: f32) -> f32 {
    let n = 2000;
    let r_e: f64 = (0..n)
        .map(|i| {
            let mu = (i as f64 + 0.5) / n as f64;
            2.0 * fr_dielectric(mu as f32, eta) as f64 * mu / n as f64
        })
        .sum();
    (1.0 - (1.0 - r_e) / (eta as f64 * eta as f64)) as f32
}

/// Lattice value noise in [0, 1] (octave `o`), hashed per integer cell corner.
fn value_noise(seed: u64, o: u64, x: f64, y: f64) -> f64 {
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let corner = |i: f64, j: f64| {
        let h = hash_words(&[seed, PUDDLE_TAG, o, i as i64 as u64, j as i64 as u64]);
        (h >> 11) as f64 / (1u64 << 53) as f64
    };
    // Quintic fade: C2-continuous across cell edges.
    let fade = |t: f64| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
    let (sx, sy) = (fade(fx), fade(fy));
    let lerp = |a: f64, b: f64, t: f64| a + (b - a) * t;
    let bottom = lerp(corner(x0, y0), corner(x0 + 1.0, y0), sx);
    let top = lerp(corner(x0, y0 + 1.0), corner(x0 + 1.0, y0 + 1.0), sx);
    lerp(bottom, top, sy)
}

/// What wetness does at one hit.
enum WetState {
    Dry,
    Wet,
    Puddle,
}

fn state(w: &Wetness, si: &SurfaceInteraction, wo: Vec3) -> WetState {
    if !WET_CLASSES.contains(&si.semantic) {
        return WetState::Dry;
    }
    let n = if si.n_geo.dot(wo) < 0.0 {
        -si.n_geo
    } else {
        si.n_geo
    };
    if n.z <= UP_FACING_Z {
        return WetState::Dry;
    }
    let p = w.origin_world + si.p.as_dvec3();
    if PUDDLE_CLASSES.contains(&si.semantic) && w.is_puddle_world(p.x, p.y) {
        WetState::Puddle
    } else {
        WetState::Wet
    }
}

/// The BSDF at a hit after wetness: `bsdf` itself when the scene is dry or
/// the surface is not an exposed, up-facing road/marking/sidewalk/terrain;
/// else a water film over the darkened base, or a smooth puddle. `wo` points
/// away from the surface (towards the viewer); `wetness` is the frame's.
pub fn wet_bsdf(wetness: Option<&Wetness>, si: &SurfaceInteraction, wo: Vec3, bsdf: Bsdf) -> Bsdf {
    let Some(w) = wetness else {
        return bsdf;
    };
    let (base, relief) = match bsdf {
        Bsdf::Lambert { albedo } => (CoatBase::Lambert { albedo }, None),
        Bsdf::Conductor { eta, k, alpha } => (CoatBase::Conductor { eta, k, alpha }, None),
        // A relief stays under a damp film; a puddle is flat.
        Bsdf::NormalMapped {
            facet: Facet::Lambert { albedo },
            wp,
        } => (CoatBase::Lambert { albedo }, Some(wp)),
        Bsdf::NormalMapped {
            facet: Facet::Conductor { eta, k, alpha },
            wp,
        } => (CoatBase::Conductor { eta, k, alpha }, Some(wp)),
        // Glass and already-coated surfaces keep their own interface.
        Bsdf::Dielectric { .. } | Bsdf::Coated { .. } | Bsdf::NormalMapped { .. } => return bsdf,
    };
    if let Some(wp) = relief {
        let flat = match base {
            CoatBase::Lambert { albedo } => Bsdf::Lambert { albedo },
            CoatBase::Conductor { eta, k, alpha } => Bsdf::Conductor { eta, k, alpha },
        };
        return match state(w, si, wo) {
            WetState::Dry => bsdf,
            WetState::Wet => wet_bsdf(wetness, si, wo, flat).normal_mapped(wp),
            WetState::Puddle => wet_bsdf(wetness, si, wo, flat),
        };
    }
    match state(w, si, wo) {
        WetState::Dry => bsdf,
        WetState::Wet => Bsdf::Coated {
            base: match base {
                CoatBase::Lambert { albedo } => CoatBase::Lambert {
                    albedo: w.wet_albedo(albedo, w.wetness),
                },
                conductor => conductor,
            },
            eta: WATER_IOR,
            alpha: w.film_alpha(),
        },
        // Standing water: a smooth interface over the soaked substrate.
        WetState::Puddle => Bsdf::Coated {
            base: CoatBase::Lambert {
                albedo: w.wet_albedo(base.albedo_hint(), 1.0),
            },
            eta: WATER_IOR,
            alpha: 0.0,
        },
    }
}

/// The GT mask bits of a hit on `material`: the material's, plus
/// `mask_bits::MIRROR` on a puddle of the frame's `wetness`. `ray_d` is the
/// camera ray's direction.
pub fn mask_at(
    material: &Material,
    wetness: Option<&Wetness>,
    si: &SurfaceInteraction,
    ray_d: Vec3,
) -> u8 {
    let bits = material.mask;
    match wetness {
        Some(w) if matches!(state(w, si, -ray_d), WetState::Puddle) => bits | mask_bits::MIRROR,
        _ => bits,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wetness(cover: f64) -> Wetness {
        let desc = WetnessDesc {
            wetness: 1.0,
            puddle_cover: cover,
            puddle_scale_m: 4.0,
            seed: 3,
        };
        Wetness::new(&desc, DVec3::new(1000.0, -20.0, 1.5))
    }

    #[test]
    fn water_internal_reflectance_matches_lekner_dorf() {
        // R̄_e ≈ 0.066 for n = 1.33, so R_i ≈ 1 − 0.934/1.769 ≈ 0.472.
        let ri = internal_reflectance(1.33);
        assert!((ri - 0.472).abs() < 3e-3, "{ri}");
    }

    #[test]
    fn wet_albedo_darkens_dark_surfaces_most_and_keeps_white() {
        let w = wetness(0.0);
        let a = w.wet_albedo(Vec3::new(0.1, 0.5, 1.0), 1.0);
        // 0.1 → 0.1·0.528/(1 − 0.0472) ≈ 0.0554.
        assert!((a.x - 0.0554).abs() < 1e-3, "{a}");
        assert!(a.x / 0.1 < a.y / 0.5 && (a.z - 1.0).abs() < 1e-6);
        assert_eq!(w.wet_albedo(Vec3::splat(0.3), 0.0), Vec3::splat(0.3));
    }

    #[test]
    fn puddle_cover_fraction_is_close_to_requested() {
        // 400 × 400 points over ~284 m × 276 m (~70 × 70 features of 4 m),
        // away from the lattice the quantile was estimated on: the covered
        // fraction must match the request to 15 % of itself (and 0.08).
        for cover in [0.1, 0.3, 0.6] {
            let w = wetness(cover);
            let n = 400;
            let hits = (0..n * n)
                .filter(|k| {
                    let (x, y) = ((k % n) as f64 * 0.71 + 500.0, (k / n) as f64 * 0.69);
                    w.is_puddle_world(x, y)
                })
                .count();
            let frac = hits as f64 / (n * n) as f64;
            assert!(
                (frac - cover).abs() < (0.15 * cover).min(0.08),
                "cover {cover}: {frac}"
            );
        }
        assert!(!wetness(0.0).is_puddle_world(3.0, 4.0));
    }

    #[test]
    fn puddle_noise_is_continuous() {
        // The documented lattice: octave 0 has cells of `scale_m` (edges where
        // x/s ∈ ℤ), octave 1 of s/2.3 offset by (17.1, −5.7) cells (edges where
        // 2.3·x/s + 17.1 ∈ ℤ, 2.3·y/s − 5.7 ∈ ℤ). Sample straddling every
        // edge: no jump in value (C0) and equal one-sided slopes (C1).
        let w = wetness(0.3);
        let s = w.scale_m;
        let oct0: Vec<f64> = (-6..6).map(|m| m as f64 * s).collect();
        let oct1_x: Vec<f64> = (-14..14).map(|m| (m as f64 - 17.1) * s / 2.3).collect();
        let oct1_y: Vec<f64> = (-14..14).map(|m| (m as f64 + 5.7) * s / 2.3).collect();
        // Along-edge coordinates, none on a lattice line of either octave.
        let along: Vec<f64> = (0..7).map(|k| -11.3 + 3.17 * k as f64).collect();
        let f = |x: f64, y: f64| w.puddle_noise(x, y) as f64;
        let (h, d) = (1e-7, 1e-3);
        let (mut lo, mut hi) = (f64::MAX, f64::MIN);
        let mut edges = 0;
        // axis 0: edges at x = e (step along x); axis 1: edges at y = e.
        for (axis, list) in [(0, &oct0), (0, &oct1_x), (1, &oct0), (1, &oct1_y)] {
            for &e in list.iter() {
                for &t in &along {
                    let at = |u: f64| if axis == 0 { f(e + u, t) } else { f(t, e + u) };
                    let (minus, mid, plus) = (at(-h), at(0.0), at(h));
                    assert!(
                        (plus - minus).abs() <= 1e-6,
                        "axis {axis} edge {e} at {t}: {minus} → {plus}"
                    );
                    let left = (mid - at(-d)) / d;
                    let right = (at(d) - mid) / d;
                    assert!(
                        (right - left).abs() <= 3e-3,
                        "axis {axis} edge {e} at {t}: slope {left} → {right}"
                    );
                    for v in [minus, mid, plus] {
                        lo = lo.min(v);
                        hi = hi.max(v);
                    }
                    edges += 1;
                }
            }
        }
        assert_eq!(edges, 7 * (12 + 28 + 12 + 28));
        assert!(hi - lo > 0.2, "noise barely varies: {lo}..{hi}");
    }
}
