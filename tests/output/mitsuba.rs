//! `parallax export --mitsuba`: the shared comparison scenes exported and
//! read back: the XML parsed (camera pose and field of view derived here
//! from the scene file's numbers, lights in render space, BSDF per
//! material, emitter, medium), every PLY file present with the triangle
//! count of its material's objects; bad input exits 2 and writes nothing.

use std::path::{Path, PathBuf};

use crate::common::cli::{parallax, repo};
use parallax::output::mitsuba::decode_ply;

fn scene(name: &str) -> PathBuf {
    repo()
        .join("benches/mitsuba/scenes")
        .join(format!("{name}.toml"))
}

/// Runs `parallax export --mitsuba SCENE -o out extra…`; (exit code, stderr).
fn export(scene: &Path, out: &Path, extra: &[&str]) -> (i32, String) {
    let mut args = vec![
        "export",
        "--mitsuba",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let o = parallax(&args).output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn floats(s: &str) -> Vec<f64> {
    s.split([',', ' '])
        .filter(|t| !t.is_empty())
        .map(|t| t.parse().unwrap())
        .collect()
}

fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol)
}

/// The `value` of the child `tag` named `name` of `node`.
fn param<'a>(node: roxmltree::Node<'a, 'a>, tag: &str, name: &str) -> &'a str {
    node.descendants()
        .find(|n| n.has_tag_name(tag) && n.attribute("name") == Some(name))
        .and_then(|n| n.attribute("value"))
        .unwrap_or_else(|| panic!("no <{tag} name={name}>"))
}

#[test]
fn night_scene_exports_camera_lights_materials_and_meshes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("night");
    let (code, err) = export(&scene("night"), &out, &[]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(out.join("scene.xml")).unwrap();
    let doc = roxmltree::Document::parse(&text).expect("well-formed XML");
    let root = doc.root_element();
    assert_eq!(root.attribute("version"), Some("3.0.0"));
    let default = |name: &str| {
        root.children()
            .find(|n| n.has_tag_name("default") && n.attribute("name") == Some(name))
            .and_then(|n| n.attribute("value"))
            .unwrap()
    };
    // max_depth 4 in parallax's count is 5 in Mitsuba's; spp from [render].
    assert_eq!((default("max_depth"), default("spp")), ("5", "64"));

    // Camera: 70° horizontal fov, 320×180; at the origin of render space
    // (world − (0, 0, 1.6)), yaw 0 and pitched 10° down: forward (cos, 0,
    // −sin), image right = world −y, image up (sin, 0, cos). Mitsuba's
    // local +x is the image's left, +y up, +z forward.
    let sensor = root.children().find(|n| n.has_tag_name("sensor")).unwrap();
    assert!((floats(param(sensor, "float", "fov"))[0] - 70.0).abs() < 1e-9);
    assert_eq!(param(sensor, "string", "fov_axis"), "x");
    assert_eq!(param(sensor, "integer", "width"), "320");
    assert_eq!(param(sensor, "integer", "height"), "180");
    let m = sensor
        .descendants()
        .find(|n| n.has_tag_name("matrix"))
        .and_then(|n| n.attribute("value"))
        .map(floats)
        .unwrap();
    let (s, c) = 10f64.to_radians().sin_cos();
    let col = |j: usize| [m[j], m[4 + j], m[8 + j]];
    assert!(close(&col(0), &[0.0, 1.0, 0.0], 1e-12), "left {:?}", col(0));
    assert!(close(&col(1), &[s, 0.0, c], 1e-12), "up {:?}", col(1));
    assert!(close(&col(2), &[c, 0.0, -s], 1e-12), "forward {:?}", col(2));
    assert!(
        close(&col(3), &[0.0, 0.0, 0.0], 1e-12),
        "centre {:?}",
        col(3)
    );

    // Lights in render space with the scene's intensities (W/sr).
    let emitters: Vec<_> = root
        .children()
        .filter(|n| n.has_tag_name("emitter"))
        .collect();
    let points: Vec<_> = emitters
        .iter()
        .filter(|n| n.attribute("type") == Some("point"))
        .collect();
    assert_eq!(points.len(), 2);
    assert!(close(
        &floats(param(*points[0], "point", "position")),
        &[8.0, 3.0, 2.4],
        1e-5
    ));
    assert!(close(
        &floats(param(*points[0], "rgb", "intensity")),
        &[120.0, 100.0, 70.0],
        1e-4
    ));
    let spots: Vec<_> = emitters
        .iter()
        .filter(|n| n.attribute("type") == Some("spot"))
        .collect();
    assert_eq!(spots.len(), 2);
    assert!((floats(param(*spots[0], "float", "cutoff_angle"))[0] - 25.0).abs() < 1e-3);
    assert!((floats(param(*spots[0], "float", "beam_width"))[0] - 25.0).abs() < 1e-3);
    let lookat = spots[0]
        .descendants()
        .find(|n| n.has_tag_name("lookat"))
        .unwrap();
    let (o, t) = (
        floats(lookat.attribute("origin").unwrap()),
        floats(lookat.attribute("target").unwrap()),
    );
    assert!(close(&o, &[6.0, -2.0, 3.4], 1e-5), "spot origin {o:?}");
    let n = (0.09f64 + 0.01 + 1.0).sqrt();
    let d: Vec<f64> = (0..3).map(|i| t[i] - o[i]).collect();
    assert!(
        close(&d, &[0.3 / n, 0.1 / n, -1.0 / n], 1e-6),
        "spot axis {d:?}"
    );
    let sky = emitters
        .iter()
        .find(|n| n.attribute("type") == Some("constant"))
        .unwrap();
    assert!(close(
        &floats(param(*sky, "rgb", "radiance")),
        &[0.002, 0.003, 0.006],
        1e-9
    ));

    // One PLY per material, with that material's triangles: ground quad 2,
    // two wall boxes 24, the steel box 12, the lamp panel 2 (an area emitter).
    let expected = [("m0", 2), ("m1", 24), ("m2", 12), ("m3", 2)];
    let shapes: Vec<_> = root
        .children()
        .filter(|n| n.has_tag_name("shape") && n.attribute("type") == Some("ply"))
        .collect();
    assert_eq!(shapes.len(), expected.len());
    for (shape, (id, tris)) in shapes.iter().zip(expected) {
        let file = param(*shape, "string", "filename");
        let mesh = decode_ply(&std::fs::read(out.join(file)).unwrap()).unwrap();
        assert_eq!(mesh.triangles.len(), tris, "{file}");
        let r = shape.descendants().find(|n| n.has_tag_name("ref")).unwrap();
        assert_eq!(r.attribute("id"), Some(id));
        let bsdf = root
            .children()
            .find(|n| n.has_tag_name("bsdf") && n.attribute("id") == Some(id))
            .unwrap_or_else(|| panic!("bsdf {id}"));
        assert_eq!(bsdf.attribute("type"), Some("twosided"), "{id}");
        let area = shape.descendants().find(|n| n.has_tag_name("emitter"));
        assert_eq!(area.is_some(), id == "m3", "{id}: area emitter");
        if let Some(a) = area {
            assert!(close(
                &floats(param(a, "rgb", "radiance")),
                &[30.0, 28.0, 24.0],
                1e-9
            ));
        }
    }
    let steel = root
        .descendants()
        .find(|n| n.attribute("type") == Some("roughconductor"))
        .unwrap();
    assert!(
        (floats(param(steel, "float", "alpha"))[0] - 0.09).abs() < 1e-9,
        "α = 0.3²"
    );
}

