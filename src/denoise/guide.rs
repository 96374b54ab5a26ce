//! The denoiser's per-pixel guide from the ground-truth pass ([`DepthGuide`]):
//! the exact depth_z, opacity 1 − Tr of each pixel-centre ray up to that
//! depth (the same ray and pixel-centre convention as `integrator/gt.rs`:
//! u = i + 0.5, v = j + 0.5, camera z = depth_z), so the filter groups
//! pixels by how much fog they look through; and pixel-centre normals from
//! that depth, which keep the light on the first surface
//! (`DenoiseSample::l_surf`) from mixing across creases. [`denoise_view`]
//! builds it for a rendered view and denoises that view.

use glam::Vec3;
use rayon::prelude::*;

use super::{denoise_guided, ViewInputs, Widths};
use crate::film::Film;
use crate::integrator::RenderCamera;
use crate::scene::Scene;

/// The view's ground truth that steers the filter, per pixel (row-major).
#[derive(Clone, Copy, Debug)]
pub struct DepthGuide<'a> {
    /// Pixel-centre depth_z in metres (+inf or NaN: sky).
    pub depth_z: &'a [f32],
    /// Opacity 1 − Tr of the pixel-centre ray up to that depth, in [0, 1].
    pub opacity: &'a [f32],
    /// Unit pixel-centre normals in any one frame (zero: unknown or sky),
    /// for the surface component; empty: depth alone steers it.
    pub normal: &'a [Vec3],
}

