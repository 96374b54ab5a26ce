//! The path pass of one view: tiles of pixels traced in parallel, camera
//! rays in packets, each pixel's samples summed in sample order, assembled
//! in raster order with the parts the denoiser treats; optionally a pilot
//! pass first and the budget's rest where it saw error (`adaptive.rs`).

use rayon::prelude::*;

use crate::accel::{Accel, Hit, Ray};
use crate::denoise::ViewInputs;
use crate::film::Film;
use crate::integrator::path::{PathStart, PixelSum};
use crate::integrator::{luminance, PathContext, RenderCamera};
use crate::sampler::{SampleStream, StreamKey};

use super::adaptive::{self, Moments};

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

/// One pixel's running sums: radiance and the denoiser's parts, and the
/// luminance moments the adaptive allocation reads (of the whole radiance,
/// and of the part the image filters leave as traced).
#[derive(Clone, Copy, Debug, Default)]
struct PixelAcc {
    sum: PixelSum,
    /// Samples taken (dropped non-finite ones included).
    n: u32,
    total: Moments,
    unfiltered: Moments,
}

/// One tile's pixels in raster order, and the work their passes did.
struct TileAcc {
    px: Vec<PixelAcc>,
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
    /// Camera samples taken (`pixels × spp`, adaptive or not).
    pub samples: u64,
    /// Samples dropped as non-finite.
    pub non_finite: u64,
    /// Its first visible surfaces' albedo and normal.
    pub aov: super::AovImages,
}

/// The view's tiles: `TILE_PX`² squares in raster order of tiles.
#[derive(Clone, Copy)]
struct Tiling {
    w: u32,
    h: u32,
    tiles_x: u32,
}

impl Tiling {
    fn new(w: u32, h: u32) -> Tiling {
        Tiling {
            w,
            h,
            tiles_x: w.div_ceil(TILE_PX),
        }
    }

    fn count(&self) -> u32 {
        self.tiles_x * self.h.div_ceil(TILE_PX)
    }

    /// Tile `t`'s pixel columns and rows.
    fn bounds(&self, t: u32) -> (std::ops::Range<u32>, std::ops::Range<u32>) {
        let (x0, y0) = ((t % self.tiles_x) * TILE_PX, (t / self.tiles_x) * TILE_PX);
        (
            x0..(x0 + TILE_PX).min(self.w),
            y0..(y0 + TILE_PX).min(self.h),
        )
    }

    /// Raster index of every pixel of tile `t`, in the tile's raster order.
    fn pixels(&self, t: u32) -> impl Iterator<Item = usize> {
        let (xs, ys) = self.bounds(t);
        let w = self.w as usize;
        ys.flat_map(move |j| xs.clone().map(move |i| j as usize * w + i as usize))
    }
}

/// Path-traces one view; pixels are independent, so any thread count gives
/// the same film.
///
/// Work is split into `TILE_PX`² tiles, assembled in raster order after.
/// The camera rays of a few neighbouring pixels of one tile row go through
/// the accelerator's batch query (Embree: coherent 8-wide packets); every
/// later bounce is traced ray by ray. A pixel's samples are summed in sample
/// order either way.
///
/// `adaptive` (and `spp` ≥ [`adaptive::MIN_ADAPTIVE_SPP`]): the same budget
/// of `pixels × spp` samples, a pilot pass then the rest where the pilot
/// saw display error (`adaptive.rs`); each pixel's samples continue its
/// sample sequence. Otherwise every pixel takes `spp` samples.
pub(super) fn render_view<A: Accel>(
    ctx: &PathContext<'_, A>,
    cam: &RenderCamera,
    key: StreamKey,
    spp: u32,
    adaptive: bool,
) -> ViewRender {
    let (w, h) = (cam.intrinsics.width, cam.intrinsics.height);
    let tiling = Tiling::new(w, h);
    let keep_filter_inputs = ctx.scene.filter_inscatter || ctx.scene.filter_indirect;
    let n_px = w as usize * h as usize;
    let adaptive = adaptive && spp >= adaptive::MIN_ADAPTIVE_SPP;
    let first = if adaptive {
        adaptive::pilot_spp(spp)
    } else {
        spp
    };
    let mut tiles: Vec<TileAcc> = (0..tiling.count())
        .map(|t| TileAcc {
            px: vec![PixelAcc::default(); tiling.pixels(t).count()],
            rays: 0,
            non_finite: 0,
        })
        .collect();
    let mut counts = vec![first; n_px];
    // Only the pilot's moments are read (by `allocate`).
    trace_pass(ctx, cam, key, tiling, &counts, adaptive, &mut tiles);
    if adaptive {
        counts = allocate(&tiling, &tiles, spp, keep_filter_inputs);
        trace_pass(ctx, cam, key, tiling, &counts, false, &mut tiles);
    }
    let mut film = Film::new(w as usize, h as usize);
    let mut denoise = keep_filter_inputs.then(|| ViewInputs::new(w as usize, h as usize));
    let mut aov = super::AovImages::new(n_px);
    for (t, tile) in tiles.iter().enumerate() {
        for (k, acc) in tiling.pixels(t as u32).zip(&tile.px) {
            let n = acc.n as f32;
            film.rgb[k] = acc.sum.l / n;
            aov.albedo[k] = acc.sum.aov.albedo / n;
            aov.normal[k] = acc.sum.aov.normal.normalize_or_zero();
            if let Some(inputs) = denoise.as_mut() {
                inputs.set_mean(k, &acc.sum.denoise, n);
            }
        }
    }
    ViewRender {
        film,
        denoise,
        rays: tiles.iter().map(|t| t.rays).sum(),
        samples: counts.iter().map(|&c| c as u64).sum(),
        non_finite: tiles.iter().map(|t| t.non_finite).sum(),
        aov,
    }
}

