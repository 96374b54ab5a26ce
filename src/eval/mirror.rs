//! Where the prediction for one ground-truth image lies in each layout a
//! prediction tree may mirror (`parallax eval --layout`). Paths are returned
//! without extension; `pred::find_prediction` tries each format.
//!
//! native: the ground truth's own `…/baseline_XXX/disp/NNNNNN`; kitti:
//! `baseline_XXX/disp_occ_0/<town>_<config>_<weather>_SSSS_NNNNNN`; sceneflow:
//! `disparity/baseline_XXX/<town>_<config>_<weather>/SSSS/left/NNNNNN`;
//! stereocarla: the depth PNG's path with `depth` → `disp` (a prediction is a
//! disparity, not a depth), e.g. `normal/town01/baseline_054/disp/SSSS_NNNNNN`.

use std::path::PathBuf;

use super::walk::GtImage;
use crate::output::layouts::{left_truth_rel, LayoutKind};

/// The prediction path (relative to the prediction root, no extension) that
/// mirrors `img` in `layout`, or an error saying why the image has none.
pub fn prediction_stem(img: &GtImage, layout: LayoutKind) -> Result<PathBuf, String> {
    let rel = match layout {
        LayoutKind::Native => return Ok(img.rel.with_extension("")),
        _ => {
            let (Some(key), Some(cm)) = (img.frame_key(), img.baseline_cm()) else {
                return Err(format!(
                    "{}: --layout {layout} needs a dataset tree \
(<town>/<config>_<weather>/<sequence>/baseline_XXX/disp/NNNNNN.pfm); \
use --layout native for a `parallax render` directory",
                    img.rel.display()
                ));
            };
            left_truth_rel(layout, &key, cm).unwrap_or_default()
        }
    };
    // StereoCarla stores depth, not disparity: its mirror puts `disp` in
    // place of the last folder, `depth` (a town or config may be named so too).
    let rel = match (layout, rel.rsplit_once("/depth/")) {
        (LayoutKind::Stereocarla, Some((dir, file))) => format!("{dir}/disp/{file}"),
        _ => rel,
    };
    Ok(PathBuf::from(rel).with_extension(""))
}
