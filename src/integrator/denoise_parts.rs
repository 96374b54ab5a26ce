//! What the path tracer hands the image-space denoiser (`crate::denoise`):
//! per camera sample, the parts of its radiance the denoiser replaces by
//! filtered estimates ([`DenoiseSample`]), their per-pixel sums
//! ([`DenoiseSum`]), and the path's bookkeeping of the vertex where the
//! filtered part splits off ([`SplitVertex`]).

use glam::Vec3;
use shaders_cpu::bsdf::fresnel::fr_dielectric;
use shaders_cpu::bsdf::{Bsdf, CoatBase, Facet};

/// The denoiser's parts of one camera sample's radiance: `l_fog` is the
/// part whose first event is a medium scatter before the first surface or
/// the sky (smooth over the image); `l_surf` the part filtered over the
/// first surface as a ratio to `rho`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DenoiseSample {
    /// First-medium-scatter part of the radiance (zero without a scattering medium).
    pub l_fog: Vec3,
    /// Opacity 1 − Tr of the camera ray's first segment, in [0, 1] (zero
    /// without a scattering medium): `l_fog / opacity` is the mean radiance
    /// scattered toward the camera along that segment.
    pub opacity: f32,
    /// The part filtered over the first surface x1, when x1 is Lambertian:
    /// with a fog filter, the light whose next event after x1 is a medium
    /// scatter (fog light on the first surface); in a medium-free scene
    /// that filters indirect light (`Scene::filter_indirect`), all the
    /// light x1 reflects except its own emission and next-event estimates
    /// (sky and indirect light). Zero otherwise.
    pub l_surf: Vec3,
    /// Throughput at x1 times x1's albedo (zero when x1 is missing or not
    /// Lambertian, or nothing is filtered): `l_surf / rho` is the filtered
    /// light's irradiance / π, smooth over a surface and free of texture.
    /// In a medium-free scene the split vertex may lie behind x1's mirrors
    /// and glass instead (`SplitVertex`).
    pub rho: Vec3,
    /// Whether the split vertex lies behind delta scatters (seen through
    /// glass or in a mirror): the filter keeps such light apart from light
    /// split at x1.
    pub split_behind_delta: bool,
    /// At a Lambertian split vertex, its own next-event estimates but the
    /// sun's (sky, lamps, headlights): direct light, filtered as a ratio to
    /// `rho_direct` with edge-stopping on its own noise level, so shadow
    /// edges stay. The sun's is left as traced: sharp, nearly noise-free,
    /// and it carries the relief's shading, which a filter would blur.
    /// At a glossy split vertex (paint, rough metal): all the light it
    /// reflects (the same filter). Zero otherwise.
    pub l_direct: Vec3,
    /// Throughput × albedo estimate that `l_direct` is filtered against:
    /// `rho` at a Lambertian split vertex, [`glossy_albedo`] at a glossy one.
    pub rho_direct: Vec3,
    /// Whether the split vertex is glossy (`l_direct` holds all its light):
    /// the filter keeps such pixels apart from Lambertian ones.
    pub glossy: bool,
    /// All the light arriving along a specular reflection at smooth glass
    /// that the camera ray meets through delta scatters (a pane's front or
    /// back face), when the sample took that reflection (zero when it
    /// refracted throughout): the sky and street a window mirrors. Filtered
    /// as a ratio to `rho_refl`. On the reflection's own branch
    /// (`PathContext::glass_lobes`) less `l_refl_sharp`.
    pub l_refl: Vec3,
    /// What the glass's reflection branch shows sharp, left as traced
    /// (part of the radiance, in no filtered part): the light it meets
    /// through delta scatters only (the sky, lamps and lit windows seen in
    /// the glass) and the sun's next-event light where it first meets a
    /// rough surface. Given the reflected ray these are nearly free of
    /// noise, and they carry what the window mirrors in detail: the sunlit
    /// brickwork, the lamps, the skyline.
    pub l_refl_sharp: Vec3,
    /// Σ throughput × Fresnel reflectance over those glass faces, on every
    /// sample that met them, reflected or not: the mean of `l_refl` is the
    /// pixel's mean `rho_refl` times the reflected radiance, whatever share
    /// of the samples happened to reflect (a window's sparkle is that share).
    pub rho_refl: Vec3,
    /// The reflected sample's own weight: throughput after the reflection
    /// (Fresnel reflectance over the probability of taking it), on the
    /// sample that took it (zero otherwise). `l_refl / rho_refl_hit` is
    /// the radiance the sample saw in the glass, with none of the sparkle
    /// of which samples reflected: the filter's ratio and its noise level.
    pub rho_refl_hit: Vec3,
    /// At a Lambertian split vertex (`rho` nonzero), how free its bounce
    /// ray's first [`OPEN_RADIUS`] is ([`openness`]; 1 where no bounce was
    /// traced): a corner's or recess's indirect light is low because its
    /// bounce rays meet the walls around it, which the albedo does not
    /// say, so the filter of `l_surf` also divides by it.
    pub openness: f32,
}

