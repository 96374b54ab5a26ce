//! The non-native layouts of a tiny rendered analytic frame (a box on a ground
//! quad under a constant sky, 64×36, spp 1), read back as their users read them.
//!
//! StereoCarla is decoded exactly as OpenStereo's `CarlaDataset` does: 16-bit
//! depth in cm, d = B_cm·f/(depth + 1e-6) in float32, valid where d < 512.
//! Depth is rounded to the nearest cm, |ΔZ| ≤ 0.005 m, so
//! |Δd| = f·B·|1/Z_q − 1/Z| ≤ f·B·0.005 / (Z·(Z − 0.005)), plus float32 rounding.
//!
//! Every layout is also compared with the native frame written from the same
//! render, read back with independent readers (`common::readback`): its left
//! and right images must be the native left view and the native right view
//! of the same baseline (not swapped, not another baseline's), and its depth
//! and disparity files the native values in the layout's encoding.

use crate::common;

use std::fs;
use std::path::Path;

use common::fixtures::analytic_text;
use common::readback::{pfm, png_gray16, rgb8, same};
use common::{render, scene_from_toml, Rendered};
use parallax::accel::Backend;
use parallax::output::frame::{camera_file, write_native_frame, WriteOptions};
use parallax::output::layouts::{
    decode_kitti_disparity, decode_stereocarla_depth, write_layout_frame, write_layout_index,
    FrameKey, LayoutKind, STEREOCARLA_VALID_MAX_PX,
};
use parallax::output::{read_jpeg_rgb8, read_pfm_gray, read_png_gray16, read_png_rgb8};

fn tiny_frame() -> Rendered {
    let text = analytic_text("box_on_ground", (64, 36), &[10.0, 54.0, 300.0]);
    render(&scene_from_toml(&text), Backend::Bvh, 1)
}

fn key(weather: &str) -> FrameKey {
    FrameKey {
        town: "town01".into(),
        config: "normal".into(),
        weather: weather.into(),
        sequence: 2,
        frame: 5,
    }
}

fn write(r: &Rendered, kind: LayoutKind, root: &Path, k: &FrameKey) -> Vec<std::path::PathBuf> {
    let meta = camera_file(&r.scene, &r.rig, &r.out, &settings(k.frame), None);
    write_layout_frame(kind, root, k, &r.rig, &r.out, &meta).expect("layout written")
}

#[test]
fn stereocarla_decoded_as_openstereo_matches_native_disparity_within_cm_quantisation() {
    let r = tiny_frame();
    let dir = tempfile::tempdir().unwrap();
    let files = write(&r, LayoutKind::Stereocarla, dir.path(), &key("clear"));
    // left jpg + 3 × (right jpg, depth png, pose json)
    assert_eq!(files.len(), 1 + 3 * 3);
    let f_px = r.rig.left.intrinsics.f_px;
    let (mut checked, mut sky) = (0, 0);
    for gt in &r.out.baselines {
        let cm = (gt.baseline_m * 100.0).round();
        let b = format!("baseline_{:03}", cm as u32);
        let base = dir.path().join("normal/town01").join(&b);
        let (w, h, depth_cm) = read_png_gray16(&base.join("depth/0002_000005.png")).unwrap();
        assert_eq!((w, h), (64, 36));
        let d = decode_stereocarla_depth(&depth_cm, cm, f_px);
        for (k, &z) in r.out.left.depth_z.iter().enumerate() {
            let valid = d[k] < STEREOCARLA_VALID_MAX_PX;
            if !z.is_finite() {
                assert!(!valid, "sky pixel {k} must be invalid, got {}", d[k]);
                sky += 1;
                continue;
            }
            let fb = f_px * gt.baseline_m;
            assert_eq!(
                valid,
                fb / ((z * 100.0).round() / 100.0) < 512.0,
                "pixel {k}"
            );
            if valid {
                let bound = fb * 0.005 / (z * (z - 0.005)) + 1e-5 * fb / z;
                let err = (d[k] as f64 - gt.disparity_left[k] as f64).abs();
                assert!(
                    err <= bound,
                    "pixel {k} B {cm}: |Δd| {err} > {bound} (Z {z})"
                );
                checked += 1;
            }
        }
        let pose: serde_json::Value =
            serde_json::from_slice(&fs::read(base.join("pose/0002_000005.json")).unwrap()).unwrap();
        assert_eq!(pose["baseline_m"].as_f64(), Some(gt.baseline_m));
        let (rw, rh, _) = read_jpeg_rgb8(&base.join("rgb/0002_000005.jpg")).unwrap();
        assert_eq!((rw, rh), (64, 36));
    }
    assert!(
        sky > 100 && checked > 3 * 500,
        "sky {sky}, checked {checked}"
    );
    // One depth file, the same bytes (hard-linked where the file system allows).
    let depth = |b: &str| {
        fs::read(
            dir.path()
                .join(format!("normal/town01/{b}/depth/0002_000005.png")),
        )
        .unwrap()
    };
    assert_eq!(depth("baseline_010"), depth("baseline_300"));
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let p = dir
            .path()
            .join("normal/town01/baseline_054/depth/0002_000005.png");
        assert_eq!(fs::metadata(p).unwrap().nlink(), 3);
    }
    assert!(read_jpeg_rgb8(&dir.path().join("normal/town01/left/rgb/0002_000005.jpg")).is_ok());
}

