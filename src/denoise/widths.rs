//! The denoiser's filter widths and their defaults per view size.

/// Filter widths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Widths {
    /// Spatial σ in pixels (> 0): the à-trous cascade gets as many levels
    /// as its σ needs to reach this.
    pub sigma_px: f32,
    /// Range σ on the pixel-centre opacity difference (> 0).
    pub sigma_opacity: f32,
    /// Range σ on |Δ ln depth_z| (the relative depth step) between two surface pixels (> 0).
    pub sigma_depth_rel: f32,
    /// à-trous levels of the direct-light component (`direct.rs`); 0 leaves
    /// direct light as traced.
    pub direct_levels: u32,
    /// Edge-stopping width, in standard deviations of its own noise, of the
    /// light on the first surface (`surface.rs`), filtered with
    /// the edge-stopping kernel at [`DIRECT_LEVELS`](super::direct::DIRECT_LEVELS);
    /// `None` filters it on geometry alone at `sigma_px` (renders use
    /// `Some`: [`Widths::for_width`]).
    pub surface_sigma_lum: Option<f32>,
}

impl Widths {
    /// Every rendered view's widths, for a view `width` pixels wide: the
    /// spatial σ scales with resolution (a fixed angular footprint) and is
    /// at least one pixel, so tiny test images still filter; indirect light
    /// on the first surface (fog light included) is filtered with
    /// edge-stopping on its own noise ([`INDIRECT_SIGMA_LUM`]).
    pub fn for_width(width: usize) -> Widths {
        Widths {
            sigma_px: (width as f32 / 160.0 * SIGMA_PX_AT_160).max(1.0),
            sigma_opacity: 0.1,
            sigma_depth_rel: 0.3,
            direct_levels: super::direct::DIRECT_LEVELS,
            surface_sigma_lum: Some(INDIRECT_SIGMA_LUM),
        }
    }
}

/// Spatial σ at 160 pixels across (8 px at 320): the fog light is smooth
/// and textureless, so it takes a wide kernel; where the fog hides a close
/// façade its few samples leave blotches several pixels across, which a
/// narrower one leaves in (measured in docs/reference.md, session 35).
const SIGMA_PX_AT_160: f32 = 4.0;

/// Edge-stopping width of indirect light on the first surface: its light
/// varies from pixel to pixel (corners, recesses, the shade under
/// balconies) at about its noise level, so a test narrower than the direct
/// light's keeps that variation.
const INDIRECT_SIGMA_LUM: f32 = 1.5;
