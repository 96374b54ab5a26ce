//! The rain pass: the frame's streaks (one world-space field, so every view
//! sees the same drops) composited over each view's path-traced radiance.
//!
//! A streak is a drop smeared over the exposure; a pixel on it sees the drop
//! for the fraction `coverage` of its area × exposure and what lies behind
//! for the rest (Garg & Nayar 2006). The streaks a pixel's centre ray meets
//! in front of its surface make one opacity α, pre-filtered to the pixel
//! (`Rain::opacity`), and the pixel becomes (1 − α)·L + α·L_drop. That
//! is deterministic, so a streak is as clean at 4 spp as at 1024 (traced
//! through the paths it was a 2 % coin flip per sample, lost in the noise).
//!
//! A drop refracts a wide (≈165°) field of the scene in front of the camera
//! and its brightness is close to that field's mean radiance (Garg & Nayar
//! 2007); the left view's mean radiance stands in for the field, one value
//! per frame shared by every view, as the exposure is.

use glam::{DMat3, DVec3, Vec3};
use rayon::prelude::*;
use shaders_cpu::medium::{Rain, Streak};

use super::RenderCamera;
use crate::film::Film;
use crate::scene::{mask_bits, Scene};

/// Opacity at which a pixel counts as rainy in the mask (one 8-bit step of
/// a mid-grey pixel is about 1 %).
pub const MASK_MIN_OPACITY: f32 = 0.01;

/// Fraction of the refracted field's mean radiance a drop shows (Garg &
/// Nayar 2007: about 94 %; the rest is lost to reflection and absorption).
const DROP_TRANSMISSION: f32 = 0.94;

/// Nearest camera depth a streak is projected from (closer parts are clipped).
const NEAR_Z_M: f64 = 1e-3;

/// Rain opacity of every pixel of `cam`, row-major: the streaks its centre
/// ray meets before the surface at `depth_z` (camera z, +inf for sky),
/// exactly as `Rain::opacity` finds them along that ray. Streaks are splatted
/// (each tested against the centre rays of the pixels its capsule projects
/// onto) rather than gathered per pixel: a few million streaks per frame
/// against a grid walk of hundreds of cells per pixel. Layers are handed out
/// in parallel and their hits applied in layer order, so the bytes do not
/// depend on the thread count.
pub fn rain_opacity(scene: &Scene, rain: &Rain, cam: &RenderCamera, depth_z: &[f64]) -> Vec<f32> {
    let (w, h) = (
        cam.intrinsics.width as usize,
        cam.intrinsics.height as usize,
    );
    assert_eq!(depth_z.len(), w * h, "depth map of another view size");
    let o_world = scene.origin_world + cam.center;
    let cam_from_world = cam.render_from_camera.transpose();
    let min_coverage = rain.min_opacity_coverage();
    let frustum = Frustum::new(cam);
    // A cell holds whole capsules: its bounding sphere bounds theirs.
    let cell_radius = 0.5 * 3f64.sqrt() * rain.cell_m;
    let layers: Vec<Vec<(u32, f64)>> = rain
        .layers()
        .collect::<Vec<_>>()
        .into_par_iter()
        .with_max_len(1)
        .map(|cz| {
            let mut hits = Vec::new();
            let cells = rain.layer_cells(cz);
            for cell in cells.filter(|&c| frustum.meets(rain.cell_centre(c) - o_world, cell_radius))
            {
                for streak in rain.streaks(cell) {
                    let Some((x0, x1, y0, y1)) =
                        pixel_bounds(rain, &streak, cam, o_world, cam_from_world)
                    else {
                        continue;
                    };
                    for j in y0..=y1 {
                        for i in x0..=x1 {
                            let dir = cam.dir(i as f64 + 0.5, j as f64 + 0.5);
                            let len = dir.length();
                            let k = j * w + i;
                            let t_max = depth_z[k] * len;
                            let Some(hit) =
                                rain.hit_streak(o_world, dir / len, &streak, min_coverage)
                            else {
                                continue;
                            };
                            if hit.t_axis > 0.0 && hit.t_axis < t_max {
                                hits.push((k as u32, rain.streak_opacity(&hit)));
                            }
                        }
                    }
                }
            }
            hits
        })
        .collect();
    let mut clear = vec![1.0f64; w * h];
    for (k, a) in layers.into_iter().flatten() {
        clear[k as usize] *= 1.0 - a;
    }
    clear.into_iter().map(|c| (1.0 - c) as f32).collect()
}

