//! Round trips and failure modes of the output writers: PFM (bit-exact, rows
//! bottom-up in the file, both byte orders), EXR depth and RGB (bit-exact,
//! +inf kept), PNG 8/16-bit, JPEG, JSON, SHA-256 records, atomic replacement,
//! and errors that name the path; and a frame written by `parallax render`
//! read back file by file against the library's render of the same scene.

use crate::common;
use crate::common::cli::parallax;
use crate::common::readback::bits;

use glam::Vec3;
use parallax::output::*;
use std::fs;
use std::path::Path;

/// Non-square, odd-sized test values with +inf, ±0, negatives and subnormals.
fn depth_pattern(w: usize, h: usize) -> Vec<f32> {
    (0..w * h)
        .map(|k| match k % 7 {
            0 => f32::INFINITY,
            1 => 0.0,
            2 => -(k as f32) * 0.37,
            3 => -0.0,
            4 => f32::MIN_POSITIVE / 3.0,
            _ => 1.0 + k as f32 * 1.618_034,
        })
        .collect()
}

/// Files left in a directory other than `keep`.
fn stray_files(dir: &Path, keep: &[&str]) -> Vec<String> {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| !keep.contains(&n.as_str()))
        .collect()
}

#[test]
fn pfm_round_trip_is_bit_exact_with_inf_zero_negative() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a/b/disp.pfm");
    let (w, h) = (7, 5);
    let data = depth_pattern(w, h);
    write_pfm_gray(&path, w, h, &data).unwrap();
    let (rw, rh, back) = read_pfm_gray(&path).unwrap();
    assert_eq!((rw, rh), (w, h));
    assert_eq!(bits(&back), bits(&data));
}

#[test]
fn pfm_file_stores_rows_bottom_up_little_endian() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("d.pfm");
    let (w, h) = (3, 2);
    // Top row 1,2,3; bottom row 4,5,6.
    let data = [1.0f32, 2.0, 3.0, 4.0, 5.0, 6.0];
    write_pfm_gray(&path, w, h, &data).unwrap();
    let raw = fs::read(&path).unwrap();
    let header = b"Pf\n3 2\n-1.0\n";
    assert_eq!(&raw[..header.len()], header);
    assert_eq!(raw.len(), header.len() + 6 * 4);
    let at = |k: usize| {
        let o = header.len() + 4 * k;
        f32::from_le_bytes(raw[o..o + 4].try_into().unwrap())
    };
    // The first stored row is the image's bottom row.
    assert_eq!([at(0), at(1), at(2)], [4.0, 5.0, 6.0]);
    assert_eq!([at(3), at(4), at(5)], [1.0, 2.0, 3.0]);
}

#[test]
fn pfm_reader_accepts_big_endian_and_bottom_up_order() {
    // Hand-built big-endian file (positive scale), 2×3, extra header spacing.
    let mut raw = b"Pf\n2  3\n1.0\n".to_vec();
    let file_rows = [[5.0f32, 6.0], [3.0, 4.0], [1.0, f32::INFINITY]];
    for row in file_rows {
        for v in row {
            raw.extend_from_slice(&v.to_be_bytes());
        }
    }
    let (w, h, data) = decode_pfm_gray(&raw).unwrap();
    assert_eq!((w, h), (2, 3));
    assert_eq!(data, vec![1.0, f32::INFINITY, 3.0, 4.0, 5.0, 6.0]);
}

#[test]
fn pfm_reader_rejects_colour_truncated_and_garbage() {
    assert!(decode_pfm_gray(b"PF\n1 1\n-1.0\n\0\0\0\0\0\0\0\0\0\0\0\0").is_err());
    assert!(decode_pfm_gray(b"Pf\n2 2\n-1.0\n\0\0\0\0").is_err());
    assert!(decode_pfm_gray(b"P6\n1 1\n255\n\0\0\0").is_err());
    assert!(decode_pfm_gray(b"Pf\n1 1\n0.0\n\0\0\0\0").is_err());
    assert!(decode_pfm_gray(b"Pf\n").is_err());
}

#[test]
fn exr_gray_round_trip_is_bit_exact_with_inf() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("depth/000000.exr");
    let (w, h) = (37, 19);
    let data = depth_pattern(w, h);
    write_exr_f32_gray(&path, w, h, &data).unwrap();
    let (rw, rh, back) = read_exr_f32_gray(&path).unwrap();
    assert_eq!((rw, rh), (w, h));
    assert_eq!(bits(&back), bits(&data));
}

