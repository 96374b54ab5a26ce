//! The town command line: `parallax render --town NAME --frame K --config C`
//! writes frame K in the native layout with the town's seed recorded;
//! `parallax town NAME --export FILE.obj` writes OBJ + MTL; bad names,
//! configurations and argument mixes exit with code 2 and say why.

use std::path::Path;
use std::process::{Command, Output};

fn parallax(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_parallax"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(args)
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

#[test]
fn render_town_writes_frame_k_with_its_seed() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = parallax(&[
        "render",
        "--town",
        "town02",
        "--seed",
        "9",
        "--frame",
        "3",
        "--config",
        "roll15",
        "--width",
        "32",
        "--height",
        "18",
        "--spp",
        "1",
        "--baselines",
        "54",
        "--threads",
        "2",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(out.join("left/rgb/000003.png").is_file());
    assert!(out.join("baseline_054/disp/000003.pfm").is_file());
    let cam: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("cameras/000003.json")).unwrap())
            .unwrap();
    let text = cam.to_string();
    assert!(text.contains("\"seed\":9"), "{text}");
}

#[test]
fn town_export_writes_obj_and_mtl() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("t.obj");
    let o = parallax(&[
        "town",
        "town07",
        "--frame",
        "2",
        "--threads",
        "2",
        "--export",
        obj.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("triangles"), "{stdout}");
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(text.starts_with("# parallax town export\nmtllib t.mtl\n"));
    assert!(text.lines().filter(|l| l.starts_with("f ")).count() > 100_000);
    assert!(Path::new(&dir.path().join("t.mtl")).is_file());
}

#[test]
fn bad_town_arguments_exit_2_with_a_reason() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let cases: [(&[&str], &str); 6] = [
        (&["render", "--town", "town99", "-o", out], "town99.toml"),
        // A bare name not found says which directory it was looked up in.
        (
            &[
                "render",
                "--town",
                "town99",
                "--scenes",
                "no_such_dir",
                "-o",
                out,
            ],
            "looked up in the --scenes directory ('no_such_dir')",
        ),
        (
            &[
                "render", "--town", "town02", "--config", "pitch45", "-o", out,
            ],
            "pitch45",
        ),
        (&["render", "-o", out], "--town"),
        (
            &[
                "render",
                "scenes/street.toml",
                "--town",
                "town02",
                "-o",
                out,
            ],
            "--town",
        ),
        (&["town", "town02", "--config", "sideways"], "sideways"),
    ];
    for (args, needle) in cases {
        let o = parallax(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!Path::new(out).exists(), "{args:?} wrote output");
    }
}
