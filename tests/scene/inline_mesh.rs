//! Inline triangle meshes (`kind = "mesh"`): checked like OBJ files (finite
//! coordinates, indices in range, degenerate triangles dropped, an
//! all-degenerate mesh refused) with errors naming the object; a valid one
//! renders the same ground-truth depth as the same mesh read from an OBJ
//! file, and its description survives TOML → desc → TOML.

use std::fmt::Write as _;
use std::path::Path;

use parallax::accel::Backend;
use parallax::scene::load::parse_desc;
use parallax::scene::{parse_scene_str, SceneErrorKind};

use crate::common;
use common::{camera_block, render, GREY_UNDER_SKY};

/// A bumpy 3 × 3 vertex sheet facing the camera 6 m ahead (all coordinates
/// exact in f32, so an OBJ copy parses to the same numbers), plus one
/// degenerate triangle that both loaders drop.
fn sheet() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut positions = Vec::new();
    for (j, z) in [-1.5, 0.0, 1.5].into_iter().enumerate() {
        for (i, y) in [-2.0, 0.0, 2.0].into_iter().enumerate() {
            let bump = if i == 1 && j == 1 {
                -1.25
            } else {
                0.125 * i as f64
            };
            positions.push([6.0 + bump, y, z]);
        }
    }
    let mut triangles = Vec::new();
    for j in 0..2u32 {
        for i in 0..2u32 {
            let a = 3 * j + i;
            triangles.push([a, a + 1, a + 4]);
            triangles.push([a, a + 4, a + 3]);
        }
    }
    triangles.push([0, 0, 1]);
    (positions, triangles)
}

/// A scene with one inline mesh object named "sheet".
fn inline_scene(positions: &[[f64; 3]], triangles: &[[u32; 3]], extra: &str) -> String {
    let mut s = camera_block(41, 31, [0.0, 0.0, 0.0]);
    s += "[render]\nspp = 1\nseed = 3\n";
    s += GREY_UNDER_SKY;
    s += "[[object]]\nname = \"sheet\"\nkind = \"mesh\"\nmaterial = \"grey\"\n";
    s += extra;
    let list = |v: Vec<String>| format!("[{}]", v.join(", "));
    // TOML spells NaN `nan`.
    let num = |x: f64| {
        if x.is_nan() {
            "nan".into()
        } else {
            format!("{x:?}")
        }
    };
    let p = positions
        .iter()
        .map(|p| format!("[{}, {}, {}]", num(p[0]), num(p[1]), num(p[2])))
        .collect();
    let t = triangles
        .iter()
        .map(|t| format!("[{}, {}, {}]", t[0], t[1], t[2]))
        .collect();
    let _ = writeln!(s, "positions = {}\ntriangles = {}", list(p), list(t));
    s
}

fn parse(text: &str) -> Result<parallax::scene::LoadedScene, parallax::scene::SceneError> {
    parse_scene_str(text, Path::new("inline.toml"))
}

#[test]
fn inline_mesh_with_a_nan_vertex_is_refused_naming_the_object() {
    let (mut p, t) = sheet();
    p[4][2] = f64::NAN;
    let e = parse(&inline_scene(&p, &t, "")).unwrap_err();
    assert_eq!(e.kind, SceneErrorKind::Invalid, "{e}");
    assert_eq!(e.key, "object[0].positions", "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains("\"sheet\"") && msg.contains("vertex 4"),
        "{msg}"
    );
    // Absurdly far vertices are refused as in OBJ files.
    let (mut p, t) = sheet();
    p[2][0] = 3e7;
    let e = parse(&inline_scene(&p, &t, "")).unwrap_err();
    assert!(e.to_string().contains("vertex 2"), "{e}");
}

#[test]
fn inline_mesh_with_an_index_out_of_range_is_refused_naming_the_object() {
    let (p, mut t) = sheet();
    t[3] = [2, 9, 4];
    let e = parse(&inline_scene(&p, &t, "")).unwrap_err();
    assert_eq!(e.key, "object[0].triangles", "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains("\"sheet\"") && msg.contains("index 9") && msg.contains("9 vertices"),
        "{msg}"
    );
}