/// Distance, in metres, within which a split vertex's bounce ray meeting a
/// surface counts as hemmed in: the depth of window reveals, balconies and
/// the space under a car, where a façade's or the road's indirect light
/// drops (0.5–2 m score alike: docs/reference.md).
pub const OPEN_RADIUS: f32 = 1.5;

/// The openness of a bounce ray whose first hit lies `distance` metres
/// away (None: it met nothing): the share of [`OPEN_RADIUS`] it crossed
/// freely, in [0, 1].
pub(super) fn openness(distance: Option<f32>) -> f32 {
    distance.map_or(1.0, |t| (t / OPEN_RADIUS).clamp(0.0, 1.0))
}

/// The albedo estimate a glossy (non-delta, non-Lambertian) split vertex's
/// light is demodulated by: a coat's base colour plus the coat's normal
/// reflectance (so black paint is not a division by nothing), a metal's
/// grey 0.5; `None` for BSDFs not filtered (glass, mirrors, Lambertian).
pub fn glossy_albedo(bsdf: &Bsdf) -> Option<Vec3> {
    const COAT_F0: f32 = 0.04;
    let coat = |base: &CoatBase| match base {
        CoatBase::Lambert { albedo } => *albedo + Vec3::splat(COAT_F0),
        CoatBase::Conductor { .. } => Vec3::splat(0.5),
    };
    match bsdf {
        Bsdf::Coated { base, .. }
        | Bsdf::NormalMapped {
            facet: Facet::Coated { base, .. },
            ..
        } => Some(coat(base)),
        Bsdf::Conductor { .. }
        | Bsdf::NormalMapped {
            facet: Facet::Conductor { .. },
            ..
        } => Some(Vec3::splat(0.5)),
        _ => None,
    }
}

/// Running sums of one pixel's [`DenoiseSample`]s, field by field.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DenoiseSum {
    /// Σ `DenoiseSample::l_fog`.
    pub l_fog: Vec3,
    /// Σ `DenoiseSample::opacity`.
    pub opacity: f32,
    /// Σ `DenoiseSample::l_surf`.
    pub l_surf: Vec3,
    /// Σ `DenoiseSample::rho`.
    pub rho: Vec3,
    /// Samples split behind delta scatters (`DenoiseSample::split_behind_delta`).
    pub behind_delta: u32,
    /// Σ `DenoiseSample::l_direct`.
    pub l_direct: Vec3,
    /// Σ luminance(`l_direct`)²: with the sum, the per-pixel variance of
    /// the direct light that steers its filter.
    pub direct_lum2: f32,
    /// Σ luminance(`l_surf`)²: the variance that steers indirect light's
    /// filter.
    pub surf_lum2: f32,
    /// Σ `DenoiseSample::rho_direct`.
    pub rho_direct: Vec3,
    /// Samples split at a glossy vertex (`DenoiseSample::glossy`).
    pub glossy: u32,
    /// Σ `DenoiseSample::l_refl`.
    pub l_refl: Vec3,
    /// Σ `DenoiseSample::rho_refl`.
    pub rho_refl: Vec3,
    /// Σ `DenoiseSample::rho_refl_hit`.
    pub rho_refl_hit: Vec3,
    /// Samples that took glass's reflection (a `rho_refl_hit` of nonzero
    /// luminance).
    pub refl_hits: u32,
    /// Σ over those samples of the radiance they saw in the glass,
    /// luminance(`l_refl`) / luminance(`rho_refl_hit`).
    pub refl_seen: f32,
    /// Σ of its squares: with the sum, the per-pixel variance of the
    /// reflected radiance that steers its filter.
    pub refl_seen2: f32,
    /// Σ `DenoiseSample::openness` over the samples with a `rho`.
    pub openness: f32,
    /// Samples with a `rho` (a Lambertian split vertex).
    pub split_samples: u32,
}

