//! Turning the image-space filters off from the command line and in a
//! dataset configuration: `render --no-filter` writes the plain path-traced
//! images (a weather preset's fog filter included) and says so in the
//! camera file, with the same ground truth; a dataset with `filter = false`
//! does the same, and one with the default writes filtered images.

use crate::common::dataset;

use std::path::Path;

use dataset::{dataset, ok, tiny_config, write_config};

/// `parallax render scenes/street.toml` at 64×36, 2 spp, one baseline,
/// seed 4, plus `extra`, into `out`.
fn render_street(out: &Path, extra: &[&str]) {
    ok(&crate::common::cli::render_street(out, (64, 36), 4, extra)
        .output()
        .unwrap());
}

/// The camera file's `image_filter` of frame `name` under `dir`.
fn image_filter(dir: &Path, name: &str) -> Option<bool> {
    let text = std::fs::read_to_string(dir.join("cameras").join(name)).unwrap();
    let cam: serde_json::Value = serde_json::from_str(&text).unwrap();
    cam["image_filter"].as_bool()
}

fn read(p: &Path) -> Vec<u8> {
    std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn render_no_filter_writes_plain_images_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let (on, off) = (dir.path().join("on"), dir.path().join("off"));
    render_street(&on, &[]);
    render_street(&off, &["--no-filter"]);
    assert_eq!(image_filter(&on, "000000.json"), Some(true));
    assert_eq!(image_filter(&off, "000000.json"), Some(false));
    for view in ["left/rgb/000000.png", "baseline_054/rgb/000000.png"] {
        assert_ne!(read(&on.join(view)), read(&off.join(view)), "{view}");
    }
    for gt in [
        "left/depth/000000.exr",
        "baseline_054/disp/000000.pfm",
        "baseline_054/occ/000000.png",
    ] {
        assert_eq!(read(&on.join(gt)), read(&off.join(gt)), "{gt}");
    }
    // A weather preset brings a fog filter; --no-filter turns it off too.
    let (fog_on, fog_off) = (dir.path().join("fog_on"), dir.path().join("fog_off"));
    render_street(&fog_on, &["--weather", "foggy"]);
    render_street(&fog_off, &["--weather", "foggy", "--no-filter"]);
    assert_eq!(image_filter(&fog_on, "000000.json"), Some(true));
    assert_eq!(image_filter(&fog_off, "000000.json"), Some(false));
    let left = "left/rgb/000000.png";
    assert_ne!(read(&fog_on.join(left)), read(&fog_off.join(left)));
}

#[test]
fn dataset_filter_key_turns_the_filters_off() {
    let dir = tempfile::tempdir().unwrap();
    let base = tiny_config(&["normal"], 1).replace("spp = 1", "spp = 2");
    let runs = [
        ("on", base.clone()),
        ("off", format!("{base}filter = false\n")),
    ];
    let frame = "town01/normal_clear/0000";
    let mut lefts = Vec::new();
    for (name, text) in runs {
        let cfg = write_config(dir.path(), &format!("{name}.toml"), &text);
        let out = dir.path().join(name);
        ok(&dataset(&cfg, &out, &[]));
        let root = out.join(frame);
        assert_eq!(
            image_filter(&root, "000000.json"),
            Some(name == "on"),
            "{name}"
        );
        lefts.push(read(&root.join("left/rgb/000000.png")));
    }
    assert_ne!(lefts[0], lefts[1]);
}
