//! The running state of one path through the surface loop (and the
//! volumetric loop, which shares it).

use glam::Vec3;

use super::RayCone;
use crate::accel::Ray;
use crate::integrator::aov::AovState;
use crate::integrator::denoise_parts::SplitVertex;

/// Bounces before Russian roulette may end a path.
const RR_START: u32 = 3;

/// The running state of one path.
pub(in crate::integrator) struct PathState {
    /// Radiance gathered so far.
    pub l: Vec3,
    /// Throughput.
    pub beta: Vec3,
    /// Solid-angle pdf of the last sampled direction.
    pub prev_pdf: f32,
    /// Whether the last direction came from the camera or a delta lobe.
    pub prev_delta: bool,
    /// The last scattering point.
    pub prev_p: Vec3,
    /// Its normal as its light-tree choice took it (`LightSet::select_at`):
    /// a reflecting surface's front geometric normal, else zero.
    pub prev_n: Vec3,
    /// Scattering events so far.
    pub bounces: u32,
    /// Where the denoised part of a surface path splits off.
    pub split: SplitVertex,
    /// The split vertex's Lambertian albedo (None: not Lambertian, or not
    /// yet shaded), recorded as it is shaded for the fog's split. The split
    /// vertex is the first that is not a delta scatter, reached from the
    /// camera through delta scatters only (x1, or a room behind a window).
    pub split_albedo: Option<Vec3>,
    /// The split vertex's `glossy_albedo` when it is glossy and emits
    /// nothing (None otherwise), recorded as it is shaded for the fog's
    /// split: all its light is then filtered as direct light.
    pub split_glossy: Option<Vec3>,
    /// Whether the path has scattered off a non-delta lobe (its glossy
    /// lobes are regularised from then on when the scene asks).
    pub rough_bounce: bool,
    /// The pixel's cone at the last vertex (`RayCone`): the footprint
    /// textures are filtered by at hits seen through delta bounces.
    pub cone: RayCone,
    /// The search for the first visible surface's albedo and normal.
    pub aov: AovState,
    /// Added to every sample dimension the path draws: 0, or
    /// `GLASS_BRANCH_DIMS` on a glass reflection's own branch, so its
    /// bounces do not reuse the numbers of the refraction's.
    pub dim_base: u32,
    /// The reflection of the smooth glass the camera ray met first, left
    /// to trace once the refraction's path has ended
    /// (`PathContext::finish_path`).
    pub glass_branch: Option<GlassBranch>,
}

/// Dimension offset of a glass reflection's branch (`PathState::dim_base`):
/// past every bounce's and candidate's own sets (`RIS_DIMS` + bounces ×
/// candidates stays below 2²⁰).
pub(in crate::integrator) const GLASS_BRANCH_DIMS: u32 = 1 << 24;

/// What the reflection of the glass a camera ray met first starts from
/// (`PathContext::glass_lobes`): the rest is a camera path's state after
/// one delta scatter.
#[derive(Clone, Copy)]
pub(in crate::integrator) struct GlassBranch {
    /// The reflected ray.
    pub ray: Ray,
    /// Its throughput: the Fresnel reflectance.
    pub beta: Vec3,
    /// The glass vertex.
    pub p: Vec3,
    /// The pixel's cone there.
    pub cone: RayCone,
}

impl PathState {
    /// A camera path starting at `o`.
    pub fn new(o: Vec3) -> Self {
        PathState {
            l: Vec3::ZERO,
            beta: Vec3::ONE,
            prev_pdf: 0.0,
            prev_delta: true,
            prev_p: o,
            prev_n: Vec3::ZERO,
            bounces: 0,
            split: SplitVertex::default(),
            split_albedo: None,
            split_glossy: None,
            rough_bounce: false,
            cone: RayCone::NONE,
            aov: AovState::default(),
            dim_base: 0,
            glass_branch: None,
        }
    }

    /// The state the reflection's path starts in: no split vertex ahead
    /// (a reflection's light is filtered as `l_refl`, not as a surface's),
    /// its own sample dimensions, nothing gathered yet.
    pub fn of_glass_branch(b: &GlassBranch) -> PathState {
        let mut st = PathState::new(b.p);
        st.beta = b.beta;
        st.bounces = 1;
        st.cone = b.cone;
        st.split.ahead = false;
        st.dim_base = GLASS_BRANCH_DIMS;
        st
    }

    /// Russian roulette after `RR_START` bounces; false ends the path.
    pub fn survives_roulette(&mut self, u_rr: f32) -> bool {
        if self.bounces >= RR_START {
            let q = (1.0 - self.beta.max_element()).clamp(0.0, 0.95);
            if u_rr < q {
                return false;
            }
            self.beta /= 1.0 - q;
        }
        true
    }
}
