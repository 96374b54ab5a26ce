//! The path pass of one view: tiles of pixels traced in parallel, camera
//! rays in packets, each pixel's samples summed in sample order, assembled
//! in raster order with the parts the denoiser treats.

use glam::Vec3;
use rayon::prelude::*;

use crate::accel::{Accel, Hit, Ray};
use crate::denoise::ViewInputs;
use crate::film::Film;
use crate::integrator::path::{PathStart, PixelSum};
use crate::integrator::{DenoiseSum, PathContext, RenderCamera};
use crate::sampler::{SampleStream, StreamKey};

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
    rays: Vec<Ray>,
    hits: Vec<Option<Hit>>,
    streams: Vec<SampleStream>,
    starts: Vec<PathStart>,
    shadow_rays: Vec<Ray>,
    shadow_slots: Vec<(u32, u8)>,
    occluded: Vec<bool>,
}

/// One tile's pixels in raster order: the mean radiance, and the sums of
/// the parts the denoiser treats (`Some` only where the scene filters fog
/// or indirect light). Those are 44 of a pixel's 56 bytes (63 MB a view at
/// 1600×900, and as much again in the view's `ViewInputs`).
struct TileMeans {
    rgb: Vec<Vec3>,
    denoise: Option<Vec<DenoiseSum>>,
    /// Rays traced.
    rays: u64,
    /// Samples dropped as non-finite.
    non_finite: u64,
}

/// One path-traced view.
pub(super) struct ViewRender {
    /// Its radiance, not yet denoised.
    pub film: Film,
    /// The parts of its radiance the denoiser treats (`None` where the
    /// scene filters neither fog nor indirect light).
    pub denoise: Option<ViewInputs>,
    /// Rays traced.
    pub rays: u64,
    /// Samples dropped as non-finite.
    pub non_finite: u64,
}

/// Path-traces one view; pixels are independent, so any thread count gives
/// the same film.
///
/// Work is split into `TILE_PX`² tiles, assembled in raster order after.
/// The camera rays of a few neighbouring pixels of one tile row go through
/// the accelerator's batch query (Embree: coherent 8-wide packets); every
/// later bounce is traced ray by ray. A pixel's samples are summed in sample
/// order either way.
pub(super) fn render_view<A: Accel>(
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
                denoise: keep_filter_inputs.then(|| Vec::with_capacity(n)),
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
    let mut denoise = keep_filter_inputs.then(|| ViewInputs::new(w as usize, h as usize));
    let n_spp = spp as f32;
    for (t, tile) in tiles.iter().enumerate() {
        let t = t as u32;
        let (x0, y0) = ((t % tiles_x) * TILE_PX, (t / tiles_x) * TILE_PX);
        let tw = ((x0 + TILE_PX).min(w) - x0) as usize;
        for (row, px) in tile.rgb.chunks(tw).enumerate() {
            let start = (y0 as usize + row) * w as usize + x0 as usize;
            film.rgb[start..start + tw].copy_from_slice(px);
            let (Some(inputs), Some(sums)) = (denoise.as_mut(), &tile.denoise) else {
                continue;
            };
            for (k, sum) in (start..start + tw).zip(&sums[row * tw..(row + 1) * tw]) {
                inputs.set_mean(k, sum, n_spp);
            }
        }
    }
    ViewRender {
        film,
        denoise,
        rays,
        non_finite,
    }
}

/// Path-traces pixels `i` of row `j` (spp samples each, camera rays as one
/// batch) and appends their mean radiance and denoiser sums to `out`, with
/// the rays traced.
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
        if let Some(sums) = out.denoise.as_mut() {
            sums.push(sum.denoise);
        }
    }
}
