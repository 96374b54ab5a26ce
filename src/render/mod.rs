//! `render_frame`: one frame, every view, as data (DESIGN.md "One frame, as
//! data"; modelled on pbrt-v4's `RenderCPU` as one linear set-up).
//!
//! The geometry is built once and shared by every view. The ground-truth pass
//! runs first and independently of the path pass, so nothing the path pass
//! does (jitter, noise) can touch it. Views: 0 = left, 1 + b = right camera of
//! baseline b; each has its own sample stream.

use std::time::Instant;

use glam::Vec3;
use rayon::prelude::*;

use crate::accel::{Accel, ShadingAccel};
use crate::camera::StereoRig;
use crate::film::{Film, FogLayer};
use crate::integrator::gt::{occlusion_mask, view_gt, ViewGt};
use crate::integrator::path::{PathContext, PathStart, PixelSum};
use crate::integrator::rain;
use crate::integrator::RenderCamera;
use crate::light::LightSet;
use crate::sampler::{SampleStream, StreamKey};
use crate::scene::Scene;
use crate::scene::SurfaceTable;

/// What to render.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RenderSettings {
    /// Samples per pixel per view (0 skips the path pass: ground truth only).
    pub spp: u32,
    /// Maximum scattering events per path.
    pub max_depth: u32,
    /// Seed of every stream.
    pub seed: u64,
    /// Frame index (part of every stream key).
    pub frame: u32,
}

/// Ground truth for one baseline.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BaselineGt {
    /// Baseline in metres.
    pub baseline_m: f64,
    /// Left-view disparity f·B/Z (px).
    pub disparity_left: Vec<f32>,
    /// Right-view depth_z (m, +inf sky).
    pub depth_right: Vec<f32>,
    /// Right-view disparity (px): a right pixel at x lands at x + d in the left image.
    pub disparity_right: Vec<f32>,
    /// Left-view occlusion mask, 255 = occluded.
    pub occlusion: Vec<u8>,
}

/// Everything one frame produces.
#[derive(Clone, Debug)]
pub struct FrameOutput {
    /// Left-view ground truth.
    pub left: ViewGt,
    /// Per-baseline ground truth, in rig order.
    pub baselines: Vec<BaselineGt>,
    /// Linear radiance per view (empty when spp = 0).
    pub images: Vec<Film>,
    /// Exposure scale computed from the left view, shared by all views.
    pub exposure_scale: f32,
    /// Statistics.
    pub stats: RenderStats,
}

/// Work done for a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    /// Rays traced by the ground-truth pass (primary + occlusion).
    pub gt_rays: u64,
    /// Rays traced by the path pass (closest-hit + any-hit).
    pub path_rays: u64,
    /// Camera samples taken by the path pass.
    pub samples: u64,
    /// Camera samples whose radiance came out NaN or infinite and were
    /// dropped from their pixel's mean (a renderer bug if ever non-zero).
    pub non_finite_samples: u64,
    /// Seconds in the ground-truth pass.
    pub gt_seconds: f64,
    /// Seconds in the path pass.
    pub path_seconds: f64,
}

impl RenderStats {
    /// A warning when samples were dropped as non-finite (None otherwise).
    pub fn non_finite_warning(&self) -> Option<String> {
        (self.non_finite_samples > 0).then(|| {
            format!(
                "warning: {} of {} samples were NaN or infinite and left out of their pixels \
                 (a renderer bug: please report the scene)",
                self.non_finite_samples, self.samples
            )
        })
    }
}

