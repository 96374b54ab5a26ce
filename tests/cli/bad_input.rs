//! Bad input through the real binary: one case per class of the scene
//! contract. Each must exit non-zero (2) before rendering, print a message
//! naming the file and the key, line or argument, and leave no output behind.

use std::path::{Path, PathBuf};

use crate::common::cli::parallax;

const GOOD: &str = r#"
[camera]
width = 32
height = 24
position = [0.0, 0.0, 1.65]
[render]
spp = 1
seed = 1
[sky]
kind = "constant"
le = [1.0, 1.0, 1.0]
[[material]]
name = "grey"
kind = "diffuse"
albedo = [0.5, 0.5, 0.5]
[[object]]
kind = "box"
size = [1.0, 1.0, 1.0]
material = "grey"
transform = { translate = [5.0, 0.0, 1.0] }
"#;

struct Case {
    dir: tempfile::TempDir,
}

impl Case {
    fn new() -> Self {
        Case {
            dir: tempfile::tempdir().unwrap(),
        }
    }
    fn file(&self, name: &str, text: &str) -> PathBuf {
        let p = self.dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        p
    }
    fn out(&self) -> PathBuf {
        self.dir.path().join("out")
    }
    /// Runs `parallax render SCENE -o out ARGS`; returns stderr after checking
    /// the exit code and that nothing was written.
    fn fails(&self, scene: &Path, args: &[&str], needles: &[&str]) -> String {
        let o = parallax(&[])
            .arg("render")
            .arg(scene)
            .arg("-o")
            .arg(self.out())
            .args(args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        assert_eq!(o.status.code(), Some(2), "exit code; stderr: {err}");
        assert!(!self.out().exists(), "output directory was created");
        for n in needles {
            assert!(err.contains(n), "message lacks {n:?}: {err}");
        }
        err
    }
}

fn with(replace: &str, by: &str) -> String {
    assert!(GOOD.contains(replace));
    GOOD.replacen(replace, by, 1)
}

#[test]
fn good_scene_renders_every_native_file() {
    let c = Case::new();
    let s = c.file("good.toml", GOOD);
    let o = parallax(&[])
        .args([
            "render",
            s.to_str().unwrap(),
            "-o",
            c.out().to_str().unwrap(),
            "--baselines",
            "10,54",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("Mrays/s") && stdout.contains("backend"),
        "{stdout}"
    );
    for f in [
        "left/rgb/000000.png",
        "left/depth/000000.exr",
        "left/normal/000000.exr",
        "left/semantic/000000.png",
        "left/instance/000000.png",
        "left/mask/000000.png",
        "baseline_010/rgb/000000.png",
        "baseline_054/disp/000000.pfm",
        "baseline_054/depth_right/000000.exr",
        "baseline_054/disp_right/000000.pfm",
        "baseline_054/occ/000000.png",
        "cameras/000000.json",
    ] {
        assert!(c.out().join(f).is_file(), "missing {f}");
    }
    let meta: serde_json::Value =
        serde_json::from_slice(&std::fs::read(c.out().join("cameras/000000.json")).unwrap())
            .unwrap();
    for key in [
        "k",
        "left_pose",
        "right",
        "exposure_scale",
        "seed",
        "sun_direction_world",
        "weather",
    ] {
        assert!(meta.get(key).is_some(), "camera file lacks {key}");
    }
    assert_eq!(meta["seed"], 1);
    assert_eq!(meta["right"].as_array().unwrap().len(), 2);
}

#[test]
fn missing_scene_file_is_named() {
    let c = Case::new();
    c.fails(&c.dir.path().join("nope.toml"), &[], &["nope.toml"]);
}

#[test]
fn toml_syntax_error_names_the_line() {
    let c = Case::new();
    let s = c.file("syntax.toml", &with("spp = 1", "spp = = 1"));
    c.fails(&s, &[], &["syntax.toml:7:"]);
}

#[test]
fn unknown_key_is_named() {
    let c = Case::new();
    let s = c.file(
        "unknown.toml",
        &with("spp = 1", "spp = 1\nsamples_per_pixle = 4"),
    );
    c.fails(&s, &[], &["unknown.toml", "samples_per_pixle"]);
}

#[test]
fn wrong_type_names_the_key() {
    let c = Case::new();
    let s = c.file("type.toml", &with("spp = 1", "spp = \"many\""));
    c.fails(&s, &[], &["type.toml", "spp"]);
}

#[test]
fn out_of_range_values_name_the_key() {
    for (from, to, key) in [
        (
            "width = 32",
            "width = 32\nbaselines_cm = [10.0, -54.0]",
            "baselines_cm",
        ),
        ("width = 32", "width = 32\nhfov_deg = 180.0", "hfov_deg"),
        ("width = 32", "width = 0", "width"),
        ("spp = 1", "spp = 0", "spp"),
        ("size = [1.0, 1.0, 1.0]", "size = [1.0, -1.0, 1.0]", "size"),
    ] {
        let c = Case::new();
        let s = c.file("range.toml", &with(from, to));
        c.fails(&s, &[], &["range.toml", key]);
    }
}

#[test]
fn unknown_material_is_named() {
    let c = Case::new();
    let s = c.file(
        "mat.toml",
        &with("material = \"grey\"", "material = \"gold_leaf\""),
    );
    c.fails(&s, &[], &["mat.toml", "gold_leaf"]);
}

fn obj_scene(c: &Case, obj: &str) -> PathBuf {
    c.file("mesh.obj", obj);
    c.file(
        "obj.toml",
        &with(
            "kind = \"box\"\nsize = [1.0, 1.0, 1.0]",
            "kind = \"obj\"\nfile = \"mesh.obj\"",
        ),
    )
}

/// A scene of one OBJ object with contents `obj` fails naming the scene,
/// the OBJ file and each of `reason`.
fn obj_fails(obj: &str, reason: &[&str]) {
    let c = Case::new();
    let s = obj_scene(&c, obj);
    let needles: Vec<&str> = ["obj.toml", "mesh.obj"]
        .iter()
        .chain(reason)
        .copied()
        .collect();
    c.fails(&s, &[], &needles);
}

#[test]
fn obj_with_non_finite_coordinates_is_refused() {
    obj_fails(
        "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n",
        &["object[0].file", "vertex 1 is not finite"],
    );
}

#[test]
fn obj_with_absurd_coordinates_is_refused() {
    obj_fails(
        "v 0 0 0\nv 1e12 0 0\nv 0 1 0\nf 1 2 3\n",
        &["object[0].file", "vertex 1 = ", "is beyond ±"],
    );
}

#[test]
fn obj_with_bad_indices_is_refused() {
    obj_fails(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n",
        &["object[0].file", "line 4: vertex index 9", "out of range"],
    );
}

#[test]
fn degenerate_or_empty_obj_is_refused() {
    obj_fails(
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
        &["no usable triangles (1 faces, 1 degenerate dropped)"],
    );
    obj_fails(
        "# nothing here\n",
        &["no usable triangles (0 faces, 0 degenerate dropped)"],
    );
}

#[test]
fn resolution_that_cannot_fit_in_memory_is_refused_before_allocating() {
    let c = Case::new();
    let s = c.file(
        "huge.toml",
        &with("width = 32\nheight = 24", "width = 200000\nheight = 100000"),
    );
    c.fails(&s, &[], &["huge.toml"]);
}

#[test]
fn triangle_count_that_cannot_fit_is_refused_before_allocating() {
    let c = Case::new();
    let s = c.file(
        "tris.toml",
        &with(
            "transform = { translate = [5.0, 0.0, 1.0] }",
            "transform = { translate = [5.0, 0.0, 1.0] }\nrepeat = [{ count = 100000, offset = [1.0, 0.0, 0.0] }, { count = 100000, offset = [0.0, 1.0, 0.0] }]",
        ),
    );
    c.fails(&s, &[], &["tris.toml", "triangle"]);
}

#[test]
fn bad_arguments_are_named() {
    let c = Case::new();
    let s = c.file("good.toml", GOOD);
    c.fails(&s, &["--spp", "0"], &["--spp"]);
    c.fails(&s, &["--baselines", "10,-3"], &["baseline"]);
    c.fails(&s, &["--width", "0"], &["--width"]);
    c.fails(
        &s,
        &["--height", "900000", "--width", "900000"],
        &["command-line", "pixels"],
    );
}

#[test]
fn scene_without_light_is_refused() {
    let c = Case::new();
    let s = c.file(
        "dark.toml",
        &with("le = [1.0, 1.0, 1.0]", "le = [0.0, 0.0, 0.0]"),
    );
    c.fails(&s, &[], &["dark.toml", "light"]);
}

/// One bad input through the binary: files written into a fresh directory
/// (the first is the input), the arguments (`FILE` and `OUT` stand for the
/// input and an output directory) and what the message must contain.
struct Row {
    files: Vec<(&'static str, String)>,
    args: &'static [&'static str],
    says: &'static [&'static str],
}

fn row(
    file: &'static str,
    text: String,
    args: &'static [&'static str],
    says: &'static [&'static str],
) -> Row {
    Row {
        files: vec![(file, text)],
        args,
        says,
    }
}

