//! Which denoiser treats a rendered view's surfaces: a render setting
//! (`[render] denoiser`), so it lives with the description; the image side
//! (`denoise`) acts on it.

/// Which denoiser treats a view's surfaces (`[render] denoiser`,
/// `--denoiser`): parallax's own depth-guided filters, or Intel Open Image
/// Denoise (`denoise::oidn`), opened at run time where it is installed. Fog light
/// (the first-scatter part) is filtered by parallax's filter either way.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Denoiser {
    /// parallax's own filters (`denoise::surface`, `denoise::direct`).
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
