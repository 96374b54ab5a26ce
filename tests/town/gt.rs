//! Ground truth of town frames in every camera configuration (GROUND_TRUTH.md
//! exactness), GT pass only at 160×90:
//! - pixel rays: the pixel-centre direction and camera centre are rebuilt
//!   here from the configuration's pose (height, pitch, roll; yaw = the
//!   ego's heading; a graded ego's body turn Rz(heading)·Ry(−pitch)·Rx(roll))
//!   and K (60° hfov, principal point at the image centre) as
//!   GROUND_TRUTH.md defines them, and match the rig's (1e-9);
//! - road pixels: on a level town depth_z equals the analytic intersection
//!   of that independent ray with the road plane z = 0 (1e-6 relative), so
//!   rolled and pitched rigs are posed exactly; on a graded town
//!   (`road_grade_m`) depth_z equals that ray's f64 intersection with the
//!   plane of the draped triangle it hits (1e-6 relative), and the world
//!   point C + d·depth_z lies on the road surface z = h(x, y) of the town's
//!   grade field within the drape's chord error;
//! - reprojection: every non-occluded left pixel's right-camera ray through
//!   (x − d, y) hits the same 3D point within 1e-4·max(Z, |X − C_R|) (the
//!   occlusion tolerance), except on triangle
//!   edges (ties between two surfaces), which must stay rare, and surfaces
//!   seen exactly edge-on from the right camera;
//! - labels: every hit pixel has a class other than "unlabeled".

use glam::{DMat3, DVec3};
use parallax::accel::{Accel, Backend, Hit, Ray};
use parallax::integrator::gt::exact_t;
use parallax::integrator::RenderCamera;
use parallax::render::recipe::BuiltScene;
use parallax::scene::semantic::class_id;
use parallax::scene::Scene;
use parallax::town::grade::Grade;
use parallax::town::rig::CAMERA_FORWARD_M;
use parallax::town::{frame_at, load_town_frame, CameraConfig, VehiclePose, CONFIGS};

use crate::common;
use common::towns::{gt_frame, town, town_file, TOWNS};

/// The left camera of `config` on `ego`, built here from first principles:
/// (world_from_camera, centre). Camera axes (OpenCV): x right, y down, z
/// forward. In the ego's body frame (x forward, y left, z up) the level
/// camera has x = −y_body, y = −z_body, z = x_body; pitching down by p turns
/// z towards y, rolling by r turns x towards y (clockwise seen from behind).
/// The body frame is Rz(heading)·Ry(−pitch)·Rx(roll) of the ego (level ego:
/// Rz(heading)); the camera sits `CAMERA_FORWARD_M` ahead of the footprint
/// centre at the configuration's height, along the body axes.
fn expected_camera(config: CameraConfig, ego: &VehiclePose) -> (DMat3, DVec3) {
    let (height, pitch, roll) = config.pose();
    let (p, r) = (pitch.to_radians(), roll.to_radians());
    let (fwd, right, down) = (DVec3::X, DVec3::NEG_Y, DVec3::NEG_Z);
    let z1 = fwd * p.cos() + down * p.sin();
    let y1 = down * p.cos() - fwd * p.sin();
    let x2 = right * r.cos() + y1 * r.sin();
    let y2 = y1 * r.cos() - right * r.sin();
    let rz = |a: f64| {
        let (s, c) = a.sin_cos();
        DMat3::from_cols_array(&[c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0])
    };
    let ry = |a: f64| {
        let (s, c) = a.sin_cos();
        DMat3::from_cols_array(&[c, 0.0, -s, 0.0, 1.0, 0.0, s, 0.0, c])
    };
    let rx = |a: f64| {
        let (s, c) = a.sin_cos();
        DMat3::from_cols_array(&[1.0, 0.0, 0.0, 0.0, c, s, 0.0, -s, c])
    };
    let body = rz(ego.heading_deg.to_radians())
        * ry(-ego.pitch_deg.to_radians())
        * rx(ego.roll_deg.to_radians());
    let centre = DVec3::from(ego.position) + body * DVec3::new(CAMERA_FORWARD_M, 0.0, height);
    (body * DMat3::from_cols(x2, y2, z1), centre)
}

/// World direction through the centre of pixel (i, j) of a W×H image with
/// a 60° horizontal field of view, scaled to camera-z component 1.
fn expected_dir(world_from_camera: DMat3, (w, h): (u32, u32), i: u32, j: u32) -> DVec3 {
    let f = (w as f64 / 2.0) / 30f64.to_radians().tan();
    let (u, v) = (i as f64 + 0.5, j as f64 + 0.5);
    world_from_camera * DVec3::new((u - w as f64 / 2.0) / f, (v - h as f64 / 2.0) / f, 1.0)
}

