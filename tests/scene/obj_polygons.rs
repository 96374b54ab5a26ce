//! OBJ polygons and non-surface elements through `load_scene`: a concave face
//! is triangulated inside its outline (areas sum to the polygon's), `l` and
//! `p` elements never become triangles, and face errors name the OBJ line.

use crate::common;

use glam::DVec3;
use parallax::scene::obj::ObjAsset;
use parallax::scene::{load_scene, SceneError};

/// Loads a scene of the one OBJ `obj` (written as m.obj next to it).
fn load(obj: &str) -> Result<ObjAsset, SceneError> {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("m.obj"), obj).unwrap();
    let path = dir.path().join("s.toml");
    std::fs::write(&path, common::obj_scene(Some("grey"))).unwrap();
    load_scene(&path).map(|s| s.objs["m.obj"].clone())
}

/// Loading fails with a message naming the scene key, the OBJ and `says`.
fn refused(obj: &str, says: &[&str]) {
    let msg = load(obj).expect_err("accepted").to_string();
    eprintln!("{msg}");
    for s in ["object[0].file: m.obj: "].iter().chain(says) {
        assert!(msg.contains(s), "message lacks {s:?}: {msg}");
    }
}

/// Even-odd point-in-polygon test in the xy plane.
fn inside(p: DVec3, poly: &[[f64; 2]]) -> bool {
    let mut odd = false;
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        if (a[1] > p.y) != (b[1] > p.y) && p.x < a[0] + (p.y - a[1]) / (b[1] - a[1]) * (b[0] - a[0])
        {
            odd = !odd;
        }
    }
    odd
}

fn obj_of(poly: &[[f64; 2]]) -> String {
    let mut s: String = poly
        .iter()
        .map(|p| format!("v {} {} 0\n", p[0], p[1]))
        .collect();
    s += "f";
    for i in 1..=poly.len() {
        s += &format!(" {i}");
    }
    s + "\n"
}

#[test]
fn concave_face_is_triangulated_inside_its_outline() {
    // A comb-like outline whose first corner sits in a notch: a fan from it
    // covers the notches and reaches outside.
    let poly = [
        [1.0, 0.5],
        [0.0, 0.0],
        [3.0, 0.0],
        [3.0, 2.0],
        [2.0, 2.0],
        [2.0, 1.0],
        [1.5, 2.0],
        [0.0, 2.0],
    ];
    let shoelace: f64 = (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0;
    let asset = load(&obj_of(&poly)).unwrap();
    let g = &asset.groups[0];
    assert_eq!(g.triangles.len(), poly.len() - 2);
    let mut area = 0.0;
    for t in &g.triangles {
        let [a, b, c] = t.map(|i| g.positions[i as usize]);
        let n = (b - a).cross(c - a);
        assert!(
            n.z > 0.0,
            "triangle {t:?} flipped against the face's winding"
        );
        area += n.length() / 2.0;
        let centroid = (a + b + c) / 3.0;
        assert!(inside(centroid, &poly), "triangle {t:?} leaves the face");
    }
    assert!((area - shoelace).abs() < 1e-9, "areas {area} vs {shoelace}");
}

#[test]
fn convex_quads_keep_their_fan() {
    let asset = load("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    assert_eq!(asset.groups[0].triangles, vec![[0, 1, 2], [0, 2, 3]]);
}

#[test]
fn polylines_and_points_are_not_surfaces() {
    let verts = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n";
    refused(
        &format!("{verts}l 1 2 3\nl 1 2 3 4\np 1 2 3\n"),
        &["no usable triangles (0 faces"],
    );
    let asset = load(&format!("{verts}l 1 2 3 4\nf 2 4 3\np 1 2 3\n")).unwrap();
    assert_eq!(asset.triangle_count(), 1);
}

#[test]
fn self_intersecting_face_is_refused_with_its_line() {
    refused(
        "v 0 0 0\nv 2 2 0\nv 2 0 0\nv 0 1 0\n# bow tie\nf 1 2 3 4\n",
        &["line 6: the 4-corner polygon crosses itself"],
    );
}

#[test]
fn index_errors_name_the_line_and_the_value() {
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\n";
    refused(
        &format!("{tri}f 1/0 2/1 3/1\n"),
        &["line 6: texcoord index 0 in face corner \"1/0\""],
    );
    refused(
        &format!("{tri}f 1/1/1 2/1/1 3//0\n"),
        &["line 6: normal index 0 in face corner \"3//0\""],
    );
    refused(
        &format!("{tri}\nf 1 2 7\n"),
        &["line 7: vertex index 7", "3 vertices defined so far"],
    );
}