/// Opacity 1 − Tr in [0, 1] of every pixel-centre ray of `cam` up to the
/// pixel's `depth_z` (metres, row-major, +inf or NaN: the sky, Tr to
/// infinity). All zero without a medium.
pub fn centre_opacity(scene: &Scene, cam: &RenderCamera, depth_z: &[f32]) -> Vec<f32> {
    let (w, h) = view_size(cam, depth_z);
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

/// Denoises one rendered view in place with the scene's denoiser
/// (parallax's filters, [`denoise_guided`]; Open Image Denoise; or the
/// mean of the two images), guided by the view's exact
/// pixel-centre `depth_z`, the opacity along those rays and the normals the
/// depth implies. Widths: [`Widths::for_width`] for the view's
/// size, with or without a medium.
pub fn denoise_view(
    scene: &Scene,
    cam: &RenderCamera,
    depth_z: &[f32],
    film: &mut Film,
    inputs: &ViewInputs,
    aux: super::SurfaceAux<'_>,
) {
    let opacity = centre_opacity(scene, cam, depth_z);
    let normal = centre_normals(cam, depth_z);
    let guide = DepthGuide {
        depth_z,
        opacity: &opacity,
        normal: &normal,
    };
    let mut widths = Widths::for_width(film.width);
    if !super::Features::for_scene(scene).direct {
        widths.direct_levels = 0;
    }
    let oidn = |film: &mut Film| {
        super::oidn::denoise_view(film, inputs, &guide, &widths, aux)
            .unwrap_or_else(|e| panic!("{e}"))
    };
    match scene.denoiser {
        super::Denoiser::Parallax => denoise_guided(film, inputs, &guide, &widths),
        super::Denoiser::Oidn => oidn(film),
        super::Denoiser::Blend => {
            // The two denoisers' errors are largely unlike (parallax's
            // filters blur what the depth guide cannot tell apart, OIDN errs
            // elsewhere), so their mean has less than either.
            let mut own = film.clone();
            denoise_guided(&mut own, inputs, &guide, &widths);
            oidn(film);
            for (px, own) in film.rgb.iter_mut().zip(&own.rgb) {
                *px = 0.5 * (*px + *own);
            }
        }
    }
}

/// Unit camera-space normals of the pixel-centre surfaces from `depth_z`
/// alone (row-major; zero for sky): the cross product of the position steps
/// to the horizontal and vertical neighbours, each taken on the side whose
/// depth is nearer (so a depth edge does not tilt it). Works for every view
/// (right views have depth but no normal map).
pub fn centre_normals(cam: &RenderCamera, depth_z: &[f32]) -> Vec<Vec3> {
    let (w, h) = view_size(cam, depth_z);
    let pos = |i: usize, j: usize| -> Option<Vec3> {
        let z = depth_z[j * w + i];
        z.is_finite()
            .then(|| (cam.intrinsics.dir_cam(i as f64 + 0.5, j as f64 + 0.5) * z as f64).as_vec3())
    };
    // The step from p toward the nearer-in-depth of two neighbours, signed
    // as the increasing index.
    let step = |p: Vec3, lo: Option<Vec3>, hi: Option<Vec3>| -> Option<Vec3> {
        match (lo, hi) {
            (Some(a), Some(b)) if (a.z - p.z).abs() <= (b.z - p.z).abs() => Some(p - a),
            (_, Some(b)) => Some(b - p),
            (Some(a), None) => Some(p - a),
            (None, None) => None,
        }
    };
    (0..w * h)
        .into_par_iter()
        .map(|k| {
            let (i, j) = (k % w, k / w);
            let Some(p) = pos(i, j) else {
                return Vec3::ZERO;
            };
            let left = (i > 0).then(|| pos(i - 1, j)).flatten();
            let right = (i + 1 < w).then(|| pos(i + 1, j)).flatten();
            let up = (j > 0).then(|| pos(i, j - 1)).flatten();
            let down = (j + 1 < h).then(|| pos(i, j + 1)).flatten();
            match (step(p, left, right), step(p, up, down)) {
                (Some(dx), Some(dy)) => dx.cross(dy).normalize_or_zero(),
                _ => Vec3::ZERO,
            }
        })
        .collect()
}

/// `cam`'s image size (width, height), checked against its depth map.
fn view_size(cam: &RenderCamera, depth_z: &[f32]) -> (usize, usize) {
    let (w, h) = (
        cam.intrinsics.width as usize,
        cam.intrinsics.height as usize,
    );
    assert_eq!(
        depth_z.len(),
        w * h,
        "depth map size does not match the camera"
    );
    (w, h)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Intrinsics;
    use glam::{DMat3, DVec3};

    #[test]
    fn depth_normals_match_each_plane_up_to_a_depth_edge() {
        let (w, h) = (16usize, 12usize);
        let cam = RenderCamera {
            intrinsics: Intrinsics::from_hfov(w as u32, h as u32, 1.0),
            render_from_camera: DMat3::IDENTITY,
            center: DVec3::ZERO,
        };
        // Camera space: left half a near tilted wall (≈ 5 m), right half a
        // far one tilted the other way (≈ 20 m); depth_z where each
        // pixel-centre ray meets its plane n·x = c.
        let near = (DVec3::new(-0.6, 0.0, -0.8), -4.0);
        let far = (DVec3::new(0.2, 0.5, 1.0).normalize(), 20.0);
        let plane = |i: usize| if i < w / 2 { near } else { far };
        let depth: Vec<f32> = (0..w * h)
            .map(|k| {
                let (i, j) = (k % w, k / w);
                let r = cam.intrinsics.dir_cam(i as f64 + 0.5, j as f64 + 0.5);
                let (n, c) = plane(i);
                (c / n.dot(r)) as f32
            })
            .collect();
        assert!(depth.iter().all(|&z| z > 0.0 && z.is_finite()));
        let normals = centre_normals(&cam, &depth);
        for (k, got) in normals.iter().enumerate() {
            let want = plane(k % w).0.as_vec3();
            // Either orientation: the filter compares neighbours only, and
            // the cross product's sign is the same over the image.
            assert!(got.dot(want).abs() > 0.999, "pixel {k}: {got} vs {want}");
        }
        // Sky has no normal.
        let mut sky = depth.clone();
        sky[5] = f32::INFINITY;
        assert_eq!(centre_normals(&cam, &sky)[5], Vec3::ZERO);
    }
}