/// Vertical chord error allowed on a graded road: the field
/// h = A/2·(sin(k·u + φ₀) + sin(k·v + φ₁)) curves by at most A·k²/2 in any
/// direction; a draped piece (sides ≤ 5 m, `drape::STEP_M`) split into
/// right triangles (circumradius ≤ 5·√2/2 m) interpolates it within
/// A·k²/2 · R²/2 = 1.5 mm for town04 (A = 8 m, λ = 800 m); 3 mm (as in
/// tests/town/highway_loop.rs) leaves room for f32 depth at ~100 m.
const GRADED_ROAD_TOL_M: f64 = 3e-3;

/// Ray parameter along `d` from `o` (render space) of the plane of the
/// triangle the accelerator hits, in f64 from the mesh's vertices.
fn plane_t(scene: &Scene, accel: &impl Accel, o: DVec3, d: DVec3) -> f64 {
    let hit = accel
        .intersect(&Ray::new(o.as_vec3(), d.as_vec3()))
        .expect("a road pixel hits");
    let [a, b, c] = scene.hit_triangle(&hit).expect("a triangle");
    let n = (b - a).cross(c - a);
    (a - o).dot(n) / d.dot(n)
}

/// Distance from the hit point to the nearest edge of its triangle (metres).
fn distance_to_edge(scene: &Scene, o: DVec3, d: DVec3, hit: &Hit) -> f64 {
    let Some([a, b, c]) = scene.hit_triangle(hit) else {
        return f64::INFINITY;
    };
    let p = o + d * exact_t(scene, o, d, hit);
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|&(u, v)| {
            let e = v - u;
            let t = ((p - u).dot(e) / e.length_squared()).clamp(0.0, 1.0);
            (u + e * t - p).length()
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn town_ground_truth_is_exact_in_every_camera_configuration() {
    let road = class_id("road").unwrap();
    for name in TOWNS {
        let path = town_file(name);
        let desc = town(name);
        // Frame 0: the ego is on a straight (mid-corner, the roll30 rig's B = 3 m
        // camera sits 0.15 m above the road beside the curb and can be walled in).
        let (seed, frame) = (4, 0);
        let loaded = load_town_frame(&desc, seed, frame, CameraConfig::Normal, &path).unwrap();
        // One build per town, centred on the normal rig; every configuration
        // sits within 10 m of it.
        let origin = DVec3::from(loaded.desc.camera.position);
        let BuiltScene { scene, accel, .. } =
            BuiltScene::build(&loaded, origin, Backend::default_backend()).unwrap();
        let ego = frame_at(&desc, seed, frame).ego;
        let grade = Grade::new(&desc, seed);
        assert_eq!(grade.is_some(), desc.road_grade_m > 0.0, "{name}");
        if grade.is_none() {
            assert_eq!(
                (ego.pitch_deg, ego.roll_deg),
                (0.0, 0.0),
                "{name}: level ego"
            );
        } else {
            // The graded case exercises a tilted rig.
            assert!(
                ego.pitch_deg.abs() > 0.1 || ego.roll_deg.abs() > 0.1,
                "{name}: ego level on the grade"
            );
        }
        for config in CONFIGS {
            let (w, h) = (160u32, 90u32);
            let (rig, out) = gt_frame(
                &scene,
                &accel,
                config,
                &ego,
                (w, h),
                &[54.0, 300.0],
                (seed, frame),
            );
            let left = RenderCamera::new(&rig.left, scene.origin_world);
            let (rot, centre) = expected_camera(config, &ego);
            assert!(
                (rig.left.center_world - centre).length() < 1e-9,
                "{name} {config}: centre {} vs {centre}",
                rig.left.center_world
            );
            for (i, j) in [
                (0, 0),
                (w - 1, 0),
                (0, h - 1),
                (w - 1, h - 1),
                (w / 2, h / 2),
                (17, 61),
            ] {
                let (got, want) = (
                    rig.left.pixel_center_dir_world(i, j),
                    expected_dir(rot, (w, h), i, j),
                );
                assert!(
                    (got - want).length() < 1e-9,
                    "{name} {config} ({i},{j}): ray {got} vs {want}"
                );
            }
            let (mut road_px, mut hits) = (0usize, 0usize);
            for j in 0..h {
                for i in 0..w {
                    let k = (j * w + i) as usize;
                    let z = out.left.depth_z[k];
                    if !z.is_finite() {
                        continue;
                    }
                    hits += 1;
                    assert_ne!(out.left.semantic[k], 0, "{name} {config}: unlabelled pixel");
                    if out.left.semantic[k] == road {
                        // d has camera-z component 1: the point is C + d·depth_z.
                        let d = expected_dir(rot, (w, h), i, j);
                        match &grade {
                            Some(g) => {
                                // Exact on the draped triangle the ray hits ...
                                let s = plane_t(&scene, &accel, centre - scene.origin_world, d);
                                assert!(
                                    (z - s).abs() <= 1e-6 * s,
                                    "{name} {config} ({i},{j}): road z {z} vs {s}"
                                );
                                // ... and that triangle lies on the grade.
                                let p = centre + d * z;
                                let dz = p.z - g.height_m(p.x, p.y);
                                assert!(
                                    dz.abs() <= GRADED_ROAD_TOL_M,
                                    "{name} {config} ({i},{j}): road point {p} is {dz} m off the grade"
                                );
                            }
                            None => {
                                let s = -centre.z / d.z;
                                assert!(
                                    (z - s).abs() <= 1e-6 * s,
                                    "{name} {config} ({i},{j}): road z {z} vs {s}"
                                );
                            }
                        }
                        road_px += 1;
                    }
                }
            }
            assert!(road_px > 200, "{name} {config}: only {road_px} road pixels");
            assert!(hits > (w * h / 3) as usize, "{name} {config}: mostly sky");
            for (b, gt) in out.baselines.iter().enumerate() {
                let right = RenderCamera::new(&rig.right(b), scene.origin_world);
                let (mut checked, mut ties) = (0usize, 0usize);
                for j in 0..h {
                    for i in 0..w {
                        let k = (j * w + i) as usize;
                        let z = out.left.depth_z[k];
                        if !z.is_finite() || gt.occlusion[k] == 255 {
                            continue;
                        }
                        let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
                        let p_left = left.center + left.dir(x, y) * z;
                        let dir_r = right.dir(x - gt.disparity_left[k] as f64, y);
                        // At B = 3 m and 30° roll the right camera is 1.5 m
                        // lower, level with curb tops: a surface seen exactly
                        // edge-on from the right has no defined reprojection.
                        let n = out.left.normal_world[k].as_dvec3();
                        if n.dot(dir_r).abs() < 1e-3 * dir_r.length() {
                            continue;
                        }
                        let hit = accel.intersect(&Ray::new(right.center_f32(), dir_r.as_vec3()));
                        let err = hit.map_or(f64::INFINITY, |hit| {
                            let t = exact_t(&scene, right.center, dir_r, &hit);
                            (right.center + dir_r * t - p_left).length() / z
                        });
                        checked += 1;
                        // A blocker within the occlusion tolerance (1e-4 of
                        // |X − C_R|, which exceeds Z at wide baselines) leaves
                        // the pixel visible: it bounds the reprojection too.
                        // The accel traces f32 rays: origin and direction
                        // carry ~2⁻²³ of the render-space scale sideways,
                        // which a surface seen at a grazing angle θ turns
                        // into an offset along it 1/|cos θ| larger.
                        let seg = (p_left - right.center).length();
                        let f32_side = f32::EPSILON as f64 * (right.center.length() + seg);
                        let grazing = f32_side / (n.dot(dir_r).abs() / dir_r.length()) / z;
                        let tol = 1e-4 * seg.max(z) / z + grazing;
                        if err > tol {
                            let left_hit = accel
                                .intersect(&Ray::new(left.center_f32(), left.dir(x, y).as_vec3()));
                            let tie = |hit: Option<Hit>, o, d| {
                                hit.is_some_and(|hh| {
                                    distance_to_edge(&scene, o, d, &hh) <= 1e-4 * z
                                })
                            };
                            assert!(
                                tie(hit, right.center, dir_r) || tie(left_hit, left.center, left.dir(x, y)),
                                "{name} {config} B={} ({i},{j}): reprojection error {err:e} away from edges",
                                gt.baseline_m
                            );
                            ties += 1;
                        }
                    }
                }
                assert!(checked > 1000, "{name} {config}: {checked} pixels checked");
                assert!(
                    ties * 100 <= checked,
                    "{name} {config}: {ties} edge ties of {checked}"
                );
            }
        }
    }
}
