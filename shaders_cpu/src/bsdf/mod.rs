//! BSDFs in the local shading frame (z = shading normal), radiance transport.
//!
//! This file is the contract (pbrt-v4 `base/bxdf.h` style); each family lives in
//! its own file: `lambert` (pbrt-v4 §9.2), `conductor` (§9.4, §9.6),
//! `dielectric` (§9.5, §9.7), `coat` (a dielectric coat over a base, after
//! Weidlich & Wilkie 2007), `normal_map` (a perturbed normal as a
//! microsurface, Schüssler et al. 2017), with `microfacet` (GGX, §9.6) and
//! `fresnel` (§9.3). `eval` is f without the cosine; `pdf` is per solid angle; a delta
//! sample carries f = (specular weight)/|cosθi| so f·|cosθi|/pdf is the weight.

pub mod fresnel;
pub mod microfacet;
pub mod normal_map;

mod coat;
mod conductor;
mod dielectric;
mod lambert;
mod presets;

use crate::sampling::Frame;
pub use coat::CoatBase;
pub use normal_map::Facet;
pub use presets::roughness_to_alpha;

use glam::{Vec2, Vec3};

/// A sampled scattering direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BsdfSample {
    /// Sampled incident direction, local frame, unit length.
    pub wi: Vec3,
    /// BSDF value f(wo, wi) (without the cosine).
    pub f: Vec3,
    /// Pdf per solid angle (for delta lobes: the discrete lobe probability).
    pub pdf: f32,
    /// Whether the sample came from a delta (perfectly specular) lobe.
    pub delta: bool,
}

impl BsdfSample {
    /// Throughput weight f·|cosθi|/pdf (zero if the pdf is zero).
    pub fn weight(&self) -> Vec3 {
        if self.pdf > 0.0 {
            self.f * (self.wi.z.abs() / self.pdf)
        } else {
            Vec3::ZERO
        }
    }
}

/// The closed set of scattering models.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Bsdf {
    /// Lambertian diffuse reflection.
    Lambert {
        /// Reflectance in [0, 1] per channel.
        albedo: Vec3,
    },
    /// GGX microfacet conductor (alpha below ~1e-3 is a perfect mirror).
    Conductor {
        /// Real part of the complex index of refraction, per channel.
        eta: Vec3,
        /// Imaginary part (absorption), per channel.
        k: Vec3,
        /// GGX roughness alpha (= perceptual roughness squared).
        alpha: f32,
    },
    /// GGX microfacet dielectric with reflection and transmission
    /// (alpha below ~1e-3 is smooth glass).
    Dielectric {
        /// Relative index of refraction inside/outside (e.g. 1.5 for glass).
        eta: f32,
        /// GGX roughness alpha.
        alpha: f32,
        /// Transmission tint per channel in [0, 1].
        tint: Vec3,
    },
    /// A dielectric coat (clear coat η ≈ 1.5, water film η ≈ 1.33) over a
    /// Lambert or conductor base; reflection only, two-sided.
    Coated {
        /// The layer under the coat.
        base: CoatBase,
        /// Relative IOR of the coat over air, > 1.
        eta: f32,
        /// GGX roughness alpha of the coat (< 1e-3: smooth, a delta lobe).
        alpha: f32,
    },
    /// A non-delta reflection-only BSDF under a perturbed normal
    /// (`normal_map`); evaluated in the frame of the geometric normal.
    NormalMapped {
        /// The BSDF on the perturbed facet.
        facet: Facet,
        /// The perturbed normal: in the local frame once [`Bsdf::in_frame`]
        /// has run (before that, in the space the frame is built in).
        wp: Vec3,
    },
}

