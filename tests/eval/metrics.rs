//! `parallax eval` figures against hand-computed values on small arrays, the
//! prediction readers' round trips, and bad inputs through the real binary.

use std::path::Path;

use parallax::eval::pred::read_prediction;
use parallax::eval::{evaluate, image_counts, EvalOptions, Fill, MetricAccumulator, Metrics};
use parallax::output::{
    write_atomic, write_exr_f32_gray, write_pfm_gray, write_png_gray16, write_png_gray8,
};

use crate::common::cli::parallax;

/// `[EPE, D1, bad1, bad2, bad3, density]` within 1e-9.
fn close(m: &Metrics, want: [f64; 6]) {
    let got = [m.epe, m.d1, m.bad1, m.bad2, m.bad3, m.density];
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() < 1e-9, "got {got:?}, want {want:?}");
    }
}

#[test]
fn metrics_match_hand_values_with_d1_both_conditions_noc_and_invalid_pixels() {
    // err: 0.5 | 3.5 (> 3 and > 5 % of 10: D1) | 4 (> 3 but < 5 % of 100: not D1,
    // occluded) | invalid gt 0 | invalid gt inf | 0 | NaN prediction: missing.
    let gt = [10.0, 10.0, 100.0, 0.0, f32::INFINITY, 50.0, 2.0];
    let pred = [10.5, 13.5, 104.0, 7.0, 7.0, 50.0, f32::NAN];
    let occ = [0, 0, 255, 0, 0, 0, 0];
    let (all, noc) = image_counts(&gt, &pred, &occ);
    assert_eq!((all.n, noc.n), (5, 4));
    assert_eq!((all.predicted, all.scored), (4, 4));
    // all: EPE 8/4 over the 4 predicted; the missing pixel is an error in D1
    // and every bad-x: D1 2/5; bad1 3/5 (3.5, 4, missing); bad2 3/5; bad3 3/5;
    // density 4/5.
    close(&all.metrics(), [2.0, 40.0, 60.0, 60.0, 60.0, 80.0]);
    // noc drops the 4 px pixel: EPE 4/3; D1 2/4; bad1 2/4; bad2 2/4; bad3 2/4; density 3/4.
    close(&noc.metrics(), [4.0 / 3.0, 50.0, 50.0, 50.0, 50.0, 75.0]);
}

/// A 4×2 native ground truth (row 1's third pixel is sky) under `root`.
fn missing_gt(root: &Path) {
    let gt = [10.0, 10.0, 10.0, 10.0, 20.0, 20.0, 0.0, 20.0];
    let base = root.join("baseline_010");
    write_pfm_gray(&base.join("disp/000000.pfm"), 4, 2, &gt).unwrap();
    write_png_gray8(&base.join("occ/000000.png"), 4, 2, &[0; 8]).unwrap();
}

