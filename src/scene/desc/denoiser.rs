//! Which denoiser treats a rendered view's surfaces: a render setting
//! (`[render] denoiser`), so it lives with the description; the image side
//! (`denoise`) acts on it.

/// Which denoiser treats a view's surfaces (`[render] denoiser`,
/// `--denoiser`): parallax's own depth-guided filters, Intel Open Image
/// Denoise (`denoise::oidn`), opened at run time where it is installed, or
/// the mean of the two. Fog light (the first-scatter part) is filtered by
/// parallax's filter in every case.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Denoiser {
    /// parallax's own filters (`denoise::surface`, `denoise::direct`).
    #[default]
    Parallax,
    /// Open Image Denoise's ray-tracing filter on the view's radiance,
    /// guided by its first-surface albedo and normal.
    Oidn,
    /// The mean of the two, pixel by pixel: their errors are largely
    /// unlike, so the mean has less than either (docs/reference.md).
    Blend,
}

impl Denoiser {
    /// Every choice, in the order messages list them.
    pub const ALL: [Denoiser; 3] = [Denoiser::Parallax, Denoiser::Oidn, Denoiser::Blend];

    /// The name in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Denoiser::Parallax => "parallax",
            Denoiser::Oidn => "oidn",
            Denoiser::Blend => "blend",
        }
    }

    /// Whether it runs Open Image Denoise (which must then be installed).
    pub fn needs_oidn(self) -> bool {
        self != Denoiser::Parallax
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
            .ok_or_else(|| {
                let names = Denoiser::ALL.map(Denoiser::name);
                let (last, first) = names.split_last().expect("denoisers");
                format!(
                    "unknown denoiser '{s}' (expected {} or {last})",
                    first.join(", ")
                )
            })
    }
}
