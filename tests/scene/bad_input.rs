//! Bad input: one test per class of error, each asserting that the message
//! names the scene file and the offending key path (or line and column).

use crate::common;

use std::path::Path;

use parallax::scene::{load_scene, parse_scene_str, SceneError, SceneErrorKind};

const FILE: &str = "scenes/bad.toml";

const CAMERA: &str = "[camera]\nposition = [0.0, 0.0, 1.5]\n";
/// A grey material under a white sky: the lit part every case starts from.
const LIT: &str = common::GREY_UNDER_SKY;

/// Parses `text` as scenes/bad.toml and returns its error.
fn error_of(text: &str) -> SceneError {
    match parse_scene_str(text, Path::new(FILE)) {
        Ok(_) => panic!("accepted bad input:\n{text}"),
        Err(e) => e,
    }
}

/// Checks the error's class and that its message names the file and `key`.
fn expect(text: &str, kind: SceneErrorKind, key: &str, says: &str) -> SceneError {
    let e = error_of(text);
    let msg = e.to_string();
    eprintln!("{msg}");
    assert_eq!(e.kind, kind, "{msg}");
    assert!(
        msg.starts_with(FILE),
        "message does not name the file: {msg}"
    );
    assert!(msg.contains(key), "message does not name `{key}`: {msg}");
    assert!(msg.contains(says), "message does not say `{says}`: {msg}");
    e
}

/// A lit scene with `body` appended.
fn scene(body: &str) -> String {
    format!("{CAMERA}{LIT}{body}")
}

const QUAD: &str = "[[object]]\nkind = \"quad\"\nsize = [1.0, 1.0]\nmaterial = \"grey\"\n";

#[test]
fn missing_file_is_an_io_error_naming_it() {
    let e = load_scene(Path::new("scenes/does_not_exist.toml")).unwrap_err();
    assert_eq!(e.kind, SceneErrorKind::Io);
    assert!(
        e.to_string().starts_with("scenes/does_not_exist.toml"),
        "{e}"
    );
}

#[test]
fn toml_syntax_error_gives_line_and_column() {
    let e = expect(
        &format!("{CAMERA}{LIT}[[object]\nkind = \"quad\"\n"),
        SceneErrorKind::Syntax,
        "",
        "",
    );
    let (line, _col) = e.line_col.expect("syntax errors carry a position");
    assert_eq!(line, 11, "{e}");
    assert!(e.to_string().starts_with("scenes/bad.toml:11:"), "{e}");
}

#[test]
fn unknown_key_is_named() {
    expect(
        &scene(&format!("{QUAD}colour = \"red\"\n")),
        SceneErrorKind::Syntax,
        "object[0]",
        "colour",
    );
    expect(
        &format!("[camera]\nposition = [0.0, 0.0, 0.0]\nzoom = 2.0\n{LIT}{QUAD}"),
        SceneErrorKind::Syntax,
        "camera",
        "zoom",
    );
    expect(
        &scene(&format!(
            "{QUAD}transform = {{ translate = [1.0, 0.0, 0.0], spin = 3.0 }}\n"
        )),
        SceneErrorKind::Syntax,
        "object[0].transform",
        "spin",
    );
}

#[test]
fn wrong_type_names_the_key_path() {
    let text = scene(QUAD).replace("[camera]\n", "[camera]\nwidth = \"wide\"\n");
    let e = expect(
        &text,
        SceneErrorKind::Syntax,
        "camera.width",
        "invalid type",
    );
    assert!(e.line_col.is_some(), "{e}");
    expect(
        &scene(&QUAD.replace("[1.0, 1.0]", "[1.0, \"a\"]")),
        SceneErrorKind::Syntax,
        "object[0]",
        "invalid type",
    );
}

