//! The ground-truth pass: one unjittered ray through every pixel centre of
//! every view, never filtered (GROUND_TRUTH.md; STYLE.md rule 5).
//!
//! Traversal is f32 (8-wide packets over 4×2 pixel tiles); the hit primitive is then
//! re-intersected in f64 (`geometry::exact`), so depth_z = t along the
//! camera-z-normalised direction is exact. Disparity d = f·B/Z is computed in
//! f64 and rounded once. Occlusion for baseline B: the left surface point X
//! falls outside the right image (x − d < 0) or the segment C_R → X hits
//! something before X (relative tolerance 1e-4 of |X − C_R|).

use glam::{DVec3, Vec3};
use rayon::prelude::*;

use super::{CentreDirs, RenderCamera};
use crate::accel::{Accel, Hit, Ray};
use crate::geometry::{ray_plane_t, ray_sphere_t};
use crate::scene::{mask_bits, surface_interaction, Scene};

/// Semantic class id of sky pixels (the class table in `scene::semantic`).
pub const SKY_CLASS: u8 = crate::scene::semantic::SKY;

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
    /// depth_z rounded to f32 (+inf stays +inf), on the thread pool.
    pub fn depth_z_f32(&self) -> Vec<f32> {
        self.depth_z.par_iter().map(|&z| z as f32).collect()
    }

    /// Disparity f·B/Z in pixels, f64 arithmetic rounded once; 0 for sky.
    /// On the thread pool: a frame converts 3 maps per baseline, and done on
    /// one thread they left the other idle.
    pub fn disparity(&self, f_px: f64, baseline_m: f64) -> Vec<f32> {
        self.depth_z
            .par_iter()
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

/// Exact (f64) ray parameter of `hit` for the ray o + t·d. A hit on an
/// instance is re-intersected in the prototype's frame, the ray carried
/// there by the f64 inverse (an affine map keeps t).
pub fn exact_t(scene: &Scene, o: DVec3, d: DVec3, hit: &Hit) -> f64 {
    let t64 = match scene.hit_mesh(hit) {
        Some((m, inst)) => {
            let tri = m.triangles[hit.prim_id as usize].map(|i| m.p_render[i as usize]);
            match inst {
                None => ray_plane_t(o, d, tri),
                Some(inst) => {
                    let x = inst.local_from_render;
                    ray_plane_t(x.transform_point3(o), x.transform_vector3(d), tri)
                }
            }
        }
        None => {
            let s = &scene.spheres[hit.prim_id as usize];
            ray_sphere_t(o, d, s.center, s.radius, 0.5 * hit.t as f64)
        }
    };
    match t64 {
        Some(t) if plausible(t, hit.t) => t,
        _ => hit.t as f64,
    }
}

/// Rows per GT task: 8-wide packets cover 4×2 pixel tiles, which keep a
/// packet's rays closer together than 8×1 rows (about 15% faster traversal on
/// Embree, measured on the city scene).
const BAND_ROWS: usize = 2;
/// Columns of one packet tile (`TILE_COLS × BAND_ROWS` = 8 lanes).
const TILE_COLS: usize = 4;

/// Fills `pixel` with the row-major indices of a `w × rows` band, tile by
/// tile (`TILE_COLS` columns of every row of the band), so consecutive runs
/// of 8 form 4×2 tiles.
fn tile_order(w: usize, rows: usize, pixel: &mut Vec<usize>) {
    pixel.clear();
    for i0 in (0..w).step_by(TILE_COLS) {
        for dj in 0..rows {
            let row = dj * w;
            pixel.extend((i0..(i0 + TILE_COLS).min(w)).map(|i| row + i));
        }
    }
}

/// Per-thread buffers of one band of pixel-centre rays, reused across bands
/// so the pass allocates nothing per ray. Rays are stored tile by tile
/// (`TILE_COLS × BAND_ROWS` pixels each); `pixel[k]` is ray k's index within
/// the band (row-major).
#[derive(Default)]
struct BandScratch {
    dirs: Vec<DVec3>,
    rays: Vec<Ray>,
    hits: Vec<Option<Hit>>,
    pixel: Vec<usize>,
}

impl BandScratch {
    /// Traces the band of rows starting at `j0` (`depth_band.len() / w`
    /// rows) of `cam` in 8-wide 4×2 tile packets, writes each pixel's exact
    /// depth_z into `depth_band` and hands every hit to `on_hit` (band
    /// index, ray, hit) right after its re-intersection, while the
    /// triangle's data is still in cache.
    #[allow(clippy::too_many_arguments)]
    fn trace_band(
        &mut self,
        scene: &Scene,
        accel: &impl Accel,
        cam: &RenderCamera,
        centre: &CentreDirs,
        j0: usize,
        depth_band: &mut [f64],
        mut on_hit: impl FnMut(usize, &Ray, &Hit),
    ) {
        let w = cam.intrinsics.width as usize;
        let rows = depth_band.len() / w;
        let o = cam.center_f32();
        tile_order(w, rows, &mut self.pixel);
        self.dirs.clear();
        self.rays.clear();
        for &k in &self.pixel {
            let d = centre.dir(k % w, j0 + k / w);
            self.dirs.push(d);
            self.rays.push(Ray::new(o, d.as_vec3()));
        }
        self.hits.clear();
        self.hits.resize(self.rays.len(), None);
        accel.intersect_batch(&self.rays, &mut self.hits);
        let traced = self.pixel.iter().zip(&self.rays).zip(&self.hits);
        for (((&k, ray), h), &d) in traced.zip(&self.dirs) {
            depth_band[k] = match h {
                Some(h) => {
                    let t = exact_t(scene, cam.center, d, h);
                    on_hit(k, ray, h);
                    t
                }
                None => f64::INFINITY,
            };
        }
    }
}

/// Full per-pixel GT of one view (labels included when `labels` is set).
/// Bands of `BAND_ROWS` rows are written in place into the output maps, one
/// task per band.
pub fn view_gt(scene: &Scene, accel: &impl Accel, cam: &RenderCamera, labels: bool) -> ViewGt {
    let (w, h) = (cam.intrinsics.width, cam.intrinsics.height);
    let centre = cam.centre_dirs();
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
    let band_len = w as usize * BAND_ROWS;
    let label_len = if labels { band_len } else { 0 };
    // Without labels the label maps are empty and every band gets `None`.
    let label_bands = gt
        .normal_world
        .chunks_mut(label_len.max(1))
        .zip(gt.semantic.chunks_mut(label_len.max(1)))
        .zip(gt.instance.chunks_mut(label_len.max(1)))
        .zip(gt.mask.chunks_mut(label_len.max(1)))
        .map(Some)
        .chain(std::iter::repeat_with(|| None));
    let bands: Vec<_> = gt
        .depth_z
        .chunks_mut(band_len.max(1))
        .zip(label_bands)
        .enumerate()
        .collect();
    // One job per band: sky bands cost almost nothing, street bands a lot, and
    // rayon's default split (a few large pieces per thread) left one thread
    // idle for a quarter of the pass.
    bands.into_par_iter().with_max_len(1).for_each_init(
        BandScratch::default,
        |scratch, (b, (depth_band, label_band))| {
            let j0 = b * BAND_ROWS;
            let Some((((normal, sem), inst), mask)) = label_band else {
                scratch.trace_band(scene, accel, cam, &centre, j0, depth_band, |_, _, _| {});
                return;
            };
            scratch.trace_band(scene, accel, cam, &centre, j0, depth_band, |k, ray, hit| {
                let si = surface_interaction(scene, ray, hit);
                let facing = if si.n_shading.dot(ray.d) > 0.0 {
                    -1.0
                } else {
                    1.0
                };
                normal[k] = si.n_shading * facing;
                sem[k] = si.semantic;
                inst[k] = si.instance;
                mask[k] = scene.material_view().mask(&si, ray.d);
            });
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
    let centre = left.centre_dirs();
    let mut occ = vec![0u8; w * h as usize];
    // Bands of rows, tile-ordered like the depth pass: the segments of one
    // packet start at the right camera centre and end on nearby surface points.
    let traced: u64 = occ
        .par_chunks_mut((w * BAND_ROWS).max(1))
        .enumerate()
        .with_max_len(1)
        .map(|(b, occ)| {
            let j0 = b * BAND_ROWS;
            let mut order = Vec::with_capacity(occ.len());
            tile_order(w, occ.len() / w, &mut order);
            let mut rays = Vec::with_capacity(occ.len());
            let mut idx = Vec::with_capacity(occ.len());
            for k in order {
                let (i, j) = (k % w, j0 + k / w);
                let z = left_gt.depth_z[j * w + i];
                if !z.is_finite() {
                    continue;
                }
                let x = i as f64 + 0.5;
                // The stored (rounded) disparity decides, so mask and file agree.
                if x - (disparity_px(f, baseline_m, z) as f64) < 0.0 {
                    occ[k] = 255;
                    continue;
                }
                let p = left.center + centre.dir(i, j) * z;
                let seg = p - c_r;
                rays.push(Ray::segment(
                    c_r.as_vec3(),
                    seg.as_vec3(),
                    OCCLUSION_T_MAX as f32,
                ));
                idx.push((k, seg));
            }
            let mut blocked = vec![false; rays.len()];
            accel.occluded_batch(&rays, &mut blocked);
            // Confirm in f64: the nearest blocker must lie before the
            // tolerance, not just round there in f32. The blocked segments of
            // a band are re-traced together, as packets.
            let (confirm, confirm_idx): (Vec<Ray>, Vec<(usize, DVec3)>) = rays
                .iter()
                .zip(&idx)
                .zip(&blocked)
                .filter(|(_, &b)| b)
                .map(|((r, &k), _)| (*r, k))
                .unzip();
            let mut hits = vec![None; confirm.len()];
            accel.intersect_batch(&confirm, &mut hits);
            for (hit, &(k, seg)) in hits.iter().zip(&confirm_idx) {
                if hit.is_some_and(|hit| exact_t(scene, c_r, seg, &hit) < OCCLUSION_T_MAX) {
                    occ[k] = 255;
                }
            }
            (rays.len() + confirm.len()) as u64
        })
        .sum();
    (occ, traced)
}
