//! Auxiliary images of the first visible surface, per camera sample: its
//! albedo and shading normal, the inputs an external denoiser (Open Image
//! Denoise) takes beside the noisy radiance. The surface is the first
//! non-delta vertex reached from the camera through delta scatters only
//! (what mirrors show and glass lets through); the albedo carries the
//! throughput of those delta scatters. A camera path that leaves the scene
//! first, or whose first event is a medium scatter, has none (both zero).

use glam::Vec3;
use shaders_cpu::bsdf::Bsdf;

use super::denoise_parts::glossy_albedo;

/// One camera sample's auxiliary values.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Aov {
    /// Throughput × albedo estimate at the first visible surface: the
    /// diffuse albedo, a glossy surface's [`glossy_albedo`], one for
    /// other non-delta surfaces (rough glass).
    pub albedo: Vec3,
    /// Its world-space unit shading normal, facing the incoming ray on
    /// two-sided surfaces.
    pub normal: Vec3,
}

/// The path's search for its first visible surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct AovState {
    /// The values found (zero until then).
    pub aov: Aov,
    /// Whether the surface may still come (every event so far a delta
    /// scatter at a surface).
    open: bool,
}

impl Default for AovState {
    fn default() -> Self {
        AovState {
            aov: Aov::default(),
            open: true,
        }
    }
}

impl AovState {
    /// A surface vertex reached along a delta direction (`prev_delta`: from
    /// the camera or a delta lobe) with throughput `beta`: a non-delta
    /// `bsdf` there is the first visible surface. Arriving any other way
    /// (after a medium scatter or a non-delta bounce) ends the search.
    pub fn at_vertex(&mut self, prev_delta: bool, beta: Vec3, bsdf: &Bsdf, n_shading: Vec3) {
        if !self.open {
            return;
        }
        if !prev_delta {
            self.open = false;
            return;
        }
        if bsdf.is_delta() {
            return;
        }
        self.open = false;
        let albedo = bsdf
            .diffuse_albedo()
            .or_else(|| glossy_albedo(bsdf))
            .unwrap_or(Vec3::ONE);
        self.aov = Aov {
            albedo: beta * albedo,
            normal: n_shading.normalize_or_zero(),
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use shaders_cpu::bsdf::CoatBase;

    const WALL: Bsdf = Bsdf::Lambert {
        albedo: Vec3::new(0.2, 0.4, 0.6),
    };

    #[test]
    fn the_first_non_delta_vertex_is_recorded_with_the_delta_throughput() {
        let mirror = Bsdf::Conductor {
            eta: Vec3::splat(0.2),
            k: Vec3::splat(3.0),
            alpha: 0.0,
        };
        assert!(mirror.is_delta());
        let mut s = AovState::default();
        s.at_vertex(true, Vec3::ONE, &mirror, Vec3::Z);
        assert_eq!(s.aov, Aov::default(), "a mirror is looked through");
        let beta = Vec3::new(0.9, 0.8, 0.7);
        s.at_vertex(true, beta, &WALL, Vec3::new(0.0, 3.0, 4.0));
        assert_eq!(s.aov.albedo, beta * Vec3::new(0.2, 0.4, 0.6));
        assert!((s.aov.normal - Vec3::new(0.0, 0.6, 0.8)).length() < 1e-6);
        // Later vertices change nothing.
        let first = s.aov;
        s.at_vertex(
            true,
            Vec3::ONE,
            &Bsdf::Lambert { albedo: Vec3::ONE },
            Vec3::X,
        );
        assert_eq!(s.aov, first);
    }

    #[test]
    fn arriving_after_a_non_delta_event_ends_the_search_and_glossy_uses_its_albedo() {
        let mut s = AovState::default();
        s.at_vertex(false, Vec3::ONE, &WALL, Vec3::Z);
        s.at_vertex(true, Vec3::ONE, &WALL, Vec3::Z);
        assert_eq!(s.aov, Aov::default());
        let paint = Bsdf::Coated {
            base: CoatBase::Lambert {
                albedo: Vec3::new(0.5, 0.1, 0.1),
            },
            eta: 1.5,
            alpha: 0.2,
        };
        let mut s = AovState::default();
        s.at_vertex(true, Vec3::ONE, &paint, Vec3::Z);
        assert_eq!(s.aov.albedo, glossy_albedo(&paint).unwrap());
        let rough_glass = Bsdf::Dielectric {
            eta: 1.5,
            alpha: 0.3,
            tint: Vec3::ONE,
        };
        if !rough_glass.is_delta() {
            let mut s = AovState::default();
            s.at_vertex(true, Vec3::splat(0.5), &rough_glass, Vec3::Z);
            assert_eq!(s.aov.albedo, Vec3::splat(0.5));
        }
    }
}
