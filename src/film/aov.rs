//! The AOV (arbitrary output variable) vocabulary: one name per ground-truth
//! output, never a bare "depth" (STYLE.md, after Mitsuba 3's `aov.cpp`), and the
//! bit and value conventions of the mask and occlusion images (GROUND_TRUTH.md).

/// Mask bit 0: the pixel sees the sky (no surface hit).
pub const MASK_SKY: u8 = 1 << 0;
/// Mask bit 1: the pixel is covered by rain: the streaks its centre ray meets
/// before the surface blend in with an opacity of at least 1 %
/// (`integrator::rain::MASK_MIN_OPACITY`).
pub const MASK_RAIN: u8 = 1 << 1;
/// Mask bit 2: the first surface is transparent (glass, water).
pub const MASK_TRANSPARENT: u8 = 1 << 2;
/// Mask bit 3: the first surface is mirror-like (puddle, chrome).
pub const MASK_MIRROR: u8 = 1 << 3;

/// Occlusion image value of a left pixel visible in the right view.
pub const OCCLUSION_VISIBLE: u8 = 0;
/// Occlusion image value of a left pixel occluded in (or outside) the right view.
pub const OCCLUSION_OCCLUDED: u8 = 255;

/// One per-pixel output of a view.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Aov {
    /// Tone-mapped 8-bit sRGB radiance.
    Rgb,
    /// Linear HDR radiance (float RGB).
    RgbHdr,
    /// Depth along the optical axis in metres, +inf for sky (float32).
    DepthZ,
    /// Disparity f·B/Z in pixels, 0 for sky (float32).
    Disparity,
    /// World-space unit normal of the first surface (float RGB).
    NormalWorld,
    /// Semantic class id (8-bit).
    Semantic,
    /// Instance id, 0 = none (16-bit).
    Instance,
    /// Bit mask: [`MASK_SKY`], [`MASK_RAIN`], [`MASK_TRANSPARENT`], [`MASK_MIRROR`].
    Mask,
    /// Left-view occlusion for one baseline: [`OCCLUSION_OCCLUDED`] or [`OCCLUSION_VISIBLE`].
    Occlusion,
}

impl Aov {
    /// Every AOV, in a fixed order.
    pub const ALL: [Aov; 9] = [
        Aov::Rgb,
        Aov::RgbHdr,
        Aov::DepthZ,
        Aov::Disparity,
        Aov::NormalWorld,
        Aov::Semantic,
        Aov::Instance,
        Aov::Mask,
        Aov::Occlusion,
    ];

    /// The canonical snake_case name used in metadata and reports.
    pub fn name(self) -> &'static str {
        match self {
            Aov::Rgb => "rgb",
            Aov::RgbHdr => "rgb_hdr",
            Aov::DepthZ => "depth_z",
            Aov::Disparity => "disparity",
            Aov::NormalWorld => "normal_world",
            Aov::Semantic => "semantic",
            Aov::Instance => "instance",
            Aov::Mask => "mask",
            Aov::Occlusion => "occlusion",
        }
    }

    /// Parses a canonical name back; `None` for an unknown name.
    pub fn from_name(name: &str) -> Option<Aov> {
        Aov::ALL.into_iter().find(|aov| aov.name() == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn aov_names_round_trip_and_are_unique() {
        for aov in Aov::ALL {
            assert_eq!(Aov::from_name(aov.name()), Some(aov));
        }
        assert_eq!(Aov::from_name("depth"), None);
    }

    #[test]
    fn mask_bits_are_distinct() {
        // GROUND_TRUTH.md: bit 0 sky, bit 1 rain, bit 2 transparent, bit 3 mirror.
        assert_eq!(MASK_SKY, 0b0001);
        assert_eq!(MASK_RAIN, 0b0010);
        assert_eq!(MASK_TRANSPARENT, 0b0100);
        assert_eq!(MASK_MIRROR, 0b1000);
        // The scene's material bits are the same bits.
        use crate::scene::mask_bits;
        assert_eq!(mask_bits::SKY, MASK_SKY);
        assert_eq!(mask_bits::RAIN, MASK_RAIN);
        assert_eq!(mask_bits::TRANSPARENT, MASK_TRANSPARENT);
        assert_eq!(mask_bits::MIRROR, MASK_MIRROR);
    }
}
