//! Independent readers of written files for read-back tests: the `exr` and
//! `image` crates called directly and a small PFM parser, not parallax's own
//! readers, so that a mistake shared by a writer and its reader cannot hide.
//! Each panics naming the file when it is not of the expected kind.

use std::collections::BTreeMap;
use std::path::Path;

use image::DynamicImage;

/// Every channel of the first layer of an EXR file as float32, row-major,
/// top row first: (width, height, channels by name).
pub fn exr_channels(path: &Path) -> (usize, usize, BTreeMap<String, Vec<f32>>) {
    use exr::prelude::{read_first_flat_layer_from_file, FlatSamples};
    let image =
        read_first_flat_layer_from_file(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let layer = image.layer_data;
    let channels = layer
        .channel_data
        .list
        .into_iter()
        .map(|c| match c.sample_data {
            FlatSamples::F32(v) => (c.name.to_string(), v),
            other => panic!(
                "{}: channel {} is not f32: {other:?}",
                path.display(),
                c.name
            ),
        })
        .collect();
    (layer.size.width(), layer.size.height(), channels)
}

/// One named float32 channel of an EXR file: (width, height, samples).
pub fn exr_channel(path: &Path, name: &str) -> (usize, usize, Vec<f32>) {
    let (w, h, mut ch) = exr_channels(path);
    let v = ch
        .remove(name)
        .unwrap_or_else(|| panic!("{}: no channel {name}", path.display()));
    (w, h, v)
}

fn decode(path: &Path) -> DynamicImage {
    image::ImageReader::open(path)
        .and_then(|r| r.with_guessed_format())
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .decode()
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// An 8-bit greyscale PNG: (width, height, pixels).
pub fn png_gray8(path: &Path) -> (usize, usize, Vec<u8>) {
    match decode(path) {
        DynamicImage::ImageLuma8(b) => (b.width() as usize, b.height() as usize, b.into_raw()),
        other => panic!("{}: {:?}, expected L8", path.display(), other.color()),
    }
}

/// A 16-bit greyscale PNG: (width, height, pixels).
pub fn png_gray16(path: &Path) -> (usize, usize, Vec<u16>) {
    match decode(path) {
        DynamicImage::ImageLuma16(b) => (b.width() as usize, b.height() as usize, b.into_raw()),
        other => panic!("{}: {:?}, expected L16", path.display(), other.color()),
    }
}

/// An 8-bit RGB image (PNG or JPEG): (width, height, interleaved RGB).
pub fn rgb8(path: &Path) -> (usize, usize, Vec<u8>) {
    match decode(path) {
        DynamicImage::ImageRgb8(b) => (b.width() as usize, b.height() as usize, b.into_raw()),
        other => panic!("{}: {:?}, expected RGB8", path.display(), other.color()),
    }
}

/// A greyscale PFM ("Pf", rows stored bottom-up, negative scale = little
/// endian): (width, height, values row-major, top row first).
pub fn pfm(path: &Path) -> (usize, usize, Vec<f32>) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    // The header is three whitespace-terminated tokens after "Pf".
    let mut fields = Vec::new();
    let mut at = 0;
    while fields.len() < 4 {
        while bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        let start = at;
        while !bytes[at].is_ascii_whitespace() {
            at += 1;
        }
        fields.push(String::from_utf8_lossy(&bytes[start..at]).into_owned());
    }
    at += 1; // the single whitespace byte ending the header
    assert_eq!(fields[0], "Pf", "{}: not a greyscale PFM", path.display());
    let (w, h): (usize, usize) = (fields[1].parse().unwrap(), fields[2].parse().unwrap());
    let scale: f32 = fields[3].parse().unwrap();
    let body = &bytes[at..];
    assert_eq!(body.len(), w * h * 4, "{}: body size", path.display());
    let mut out = vec![0.0f32; w * h];
    for (k, c) in body.chunks_exact(4).enumerate() {
        let b: [u8; 4] = c.try_into().unwrap();
        let v = if scale < 0.0 {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        };
        let (row_from_bottom, x) = (k / w, k % w);
        out[(h - 1 - row_from_bottom) * w + x] = v;
    }
    (w, h, out)
}

/// Bit patterns, so that comparisons see −0, +inf and NaN payloads.
pub fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

/// Asserts that `got` equals `want` element for element; on failure names
/// `what`, the number of differing elements and the first of them (not the
/// whole buffers).
pub fn same<T: PartialEq + std::fmt::Debug>(got: &[T], want: &[T], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: length");
    let diff: Vec<usize> = (0..got.len()).filter(|&k| got[k] != want[k]).collect();
    if let Some(&k) = diff.first() {
        panic!(
            "{what}: {} of {} differ, first at {k}: {:?}, expected {:?}",
            diff.len(),
            got.len(),
            got[k],
            want[k]
        );
    }
}
