//! `parallax stats` through the real binary on a small hand-made native tree
//! (PFMs written here), against numpy-style hand values: valid = finite and
//! > 0; median = mean of the two middle values for an even count.

use std::fs;
use std::path::Path;

use parallax::output::write_pfm_gray;

use crate::common::cli::parallax;

fn pfm(root: &Path, rel: &str, v: [f32; 4]) {
    write_pfm_gray(&root.join(rel), 2, 2, &v).unwrap();
}

fn stats(args: &[&str]) -> (i32, String, String) {
    let out = parallax(&[]).arg("stats").args(args).output().unwrap();
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

fn near(v: &serde_json::Value, want: f64) {
    let got = v.as_f64().unwrap_or(f64::NAN);
    assert!((got - want).abs() < 1e-9, "got {got}, want {want}");
}

#[test]
fn stats_match_numpy_style_hand_values_and_count_frames() {
    let d = tempfile::tempdir().unwrap();
    let r = d.path();
    let s1 = "town01/normal_clear/0000";
    pfm(
        r,
        &format!("{s1}/baseline_010/disp/000000.pfm"),
        [0.0, 2.0, 4.0, f32::NAN],
    );
    pfm(
        r,
        &format!("{s1}/baseline_054/disp/000000.pfm"),
        [0.0, 10.75, 21.5, 3.0],
    );
    pfm(
        r,
        &format!("{s1}/baseline_010/disp/000001.pfm"),
        [1.0, 1.0, 1.0, f32::INFINITY],
    );
    pfm(
        r,
        "town02/pitch30_night/0003/baseline_010/disp/000000.pfm",
        [100.0, 0.5, 0.0, -1.0],
    );
    // Not disparities: must be ignored.
    pfm(
        r,
        &format!("{s1}/baseline_010/disp_right/000000.pfm"),
        [9e3; 4],
    );
    let json = r.join("stats.json");
    let plots = r.join("plots");
    let (code, out, err) = stats(&[
        r.to_str().unwrap(),
        "--json",
        json.to_str().unwrap(),
        "--plot",
        plots.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(
        out.contains("overall") && out.contains("baseline_054"),
        "{out}"
    );
    let v: serde_json::Value = serde_json::from_slice(&fs::read(&json).unwrap()).unwrap();
    // baseline_010 valid: 2, 4, 1, 1, 1, 100, 0.5 → sorted 0.5 1 1 1 2 4 100.
    let b010 = &v["per_baseline"]["baseline_010"];
    assert_eq!(b010["pixels"].as_u64(), Some(7));
    near(&b010["min"], 0.5);
    near(&b010["max"], 100.0);
    near(&b010["mean"], 109.5 / 7.0);
    near(&b010["median"], 1.0);
    // baseline_054 valid: 10.75, 21.5, 3 → median 10.75, mean 11.75.
    let b054 = &v["per_baseline"]["baseline_054"];
    near(&b054["median"], 10.75);
    near(&b054["mean"], 11.75);
    // overall, 10 values: 0.5 1 1 1 2 | 3 4 10.75 21.5 100 → median 2.5.
    let o = &v["overall"];
    assert_eq!(o["pixels"].as_u64(), Some(10));
    near(&o["median"], 2.5);
    near(&o["mean"], 144.75 / 10.0);
    assert_eq!(v["frames"].as_u64(), Some(3));
    assert_eq!(v["disparity_images"].as_u64(), Some(4));
    assert_eq!(v["frames_per_town"]["town01"].as_u64(), Some(2));
    assert_eq!(v["frames_per_town"]["town02"].as_u64(), Some(1));
    assert_eq!(v["frames_per_config"]["pitch30"].as_u64(), Some(1));
    assert_eq!(v["frames_per_weather"]["clear"].as_u64(), Some(2));
    near(&v["median_bin_width_px"], 1.0 / 32.0);
    // Plots: one PNG and one CSV per histogram; the CSV bars hold every pixel.
    for name in ["overall", "baseline_010", "baseline_054"] {
        assert!(plots.join(format!("hist_{name}.png")).is_file());
    }
    let csv = fs::read_to_string(plots.join("hist_overall.csv")).unwrap();
    let total: u64 = csv
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap().parse::<u64>().unwrap())
        .sum();
    assert_eq!(total, 10);
}

/// `stats ROOT --json FILE --plot DIR` with the outputs in `sink`; checks exit
/// 2, that stderr names every one of `needles`, and that neither output was
/// created.
fn fails_without_output(root: &str, sink: &Path, needles: &[&str]) {
    let (json, plots) = (sink.join("stats.json"), sink.join("plots"));
    let (code, out, err) = stats(&[
        root,
        "--json",
        json.to_str().unwrap(),
        "--plot",
        plots.to_str().unwrap(),
    ]);
    assert_eq!(code, 2, "{root}: stdout {out}\nstderr {err}");
    for n in needles {
        assert!(err.contains(n), "stderr does not name `{n}`: {err}");
    }
    assert!(
        !json.exists(),
        "{root}: a failed run wrote {}",
        json.display()
    );
    assert!(
        !plots.exists(),
        "{root}: a failed run created {}",
        plots.display()
    );
}

#[test]
fn stats_bad_inputs_exit_2_naming_the_path() {
    let sink = tempfile::tempdir().unwrap();
    fails_without_output("/no/such/dataset", sink.path(), &["/no/such/dataset"]);
    let d = tempfile::tempdir().unwrap();
    let root = d.path().to_str().unwrap();
    fails_without_output(root, sink.path(), &[root, "no native disparity"]);
    // A corrupt disparity names the file (a good one beside it is not enough).
    pfm(
        d.path(),
        "baseline_010/disp/000001.pfm",
        [1.0, 2.0, 3.0, 4.0],
    );
    let bad = d.path().join("baseline_010/disp/000000.pfm");
    fs::write(&bad, b"Pf\n2 2\n-1.0\nxx").unwrap();
    fails_without_output(root, sink.path(), &[bad.to_str().unwrap()]);
    assert_eq!(
        fs::read_dir(sink.path()).unwrap().count(),
        0,
        "failed runs left files behind"
    );
}

/// Dark (ink) pixel of an RGB8 image.
fn dark(rgb: &[u8], w: usize, x: usize, y: usize) -> bool {
    let i = (y * w + x) * 3;
    rgb[i..i + 3].iter().all(|&v| v < 64)
}

#[test]
fn histogram_png_has_axes_ticks_labels_and_a_title() {
    let d = tempfile::tempdir().unwrap();
    let r = d.path();
    pfm(r, "baseline_054/disp/000000.pfm", [1.0, 2.5, 40.0, 97.0]);
    let plots = r.join("plots");
    let (code, _, err) = stats(&[r.to_str().unwrap(), "--plot", plots.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let (w, h, rgb) =
        parallax::output::read_png_rgb8(&plots.join("hist_baseline_054.png")).unwrap();
    assert_eq!((w, h), parallax::stats::PLOT_SIZE);
    let (ax, ay) = parallax::stats::AXES_AT;
    // The x axis: one dark row under the 512 px of bars; the y axis: one dark
    // column the 200 px plot height.
    assert!(
        (ax..ax + 512).all(|x| dark(&rgb, w, x, ay)),
        "x axis row {ay}"
    );
    assert!(
        (ay - 199..=ay).all(|y| dark(&rgb, w, ax, y)),
        "y axis column {ax}"
    );
    let ink = |xs: std::ops::Range<usize>, ys: std::ops::Range<usize>| {
        ys.flat_map(|y| xs.clone().map(move |x| (x, y)))
            .filter(|&(x, y)| dark(&rgb, w, x, y))
            .count()
    };
    // Text: title above the plot, tick numbers and the x label below the x
    // axis, tick numbers and the turned y label left of the y axis.
    assert!(ink(0..w, 0..ay - 200) > 100, "no title");
    assert!(ink(ax + 1..w, ay + 2..h) > 150, "no x tick numbers / label");
    assert!(ink(0..ax - 1, 0..h) > 100, "no y tick numbers / label");
    // Tick marks: dark pixels just below the x axis at 0 px (the axis start).
    assert!(dark(&rgb, w, ax + 1, ay + 3), "no tick at 0 px");
}
