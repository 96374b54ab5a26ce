//! The `native` frame layout of DATASET.md as path functions: a sequence
//! directory holds `left/<aov>/NNNNNN.<ext>`, `baseline_XXX/<aov>/NNNNNN.<ext>`
//! (XXX = baseline in whole centimetres, zero-padded to 3 digits) and
//! `cameras/NNNNNN.json` (folder names from `camera::baseline_dir_name`, the
//! rig's rule), and the recogniser of native-layout paths. Nothing here
//! touches the file system.

use std::path::{Component, Path, PathBuf};

use super::registry::{maps_in, Map, CAMERAS_DIR, LEFT_DIR};
use crate::camera::baseline_dir_name;

/// Six-digit zero-padded frame stem: frame 7 → "000007".
pub fn frame_stem(frame: u32) -> String {
    format!("{frame:06}")
}

/// What a path below a sequence directory is in the native layout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NativePath {
    /// One of the layout's folders (`left`, `left/rgb`, `baseline_054/occ`, …).
    Folder,
    /// A file of frame `frame` (exactly `NNNNNN.<ext>`; a temporary of the
    /// atomic writers is recognised by its `temp_base`).
    File {
        /// The frame the file belongs to.
        frame: u32,
    },
}

/// Recognises `rel` (relative to a sequence directory) as a folder or file
/// the native layout writes; `None` for anything else.
pub fn native_path(rel: &Path) -> Option<NativePath> {
    let mut parts = Vec::new();
    for c in rel.components() {
        match c {
            Component::Normal(s) => parts.push(s.to_str()?),
            _ => return None,
        }
    }
    let per_baseline = match *parts.first()? {
        LEFT_DIR => Some(false),
        CAMERAS_DIR => None,
        top if is_baseline_dir(top) => Some(true),
        _ => return None,
    };
    let ext_of = |folder: &str| -> Option<&'static str> {
        maps_in(per_baseline?)
            .find(|m| m.folder == folder)
            .map(|m| m.format.ext())
    };
    match parts[..] {
        [_] => Some(NativePath::Folder),
        [CAMERAS_DIR, file] => frame_file(file, "json").map(|frame| NativePath::File { frame }),
        [_, folder] => ext_of(folder).map(|_| NativePath::Folder),
        [_, folder, file] => {
            frame_file(file, ext_of(folder)?).map(|frame| NativePath::File { frame })
        }
        _ => None,
    }
}

/// The folder `parallax preview DIR` writes its pictures to by default.
pub const PREVIEW_DIR: &str = "preview";

/// A picture `parallax preview` writes: `NNNNNN_<map>.png`.
pub fn is_preview_file(name: &str) -> bool {
    name.strip_suffix(".png")
        .and_then(|s| s.split_once('_'))
        .is_some_and(|(frame, map)| {
            frame.len() == 6 && frame.bytes().all(|b| b.is_ascii_digit()) && !map.is_empty()
        })
}

/// `baseline_` followed by three or more digits, as `baseline_dir_name` writes.
fn is_baseline_dir(name: &str) -> bool {
    name.strip_prefix("baseline_")
        .is_some_and(|d| d.len() >= 3 && d.bytes().all(|b| b.is_ascii_digit()))
}

/// `NNNNNN.<ext>`: the frame.
fn frame_file(name: &str, ext: &str) -> Option<u32> {
    let (stem, rest) = name.split_once('.')?;
    let frame: u32 = stem.parse().ok()?;
    (frame_stem(frame) == stem && rest == ext).then_some(frame)
}

/// Paths of the native layout below one sequence directory.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct NativeLayout {
    /// The sequence directory (for `parallax render`: the output directory).
    pub root: PathBuf,
}

impl NativeLayout {
    /// A layout rooted at `root`.
    pub fn new(root: impl Into<PathBuf>) -> NativeLayout {
        NativeLayout { root: root.into() }
    }

    /// The file of `map` for frame `frame`: `left/<folder>/NNNNNN.<ext>`,
    /// or `baseline_XXX/<folder>/NNNNNN.<ext>` for a per-baseline map of the
    /// baseline `baseline_cm` (ignored for the others). Precondition: a
    /// per-baseline map comes with its baseline.
    pub fn path(&self, map: Map, frame: u32, baseline_cm: Option<f64>) -> PathBuf {
        let top = if map.spec().per_baseline {
            let cm = baseline_cm.expect("a per-baseline map needs its baseline");
            baseline_dir_name(cm)
        } else {
            LEFT_DIR.to_string()
        };
        self.path_in(&top, map, frame)
    }