/// The four side planes of a camera's view pyramid (inward unit normals,
/// through the camera centre).
struct Frustum {
    normals: [DVec3; 4],
}

impl Frustum {
    fn new(cam: &RenderCamera) -> Self {
        let (w, h) = (cam.intrinsics.width as f64, cam.intrinsics.height as f64);
        let corners = [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)].map(|(u, v)| cam.dir(u, v));
        let inside = cam.dir(0.5 * w, 0.5 * h);
        let normals = std::array::from_fn(|k| {
            let n = corners[k].cross(corners[(k + 1) % 4]).normalize();
            if n.dot(inside) < 0.0 {
                -n
            } else {
                n
            }
        });
        Frustum { normals }
    }

    /// Whether a sphere at `p` (relative to the camera centre) of `radius`
    /// reaches into the pyramid.
    fn meets(&self, p: DVec3, radius: f64) -> bool {
        self.normals.iter().all(|n| n.dot(p) >= -radius)
    }
}

/// Inclusive pixel bounds (x0, x1, y0, y1) of the image of `streak`'s
/// capsule in `cam`, `None` when it lies behind the camera or off the image.
fn pixel_bounds(
    rain: &Rain,
    streak: &Streak,
    cam: &RenderCamera,
    o_world: DVec3,
    cam_from_world: DMat3,
) -> Option<(usize, usize, usize, usize)> {
    let radius = rain.streak_radius(streak);
    let r = streak.drop_radius_m;
    let top = cam_from_world * (streak.axis_top + DVec3::Z * r - o_world);
    let bottom = cam_from_world * (streak.axis_top - DVec3::Z * (streak.length_m + r) - o_world);
    // Clip the axis to the part at least the radius in front of the camera.
    let near = NEAR_Z_M + radius;
    let (mut a, mut b) = (top, bottom);
    if a.z < near && b.z < near {
        return None;
    }
    if a.z < near {
        a = b + (a - b) * ((b.z - near) / (b.z - a.z));
    } else if b.z < near {
        b = a + (b - a) * ((a.z - near) / (a.z - b.z));
    }
    let k = &cam.intrinsics;
    let (pa, pb) = (k.project(a), k.project(b));
    // The capsule's image lies within its radius's image of the projected
    // axis: f·R/z at the nearer end, stretched off-axis by up to 1/cos² of
    // the angle to the optical axis (× 2 bounds it under 45°); one pixel of
    // slack for rounding.
    let pad = 2.0 * k.f_px * radius / a.z.min(b.z) + 1.0;
    let (w, h) = (k.width as f64, k.height as f64);
    let (x0, x1) = (pa.x.min(pb.x) - pad, pa.x.max(pb.x) + pad);
    let (y0, y1) = (pa.y.min(pb.y) - pad, pa.y.max(pb.y) + pad);
    if x1 < 0.0 || y1 < 0.0 || x0 >= w || y0 >= h {
        return None;
    }
    let clamp = |v: f64, n: f64| v.clamp(0.0, n - 1.0) as usize;
    Some((clamp(x0, w), clamp(x1, w), clamp(y0, h), clamp(y1, h)))
}

/// Sets the rain bit of `mask` where `alpha` reaches [`MASK_MIN_OPACITY`].
/// Depth and every other map stay untouched: rain is not a surface
/// (GROUND_TRUTH.md).
pub fn mark_rain(mask: &mut [u8], alpha: &[f32]) {
    for (m, &a) in mask.iter_mut().zip(alpha) {
        if a >= MASK_MIN_OPACITY {
            *m |= mask_bits::RAIN;
        }
    }
}

/// Radiance of a drop seen in the frame whose left view is `left`: the
/// view's mean radiance (over its finite pixels) × the drop's transmission.
pub fn drop_radiance(left: &Film) -> Vec3 {
    let (sum, n) = left
        .rgb
        .iter()
        .filter(|c| c.is_finite())
        .fold((DVec3::ZERO, 0u64), |(s, n), c| (s + c.as_dvec3(), n + 1));
    (sum / n.max(1) as f64).as_vec3() * DROP_TRANSMISSION
}

/// Composites streaks of opacity `alpha` and radiance `l_drop` over `film`.
pub fn composite(film: &mut Film, alpha: &[f32], l_drop: Vec3) {
    assert_eq!(
        film.rgb.len(),
        alpha.len(),
        "opacity map of another view size"
    );
    for (c, &a) in film.rgb.iter_mut().zip(alpha) {
        if a > 0.0 {
            *c = *c * (1.0 - a) + l_drop * a;
        }
    }
}
