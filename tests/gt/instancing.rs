//! Ground truth through two-level instances: the same prefab placements
//! built as instances and flattened give the same depth (1e-9 relative,
//! tighter than the 1e-6 contract),
//! identical semantic and instance ids, the same disparity and identical
//! occlusion masks — near the origin and 2e5 m from it (the render origin
//! follows the camera, so the rig stands there too), with rotated and
//! non-uniformly scaled instances, a nested prefab and per-instance label
//! overrides, on the default backend and the pure-Rust BVH.

use crate::common;

use glam::DVec3;
use parallax::accel::{build_accel, AnyAccel, Backend};
use parallax::camera::StereoRig;
use parallax::integrator::gt::{occlusion_mask, view_gt, ViewGt};
use parallax::integrator::RenderCamera;
use parallax::scene::semantic::class_id;
use parallax::scene::{build_scene_with, Instancing, LoadedScene, Scene};

const W: u32 = 96;
const H: u32 = 54;

/// Four placements of prefab "kiosk" (a box, an ellipsoid with smooth
/// normals, a cylinder and a nested "lamp" prefab) in front of a camera at
/// `base` + (0, 0, 1.65) looking along +x, over a ground quad.
fn scene_text(base: DVec3) -> String {
    let at =
        |x: f64, y: f64, z: f64| format!("[{:?}, {:?}, {:?}]", base.x + x, base.y + y, base.z + z);
    let mut t = common::camera_block(W, H, [base.x, base.y, base.z + 1.65]);
    t += "baselines_cm = [54.0, 300.0]\n";
    t += common::GREY_UNDER_SKY;
    t += "[[material]]\nname = \"red\"\nkind = \"diffuse\"\nalbedo = [0.6, 0.1, 0.1]\n";
    t += &format!(
        "\n[[object]]\nkind = \"quad\"\nsize = [400.0, 400.0]\nmaterial = \"grey\"\nsemantic = \"road\"\ntransform = {{ translate = {} }}\n",
        at(0.0, 0.0, 0.0)
    );
    t += r#"
[[prefab]]
name = "lamp"
[[prefab.object]]
kind = "cylinder"
radius = 0.08
height = 2.5
segments = 10
material = "grey"
semantic = "pole"
[[prefab.object]]
kind = "ellipsoid"
radii = [0.3, 0.2, 0.15]
segments = 12
rings = 6
material = "red"
semantic = "pole"
transform = { translate = [0.0, 0.0, 2.6] }

[[prefab]]
name = "kiosk"
[[prefab.object]]
kind = "box"
size = [1.2, 2.0, 2.2]
material = "red"
semantic = "building"
transform = { translate = [0.0, 0.0, 1.1], rotate_deg = [0.0, 0.0, 17.0] }
[[prefab.object]]
kind = "ellipsoid"
radii = [0.9, 0.7, 0.5]
segments = 16
rings = 8
material = "grey"
semantic = "static"
transform = { translate = [0.3, -1.4, 0.6] }
[[prefab.object]]
kind = "instance"
prefab = "lamp"
transform = { translate = [-0.9, 1.3, 0.0] }
"#;
    let placements = [
        ("[6.3, 1.1, 0.0]", "[0.0, 0.0, 20.0]", "1.0", ""),
        (
            "[9.7, -2.9, 0.0]",
            "[0.0, 0.0, -65.0]",
            "[1.5, 0.6, 1.2]",
            "instance = 7\n",
        ),
        (
            "[14.2, 3.3, 0.4]",
            "[8.0, -5.0, 140.0]",
            "[0.7, 1.3, 0.9]",
            "semantic = \"vegetation\"\n",
        ),
        (
            "[19.5, -0.6, 0.0]",
            "[0.0, 0.0, 95.0]",
            "2.0",
            "instance = 9\nsemantic = \"fence\"\n",
        ),
    ];
    for (p, r, s, labels) in placements {
        let p: Vec<f64> = p
            .trim_matches(['[', ']'])
            .split(", ")
            .map(|v| v.parse().unwrap())
            .collect();
        t += &format!(
            "\n[[object]]\nkind = \"instance\"\nprefab = \"kiosk\"\n{labels}transform = {{ translate = {}, rotate_deg = {r}, scale = {s} }}\n",
            at(p[0], p[1], p[2])
        );
    }
    t
}

