//! Ground-truth exactness on analytic scenes at full 1600×900 for every default
//! baseline (GROUND_TRUTH.md "Exactness, as tests check it"):
//! |Z − Z*| ≤ 1e-5·Z*, |d − d*| ≤ 1e-5·d* + 1e-6, sky = +inf and 0.
//! Expected values are derived here independently of the renderer: for a level
//! rig looking along +x the ray through (u, v) is (1, −(u−cx)/f, −(v−cy)/f).

use crate::common;

use common::boxes::{boxes_scene, grazes_box_edge, slab, BOXES};
use common::{
    camera_block, level_right_centre, render, scene_from_toml, Rendered, DEFAULT_BASELINES_M,
    GREY_UNDER_SKY,
};
use glam::DVec3;
use parallax::accel::Backend;

const W: u32 = 1600;
const H: u32 = 900;

fn f_px() -> f64 {
    800.0 / (30f64.to_radians()).tan()
}

/// World direction with camera-z component 1 for a level rig looking along +x.
fn dir(i: u32, j: u32) -> DVec3 {
    let f = f_px();
    DVec3::new(
        1.0,
        -((i as f64 + 0.5) - 800.0) / f,
        -((j as f64 + 0.5) - 450.0) / f,
    )
}

/// The scenes here set no `baselines_cm`: every default one is rendered.
const BASELINES_M: [f64; 5] = DEFAULT_BASELINES_M;

/// Checks the rig against the independent convention and returns the right
/// centres derived here (not read from the renderer).
fn right_centres(r: &Rendered, c_left: DVec3) -> Vec<DVec3> {
    assert_eq!(
        r.rig.left.center_world, c_left,
        "left centre is the scene's position"
    );
    assert_eq!(r.out.baselines.len(), BASELINES_M.len(), "baseline count");
    assert_eq!(r.rig.baselines_m.len(), BASELINES_M.len(), "rig baselines");
    BASELINES_M
        .iter()
        .enumerate()
        .map(|(bi, &b)| {
            assert!(
                (r.out.baselines[bi].baseline_m - b).abs() < 1e-12,
                "baseline {bi}: {} m, expected {b} m",
                r.out.baselines[bi].baseline_m
            );
            let c = level_right_centre(c_left, b);
            let got = r.rig.right(bi).center_world;
            assert!(
                (got - c).length() <= 1e-9,
                "right centre {bi}: {got} vs {c} (C_L + B·x_L)"
            );
            c
        })
        .collect()
}

/// Checks every pixel of the left view and of every right view against
/// `z_true(camera_centre, i, j)` (None = sky); `c_left` is the scene's camera position.
fn check_all(r: &Rendered, c_left: DVec3, z_true: impl Fn(DVec3, u32, u32) -> Option<f64>) {
    check_all_with_ties(r, c_left, z_true, |_, _, _| false)
}

