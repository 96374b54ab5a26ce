//! OBJ + MTL export of a town frame, re-imported through the scene's OBJ
//! loader: the same triangle count, the same bounds (to f32 precision of the
//! loader), every face on the material and the vertices of the scene's
//! triangle it came from (in order), every material resolved, and a scene
//! referencing the export builds with the same triangle count (the static
//! tiles' pieces, as written).

use std::path::Path;

use glam::DVec3;
use parallax::scene::obj::load_obj;
use parallax::scene::{build_scene, load_scene};
use parallax::town::export::write_obj;
use parallax::town::{load_town, load_town_frame, CameraConfig};

fn bounds(points: impl Iterator<Item = DVec3>) -> (DVec3, DVec3) {
    points.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}

#[test]
fn export_then_reimport_keeps_triangle_count_and_bounds() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/town02.toml");
    let desc = load_town(&path).unwrap_or_else(|e| panic!("{e}"));
    let loaded = load_town_frame(&desc, 5, 12, CameraConfig::Normal, &path).unwrap();
    let scene = build_scene(&loaded, DVec3::new(100.0, 50.0, 1.65)).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let obj = dir.path().join("town02.obj");
    let stats = write_obj(&loaded, &scene, &obj).expect("export writes");
    // The export writes the static tiles' pieces: a mesh wider than a tile
    // is cut at tile edges, which adds `cut_triangles` to the scene's count.
    let content = scene.content();
    assert!(content.cut_triangles > 0, "the ground is cut into tiles");
    let written = content.instanced_triangles + content.cut_triangles;
    assert_eq!(stats.triangles, written);
    assert!(dir.path().join("town02.mtl").is_file());

    let asset = load_obj(&dir.path().join("s.toml"), "object[0]", "town02.obj", &obj)
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(asset.dropped_degenerate, 0);
    assert_eq!(asset.triangle_count(), written);
    assert_eq!(asset.materials.len(), stats.materials);
    assert!(asset.groups.iter().all(|g| g.material.is_some()));

    let want = bounds(scene.flattened_meshes().flat_map(|m| {
        m.p_render
            .iter()
            .map(|&p| p + scene.origin_world)
            .collect::<Vec<_>>()
    }));
    let got = bounds(
        asset
            .groups
            .iter()
            .flat_map(|g| g.positions.iter().copied()),
    );
    // The loader may parse in f32: allow its rounding at a few hundred metres.
    for (a, b) in [(want.0, got.0), (want.1, got.1)] {
        assert!((a - b).abs().max_element() < 1e-3, "bounds {a} vs {b}");
    }
    assert!((want.1 - want.0).x > 200.0, "the export covers the town");

    // Face by face, in order: the re-imported triangle has the world
    // vertices and the material (MTL names carry no whitespace, the loader
    // prefixes the file name) of the scene's triangle it was written from.
    let want_faces = scene.flattened_meshes().flat_map(|m| {
        let faces: Vec<_> = m
            .triangles
            .iter()
            .zip(&m.tri_material)
            .map(|(t, &mi)| {
                (
                    t.map(|i| m.p_render[i as usize] + scene.origin_world),
                    format!(
                        "town02.obj/{}",
                        scene.materials[mi as usize]
                            .name
                            .replace(char::is_whitespace, "_")
                    ),
                )
            })
            .collect();
        faces
    });
    let got_faces = asset.groups.iter().flat_map(|g| {
        let name = &asset.materials[g.material.expect("usemtl")].name;
        g.triangles
            .iter()
            .map(move |t| (t.map(|i| g.positions[i as usize]), name))
    });
    let mut faces = 0u64;
    let mut used = std::collections::BTreeSet::new();
    for (k, ((wp, wm), (gp, gm))) in want_faces.zip(got_faces).enumerate() {
        assert_eq!(&wm, gm, "face {k}: material");
        for (a, b) in wp.iter().zip(&gp) {
            assert!((*a - *b).abs().max_element() < 1e-3, "face {k}: {a} vs {b}");
        }
        used.insert(wm);
        faces += 1;
    }
    assert_eq!(faces, written);
    // Not one material for everything: a town uses dozens.
    assert!(used.len() > 10, "{} materials in use", used.len());

    // A scene file referencing the export loads, validates and builds with
    // the same triangle count.
    let scene_file = dir.path().join("s.toml");
    std::fs::write(
        &scene_file,
        "[camera]\nwidth = 16\nheight = 9\nposition = [100.0, 50.0, 1.65]\n\
         [sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n\
         [[object]]\nkind = \"obj\"\nfile = \"town02.obj\"\nsemantic = \"road\"\n",
    )
    .unwrap();
    let reloaded = load_scene(&scene_file).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(reloaded.triangle_estimate, written);
    let rebuilt = build_scene(&reloaded, DVec3::new(100.0, 50.0, 1.65)).unwrap();
    assert_eq!(rebuilt.triangle_count() as u64, written);
    assert_eq!(rebuilt.materials.len(), stats.materials);

    // Materials come back with their kinds: the glass stays a dielectric.
    let glass = asset
        .materials
        .iter()
        .find(|m| m.name.ends_with("/glass"))
        .expect("glass exported");
    assert!(matches!(
        glass.kind,
        parallax::scene::desc::MaterialKindDesc::Dielectric { .. }
    ));
}
