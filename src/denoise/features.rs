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

/// Which denoiser treats a view's surfaces (`[render] denoiser`,
/// `--denoiser`): parallax's own depth-guided filters, or Intel Open Image
/// Denoise (`oidn/`), opened at run time where it is installed. Fog light
/// (the first-scatter part) is filtered by parallax's filter either way.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Denoiser {
    /// parallax's filters (`surface.rs`, `direct.rs`).
    #[default]
    Parallax,
    /// Open Image Denoise's ray-tracing filter on the view's radiance,
    /// guided by its first-surface albedo and normal.
    Oidn,
}

impl Denoiser {
    /// Every choice, in the order messages list them.
    pub const ALL: [Denoiser; 2] = [Denoiser::Parallax, Denoiser::Oidn];

    /// The name in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Denoiser::Parallax => "parallax",
            Denoiser::Oidn => "oidn",
        }
    }

    /// Whether this is the default (the description leaves it out).
    pub fn is_default(&self) -> bool {
        *self == Denoiser::default()
    }
}

impl std::fmt::Display for Denoiser {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for Denoiser {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Denoiser::ALL
            .into_iter()
            .find(|d| d.name() == s)
            .ok_or_else(|| format!("unknown denoiser '{s}' (expected parallax or oidn)"))
    }
}