/// Renders one frame of `scene` (built around the rig's left camera) from every view.
pub fn render_frame(
    scene: &Scene,
    accel: &impl Accel,
    rig: &StereoRig,
    settings: &RenderSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> FrameOutput {
    let cams: Vec<RenderCamera> = rig
        .views()
        .iter()
        .map(|c| RenderCamera::new(c, scene.origin_world))
        .collect();
    let f_px = rig.left.intrinsics.f_px;
    let n_views = cams.len();
    let mut stats = RenderStats::default();

    let t0 = Instant::now();
    // One rain field per frame: every view sees its streaks (opacity per
    // pixel, composited after the path pass) and the left mask marks them.
    let rain = crate::integrator::frame_rain(scene, settings.seed, settings.frame, f_px);
    let mut rain_alpha = Vec::new();
    let mut left = view_gt(scene, accel, &cams[0], true);
    if let Some(rain) = &rain {
        let alpha = rain::rain_opacity(scene, rain, &cams[0], &left.depth_z);
        rain::mark_rain(&mut left.mask, &alpha);
        rain_alpha.push(alpha);
    }
    stats.gt_rays += left.depth_z.len() as u64;
    let mut baselines = Vec::with_capacity(rig.baselines_m.len());
    for (b, &baseline_m) in rig.baselines_m.iter().enumerate() {
        let right = view_gt(scene, accel, &cams[1 + b], false);
        // Right views need rain only to composite their images.
        if let Some(rain) = rain.as_ref().filter(|_| settings.spp > 0) {
            rain_alpha.push(rain::rain_opacity(
                scene,
                rain,
                &cams[1 + b],
                &right.depth_z,
            ));
        }
        let (occlusion, occ_rays) =
            occlusion_mask(scene, accel, &cams[0], &cams[1 + b], &left, baseline_m);
        stats.gt_rays += right.depth_z.len() as u64 + occ_rays;
        baselines.push(BaselineGt {
            baseline_m,
            disparity_left: left.disparity(f_px, baseline_m),
            depth_right: right.depth_z_f32(),
            disparity_right: right.disparity(f_px, baseline_m),
            occlusion,
        });
    }
    stats.gt_seconds = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let mut images = Vec::new();
    if settings.spp > 0 {
        let lights = LightSet::build(scene);
        let surfaces = SurfaceTable::build(scene);
        // Paths trace on the backend's fast, not necessarily watertight
        // variant; ground truth above stayed on the watertight one.
        let shading = ShadingAccel(accel);
        let ctx = PathContext::new(scene, &shading, &lights, &surfaces, settings.max_depth);
        for (view, cam) in cams.iter().enumerate() {
            progress(view, n_views);
            let key = StreamKey {
                seed: settings.seed,
                frame: settings.frame,
                view: view as u32,
            };
            let ViewRender {
                mut film,
                fog,
                rays,
                non_finite,
            } = render_view(&ctx, cam, key, settings.spp);
            // Fog light, or indirect light on first surfaces, filtered per
            // view, guided by this view's exact pixel-centre depth (left, or
            // baseline b's right view).
            if let Some(fog) = fog {
                let depth_z = match view {
                    0 => left.depth_z_f32(),
                    v => baselines[v - 1].depth_right.clone(),
                };
                crate::integrator::volpath::filter_view(scene, cam, &depth_z, &mut film, &fog);
            }
            stats.path_rays += rays;
            stats.non_finite_samples += non_finite;
            stats.samples +=
                cam.intrinsics.width as u64 * cam.intrinsics.height as u64 * settings.spp as u64;
            images.push(film);
        }
        progress(n_views, n_views);
        if let Some(left_film) = images.first().filter(|_| !rain_alpha.is_empty()) {
            let l_drop = rain::drop_radiance(left_film);
            for (film, alpha) in images.iter_mut().zip(&rain_alpha) {
                rain::composite(film, alpha, l_drop);
            }
        }
    }
    stats.path_seconds = t1.elapsed().as_secs_f64();
    let exposure_scale = images.first().map_or(1.0, crate::film::frame_exposure);
    FrameOutput {
        left,
        baselines,
        images,
        exposure_scale,
        stats,
    }
}

/// Pixels per chunk of camera rays traced together as packets (with spp
/// samples each, the chunk fills `PACKET_PIXELS · spp / 8` 8-wide packets).
const PACKET_PIXELS: u32 = 8;

/// Side of the square pixel tiles scheduled as units of work (a multiple of
/// `PACKET_PIXELS`, so chunks never straddle tiles): neighbouring paths then
/// run back to back on one thread and their secondary rays find the same
/// BVH nodes in cache, which rows of the full width would evict.
const TILE_PX: u32 = 16;

/// Per-thread buffers for one chunk of camera rays.
#[derive(Default)]
struct ChunkScratch {
    rays: Vec<crate::accel::Ray>,
    hits: Vec<Option<crate::accel::Hit>>,
    streams: Vec<SampleStream>,
    starts: Vec<PathStart>,
    shadow_rays: Vec<crate::accel::Ray>,
    shadow_slots: Vec<(u32, u8)>,
    occluded: Vec<bool>,
}

/// Per pixel, the fog filter's inputs: (mean l_fog, mean first-segment
/// opacity, mean l_surf, mean rho, share of samples split behind delta
/// scatters).
type FogMeans = (Vec3, f32, Vec3, Vec3, f32);

/// One tile's pixel means in raster order: the radiance, and the image
/// filter's inputs (`Some` only where the scene filters fog or indirect
/// light). Those are 44 of a pixel's 56 bytes (63 MB a view at 1600×900,
/// and as much again in the view's `FogLayer`).
struct TileMeans {
    rgb: Vec<Vec3>,
    fog: Option<Vec<FogMeans>>,
    /// Rays traced.
    rays: u64,
    /// Samples dropped as non-finite.
    non_finite: u64,
}

/// One path-traced view.
struct ViewRender {
    film: Film,
    /// The parts of its radiance the image filter treats (`None` where the
    /// scene filters neither fog nor indirect light).
    fog: Option<FogLayer>,
    /// Rays traced.
    rays: u64,
    /// Samples dropped as non-finite.
    non_finite: u64,
}

/// Path-traces one view; pixels are independent, so any thread count gives
/// the same film.
///
/// Work is split into `TILE_PX`² tiles, assembled in raster order after.
/// The camera rays of a few neighbouring pixels of one tile row go through
/// the accelerator's batch query (Embree: coherent 8-wide packets); every
/// later bounce is traced ray by ray. A pixel's samples are summed in sample
/// order either way.
fn render_view<A: Accel>(
    ctx: &PathContext<'_, A>,
    cam: &RenderCamera,
    key: StreamKey,
    spp: u32,
) -> ViewRender {
    let (w, h) = (cam.intrinsics.width, cam.intrinsics.height);
    let tiles_x = w.div_ceil(TILE_PX);
    let n_tiles = tiles_x * h.div_ceil(TILE_PX);
    let keep_filter_inputs = ctx.scene.filter_inscatter || ctx.scene.filter_indirect;
    let tiles: Vec<TileMeans> = (0..n_tiles)
        .into_par_iter()
        .with_max_len(1) // tiles differ in cost (sky vs street): balance per tile
        .map_init(ChunkScratch::default, |scratch, t| {
            let (x0, y0) = ((t % tiles_x) * TILE_PX, (t / tiles_x) * TILE_PX);
            let (x1, y1) = ((x0 + TILE_PX).min(w), (y0 + TILE_PX).min(h));
            let n = ((x1 - x0) * (y1 - y0)) as usize;
            let mut tile = TileMeans {
                rgb: Vec::with_capacity(n),
                fog: keep_filter_inputs.then(|| Vec::with_capacity(n)),
                rays: 0,
                non_finite: 0,
            };
            for j in y0..y1 {
                for i0 in (x0..x1).step_by(PACKET_PIXELS as usize) {
                    let i1 = (i0 + PACKET_PIXELS).min(x1);
                    render_chunk(ctx, cam, key, spp, (i0..i1, j), scratch, &mut tile);
                }
            }
            tile
        })
        .collect();
    let rays = tiles.iter().map(|t| t.rays).sum();
    let non_finite = tiles.iter().map(|t| t.non_finite).sum();
    let mut film = Film::new(w as usize, h as usize);
    let mut fog = keep_filter_inputs.then(|| FogLayer::new(w as usize, h as usize));
    for (t, tile) in tiles.iter().enumerate() {
        let t = t as u32;
        let (x0, y0) = ((t % tiles_x) * TILE_PX, (t / tiles_x) * TILE_PX);
        let tw = ((x0 + TILE_PX).min(w) - x0) as usize;
        for (row, px) in tile.rgb.chunks(tw).enumerate() {
            let start = (y0 as usize + row) * w as usize + x0 as usize;
            film.rgb[start..start + tw].copy_from_slice(px);
            let (Some(fog), Some(means)) = (fog.as_mut(), &tile.fog) else {
                continue;
            };
            let means = &means[row * tw..(row + 1) * tw];
            for (k, &(l_fog, opacity, l_sf, rho, behind)) in (start..start + tw).zip(means) {
                (fog.l_fog[k], fog.opacity[k]) = (l_fog, opacity);
                (fog.l_surf[k], fog.rho[k]) = (l_sf, rho);
                fog.behind_delta[k] = behind;
            }
        }
    }
    ViewRender {
        film,
        fog,
        rays,
        non_finite,
    }
}

/// Path-traces pixels `i` of row `j` (spp samples each, camera rays as one
/// batch) and appends their means to `out`, with the rays traced.
fn render_chunk<A: Accel>(
    ctx: &PathContext<'_, A>,
    cam: &RenderCamera,
    key: StreamKey,
    spp: u32,
    (i, j): (std::ops::Range<u32>, u32),
    scratch: &mut ChunkScratch,
    out: &mut TileMeans,
) {
    scratch.rays.clear();
    scratch.streams.clear();
    for i in i {
        for s in 0..spp {
            let mut stream = SampleStream::new(key, i, j, s);
            scratch.rays.push(cam.jittered_ray(i, j, &mut stream));
            scratch.streams.push(stream);
        }
    }
    scratch.hits.clear();
    scratch.hits.resize(scratch.rays.len(), None);
    ctx.accel.intersect_batch(&scratch.rays, &mut scratch.hits);
    // Start every first hit's record load now, so the misses overlap.
    for hit in scratch.hits.iter().flatten() {
        ctx.surfaces.prefetch(ctx.scene, hit);
    }
    // Every path's first vertex; then the chunk's coherent shadow rays (the
    // sun's, from neighbouring points) in packets; then each path goes on.
    scratch.starts.clear();
    for ((ray, hit), stream) in scratch
        .rays
        .iter()
        .zip(&scratch.hits)
        .zip(&mut scratch.streams)
    {
        scratch
            .starts
            .push(ctx.start_path(*ray, *hit, stream, &mut out.rays));
    }
    scratch.shadow_rays.clear();
    scratch.shadow_slots.clear();
    for (p, start) in scratch.starts.iter().enumerate() {
        start.collect_coherent(p, &mut scratch.shadow_rays, &mut scratch.shadow_slots);
    }
    scratch.occluded.clear();
    scratch.occluded.resize(scratch.shadow_rays.len(), false);
    ctx.accel
        .occluded_batch(&scratch.shadow_rays, &mut scratch.occluded);
    for (&(p, item), &occluded) in scratch.shadow_slots.iter().zip(&scratch.occluded) {
        scratch.starts[p as usize].set_occluded(item, occluded);
    }
    let mut starts = scratch.starts.drain(..);
    for stream_px in scratch.streams.chunks_mut(spp as usize) {
        let mut sum = PixelSum::default();
        // The pixel's streams lead the zip: it must not pull a start too many.
        for (stream, start) in stream_px.iter_mut().zip(starts.by_ref()) {
            let li = ctx.finish_path(start, stream, &mut out.rays);
            // A non-finite sample would poison the pixel: drop it, counted.
            if li.l.is_finite() {
                sum.add(&li);
            } else {
                out.non_finite += 1;
            }
        }
        let n = spp as f32;
        out.rgb.push(sum.l / n);
        if let Some(means) = out.fog.as_mut() {
            let behind = sum.behind_delta as f32 / n;
            means.push((
                sum.l_fog / n,
                sum.opacity / n,
                sum.l_surf / n,
                sum.rho / n,
                behind,
            ));
        }
    }
}
