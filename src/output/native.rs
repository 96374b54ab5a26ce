//! The native writer's two halves, so that a map declared in the registry
//! needs no writing code of its own: where a declared map's pixels live in a
//! rendered frame ([`map_pixels`]) and how pixels are written in a declared
//! format ([`write_map`]).

use std::borrow::Cow;
use std::io;
use std::path::Path;

use glam::Vec3;

use super::atomic::invalid_input;
use super::registry::{Format, Map, Pixel};
use super::{
    write_exr_f32_gray, write_exr_rgb_f32, write_pfm_gray, write_png_gray16, write_png_gray8,
    write_png_rgb8,
};
use crate::film::tonemap_to_srgb8;
use crate::render::FrameOutput;

/// The pixels of one map of one frame, row-major, top row first.
#[derive(Clone, Debug, PartialEq)]
pub enum MapPixels<'a> {
    /// One byte per pixel.
    Gray8(&'a [u8]),
    /// One 16-bit value per pixel.
    Gray16(&'a [u16]),
    /// One float32 per pixel.
    GrayF32(Cow<'a, [f32]>),
    /// Three sRGB bytes per pixel.
    Rgb8(Vec<u8>),
    /// One linear float RGB triple per pixel.
    RgbF32(&'a [Vec3]),
}

impl MapPixels<'_> {
    /// The pixel type these pixels are.
    pub fn pixel(&self) -> Pixel {
        match self {
            MapPixels::Gray8(_) => Pixel::Gray8,
            MapPixels::Gray16(_) => Pixel::Gray16,
            MapPixels::GrayF32(_) => Pixel::GrayF32,
            MapPixels::Rgb8(_) => Pixel::Rgb8,
            MapPixels::RgbF32(_) => Pixel::RgbF32,
        }
    }
}

/// The pixels of `map` in `out`; `b` is the baseline index of a
/// per-baseline map (ignored for the others). `None` when the frame has no
/// such pixels: the images of an spp-0 render, or a baseline it lacks.
pub fn map_pixels(map: Map, out: &FrameOutput, b: usize) -> Option<MapPixels<'_>> {
    use MapPixels::*;
    let gt = out.baselines.get(b);
    let srgb = |view: usize| {
        let film = out.images.get(view)?;
        Some(Rgb8(tonemap_to_srgb8(film, out.exposure_scale)))
    };
    let hdr = |view: usize| out.images.get(view).map(|film| RgbF32(&film.rgb));
    match map {
        Map::LeftRgb => srgb(0),
        Map::LeftRgbHdr => hdr(0),
        Map::LeftAlbedo => out.aov.as_ref().map(|a| RgbF32(&a.albedo)),
        Map::LeftAovNormal => out.aov.as_ref().map(|a| RgbF32(&a.normal)),
        Map::Depth => Some(GrayF32(Cow::Owned(out.left.depth_z_f32()))),
        Map::Normal => Some(RgbF32(&out.left.normal_world)),
        Map::Semantic => Some(Gray8(&out.left.semantic)),
        Map::Instance => Some(Gray16(&out.left.instance)),
        Map::Mask => Some(Gray8(&out.left.mask)),
        Map::Disparity => gt.map(|g| GrayF32(Cow::Borrowed(&g.disparity_left))),
        Map::RightDepth => gt.map(|g| GrayF32(Cow::Borrowed(&g.depth_right))),
        Map::RightDisparity => gt.map(|g| GrayF32(Cow::Borrowed(&g.disparity_right))),
        Map::Occlusion => gt.map(|g| Gray8(&g.occlusion)),
        Map::RightRgb => srgb(1 + b),
        Map::RightRgbHdr => hdr(1 + b),
    }
}

/// Writes `w × h` pixels to `path` in `format`, atomically; an
/// `InvalidInput` error for pixels the format cannot hold.
pub fn write_map(
    path: &Path,
    w: usize,
    h: usize,
    format: Format,
    pixels: &MapPixels,
) -> io::Result<()> {
    match (format, pixels) {
        (Format::Png, MapPixels::Gray8(d)) => write_png_gray8(path, w, h, d),
        (Format::Png, MapPixels::Gray16(d)) => write_png_gray16(path, w, h, d),
        (Format::Png, MapPixels::Rgb8(d)) => write_png_rgb8(path, w, h, d),
        (Format::Exr, MapPixels::GrayF32(d)) => write_exr_f32_gray(path, w, h, d),
        (Format::Exr, MapPixels::RgbF32(d)) => write_exr_rgb_f32(path, w, h, d),
        (Format::Pfm, MapPixels::GrayF32(d)) => write_pfm_gray(path, w, h, d),
        (format, p) => Err(invalid_input(format!(
            "{}: {:?} pixels cannot be written as {:?}",
            path.display(),
            p.pixel(),
            format
        ))),
    }
}
