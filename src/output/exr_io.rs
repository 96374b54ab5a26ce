//! OpenEXR writers and readers (the only file naming the `exr` crate).
//!
//! Depth Z is one float32 channel named "Z"; linear radiance and world normals
//! are float32 "R", "G", "B". Compression is ZIP over 16 scanlines (lossless,
//! every f32 bit pattern kept, +inf included) in increasing line order, encoded
//! on the calling thread, so the bytes are a pure function of the pixels.

use super::atomic::{check_len, invalid_data, read_file, write_atomic, Access, OutputError};
use exr::prelude::*;
use glam::Vec3;
use std::io::{self, Cursor};
use std::path::Path;

fn exr_to_io(e: exr::error::Error) -> io::Error {
    match e {
        exr::error::Error::Io(e) => e,
        other => invalid_data(other.to_string()),
    }
}

/// Runs an EXR encoder into memory (on this thread), then writes atomically.
fn write_encoded_atomic(
    path: &Path,
    encode: impl FnOnce(&mut Cursor<Vec<u8>>) -> exr::error::UnitResult,
) -> io::Result<()> {
    let mut buf = Cursor::new(Vec::new());
    encode(&mut buf).map_err(|e| OutputError::wrap(path, Access::Write, exr_to_io(e)))?;
    write_atomic(path, buf.get_ref())
}

/// Writes a single-channel float32 image (row-major, top row first) as EXR with
/// one channel "Z" (depth_z in metres, +inf for sky), atomically.
pub fn write_exr_f32_gray(path: &Path, w: usize, h: usize, data: &[f32]) -> io::Result<()> {
    check_len(data.len(), w, h, 1).map_err(|e| OutputError::wrap(path, Access::Write, e))?;
    let channels = SpecificChannels::build()
        .with_channel("Z")
        .with_pixel_fn(|p: Vec2<usize>| (data[p.y() * w + p.x()],));
    let image = Image::from_encoded_channels((w, h), Encoding::SMALL_LOSSLESS, channels);
    write_encoded_atomic(path, |buf| image.write().non_parallel().to_buffered(buf))
}

/// Writes a float32 RGB image (row-major, top row first; linear radiance or
/// world-space normals) as EXR channels "R", "G", "B", atomically.
pub fn write_exr_rgb_f32(path: &Path, w: usize, h: usize, data: &[Vec3]) -> io::Result<()> {
    check_len(data.len(), w, h, 1).map_err(|e| OutputError::wrap(path, Access::Write, e))?;
    let channels = SpecificChannels::rgb(|p: Vec2<usize>| {
        let v = data[p.y() * w + p.x()];
        (v.x, v.y, v.z)
    });
    let image = Image::from_encoded_channels((w, h), Encoding::SMALL_LOSSLESS, channels);
    write_encoded_atomic(path, |buf| image.write().non_parallel().to_buffered(buf))
}

/// Reads the "Z" channel of an EXR file as float32; returns `(w, h, data)`,
/// row-major, top row first. Errors name the path.
pub fn read_exr_f32_gray(path: &Path) -> io::Result<(usize, usize, Vec<f32>)> {
    let bytes = read_file(path)?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .specific_channels()
        .required("Z")
        .collect_pixels(
            |size: Vec2<usize>, _| (size.width(), vec![0.0f32; size.area()]),
            |(w, data): &mut (usize, Vec<f32>), p: Vec2<usize>, (z,): (f32,)| {
                data[p.y() * *w + p.x()] = z;
            },
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| OutputError::wrap(path, Access::Read, exr_to_io(e)))?;
    let size = image.layer_data.size;
    let (_, data) = image.layer_data.channel_data.pixels;
    Ok((size.width(), size.height(), data))
}

/// Reads the "R", "G", "B" channels of an EXR file as float32; returns
/// `(w, h, data)`, row-major, top row first. Errors name the path.
pub fn read_exr_rgb_f32(path: &Path) -> io::Result<(usize, usize, Vec<Vec3>)> {
    let bytes = read_file(path)?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgb_channels(
            |size: Vec2<usize>, _| (size.width(), vec![Vec3::ZERO; size.area()]),
            |(w, data): &mut (usize, Vec<Vec3>), p: Vec2<usize>, (r, g, b): (f32, f32, f32)| {
                data[p.y() * *w + p.x()] = Vec3::new(r, g, b);
            },
        )
        .first_valid_layer()
        .all_attributes()
        .non_parallel()
        .from_buffered(Cursor::new(bytes))
        .map_err(|e| OutputError::wrap(path, Access::Read, exr_to_io(e)))?;
    let size = image.layer_data.size;
    let (_, data) = image.layer_data.channel_data.pixels;
    Ok((size.width(), size.height(), data))
}
