//! Pictures a person can open (`parallax preview`): the ground-truth maps of
//! one native frame colour-coded with a legend, plus the drawing surface with
//! a bitmap font that the histogram plots share.
//!
//! Per frame `NNNNNN` of a native render or dataset sequence directory:
//! `NNNNNN_depth.png` (depth_z, turbo on a log scale, near red),
//! `NNNNNN_semantic.png` (CARLA palette), `NNNNNN_instance.png` (hashed
//! palette), `NNNNNN_mask.png` (a colour per bit) and per baseline
//! `NNNNNN_baseline_XXX_disp.png` (turbo, 0 px to the largest disparity) and
//! `NNNNNN_baseline_XXX_occ.png` (the left image, occluded pixels tinted
//! magenta: (c + [`OCC_TINT`]) / 2). Black is sky or no value in every
//! colour-coded map. Every input is read and checked before anything is written.

pub mod canvas;
pub mod colormap;
pub mod maps;

use std::fs;
use std::io;
use std::path::{Path, PathBuf};

use canvas::Canvas;
use colormap::{instance_colour, mask_colour, semantic_colour, MASK_COLOURS};
use maps::{palette_map, scalar_map, Scale};

use crate::output::registry::OCCLUSION_VISIBLE;
use crate::output::{
    frame_stem, read_exr_f32_gray, read_pfm_gray, read_png_gray16, read_png_gray8, read_png_rgb8,
    Access, Map, NativeLayout, OutputError, LEFT_DIR,
};
use crate::scene::semantic::class_name;

/// The colour occluded pixels are blended with (half and half).
pub const OCC_TINT: [u8; 3] = [255, 0, 255];
/// The base of the occlusion overlay when the frame has no left image (spp 0).
const NO_IMAGE_GREY: u8 = 96;

/// The left-view ground truth of one baseline.
pub struct BaselineMaps {
    /// Directory name (`baseline_054`).
    pub name: String,
    /// Left-view disparity, px.
    pub disparity: Vec<f32>,
    /// Occlusion mask, 255 = occluded.
    pub occlusion: Vec<u8>,
}

/// Every map of one native frame that the preview shows.
pub struct FrameMaps {
    /// Frame stem (`000000`).
    pub stem: String,
    /// Width, px.
    pub w: usize,
    /// Height, px.
    pub h: usize,
    /// The 8-bit left image (absent when rendered with spp 0).
    pub left_rgb: Option<Vec<u8>>,
    /// depth_z, m (+inf for sky).
    pub depth: Vec<f32>,
    /// Semantic class ids.
    pub semantic: Vec<u8>,
    /// Instance ids (0 = none).
    pub instance: Vec<u16>,
    /// Mask bits.
    pub mask: Vec<u8>,
    /// Per baseline directory, sorted by name.
    pub baselines: Vec<BaselineMaps>,
}

fn bad(path: &Path, msg: impl std::fmt::Display) -> io::Error {
    io::Error::new(
        io::ErrorKind::InvalidData,
        format!("{}: {msg}", path.display()),
    )
}

/// Checks that an image read from `path` is `w × h`.
fn same_size(path: &Path, got: (usize, usize), want: (usize, usize)) -> io::Result<()> {
    if got != want {
        return Err(bad(
            path,
            format!(
                "is {}×{}, the depth map is {}×{}",
                got.0, got.1, want.0, want.1
            ),
        ));
    }
    Ok(())
}

/// The smallest frame index with a depth map in `dir/left/depth/` (the
/// default frame); an error naming the directory when there is none.
pub fn first_frame(dir: &Path) -> io::Result<u32> {
    let depth_dir = NativeLayout::new(dir).map_dir(LEFT_DIR, Map::Depth);
    let none = || {
        bad(
            &depth_dir,
            "no NNNNNN.exr depth map: DIR must be a native render or sequence directory",
        )
    };
    let entries = fs::read_dir(&depth_dir).map_err(|_| none())?;
    entries
        .filter_map(|e| e.ok())
        .filter_map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            let (stem, ext) = name.split_once('.')?;
            (ext == Map::Depth.spec().format.ext()).then_some(())?;
            stem.parse::<u32>().ok()
        })
        .min()
        .ok_or_else(none)
}

/// Reads frame `frame` of the native directory `dir` (a `parallax render`
/// output or a dataset sequence directory). Errors name the file or directory.
pub fn read_frame(dir: &Path, frame: u32) -> io::Result<FrameMaps> {
    if !dir.is_dir() {
        return Err(io::Error::new(
            io::ErrorKind::NotFound,
            format!("{}: not a directory", dir.display()),
        ));
    }
    let l = NativeLayout::new(dir);
    let depth_path = l.path(Map::Depth, frame, None);
    if !depth_path.is_file() {
        return Err(bad(
            &depth_path,
            format!("no such file: DIR must be a native render or sequence directory holding frame {frame}"),
        ));
    }
    let (w, h, depth) = read_exr_f32_gray(&depth_path)?;
    let check = |p: &Path, got: (usize, usize)| same_size(p, got, (w, h));
    let p = l.path(Map::Semantic, frame, None);
    let (sw, sh, semantic) = read_png_gray8(&p)?;
    check(&p, (sw, sh))?;
    let p = l.path(Map::Instance, frame, None);
    let (iw, ih, instance) = read_png_gray16(&p)?;
    check(&p, (iw, ih))?;
    let p = l.path(Map::Mask, frame, None);
    let (mw, mh, mask) = read_png_gray8(&p)?;
    check(&p, (mw, mh))?;
    let p = l.path(Map::LeftRgb, frame, None);
    let left_rgb = if p.is_file() {
        let (rw, rh, rgb) = read_png_rgb8(&p)?;
        check(&p, (rw, rh))?;
        Some(rgb)
    } else {
        None
    };
    let stem = frame_stem(frame);
    let entries = fs::read_dir(dir).map_err(|e| OutputError::wrap(dir, Access::Read, e))?;
    let mut names: Vec<String> = entries
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("baseline_") && l.map_dir(n, Map::Disparity).is_dir())
        .collect();
    names.sort();
    let mut baselines = Vec::new();
    for name in names {
        let p = l.path_in(&name, Map::Disparity, frame);
        let (dw, dh, disparity) = read_pfm_gray(&p)?;
        check(&p, (dw, dh))?;
        let p = l.path_in(&name, Map::Occlusion, frame);
        let (ow, oh, occlusion) = read_png_gray8(&p)?;
        check(&p, (ow, oh))?;
        baselines.push(BaselineMaps {
            name,
            disparity,
            occlusion,
        });
    }
    Ok(FrameMaps {
        stem,
        w,
        h,
        left_rgb,
        depth,
        semantic,
        instance,
        mask,
        baselines,
    })
}