#[test]
fn out_of_range_camera_and_render_values_are_named() {
    let with = |line: &str| scene(QUAD).replace("[camera]\n", &format!("[camera]\n{line}\n"));
    expect(
        &with("baselines_cm = [10.0, -5.0]"),
        SceneErrorKind::Invalid,
        "camera.baselines_cm",
        "> 0",
    );
    expect(
        &with("baselines_cm = [0.0]"),
        SceneErrorKind::Invalid,
        "camera.baselines_cm",
        "> 0",
    );
    expect(
        &with("hfov_deg = 180.0"),
        SceneErrorKind::Invalid,
        "camera.hfov_deg",
        "(0, 180)",
    );
    expect(
        &with("hfov_deg = 0.0"),
        SceneErrorKind::Invalid,
        "camera.hfov_deg",
        "(0, 180)",
    );
    expect(
        &with("width = 0"),
        SceneErrorKind::Invalid,
        "camera.width",
        "at least 1",
    );
    expect(
        &with("height = 0"),
        SceneErrorKind::Invalid,
        "camera.height",
        "at least 1",
    );
    expect(
        &scene(&format!("[render]\nspp = 0\n{QUAD}")),
        SceneErrorKind::Invalid,
        "render.spp",
        "must be in [1, 65536]",
    );
    expect(
        &scene(&format!("[render]\nspp = 70000\n{QUAD}")),
        SceneErrorKind::Invalid,
        "render.spp",
        "must be in [1, 65536]",
    );
    expect(
        &scene(&format!("[render]\nmax_depth = 0\n{QUAD}")),
        SceneErrorKind::Invalid,
        "render.max_depth",
        "≥ 1",
    );
}

#[test]
fn negative_sizes_and_radii_are_named() {
    expect(
        &scene(&QUAD.replace("[1.0, 1.0]", "[1.0, -1.0]")),
        SceneErrorKind::Invalid,
        "object[0].size",
        "> 0",
    );
    let sphere = "[[object]]\nkind = \"sphere\"\nradius = -2.0\nmaterial = \"grey\"\n";
    expect(
        &scene(sphere),
        SceneErrorKind::Invalid,
        "object[0].radius",
        "> 0",
    );
    let cyl = "[[object]]\nkind = \"cylinder\"\nradius = 1.0\nheight = 0.0\nmaterial = \"grey\"\n";
    expect(
        &scene(cyl),
        SceneErrorKind::Invalid,
        "object[0].height",
        "> 0",
    );
}

#[test]
fn non_finite_numbers_are_named() {
    let text = scene(&format!(
        "{QUAD}transform = {{ translate = [nan, 0.0, 0.0] }}\n"
    ));
    expect(
        &text,
        SceneErrorKind::Invalid,
        "object[0].transform.translate",
        "not a finite number",
    );
    let text = scene(QUAD).replace("position = [0.0, 0.0, 1.5]", "position = [inf, 0.0, 1.5]");
    expect(
        &text,
        SceneErrorKind::Invalid,
        "camera.position",
        "not a finite number",
    );
}

#[test]
fn material_parameters_out_of_range_are_named() {
    let metal =
        "[[material]]\nname = \"m\"\nkind = \"conductor\"\npreset = \"gold\"\nroughness = 1.5\n";
    expect(
        &scene(&format!("{metal}{QUAD}")),
        SceneErrorKind::Invalid,
        "material[1].roughness",
        "[0, 1]",
    );
    let glass = "[[material]]\nname = \"g\"\nkind = \"dielectric\"\nior = 0.0\n";
    expect(
        &scene(&format!("{glass}{QUAD}")),
        SceneErrorKind::Invalid,
        "material[1].ior",
        "> 0",
    );
    let both = "[[material]]\nname = \"m\"\nkind = \"conductor\"\npreset = \"gold\"\neta = [1.0, 1.0, 1.0]\n";
    expect(
        &scene(&format!("{both}{QUAD}")),
        SceneErrorKind::Invalid,
        "material[1].preset",
        "either",
    );
    let unknown_preset =
        "[[material]]\nname = \"m\"\nkind = \"conductor\"\npreset = \"unobtainium\"\n";
    expect(
        &scene(&format!("{unknown_preset}{QUAD}")),
        SceneErrorKind::Syntax,
        "material[1]",
        "unobtainium",
    );
}