/// Left GT, per-baseline disparity and occlusion of `loaded` built with `mode`.
struct Gt {
    scene: Scene,
    left: ViewGt,
    disparity: Vec<Vec<f32>>,
    occlusion: Vec<Vec<u8>>,
}

fn ground_truth(loaded: &LoadedScene, mode: Instancing, backend: Backend) -> Gt {
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let scene = build_scene_with(loaded, rig.left.center_world, mode).expect("scene builds");
    let accel: AnyAccel = build_accel(backend, &scene.accel_geometry()).expect("accel builds");
    let left_cam = RenderCamera::new(&rig.left, scene.origin_world);
    let left = view_gt(&scene, &accel, &left_cam, true);
    let (mut disparity, mut occlusion) = (Vec::new(), Vec::new());
    for (b, &bm) in rig.baselines_m.iter().enumerate() {
        let right = RenderCamera::new(&rig.right(b), scene.origin_world);
        disparity.push(left.disparity(rig.left.intrinsics.f_px, bm));
        occlusion.push(occlusion_mask(&scene, &accel, &left_cam, &right, &left, bm).0);
    }
    Gt {
        scene,
        left,
        disparity,
        occlusion,
    }
}

fn assert_same_ground_truth(base: DVec3) {
    let loaded = common::scene_from_toml(&scene_text(base));
    let flat = ground_truth(&loaded, Instancing::Flat, Backend::Bvh);
    assert_eq!(flat.scene.instances.len(), 0);
    let mut backends = vec![Backend::Bvh];
    if cfg!(feature = "embree") {
        backends.push(Backend::Embree);
    }
    for backend in backends {
        let inst = ground_truth(&loaded, Instancing::Prototypes, backend);
        let c = inst.scene.content();
        assert_eq!((c.prototypes, c.instances), (1, 4), "{backend}");
        assert_eq!(c.instanced_triangles, flat.scene.content().unique_triangles);
        let (a, b) = (&inst.left, &flat.left);
        let mut on_kiosks = 0;
        for k in 0..a.depth_z.len() {
            let (za, zb) = (a.depth_z[k], b.depth_z[k]);
            let what = format!("{backend} at {base}: pixel {k}");
            assert_eq!(za.is_finite(), zb.is_finite(), "{what}: {za} vs {zb}");
            if za.is_finite() {
                // 1e-6 is the contract; 1e-9 shows both are the f64
                // re-intersection (traversal's f32 t is ~1e-7 off).
                assert!((za - zb).abs() <= 1e-9 * zb, "{what}: depth {za} vs {zb}");
            }
            assert_eq!(a.semantic[k], b.semantic[k], "{what}: semantic");
            assert_eq!(a.instance[k], b.instance[k], "{what}: instance id");
            assert_eq!(a.mask[k], b.mask[k], "{what}: mask");
            let cos = a.normal_world[k].dot(b.normal_world[k]);
            assert!(za.is_infinite() || cos > 0.9999, "{what}: normals {cos}");
            on_kiosks += (a.semantic[k] != 1 && za.is_finite()) as usize;
        }
        assert!(
            on_kiosks > 300,
            "{backend}: only {on_kiosks} pixels see the kiosks"
        );
        for (da, db) in inst.disparity.iter().zip(&flat.disparity) {
            for (x, y) in da.iter().zip(db) {
                assert!(
                    (x - y).abs() <= 1e-6 * y.abs(),
                    "{backend}: disparity {x} vs {y}"
                );
            }
        }
        assert_eq!(
            inst.occlusion, flat.occlusion,
            "{backend} at {base}: occlusion"
        );
    }
    // Every label the overrides give is seen: 7 and 9 as ids, vegetation and fence.
    let seen = |v: u16| flat.left.instance.contains(&v);
    assert!(seen(7) && seen(9), "instance overrides not visible");
    for class in ["vegetation", "fence", "pole", "static"] {
        let id = class_id(class).unwrap();
        assert!(flat.left.semantic.contains(&id), "{class} not visible");
    }
}

#[test]
fn instanced_and_flattened_prefabs_give_the_same_ground_truth_near_the_origin() {
    assert_same_ground_truth(DVec3::ZERO);
}

#[test]
fn instanced_and_flattened_prefabs_give_the_same_ground_truth_2e5_m_out() {
    assert_same_ground_truth(DVec3::new(2.0e5, -1.3e5, 12.0));
}