/// The left image with occluded pixels blended half and half with [`OCC_TINT`].
pub fn occlusion_overlay(left_rgb: &[u8], occlusion: &[u8]) -> Vec<u8> {
    left_rgb
        .chunks(3)
        .zip(occlusion)
        .flat_map(|(c, &o)| {
            let c = [c[0], c[1], c[2]];
            if o == OCCLUSION_VISIBLE {
                c
            } else {
                [0, 1, 2].map(|k| ((c[k] as u16 + OCC_TINT[k] as u16) / 2) as u8)
            }
        })
        .collect()
}

fn positive_range(v: &[f32]) -> Option<(f64, f64)> {
    let valid = v
        .iter()
        .filter(|d| d.is_finite() && **d > 0.0)
        .map(|&d| d as f64);
    valid.fold(None, |r, d| match r {
        None => Some((d, d)),
        Some((lo, hi)) => Some((lo.min(d), hi.max(d))),
    })
}

/// Every preview picture of a frame, with its file name.
pub fn previews(m: &FrameMaps) -> Vec<(String, Canvas)> {
    let (w, h, s) = (m.w, m.h, &m.stem);
    let mut out = Vec::new();
    let (near, far) = positive_range(&m.depth).unwrap_or((1.0, 1.0));
    let title = "depth_z [m], log scale; black = sky";
    let scale = Scale::LogReversed { near, far };
    out.push((
        format!("{s}_depth.png"),
        scalar_map(title, "m", w, h, &m.depth, scale),
    ));
    let rgb: Vec<u8> = m
        .semantic
        .iter()
        .flat_map(|&c| semantic_colour(c))
        .collect();
    let mut ids: Vec<u8> = m.semantic.clone();
    ids.sort_unstable();
    ids.dedup();
    let entries: Vec<([u8; 3], String)> = ids
        .iter()
        .map(|&id| {
            (
                semantic_colour(id),
                class_name(id).map_or(format!("id {id}"), str::to_string),
            )
        })
        .collect();
    out.push((
        format!("{s}_semantic.png"),
        palette_map("semantic classes (CARLA palette)", w, h, &rgb, &entries),
    ));
    let rgb: Vec<u8> = m
        .instance
        .iter()
        .flat_map(|&i| instance_colour(i))
        .collect();
    let mut ids = m.instance.clone();
    ids.sort_unstable();
    ids.dedup();
    let objects = ids.iter().filter(|&&i| i != 0).count();
    let title = format!("instance ids: {objects} objects, hashed colours");
    let entries = [(instance_colour(0), "no instance".to_string())];
    out.push((
        format!("{s}_instance.png"),
        palette_map(&title, w, h, &rgb, &entries),
    ));
    let rgb: Vec<u8> = m.mask.iter().flat_map(|&b| mask_colour(b)).collect();
    let mut entries: Vec<([u8; 3], String)> = MASK_COLOURS
        .iter()
        .map(|&(_, n, c)| (c, n.to_string()))
        .collect();
    entries.push((mask_colour(0), "no bit".into()));
    let title = "mask bits (several set: mean colour)";
    out.push((
        format!("{s}_mask.png"),
        palette_map(title, w, h, &rgb, &entries),
    ));
    let grey = vec![NO_IMAGE_GREY; w * h * 3];
    let left = m.left_rgb.as_deref().unwrap_or(&grey);
    for b in &m.baselines {
        let hi = positive_range(&b.disparity).map_or(1.0, |r| r.1);
        let title = format!("disparity {} [px]; black = sky", b.name);
        let scale = Scale::Linear { lo: 0.0, hi };
        let c = scalar_map(&title, "px", w, h, &b.disparity, scale);
        out.push((format!("{s}_{}_disp.png", b.name), c));
        let rgb = occlusion_overlay(left, &b.occlusion);
        let title = format!("occlusion {} over the left image", b.name);
        let entries = [(OCC_TINT, "occluded: (pixel + tint) / 2".to_string())];
        out.push((
            format!("{s}_{}_occ.png", b.name),
            palette_map(&title, w, h, &rgb, &entries),
        ));
    }
    out
}

/// Writes every preview of `maps` into `out_dir`; returns the files written.
pub fn write_previews(maps: &FrameMaps, out_dir: &Path) -> io::Result<Vec<PathBuf>> {
    let mut written = Vec::new();
    for (name, canvas) in previews(maps) {
        let p = out_dir.join(name);
        canvas.write_png(&p)?;
        written.push(p);
    }
    Ok(written)
}
