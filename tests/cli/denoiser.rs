//! Choosing the denoiser on the command line, in a scene file and in a
//! dataset configuration (`--denoiser`, `[render] denoiser`, `denoiser`):
//! the camera file says which one made the images; a bad name, a
//! contradiction and a missing Open Image Denoise are refused with exit 2
//! before anything is written. With the library installed (`pip install
//! pyoidn`; `.ci/run` installs it), an `oidn` or `blend` render writes
//! other images over the same ground truth.

use crate::common::dataset;

use std::path::{Path, PathBuf};
use std::process::Output;

use dataset::{mtimes, ok, parallax, tiny_config, write_config};

/// A library path that does not exist, so no Open Image Denoise is found.
fn nowhere(dir: &Path) -> PathBuf {
    dir.join("nowhere").join("libOpenImageDenoise.so.2")
}

/// `parallax render scenes/street.toml` at 48×27, 2 spp, one baseline,
/// seed 4, plus `extra`, into `out`, with `PARALLAX_OIDN` set to `lib`
/// when given.
fn render_street(out: &Path, extra: &[&str], lib: Option<&Path>) -> Output {
    let mut c = crate::common::cli::render_street(out, (48, 27), 4, extra);
    if let Some(lib) = lib {
        c.env("PARALLAX_OIDN", lib);
    }
    c.output().unwrap()
}

/// The camera file's `denoiser` of frame 0 under `dir`.
fn denoiser(dir: &Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("cameras").join("000000.json")).unwrap();
    let cam: serde_json::Value = serde_json::from_str(&text).unwrap();
    cam["denoiser"].clone()
}

fn refused(o: &Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{err}");
    err
}

#[test]
fn the_camera_file_names_the_denoiser() {
    let dir = tempfile::tempdir().unwrap();
    let (on, off) = (dir.path().join("on"), dir.path().join("off"));
    ok(&render_street(&on, &[], None));
    ok(&render_street(&off, &["--no-filter"], None));
    assert_eq!(denoiser(&on), "parallax");
    assert_eq!(denoiser(&off), serde_json::Value::Null);
}

#[test]
fn a_missing_open_image_denoise_is_refused_before_any_output() {
    let dir = tempfile::tempdir().unwrap();
    let lib = nowhere(dir.path());
    let out = dir.path().join("out");
    for name in ["oidn", "blend"] {
        let err = refused(&render_street(&out, &["--denoiser", name], Some(&lib)));
        assert!(
            err.contains(&lib.display().to_string()) && err.contains("pip install pyoidn"),
            "{err}"
        );
        assert!(!out.exists(), "nothing written");
    }
    // A scene file asking for it is refused alike.
    let scene = dir.path().join("oidn.toml");
    let street =
        std::fs::read_to_string(format!("{}/scenes/street.toml", env!("CARGO_MANIFEST_DIR")))
            .unwrap();
    std::fs::write(
        &scene,
        street.replacen("[render]\n", "[render]\ndenoiser = \"oidn\"\n", 1),
    )
    .unwrap();
    let o = parallax(&[
        "render",
        scene.to_str().unwrap(),
        "--width",
        "48",
        "--height",
        "27",
        "--spp",
        "1",
        "-o",
        out.to_str().unwrap(),
    ])
    .env("PARALLAX_OIDN", &lib)
    .output()
    .unwrap();
    assert!(refused(&o).contains("pip install pyoidn"));
    assert!(!out.exists(), "nothing written");
    // And a dataset configuration, before its first frame.
    let config = write_config(
        dir.path(),
        "d.toml",
        &format!("{}denoiser = \"blend\"\n", tiny_config(&["normal"], 1)),
    );
    let root = dir.path().join("ds");
    let o = parallax(&[
        "dataset",
        config.to_str().unwrap(),
        "-o",
        root.to_str().unwrap(),
    ])
    .env("PARALLAX_OIDN", &lib)
    .output()
    .unwrap();
    let err = refused(&o);
    assert!(
        err.contains("denoiser \"blend\"") && err.contains("pip install pyoidn"),
        "{err}"
    );
    assert!(!root.join("left").exists(), "no frame written");
}

#[test]
fn dataset_json_records_the_default_denoiser_and_an_older_record_resumes() {
    let dir = tempfile::tempdir().unwrap();
    let config = write_config(dir.path(), "d.toml", &tiny_config(&["normal"], 1));
    let root = dir.path().join("ds");
    ok(&dataset::dataset(&config, &root, &[]));
    let record = root.join("dataset.json");
    let text = std::fs::read_to_string(&record).unwrap();
    let meta: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(meta["config"]["denoiser"], "parallax", "{text}");
    // A record written before the key existed resumes as it is: no frame
    // is rendered again and the record is not rewritten.
    let older = text.replace(",\n    \"denoiser\": \"parallax\"", "");
    assert_ne!(older, text, "the key is written as expected");
    std::fs::write(&record, &older).unwrap();
    let before = mtimes(&root);
    ok(&dataset::dataset(&config, &root, &[]));
    assert_eq!(mtimes(&root), before);
    assert_eq!(std::fs::read_to_string(&record).unwrap(), older);
}

#[test]
fn bad_denoiser_choices_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let err = refused(&render_street(&out, &["--denoiser", "magic"], None));
    assert!(
        err.contains("magic") && err.contains("parallax, oidn or blend"),
        "{err}"
    );
    // Plain images have nothing to denoise.
    refused(&render_street(
        &out,
        &["--denoiser", "oidn", "--no-filter"],
        None,
    ));
    refused(&render_street(
        &out,
        &["--denoiser", "oidn", "--reference"],
        None,
    ));
    let scene = dir.path().join("bad.toml");
    let street =
        std::fs::read_to_string(format!("{}/scenes/street.toml", env!("CARGO_MANIFEST_DIR")))
            .unwrap();
    std::fs::write(
        &scene,
        street.replacen("[render]\n", "[render]\ndenoiser = \"magic\"\n", 1),
    )
    .unwrap();
    let o = parallax(&[
        "render",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ])
    .output()
    .unwrap();
    let err = refused(&o);
    assert!(
        err.contains("render.denoiser") && err.contains("magic"),
        "{err}"
    );
    assert!(!out.exists(), "nothing written");
}

#[test]
fn oidn_and_blend_renders_change_the_images_not_the_ground_truth() {
    if let Err(e) = parallax::denoise::oidn::check() {
        assert!(
            std::env::var_os("PARALLAX_REQUIRE_OIDN").is_none(),
            "PARALLAX_REQUIRE_OIDN is set: {e}"
        );
        eprintln!("skipped, Open Image Denoise is not installed: {e}");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let own = dir.path().join("own");
    ok(&render_street(&own, &[], None));
    let read = |p: PathBuf| std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
    for name in ["oidn", "blend"] {
        let other = dir.path().join(name);
        ok(&render_street(&other, &["--denoiser", name], None));
        assert_eq!(denoiser(&other), name);
        for view in ["left/rgb/000000.png", "baseline_054/rgb/000000.png"] {
            assert_ne!(
                read(own.join(view)),
                read(other.join(view)),
                "{name}: {view}"
            );
        }
        for gt in ["left/depth/000000.exr", "baseline_054/disp/000000.pfm"] {
            assert_eq!(read(own.join(gt)), read(other.join(gt)), "{name}: {gt}");
        }
    }
}