#[test]
fn exr_rgb_round_trip_is_bit_exact() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("normal.exr");
    let (w, h) = (9, 4);
    let data: Vec<Vec3> = (0..w * h)
        .map(|k| Vec3::new(k as f32 * 0.1, -(k as f32), 1e6 / (k as f32 + 1.0)))
        .collect();
    write_exr_rgb_f32(&path, w, h, &data).unwrap();
    let (rw, rh, back) = read_exr_rgb_f32(&path).unwrap();
    assert_eq!((rw, rh), (w, h));
    assert_eq!(back, data);
}

#[test]
fn exr_bytes_are_identical_for_identical_pixels() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("a.exr"), dir.path().join("b.exr"));
    let data = depth_pattern(64, 40);
    write_exr_f32_gray(&a, 64, 40, &data).unwrap();
    write_exr_f32_gray(&b, 64, 40, &data).unwrap();
    assert_eq!(fs::read(&a).unwrap(), fs::read(&b).unwrap());
}

#[test]
fn exr_gray_reader_requires_z_channel() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("rgb.exr");
    write_exr_rgb_f32(&path, 2, 2, &[Vec3::ONE; 4]).unwrap();
    let err = read_exr_f32_gray(&path).unwrap_err();
    assert!(err.to_string().contains("rgb.exr"), "{err}");
}

#[test]
fn png_rgb8_and_gray8_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (5, 3);
    let rgb: Vec<u8> = (0..w * h * 3).map(|k| (k * 17 % 256) as u8).collect();
    let gray: Vec<u8> = (0..w * h).map(|k| (255 - k * 13 % 256) as u8).collect();
    let (p_rgb, p_gray) = (dir.path().join("rgb.png"), dir.path().join("g.png"));
    write_png_rgb8(&p_rgb, w, h, &rgb).unwrap();
    write_png_gray8(&p_gray, w, h, &gray).unwrap();
    assert_eq!(read_png_rgb8(&p_rgb).unwrap(), (w, h, rgb));
    assert_eq!(read_png_gray8(&p_gray).unwrap(), (w, h, gray));
    // No silent conversion between pixel types.
    assert!(read_png_gray8(&p_rgb).is_err());
    assert!(read_png_gray16(&p_gray).is_err());
}

#[test]
fn png_gray16_round_trip_keeps_full_range() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("instance.png");
    let (w, h) = (3, 7);
    let mut data: Vec<u16> = (0..w * h).map(|k| (k as u16).wrapping_mul(3119)).collect();
    data[0] = 0;
    data[1] = u16::MAX;
    data[2] = 0x0100; // a byte-order mix-up would read 0x0001
    write_png_gray16(&path, w, h, &data).unwrap();
    assert_eq!(read_png_gray16(&path).unwrap(), (w, h, data));
}

#[test]
fn jpeg_round_trip_is_close_at_high_quality() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("left/rgb/000000.jpg");
    let (w, h) = (16, 8);
    let rgb: Vec<u8> = (0..w * h).flat_map(|k| [(k * 2) as u8, 128, 200]).collect();
    write_jpeg_rgb8(&path, w, h, &rgb, 95).unwrap();
    let (rw, rh, back) = read_jpeg_rgb8(&path).unwrap();
    assert_eq!((rw, rh), (w, h));
    let max_err = rgb
        .iter()
        .zip(&back)
        .map(|(a, b)| a.abs_diff(*b))
        .max()
        .unwrap();
    assert!(max_err <= 8, "max error {max_err}");
    assert!(write_jpeg_rgb8(&path, w, h, &rgb, 0).is_err());
}

#[test]
fn writers_reject_wrong_buffer_length_naming_path() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("short.png");
    let err = write_png_rgb8(&path, 4, 4, &[0u8; 47]).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::InvalidInput);
    assert!(err.to_string().contains("short.png"), "{err}");
    assert!(write_pfm_gray(&path, 2, 2, &[0.0; 3]).is_err());
    assert!(write_exr_f32_gray(&path, 2, 2, &[0.0; 5]).is_err());
    assert!(!path.exists());
}

