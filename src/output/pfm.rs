//! Portable Float Map (PFM), single channel ("Pf"), written by hand.
//!
//! Format (Debevec's HDRShop / Netpbm PFM): ASCII header `Pf\n<w> <h>\n<scale>\n`,
//! then `w × h` float32 samples, rows from the BOTTOM of the image to the top.
//! A negative scale means little-endian samples, positive big-endian. We write
//! scale -1.0 (little-endian); the reader accepts both byte orders and returns
//! rows top-first, row-major, like every other buffer in parallax.

use super::atomic::{check_len, invalid_data, read_file, write_atomic, Access, OutputError};
use std::io;
use std::path::Path;

/// Encodes a single-channel float image (row-major, top row first) as PFM bytes:
/// header `Pf\n<w> <h>\n-1.0\n`, little-endian rows bottom-to-top.
/// Every f32 bit pattern (±inf, NaN, -0.0) is stored unchanged.
pub fn encode_pfm_gray(w: usize, h: usize, data: &[f32]) -> io::Result<Vec<u8>> {
    check_len(data.len(), w, h, 1)?;
    let header = format!("Pf\n{w} {h}\n-1.0\n");
    let mut out = Vec::with_capacity(header.len() + data.len() * 4);
    out.extend_from_slice(header.as_bytes());
    for j in (0..h).rev() {
        for &v in &data[j * w..(j + 1) * w] {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    Ok(out)
}

/// Writes a single-channel float image (row-major, top row first) as PFM,
/// atomically. Errors name the path.
pub fn write_pfm_gray(path: &Path, w: usize, h: usize, data: &[f32]) -> io::Result<()> {
    let bytes =
        encode_pfm_gray(w, h, data).map_err(|e| OutputError::wrap(path, Access::Write, e))?;
    write_atomic(path, &bytes)
}

/// Reads a single-channel PFM file; returns `(w, h, data)` with data row-major,
/// top row first. Accepts both byte orders. Errors name the path.
pub fn read_pfm_gray(path: &Path) -> io::Result<(usize, usize, Vec<f32>)> {
    let bytes = read_file(path)?;
    decode_pfm_gray(&bytes).map_err(|e| OutputError::wrap(path, Access::Read, e))
}

/// Decodes single-channel PFM bytes; see [`read_pfm_gray`].
pub fn decode_pfm_gray(bytes: &[u8]) -> io::Result<(usize, usize, Vec<f32>)> {
    // Header: three whitespace-separated tokens after the magic, then exactly
    // one whitespace byte before the binary samples.
    let mut pos = 0;
    let mut tokens = Vec::with_capacity(4);
    while tokens.len() < 4 {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        if start == pos || pos - start > 64 {
            return Err(invalid_data("truncated or malformed PFM header"));
        }
        tokens.push(std::str::from_utf8(&bytes[start..pos]).unwrap_or(""));
    }
    if pos >= bytes.len() {
        return Err(invalid_data("PFM header not followed by data"));
    }
    pos += 1; // the single whitespace byte ending the header
    match tokens[0] {
        "Pf" => {}
        "PF" => return Err(invalid_data("PFM is 3-channel (PF), expected grey (Pf)")),
        other => return Err(invalid_data(format!("not a PFM file (magic {other:?})"))),
    }
    let parse_dim = |s: &str| {
        s.parse::<usize>()
            .map_err(|_| invalid_data(format!("bad PFM dimension {s:?}")))
    };
    let w = parse_dim(tokens[1])?;
    let h = parse_dim(tokens[2])?;
    let scale: f32 = tokens[3]
        .parse()
        .map_err(|_| invalid_data(format!("bad PFM scale {:?}", tokens[3])))?;
    if scale == 0.0 || !scale.is_finite() {
        return Err(invalid_data(format!("bad PFM scale {scale}")));
    }
    let little_endian = scale < 0.0;
    let n = w
        .checked_mul(h)
        .filter(|n| n.checked_mul(4).is_some())
        .ok_or_else(|| invalid_data("PFM dimensions overflow"))?;
    let body = &bytes[pos..];
    if body.len() < n * 4 {
        return Err(invalid_data(format!(
            "PFM data truncated: {} bytes, expected {}",
            body.len(),
            n * 4
        )));
    }
    let mut data = vec![0.0f32; n];
    for (k, chunk) in body[..n * 4].chunks_exact(4).enumerate() {
        let b = [chunk[0], chunk[1], chunk[2], chunk[3]];
        let v = if little_endian {
            f32::from_le_bytes(b)
        } else {
            f32::from_be_bytes(b)
        };
        // File row r counts from the bottom: image row h - 1 - r.
        let (r, i) = (k / w, k % w);
        data[(h - 1 - r) * w + i] = v;
    }
    Ok((w, h, data))
}
