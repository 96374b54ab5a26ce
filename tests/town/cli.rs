//! The town command line: `parallax render --town NAME --frame K --config C`
//! writes frame K in the native layout with the town's seed, the frame
//! index, K, the configuration's rig pose on the ego of that frame and the
//! requested image size;
//! `parallax town NAME --export FILE.obj --report FILE.json` writes OBJ +
//! MTL and a content report that counts what the OBJ holds; bad names,
//! configurations and argument mixes exit with code 2 and say why.

use std::path::Path;
use std::process::Output;

use parallax::camera::StereoRig;
use parallax::town::{frame_at, load_town, rig_desc, CameraConfig};

use crate::common::cli::parallax_run;

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).to_string()
}

#[test]
fn render_town_writes_frame_k_with_its_seed() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = parallax_run(&[
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
    assert_eq!(cam["seed"].as_u64(), Some(9), "{cam}");
    assert_eq!(cam["frame"].as_u64(), Some(3), "{cam}");
    assert_eq!(
        (cam["width"].as_u64(), cam["height"].as_u64()),
        (Some(32), Some(18))
    );
    // K of a 32-pixel-wide 60° camera: f = 16 / tan 30°, centre (16, 9).
    let f = 16.0 / 30f64.to_radians().tan();
    let want_k = [[f, 0.0, 16.0], [0.0, f, 9.0], [0.0, 0.0, 1.0]];
    for (r, row) in want_k.iter().enumerate() {
        for (c, &w) in row.iter().enumerate() {
            let got = cam["k"][r][c].as_f64().unwrap();
            assert!((got - w).abs() < 1e-9, "K[{r}][{c}] {got} vs {w}");
        }
    }
    // The left pose is the roll15 rig on town02's ego at seed 9, frame 3.
    let pose: Vec<Vec<f64>> = (0..4)
        .map(|r| {
            (0..4)
                .map(|c| cam["left_pose"][r][c].as_f64().unwrap())
                .collect()
        })
        .collect();
    let desc =
        load_town(&Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/town02.toml")).unwrap();
    let ego = frame_at(&desc, 9, 3).ego;
    assert_ne!(
        ego.position,
        frame_at(&desc, 9, 0).ego.position,
        "the ego moved by frame 3"
    );
    assert_eq!((ego.pitch_deg, ego.roll_deg), (0.0, 0.0), "town02 is level");
    let want = StereoRig::from_desc(&rig_desc(CameraConfig::Roll15, &ego))
        .left
        .pose_matrix();
    for r in 0..4 {
        for c in 0..4 {
            assert!(
                (pose[r][c] - want[r][c]).abs() < 1e-9,
                "pose[{r}][{c}] {pose:?} vs {want:?}"
            );
        }
    }
    // From the pose alone: 1.65 m above the level road, ahead of the ego
    // along its heading, looking along the heading, rolled 15° (the camera's
    // x axis dips by sin 15°; columns are the camera axes in world).
    let h = ego.heading_deg.to_radians();
    let ahead = [pose[0][3] - ego.position[0], pose[1][3] - ego.position[1]];
    assert!(
        (pose[2][3] - 1.65).abs() < 1e-9,
        "camera height {}",
        pose[2][3]
    );
    assert!(
        (ahead[0] * h.sin() - ahead[1] * h.cos()).abs() < 1e-9,
        "off the ego's axis: {ahead:?}"
    );
    assert!(
        ahead[0] * h.cos() + ahead[1] * h.sin() > 0.5,
        "not ahead: {ahead:?}"
    );
    let forward = [pose[0][2], pose[1][2], pose[2][2]];
    assert!(
        (forward[0] - h.cos()).abs() < 1e-9
            && (forward[1] - h.sin()).abs() < 1e-9
            && forward[2].abs() < 1e-9
    );
    let roll = (-pose[2][0]).asin().to_degrees();
    assert!((roll - 15.0).abs() < 1e-9, "roll {roll}°");
    assert_eq!(cam["right"][0]["baseline_m"].as_f64(), Some(0.54));
    // The image has the requested size (PNG IHDR: width, height big-endian).
    let png = std::fs::read(out.join("left/rgb/000003.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&png[12..16], b"IHDR");
    let be = |b: &[u8]| u32::from_be_bytes([b[0], b[1], b[2], b[3]]);
    assert_eq!((be(&png[16..20]), be(&png[20..24])), (32, 18));
}

#[test]
fn town_export_writes_obj_and_mtl() {
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("t.obj");
    let report = dir.path().join("t.json");
    let o = parallax_run(&[
        "town",
        "town07",
        "--frame",
        "2",
        "--threads",
        "2",
        "--export",
        obj.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("triangles"), "{stdout}");
    let text = std::fs::read_to_string(&obj).unwrap();
    assert!(text.starts_with("# parallax town export\nmtllib t.mtl\n"));
    let faces = text.lines().filter(|l| l.starts_with("f ")).count();
    assert!(faces > 100_000);
    assert!(Path::new(&dir.path().join("t.mtl")).is_file());

    // The content report counts what the (flattened) export holds.
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    let geometry = &r["geometry"];
    let cut = geometry["cut_triangles"].as_u64().unwrap();
    assert!(cut > 0, "{r}");
    assert_eq!(
        geometry["instanced_triangles"].as_u64(),
        Some(faces as u64 - cut),
        "{r}"
    );
    let unique = geometry["unique_triangles"].as_u64().unwrap();
    assert!(unique > 0 && unique <= faces as u64, "{r}");
    assert_eq!(
        (r["town"].as_str(), r["frame"].as_u64()),
        (Some("town07"), Some(2))
    );
    let objects = r["objects"].as_u64().unwrap();
    assert!(stdout.contains(&format!("{objects} objects")), "{stdout}");
    let per_class = r["objects_per_class"].as_object().unwrap();
    for (class, n) in per_class {
        assert!(
            parallax::scene::semantic::class_id(class).is_some(),
            "{class}"
        );
        assert!(n.as_u64().unwrap() > 0, "{class}");
    }
    // Every town object carries a class; roads, buildings and cars exist.
    assert!(!per_class.contains_key("unlabeled"), "{r}");
    for class in ["road", "building", "car", "vegetation"] {
        assert!(per_class.contains_key(class), "{class}: {r}");
    }
    let counted: u64 = per_class.values().map(|n| n.as_u64().unwrap()).sum();
    assert!(counted >= objects, "{r}");
    assert!(r["peak_rss_bytes"].as_u64().unwrap() > 1 << 20, "{r}");
}

#[test]
fn bad_town_arguments_exit_2_with_a_reason() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let out = out.to_str().unwrap();
    let cases: [(&[&str], &str); 7] = [
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
        (
            &["town", "town02", "--report", "no_such_dir/r.json"],
            "--report",
        ),
    ];
    for (args, needle) in cases {
        let o = parallax_run(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!Path::new(out).exists(), "{args:?} wrote output");
    }
}
