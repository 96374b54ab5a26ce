//! `parallax bench` through the real binary: a tiny analytic scene measured
//! over two rounds, a plain OBJ seen from a camera file in the shared
//! benchmark's format, and bad arguments refused with a message naming them.

use crate::common::cli::parallax;

fn bench(args: &[&str]) -> std::process::Output {
    parallax(&[])
        .arg("bench")
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap()
}

/// The path pass's rays per camera sample, from "(R rays/sample)".
fn rays_per_sample(text: &str) -> f64 {
    text.split(" rays/sample")
        .next()
        .and_then(|s| s.rsplit('(').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no rays/sample in\n{text}"))
}

/// The CPU-scaled figure of a report line "NAME  W unit wall  C cpu ...".
fn cpu_figure(text: &str, name: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.starts_with(name))
        .unwrap_or_else(|| panic!("no line {name:?} in\n{text}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    let k = words.iter().position(|w| *w == "cpu").unwrap();
    words[k - 1].parse().unwrap()
}

#[test]
fn two_rounds_on_a_small_scene_report_every_figure() {
    let o = bench(&[
        "scenes/analytic/boxes.toml",
        "--width",
        "64",
        "--height",
        "36",
        "--threads",
        "1",
        "--rounds",
        "2",
    ]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(text.contains("1 threads"), "{text}");
    assert!(text.contains("medians of 2 rounds"), "{text}");
    for name in [
        "GT pass",
        "path tracing",
        "path samples",
        "raw primary single",
        "raw primary tile4x2",
        "raw incoherent hit",
        "raw shading any",
    ] {
        let x = cpu_figure(&text, name);
        assert!(x.is_finite() && x > 0.0, "{name}: {x}\n{text}");
    }
    // Every camera sample traces its camera ray; max depth 5 bounds the rest
    // (a closest hit and at most sun + sky shadow rays per vertex).
    let per_sample = rays_per_sample(&text);
    assert!((1.0..=16.0).contains(&per_sample), "{per_sample}\n{text}");
}

#[test]
fn bad_arguments_are_named() {
    for (args, needle) in [
        (
            vec!["scenes/analytic/boxes.toml", "--rounds", "0"],
            "--rounds",
        ),
        (
            vec!["scenes/analytic/boxes.toml", "--threads", "0"],
            "--threads",
        ),
        (vec!["no/such/mesh.obj"], "no/such/mesh.obj"),
    ] {
        let o = bench(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

/// A wall of 2 triangles (one quad face) across z = 8 m plus one triangle
/// beside it, in the shared benchmark's OBJ frame (y up), with its MTL.
const WALL_OBJ: &str = "# a wall facing -z and a stray triangle\nmtllib wall.mtl\n\
v -30 -5 8\nv 30 -5 8\nv 30 25 8\nv -30 25 8\n\
v 40 0 -3\nv 41 0 -3\nv 40 1 -3\n\
usemtl paint\nf 1 2 3 4\nf 5 6 7\n";

/// Writes `wall.obj` and its `wall.mtl` into `dir`; returns the OBJ's path.
fn write_wall(dir: &std::path::Path) -> std::path::PathBuf {
    std::fs::write(dir.join("wall.mtl"), "newmtl paint\nKd 0.6 0.5 0.4\n").unwrap();
    let obj = dir.join("wall.obj");
    std::fs::write(&obj, WALL_OBJ).unwrap();
    obj
}

/// A camera file as `../shared/bench/make_city.py` writes it (every key it
/// has), 32×18, looking along +z at the wall from 8 m.
fn camera_json(forward_z: f64) -> String {
    serde_json::json!({
        "description": "driver-view stereo rig; pinhole",
        "width": 32, "height": 18, "hfov_deg": 60.0,
        "fx": 27.7128, "fy": 27.7128, "cx": 16.0, "cy": 9.0,
        "forward": [0.0, 0.0, forward_z], "up": [0.0, 1.0, 0.0], "right_axis": [-1.0, 0.0, 0.0],
        "baseline_m": 0.54,
        "cameras": {"left": {"position": [0.0, 1.6, 0.0]}, "right": {"position": [-0.54, 1.6, 0.0]}},
        "depth_definition": "z-depth along forward; disparity_px = fx * baseline_m / depth",
    })
    .to_string()
}

#[test]
fn obj_with_a_camera_file_is_measured_from_that_camera() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write_wall(dir.path());
    let run = |camera: Option<&str>| {
        let mut args = vec![obj.to_str().unwrap().to_string()];
        if let Some(text) = camera {
            let p = dir.path().join("camera.json");
            std::fs::write(&p, text).unwrap();
            args.extend(["--camera".into(), p.to_str().unwrap().into()]);
        }
        let flags = [
            "--width", "32", "--height", "18", "--spp", "1", "--rounds", "1",
        ];
        args.extend(flags.map(String::from));
        args.extend(["--threads", "2", "--backend", "bvh"].map(String::from));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = bench(&args);
        let text = String::from_utf8_lossy(&o.stdout).into_owned();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(text.starts_with("scene: 3 triangles,"), "{text}");
        // The report says which view it measured (the y-up file, in z-up world).
        let from = match camera {
            Some(_) => format!(
                "camera: {}: 32x18 px",
                dir.path().join("camera.json").display()
            ),
            None => "camera: the scene's camera: 32x18 px".to_string(),
        };
        assert!(text.contains(&from), "{text}");
        if camera.is_some() {
            assert!(text.contains("position (0, 0, 1.6) m (z up)"), "{text}");
        }
        rays_per_sample(&text)
    };
    // Facing the wall every camera ray hits and the path goes on (shadow
    // rays, bounces); facing away, or from the default camera (looking
    // along -z from [1.5, 1.6, 0]), every camera ray escapes to the sky alone.
    let facing = run(Some(&camera_json(1.0)));
    assert!(facing > 2.0, "facing the wall: {facing} rays/sample");
    assert_eq!(run(Some(&camera_json(-1.0))), 1.0);
    assert_eq!(run(None), 1.0);
}

#[test]
fn bad_camera_file_exits_2_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    let obj = write_wall(dir.path());
    let no_forward = camera_json(1.0).replace("\"forward\"", "\"forwards\"");
    for (name, text) in [
        ("missing.json", None),
        ("no_forward.json", Some(no_forward.as_str())),
        ("garbage.json", Some("{\"width\": 32,")),
    ] {
        let cam = dir.path().join(name);
        if let Some(t) = text {
            std::fs::write(&cam, t).unwrap();
        }
        let o = bench(&[obj.to_str().unwrap(), "--camera", cam.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(err.contains(cam.to_str().unwrap()), "{name}: {err}");
        assert!(o.stdout.is_empty(), "{name}: printed a report");
    }
}