#[test]
fn stereocarla_split_lists_name_existing_files_relative_to_the_root() {
    let r = tiny_frame();
    let dir = tempfile::tempdir().unwrap();
    let keys = [key("clear"), key("foggy")];
    for k in &keys {
        write(&r, LayoutKind::Stereocarla, dir.path(), k);
    }
    let written = write_layout_index(
        LayoutKind::Stereocarla,
        dir.path(),
        &keys,
        &[10.0, 54.0, 300.0],
    )
    .unwrap();
    assert_eq!(written.len(), 4);
    let all = fs::read_to_string(dir.path().join("splits/stereocarla_all.txt")).unwrap();
    let lines: Vec<&str> = all.lines().collect();
    assert_eq!(lines.len(), 6);
    assert_eq!(
        lines[1],
        "weather/town01_foggy/left/rgb/0002_000005.jpg \
weather/town01_foggy/baseline_010/rgb/0002_000005.jpg \
weather/town01_foggy/baseline_010/depth/0002_000005.png"
    );
    for line in lines {
        let parts: Vec<&str> = line.split(' ').collect();
        assert_eq!(parts.len(), 3);
        for p in parts {
            assert!(dir.path().join(p).is_file(), "{p} listed but missing");
        }
    }
}

#[test]
fn kitti_disparity_png_round_trips_within_1_over_512_px() {
    let r = tiny_frame();
    let dir = tempfile::tempdir().unwrap();
    let files = write(&r, LayoutKind::Kitti, dir.path(), &key("clear"));
    assert_eq!(files.len(), 3 * 4);
    let stem = "town01_normal_clear_0002_000005.png";
    for gt in &r.out.baselines {
        let b = format!("baseline_{:03}", (gt.baseline_m * 100.0).round() as u32);
        let base = dir.path().join(&b);
        let (_, _, occ_v) = read_png_gray16(&base.join("disp_occ_0").join(stem)).unwrap();
        let (_, _, noc_v) = read_png_gray16(&base.join("disp_noc_0").join(stem)).unwrap();
        let (occ, noc) = (
            decode_kitti_disparity(&occ_v),
            decode_kitti_disparity(&noc_v),
        );
        let mut valid = 0;
        for (k, &d) in gt.disparity_left.iter().enumerate() {
            let fits = d * 256.0 >= 0.5 && d * 256.0 < 65535.5;
            match occ[k] {
                Some(v) => {
                    assert!((v - d).abs() <= 1.0 / 512.0 + 1e-6, "pixel {k}: {v} vs {d}");
                    valid += 1;
                }
                None => assert!(!fits, "pixel {k} with d {d} should be stored"),
            }
            let occluded = gt.occlusion[k] != 0;
            assert_eq!(noc[k], if occluded { None } else { occ[k] }, "pixel {k}");
        }
        assert!(valid > 500);
        assert!(read_png_rgb8(&base.join("image_3").join(stem)).is_ok());
    }
    let idx = write_layout_index(LayoutKind::Kitti, dir.path(), &[key("clear")], &[54.0]).unwrap();
    let text = fs::read_to_string(&idx[0]).unwrap();
    assert_eq!(
        text,
        format!("baseline_054/image_2/{stem} baseline_054/image_3/{stem} baseline_054/disp_occ_0/{stem}\n")
    );
}

#[test]
fn sceneflow_pfms_hold_both_disparities_bit_exactly() {
    let r = tiny_frame();
    let dir = tempfile::tempdir().unwrap();
    write(&r, LayoutKind::Sceneflow, dir.path(), &key("night"));
    for gt in &r.out.baselines {
        let b = format!("baseline_{:03}", (gt.baseline_m * 100.0).round() as u32);
        let seq = dir
            .path()
            .join("disparity")
            .join(&b)
            .join("town01_normal_night/0002");
        let (_, _, left) = read_pfm_gray(&seq.join("left/000005.pfm")).unwrap();
        let (_, _, right) = read_pfm_gray(&seq.join("right/000005.pfm")).unwrap();
        assert_eq!(left, gt.disparity_left);
        assert_eq!(right, gt.disparity_right);
    }
}

