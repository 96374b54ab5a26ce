//! Finds every native ground-truth disparity `baseline_XXX/disp/NNNNNN.pfm`
//! below a directory and names its group from the path: in a dataset
//! `<town>/<config>_<weather>/<sequence>/baseline_XXX/…`; a bare
//! `parallax render` directory (no prefix) is one group named "-".

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use crate::output::layouts::FrameKey;
use crate::output::{Access, Map, OutputError};

/// One ground-truth disparity image of a native tree.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct GtImage {
    /// Path of the disparity PFM relative to the root.
    pub rel: PathBuf,
    /// Town ("-" when the path does not say).
    pub town: String,
    /// Camera configuration ("-" when the path does not say).
    pub config: String,
    /// Weather ("-" when the path does not say).
    pub weather: String,
    /// Baseline directory name (`baseline_054`).
    pub baseline: String,
}

impl GtImage {
    /// The occlusion mask beside the disparity: `baseline_XXX/occ/NNNNNN.png`.
    pub fn occ_rel(&self) -> PathBuf {
        let stem = self.rel.file_stem().unwrap_or_default();
        let base = self
            .rel
            .parent()
            .and_then(Path::parent)
            .unwrap_or(Path::new(""));
        let occ = Map::Occlusion.spec();
        base.join(occ.folder)
            .join(stem)
            .with_extension(occ.format.ext())
    }

    /// The dataset frame of this image, `None` unless the path is
    /// `<town>/<config>_<weather>/<SSSS>/baseline_XXX/disp/<NNNNNN>.pfm`.
    pub fn frame_key(&self) -> Option<FrameKey> {
        let names: Vec<&str> = self.rel.iter().filter_map(|c| c.to_str()).collect();
        let [_, _, seq, _, _, file] = names[..] else {
            return None;
        };
        if self.weather == "-" {
            return None;
        }
        Some(FrameKey {
            town: self.town.clone(),
            config: self.config.clone(),
            weather: self.weather.clone(),
            sequence: seq.parse().ok()?,
            frame: Path::new(file).file_stem()?.to_str()?.parse().ok()?,
        })
    }

    /// The baseline in centimetres, from the directory name (`baseline_054` → 54).
    pub fn baseline_cm(&self) -> Option<f64> {
        self.baseline.strip_prefix("baseline_")?.parse().ok()
    }

    /// The sequence directory relative to the root, with the frame stem: one
    /// identifier per frame (shared by the frame's baselines).
    pub fn frame_id(&self) -> PathBuf {
        let stem = self.rel.file_stem().unwrap_or_default();
        let seq = self
            .rel
            .parent()
            .and_then(Path::parent)
            .and_then(Path::parent)
            .unwrap_or(Path::new(""));
        seq.join(stem)
    }
}

fn is_disparity(rel: &Path) -> bool {
    let names: Vec<&str> = rel.iter().filter_map(|c| c.to_str()).collect();
    let n = names.len();
    let disp = Map::Disparity.spec();
    n >= 3
        && names[n - 2] == disp.folder
        && names[n - 3].starts_with("baseline_")
        && names[n - 1].ends_with(&format!(".{}", disp.format.ext()))
        && crate::output::temp_base(names[n - 1]).is_none()
}

fn group_of(rel: &Path) -> GtImage {
    let names: Vec<String> = rel
        .iter()
        .map(|c| c.to_string_lossy().into_owned())
        .collect();
    let n = names.len();
    let prefix = &names[..n - 3];
    let dash = || "-".to_string();
    let (town, config, weather) = match prefix {
        [] => (dash(), dash(), dash()),
        [town, cw, _seq] => match cw.split_once('_') {
            Some((c, w)) => (town.clone(), c.to_string(), w.to_string()),
            None => (town.clone(), cw.clone(), dash()),
        },
        other => (other.join("/"), dash(), dash()),
    };
    GtImage {
        rel: rel.to_path_buf(),
        town,
        config,
        weather,
        baseline: names[n - 3].clone(),
    }
}

fn walk(root: &Path, dir: &Path, out: &mut Vec<GtImage>) -> io::Result<()> {
    let entries = fs::read_dir(dir).map_err(|e| OutputError::wrap(dir, Access::Read, e))?;
    for entry in entries {
        let entry = entry.map_err(|e| OutputError::wrap(dir, Access::Read, e))?;
        let path = entry.path();
        let ty = entry
            .file_type()
            .map_err(|e| OutputError::wrap(&path, Access::Read, e))?;
        if ty.is_dir() {
            walk(root, &path, out)?;
        } else if let Ok(rel) = path.strip_prefix(root) {
            if is_disparity(rel) {
                out.push(group_of(rel));
            }
        }
    }
    Ok(())
}

/// Every ground-truth disparity below `root`, sorted by path. Errors name the
/// directory that could not be read.
pub fn find_gt_disparities(root: &Path) -> io::Result<Vec<GtImage>> {
    let mut out = Vec::new();
    walk(root, root, &mut out)?;
    out.sort();
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn groups_parse_from_dataset_and_bare_render_paths() {
        let g = group_of(Path::new(
            "town03/roll15_foggy/0002/baseline_054/disp/000007.pfm",
        ));
        assert_eq!(
            (g.town.as_str(), g.config.as_str(), g.weather.as_str()),
            ("town03", "roll15", "foggy")
        );
        assert_eq!(g.baseline, "baseline_054");
        assert_eq!(g.baseline_cm(), Some(54.0));
        let k = g.frame_key().unwrap();
        assert_eq!((k.sequence, k.frame, k.weather.as_str()), (2, 7, "foggy"));
        assert_eq!(
            g.occ_rel(),
            PathBuf::from("town03/roll15_foggy/0002/baseline_054/occ/000007.png")
        );
        assert_eq!(
            g.frame_id(),
            PathBuf::from("town03/roll15_foggy/0002/000007")
        );
        let g = group_of(Path::new("baseline_010/disp/000000.pfm"));
        assert_eq!((g.town.as_str(), g.config.as_str()), ("-", "-"));
        assert_eq!(g.frame_key(), None);
        assert!(is_disparity(Path::new("baseline_010/disp/000000.pfm")));
        assert!(!is_disparity(Path::new(
            "baseline_010/disp_right/000000.pfm"
        )));
    }
}
