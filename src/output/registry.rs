//! The output registry: every per-pixel map a frame writes in the native
//! layout, declared once with its name, view, folder, pixel type and file
//! format. The native writer (`output::frame`), the path functions and the
//! recogniser of native paths (`output::layout`), the dataset's ownership
//! rule, `verify`, `preview` and `eval` all read these declarations; adding a
//! map is one entry here (plus the code that computes it and the arm of
//! `output::native::map_pixels` that hands it to the writer).

/// One map of the registry (the key of its declaration in [`MAPS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Map {
    /// Tone-mapped 8-bit sRGB left image.
    LeftRgb,
    /// Linear HDR radiance of the left view (only with `--hdr`).
    LeftRgbHdr,
    /// Mean albedo of the left view's first visible surfaces, an auxiliary
    /// image for an external denoiser (only with `--hdr`; `render::AovImages`).
    LeftAlbedo,
    /// Mean shading normal of the left view's first visible surfaces, world
    /// space (only with `--hdr`; unlike `Normal`, seen through mirrors and glass).
    LeftAovNormal,
    /// Left depth_z along the optical axis, metres, +inf for sky.
    Depth,
    /// World-space unit normal of the first surface (zero for sky).
    Normal,
    /// Semantic class id.
    Semantic,
    /// Instance id, 0 = none.
    Instance,
    /// Mask bits (`crate::scene::mask_bits`).
    Mask,
    /// Left-view disparity f·B/Z for one baseline, px, 0 for sky.
    Disparity,
    /// Right-view depth_z for one baseline, metres.
    RightDepth,
    /// Right-view disparity for one baseline, px.
    RightDisparity,
    /// Left-view occlusion for one baseline: [`OCCLUSION_OCCLUDED`] or [`OCCLUSION_VISIBLE`].
    Occlusion,
    /// Tone-mapped 8-bit sRGB right image of one baseline.
    RightRgb,
    /// Linear HDR radiance of one baseline's right view (only with `--hdr`).
    RightRgbHdr,
}

/// The camera a map is seen from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum View {
    /// The left (reference) camera.
    Left,
    /// The right camera of the map's baseline.
    Right,
}

/// Whether a map is exact ground truth or a rendered image; the native
/// writer writes every ground-truth map before the images.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Exact, from the ground-truth pass.
    Truth,
    /// Path-traced radiance (absent when rendered with spp 0).
    Image,
}

/// The pixel type of a map as stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pixel {
    /// One unsigned byte.
    Gray8,
    /// One unsigned 16-bit value.
    Gray16,
    /// One float32.
    GrayF32,
    /// Three bytes, sRGB.
    Rgb8,
    /// Three float32, linear.
    RgbF32,
}

/// The file format of a map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Lossless PNG.
    Png,
    /// OpenEXR, lossless compression.
    Exr,
    /// Portable float map.
    Pfm,
}

impl Format {
    /// The files' extension.
    pub fn ext(self) -> &'static str {
        match self {
            Format::Png => "png",
            Format::Exr => "exr",
            Format::Pfm => "pfm",
        }
    }
}

/// The declaration of one map.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MapSpec {
    /// The key.
    pub map: Map,
    /// Canonical snake_case name used in reports.
    pub name: &'static str,
    /// The camera it is seen from.
    pub view: View,
    /// Written once per baseline, in `baseline_XXX/` (else in `left/`).
    pub per_baseline: bool,
    /// Ground truth or image.
    pub kind: Kind,
    /// Stored pixel type.
    pub pixel: Pixel,
    /// File format.
    pub format: Format,
    /// Folder below `left/` or `baseline_XXX/`.
    pub folder: &'static str,
    /// Written only when HDR output is asked for (`--hdr`, `hdr = true`).
    pub hdr_only: bool,
}

const fn truth(map: Map, name: &'static str, folder: &'static str) -> MapSpec {
    MapSpec {
        map,
        name,
        view: View::Left,
        per_baseline: false,
        kind: Kind::Truth,
        pixel: Pixel::Gray8,
        format: Format::Png,
        folder,
        hdr_only: false,
    }
}