#[test]
fn native_layout_and_frames_without_images_are_refused() {
    let mut r = tiny_frame();
    let dir = tempfile::tempdir().unwrap();
    let meta = camera_file(&r.scene, &r.rig, &r.out, &settings(0), None);
    let e = write_layout_frame(
        LayoutKind::Native,
        dir.path(),
        &key("clear"),
        &r.rig,
        &r.out,
        &meta,
    )
    .expect_err("the native layout is not a layout_frame");
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput, "{e}");
    assert!(e.to_string().contains("native"), "{e}");
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 0, "wrote files");
    r.out.images.clear();
    let e = write_layout_frame(
        LayoutKind::Kitti,
        dir.path(),
        &key("clear"),
        &r.rig,
        &r.out,
        &meta,
    )
    .expect_err("a frame without images");
    let msg = e.to_string();
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidInput, "{msg}");
    // 3 baselines: the left view and 3 right views, none rendered.
    assert!(
        msg.contains("kitti") && msg.contains("0 images") && msg.contains("expected 4"),
        "{msg}"
    );
    assert!(msg.contains("spp"), "{msg}");
    assert_eq!(fs::read_dir(dir.path()).unwrap().count(), 0, "wrote files");
}

/// The render settings recorded in a test frame's camera file.
fn settings(frame: u32) -> parallax::render::RenderSettings {
    parallax::render::RenderSettings {
        spp: 1,
        max_depth: 4,
        seed: 3,
        frame,
        adaptive: false,
    }
}

/// The tiny frame written natively (`native/`, frame 5) and in `kind`'s
/// layout (`<kind>/`, key("clear")) from the one render.
fn native_and(kind: LayoutKind) -> (tempfile::TempDir, Rendered) {
    let r = tiny_frame();
    let dir = tempfile::tempdir().unwrap();
    let meta = camera_file(&r.scene, &r.rig, &r.out, &settings(5), None);
    let native = dir.path().join("native");
    write_native_frame(&native, 5, &r.rig, &r.out, meta, WriteOptions::default()).unwrap();
    write(&r, kind, &dir.path().join(kind.name()), &key("clear"));
    (dir, r)
}

/// Baseline directory names of the tiny frame, in rig order.
const BASELINES: [&str; 3] = ["baseline_010", "baseline_054", "baseline_300"];

/// The native views' pixels, left first then each baseline's right view;
/// checks that they all differ, so that a swap cannot go unseen.
fn native_views(root: &Path) -> Vec<Vec<u8>> {
    let mut paths = vec![root.join("native/left/rgb/000005.png")];
    paths.extend(BASELINES.map(|b| root.join(format!("native/{b}/rgb/000005.png"))));
    let views: Vec<Vec<u8>> = paths.iter().map(|p| rgb8(p).2).collect();
    for a in 0..views.len() {
        for b in 0..a {
            assert_ne!(views[a], views[b], "native views {a} and {b} are identical");
        }
    }
    views
}

/// KITTI's 16-bit encoding of a disparity, written out here from its
/// definition: round(d·256), 0 where that is not in 1..=65535.
fn kitti_value(d: f32) -> u16 {
    let v = (d as f64 * 256.0).round();
    if (1.0..=65535.0).contains(&v) {
        v as u16
    } else {
        0
    }
}

#[test]
fn kitti_images_and_disparities_are_the_native_ones_of_their_baseline() {
    let (dir, _r) = native_and(LayoutKind::Kitti);
    let root = dir.path();
    let views = native_views(root);
    let stem = "town01_normal_clear_0002_000005.png";
    for (b, name) in BASELINES.iter().enumerate() {
        let at = |sub: &str| root.join(format!("kitti/{name}/{sub}/{stem}"));
        same(
            &rgb8(&at("image_2")).2,
            &views[0],
            &format!("{name} image_2"),
        );
        same(
            &rgb8(&at("image_3")).2,
            &views[1 + b],
            &format!("{name} image_3"),
        );
        let (_, _, disp) = pfm(&root.join(format!("native/{name}/disp/000005.pfm")));
        let (_, _, occ) =
            common::readback::png_gray8(&root.join(format!("native/{name}/occ/000005.png")));
        let want_occ: Vec<u16> = disp.iter().map(|&d| kitti_value(d)).collect();
        let want_noc: Vec<u16> = want_occ
            .iter()
            .zip(&occ)
            .map(|(&v, &o)| if o == 255 { 0 } else { v })
            .collect();
        assert!(want_occ.iter().filter(|&&v| v > 0).count() > 500);
        assert_ne!(want_occ, want_noc, "{name}: no occluded valid pixel");
        let occ_0 = png_gray16(&at("disp_occ_0")).2;
        same(&occ_0, &want_occ, &format!("{name} disp_occ_0"));
        let noc_0 = png_gray16(&at("disp_noc_0")).2;
        same(&noc_0, &want_noc, &format!("{name} disp_noc_0"));
    }
}

