//! The `kitti` layout (KITTI 2015 stereo style), one directory per baseline:
//! `baseline_XXX/image_2/<stem>.png` (left), `image_3` (right),
//! `disp_occ_0` (every valid pixel) and `disp_noc_0` (non-occluded only), with
//! stem `<town>_<config>_<weather>_SSSS_NNNNNN`.
//!
//! Disparity PNGs are 16-bit, value = round(d · 256), 0 = invalid: sky (d = 0),
//! d < 1/512 px (would round to 0) and d ≥ 65535.5/256 ≈ 256 px (does not fit)
//! are written as 0, so every stored value is within 1/512 px of the truth.

use std::io;
use std::path::{Path, PathBuf};

use super::{flat_stem, rel_str, srgb_views, write_baseline_splits, FrameKey};
use crate::camera::StereoRig;
use crate::output::{baseline_dir_name, write_png_gray16, write_png_rgb8};
use crate::render::FrameOutput;

/// Encodes disparity (px) as KITTI 16-bit: round(d·256), 0 where invalid or
/// out of range (see the module header). `occlusion` (255 = occluded), when
/// given, also zeroes occluded pixels (`disp_noc`).
pub fn encode_kitti_disparity(disparity_px: &[f32], occlusion: Option<&[u8]>) -> Vec<u16> {
    disparity_px
        .iter()
        .enumerate()
        .map(|(i, &d)| {
            let v = (d as f64 * 256.0).round();
            let occluded = occlusion.is_some_and(|o| o[i] != 0);
            if !occluded && v.is_finite() && (1.0..=65535.0).contains(&v) {
                v as u16
            } else {
                0
            }
        })
        .collect()
}

/// Decodes KITTI 16-bit disparity: v/256 px, `None` where v = 0 (invalid).
pub fn decode_kitti_disparity(values: &[u16]) -> Vec<Option<f32>> {
    values
        .iter()
        .map(|&v| (v > 0).then(|| v as f32 / 256.0))
        .collect()
}

fn stem(key: &FrameKey) -> String {
    format!(
        "{}_{}_{}_{}",
        key.town,
        key.config,
        key.weather,
        flat_stem(key)
    )
}

/// Root-relative `[image_2, image_3, disp_occ_0, disp_noc_0]` of a frame.
pub(super) fn sample_paths(key: &FrameKey, baseline_cm: f64) -> [String; 4] {
    let b = baseline_dir_name(baseline_cm);
    let file = format!("{}.png", stem(key));
    ["image_2", "image_3", "disp_occ_0", "disp_noc_0"].map(|d| rel_str(&[&b, d, &file]))
}

/// Writes one frame; returns the files written.
pub(super) fn write_frame(
    root: &Path,
    key: &FrameKey,
    rig: &StereoRig,
    out: &FrameOutput,
) -> io::Result<Vec<PathBuf>> {
    let (w, h) = (out.left.width as usize, out.left.height as usize);
    let srgb = srgb_views(out);
    let mut written = Vec::new();
    for (b, &baseline_m) in rig.baselines_m.iter().enumerate() {
        let gt = &out.baselines[b];
        let [left, right, occ, noc] = sample_paths(key, baseline_m * 100.0).map(|p| root.join(p));
        write_png_rgb8(&left, w, h, &srgb[0])?;
        write_png_rgb8(&right, w, h, &srgb[1 + b])?;
        write_png_gray16(
            &occ,
            w,
            h,
            &encode_kitti_disparity(&gt.disparity_left, None),
        )?;
        let noc_values = encode_kitti_disparity(&gt.disparity_left, Some(&gt.occlusion));
        write_png_gray16(&noc, w, h, &noc_values)?;
        written.extend([left, right, occ, noc]);
    }
    Ok(written)
}

/// Writes `splits/kitti_baseline_XXX.txt`: `image_2 image_3 disp_occ_0` per line.
pub(super) fn write_index(
    root: &Path,
    keys: &[FrameKey],
    baselines_cm: &[f64],
) -> io::Result<Vec<PathBuf>> {
    let line = |k: &FrameKey, cm: f64| sample_paths(k, cm)[..3].join(" ");
    Ok(write_baseline_splits(root, "kitti", keys, baselines_cm, line)?.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kitti_encoding_marks_sky_tiny_huge_and_occluded_invalid() {
        let d = [0.0, 1.0 / 1024.0, 10.5, 300.0, f32::NAN, 2.0];
        assert_eq!(
            encode_kitti_disparity(&d, None),
            vec![0, 0, 2688, 0, 0, 512]
        );
        let occ = [0, 0, 255, 0, 0, 0];
        assert_eq!(
            encode_kitti_disparity(&d, Some(&occ)),
            vec![0, 0, 0, 0, 0, 512]
        );
        assert_eq!(decode_kitti_disparity(&[0, 2688]), vec![None, Some(10.5)]);
    }
}
