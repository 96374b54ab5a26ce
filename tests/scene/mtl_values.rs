//! MTL values through `load_scene`: non-finite or out-of-range `Kd`, `Ks`,
//! `Ke`, `Ni`, `d` and `Ns` are refused with the MTL file, line and key; good
//! values still map to the materials they did.

use crate::common;

use parallax::scene::desc::MaterialKindDesc;
use parallax::scene::load_scene;

const OBJ: &str = "mtllib looks.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl paint\nf 1 2 3\n";

/// Loads the scene with `mtl` as looks.mtl; the error message or the
/// material kind of "m.obj/paint".
fn load(mtl: &str) -> Result<MaterialKindDesc, String> {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.obj"), OBJ).unwrap();
    std::fs::write(dir.path().join("looks.mtl"), mtl).unwrap();
    let path = dir.path().join("s.toml");
    std::fs::write(&path, common::obj_scene(None)).unwrap();
    let s = load_scene(&path).map_err(|e| e.to_string())?;
    Ok(s.objs["m.obj"].materials[0].kind.clone())
}

#[test]
fn bad_values_are_refused_naming_file_line_and_key() {
    for (line, value) in [
        ("Kd nan 0.5 0.5", "Kd: nan is out of range"),
        ("Kd 0.5 1.5 0.5", "Kd: 1.5 is out of range"),
        ("Ks 0.5 0.5 -0.1", "Ks: -0.1 is out of range"),
        ("Ke inf 1 1", "Ke: inf is out of range"),
        ("Ke -2 1 1", "Ke: -2 is out of range"),
        (
            "Ni nan",
            "Ni: nan is out of range; allowed: a number > 0 and finite",
        ),
        ("Ni 0", "Ni: 0 is out of range"),
        ("d 2", "d: 2 is out of range; allowed: a number in [0, 1]"),
        ("Ns -1", "Ns: -1 is out of range"),
        (
            "Kd 0.5",
            "Kd: \"0.5\" has 1 values; allowed: 3 numbers (r g b)",
        ),
    ] {
        let mtl = format!("# looks\nnewmtl paint\n{line}\n");
        let msg = load(&mtl).expect_err(line);
        eprintln!("{msg}");
        let want = format!("object[0].file: m.obj: looks.mtl: line 3: {value}");
        assert!(msg.contains(&want), "{line}: wanted {want:?} in {msg}");
    }
}

#[test]
fn good_values_still_map_to_materials() {
    let kind = load("newmtl paint\nKd 0.2 0.4 0.6\nNs 10\n").unwrap();
    assert_eq!(
        kind,
        MaterialKindDesc::Diffuse {
            albedo: [0.2f32 as f64, 0.4f32 as f64, 0.6f32 as f64]
        }
    );
    match load("newmtl paint\nKd 1 1 1\nNi 0.75\nd 0.5\n").unwrap() {
        MaterialKindDesc::Dielectric { ior, .. } => assert_eq!(ior, 0.75),
        k => panic!("not a dielectric: {k:?}"),
    }
}