impl DenoiseSum {
    /// Adds one sample.
    pub fn add(&mut self, d: &DenoiseSample) {
        self.l_fog += d.l_fog;
        self.opacity += d.opacity;
        self.l_surf += d.l_surf;
        self.rho += d.rho;
        self.behind_delta += d.split_behind_delta as u32;
        self.l_direct += d.l_direct;
        self.direct_lum2 += luminance(d.l_direct).powi(2);
        self.surf_lum2 += luminance(d.l_surf).powi(2);
        self.rho_direct += d.rho_direct;
        self.glossy += d.glossy as u32;
        self.l_refl += d.l_refl;
        self.rho_refl += d.rho_refl;
        self.rho_refl_hit += d.rho_refl_hit;
        if d.rho != Vec3::ZERO {
            self.openness += d.openness;
            self.split_samples += 1;
        }
        let hit = luminance(d.rho_refl_hit);
        if hit > 0.0 {
            let seen = luminance(d.l_refl) / hit;
            self.refl_hits += 1;
            self.refl_seen += seen;
            self.refl_seen2 += seen * seen;
        }
    }
}

/// Rec. 709 luminance of linear RGB: the scalar whose sample moments steer
/// the filter of direct light and adaptive sampling.
#[inline]
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

/// A surface path's split vertex: the first vertex that is not a delta
/// scatter (x1, or what x1's mirrors show and its glass lets through),
/// where the scene filters indirect light and that vertex is Lambertian.
#[derive(Clone, Copy, Debug)]
pub(super) struct SplitVertex {
    /// Throughput × albedo at the split vertex (else zero): `DenoiseSample::rho`.
    pub rho: Vec3,
    /// Whether the split vertex is still ahead (every vertex so far
    /// scattered through a delta lobe, and no glass reflected).
    pub ahead: bool,
    /// Whether the split vertex came after delta scatters.
    pub behind_delta: bool,
    /// Throughput × [`glossy_albedo`] at a glossy split vertex (else zero):
    /// `DenoiseSample::rho_direct` there.
    pub rho_gloss: Vec3,
    /// Σ throughput × Fresnel reflectance over the smooth glass met
    /// through delta scatters (else zero): `DenoiseSample::rho_refl`.
    pub rho_refl: Vec3,
    /// The radiance gathered when the path took that glass's reflection
    /// (None: it did not): what it gathers after is `DenoiseSample::l_refl`.
    pub refl_from: Option<Vec3>,
    /// The throughput after that reflection (else zero):
    /// `DenoiseSample::rho_refl_hit`.
    pub rho_refl_hit: Vec3,
}

impl SplitVertex {
    /// At a vertex reached from the camera through delta scatters only
    /// (`ahead`), whose BSDF in its shading frame is `bsdf`, seen from
    /// `wo` and continued toward `wi` (both local) with the sampled weight
    /// f·|cos θi|/pdf `weight`, with throughput `beta` and radiance `l`
    /// gathered so far: smooth glass adds its reflectance (a pane's front
    /// face, and its back face for samples that refracted at the front),
    /// and where `wi` is its reflection, records `l` (what the path
    /// gathers from here on is `DenoiseSample::l_refl`) and the throughput
    /// after it, `beta · weight`; a reflection ends `ahead`, so a path
    /// records at most one.
    pub fn at_glass(&mut self, bsdf: &Bsdf, wo: Vec3, wi: Vec3, weight: Vec3, beta: Vec3, l: Vec3) {
        let Bsdf::Dielectric { eta, .. } = *bsdf else {
            return;
        };
        if !bsdf.is_delta() {
            return;
        }
        // The smooth interface reflects with probability q and weight R/q
        // (`dielectric::sample_smooth`): the reflected light's mean is
        // beta·R·L whatever q is.
        self.rho_refl += beta * fr_dielectric(wo.z, eta);
        if wi.z * wo.z > 0.0 {
            // After a split (`split_glass`) this is the pane's back face
            // reflecting inside: a second, fainter mirror image, filtered
            // with the first.
            self.refl_from = Some(l);
            self.rho_refl_hit += beta * weight;
        }
    }

