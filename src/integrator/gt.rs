//! The ground-truth pass: one unjittered ray through every pixel centre of
//! every view, never filtered (GROUND_TRUTH.md; STYLE.md rule 5).
//!
//! Traversal is f32 (8-wide packets along a row); the hit primitive is then
//! re-intersected in f64 (`geometry::exact`), so depth_z = t along the
//! camera-z-normalised direction is exact. Disparity d = f·B/Z is computed in
//! f64 and rounded once. Occlusion for baseline B: the left surface point X
//! falls outside the right image (x − d < 0) or the segment C_R → X hits
//! something before X (relative tolerance 1e-4 of |X − C_R|).

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use super::RenderCamera;
use crate::accel::{Accel, Hit, Ray};
use crate::geometry::{ray_plane_t, ray_sphere_t, surface_interaction};
use crate::scene::{mask_bits, Scene};

/// Semantic class id of sky pixels (the class table in `scene::semantic`).
pub const SKY_CLASS: u8 = 13;

/// Per-pixel geometry of one view.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ViewGt {
    /// Image width.
    pub width: u32,
    /// Image height.
    pub height: u32,
    /// depth_z in f64 (exact); +inf for sky.
    pub depth_z: Vec<f64>,
    /// Unit world normals facing the camera (zero for sky).
    pub normal_world: Vec<Vec3>,
    /// Semantic class ids (sky class for no hit).
    pub semantic: Vec<u8>,
    /// Instance ids (0 = none).
    pub instance: Vec<u16>,
    /// Mask bits (GROUND_TRUTH.md: sky, rain, transparent, mirror-like).
    pub mask: Vec<u8>,
}

impl ViewGt {
    /// depth_z rounded to f32 (+inf stays +inf).
    pub fn depth_z_f32(&self) -> Vec<f32> {
        self.depth_z.iter().map(|&z| z as f32).collect()
    }

    /// Disparity f·B/Z in pixels, f64 arithmetic rounded once; 0 for sky.
    pub fn disparity(&self, f_px: f64, baseline_m: f64) -> Vec<f32> {
        self.depth_z
            .iter()
            .map(|&z| disparity_px(f_px, baseline_m, z))
            .collect()
    }
}

/// d = f·B/Z in f64, rounded once to f32; a point at infinity has disparity 0.
pub fn disparity_px(f_px: f64, baseline_m: f64, depth_z: f64) -> f32 {
    if depth_z.is_finite() {
        (f_px * baseline_m / depth_z) as f32
    } else {
        0.0
    }
}

/// Whether the f64 re-intersection agrees with traversal closely enough to be
/// the same surface (guards the near-parallel case where it is ill-conditioned).
fn plausible(t64: f64, t32: f32) -> bool {
    t64.is_finite() && t64 > 0.0 && (t64 - t32 as f64).abs() <= 1e-3 * t32 as f64 + 1e-3
}

/// Exact (f64) ray parameter of `hit` for the ray o + t·d.
pub fn exact_t(scene: &Scene, o: DVec3, d: DVec3, hit: &Hit) -> f64 {
    let g = hit.geom_id as usize;
    let t64 = if g < scene.meshes.len() {
        let m = &scene.meshes[g];
        let tri = m.triangles[hit.prim_id as usize];
        ray_plane_t(o, d, tri.map(|i| m.p_render[i as usize]))
    } else {
        let s = &scene.spheres[hit.prim_id as usize];
        ray_sphere_t(o, d, s.center, s.radius, 0.5 * hit.t as f64)
    };
    match t64 {
        Some(t) if plausible(t, hit.t) => t,
        _ => hit.t as f64,
    }
}

/// Per-thread buffers of one row of pixel-centre rays, reused across rows so
/// the pass allocates nothing per ray.
#[derive(Default)]
struct RowScratch {
    dirs: Vec<DVec3>,
    rays: Vec<Ray>,
    hits: Vec<Option<Hit>>,
}

impl RowScratch {
    /// Traces row `j` of `cam` (8-wide packets) and writes each pixel's exact
    /// depth_z into `depth_row`; the rays and hits stay in `self`.
    fn trace_row(
        &mut self,
        scene: &Scene,
        accel: &impl Accel,
        cam: &RenderCamera,
        j: usize,
        depth_row: &mut [f64],
    ) {
        let o = cam.center_f32();
        let v = j as f64 + 0.5;
        self.dirs.clear();
        self.dirs
            .extend((0..depth_row.len()).map(|i| cam.dir(i as f64 + 0.5, v)));
        self.rays.clear();
        self.rays
            .extend(self.dirs.iter().map(|d| Ray::new(o, d.as_vec3())));
        self.hits.clear();
        self.hits.resize(self.rays.len(), None);
        accel.intersect_batch(&self.rays, &mut self.hits);
        for ((z, h), &d) in depth_row.iter_mut().zip(&self.hits).zip(&self.dirs) {
            *z = match h {
                Some(h) => exact_t(scene, cam.center, d, h),
                None => f64::INFINITY,
            };
        }
    }
}

