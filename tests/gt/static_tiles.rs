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

/// z of the tilted ground of [`wide_ground`] at world (x, y).
fn ground_z(x: f64, y: f64) -> f64 {
    0.02 * (x - 2e5) - 0.015 * (y - 2e5) + 1.0
}

/// A scene holding one static ground mesh 2e5 m from the origin, 300 m ×
/// 240 m of jittered 19 m quads (wider than a tile, so it is cut into
/// pieces along tile edges), with the camera at `cam`.
fn wide_ground(cam: [f64; 3]) -> LoadedScene {
    use std::fmt::Write as _;
    let (x0, y0, n, m) = (2e5 - 141.3, 2e5 - 97.7, 16, 13);
    let mut s = 0x9e37_79b9_7f4a_7c15u64;
    let mut jitter = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 5.0
    };
    let mut p = Vec::new();
    for j in 0..=m {
        for i in 0..=n {
            let inner = i > 0 && j > 0 && i < n && j < m;
            let (dx, dy) = if inner {
                (jitter(), jitter())
            } else {
                (0.0, 0.0)
            };
            let (x, y) = (x0 + 19.0 * i as f64 + dx, y0 + 19.0 * j as f64 + dy);
            p.push(format!("[{x:?}, {y:?}, {:?}]", ground_z(x, y)));
        }
    }
    let mut t = Vec::new();
    for j in 0..m {
        for i in 0..n {
            let a = j * (n + 1) + i;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            t.push(format!("[{a}, {b}, {c}], [{a}, {c}, {d}]"));
        }
    }
    let mut text = crate::common::camera_block(8, 8, cam);
    text += crate::common::GREY_UNDER_SKY;
    text += "[[object]]\nname = \"ground\"\nkind = \"mesh\"\nmaterial = \"grey\"\nsemantic = \"terrain\"\n";
    let _ = writeln!(
        text,
        "positions = [{}]\ntriangles = [{}]",
        p.join(", "),
        t.join(", ")
    );
    let mut loaded = parallax::scene::parse_scene_str(&text, std::path::Path::new("ground.toml"))
        .expect("ground scene parses");
    loaded.static_objects = std::iter::once(0..1).collect();
    loaded
}

#[test]
fn rays_along_tile_seams_meet_a_wide_ground_cut_into_tiles() {
    use parallax::accel::Accel;
    use parallax::geometry::Ray;
    let cam = [2e5 + 3.7, 2e5 - 5.1, 40.0];
    let loaded = wide_ground(cam);
    let scene = build_scene(&loaded, glam::DVec3::from(cam)).expect("scene builds");
    assert!(scene.meshes.is_empty(), "the ground is no flat mesh");
    let tiles = scene.prototypes.iter().filter(|p| is_tile(p)).count();
    assert_eq!(tiles, 6 * 5, "tiles the ground crosses");
    // Reported as the one mesh it was: 16 × 13 quads.
    let c = scene.content();
    assert_eq!(
        (c.meshes, c.instanced_triangles, c.unique_triangles),
        (1, 416, 416)
    );
    assert_eq!(c.objects_per_class.values().sum::<u64>(), 1);
    let mut backends = vec![Backend::Bvh];
    if cfg!(feature = "embree") {
        backends.push(Backend::Embree);
    }
    for backend in backends {
        let accel = build_accel(backend, &scene.accel_geometry()).expect("accel builds");
        let mut shot = 0;
        // Points on and beside every tile edge the ground crosses (x and y
        // lines), each hit by a steep and a grazing ray from 12 m above.
        let x_lines = [-128.0, -64.0, 0.0, 64.0, 128.0].map(|v| 2e5 + v);
        let y_lines = [-64.0, 0.0, 64.0, 128.0].map(|v| 2e5 + v);
        let on_lines = x_lines
            .iter()
            .flat_map(|&x| (0..40).map(move |s| (x, 2e5 - 96.0 + 6.1 * s as f64, 0)))
            .chain(
                y_lines
                    .iter()
                    .flat_map(|&y| (0..40).map(move |s| (2e5 - 126.0 + 6.1 * s as f64, y, 1))),
            );
        for (lx, ly, axis) in on_lines {
            for off in [0.0, 1e-7, -1e-7, 5e-4, -5e-4, 2e-3, -2e-3] {
                let (x, y) = if axis == 0 {
                    (lx + off, ly)
                } else {
                    (lx, ly + off)
                };
                let z = ground_z(x, y);
                for dir in [[0.3, -0.2, -1.0], [4.0, 3.0, -0.2], [-5.0, 0.5, -0.3]] {
                    let d = glam::DVec3::from(dir).normalize();
                    let target = glam::DVec3::new(x, y, z);
                    let from = target - d * 12.0 / d.z.abs();
                    let o = (from - glam::DVec3::from(cam)).as_vec3();
                    let ray = Ray::new(o, d.as_vec3());
                    let what = format!("{backend}: ray at ({x}, {y}) along {dir:?}");
                    let hit = accel
                        .intersect(&ray)
                        .unwrap_or_else(|| panic!("{what} slips through"));
                    let want = (target - from).length();
                    assert!(
                        (hit.t as f64 - want).abs() < 1e-4 * want,
                        "{what}: t {} vs {want}",
                        hit.t
                    );
                    let exact = scene.hit_triangle(&hit).expect("a triangle");
                    let n = (exact[1] - exact[0]).cross(exact[2] - exact[0]).normalize();
                    assert!(n.z.abs() > 0.999, "{what}: normal {n}");
                    shot += 1;
                }
            }
        }
        assert_eq!(shot, 9 * 40 * 7 * 3);
    }
}
