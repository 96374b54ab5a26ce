//! What a frame writes and how: the output registry (`registry`: every
//! map declared once), the native layout's paths (`layout`) and writer
//! (`frame`, `native`), the other layouts (`layouts`), and file writers and
//! readers for every output format, all writes atomic; `mitsuba` writes a
//! frame as a Mitsuba 3 scene.
//!
//! Every writer encodes into memory, then [`write_atomic`] writes
//! `<name>.tmp-<pid>-<seq>` in the target directory, fsyncs it and renames it
//! over the target, so a file is either whole or absent (DATASET.md,
//! bookkeeping). Every error is an `io::Error` wrapping an [`OutputError`] that
//! names the path. Images are row-major with the top row first, as `Film`.
//! This module is the only home of the `exr` and `image` crates (STYLE.md).

mod atomic;
mod exr_io;
mod hash;
mod image_io;
mod layout;
mod native;
mod pfm;
mod render_dir;

pub mod frame;
pub mod layouts;
pub mod mitsuba;
pub mod registry;

pub use crate::camera::{baseline_dir_name, check_baseline_dirs, SharedBaselineDir};
pub use atomic::{read_file, temp_base, write_atomic, Access, OutputError};
pub use exr_io::{read_exr_f32_gray, read_exr_rgb_f32, write_exr_f32_gray, write_exr_rgb_f32};
pub use hash::{sha256_bytes, sha256_file, write_json, FileRecord};
pub use image_io::{
    read_jpeg_rgb8, read_png_gray16, read_png_gray8, read_png_rgb8, write_jpeg_rgb8,
    write_png_gray16, write_png_gray8, write_png_rgb8,
};
pub use layout::{frame_stem, is_preview_file, native_path, NativeLayout, NativePath, PREVIEW_DIR};
pub use native::{map_pixels, write_map, MapPixels};
pub use pfm::{decode_pfm_gray, encode_pfm_gray, read_pfm_gray, write_pfm_gray};
pub use registry::{Map, MapSpec, CAMERAS_DIR, LEFT_DIR, MAPS};
pub use render_dir::StagedDir;