#[test]
fn sceneflow_images_and_disparities_are_the_native_ones_of_their_baseline() {
    let (dir, _r) = native_and(LayoutKind::Sceneflow);
    let root = dir.path();
    let views = native_views(root);
    for (b, name) in BASELINES.iter().enumerate() {
        let seq = |pass: &str, side: &str, ext: &str| {
            root.join(format!(
                "sceneflow/{pass}/{name}/town01_normal_clear/0002/{side}/000005.{ext}"
            ))
        };
        let left = rgb8(&seq("frames_cleanpass", "left", "png")).2;
        same(&left, &views[0], &format!("{name} left"));
        let right = rgb8(&seq("frames_cleanpass", "right", "png")).2;
        same(&right, &views[1 + b], &format!("{name} right"));
        for (side, native) in [("left", "disp"), ("right", "disp_right")] {
            let n = fs::read(root.join(format!("native/{name}/{native}/000005.pfm"))).unwrap();
            let l = fs::read(seq("disparity", side, "pfm")).unwrap();
            assert!(n == l, "{name}: {side} PFM differs from native {native}");
        }
    }
}

/// Mean absolute difference of two 8-bit images, per channel value.
fn mean_abs_diff(a: &[u8], b: &[u8]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(x, y)| x.abs_diff(*y) as f64)
        .sum::<f64>()
        / a.len() as f64
}

#[test]
fn stereocarla_jpegs_are_nearest_to_the_native_view_of_their_baseline() {
    let (dir, r) = native_and(LayoutKind::Stereocarla);
    let root = dir.path();
    let views = native_views(root);
    let base = root.join("stereocarla/normal/town01");
    // The JPEG of view v against every native view: its own must be nearest,
    // by a clear factor (JPEG at quality 95 against different pixels).
    let check = |path: &Path, own: usize| {
        let jpeg = rgb8(path).2;
        let d: Vec<f64> = views.iter().map(|v| mean_abs_diff(&jpeg, v)).collect();
        for (k, &dk) in d.iter().enumerate() {
            if k != own {
                assert!(
                    MARGIN * d[own] < dk,
                    "{}: distances {d:?}, own view {own}",
                    path.display()
                );
            }
        }
    };
    check(&base.join("left/rgb/0002_000005.jpg"), 0);
    let native_cam: serde_json::Value =
        serde_json::from_slice(&fs::read(root.join("native/cameras/000005.json")).unwrap())
            .unwrap();
    let (_, _, depth) =
        common::readback::exr_channel(&root.join("native/left/depth/000005.exr"), "Z");
    let want_cm: Vec<u16> = depth
        .iter()
        .map(|&z| {
            let cm = (z as f64 * 100.0).round();
            if cm.is_finite() && (1.0..=65535.0).contains(&cm) {
                cm as u16
            } else {
                0
            }
        })
        .collect();
    assert!(want_cm.contains(&0) && want_cm.iter().filter(|&&v| v > 0).count() > 500);
    for (b, name) in BASELINES.iter().enumerate() {
        check(&base.join(format!("{name}/rgb/0002_000005.jpg")), 1 + b);
        let (_, _, cm) = png_gray16(&base.join(format!("{name}/depth/0002_000005.png")));
        same(&cm, &want_cm, &format!("{name} depth"));
        let pose: serde_json::Value = serde_json::from_slice(
            &fs::read(base.join(format!("{name}/pose/0002_000005.json"))).unwrap(),
        )
        .unwrap();
        assert_eq!(pose["right_pose"], native_cam["right"][b]["pose"], "{name}");
        assert_eq!(pose["left_pose"], native_cam["left_pose"], "{name}");
        assert_eq!(pose["baseline_m"].as_f64(), Some(r.rig.baselines_m[b]));
    }
}

/// How much nearer a StereoCarla JPEG must be to its own native view than to
/// any other view, in mean absolute difference: measured 0.94–1.05 to its
/// own view against 9.2–14.3 to the others (64×36, spp 1: the views differ
/// by parallax and by their independent sample noise).
const MARGIN: f64 = 4.0;
