//! Ground truth through static tiles (`scene::anchored`): a town's static
//! flat meshes, grouped into prototypes anchored on a world grid and placed
//! by a translation, give the ground truth of the same meshes built flat
//! around the camera — at the far corner of the town reaching farthest
//! from its origin (town06, x ≈ 1.5 km), where a tile's local f32
//! coordinates are as small as anywhere, on both backends.

use parallax::accel::{build_accel, Backend};
use parallax::camera::StereoRig;
use parallax::integrator::gt::{occlusion_mask, view_gt, ViewGt};
use parallax::integrator::RenderCamera;
use parallax::scene::{build_scene, is_tile, LoadedScene, Scene};
use parallax::town::{load_named_town, load_town_frame, CameraConfig};

/// Left GT and the occlusion masks of `loaded` on `backend`.
fn ground_truth(loaded: &LoadedScene, backend: Backend) -> (Scene, ViewGt, Vec<Vec<u8>>) {
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let scene = build_scene(loaded, rig.left.center_world).expect("scene builds");
    let accel = build_accel(backend, &scene.accel_geometry()).expect("accel builds");
    let left_cam = RenderCamera::new(&rig.left, scene.origin_world);
    let left = view_gt(&scene, &accel, &left_cam, true);
    let occlusion = rig
        .baselines_m
        .iter()
        .enumerate()
        .map(|(b, &bm)| {
            let right = RenderCamera::new(&rig.right(b), scene.origin_world);
            occlusion_mask(&scene, &accel, &left_cam, &right, &left, bm).0
        })
        .collect();
    (scene, left, occlusion)
}

#[test]
fn static_tiles_give_the_flat_ground_truth_at_the_far_corner_of_the_biggest_town() {
    let town = load_named_town("town06", None).unwrap();
    let mut tiled = load_town_frame(&town.desc, 3, 0, CameraConfig::Normal, &town.path).unwrap();
    // The static object reaching farthest east: stand 12 m above it and
    // look back west into the town, pitched down.
    let far = tiled.desc.objects[tiled.static_objects[0].clone()]
        .iter()
        .filter_map(|o| o.transform.translate)
        .max_by(|a, b| a[0].total_cmp(&b[0]))
        .unwrap();
    assert!(far[0] > 1400.0, "farthest static object at {far:?}");
    let cam = &mut tiled.desc.camera;
    (cam.width, cam.height) = (96, 54);
    cam.baselines_cm = vec![54.0, 300.0];
    cam.position = [far[0] - 10.0, far[1], far[2] + 12.0];
    (cam.yaw_deg, cam.pitch_deg, cam.roll_deg) = (180.0, 20.0, 0.0);
    // The same frame with every flat mesh built around the camera.
    let mut flat = tiled.clone();
    flat.static_objects.clear();
    let mut backends = vec![Backend::Bvh];
    if cfg!(feature = "embree") {
        backends.push(Backend::Embree);
    }
    let (fs, b, b_occ) = ground_truth(&flat, Backend::Bvh);
    assert!(!fs.prototypes.iter().any(is_tile));
    for backend in backends {
        let (ts, a, a_occ) = ground_truth(&tiled, backend);
        let tiles = ts.prototypes.iter().filter(|p| is_tile(p)).count();
        assert!(tiles > 20, "{tiles} tiles");
        // Counted as the flat meshes they hold, the two scenes hold the
        // same triangles.
        let (ct, cf) = (ts.content(), fs.content());
        assert_eq!(ct.instanced_triangles, cf.instanced_triangles, "{backend}");
        let mut seen = 0;
        for k in 0..a.depth_z.len() {
            let (za, zb) = (a.depth_z[k], b.depth_z[k]);
            let what = format!("{backend}: pixel {k}");
            assert_eq!(za.is_finite(), zb.is_finite(), "{what}: {za} vs {zb}");
            if za.is_finite() {
                assert!((za - zb).abs() <= 1e-6 * zb, "{what}: depth {za} vs {zb}");
                seen += 1;
            }
            assert_eq!(a.semantic[k], b.semantic[k], "{what}: semantic");
            assert_eq!(a.instance[k], b.instance[k], "{what}: instance id");
            assert_eq!(a.mask[k], b.mask[k], "{what}: mask");
        }
        assert!(seen > 2000, "{backend}: only {seen} pixels hit the town");
        assert_eq!(a_occ, b_occ, "{backend}: occlusion");
    }
    // The camera really stands far out: render space is centred on it.
    assert!(fs.origin_world.length() > 1400.0);
}