#[test]
fn atomic_write_replaces_whole_file_and_leaves_no_temp() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("x.bin");
    write_atomic(&path, &[7u8; 10_000]).unwrap();
    write_atomic(&path, b"short").unwrap();
    assert_eq!(fs::read(&path).unwrap(), b"short");
    write_pfm_gray(&dir.path().join("d.pfm"), 1, 1, &[2.0]).unwrap();
    assert_eq!(
        stray_files(dir.path(), &["x.bin", "d.pfm"]),
        Vec::<String>::new()
    );
}

#[test]
fn unwritable_path_errors_name_the_path_and_leave_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let blocker = dir.path().join("file");
    fs::write(&blocker, b"not a directory").unwrap();
    // The parent "directory" is a regular file: fails even when run as root.
    let path = blocker.join("sub/000000.png");
    let err = write_png_gray8(&path, 1, 1, &[0]).unwrap_err();
    let msg = err.to_string();
    assert!(msg.starts_with("cannot write "), "{msg}");
    assert!(msg.contains(&path.display().to_string()), "{msg}");
    let inner = err
        .get_ref()
        .unwrap()
        .downcast_ref::<OutputError>()
        .unwrap();
    assert_eq!(inner.path, path);
    assert_eq!(inner.access, Access::Write);
    assert!(write_json(&blocker.join("c.json"), &1).is_err());
    assert_eq!(stray_files(dir.path(), &["file"]), Vec::<String>::new());
    assert_eq!(fs::read(&blocker).unwrap(), b"not a directory");
}

#[test]
fn missing_file_read_error_names_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("nope.pfm");
    let err = read_pfm_gray(&path).unwrap_err();
    assert_eq!(err.kind(), std::io::ErrorKind::NotFound);
    assert!(err.to_string().starts_with("cannot read "), "{err}");
    assert!(err.to_string().contains("nope.pfm"), "{err}");
    assert!(sha256_file(&path)
        .unwrap_err()
        .to_string()
        .contains("nope.pfm"));
}

#[test]
fn json_is_pretty_and_parses_back() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("cameras/000000.json");
    let value = serde_json::json!({"fx_px": 1385.64, "baselines_m": [0.1, 0.54]});
    write_json(&path, &value).unwrap();
    let text = fs::read_to_string(&path).unwrap();
    assert!(text.contains("\n  \"fx_px\""), "{text}");
    assert!(text.ends_with("}\n"));
    let back: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(back, value);
}

#[test]
fn file_record_has_relative_path_size_and_known_hash() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("left/rgb/abc.txt");
    write_atomic(&path, b"abc").unwrap();
    // FIPS 180-2 test vector for "abc".
    let expected = "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad";
    assert_eq!(sha256_file(&path).unwrap(), expected);
    let rec = FileRecord::of(dir.path(), &path).unwrap();
    assert_eq!(rec.path, "left/rgb/abc.txt");
    assert_eq!(rec.bytes, 3);
    assert_eq!(rec.sha256, expected);
    assert!(rec.verify(dir.path()).unwrap());
    write_atomic(&path, b"abd").unwrap();
    assert!(!rec.verify(dir.path()).unwrap());
    assert!(FileRecord::of(Path::new("/elsewhere"), &path).is_err());
}

#[test]
fn native_layout_files_round_trip_through_writers() {
    let dir = tempfile::tempdir().unwrap();
    let layout = NativeLayout::new(dir.path());
    let disp = [0.0f32, 12.5, 3318.0, 0.25];
    write_pfm_gray(&layout.path(Map::Disparity, 42, Some(54.0)), 2, 2, &disp).unwrap();
    let (_, _, back) = read_pfm_gray(&dir.path().join("baseline_054/disp/000042.pfm")).unwrap();
    assert_eq!(back, disp);
}

/// A small analytic scene with every ground-truth channel non-trivial: sky
/// (mask bit 1), a mirror-flagged box (bit 8), semantic classes and a
/// 16-bit instance id above 255, three baselines.
fn labelled_scene() -> String {
    common::camera_block(64, 36, [0.0, 0.0, 1.65])
        + "baselines_cm = [10.0, 54.0, 300.0]\n[render]\nspp = 2\nmax_depth = 3\nseed = 9\n"
        + common::GREY_UNDER_SKY
        + r#"
[[material]]
name = "chrome"
kind = "diffuse"
albedo = [0.8, 0.8, 0.8]
mask = ["mirror"]
[[object]]
kind = "quad"
size = [1000.0, 1000.0]
material = "grey"
semantic = "road"
[[object]]
kind = "box"
size = [2.0, 1.6, 1.5]
material = "grey"
semantic = "car"
instance = 300
transform = { translate = [7.0, 0.8, 0.75] }
[[object]]
kind = "box"
size = [1.0, 1.0, 3.0]
material = "chrome"
semantic = "pole"
instance = 7
transform = { translate = [11.0, -2.5, 1.5] }
"#
}