/// As `check_all`, but a pixel whose ray `grazes(camera_centre, i, j)` an edge
/// within tolerance may go either way (the contract's edge tie); such pixels
/// must stay rare.
fn check_all_with_ties(
    r: &Rendered,
    c_left: DVec3,
    z_true: impl Fn(DVec3, u32, u32) -> Option<f64>,
    grazes: impl Fn(DVec3, u32, u32) -> bool,
) {
    let mut ties = 0usize;
    let f = f_px();
    let c_rights = right_centres(r, c_left);
    let mut worst = 0.0f64;
    let left32 = r.out.left.depth_z_f32();
    for j in 0..H {
        for i in 0..W {
            let k = (j * W + i) as usize;
            let z = r.out.left.depth_z[k];
            if grazes(c_left, i, j) || c_rights.iter().any(|&c| grazes(c, i, j)) {
                ties += 1;
                continue;
            }
            match z_true(c_left, i, j) {
                None => {
                    assert!(
                        z.is_infinite() && z > 0.0,
                        "pixel ({i},{j}) should be sky, got {z}"
                    );
                    for b in &r.out.baselines {
                        assert_eq!(b.disparity_left[k], 0.0);
                    }
                }
                Some(zt) => {
                    let rel = (z - zt).abs() / zt;
                    worst = worst.max(rel);
                    assert!(rel <= 1e-5, "pixel ({i},{j}): Z {z} vs {zt}");
                    let z32 = left32[k] as f64;
                    assert!((z32 - zt).abs() <= 1e-5 * zt);
                    for (b, bm) in r.out.baselines.iter().zip(BASELINES_M) {
                        let dt = f * bm / zt;
                        let d = b.disparity_left[k] as f64;
                        assert!(
                            (d - dt).abs() <= 1e-5 * dt + 1e-6,
                            "pixel ({i},{j}) B={}: d {d} vs {dt}",
                            b.baseline_m
                        );
                    }
                }
            }
            for (bi, b) in r.out.baselines.iter().enumerate() {
                let c_right = c_rights[bi];
                match z_true(c_right, i, j) {
                    None => assert!(
                        b.depth_right[k].is_infinite() && b.disparity_right[k] == 0.0,
                        "right ({i},{j}) B={} should be sky, got {}",
                        b.baseline_m,
                        b.depth_right[k]
                    ),
                    Some(zt) => {
                        let zr = b.depth_right[k] as f64;
                        assert!(
                            (zr - zt).abs() <= 1e-5 * zt,
                            "right ({i},{j}) B={}: {zr} vs {zt}",
                            b.baseline_m
                        );
                        let dt = f * BASELINES_M[bi] / zt;
                        let d = b.disparity_right[k] as f64;
                        assert!((d - dt).abs() <= 1e-5 * dt + 1e-6);
                    }
                }
            }
        }
    }
    eprintln!("worst relative depth error {worst:e}, {ties} edge ties skipped");
    assert!(ties <= (W * H) as usize / 10_000, "{ties} edge ties");
}

/// Renders a plane 10 m ahead of a rig at (0, 0, 1.65) + `offset`; returns the
/// frame and the rig position.
fn fronto_plane(offset: DVec3) -> (Rendered, DVec3) {
    let c = DVec3::new(0.0, 0.0, 1.65) + offset;
    let text = format!(
        "{}{GREY_UNDER_SKY}\n[[object]]\nkind = \"quad\"\nsize = [400.0, 400.0]\nmaterial = \"grey\"\ntransform = {{ translate = [{:?}, {:?}, {:?}], rotate_deg = [0.0, -90.0, 0.0] }}\n",
        camera_block(W, H, c.to_array()),
        c.x + 10.0,
        c.y,
        c.z
    );
    (
        render(&scene_from_toml(&text), Backend::default_backend(), 0),
        c,
    )
}

#[test]
fn depth_and_disparity_exact_on_fronto_parallel_plane() {
    let (r, c_left) = fronto_plane(DVec3::ZERO);
    // The plane x = C_L.x + 10: Z = C_L.x + 10 − C.x for every camera (right cameras share x).
    check_all(&r, c_left, |c, _, _| Some(c_left.x + 10.0 - c.x));
}

#[test]
fn depth_and_disparity_exact_far_from_the_origin() {
    let (r, c_left) = fronto_plane(FAR);
    check_all(&r, c_left, |c, _, _| Some(c_left.x + 10.0 - c.x));
}

/// A scene far from the world origin: ~2e5 m, where f32 world coordinates
/// would have 1.5 cm steps.
const FAR: DVec3 = DVec3::new(2.0e5, -1.5e5, 30.0);

#[test]
fn depth_and_disparity_exact_on_tilted_plane() {
    tilted_plane(DVec3::ZERO);
}

#[test]
fn depth_and_disparity_exact_on_tilted_plane_far_from_the_origin() {
    tilted_plane(FAR);
}

