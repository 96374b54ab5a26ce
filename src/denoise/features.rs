//! The one switch board of the image side's biased features: what a
//! scene's filter flags turn on, and what `--no-filter` (the scene's
//! `filter_indirect` and `filter_inscatter` off) turns off together.

use crate::scene::Scene;

/// Which image-side features a render uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Features {
    /// Filter the direct light (sky, lamps) on the first diffuse surface
    /// and all the light of a glossy one (`direct.rs`; it needs the
    /// indirect filter's split, or with a medium the fog filter's, which
    /// splits glossy first surfaces only).
    pub direct: bool,
}

impl Features {
    /// Every feature off: plain path tracing.
    pub const OFF: Features = Features { direct: false };

    /// The features `scene` asks for: on when it filters indirect light
    /// or fog light, off under `--no-filter`.
    pub fn for_scene(scene: &Scene) -> Features {
        Features {
            direct: scene.filter_indirect || scene.filter_inscatter,
        }
    }
}