impl Bsdf {
    /// f(wo, wi), local frame (zero for delta lobes).
    #[inline]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match *self {
            Bsdf::Lambert { albedo } => lambert::eval(albedo, wo, wi),
            Bsdf::Conductor { eta, k, alpha } => conductor::eval(eta, k, alpha, wo, wi),
            Bsdf::Dielectric { eta, alpha, tint } => dielectric::eval(eta, alpha, tint, wo, wi),
            Bsdf::Coated { base, eta, alpha } => coat::eval(&base, eta, alpha, wo, wi),
            Bsdf::NormalMapped { facet, wp } => normal_map::eval(&facet, wp, wo, wi),
        }
    }
    /// Pdf per solid angle of sampling `wi` given `wo` (zero for delta lobes).
    #[inline]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match *self {
            Bsdf::Lambert { .. } => lambert::pdf(wo, wi),
            Bsdf::Conductor { alpha, .. } => conductor::pdf(alpha, wo, wi),
            Bsdf::Dielectric { eta, alpha, .. } => dielectric::pdf(eta, alpha, wo, wi),
            Bsdf::Coated { base, eta, alpha } => coat::pdf(&base, eta, alpha, wo, wi),
            Bsdf::NormalMapped { facet, wp } => normal_map::pdf(&facet, wp, wo, wi),
        }
    }
    /// [`Bsdf::eval`] and [`Bsdf::pdf`] together (a normal-mapped surface
    /// builds its groove once for both).
    #[inline]
    pub fn eval_pdf(&self, wo: Vec3, wi: Vec3) -> (Vec3, f32) {
        match *self {
            Bsdf::NormalMapped { facet, wp } => normal_map::eval_pdf(&facet, wp, wo, wi),
            _ => (self.eval(wo, wi), self.pdf(wo, wi)),
        }
    }
    /// Samples `wi` given `wo`, a lobe-selection number and a 2D sample.
    #[inline]
    pub fn sample(&self, wo: Vec3, u_lobe: f32, u: Vec2) -> Option<BsdfSample> {
        match *self {
            Bsdf::Lambert { albedo } => lambert::sample(albedo, wo, u),
            Bsdf::Conductor { eta, k, alpha } => conductor::sample(eta, k, alpha, wo, u),
            Bsdf::Dielectric { eta, alpha, tint } => {
                dielectric::sample(eta, alpha, tint, wo, u_lobe, u)
            }
            Bsdf::Coated { base, eta, alpha } => coat::sample(&base, eta, alpha, wo, u_lobe, u),
            Bsdf::NormalMapped { facet, wp } => normal_map::sample(&facet, wp, wo, u_lobe, u),
        }
    }
    /// The BSDF with every reflecting microfacet lobe at least `min_alpha`
    /// rough (conductors, clear coats and their metallic bases); Lambert,
    /// glass and normal-mapped facets are unchanged. Path regularisation:
    /// a sun seen in a mirror-like lobe from a diffuse surface is then
    /// found by next-event estimation instead of by rare BSDF samples.
    pub fn regularized(self, min_alpha: f32) -> Bsdf {
        match self {
            Bsdf::Conductor { eta, k, alpha } => Bsdf::Conductor {
                eta,
                k,
                alpha: alpha.max(min_alpha),
            },
            Bsdf::Coated { base, eta, alpha } => Bsdf::Coated {
                base: match base {
                    CoatBase::Conductor { eta, k, alpha } => CoatBase::Conductor {
                        eta,
                        k,
                        alpha: alpha.max(min_alpha),
                    },
                    lambert => lambert,
                },
                eta,
                alpha: alpha.max(min_alpha),
            },
            other => other,
        }
    }
    /// Whether every lobe is a delta (eval and pdf are then always zero).
    #[inline]
    pub fn is_delta(&self) -> bool {
        match *self {
            Bsdf::Lambert { .. } => false,
            Bsdf::Conductor { alpha, .. } => {
                microfacet::TrowbridgeReitz::new(alpha).effectively_smooth()
            }
            Bsdf::Dielectric { eta, alpha, .. } => dielectric::is_delta(eta, alpha),
            Bsdf::Coated { base, alpha, .. } => coat::is_delta(&base, alpha),
            Bsdf::NormalMapped { .. } => false,
        }
    }
    /// A rough colour for debug views: Lambert albedo, a conductor's normal-
    /// incidence reflectance F0, a dielectric's tint.
    pub fn albedo_hint(&self) -> Vec3 {
        match *self {
            Bsdf::Lambert { albedo } => albedo,
            Bsdf::Conductor { eta, k, .. } => fresnel::fr_complex_rgb(1.0, eta, k),
            Bsdf::Dielectric { tint, .. } => tint,
            Bsdf::Coated { base, .. } => base.albedo_hint(),
            Bsdf::NormalMapped { facet, .. } => facet.albedo_hint(),
        }
    }

    /// The Lambertian reflectance of a diffuse surface, bumped or not
    /// (what image-space filtering divides by); None for other models.
    pub fn diffuse_albedo(&self) -> Option<Vec3> {
        match *self {
            Bsdf::Lambert { albedo }
            | Bsdf::NormalMapped {
                facet: Facet::Lambert { albedo },
                ..
            } => Some(albedo),
            _ => None,
        }
    }

    /// `self` under the perturbed normal `wp` (unit, in the space the
    /// shading frame will be built in, on the geometric normal's side):
    /// [`Bsdf::NormalMapped`] for a reflection-only model without delta
    /// lobes, `self` unchanged otherwise (glass, mirrors, smooth coats).
    pub fn normal_mapped(self, wp: Vec3) -> Bsdf {
        let facet = match self {
            Bsdf::Lambert { albedo } => Facet::Lambert { albedo },
            Bsdf::Conductor { eta, k, alpha } if !self.is_delta() => {
                Facet::Conductor { eta, k, alpha }
            }
            Bsdf::Coated { base, eta, alpha }
                if !base.is_delta()
                    && !microfacet::TrowbridgeReitz::new(alpha).effectively_smooth() =>
            {
                Facet::Coated { base, eta, alpha }
            }
            _ => return self,
        };
        Bsdf::NormalMapped { facet, wp }
    }

    /// Expresses a [`Bsdf::NormalMapped`]'s normal in `frame` (built on the
    /// geometric normal, flipped as the surface was), mirrored to the
    /// frame's upper side; other models unchanged.
    pub fn in_frame(self, frame: &Frame) -> Bsdf {
        match self {
            Bsdf::NormalMapped { facet, wp } => {
                let local = frame.to_local(wp);
                let wp = if local.z < 0.0 { -local } else { local };
                Bsdf::NormalMapped { facet, wp }
            }
            other => other,
        }
    }
}