/// Full per-pixel GT of one view (labels included when `labels` is set).
/// Rows are written in place into the output maps, one task per row.
pub fn view_gt(scene: &Scene, accel: &impl Accel, cam: &RenderCamera, labels: bool) -> ViewGt {
    let (w, h) = (cam.intrinsics.width, cam.intrinsics.height);
    let (n, n_labels) = (
        w as usize * h as usize,
        if labels { w as usize * h as usize } else { 0 },
    );
    let mut gt = ViewGt {
        width: w,
        height: h,
        depth_z: vec![0.0; n],
        normal_world: vec![Vec3::ZERO; n_labels],
        semantic: vec![SKY_CLASS; n_labels],
        instance: vec![0u16; n_labels],
        mask: vec![mask_bits::SKY; n_labels],
    };
    let row_len = w as usize;
    let label_len = if labels { row_len } else { 0 };
    // Without labels the label maps are empty and every row gets `None`.
    let label_rows = gt
        .normal_world
        .chunks_mut(label_len.max(1))
        .zip(gt.semantic.chunks_mut(label_len.max(1)))
        .zip(gt.instance.chunks_mut(label_len.max(1)))
        .zip(gt.mask.chunks_mut(label_len.max(1)))
        .map(Some)
        .chain(std::iter::repeat_with(|| None));
    let rows: Vec<_> = gt
        .depth_z
        .chunks_mut(row_len)
        .zip(label_rows)
        .enumerate()
        .collect();
    rows.into_par_iter().for_each_init(
        RowScratch::default,
        |scratch, (j, (depth_row, label_row))| {
            scratch.trace_row(scene, accel, cam, j, depth_row);
            let Some((((normal, sem), inst), mask)) = label_row else {
                return;
            };
            for (i, (ray, hit)) in scratch.rays.iter().zip(&scratch.hits).enumerate() {
                let Some(hit) = hit else { continue };
                let si = surface_interaction(scene, ray, hit);
                let facing = if si.n_shading.dot(ray.d) > 0.0 {
                    -1.0
                } else {
                    1.0
                };
                normal[i] = si.n_shading * facing;
                sem[i] = si.semantic;
                inst[i] = si.instance;
                mask[i] = super::wet::mask_at(scene, &si, ray.d);
            }
        },
    );
    gt
}

/// Segments C_R → X end at this fraction of |X − C_R| (the contract's 1e-4
/// relative tolerance).
const OCCLUSION_T_MAX: f64 = 1.0 - 1e-4;

/// Left-view occlusion for the right camera `right`: 255 where the left
/// surface point is outside the right image or hidden from the right camera.
/// Returns the mask and the number of shadow rays traced.
pub fn occlusion_mask(
    scene: &Scene,
    accel: &impl Accel,
    left: &RenderCamera,
    right: &RenderCamera,
    left_gt: &ViewGt,
    baseline_m: f64,
) -> (Vec<u8>, u64) {
    let (w, h) = (left.intrinsics.width as usize, left.intrinsics.height);
    let f = left.intrinsics.f_px;
    let c_r = right.center;
    let rows: Vec<(Vec<u8>, u64)> = (0..h)
        .into_par_iter()
        .map(|j| {
            let v = j as f64 + 0.5;
            let mut occ = vec![0u8; w];
            let mut rays = Vec::with_capacity(w);
            let mut idx = Vec::with_capacity(w);
            for (i, o) in occ.iter_mut().enumerate() {
                let z = left_gt.depth_z[j as usize * w + i];
                if !z.is_finite() {
                    continue;
                }
                let x = i as f64 + 0.5;
                // The stored (rounded) disparity decides, so mask and file agree.
                if x - (disparity_px(f, baseline_m, z) as f64) < 0.0 {
                    *o = 255;
                    continue;
                }
                let p = left.center + left.dir(x, v) * z;
                let seg = p - c_r;
                rays.push(Ray::segment(
                    c_r.as_vec3(),
                    seg.as_vec3(),
                    OCCLUSION_T_MAX as f32,
                ));
                idx.push((i, seg));
            }
            let mut blocked = vec![false; rays.len()];
            accel.occluded_batch(&rays, &mut blocked);
            // Confirm in f64: the nearest blocker must lie before the
            // tolerance, not just round there in f32. The blocked segments of
            // a row are re-traced together, as packets.
            let (confirm, confirm_idx): (Vec<Ray>, Vec<(usize, DVec3)>) = rays
                .iter()
                .zip(&idx)
                .zip(&blocked)
                .filter(|(_, &b)| b)
                .map(|((r, &k), _)| (*r, k))
                .unzip();
            let mut hits = vec![None; confirm.len()];
            accel.intersect_batch(&confirm, &mut hits);
            let traced = (rays.len() + confirm.len()) as u64;
            for (hit, &(i, seg)) in hits.iter().zip(&confirm_idx) {
                if hit.is_some_and(|hit| exact_t(scene, c_r, seg, &hit) < OCCLUSION_T_MAX) {
                    occ[i] = 255;
                }
            }
            (occ, traced)
        })
        .collect();
    let rays = rows.iter().map(|r| r.1).sum();
    (rows.into_iter().flat_map(|r| r.0).collect(), rays)
}

/// Sets the rain bit (`mask_bits::RAIN`) of `gt.mask` where the pixel-centre
/// ray meets a rain streak before the surface. Depth and every other map stay
/// untouched: rain is not a surface (GROUND_TRUTH.md).
pub fn add_rain_mask(
    scene: &Scene,
    rain: &shaders_cpu::medium::Rain,
    cam: &RenderCamera,
    gt: &mut ViewGt,
) {
    let w = cam.intrinsics.width as usize;
    let o_world = scene.origin_world + cam.center;
    gt.mask.par_chunks_mut(w).enumerate().for_each(|(j, row)| {
        for (i, m) in row.iter_mut().enumerate() {
            let dir = cam.dir(i as f64 + 0.5, j as f64 + 0.5);
            let len = dir.length();
            // depth_z is t along the camera-z-normalised direction.
            let t_max = gt.depth_z[j * w + i] * len;
            if rain.intersect(o_world, dir / len, 0.0, t_max).is_some() {
                *m |= mask_bits::RAIN;
            }
        }
    });
}
