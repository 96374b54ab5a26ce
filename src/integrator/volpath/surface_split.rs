//! Bookkeeping of a Lambertian first surface vertex x1's light for the
//! denoiser, split as a medium-free path splits it (`path.rs`): x1's
//! next-event estimates but the suns' are its direct light
//! (`DenoiseSample::l_direct`); everything the path gathers after them
//! (fog light, and light by way of other surfaces) is its indirect light
//! (`DenoiseSample::l_surf`). Both are filtered as ratios to β·ρ at x1.
//! Left unfiltered, light by way of other surfaces kept a hazy scene's
//! indirect light as noisy as plain path tracing, and a rare path to the
//! sun by way of a window stood out of fog as a white speck.

use glam::Vec3;

/// The split at x1, once the path has shaded it.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct SurfaceSplit {
    /// β(x1)·ρ(x1) (zero: no Lambertian x1 on this path).
    pub rho: Vec3,
    /// x1's next-event estimates but the suns'.
    pub direct: Vec3,
    /// Path radiance once x1's own light was in.
    after_x1: Option<Vec3>,
}

impl SurfaceSplit {
    /// Records x1 shaded: `rho` = β·albedo; the path radiance `before` its
    /// next-event estimates (its emission in) and `after` them; `sun`
    /// their suns' part (left as traced: sharp, nearly noise-free).
    pub fn at_first_vertex(rho: Vec3, before: Vec3, sun: Vec3, after: Vec3) -> SurfaceSplit {
        SurfaceSplit {
            rho,
            direct: after - before - sun,
            after_x1: Some(after),
        }
    }

    /// Whether the path had a Lambertian x1.
    pub fn is_split(&self) -> bool {
        self.after_x1.is_some()
    }

    /// x1's indirect light given the path's final radiance `l`.
    pub fn l_surf(&self, l: Vec3) -> Vec3 {
        self.after_x1.map_or(Vec3::ZERO, |a| l - a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn direct_is_the_next_event_light_but_the_suns_and_indirect_what_follows() {
        let (before, sun, after) = (Vec3::splat(1.0), Vec3::splat(2.0), Vec3::splat(7.0));
        let s = SurfaceSplit::at_first_vertex(Vec3::splat(0.5), before, sun, after);
        assert!(s.is_split());
        // 7 − 1 − 2: the sky's and lamps' estimates.
        assert_eq!(s.direct, Vec3::splat(4.0));
        assert_eq!(s.l_surf(Vec3::splat(10.0)), Vec3::splat(3.0));
        // A path without x1 hands nothing over.
        let none = SurfaceSplit::default();
        assert!(!none.is_split());
        assert_eq!(none.l_surf(Vec3::splat(10.0)), Vec3::ZERO);
    }
}
