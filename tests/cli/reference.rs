//! `render --reference`: plain, unbiased path tracing. On a frame with an
//! image filter and a preset's sensor noise (street under `storm`) it writes
//! exactly the images `--no-filter --sensor-noise 0` writes, which differ
//! from the default's; it refuses a sensor-noise override (exit 2).

use crate::common::dataset;

use std::path::Path;

use dataset::ok;

/// `parallax render scenes/street.toml --weather storm` at 48×27, 2 spp,
/// one baseline, seed 9, plus `extra`, into `out`.
fn render_storm(out: &Path, extra: &[&str]) -> std::process::Output {
    let mut args = vec!["--weather", "storm"];
    args.extend_from_slice(extra);
    crate::common::cli::render_street(out, (48, 27), 9, &args)
        .output()
        .unwrap()
}

fn read(p: &Path) -> Vec<u8> {
    std::fs::read(p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

#[test]
fn reference_is_the_plain_unfiltered_noiseless_render() {
    let dir = tempfile::tempdir().unwrap();
    let [reference, plain, default] = ["reference", "plain", "default"].map(|n| dir.path().join(n));
    ok(&render_storm(&reference, &["--reference"]));
    ok(&render_storm(
        &plain,
        &["--no-filter", "--sensor-noise", "0"],
    ));
    ok(&render_storm(&default, &[]));
    for view in [
        "left/rgb/000000.png",
        "baseline_054/rgb/000000.png",
        "cameras/000000.json",
    ] {
        let r = read(&reference.join(view));
        assert_eq!(r, read(&plain.join(view)), "{view}: --reference vs plain");
        assert_ne!(
            r,
            read(&default.join(view)),
            "{view}: --reference vs default"
        );
    }
}

#[test]
fn reference_refuses_a_sensor_noise_override() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x");
    let o = render_storm(&out, &["--reference", "--sensor-noise", "400"]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--reference") && err.contains("--sensor-noise"),
        "{err}"
    );
    assert!(!out.exists(), "nothing written");
}