#[test]
fn fog_scene_exports_a_homogeneous_medium_around_the_camera() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fog");
    let (code, err) = export(
        &scene("fog"),
        &out,
        &["--view", "right", "--baseline", "30"],
    );
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(out.join("scene.xml")).unwrap();
    let doc = roxmltree::Document::parse(&text).unwrap();
    let root = doc.root_element();
    let integrator = root
        .children()
        .find(|n| n.has_tag_name("integrator"))
        .unwrap();
    assert_eq!(integrator.attribute("type"), Some("volpath"));
    let medium = root.children().find(|n| n.has_tag_name("medium")).unwrap();
    assert_eq!(medium.attribute("type"), Some("homogeneous"));
    assert!((floats(param(medium, "float", "sigma_t"))[0] - 0.04).abs() < 1e-12);
    assert!(close(
        &floats(param(medium, "rgb", "albedo")),
        &[0.9; 3],
        1e-6
    ));
    assert!((floats(param(medium, "float", "g"))[0] - 0.6).abs() < 1e-6);
    let sensor = root.children().find(|n| n.has_tag_name("sensor")).unwrap();
    assert!(
        sensor
            .children()
            .any(|n| n.has_tag_name("ref") && n.attribute("id") == Some("fog")),
        "the camera sits in the fog"
    );
    let boundary = root
        .children()
        .find(|n| n.has_tag_name("shape") && n.attribute("type") == Some("cube"))
        .unwrap();
    assert!(boundary
        .descendants()
        .any(|n| n.has_tag_name("bsdf") && n.attribute("type") == Some("null")));
    // The right view 30 cm along the camera's +x (world −y at yaw 0).
    let m = sensor
        .descendants()
        .find(|n| n.has_tag_name("matrix"))
        .map(|n| floats(n.attribute("value").unwrap()))
        .unwrap();
    assert!(
        close(&[m[3], m[7], m[11]], &[0.0, -0.3, 0.0], 1e-12),
        "{m:?}"
    );
}