#[test]
fn inline_mesh_of_only_degenerate_triangles_is_refused_naming_the_object() {
    // Collinear and repeated vertices: no triangle has an area.
    let p = [[6.0, 0.0, 0.0], [6.0, 1.0, 0.0], [6.0, 2.0, 0.0]];
    let t = [[0, 1, 2], [0, 0, 1], [2, 2, 2]];
    let e = parse(&inline_scene(&p, &t, "")).unwrap_err();
    assert_eq!(e.key, "object[0].triangles", "{e}");
    let msg = e.to_string();
    assert!(
        msg.contains("\"sheet\"") && msg.contains("3 degenerate"),
        "{msg}"
    );
    // So is an empty mesh, and a normal list of the wrong length.
    let e = parse(&inline_scene(&[], &[], "")).unwrap_err();
    assert!(e.to_string().contains("\"sheet\""), "{e}");
    let (p, t) = sheet();
    let e = parse(&inline_scene(&p, &t, "normals = [[0.0, 0.0, 1.0]]\n")).unwrap_err();
    assert_eq!(e.key, "object[0].normals", "{e}");
}

#[test]
fn inline_mesh_renders_the_same_ground_truth_as_the_same_obj_file() {
    let (p, t) = sheet();
    let inline = parse(&inline_scene(&p, &t, "")).unwrap_or_else(|e| panic!("{e}"));
    // The degenerate triangle is dropped, as the OBJ loader drops it.
    assert_eq!(inline.triangle_estimate, t.len() as u64 - 1);

    let dir = tempfile::tempdir().unwrap();
    let mut obj = String::new();
    for v in &p {
        let _ = writeln!(obj, "v {:?} {:?} {:?}", v[0], v[1], v[2]);
    }
    for f in &t {
        let _ = writeln!(obj, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    std::fs::write(dir.path().join("sheet.obj"), obj).unwrap();
    let mut text = camera_block(41, 31, [0.0, 0.0, 0.0]);
    text += "[render]\nspp = 1\nseed = 3\n";
    text += GREY_UNDER_SKY;
    text +=
        "[[object]]\nname = \"sheet\"\nkind = \"obj\"\nfile = \"sheet.obj\"\nmaterial = \"grey\"\n";
    let from_obj =
        parse_scene_str(&text, &dir.path().join("s.toml")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(from_obj.triangle_estimate, inline.triangle_estimate);

    let (a, b) = (
        render(&inline, Backend::default_backend(), 0),
        render(&from_obj, Backend::default_backend(), 0),
    );
    let (ga, gb) = (&a.out.left, &b.out.left);
    let hits = ga.depth_z.iter().filter(|z| z.is_finite()).count();
    assert!(
        hits > 300 && hits < ga.depth_z.len(),
        "{hits} pixels see the sheet"
    );
    for k in 0..ga.depth_z.len() {
        assert_eq!(
            ga.depth_z[k].to_bits(),
            gb.depth_z[k].to_bits(),
            "depth_z at {k}"
        );
        assert_eq!(ga.normal_world[k], gb.normal_world[k], "normal at {k}");
    }
    // The bump (1.25 m nearer) is seen in the middle of the image.
    let mid = (15 * 41 + 20) as usize;
    assert!((ga.depth_z[mid] - 4.75).abs() < 1e-9, "{}", ga.depth_z[mid]);
}

#[test]
fn inline_mesh_description_round_trips_through_toml() {
    let (p, t) = sheet();
    let normals = "normals = [".to_string() + &vec!["[-1.0, 0.0, 0.0]"; p.len()].join(", ") + "]\n";
    let loaded = parse(&inline_scene(&p, &t, &normals)).unwrap_or_else(|e| panic!("{e}"));
    let back = parse_desc(&loaded.desc.to_toml(), Path::new("back.toml")).unwrap();
    assert_eq!(back, loaded.desc);
    // Shading normals reach the built mesh, one per vertex.
    let r = render(&loaded, Backend::default_backend(), 0);
    assert_eq!(r.scene.meshes[0].normals.len(), p.len());
    assert_eq!(r.scene.meshes[0].triangles.len(), t.len() - 1);
}
