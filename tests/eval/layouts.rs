//! `parallax eval --layout`: predictions laid out as the kitti, sceneflow and
//! stereocarla layouts are found under their documented names and scored
//! exactly as the same prediction in the native tree; and the layouts that
//! parallax writes (a tiny rendered frame) are found by those names.

use crate::common;

use std::path::Path;

use common::fixtures::analytic_text;
use common::{render, scene_from_toml};
use parallax::accel::Backend;
use parallax::eval::{evaluate, EvalOptions, EvalReport, Fill};
use parallax::output::frame::camera_file;
use parallax::output::layouts::{write_layout_frame, FrameKey, LayoutKind};
use parallax::output::{write_pfm_gray, write_png_gray8};

/// Two native ground-truth images: a clear `normal` frame and a foggy `roll05`
/// one (stereocarla puts the latter under `weather/` with a config prefix).
const FRAMES: [(&str, &str, &str); 2] = [
    ("town01/normal_clear/0002", "baseline_054", "000005"),
    ("town01/roll05_foggy/0000", "baseline_010", "000001"),
];

/// Where each layout's mirror puts the prediction of `FRAMES[i]` (DATASET.md
/// names, spelled out here so that the test checks the documented paths).
fn mirrored(layout: LayoutKind, i: usize) -> &'static str {
    match (layout, i) {
        (LayoutKind::Native, 0) => "town01/normal_clear/0002/baseline_054/disp/000005",
        (LayoutKind::Native, _) => "town01/roll05_foggy/0000/baseline_010/disp/000001",
        (LayoutKind::Kitti, 0) => "baseline_054/disp_occ_0/town01_normal_clear_0002_000005",
        (LayoutKind::Kitti, _) => "baseline_010/disp_occ_0/town01_roll05_foggy_0000_000001",
        (LayoutKind::Sceneflow, 0) => "disparity/baseline_054/town01_normal_clear/0002/left/000005",
        (LayoutKind::Sceneflow, _) => "disparity/baseline_010/town01_roll05_foggy/0000/left/000001",
        (LayoutKind::Stereocarla, 0) => "normal/town01/baseline_054/disp/0002_000005",
        (LayoutKind::Stereocarla, _) => "weather/town01_foggy/baseline_010/disp/roll05_0000_000001",
    }
}

fn run(gt: &Path, pred: &Path, layout: LayoutKind) -> EvalReport {
    let opts = EvalOptions {
        layout,
        fill: Fill::None,
    };
    evaluate(gt, pred, &opts).unwrap_or_else(|e| panic!("{layout}: {e}"))
}

#[test]
fn every_layout_mirror_is_found_and_scored_as_the_native_one() {
    let gt = tempfile::tempdir().unwrap();
    // Image 0: errors 1, 0, missing, 5 (D1); image 1: errors 0.5 × 4.
    let truth = [[10.0, 20.0, 30.0, 40.0], [8.0; 4]];
    let preds = [[11.0, 20.0, f32::NAN, 45.0], [8.5; 4]];
    for (i, (seq, b, n)) in FRAMES.iter().enumerate() {
        let base = gt.path().join(seq).join(b);
        write_pfm_gray(&base.join(format!("disp/{n}.pfm")), 2, 2, &truth[i]).unwrap();
        write_png_gray8(&base.join(format!("occ/{n}.png")), 2, 2, &[0; 4]).unwrap();
    }
    let mut reports = Vec::new();
    for layout in LayoutKind::ALL {
        let pred = tempfile::tempdir().unwrap();
        for (i, p) in preds.iter().enumerate() {
            let path = pred.path().join(format!("{}.pfm", mirrored(layout, i)));
            write_pfm_gray(&path, 2, 2, p).unwrap();
        }
        let r = run(gt.path(), pred.path(), layout);
        assert_eq!(
            r.images_evaluated, 2,
            "{layout}: {:?}",
            r.missing_predictions
        );
        // Pooled over 8 valid pixels, 7 predicted: EPE (1 + 5 + 2) / 7; D1
        // (45 vs 40 and the missing pixel) 2/8; density 7/8.
        let o = &r.overall.all.pooled;
        assert!((o.epe - 8.0 / 7.0).abs() < 1e-9, "{layout}: {o:?}");
        assert!((o.d1 - 25.0).abs() < 1e-9 && (o.density - 87.5).abs() < 1e-9);
        let json = serde_json::to_value(&r).unwrap();
        reports.push((layout, json));
    }
    let strip = |v: &serde_json::Value| {
        let mut v = v.clone();
        for k in ["pred", "layout"] {
            v.as_object_mut().unwrap().remove(k);
        }
        v
    };
    let native = strip(&reports[0].1);
    for (layout, r) in &reports[1..] {
        assert_eq!(strip(r), native, "{layout} scores differently from native");
    }
    // A tree laid out otherwise finds nothing, and says where it looked.
    let pred = tempfile::tempdir().unwrap();
    write_pfm_gray(
        &pred
            .path()
            .join(format!("{}.pfm", mirrored(LayoutKind::Kitti, 0))),
        2,
        2,
        &preds[0],
    )
    .unwrap();
    let r = run(gt.path(), pred.path(), LayoutKind::Sceneflow);
    assert_eq!(r.images_evaluated, 0);
    assert_eq!(r.missing_predictions[0], mirrored(LayoutKind::Sceneflow, 0));
}