/// Every map, in the order the native writer writes them within one folder.
pub const MAPS: [MapSpec; 15] = [
    MapSpec {
        pixel: Pixel::GrayF32,
        format: Format::Exr,
        ..truth(Map::Depth, "depth_z", "depth")
    },
    MapSpec {
        pixel: Pixel::RgbF32,
        format: Format::Exr,
        ..truth(Map::Normal, "normal_world", "normal")
    },
    truth(Map::Semantic, "semantic", "semantic"),
    MapSpec {
        pixel: Pixel::Gray16,
        ..truth(Map::Instance, "instance", "instance")
    },
    truth(Map::Mask, "mask", "mask"),
    MapSpec {
        per_baseline: true,
        pixel: Pixel::GrayF32,
        format: Format::Pfm,
        ..truth(Map::Disparity, "disparity", "disp")
    },
    MapSpec {
        view: View::Right,
        per_baseline: true,
        pixel: Pixel::GrayF32,
        format: Format::Exr,
        ..truth(Map::RightDepth, "depth_z_right", "depth_right")
    },
    MapSpec {
        view: View::Right,
        per_baseline: true,
        pixel: Pixel::GrayF32,
        format: Format::Pfm,
        ..truth(Map::RightDisparity, "disparity_right", "disp_right")
    },
    MapSpec {
        per_baseline: true,
        ..truth(Map::Occlusion, "occlusion", "occ")
    },
    MapSpec {
        kind: Kind::Image,
        pixel: Pixel::Rgb8,
        ..truth(Map::LeftRgb, "rgb", "rgb")
    },
    MapSpec {
        kind: Kind::Image,
        pixel: Pixel::RgbF32,
        format: Format::Exr,
        hdr_only: true,
        ..truth(Map::LeftRgbHdr, "rgb_hdr", "rgb_hdr")
    },
    MapSpec {
        kind: Kind::Image,
        pixel: Pixel::RgbF32,
        format: Format::Exr,
        hdr_only: true,
        ..truth(Map::LeftAlbedo, "albedo", "albedo")
    },
    MapSpec {
        kind: Kind::Image,
        pixel: Pixel::RgbF32,
        format: Format::Exr,
        hdr_only: true,
        ..truth(Map::LeftAovNormal, "aov_normal", "aov_normal")
    },
    MapSpec {
        view: View::Right,
        per_baseline: true,
        kind: Kind::Image,
        pixel: Pixel::Rgb8,
        ..truth(Map::RightRgb, "rgb_right", "rgb")
    },
    MapSpec {
        view: View::Right,
        per_baseline: true,
        kind: Kind::Image,
        pixel: Pixel::RgbF32,
        format: Format::Exr,
        hdr_only: true,
        ..truth(Map::RightRgbHdr, "rgb_hdr_right", "rgb_hdr")
    },
];

/// The folder of the left view's maps (`left/<folder>/`); per-baseline
/// maps go to `baseline_XXX/<folder>/` (`output::baseline_dir_name`).
pub const LEFT_DIR: &str = "left";
/// The folder of the per-frame camera files (`cameras/NNNNNN.json`).
pub const CAMERAS_DIR: &str = "cameras";

/// Occlusion map value of a left pixel visible in the right view.
pub const OCCLUSION_VISIBLE: u8 = 0;
/// Occlusion map value of a left pixel occluded in (or outside) the right view.
pub const OCCLUSION_OCCLUDED: u8 = 255;

impl Map {
    /// The declaration of this map.
    pub fn spec(self) -> &'static MapSpec {
        MAPS.iter()
            .find(|s| s.map == self)
            .expect("every map is declared in MAPS")
    }
}

/// The maps written in `left/` (`per_baseline == false`) or in each
/// `baseline_XXX/` (`true`), in writing order.
pub fn maps_in(per_baseline: bool) -> impl Iterator<Item = &'static MapSpec> {
    MAPS.iter().filter(move |s| s.per_baseline == per_baseline)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_map_is_declared_once_with_a_unique_name_and_folder() {
        for (i, s) in MAPS.iter().enumerate() {
            assert_eq!(s.map.spec(), s, "{}", s.name);
            for t in &MAPS[..i] {
                assert_ne!(t.map, s.map, "{} declared twice", s.name);
                assert_ne!(t.name, s.name);
                let same_place = t.per_baseline == s.per_baseline && t.folder == s.folder;
                assert!(!same_place, "{} and {} share a folder", t.name, s.name);
            }
        }
    }

    #[test]
    fn mask_bits_are_ground_truth_mds() {
        // GROUND_TRUTH.md: bit 0 sky, bit 1 rain, bit 2 transparent, bit 3
        // mirror; defined once, where scene building sets them.
        use crate::scene::mask_bits::{MIRROR, RAIN, SKY, TRANSPARENT};
        assert_eq!(
            [SKY, RAIN, TRANSPARENT, MIRROR],
            [0b0001, 0b0010, 0b0100, 0b1000]
        );
        assert_eq!((OCCLUSION_VISIBLE, OCCLUSION_OCCLUDED), (0, 255));
    }

    #[test]
    fn pixel_types_fit_their_formats() {
        for s in MAPS {
            let ok = match s.format {
                Format::Png => matches!(s.pixel, Pixel::Gray8 | Pixel::Gray16 | Pixel::Rgb8),
                Format::Exr => matches!(s.pixel, Pixel::GrayF32 | Pixel::RgbF32),
                Format::Pfm => s.pixel == Pixel::GrayF32,
            };
            assert!(ok, "{}: {:?} in {:?}", s.name, s.pixel, s.format);
            // Right-view maps only exist per baseline.
            assert!(s.view == View::Left || s.per_baseline, "{}", s.name);
        }
    }
}
