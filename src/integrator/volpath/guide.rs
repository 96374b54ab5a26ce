//! The fog filter's per-pixel guide from the ground-truth pass: opacity
//! 1 − Tr of each pixel-centre ray up to its exact depth (the same ray and
//! pixel-centre convention as `gt.rs`: u = i + 0.5, v = j + 0.5, camera
//! z = depth_z), so the filter groups pixels by how much fog they look through.

use rayon::prelude::*;

use crate::film::{filter_fog, Film, FogFilter, FogGuide, FogLayer};
use crate::integrator::RenderCamera;
use crate::scene::Scene;

/// Opacity 1 − Tr in [0, 1] of every pixel-centre ray of `cam` up to the
/// pixel's `depth_z` (metres, row-major, +inf or NaN: the sky, Tr to
/// infinity). All zero without a medium.
pub fn centre_opacity(scene: &Scene, cam: &RenderCamera, depth_z: &[f32]) -> Vec<f32> {
    let (w, h) = (
        cam.intrinsics.width as usize,
        cam.intrinsics.height as usize,
    );
    assert_eq!(
        depth_z.len(),
        w * h,
        "depth map size does not match the camera"
    );
    let Some(m) = scene.medium.as_ref() else {
        return vec![0.0; w * h];
    };
    let o = cam.center_f32();
    depth_z
        .par_iter()
        .enumerate()
        .map(|(k, &z)| {
            let (i, j) = (k % w, k / w);
            let d = cam.dir(i as f64 + 0.5, j as f64 + 0.5);
            // dir has camera z = 1, so the distance along the ray is z·|d|.
            let t = if z.is_finite() {
                (z as f64 * d.length()) as f32
            } else {
                f32::INFINITY
            };
            (1.0 - m.tr(o, d.normalize().as_vec3(), t)).clamp(0.0, 1.0)
        })
        .collect()
}

/// Filters the fog in-scattering of one rendered view in place
/// (`film::filter_fog` with the default widths for its size), guided by the
/// view's exact pixel-centre `depth_z` and the opacity along those rays.
pub fn filter_view_inscatter(
    scene: &Scene,
    cam: &RenderCamera,
    depth_z: &[f32],
    film: &mut Film,
    fog: &FogLayer,
) {
    let opacity = centre_opacity(scene, cam, depth_z);
    let guide = FogGuide {
        depth_z,
        opacity: &opacity,
    };
    filter_fog(film, fog, &guide, &FogFilter::for_width(film.width));
}
