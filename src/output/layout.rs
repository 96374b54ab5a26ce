//! The `native` frame layout of DATASET.md as path functions: a sequence
//! directory holds `left/<aov>/NNNNNN.<ext>`, `baseline_XXX/<aov>/NNNNNN.<ext>`
//! (XXX = baseline in whole centimetres, zero-padded to 3 digits) and
//! `cameras/NNNNNN.json` (folder names from `camera::baseline_dir_name`, the
//! rig's rule), and the recogniser of native-layout paths. Nothing here
//! touches the file system.

use std::path::{Component, Path, PathBuf};

use crate::camera::baseline_dir_name;

/// Six-digit zero-padded frame stem: frame 7 → "000007".
pub fn frame_stem(frame: u32) -> String {
    format!("{frame:06}")
}

/// AOV folders below `left/` and their files' extension.
const LEFT_AOVS: [(&str, &str); 7] = [
    ("rgb", "png"),
    ("rgb_hdr", "exr"),
    ("depth", "exr"),
    ("normal", "exr"),
    ("semantic", "png"),
    ("instance", "png"),
    ("mask", "png"),
];

/// AOV folders below `baseline_XXX/` and their files' extension.
const BASELINE_AOVS: [(&str, &str); 6] = [
    ("rgb", "png"),
    ("rgb_hdr", "exr"),
    ("disp", "pfm"),
    ("depth_right", "exr"),
    ("disp_right", "pfm"),
    ("occ", "png"),
];

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
    let aovs: &[(&str, &str)] = match *parts.first()? {
        "left" => &LEFT_AOVS,
        "cameras" => &[],
        top if is_baseline_dir(top) => &BASELINE_AOVS,
        _ => return None,
    };
    match parts[..] {
        [_] => Some(NativePath::Folder),
        ["cameras", file] => frame_file(file, "json").map(|frame| NativePath::File { frame }),
        [_, aov] => aovs
            .iter()
            .any(|(a, _)| *a == aov)
            .then_some(NativePath::Folder),
        [_, aov, file] => {
            let (_, ext) = aovs.iter().find(|(a, _)| *a == aov)?;
            frame_file(file, ext).map(|frame| NativePath::File { frame })
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

    fn file(&self, dir: &[&str], frame: u32, ext: &str) -> PathBuf {
        let mut p = self.root.clone();
        for d in dir {
            p.push(d);
        }
        p.push(format!("{}.{ext}", frame_stem(frame)));
        p
    }

    fn baseline_file(&self, baseline_cm: f64, aov: &str, frame: u32, ext: &str) -> PathBuf {
        self.file(&[&baseline_dir_name(baseline_cm), aov], frame, ext)
    }

    /// `left/rgb/NNNNNN.png`: 8-bit sRGB left image.
    pub fn left_rgb(&self, frame: u32) -> PathBuf {
        self.file(&["left", "rgb"], frame, "png")
    }

    /// `left/rgb_hdr/NNNNNN.exr`: optional linear radiance of the left view.
    pub fn left_rgb_hdr(&self, frame: u32) -> PathBuf {
        self.file(&["left", "rgb_hdr"], frame, "exr")
    }

    /// `left/depth/NNNNNN.exr`: float32 depth_z in metres, +inf for sky.
    pub fn left_depth(&self, frame: u32) -> PathBuf {
        self.file(&["left", "depth"], frame, "exr")
    }

    /// `left/normal/NNNNNN.exr`: world-space unit normals.
    pub fn left_normal(&self, frame: u32) -> PathBuf {
        self.file(&["left", "normal"], frame, "exr")
    }

    /// `left/semantic/NNNNNN.png`: 8-bit class ids.
    pub fn left_semantic(&self, frame: u32) -> PathBuf {
        self.file(&["left", "semantic"], frame, "png")
    }

    /// `left/instance/NNNNNN.png`: 16-bit instance ids (0 = none).
    pub fn left_instance(&self, frame: u32) -> PathBuf {
        self.file(&["left", "instance"], frame, "png")
    }

    /// `left/mask/NNNNNN.png`: 8-bit mask bits (sky, rain, transparent, mirror).
    pub fn left_mask(&self, frame: u32) -> PathBuf {
        self.file(&["left", "mask"], frame, "png")
    }

    /// `baseline_XXX/rgb/NNNNNN.png`: the right image for this baseline.
    pub fn baseline_rgb(&self, frame: u32, baseline_cm: f64) -> PathBuf {
        self.baseline_file(baseline_cm, "rgb", frame, "png")
    }

    /// `baseline_XXX/rgb_hdr/NNNNNN.exr`: the right image's linear radiance (optional).
    pub fn baseline_rgb_hdr(&self, frame: u32, baseline_cm: f64) -> PathBuf {
        self.baseline_file(baseline_cm, "rgb_hdr", frame, "exr")
    }

    /// `baseline_XXX/disp/NNNNNN.pfm`: left-view disparity, float32 px.
    pub fn baseline_disp(&self, frame: u32, baseline_cm: f64) -> PathBuf {
        self.baseline_file(baseline_cm, "disp", frame, "pfm")
    }

    /// `baseline_XXX/depth_right/NNNNNN.exr`: right-view depth_z in metres.
    pub fn baseline_depth_right(&self, frame: u32, baseline_cm: f64) -> PathBuf {
        self.baseline_file(baseline_cm, "depth_right", frame, "exr")
    }

    /// `baseline_XXX/disp_right/NNNNNN.pfm`: right-view disparity, float32 px.
    pub fn baseline_disp_right(&self, frame: u32, baseline_cm: f64) -> PathBuf {
        self.baseline_file(baseline_cm, "disp_right", frame, "pfm")
    }

    /// `baseline_XXX/occ/NNNNNN.png`: left-view occlusion mask, 255 = occluded.
    pub fn baseline_occ(&self, frame: u32, baseline_cm: f64) -> PathBuf {
        self.baseline_file(baseline_cm, "occ", frame, "png")
    }

    /// `cameras/NNNNNN.json`: K, poses, weather, sun, exposure, seed.
    pub fn camera_json(&self, frame: u32) -> PathBuf {
        self.file(&["cameras"], frame, "json")
    }

    /// The root as a path (for relative paths in manifests).
    pub fn root(&self) -> &Path {
        &self.root
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn native_paths_match_dataset_md() {
        let l = NativeLayout::new("/seq");
        assert_eq!(l.left_rgb(0), PathBuf::from("/seq/left/rgb/000000.png"));
        assert_eq!(
            l.left_depth(12),
            PathBuf::from("/seq/left/depth/000012.exr")
        );
        assert_eq!(
            l.left_rgb_hdr(1),
            PathBuf::from("/seq/left/rgb_hdr/000001.exr")
        );
        assert_eq!(
            l.left_normal(1),
            PathBuf::from("/seq/left/normal/000001.exr")
        );
        assert_eq!(
            l.left_semantic(1),
            PathBuf::from("/seq/left/semantic/000001.png")
        );
        assert_eq!(
            l.left_instance(1),
            PathBuf::from("/seq/left/instance/000001.png")
        );
        assert_eq!(l.left_mask(1), PathBuf::from("/seq/left/mask/000001.png"));
        assert_eq!(
            l.baseline_rgb(3, 54.0),
            PathBuf::from("/seq/baseline_054/rgb/000003.png")
        );
        assert_eq!(
            l.baseline_disp(3, 10.0),
            PathBuf::from("/seq/baseline_010/disp/000003.pfm")
        );
        assert_eq!(
            l.baseline_depth_right(3, 300.0),
            PathBuf::from("/seq/baseline_300/depth_right/000003.exr")
        );
        assert_eq!(
            l.baseline_disp_right(3, 100.0),
            PathBuf::from("/seq/baseline_100/disp_right/000003.pfm")
        );
        assert_eq!(
            l.baseline_occ(3, 200.0),
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
                for p in [
                    l.left_rgb(f),
                    l.left_rgb_hdr(f),
                    l.left_depth(f),
                    l.left_normal(f),
                    l.left_semantic(f),
                    l.left_instance(f),
                    l.left_mask(f),
                    l.baseline_rgb(f, b),
                    l.baseline_rgb_hdr(f, b),
                    l.baseline_disp(f, b),
                    l.baseline_depth_right(f, b),
                    l.baseline_disp_right(f, b),
                    l.baseline_occ(f, b),
                ] {
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