const RENDER: &[&str] = &["render", "FILE", "-o", "OUT"];

/// A row of a scene naming mesh.obj, with looks.mtl beside it.
fn obj_row(obj: &str, mtl: &str, says: &'static [&'static str]) -> Row {
    let scene = with(
        "kind = \"box\"\nsize = [1.0, 1.0, 1.0]\nmaterial = \"grey\"",
        "kind = \"obj\"\nfile = \"mesh.obj\"",
    );
    Row {
        files: vec![
            ("obj.toml", scene),
            ("mesh.obj", obj.into()),
            ("looks.mtl", mtl.into()),
        ],
        args: RENDER,
        says,
    }
}

/// An OBJ triangle of material "paint", defined in looks.mtl as `paint`.
fn mtl_row(paint: &str, says: &'static [&'static str]) -> Row {
    let obj = "mtllib looks.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n";
    obj_row(obj, &format!("newmtl paint\n{paint}\n"), says)
}

#[test]
fn bad_inputs_name_the_place_the_value_and_what_is_allowed() {
    let rows = [
        row(
            "far.toml",
            with("translate = [5.0", "translate = [1e308"),
            RENDER,
            &["far.toml: object[0].transform.translate: 1e308 is beyond the coordinate limit of ±1e7 m"],
        ),
        row(
            "big.toml",
            with("size = [1.0, 1.0, 1.0]", "size = [1.0, 1e308, 1.0]"),
            RENDER,
            &["big.toml: object[0].size: 1e308 is beyond the coordinate limit of ±1e7 m"],
        ),
        row(
            "cam.toml",
            with("position = [0.0, 0.0, 1.65]", "position = [0.0, -1e308, 1.65]"),
            RENDER,
            &["cam.toml: camera.position: -1e308 is beyond the coordinate limit"],
        ),
        row(
            "end.toml",
            format!("{GOOD}foo ="),
            RENDER,
            &["end.toml:21:6: the file ends inside \"foo =\": a value is missing"],
        ),
        row(
            "sky.toml",
            with("le = [1.0, 1.0, 1.0]", "le = [1.0, -1.0, 1.0]"),
            RENDER,
            &["sky.toml: sky.le: must be ≥ 0, got -1\n"],
        ),
        row(
            "good.toml",
            GOOD.into(),
            &["render", "FILE", "-o", "OUT", "--spp", "4294967296"],
            &["error: invalid value '4294967296' for '--spp <SPP>'", "1..=65536"],
        ),
        row(
            "good.toml",
            GOOD.into(),
            &["render", "FILE", "-o", "OUT", "--spp", "99999"],
            &["error: invalid value '99999' for '--spp <SPP>'", "1..=65536"],
        ),
        row(
            "data.toml",
            "seed = 1\ntowns = [\"town01\"]\nframes_per_sequence = 1\nspp =".into(),
            &["dataset", "FILE", "-o", "OUT"],
            &["data.toml: line 4, column 6: the file ends inside \"spp =\": a value is missing"],
        ),
        row(
            "tw.toml",
            "seed =".into(),
            &["town", "FILE"],
            &["tw.toml:1:7: the file ends inside \"seed =\": a value is missing"],
        ),
        row(
            "scale.toml",
            with("translate = [5.0, 0.0, 1.0] }", "translate = [5.0, 0.0, 1.0], scale = 1e308 }"),
            RENDER,
            &["scale.toml: object[0].transform.scale: must be in [0, 1e7], got 1e308"],
        ),
        obj_row(
            "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/0\n",
            "",
            &["obj.toml: object[0].file: mesh.obj: line 5: texcoord index 0 in face corner \"3/0\""],
        ),
        mtl_row("Kd 0.5 nan 0.5", &["obj.toml: object[0].file: mesh.obj: looks.mtl: line 2: Kd: nan is out of range; allowed: 3 numbers (r g b), each in [0, 1]"]),
        mtl_row("Ni inf", &["looks.mtl: line 2: Ni: inf is out of range; allowed: a number > 0 and finite"]),
    ];
    // Every row runs; the failures are reported together.
    let mut failures = Vec::new();
    for r in rows {
        let c = Case::new();
        let paths: Vec<PathBuf> = r.files.iter().map(|(n, t)| c.file(n, t)).collect();
        let args: Vec<std::ffi::OsString> = r
            .args
            .iter()
            .map(|&a| match a {
                "FILE" => paths[0].clone().into_os_string(),
                "OUT" => c.out().into_os_string(),
                a => a.into(),
            })
            .collect();
        let o = parallax(&[]).args(&args).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        let mut wrong = Vec::new();
        if o.status.code() != Some(2) {
            wrong.push(format!("exit code {:?}", o.status.code()));
        }
        if c.out().exists() {
            wrong.push("output directory created".into());
        }
        if !err.starts_with("error: ") || err.starts_with("error: error:") {
            wrong.push("not one \"error: \" prefix".into());
        }
        if err.len() >= 400 {
            wrong.push(format!("{} bytes long", err.len()));
        }
        for s in r.says {
            if !err.contains(s) {
                wrong.push(format!("lacks {s:?}"));
            }
        }
        if !wrong.is_empty() {
            failures.push(format!(
                "{}: {}\n  stderr: {err}",
                r.files[0].0,
                wrong.join("; ")
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
