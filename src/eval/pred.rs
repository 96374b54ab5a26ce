//! Readers for predicted disparity maps (the only home of `npyz`): PFM, 16-bit
//! KITTI PNG (value/256, 0 = no estimate → NaN, i.e. missing), float EXR (one channel) and
//! NumPy `.npy` (2-D float32 or float64, C or Fortran order). Every reader
//! returns `(w, h, disparity_px)` row-major, top row first; errors name the path.

use std::io;
use std::path::{Path, PathBuf};

use crate::output::{read_exr_f32_gray, read_file, read_pfm_gray, read_png_gray16};
use crate::output::{Access, OutputError};

/// Extensions tried for a prediction, in this order.
pub const PREDICTION_EXTENSIONS: [&str; 4] = ["pfm", "png", "exr", "npy"];

/// The first existing prediction file for `stem_path` (any extension of
/// [`PREDICTION_EXTENSIONS`]), or `None`.
pub fn find_prediction(stem_path: &Path) -> Option<PathBuf> {
    PREDICTION_EXTENSIONS
        .iter()
        .map(|e| stem_path.with_extension(e))
        .find(|p| p.is_file())
}

/// Reads a prediction, choosing the decoder by extension.
pub fn read_prediction(path: &Path) -> io::Result<(usize, usize, Vec<f32>)> {
    match path.extension().and_then(|e| e.to_str()) {
        Some("pfm") => read_pfm_gray(path),
        Some("exr") => read_exr_f32_gray(path),
        Some("png") => {
            let (w, h, v) = read_png_gray16(path)?;
            let d = v.into_iter().map(|x| match x {
                0 => f32::NAN,
                x => x as f32 / 256.0,
            });
            Ok((w, h, d.collect()))
        }
        Some("npy") => read_npy(path),
        _ => Err(OutputError::wrap(
            path,
            Access::Read,
            io::Error::new(
                io::ErrorKind::InvalidInput,
                "unknown prediction format (expected .pfm, .png, .exr or .npy)",
            ),
        )),
    }
}

/// Reads a 2-D float32/float64 `.npy` array of shape (h, w).
pub fn read_npy(path: &Path) -> io::Result<(usize, usize, Vec<f32>)> {
    let bytes = read_file(path)?;
    decode_npy(&bytes).map_err(|e| OutputError::wrap(path, Access::Read, e))
}

fn decode_npy(bytes: &[u8]) -> io::Result<(usize, usize, Vec<f32>)> {
    let bad = |m: String| io::Error::new(io::ErrorKind::InvalidData, m);
    let npy = npyz::NpyFile::new(bytes)?;
    let shape = npy.shape().to_vec();
    let fortran = npy.order() == npyz::Order::Fortran;
    let [h, w] = shape[..] else {
        return Err(bad(format!("expected a 2-D array, found shape {shape:?}")));
    };
    let (h, w) = (h as usize, w as usize);
    let descr = npy.dtype().descr().trim_matches('\'').to_string();
    let values: Vec<f32> = match descr.get(1..) {
        Some("f4") => npy.into_vec::<f32>()?,
        Some("f8") => npy
            .into_vec::<f64>()?
            .into_iter()
            .map(|v| v as f32)
            .collect(),
        _ => return Err(bad(format!("dtype {descr} is not float32 or float64"))),
    };
    if values.len() != w * h {
        return Err(bad(format!("{} values for shape ({h}, {w})", values.len())));
    }
    if !fortran {
        return Ok((w, h, values));
    }
    // Fortran order stores columns first: element (j, i) at i·h + j.
    let mut rows = vec![0.0; w * h];
    for i in 0..w {
        for j in 0..h {
            rows[j * w + i] = values[i * h + j];
        }
    }
    Ok((w, h, rows))
}