/// Sample counts per pixel (raster order) for the whole budget from the
/// pilot pass summed in `tiles`: the error of `adaptive::display_sd` at
/// the pilot film's exposure, of the radiance the filters leave as traced
/// (plus a share of the filtered part's, which the filters reduce but do
/// not remove), smoothed, then [`adaptive::allocate`].
fn allocate(tiling: &Tiling, tiles: &[TileAcc], spp: u32, filtered: bool) -> Vec<u32> {
    let (w, h) = (tiling.w as usize, tiling.h as usize);
    let mut pilot = Film::new(w, h);
    let mut moments = vec![(Moments::default(), Moments::default()); w * h];
    for (t, tile) in tiles.iter().enumerate() {
        for (k, acc) in tiling.pixels(t as u32).zip(&tile.px) {
            pilot.rgb[k] = acc.sum.l / acc.n as f32;
            moments[k] = (acc.total, acc.unfiltered);
        }
    }
    let exposure = crate::film::frame_exposure(&pilot);
    let err: Vec<f32> = moments
        .iter()
        .map(|(total, unfiltered)| {
            let (m, sd_total) = total.mean_sd();
            let sd = if filtered {
                let (_, sd_u) = unfiltered.mean_sd();
                (sd_u * sd_u + FILTERED_SHARE * sd_total * sd_total).sqrt()
            } else {
                sd_total
            };
            adaptive::display_sd(m, sd, exposure)
        })
        .collect();
    let err = adaptive::smooth_3x3(&err, w, h);
    let budget = (w * h) as u64 * spp as u64;
    adaptive::allocate(&err, budget, adaptive::min_spp(spp), adaptive::max_spp(spp))
}

/// Weight of the filtered parts' sample variance in the allocation's error:
/// the image filters average it over many pixels.
const FILTERED_SHARE: f32 = 1.0 / 16.0;

/// Traces, for every pixel, its samples `acc.n .. counts[k]` (continuing
/// its sequence) into the tiles' sums, tiles in parallel; with `moments`,
/// also the luminance moments the adaptive allocation reads.
fn trace_pass<A: Accel>(
    ctx: &PathContext<'_, A>,
    cam: &RenderCamera,
    key: StreamKey,
    tiling: Tiling,
    counts: &[u32],
    moments: bool,
    tiles: &mut [TileAcc],
) {
    tiles
        .par_iter_mut()
        .enumerate()
        .with_max_len(1) // tiles differ in cost (sky vs street): balance per tile
        .for_each_init(ChunkScratch::default, |scratch, (t, tile)| {
            let (xs, ys) = tiling.bounds(t as u32);
            let tw = xs.len();
            for (row, j) in ys.enumerate() {
                let row_start = j as usize * tiling.w as usize;
                for i0 in xs.clone().step_by(PACKET_PIXELS as usize) {
                    let i1 = (i0 + PACKET_PIXELS).min(xs.end);
                    let at = row * tw + (i0 - xs.start) as usize;
                    let px = &mut tile.px[at..at + (i1 - i0) as usize];
                    let ends = &counts[row_start + i0 as usize..row_start + i1 as usize];
                    let (rays, non_finite) =
                        render_chunk(ctx, cam, key, (i0, j), ends, moments, scratch, px);
                    tile.rays += rays;
                    tile.non_finite += non_finite;
                }
            }
        });
}

/// Path-traces pixels `i0 .. i0 + px.len()` of row `j`, each from its
/// next sample `px[p].n` up to `ends[p]` (camera rays as one batch), adding
/// the samples to `px` in sample order (and their luminance moments with
/// `moments`). Returns the rays traced and the samples dropped as
/// non-finite.
#[allow(clippy::too_many_arguments)]
fn render_chunk<A: Accel>(
    ctx: &PathContext<'_, A>,
    cam: &RenderCamera,
    key: StreamKey,
    (i0, j): (u32, u32),
    ends: &[u32],
    moments: bool,
    scratch: &mut ChunkScratch,
    px: &mut [PixelAcc],
) -> (u64, u64) {
    let (mut rays, mut non_finite) = (0u64, 0u64);
    scratch.rays.clear();
    scratch.streams.clear();
    for (p, (acc, &end)) in px.iter().zip(ends).enumerate() {
        let i = i0 + p as u32;
        for s in acc.n..end {
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
            .push(ctx.start_path(*ray, *hit, cam.cone(ray.d), stream, &mut rays));
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
    let mut streams = scratch.streams.iter_mut();
    for (acc, &end) in px.iter_mut().zip(ends) {
        let taken = end.saturating_sub(acc.n) as usize;
        // The pixel's streams lead the zip: it must not pull a start too many.
        for (stream, start) in streams.by_ref().take(taken).zip(starts.by_ref()) {
            let li = ctx.finish_path(start, stream, &mut rays);
            // A non-finite sample would poison the pixel: drop it, counted.
            if li.l.is_finite() {
                acc.sum.add(&li);
                if moments {
                    acc.total.add(luminance(li.l));
                    let d = &li.denoise;
                    acc.unfiltered
                        .add(luminance(li.l - d.l_fog - d.l_surf - d.l_direct - d.l_refl));
                }
            } else {
                non_finite += 1;
            }
        }
        acc.n = acc.n.max(end);
    }
    (rays, non_finite)
}
