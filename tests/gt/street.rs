//! Ground truth on the hand-built street (`scenes/street.toml`) at full
//! 1600×900 and every default baseline:
//! - reprojection (GROUND_TRUTH.md): for every non-occluded left pixel the
//!   right camera's ray through (x − d, y) hits the same 3D point within 1e-4·Z;
//! - independent intersectors: Embree and the pure-Rust BVH give the same
//!   depth_z on every pixel within 1e-5 relative (ties on triangle edges aside).

use crate::common;

use glam::DVec3;
use parallax::accel::{Accel, Backend, Ray};
use parallax::integrator::gt::exact_t;
use parallax::integrator::RenderCamera;
use parallax::scene::load_scene;

fn street() -> parallax::scene::LoadedScene {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/street.toml");
    load_scene(std::path::Path::new(path)).expect("street.toml loads")
}

#[test]
fn street_reprojection_hits_the_same_point_for_every_non_occluded_pixel() {
    let r = common::render(&street(), Backend::default_backend(), 0);
    let (w, h) = (r.rig.left.intrinsics.width, r.rig.left.intrinsics.height);
    let left = RenderCamera::new(&r.rig.left, r.scene.origin_world);
    for (b, gt) in r.out.baselines.iter().enumerate() {
        let right = RenderCamera::new(&r.rig.right(b), r.scene.origin_world);
        let (mut checked, mut bad, mut ties, mut worst) = (0usize, 0usize, 0usize, 0.0f64);
        for j in 0..h {
            for i in 0..w {
                let k = (j * w + i) as usize;
                let z = r.out.left.depth_z[k];
                if !z.is_finite() || gt.occlusion[k] == 255 {
                    continue;
                }
                let (x, y) = (i as f64 + 0.5, j as f64 + 0.5);
                let p_left: DVec3 = left.center + left.dir(x, y) * z;
                let d = gt.disparity_left[k] as f64;
                let dir_r = right.dir(x - d, y);
                let ray = Ray::new(right.center_f32(), dir_r.as_vec3());
                let left_ray = Ray::new(left.center_f32(), left.dir(x, y).as_vec3());
                let near_edge = |hit: Option<parallax::accel::Hit>, o: DVec3, dir: DVec3| {
                    hit.is_some_and(|h| distance_to_edge(&r.scene, o, dir, &h) <= 1e-4 * z)
                };
                let hit = r.accel.intersect(&ray);
                let err = hit.map_or(f64::INFINITY, |hit| {
                    let p_right =
                        right.center + dir_r * exact_t(&r.scene, right.center, dir_r, &hit);
                    (p_right - p_left).length() / z
                });
                checked += 1;
                if err > 1e-4 {
                    // Allowed only where a ray grazes a triangle edge (a tie).
                    let tie = near_edge(hit, right.center, dir_r)
                        || near_edge(r.accel.intersect(&left_ray), left.center, left.dir(x, y));
                    if tie {
                        ties += 1;
                    } else {
                        bad += 1;
                        worst = worst.max(err);
                    }
                }
            }
        }
        eprintln!(
            "B = {} m: {checked} pixels, {ties} edge ties, {bad} off (worst {worst:e})",
            gt.baseline_m
        );
        assert!(checked > (w * h / 2) as usize);
        assert_eq!(
            bad, 0,
            "pixels reproject to another point away from any edge"
        );
        assert!(ties * 10_000 <= checked, "{ties} edge ties is too many");
    }
}

/// Closest approach (metres) between the ray o + s·d and the edges of the
/// triangle it hit: a ray grazing a silhouette passes close to an edge even
/// where the two hit points lie far apart along the surface.
fn distance_to_edge(
    scene: &parallax::scene::Scene,
    o: DVec3,
    d: DVec3,
    hit: &parallax::accel::Hit,
) -> f64 {
    let Some([a, b, c]) = scene.hit_triangle(hit) else {
        return f64::INFINITY; // spheres have no edges
    };
    let d = d.normalize();
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|&(u, v)| {
            // Line–segment closest points: minimise |w0 + s·d − t·e|², t ∈ [0, 1].
            let (e, w0) = (v - u, o - u);
            let (bb, cc, dd, ee) = (d.dot(e), e.dot(e), d.dot(w0), e.dot(w0));
            let denom = cc - bb * bb;
            let t = if denom > 1e-12 * cc {
                ((ee - bb * dd) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let s = bb * t - dd;
            (w0 + d * s - e * t).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Needs Embree: without feature `embree` there is no second intersector, and
/// the test is not compiled rather than passing without comparing anything.
#[cfg(feature = "embree")]
#[test]
fn embree_and_bvh_agree_on_street_depth() {
    assert_eq!(Backend::default_backend(), Backend::Embree);
    let mut loaded = street();
    loaded.desc.camera.baselines_cm = vec![54.0];
    let a = common::render(&loaded, Backend::Embree, 0);
    let b = common::render(&loaded, Backend::Bvh, 0);
    let cam = RenderCamera::new(&a.rig.left, a.scene.origin_world);
    let w = cam.intrinsics.width;
    let (mut differ, mut off_edge) = (0usize, 0usize);
    for (k, (&za, &zb)) in a
        .out
        .left
        .depth_z
        .iter()
        .zip(&b.out.left.depth_z)
        .enumerate()
    {
        if (za.is_infinite() && zb.is_infinite()) || (za - zb).abs() <= 1e-5 * za.min(zb) {
            continue;
        }
        differ += 1;
        // A disagreement is a tie only if the ray passes through a triangle
        // edge within the depth tolerance: one backend reports the edge (a
        // grazing hit), the other the surface behind it.
        let (i, j) = (k as u32 % w, k as u32 / w);
        let d = cam.dir(i as f64 + 0.5, j as f64 + 0.5);
        let ray = Ray::new(cam.center_f32(), d.as_vec3());
        let z = za.min(zb);
        let on_edge = |hit: Option<parallax::accel::Hit>, scene| {
            hit.is_some_and(|h| distance_to_edge(scene, cam.center, d, &h) <= 1e-5 * z)
        };
        if !(on_edge(a.accel.intersect(&ray), &a.scene)
            || on_edge(b.accel.intersect(&ray), &b.scene))
        {
            off_edge += 1;
            if off_edge <= 6 {
                let (ha, hb) = (a.accel.intersect(&ray), b.accel.intersect(&ray));
                eprintln!(
                    "({i},{j}) z {za} vs {zb}: embree {:?} {:?}, bvh {:?} {:?}",
                    ha.map(|h| (h.geom_id, h.prim_id, h.t)),
                    ha.map(|h| distance_to_edge(&a.scene, cam.center, d, &h)),
                    hb.map(|h| (h.geom_id, h.prim_id, h.t)),
                    hb.map(|h| distance_to_edge(&b.scene, cam.center, d, &h))
                );
            }
        }
    }
    eprintln!(
        "{differ} of {} pixels differ, {off_edge} not on a triangle edge",
        a.out.left.depth_z.len()
    );
    assert_eq!(
        off_edge, 0,
        "Embree and the BVH disagree away from triangle edges"
    );
    assert!(
        differ * 10_000 <= a.out.left.depth_z.len(),
        "{differ} edge ties is too many"
    );
}
