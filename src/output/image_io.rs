//! PNG and JPEG writers and readers (the only file naming the `image` crate).
//!
//! PNG is lossless: 8-bit sRGB RGB, 8-bit grey (semantic ids, masks, occlusion)
//! and 16-bit grey (instance ids, StereoCarla depth in cm). JPEG exists only for
//! the StereoCarla compatibility layout. Buffers are row-major, top row first,
//! RGB interleaved.

use super::atomic::{check_len, invalid_data, invalid_input, read_file, write_atomic};
use super::atomic::{Access, OutputError};
use image::codecs::jpeg::JpegEncoder;
use image::codecs::png::PngEncoder;
use image::{DynamicImage, ExtendedColorType, ImageEncoder, ImageFormat};
use std::io;
use std::path::Path;

fn image_to_io(e: image::ImageError) -> io::Error {
    match e {
        image::ImageError::IoError(e) => e,
        other => invalid_data(other.to_string()),
    }
}

fn dims_u32(w: usize, h: usize) -> io::Result<(u32, u32)> {
    match (u32::try_from(w), u32::try_from(h)) {
        (Ok(w), Ok(h)) => Ok((w, h)),
        _ => Err(invalid_input(format!("image size {w}×{h} too large"))),
    }
}

/// Encodes `bytes` (already in the layout `color` expects, native-endian for
/// 16-bit) as PNG and writes it atomically.
fn write_png(
    path: &Path,
    w: usize,
    h: usize,
    bytes: &[u8],
    color: ExtendedColorType,
) -> io::Result<()> {
    let encoded = (|| {
        let (w32, h32) = dims_u32(w, h)?;
        let mut buf = Vec::new();
        PngEncoder::new(&mut buf)
            .write_image(bytes, w32, h32, color)
            .map_err(image_to_io)?;
        Ok(buf)
    })()
    .map_err(|e| OutputError::wrap(path, Access::Write, e))?;
    write_atomic(path, &encoded)
}

/// Writes 8-bit sRGB RGB (`3·w·h` bytes, interleaved) as PNG, atomically.
pub fn write_png_rgb8(path: &Path, w: usize, h: usize, rgb: &[u8]) -> io::Result<()> {
    check_len(rgb.len(), w, h, 3).map_err(|e| OutputError::wrap(path, Access::Write, e))?;
    write_png(path, w, h, rgb, ExtendedColorType::Rgb8)
}

/// Writes 8-bit grey (`w·h` bytes) as PNG, atomically.
pub fn write_png_gray8(path: &Path, w: usize, h: usize, gray: &[u8]) -> io::Result<()> {
    check_len(gray.len(), w, h, 1).map_err(|e| OutputError::wrap(path, Access::Write, e))?;
    write_png(path, w, h, gray, ExtendedColorType::L8)
}

/// Writes 16-bit grey (`w·h` values) as PNG, atomically.
pub fn write_png_gray16(path: &Path, w: usize, h: usize, gray: &[u16]) -> io::Result<()> {
    check_len(gray.len(), w, h, 1).map_err(|e| OutputError::wrap(path, Access::Write, e))?;
    let bytes: Vec<u8> = gray.iter().flat_map(|v| v.to_ne_bytes()).collect();
    write_png(path, w, h, &bytes, ExtendedColorType::L16)
}

/// Writes 8-bit sRGB RGB (`3·w·h` bytes) as baseline JPEG with `quality` in
/// 1..=100, atomically. Lossy: only for the StereoCarla layout.
pub fn write_jpeg_rgb8(path: &Path, w: usize, h: usize, rgb: &[u8], quality: u8) -> io::Result<()> {
    let encoded = (|| {
        check_len(rgb.len(), w, h, 3)?;
        if !(1..=100).contains(&quality) {
            return Err(invalid_input(format!(
                "JPEG quality {quality} not in 1..=100"
            )));
        }
        let (w32, h32) = dims_u32(w, h)?;
        let mut buf = Vec::new();
        JpegEncoder::new_with_quality(&mut buf, quality)
            .write_image(rgb, w32, h32, ExtendedColorType::Rgb8)
            .map_err(image_to_io)?;
        Ok(buf)
    })()
    .map_err(|e| OutputError::wrap(path, Access::Write, e))?;
    write_atomic(path, &encoded)
}

/// Decodes a file of the given format; errors name the path.
fn read_image(path: &Path, format: ImageFormat) -> io::Result<DynamicImage> {
    let bytes = read_file(path)?;
    image::load_from_memory_with_format(&bytes, format)
        .map_err(|e| OutputError::wrap(path, Access::Read, image_to_io(e)))
}

/// The error for a file whose pixel type is not the one asked for.
fn wrong_type(path: &Path, want: &str, got: &DynamicImage) -> io::Error {
    let msg = format!("expected {want}, found {:?}", got.color());
    OutputError::wrap(path, Access::Read, invalid_data(msg))
}

/// Reads an 8-bit RGB PNG; returns `(w, h, rgb)` interleaved. Any other pixel
/// type is an error (no silent conversion of data).
pub fn read_png_rgb8(path: &Path) -> io::Result<(usize, usize, Vec<u8>)> {
    match read_image(path, ImageFormat::Png)? {
        DynamicImage::ImageRgb8(img) => {
            Ok((img.width() as usize, img.height() as usize, img.into_raw()))
        }
        other => Err(wrong_type(path, "8-bit RGB", &other)),
    }
}

/// Reads an 8-bit grey PNG; returns `(w, h, values)`. Any other pixel type is
/// an error.
pub fn read_png_gray8(path: &Path) -> io::Result<(usize, usize, Vec<u8>)> {
    match read_image(path, ImageFormat::Png)? {
        DynamicImage::ImageLuma8(img) => {
            Ok((img.width() as usize, img.height() as usize, img.into_raw()))
        }
        other => Err(wrong_type(path, "8-bit grey", &other)),
    }
}

/// Reads a 16-bit grey PNG; returns `(w, h, values)`. Any other pixel type is
/// an error.
pub fn read_png_gray16(path: &Path) -> io::Result<(usize, usize, Vec<u16>)> {
    match read_image(path, ImageFormat::Png)? {
        DynamicImage::ImageLuma16(img) => {
            Ok((img.width() as usize, img.height() as usize, img.into_raw()))
        }
        other => Err(wrong_type(path, "16-bit grey", &other)),
    }
}

/// Reads a JPEG as 8-bit RGB (grey JPEGs are expanded); returns `(w, h, rgb)`.
pub fn read_jpeg_rgb8(path: &Path) -> io::Result<(usize, usize, Vec<u8>)> {
    let img = read_image(path, ImageFormat::Jpeg)?.into_rgb8();
    Ok((img.width() as usize, img.height() as usize, img.into_raw()))
}