#[test]
fn layouts_written_by_parallax_are_found_by_their_mirrors() {
    let text = analytic_text("box_on_ground", (32, 18), &[10.0, 54.0]);
    let r = render(&scene_from_toml(&text), Backend::Bvh, 1);
    let (w, h) = (r.out.left.width as usize, r.out.left.height as usize);
    let settings = parallax::render::RenderSettings {
        spp: 1,
        max_depth: 4,
        seed: 3,
        frame: 5,
        adaptive: false,
    };
    let meta = camera_file(&r.scene, &r.rig, &r.out, &settings, None);
    let key = FrameKey {
        town: "town01".into(),
        config: "roll05".into(),
        weather: "foggy".into(),
        sequence: 2,
        frame: 5,
    };
    // The native ground truth of the frame, as the dataset run lays it out.
    let gt = tempfile::tempdir().unwrap();
    for b in &r.out.baselines {
        let base = gt.path().join(format!(
            "town01/roll05_foggy/0002/baseline_{:03}",
            (b.baseline_m * 100.0).round() as u32
        ));
        write_pfm_gray(&base.join("disp/000005.pfm"), w, h, &b.disparity_left).unwrap();
        write_png_gray8(&base.join("occ/000005.png"), w, h, &b.occlusion).unwrap();
    }
    let root = tempfile::tempdir().unwrap();
    for kind in [LayoutKind::Kitti, LayoutKind::Sceneflow] {
        let dir = root.path().join(kind.name());
        write_layout_frame(kind, &dir, &key, &r.rig, &r.out, &meta).unwrap();
        // The layout's own left disparity, scored as a prediction.
        let rep = run(gt.path(), &dir, kind);
        assert_eq!((rep.gt_images, rep.images_evaluated), (2, 2), "{kind}");
        let o = &rep.overall.all.pooled;
        match kind {
            // 16-bit PNG × 256: within 1/512 px wherever stored.
            LayoutKind::Kitti => assert!(o.epe <= 1.0 / 512.0 + 1e-6, "{o:?}"),
            _ => assert_eq!((o.epe, o.density, o.d1), (0.0, 100.0, 0.0)),
        }
    }
    // StereoCarla stores depth: its mirror is the depth file's path with
    // `disp` for `depth`; the depth files it names must exist.
    let dir = root.path().join("stereocarla");
    write_layout_frame(LayoutKind::Stereocarla, &dir, &key, &r.rig, &r.out, &meta).unwrap();
    for img in parallax::eval::find_gt_disparities(gt.path()).unwrap() {
        let stem = parallax::eval::mirror::prediction_stem(&img, LayoutKind::Stereocarla).unwrap();
        let depth = stem.to_str().unwrap().replace("/disp/", "/depth/") + ".png";
        assert!(
            dir.join(&depth).is_file(),
            "{depth} not written by the layout"
        );
    }
}