#[test]
fn bad_export_input_exits_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    // Height fog has no Mitsuba twin.
    let text = std::fs::read_to_string(scene("fog")).unwrap().replace(
        "kind = \"homogeneous\"",
        "kind = \"height_fog\"\nheight_scale_m = 30.0",
    );
    let bad = dir.path().join("height_fog.toml");
    std::fs::write(&bad, text).unwrap();
    let out = dir.path().join("x");
    let (code, err) = export(&bad, &out, &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("height_fog"), "{err}");
    assert!(!out.exists());
    // A baseline for the left view.
    let (code, err) = export(&scene("night"), &out, &["--baseline", "30"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--baseline"), "{err}");
    assert!(!out.exists());
    // A non-empty output directory is refused untouched.
    std::fs::create_dir_all(&out).unwrap();
    std::fs::write(out.join("keep.txt"), "mine").unwrap();
    let (code, err) = export(&scene("night"), &out, &[]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--output") && err.contains("empty"), "{err}");
    assert_eq!(std::fs::read_dir(&out).unwrap().count(), 1);
    // No format named.
    let o = parallax(&[
        "export",
        scene("night").to_str().unwrap(),
        "-o",
        "/tmp/never",
    ])
    .output()
    .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--mitsuba"));
}

#[test]
fn prefabs_stay_instanced_with_their_placements() {
    // A 1 m box prefab (12 triangles) placed three times, on a quad.
    let text = "[camera]\nwidth = 32\nheight = 18\nposition = [0.0, 0.0, 1.5]\n\
[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n\
[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
[[prefab]]\nname = \"crate\"\n[[prefab.object]]\nkind = \"box\"\nsize = [1.0, 1.0, 1.0]\nmaterial = \"grey\"\n\
[[object]]\nkind = \"quad\"\nsize = [50.0, 50.0]\nmaterial = \"grey\"\n\
[[object]]\nkind = \"instance\"\nprefab = \"crate\"\ntransform = { translate = [5.0, 0.0, 0.5] }\n\
[[object]]\nkind = \"instance\"\nprefab = \"crate\"\ntransform = { translate = [8.0, 2.0, 0.5], rotate_deg = [0.0, 0.0, 90.0] }\n\
[[object]]\nkind = \"instance\"\nprefab = \"crate\"\ntransform = { translate = [11.0, -2.0, 1.0], scale = 2.0 }\n";
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("crates.toml");
    std::fs::write(&file, text).unwrap();
    let out = dir.path().join("out");
    let (code, err) = export(&file, &out, &[]);
    assert_eq!(code, 0, "{err}");
    let xml = std::fs::read_to_string(out.join("scene.xml")).unwrap();
    let doc = roxmltree::Document::parse(&xml).unwrap();
    let root = doc.root_element();
    let group = root
        .children()
        .find(|n| n.has_tag_name("shape") && n.attribute("type") == Some("shapegroup"))
        .expect("the prefab as a shape group");
    let id = group.attribute("id").unwrap();
    let file = param(group, "string", "filename");
    let mesh = decode_ply(&std::fs::read(out.join(file)).unwrap()).unwrap();
    assert_eq!(mesh.triangles.len(), 12, "the box stored once");
    assert!(
        mesh.positions
            .iter()
            .all(|p| p.abs().max_element() <= 0.5 + 1e-6),
        "local frame"
    );
    let instances: Vec<Vec<f64>> = root
        .children()
        .filter(|n| n.has_tag_name("shape") && n.attribute("type") == Some("instance"))
        .map(|n| {
            assert_eq!(
                n.children()
                    .find(|c| c.has_tag_name("ref"))
                    .unwrap()
                    .attribute("id"),
                Some(id)
            );
            floats(
                n.descendants()
                    .find(|c| c.has_tag_name("matrix"))
                    .unwrap()
                    .attribute("value")
                    .unwrap(),
            )
        })
        .collect();
    assert_eq!(instances.len(), 3);
    // Render space: world − (0, 0, 1.5). Translations, the 90° turn, the scale.
    let t = |m: &Vec<f64>| [m[3], m[7], m[11]];
    assert!(close(&t(&instances[0]), &[5.0, 0.0, -1.0], 1e-9));
    assert!(close(&t(&instances[1]), &[8.0, 2.0, -1.0], 1e-9));
    assert!(close(&t(&instances[2]), &[11.0, -2.0, -0.5], 1e-9));
    let r = &instances[1];
    assert!(
        close(&[r[0], r[4], r[8]], &[0.0, 1.0, 0.0], 1e-12),
        "local x → world y"
    );
    assert!((instances[2][0] - 2.0).abs() < 1e-12, "scale 2");
    // The quad stays flat (render space).
    let flat: Vec<_> = root
        .children()
        .filter(|n| n.has_tag_name("shape") && n.attribute("type") == Some("ply"))
        .collect();
    assert_eq!(flat.len(), 1);
}