#[test]
fn unknown_material_is_named() {
    expect(
        &scene(&QUAD.replace("\"grey\"", "\"foo\"")),
        SceneErrorKind::Invalid,
        "object[0].material",
        "unknown material \"foo\"",
    );
    let prefab = "[[object]]\nkind = \"instance\"\nprefab = \"p\"\nmaterial_map = { grey = \"nope\" }\n\
                  [[prefab]]\nname = \"p\"\n[[prefab.object]]\nkind = \"box\"\nsize = [1.0, 1.0, 1.0]\nmaterial = \"grey\"\n";
    expect(
        &scene(prefab),
        SceneErrorKind::Invalid,
        "prefab[0].object[0].material (via object[0])",
        "\"nope\" (mapped from \"grey\")",
    );
}

#[test]
fn unknown_prefab_is_named() {
    let text = scene("[[object]]\nkind = \"instance\"\nprefab = \"tree\"\n");
    expect(
        &text,
        SceneErrorKind::Invalid,
        "object[0].prefab",
        "unknown prefab \"tree\"",
    );
}

#[test]
fn prefab_cycle_is_rejected_with_the_cycle_spelled_out() {
    let text = scene(
        "[[object]]\nkind = \"instance\"\nprefab = \"a\"\n\
         [[prefab]]\nname = \"a\"\n[[prefab.object]]\nkind = \"instance\"\nprefab = \"b\"\n\
         [[prefab]]\nname = \"b\"\n[[prefab.object]]\nkind = \"instance\"\nprefab = \"a\"\n",
    );
    expect(
        &text,
        SceneErrorKind::Invalid,
        "prefab[0]",
        "prefab cycle: a → b → a",
    );
}

#[test]
fn unknown_semantic_class_is_named() {
    let text = scene(&format!("{QUAD}semantic = \"spaceship\"\n"));
    expect(
        &text,
        SceneErrorKind::Invalid,
        "object[0].semantic",
        "unknown semantic class \"spaceship\"",
    );
}

#[test]
fn duplicate_material_names_are_named() {
    let dup = "[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.1, 0.1, 0.1]\n";
    expect(
        &scene(&format!("{dup}{QUAD}")),
        SceneErrorKind::Invalid,
        "material[1].name",
        "duplicate material name \"grey\"",
    );
}

#[test]
fn sphere_with_rotation_or_stretch_is_named() {
    let sphere = "[[object]]\nkind = \"sphere\"\nradius = 1.0\nmaterial = \"grey\"\n";
    let rotated = format!("{sphere}transform = {{ rotate_deg = [0.0, 0.0, 10.0] }}\n");
    expect(
        &scene(&rotated),
        SceneErrorKind::Invalid,
        "object[0].transform.rotate_deg",
        "sphere",
    );
    let stretched = format!("{sphere}transform = {{ scale = [1.0, 2.0, 1.0] }}\n");
    expect(
        &scene(&stretched),
        SceneErrorKind::Invalid,
        "object[0].transform.scale",
        "uniformly",
    );
}

#[test]
fn no_light_is_an_error() {
    let text = format!("{CAMERA}[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n{QUAD}");
    expect(&text, SceneErrorKind::NoLight, "", "no light");
    // An emissive material that no object uses does not light the scene.
    let unused = "[[material]]\nname = \"lamp\"\nkind = \"emissive\"\nradiance = [1.0, 1.0, 1.0]\n";
    let text = format!("{CAMERA}[sky]\nkind = \"constant\"\nle = [0.0, 0.0, 0.0]\n{unused}[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n{QUAD}");
    expect(&text, SceneErrorKind::NoLight, "", "no light");
    // A sun with zero irradiance is no light either.
    let dark_sun = "[[light]]\nkind = \"sun\"\nelevation_deg = 30.0\nazimuth_deg = 0.0\nirradiance = [0.0, 0.0, 0.0]\n";
    let text = format!("{CAMERA}{dark_sun}[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n{QUAD}");
    expect(&text, SceneErrorKind::NoLight, "", "no light");
}

