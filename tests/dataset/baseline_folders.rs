//! Baselines that would share a `baseline_XXX/` folder (the same whole
//! centimetre) are refused before anything is written, by `render` (scene
//! file and `--baselines`) and by `dataset`, with a message naming the values
//! and the folder; and a baseline's folder is the one its centimetres round
//! to, whichever way it is computed.

use crate::common;
use crate::common::dataset;

use std::path::Path;

use common::{camera_block, GREY_UNDER_SKY};
use dataset::{dataset, parallax, text, tiny_config, write_config};

/// A tiny lit scene with the given `camera.baselines_cm`.
fn scene(baselines: &str) -> String {
    format!(
        "{}baselines_cm = {baselines}\n[render]\nspp = 1\nseed = 1\n{GREY_UNDER_SKY}\
         [[object]]\nkind = \"box\"\nsize = [1.0, 1.0, 1.0]\nmaterial = \"grey\"\n\
         transform = {{ translate = [5.0, 0.0, 1.0] }}\n",
        camera_block(32, 18, [0.0, 0.0, 1.65])
    )
}

/// Asserts exit code 2, that `out` was not created, and that the message
/// holds every needle.
fn refused(o: &std::process::Output, out: &Path, needles: &[&str]) {
    let msg = text(o);
    assert_eq!(o.status.code(), Some(2), "{msg}");
    assert!(!out.exists(), "{} was created", out.display());
    for n in needles {
        assert!(msg.contains(n), "message lacks {n:?}: {msg}");
    }
}

#[test]
fn render_refuses_scene_baselines_sharing_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    let s = write_config(dir.path(), "twins.toml", &scene("[10.0, 53.6, 54.4]"));
    let out = dir.path().join("out");
    let o = parallax(&["render", s.to_str().unwrap(), "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    refused(
        &o,
        &out,
        &[
            "twins.toml",
            "camera.baselines_cm[2]",
            "53.6 cm and 54.4 cm",
            "baseline_054",
        ],
    );
}

#[test]
fn render_refuses_command_line_baselines_sharing_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    let s = write_config(dir.path(), "one.toml", &scene("[54.0]"));
    let out = dir.path().join("out");
    for (list, needles) in [
        (
            "54,54.4",
            &["--baselines", "54 cm and 54.4 cm", "baseline_054"][..],
        ),
        (
            "10,100,10",
            &["--baselines", "10 cm is listed twice", "baseline_010"][..],
        ),
    ] {
        let args = ["render", s.to_str().unwrap(), "--baselines", list, "-o"];
        let o = parallax(&args).arg(&out).output().unwrap();
        refused(&o, &out, needles);
    }
}

#[test]
fn dataset_refuses_baselines_sharing_a_folder() {
    let dir = tempfile::tempdir().unwrap();
    let text = tiny_config(&["normal"], 1).replace(
        "baselines_cm = [10.0, 54.0]",
        "baselines_cm = [10.0, 54.0, 100.0, 99.5]",
    );
    let config = write_config(dir.path(), "twins.toml", &text);
    let out = dir.path().join("ds");
    let o = dataset(&config, &out, &[]);
    refused(
        &o,
        &out,
        &[
            "twins.toml",
            "baselines_cm[3]",
            "100 cm and 99.5 cm",
            "baseline_100",
        ],
    );
}

#[test]
fn half_centimetre_baseline_lands_in_the_folder_it_rounds_to() {
    // 14.5 cm is 0.145 m; 0.145 * 100 is 14.4999…, which used to name
    // baseline_014 while the configured 14.5 (split lists, this check)
    // names baseline_015.
    let dir = tempfile::tempdir().unwrap();
    let s = write_config(dir.path(), "half.toml", &scene("[14.5]"));
    let out = dir.path().join("out");
    let o = parallax(&["render", s.to_str().unwrap(), "-o", out.to_str().unwrap()])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", text(&o));
    assert!(out.join("baseline_015/disp/000000.pfm").is_file());
    let cam: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("cameras/000000.json")).unwrap()).unwrap();
    assert_eq!(cam["right"][0]["dir"], "baseline_015");
}