#[test]
fn missing_predictions_are_errors_by_default_and_filled_as_kitti_on_request() {
    // Prediction (· = missing): row 0 [11 · · 12], row 1 [· 20 25 24].
    // As a KITTI PNG (0 = missing) and as a PFM (NaN and -1 = missing).
    let gt = tempfile::tempdir().unwrap();
    missing_gt(gt.path());
    let (png, pfm) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let rel = "baseline_010/disp/000000";
    let v = [11.0f32, 0.0, 0.0, 12.0, 0.0, 20.0, 25.0, 24.0];
    let k: Vec<u16> = v.iter().map(|x| (x * 256.0) as u16).collect();
    write_png_gray16(&png.path().join(format!("{rel}.png")), 4, 2, &k).unwrap();
    let f = [11.0, f32::NAN, -1.0, 12.0, f32::NAN, 20.0, 25.0, 24.0];
    write_pfm_gray(&pfm.path().join(format!("{rel}.pfm")), 4, 2, &f).unwrap();
    let run = |pred: &Path, fill: Fill| {
        let opts = EvalOptions {
            fill,
            ..EvalOptions::default()
        };
        evaluate(gt.path(), pred, &opts).unwrap()
    };
    for pred in [png.path(), pfm.path()] {
        // 7 valid pixels, 4 predicted (errors 1, 2, 0, 4): EPE 7/4; bad1 (2, 4,
        // 3 missing) 5/7; bad2 (4 + 3) 4/7; bad3 4/7; D1 4/7; density 4/7.
        let r = run(pred, Fill::None);
        let p = 100.0 / 7.0;
        close(
            &r.overall.all.pooled,
            [1.75, 4.0 * p, 5.0 * p, 4.0 * p, 4.0 * p, 4.0 * p],
        );
        assert_eq!(r.fill, Fill::None);
        assert!(
            r.missing_rule.contains("counted in D1"),
            "{}",
            r.missing_rule
        );
        // KITTI fill: row 0's gap takes min(11, 12) = 11 (errors 1, 1); row 1's
        // left end takes 20 (error 0). Errors 1 1 1 2 | 0 0 4: EPE 9/7; bad1
        // 2/7; bad2, bad3, D1 1/7; density still 4/7 (before the fill).
        let r = run(pred, Fill::Kitti);
        close(
            &r.overall.all.pooled,
            [9.0 / 7.0, p, 2.0 * p, p, p, 4.0 * p],
        );
        assert!(
            r.missing_rule.contains("KITTI devkit"),
            "{}",
            r.missing_rule
        );
    }
}

#[test]
fn pooled_and_per_image_means_differ_as_computed_by_hand() {
    let mut acc = MetricAccumulator::default();
    // Image A: one pixel, error 4 (a D1 outlier). Image B: three exact pixels.
    let (a, _) = image_counts(&[10.0], &[14.0], &[0]);
    let (b, _) = image_counts(&[10.0, 20.0, 30.0], &[10.0, 20.0, 30.0], &[0, 0, 0]);
    let (empty, _) = image_counts(&[0.0], &[1.0], &[0]);
    acc.add_image(&a);
    acc.add_image(&b);
    acc.add_image(&empty);
    close(&acc.pooled(), [1.0, 25.0, 25.0, 25.0, 25.0, 100.0]);
    close(&acc.per_image_mean(), [2.0, 50.0, 50.0, 50.0, 50.0, 100.0]);
    assert_eq!((acc.images, acc.images_with_pixels()), (3, 2));
}

fn npy_bytes(descr: &str, fortran: bool, h: usize, w: usize, data: &[u8]) -> Vec<u8> {
    let mut header = format!(
        "{{'descr': '{descr}', 'fortran_order': {}, 'shape': ({h}, {w}), }}",
        if fortran { "True" } else { "False" }
    );
    while (10 + header.len() + 1) % 64 != 0 {
        header.push(' ');
    }
    header.push('\n');
    let mut out = b"\x93NUMPY\x01\x00".to_vec();
    out.extend_from_slice(&(header.len() as u16).to_le_bytes());
    out.extend_from_slice(header.as_bytes());
    out.extend_from_slice(data);
    out
}