#[test]
fn too_many_pixels_is_a_resource_error() {
    let text = scene(QUAD).replace("[camera]\n", "[camera]\nwidth = 10000\nheight = 10000\n");
    expect(
        &text,
        SceneErrorKind::Resource,
        "camera.width",
        "exceeds the limit",
    );
}

#[test]
fn too_many_triangles_is_refused_before_tessellating() {
    let text = scene(&format!(
        "{}repeat = [{{ count = 100000, offset = [1.0, 0.0, 0.0] }}, {{ count = 100000, offset = [0.0, 1.0, 0.0] }}]\n",
        QUAD.replace("quad\"\nsize = [1.0, 1.0]", "box\"\nsize = [1.0, 1.0, 1.0]")
    ));
    expect(
        &text,
        SceneErrorKind::Resource,
        "object",
        "120000000000 triangles",
    );
}

/// Writes `obj` (and an MTL) next to a scene that uses it; returns the error.
fn obj_error(obj: &str, mtl: &str, kind: SceneErrorKind, says: &str) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.obj"), obj).unwrap();
    std::fs::write(dir.path().join("m.mtl"), mtl).unwrap();
    let path = dir.path().join("bad.toml");
    std::fs::write(
        &path,
        scene("[[object]]\nkind = \"obj\"\nfile = \"m.obj\"\nmaterial = \"grey\"\n"),
    )
    .unwrap();
    let e = load_scene(&path).unwrap_err();
    let msg = e.to_string();
    eprintln!("{msg}");
    assert_eq!(e.kind, kind, "{msg}");
    assert!(msg.starts_with(&path.display().to_string()), "{msg}");
    assert!(msg.contains("object[0].file"), "{msg}");
    assert!(msg.contains(says), "{msg}");
}

const TRI: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";

#[test]
fn obj_with_non_finite_or_absurd_coordinates_is_rejected() {
    obj_error(
        "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
        "",
        SceneErrorKind::Obj,
        "not finite",
    );
    obj_error(
        "v 0 0 0\nv 1e9 0 0\nv 0 1 0\nf 1 2 3\n",
        "",
        SceneErrorKind::Obj,
        "beyond",
    );
}

#[test]
fn obj_with_bad_indices_is_rejected() {
    obj_error(&format!("{TRI}f 1 2 7\n"), "", SceneErrorKind::Obj, "m.obj");
}

#[test]
fn obj_with_only_degenerate_or_no_triangles_is_rejected() {
    obj_error(
        "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
        "",
        SceneErrorKind::Obj,
        "no usable triangles",
    );
    obj_error(TRI, "", SceneErrorKind::Obj, "no usable triangles");
}

#[test]
fn obj_with_unknown_mtl_material_is_rejected() {
    let obj = format!("mtllib m.mtl\n{TRI}usemtl chrome\nf 1 2 3\n");
    obj_error(
        &obj,
        "newmtl paint\nKd 1 0 0\n",
        SceneErrorKind::Obj,
        "line 5: unknown MTL material \"chrome\"",
    );
}

#[test]
fn missing_obj_file_is_an_io_error_naming_the_key() {
    let text = scene("[[object]]\nkind = \"obj\"\nfile = \"nowhere.obj\"\n");
    expect(&text, SceneErrorKind::Io, "object[0].file", "nowhere.obj");
}

#[test]
fn material_map_key_that_renames_nothing_is_named() {
    let text = scene(
        "[[object]]\nkind = \"instance\"\nprefab = \"p\"\nmaterial_map = { gray = \"grey\" }\n\
         [[prefab]]\nname = \"p\"\n[[prefab.object]]\nkind = \"box\"\nsize = [1.0, 1.0, 1.0]\nmaterial = \"grey\"\n",
    );
    expect(
        &text,
        SceneErrorKind::Invalid,
        "object[0].material_map.gray",
        "uses material \"gray\"",
    );
}