/// `parallax render` writes a frame; every file, read back with the `exr`
/// and `image` crates and a PFM parser of its own, holds bit for bit what the
/// library renders from the same scene, and the camera file's right poses
/// are the left pose moved by B·x_L (GROUND_TRUTH.md, stereo rig).
#[test]
fn native_frame_written_by_the_binary_reads_back_as_the_render() {
    use common::readback::{
        bits, exr_channel, exr_channels, pfm, png_gray16, png_gray8, rgb8, same,
    };
    let dir = tempfile::tempdir().unwrap();
    let text = labelled_scene();
    let scene_path = dir.path().join("scene.toml");
    fs::write(&scene_path, &text).unwrap();
    let out_dir = dir.path().join("out");
    let o = parallax(&[])
        .args(["render", scene_path.to_str().unwrap(), "-o"])
        .arg(&out_dir)
        .args(["--backend", "bvh", "--threads", "2", "--hdr"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let r = common::render(
        &common::scene_from_toml(&text),
        parallax::accel::Backend::Bvh,
        2,
    );
    let g = &r.out.left;
    let file = |rel: &str| out_dir.join(rel);

    // Every channel must carry information, or its comparison proves little.
    let sky = g.depth_z.iter().filter(|z| z.is_infinite()).count();
    assert!(sky > 100 && sky < 64 * 36 - 100, "sky pixels {sky}");
    for (bit, name) in [(1u8, "sky"), (8, "mirror")] {
        assert!(g.mask.iter().any(|m| m & bit != 0), "no {name} bit");
    }
    assert!(g.instance.contains(&300) && g.instance.contains(&7));
    let classes: std::collections::BTreeSet<u8> = g.semantic.iter().copied().collect();
    assert!(classes.len() >= 4, "classes {classes:?}");

    // Each reader's (width, height, data), checked to be 64×36.
    fn sized<T>((fw, fh, v): (usize, usize, T), what: &str) -> T {
        assert_eq!((fw, fh), (64, 36), "{what}: size");
        v
    }
    let depth: Vec<f32> = g.depth_z.iter().map(|&z| z as f32).collect();
    let read = sized(exr_channel(&file("left/depth/000000.exr"), "Z"), "depth");
    same(&bits(&read), &bits(&depth), "left depth");
    let normal = sized(exr_channels(&file("left/normal/000000.exr")), "normal");
    for (c, name) in ["R", "G", "B"].iter().enumerate() {
        let want: Vec<f32> = g.normal_world.iter().map(|n| n[c]).collect();
        same(
            &bits(&normal[*name]),
            &bits(&want),
            &format!("normal {name}"),
        );
    }
    let semantic = sized(png_gray8(&file("left/semantic/000000.png")), "semantic");
    same(&semantic, &g.semantic, "semantic");
    let instance = sized(png_gray16(&file("left/instance/000000.png")), "instance");
    same(&instance, &g.instance, "instance");
    same(
        &sized(png_gray8(&file("left/mask/000000.png")), "mask"),
        &g.mask,
        "mask",
    );
    let mut seen_occlusion = false;
    for (b, gt) in r.out.baselines.iter().enumerate() {
        let d = format!("baseline_{:03}", [10, 54, 300][b]);
        let disp = sized(pfm(&file(&format!("{d}/disp/000000.pfm"))), &d);
        same(
            &bits(&disp),
            &bits(&gt.disparity_left),
            &format!("{d} disp"),
        );
        // The stored values are f·B/Z of the stored depth (not a swapped map).
        let f = r.rig.left.intrinsics.f_px;
        for (k, &z) in depth.iter().enumerate() {
            let want = if z.is_finite() {
                f * gt.baseline_m / z as f64
            } else {
                0.0
            };
            assert!(
                (disp[k] as f64 - want).abs() <= 1e-5 * want.max(1.0),
                "{d} {k}"
            );
        }
        let disp_r = sized(pfm(&file(&format!("{d}/disp_right/000000.pfm"))), &d);
        same(
            &bits(&disp_r),
            &bits(&gt.disparity_right),
            &format!("{d} disp_right"),
        );
        let depth_r = exr_channel(&file(&format!("{d}/depth_right/000000.exr")), "Z");
        let depth_r = sized(depth_r, &d);
        same(
            &bits(&depth_r),
            &bits(&gt.depth_right),
            &format!("{d} depth_right"),
        );
        let occ = sized(png_gray8(&file(&format!("{d}/occ/000000.png"))), &d);
        same(&occ, &gt.occlusion, &format!("{d} occ"));
        seen_occlusion |= gt.occlusion.contains(&255);
    }
    assert!(seen_occlusion, "no occluded pixel at any baseline");

    // Images: the tone-mapped film of each view, and its linear radiance.
    let views = std::iter::once("left".to_string())
        .chain([10, 54, 300].map(|cm| format!("baseline_{cm:03}")));
    for (film, v) in r.out.images.iter().zip(views) {
        let srgb = parallax::film::tonemap_to_srgb8(film, r.out.exposure_scale);
        let png = sized(rgb8(&file(&format!("{v}/rgb/000000.png"))), &v);
        same(&png, &srgb, &format!("{v} rgb"));
        let hdr = sized(exr_channels(&file(&format!("{v}/rgb_hdr/000000.exr"))), &v);
        for (c, name) in ["R", "G", "B"].iter().enumerate() {
            let want: Vec<f32> = film.rgb.iter().map(|p| p[c]).collect();
            same(&bits(&hdr[*name]), &bits(&want), &format!("{v} hdr {name}"));
        }
    }

    let cam: serde_json::Value =
        serde_json::from_slice(&fs::read(file("cameras/000000.json")).unwrap()).unwrap();
    let m = |v: &serde_json::Value| -> [[f64; 4]; 4] { serde_json::from_value(v.clone()).unwrap() };
    let left = m(&cam["left_pose"]);
    assert_eq!(left, r.rig.left.pose_matrix());
    let right = cam["right"].as_array().unwrap();
    assert_eq!(right.len(), 3);
    for (b, entry) in right.iter().enumerate() {
        let bm = [0.10, 0.54, 3.0][b];
        assert_eq!(entry["baseline_m"].as_f64(), Some(bm));
        assert_eq!(entry["dir"], format!("baseline_{:03}", [10, 54, 300][b]));
        let pose = m(&entry["pose"]);
        for row in 0..3 {
            // Same rotation; centre C_L + B·x_L, x_L the rotation's first column.
            assert_eq!(pose[row][..3], left[row][..3], "baseline {bm} row {row}");
            let want = left[row][3] + bm * left[row][0];
            assert!((pose[row][3] - want).abs() < 1e-12, "{bm}: {pose:?}");
        }
        assert_eq!(pose[3], [0.0, 0.0, 0.0, 1.0]);
    }
    // A level rig at [0, 0, 1.65] looking along +x: x_L is the world's −y.
    let c = common::level_right_centre(glam::DVec3::new(0.0, 0.0, 1.65), 0.54);
    let p = m(&right[1]["pose"]);
    assert!((glam::DVec3::new(p[0][3], p[1][3], p[2][3]) - c).length() < 1e-12);
    assert_eq!(cam["seed"], 9);
    assert_eq!(cam["spp"], 2);
    assert_eq!(cam["f_px"].as_f64(), Some(r.rig.left.intrinsics.f_px));
    // Written as an f32's shortest decimal: read back as f32.
    assert_eq!(
        cam["exposure_scale"].as_f64().map(|x| x as f32),
        Some(r.out.exposure_scale)
    );

    // Nothing else was written: left 5 maps + rgb + rgb_hdr + the two
    // denoiser AOVs (albedo, aov_normal) that come with --hdr, per baseline
    // 4 maps + rgb + rgb_hdr, one camera file.
    let count = walk_files(&out_dir);
    assert_eq!(count, 5 + 2 + 2 + 3 * (4 + 2) + 1);
}

/// Number of regular files below `dir`.
fn walk_files(dir: &Path) -> usize {
    fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .map(|p| if p.is_dir() { walk_files(&p) } else { 1 })
        .sum()
}