    /// The file of `map` for frame `frame` below the folder `top` of the
    /// root (`left`, or a baseline folder as found on disk).
    pub fn path_in(&self, top: &str, map: Map, frame: u32) -> PathBuf {
        self.map_dir(top, map)
            .join(format!("{}.{}", frame_stem(frame), map.spec().format.ext()))
    }

    /// The folder of `map`'s files below the folder `top` of the root.
    pub fn map_dir(&self, top: &str, map: Map) -> PathBuf {
        self.root.join(top).join(map.spec().folder)
    }

    /// `cameras/NNNNNN.json`: K, poses, weather, sun, exposure, seed.
    pub fn camera_json(&self, frame: u32) -> PathBuf {
        self.root
            .join(CAMERAS_DIR)
            .join(format!("{}.json", frame_stem(frame)))
    }

    /// The root as a path (for relative paths in manifests).
    pub fn root(&self) -> &Path {
        &self.root
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::output::registry::MAPS;

    #[test]
    fn native_paths_match_dataset_md() {
        let l = NativeLayout::new("/seq");
        assert_eq!(
            l.path(Map::LeftRgb, 0, None),
            PathBuf::from("/seq/left/rgb/000000.png")
        );
        assert_eq!(
            l.path(Map::Depth, 12, None),
            PathBuf::from("/seq/left/depth/000012.exr")
        );
        assert_eq!(
            l.path(Map::LeftRgbHdr, 1, None),
            PathBuf::from("/seq/left/rgb_hdr/000001.exr")
        );
        assert_eq!(
            l.path(Map::Normal, 1, None),
            PathBuf::from("/seq/left/normal/000001.exr")
        );
        assert_eq!(
            l.path(Map::Semantic, 1, None),
            PathBuf::from("/seq/left/semantic/000001.png")
        );
        assert_eq!(
            l.path(Map::Instance, 1, None),
            PathBuf::from("/seq/left/instance/000001.png")
        );
        assert_eq!(
            l.path(Map::Mask, 1, None),
            PathBuf::from("/seq/left/mask/000001.png")
        );
        assert_eq!(
            l.path(Map::RightRgb, 3, Some(54.0)),
            PathBuf::from("/seq/baseline_054/rgb/000003.png")
        );
        assert_eq!(
            l.path(Map::RightRgbHdr, 3, Some(54.0)),
            PathBuf::from("/seq/baseline_054/rgb_hdr/000003.exr")
        );
        assert_eq!(
            l.path(Map::Disparity, 3, Some(10.0)),
            PathBuf::from("/seq/baseline_010/disp/000003.pfm")
        );
        assert_eq!(
            l.path(Map::RightDepth, 3, Some(300.0)),
            PathBuf::from("/seq/baseline_300/depth_right/000003.exr")
        );
        assert_eq!(
            l.path(Map::RightDisparity, 3, Some(100.0)),
            PathBuf::from("/seq/baseline_100/disp_right/000003.pfm")
        );
        assert_eq!(
            l.path(Map::Occlusion, 3, Some(200.0)),
            PathBuf::from("/seq/baseline_200/occ/000003.png")
        );
        assert_eq!(
            l.camera_json(999_999),
            PathBuf::from("/seq/cameras/999999.json")
        );
    }

    #[test]
    fn every_native_path_is_recognised() {
        let l = NativeLayout::new("");
        for b in [10.0, 54.0, 1234.0] {
            for f in [0, 7, 1_000_000] {
                for p in MAPS.iter().map(|m| l.path(m.map, f, Some(b))) {
                    let file = NativePath::File { frame: f };
                    assert_eq!(native_path(&p), Some(file), "{}", p.display());
                    let mut tmp = p.clone().into_os_string();
                    tmp.push(".tmp-123-4");
                    assert_eq!(native_path(Path::new(&tmp)), None);
                    for dir in p.ancestors().skip(1).filter(|d| !d.as_os_str().is_empty()) {
                        assert_eq!(native_path(dir), Some(NativePath::Folder));
                    }
                }
                let cam = NativePath::File { frame: f };
                assert_eq!(native_path(&l.camera_json(f)), Some(cam));
            }
        }
        for other in [
            "notes.txt",
            "left/rgb/000000.jpg",
            "left/rgb/0.png",
            "left/rgb/0000001.png",
            "left/disp/000000.pfm",
            "baseline_54/rgb/000000.png",
            "baseline_054/rgb/000000.png/x",
            "cameras/000000.json.bak",
            "cameras/notes.json",
            "dataset.json",
            "manifest",
            "../left",
            "/left",
        ] {
            assert_eq!(native_path(Path::new(other)), None, "{other}");
        }
    }
}
