//! Prefab instancing in the built scene: what becomes a prototype and what
//! stays flat, the content counts, and instanced geometry equal to the
//! flattened build up to the rounding of the instance transform.

use crate::common;

use glam::DVec3;
use parallax::scene::{build_scene, build_scene_with, load_scene, Instancing, Mesh, Scene};

/// Three placements of `name` (a box; `extra` adds to the prefab): one,
/// then a repeat of two with `material_map`.
fn placed_thrice(name: &str, extra: &str, material_map: &str) -> String {
    format!(
        r#"
[[prefab]]
name = "{name}"
[[prefab.object]]
kind = "box"
size = [1.0, 2.0, 3.0]
material = "grey"
semantic = "static"
{extra}
[[object]]
kind = "instance"
prefab = "{name}"
transform = {{ translate = [5.0, 1.0, 0.0] }}
[[object]]
kind = "instance"
prefab = "{name}"
{material_map}
transform = {{ translate = [9.0, -2.0, 0.0], rotate_deg = [0.0, 0.0, 30.0] }}
repeat = [{{ count = 2, offset = [0.0, 4.0, 0.0] }}]
"#
    )
}

fn build(body: &str) -> Scene {
    let text = common::camera_block(32, 18, [0.0, 0.0, 1.5])
        + common::GREY_UNDER_SKY
        + "[[material]]\nname = \"lamp\"\nkind = \"emissive\"\nradiance = [5.0, 5.0, 5.0]\n"
        + "[[material]]\nname = \"red\"\nkind = \"diffuse\"\nalbedo = [0.6, 0.1, 0.1]\n"
        + body;
    build_scene(&common::scene_from_toml(&text), DVec3::ZERO).expect("scene builds")
}

#[test]
fn shared_prefabs_become_instances_and_emitters_spheres_and_singletons_stay_flat() {
    // Placed thrice, same materials: one prototype, three instances, no flat mesh.
    let s = build(&placed_thrice("a", "", ""));
    let c = s.content();
    assert_eq!((c.prototypes, c.instances, c.meshes), (1, 3, 0));
    assert_eq!((c.unique_triangles, c.instanced_triangles), (12, 36));
    assert_eq!(c.objects_per_class.values().sum::<u64>(), 3);
    // Another material map on the repeat: its own prototype (materials are
    // resolved); the first placement, now alone with its map, stays flat.
    let s = build(&placed_thrice("a", "", "material_map = { grey = \"red\" }"));
    let c = s.content();
    assert_eq!((c.prototypes, c.instances, c.meshes), (1, 2, 1));
    // An emitter inside: flat, so the light set finds it.
    let lamp = "[[prefab.object]]\nkind = \"quad\"\nsize = [0.5, 0.5]\nmaterial = \"lamp\"\n";
    let s = build(&placed_thrice("a", lamp, ""));
    assert_eq!((s.content().prototypes, s.content().meshes), (0, 6));
    // Mapped to a non-emitter, the same prefab instances.
    let s = build(&placed_thrice(
        "a",
        lamp,
        "material_map = { lamp = \"red\" }",
    ));
    assert_eq!((s.content().prototypes, s.content().meshes), (1, 2));
    // A sphere inside: flat (spheres stay analytic).
    let ball = "[[prefab.object]]\nkind = \"sphere\"\nradius = 0.3\nmaterial = \"grey\"\n";
    let s = build(&placed_thrice("a", ball, ""));
    assert_eq!((s.content().prototypes, s.content().spheres), (0, 3));
    // Placed once: flat.
    let once = placed_thrice("a", "", "");
    let once = &once[..once.rfind("[[object]]").unwrap()];
    let s = build(once);
    assert_eq!((s.content().prototypes, s.content().meshes), (0, 1));
}

/// A mesh as a comparable record: labels, triangles, materials, world vertices.
type Record = (u8, u16, Vec<[u32; 3]>, Vec<u32>, Vec<DVec3>);

/// Meshes as comparable records: labels, triangles and f64 world vertices.
fn records(meshes: impl Iterator<Item = Mesh>, origin: DVec3) -> Vec<Record> {
    let mut v: Vec<_> = meshes
        .map(|m| {
            let p = m.p_render.iter().map(|&p| p + origin).collect::<Vec<_>>();
            (m.semantic, m.instance, m.triangles, m.tri_material, p)
        })
        .collect();
    // Order-free: the instanced build lists flat meshes before instances.
    let key = |r: &Record| {
        let p = r.4[0];
        (
            r.0,
            r.1,
            r.2.len(),
            (p.x * 1e4).round() as i64,
            (p.y * 1e4).round() as i64,
            (p.z * 1e4).round() as i64,
        )
    };
    v.sort_by_key(key);
    v
}

#[test]
fn the_street_instanced_holds_the_flattened_street_up_to_rounding() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/street.toml");
    let loaded = load_scene(&path).expect("street loads");
    // Far out, as a town frame can be: rounding stays relative to the origin.
    let origin = DVec3::new(2.0e5, 1.0e5, 0.0);
    let inst = build_scene_with(&loaded, origin, Instancing::Prototypes).unwrap();
    let flat = build_scene_with(&loaded, origin, Instancing::Flat).unwrap();
    let (ci, cf) = (inst.content(), flat.content());
    assert!(ci.prototypes >= 2 && ci.instances >= 10, "{ci:?}");
    assert!(ci.unique_triangles < cf.unique_triangles, "{ci:?}");
    assert_eq!(ci.instanced_triangles, cf.unique_triangles);
    assert_eq!(inst.triangle_count(), flat.triangle_count());
    assert_eq!(
        ci.objects_per_class.values().sum::<u64>(),
        ci.meshes + ci.spheres + ci.instances
    );
    let a = records(inst.flattened_meshes().map(|m| m.into_owned()), origin);
    let b = records(flat.meshes.iter().cloned(), origin);
    assert_eq!(a.len(), b.len());
    for (x, y) in a.iter().zip(&b) {
        assert_eq!((x.0, x.1, &x.2, &x.3), (y.0, y.1, &y.2, &y.3));
        for (p, q) in x.4.iter().zip(&y.4) {
            assert!((*p - *q).length() < 1e-9, "{p} vs {q}");
        }
    }
}
