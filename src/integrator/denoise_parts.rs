//! What the path tracer hands the image-space denoiser (`crate::denoise`):
//! per camera sample, the parts of its radiance the denoiser replaces by
//! filtered estimates ([`DenoiseSample`]), their per-pixel sums
//! ([`DenoiseSum`]), and the path's bookkeeping of the vertex where the
//! filtered part splits off ([`SplitVertex`]).

use glam::Vec3;

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
}

impl DenoiseSum {
    /// Adds one sample.
    pub fn add(&mut self, d: &DenoiseSample) {
        self.l_fog += d.l_fog;
        self.opacity += d.opacity;
        self.l_surf += d.l_surf;
        self.rho += d.rho;
        self.behind_delta += d.split_behind_delta as u32;
    }
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
}

impl Default for SplitVertex {
    fn default() -> Self {
        SplitVertex {
            rho: Vec3::ZERO,
            ahead: true,
            behind_delta: false,
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
        };
        let b = DenoiseSample {
            l_fog: Vec3::splat(1.0),
            opacity: 0.5,
            l_surf: Vec3::splat(0.25),
            rho: Vec3::splat(0.5),
            split_behind_delta: false,
        };
        let mut sum = DenoiseSum::default();
        for s in [a, b, a] {
            sum.add(&s);
        }
        assert_eq!(sum.l_fog, Vec3::new(3.0, 5.0, 7.0));
        assert_eq!(sum.opacity, 1.0);
        assert_eq!(sum.l_surf, Vec3::splat(1.25));
        assert_eq!(sum.rho, Vec3::new(1.0, 1.5, 2.0));
        assert_eq!(sum.behind_delta, 2);
    }
}