#[test]
fn prediction_readers_round_trip_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let (w, h) = (3, 2);
    let v: Vec<f32> = vec![0.0, 1.5, 2.25, 100.0, 255.5, 7.75];
    let p = dir.path().join("a.pfm");
    write_pfm_gray(&p, w, h, &v).unwrap();
    assert_eq!(read_prediction(&p).unwrap(), (w, h, v.clone()));
    let p = dir.path().join("a.exr");
    write_exr_f32_gray(&p, w, h, &v).unwrap();
    assert_eq!(read_prediction(&p).unwrap(), (w, h, v.clone()));
    // KITTI ×256: these values are multiples of 1/256, so exact; 0 = missing (NaN).
    let p = dir.path().join("a.png");
    let k: Vec<u16> = v.iter().map(|x| (x * 256.0) as u16).collect();
    write_png_gray16(&p, w, h, &k).unwrap();
    let (pw, ph, got) = read_prediction(&p).unwrap();
    assert_eq!((pw, ph), (w, h));
    assert!(got[0].is_nan(), "PNG 0 reads as missing, got {}", got[0]);
    assert_eq!(got[1..], v[1..]);
    // .npy: float32 C order, float64 C order, float32 Fortran order.
    let f32_c: Vec<u8> = v.iter().flat_map(|x| x.to_le_bytes()).collect();
    let f64_c: Vec<u8> = v.iter().flat_map(|x| (*x as f64).to_le_bytes()).collect();
    let mut f32_f = Vec::new();
    for i in 0..w {
        for j in 0..h {
            f32_f.extend_from_slice(&v[j * w + i].to_le_bytes());
        }
    }
    for (name, descr, fortran, data) in [
        ("c32.npy", "<f4", false, f32_c),
        ("c64.npy", "<f8", false, f64_c),
        ("f32.npy", "<f4", true, f32_f),
    ] {
        let p = dir.path().join(name);
        write_atomic(&p, &npy_bytes(descr, fortran, h, w, &data)).unwrap();
        assert_eq!(read_prediction(&p).unwrap(), (w, h, v.clone()), "{name}");
    }
    let p = dir.path().join("i32.npy");
    write_atomic(&p, &npy_bytes("<i4", false, h, w, &[0u8; 24])).unwrap();
    let e = read_prediction(&p).unwrap_err().to_string();
    assert!(e.contains("i32.npy") && e.contains("float"), "{e}");
}

/// Writes one native GT image (disparity + occlusion) below `root/seq`.
fn gt_image(root: &Path, seq: &str, b: &str, disp: &[f32], occ: &[u8]) {
    let base = root.join(seq).join(b);
    write_pfm_gray(&base.join("disp/000000.pfm"), 2, 2, disp).unwrap();
    write_png_gray8(&base.join("occ/000000.png"), 2, 2, occ).unwrap();
}

#[test]
fn dataset_groups_are_parsed_from_paths_and_missing_predictions_counted() {
    let gt = tempfile::tempdir().unwrap();
    let pred = tempfile::tempdir().unwrap();
    let s1 = "town01/normal_clear/0000";
    let s2 = "town02/roll05_foggy/0001";
    gt_image(
        gt.path(),
        s1,
        "baseline_010",
        &[10.0, 10.0, 0.0, 20.0],
        &[0, 0, 0, 255],
    );
    gt_image(
        gt.path(),
        s2,
        "baseline_010",
        &[4.0, 4.0, 4.0, 4.0],
        &[0; 4],
    );
    gt_image(gt.path(), s2, "baseline_054", &[1.0; 4], &[0; 4]);
    // s1: errors 2, 0, (invalid), 10 (occluded, D1) — as a 16-bit KITTI PNG.
    let k: Vec<u16> = [12.0f32, 10.0, 3.0, 30.0]
        .iter()
        .map(|x| (x * 256.0) as u16)
        .collect();
    write_png_gray16(
        &pred.path().join(s1).join("baseline_010/disp/000000.png"),
        2,
        2,
        &k,
    )
    .unwrap();
    // s2 baseline_010: every error 1 — as PFM; baseline_054 missing.
    write_pfm_gray(
        &pred.path().join(s2).join("baseline_010/disp/000000.pfm"),
        2,
        2,
        &[5.0; 4],
    )
    .unwrap();
    let r = evaluate(gt.path(), pred.path(), &EvalOptions::default()).unwrap();
    assert_eq!((r.gt_images, r.images_evaluated), (3, 2));
    assert_eq!(
        r.missing_predictions,
        vec![format!("{s2}/baseline_054/disp/000000")]
    );
    // Pooled all: errors 2, 0, 10, 1, 1, 1, 1 → 16/7 px; bad1 2/7; D1 1/7.
    let o = &r.overall.all.pooled;
    assert!((o.epe - 16.0 / 7.0).abs() < 1e-12);
    assert!((o.bad1 - 200.0 / 7.0).abs() < 1e-9 && (o.d1 - 100.0 / 7.0).abs() < 1e-9);
    // Per image: EPE 4 and 1 → 2.5.
    assert!((r.overall.all.per_image_mean.epe - 2.5).abs() < 1e-12);
    // noc drops the 10 px pixel: errors 2, 0, 1, 1, 1, 1 → 1 px.
    assert!((r.overall.noc.pooled.epe - 1.0).abs() < 1e-12);
    assert_eq!(r.per_town["town01"].images, 1);
    assert!((r.per_town["town01"].all.pooled.epe - 4.0).abs() < 1e-12);
    assert_eq!(r.per_config["roll05"].pixels_all, 4);
    assert_eq!(r.per_weather["foggy"].images, 1);
    assert_eq!(r.per_baseline.len(), 1, "baseline_054 had no prediction");
}