    /// At the smooth glass a camera ray meets first, whose reflection is
    /// traced whole as a branch of its own, of throughput `beta · r` (`r`
    /// the reflection's f·|cos θi|, its Fresnel reflectance), while the
    /// path goes on through the glass: every sample then sees what the
    /// glass mirrors. The branch's light is `DenoiseSample::l_refl`;
    /// `rho_refl` gains the reflectance as in [`SplitVertex::at_glass`].
    pub fn split_glass(&mut self, r: Vec3, beta: Vec3) {
        self.rho_refl += beta * r;
        self.rho_refl_hit = beta * r;
    }
}

impl Default for SplitVertex {
    fn default() -> Self {
        SplitVertex {
            rho: Vec3::ZERO,
            ahead: true,
            behind_delta: false,
            rho_gloss: Vec3::ZERO,
            rho_refl: Vec3::ZERO,
            refl_from: None,
            rho_refl_hit: Vec3::ZERO,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_add_every_part_and_count_samples_split_behind_delta() {
        let a = DenoiseSample {
            l_fog: Vec3::new(1.0, 2.0, 3.0),
            opacity: 0.25,
            l_surf: Vec3::splat(0.5),
            rho: Vec3::new(0.25, 0.5, 0.75),
            split_behind_delta: true,
            l_direct: Vec3::new(0.0, 2.0, 0.0),
            rho_direct: Vec3::splat(0.25),
            glossy: true,
            l_refl: Vec3::new(0.0, 0.0, 4.0),
            // Left as traced: in no filtered sum.
            l_refl_sharp: Vec3::splat(9.0),
            rho_refl: Vec3::splat(0.125),
            rho_refl_hit: Vec3::splat(0.5),
            openness: 0.25,
        };
        let b = DenoiseSample {
            l_fog: Vec3::splat(1.0),
            opacity: 0.5,
            l_surf: Vec3::splat(0.25),
            rho: Vec3::splat(0.5),
            split_behind_delta: false,
            openness: 1.0,
            ..DenoiseSample::default()
        };
        // No rho: its openness is not counted.
        let c = DenoiseSample {
            openness: 0.5,
            ..DenoiseSample::default()
        };
        let mut sum = DenoiseSum::default();
        for s in [a, b, a, c] {
            sum.add(&s);
        }
        assert_eq!(sum.l_fog, Vec3::new(3.0, 5.0, 7.0));
        assert_eq!(sum.opacity, 1.0);
        assert_eq!(sum.l_surf, Vec3::splat(1.25));
        assert_eq!(sum.rho, Vec3::new(1.0, 1.5, 2.0));
        assert_eq!(sum.behind_delta, 2);
        assert_eq!(sum.l_direct, Vec3::new(0.0, 4.0, 0.0));
        assert_eq!(sum.direct_lum2, 2.0 * (2.0f32 * 0.7152).powi(2));
        assert!((sum.surf_lum2 - (2.0 * 0.25 + 0.0625)).abs() < 1e-6);
        assert_eq!(sum.rho_direct, Vec3::splat(0.5));
        assert_eq!(sum.glossy, 2);
        assert_eq!(sum.l_refl, Vec3::new(0.0, 0.0, 8.0));
        assert_eq!(sum.rho_refl, Vec3::splat(0.25));
        assert_eq!(sum.rho_refl_hit, Vec3::splat(1.0));
        assert_eq!((sum.openness, sum.split_samples), (1.5, 3));
        // Seen in the glass: luminance 4·0.0722 over 0.5, on a's two samples.
        let seen = 4.0f32 * 0.0722 / 0.5;
        assert_eq!(sum.refl_hits, 2);
        assert!(
            (sum.refl_seen - 2.0 * seen).abs() < 1e-6,
            "{}",
            sum.refl_seen
        );
        assert!((sum.refl_seen2 - 2.0 * seen * seen).abs() < 1e-6);
    }

    #[test]
    fn openness_is_the_free_share_of_the_radius() {
        assert_eq!(openness(None), 1.0);
        assert_eq!(openness(Some(0.0)), 0.0);
        assert!((openness(Some(0.25 * OPEN_RADIUS)) - 0.25).abs() < 1e-6);
        assert_eq!(openness(Some(OPEN_RADIUS)), 1.0);
        assert_eq!(openness(Some(100.0)), 1.0);
    }

    #[test]
    fn glass_adds_its_reflectance_on_every_sample_and_marks_the_reflected_ones() {
        let glass = Bsdf::Dielectric {
            eta: 1.5,
            alpha: 0.0,
            tint: Vec3::new(1.0, 0.5, 1.0),
        };
        // Normal incidence: R = ((1.5 − 1)/(1.5 + 1))² = 0.04.
        let (wo, beta, l) = (Vec3::Z, Vec3::new(1.0, 0.5, 0.25), Vec3::splat(3.0));
        // The sampled weights: R/q reflected (q = 0.25), T/(1 − q) refracted.
        let (w_refl, w_refr) = (Vec3::splat(0.16), Vec3::splat(1.28));
        let mut reflected = SplitVertex::default();
        reflected.at_glass(&glass, wo, Vec3::Z, w_refl, beta, l);
        assert!((reflected.rho_refl - beta * 0.04).abs().max_element() < 1e-6);
        assert_eq!(reflected.refl_from, Some(l));
        assert_eq!(reflected.rho_refl_hit, beta * w_refl);
        let mut refracted = SplitVertex::default();
        refracted.at_glass(&glass, wo, -Vec3::Z, w_refr, beta, l);
        assert_eq!(refracted.rho_refl, reflected.rho_refl);
        assert_eq!(
            (refracted.refl_from, refracted.rho_refl_hit),
            (None, Vec3::ZERO)
        );
        // The back face, from inside (wo.z < 0), adds its own reflectance.
        refracted.at_glass(&glass, -Vec3::Z, Vec3::Z, w_refr, beta, Vec3::ONE);
        assert!((refracted.rho_refl - beta * 0.08).abs().max_element() < 1e-6);
        assert_eq!(
            (refracted.refl_from, refracted.rho_refl_hit),
            (None, Vec3::ZERO),
            "leaving the pane is no reflection"
        );
        // Rough glass, walls and mirrors are not this component's.
        let rough = Bsdf::Dielectric {
            eta: 1.5,
            alpha: 0.3,
            tint: Vec3::ONE,
        };
        let mirror = Bsdf::Conductor {
            eta: Vec3::splat(0.2),
            k: Vec3::splat(3.0),
            alpha: 0.0,
        };
        for bsdf in [rough, mirror, Bsdf::Lambert { albedo: Vec3::ONE }] {
            let mut s = SplitVertex::default();
            s.at_glass(&bsdf, wo, Vec3::Z, Vec3::ONE, beta, l);
            assert_eq!((s.rho_refl, s.refl_from), (Vec3::ZERO, None), "{bsdf:?}");
            assert_eq!(s.rho_refl_hit, Vec3::ZERO, "{bsdf:?}");
        }
    }

    #[test]
    fn glossy_albedo_is_the_base_plus_the_coat_and_none_for_lambert_and_glass() {
        let albedo = Vec3::new(0.02, 0.3, 0.6);
        let paint = Bsdf::Coated {
            base: CoatBase::Lambert { albedo },
            eta: 1.5,
            alpha: 0.0,
        };
        assert_eq!(glossy_albedo(&paint), Some(albedo + Vec3::splat(0.04)));
        let metal = Bsdf::Conductor {
            eta: Vec3::splat(0.2),
            k: Vec3::splat(3.0),
            alpha: 0.2,
        };
        assert_eq!(glossy_albedo(&metal), Some(Vec3::splat(0.5)));
        assert_eq!(glossy_albedo(&Bsdf::Lambert { albedo }), None);
        let glass = Bsdf::Dielectric {
            eta: 1.5,
            alpha: 0.0,
            tint: Vec3::ONE,
        };
        assert_eq!(glossy_albedo(&glass), None);
    }
}