fn tilted_plane(offset: DVec3) {
    // Plane through P0 = (12, 0, 1.65) + offset with normal n (tilted 35° about z and 20° up).
    let n = DVec3::new(-(35f64.to_radians().cos()), 35f64.to_radians().sin(), 0.3).normalize();
    let p0 = DVec3::new(12.0, 0.0, 1.65) + offset;
    let c_left = DVec3::new(0.0, 0.0, 1.65) + offset;
    // quad normal +z rotated: rotate about y then z to match n.
    let elev = n.z.asin();
    let az = n.y.atan2(n.x);
    let text = format!(
        "{}{GREY_UNDER_SKY}\n[[object]]\nkind = \"quad\"\nsize = [600.0, 600.0]\nmaterial = \"grey\"\ntransform = {{ translate = [{:?}, {:?}, {:?}], rotate_deg = [0.0, {:?}, {:?}] }}\n",
        camera_block(W, H, c_left.to_array()),
        p0.x,
        p0.y,
        p0.z,
        90.0 - elev.to_degrees(),
        az.to_degrees()
    );
    let r = render(&scene_from_toml(&text), Backend::default_backend(), 0);
    check_all(&r, c_left, |c, i, j| {
        let d = dir(i, j);
        let t = n.dot(p0 - c) / n.dot(d);
        (t > 0.0).then_some(t)
    });
}

#[test]
fn depth_and_disparity_exact_on_analytic_sphere() {
    analytic_sphere(DVec3::ZERO);
}

#[test]
fn depth_and_disparity_exact_on_analytic_sphere_far_from_the_origin() {
    analytic_sphere(FAR);
}

fn analytic_sphere(offset: DVec3) {
    let center = DVec3::new(15.0, 1.0, 2.0) + offset;
    let radius = 4.0;
    let c_left = DVec3::new(0.0, 0.0, 1.65) + offset;
    let text = format!(
        "{}{GREY_UNDER_SKY}\n[[object]]\nkind = \"sphere\"\nradius = {radius:?}\nmaterial = \"grey\"\ntransform = {{ translate = [{:?}, {:?}, {:?}] }}\n",
        camera_block(W, H, c_left.to_array()),
        center.x,
        center.y,
        center.z
    );
    let r = render(&scene_from_toml(&text), Backend::default_backend(), 0);
    check_all(&r, c_left, |c, i, j| {
        // Textbook quadratic a t² + b t + c = 0 (independent of the renderer's form).
        let d = dir(i, j);
        let oc = c - center;
        let (a, b, cc) = (d.dot(d), 2.0 * oc.dot(d), oc.dot(oc) - radius * radius);
        let disc = b * b - 4.0 * a * cc;
        (disc >= 0.0)
            .then(|| (-b - disc.sqrt()) / (2.0 * a))
            .filter(|&t| t > 0.0)
    });
}

#[test]
fn depth_and_disparity_exact_on_boxes() {
    let r = render(
        &scene_from_toml(&boxes_scene(W, H)),
        Backend::default_backend(),
        0,
    );
    check_all_with_ties(
        &r,
        DVec3::new(0.0, 0.0, 1.65),
        |c, i, j| {
            let d = dir(i, j);
            let ground = (d.z < 0.0).then(|| c.z / -d.z);
            BOXES
                .iter()
                .filter_map(|(ctr, s)| {
                    let (ctr, h) = (DVec3::from_array(*ctr), DVec3::from_array(*s) * 0.5);
                    slab(c, d, ctr - h, ctr + h)
                })
                .chain(ground)
                .min_by(|a, b| a.total_cmp(b))
        },
        |c, i, j| grazes_box_edge(c, dir(i, j)),
    );
}

#[test]
fn road_plane_to_the_horizon_is_exact_and_sky_is_infinite() {
    let text = format!(
        "{}{GREY_UNDER_SKY}\n[[object]]\nkind = \"quad\"\nsize = [40000.0, 40000.0]\nmaterial = \"grey\"\nsemantic = \"road\"\n",
        camera_block(W, H, [0.0, 0.0, 1.65])
    );
    let r = render(&scene_from_toml(&text), Backend::default_backend(), 0);
    let c_left = DVec3::new(0.0, 0.0, 1.65);
    check_all(&r, c_left, |c, i, j| {
        let d = dir(i, j);
        (d.z < 0.0).then(|| c.z / -d.z)
    });
    // Sky pixels carry the sky mask bit; road pixels the road class.
    assert_eq!(r.out.left.mask[0] & 1, 1);
    assert_eq!(r.out.left.semantic[(W * (H - 1)) as usize], 1);
}