/// `(exit code, stderr, stdout)` of `parallax eval ARGS`.
fn run_eval(args: &[&str]) -> (i32, String, String) {
    let out = parallax(&[]).arg("eval").args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

#[test]
fn eval_cli_bad_inputs_exit_2_naming_the_path() {
    let gt = tempfile::tempdir().unwrap();
    let pred = tempfile::tempdir().unwrap();
    let sink = tempfile::tempdir().unwrap();
    gt_image(gt.path(), "", "baseline_010", &[1.0; 4], &[0; 4]);
    let (g, p) = (gt.path().to_str().unwrap(), pred.path().to_str().unwrap());
    let report = sink.path().join("report.json");
    let r = report.to_str().unwrap();
    // Every failing run asks for a report: none may be written.
    let fails = |args: &[&str], needles: &[&str]| {
        let (code, err, _) = run_eval(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        for n in needles {
            assert!(err.contains(n), "stderr does not name `{n}`: {err}");
        }
        assert!(!report.exists(), "{args:?}: a failed run wrote the report");
    };
    fails(
        &["--gt", "/no/such/gt", "--pred", p, "--json", r],
        &["/no/such/gt"],
    );
    // Wrong size.
    let bad = pred.path().join("baseline_010/disp/000000.pfm");
    write_pfm_gray(&bad, 3, 1, &[1.0; 3]).unwrap();
    let b = bad.to_str().unwrap();
    fails(&["--gt", g, "--pred", p, "--json", r], &[b, "3×1"]);
    // Unreadable (garbage bytes).
    write_atomic(&bad, b"not a pfm").unwrap();
    fails(&["--gt", g, "--pred", p, "--json", r], &[b]);
    // Unknown fill or layout; a layout a bare render directory cannot have.
    fails(
        &["--gt", g, "--pred", p, "--fill", "zero", "--json", r],
        &["--fill", "zero", "none or kitti"],
    );
    fails(
        &[
            "--gt",
            g,
            "--pred",
            p,
            "--layout",
            "middlebury",
            "--json",
            r,
        ],
        &["--layout", "middlebury", "kitti"],
    );
    fails(
        &["--gt", g, "--pred", p, "--layout", "kitti", "--json", r],
        &[g, "baseline_010/disp/000000.pfm", "--layout native"],
    );
    assert_eq!(std::fs::read_dir(sink.path()).unwrap().count(), 0);
    // A good prediction: exit 0 and a JSON report.
    write_pfm_gray(&bad, 2, 2, &[1.0; 4]).unwrap();
    let (code, err, out) = run_eval(&["--gt", g, "--pred", p, "--json", r]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("dens %") && out.contains("fill none: missing prediction"),
        "{out}"
    );
    let v: serde_json::Value = serde_json::from_slice(&std::fs::read(&report).unwrap()).unwrap();
    assert_eq!(v["overall"]["all"]["pooled"]["epe"].as_f64(), Some(0.0));
    assert_eq!(v["per_town"]["-"]["images"].as_u64(), Some(1));
    assert_eq!(
        v["overall"]["all"]["pooled"]["density"].as_f64(),
        Some(100.0)
    );
    assert_eq!(v["fill"].as_str(), Some("none"));
    assert_eq!(v["layout"].as_str(), Some("native"));
    assert!(v["missing_rule"].as_str().unwrap().contains("density"));
}
