//! Raw traversal throughput of an accelerator with no shading at all: the
//! ceiling the renderer is measured against. Incoherent rays start at the
//! primary hit points and head in uniformly distributed directions.

use glam::Vec3;
use rayon::prelude::*;

use super::clock::{Span, Stopwatch};
use crate::accel::{Accel, Hit, Ray, ShadingAccel};
use crate::camera::StereoRig;
use crate::integrator::RenderCamera;
use crate::sampler::mix64;
use crate::scene::surface_interaction;
use crate::scene::Scene;

/// Raw traversal rates, Mrays/s: the watertight queries ground truth uses,
/// and the shading queries the path pass uses (the same numbers unless the
/// backend keeps a faster twin, see [`crate::accel::Accel::intersect_shading`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct RawThroughput {
    /// Primary rays one at a time.
    pub primary_single_mrays: Rate,
    /// Primary rays in 8-wide packets along rows (8×1 pixels).
    pub primary_packet_mrays: Rate,
    /// Primary rays in 8-wide packets over 4×2 pixel tiles (the GT pass's shape).
    pub primary_tile_mrays: Rate,
    /// Incoherent closest-hit rays.
    pub incoherent_closest_mrays: Rate,
    /// Incoherent any-hit rays.
    pub incoherent_any_mrays: Rate,
    /// Shading queries: primary rays in 8-wide packets.
    pub shading_packet_mrays: Rate,
    /// Shading queries: incoherent closest-hit rays.
    pub shading_closest_mrays: Rate,
    /// Shading queries: incoherent any-hit rays.
    pub shading_any_mrays: Rate,
}

/// One throughput figure, Mrays/s: per wall second, and per CPU second spread
/// over the pool's threads (see [`super::clock`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Rate {
    /// Per wall-clock second.
    pub wall: f64,
    /// As if the pool's threads had the machine to themselves.
    pub cpu: f64,
}

impl Rate {
    /// The rate of `n` rays over `span` on a pool of `threads` threads (the
    /// pool that ran the phase: outside it rayon reports the global pool).
    pub fn of(n: u64, span: Span, threads: usize) -> Rate {
        Rate {
            wall: span.wall_rate(n),
            cpu: span.cpu_rate(n, threads),
        }
    }
}

// Every parallel loop here hands out one row, tile or chunk per job
// (`with_max_len(1)`), as the C baseline's atomic counter does: rows differ
// in cost (sky vs street), and rayon's default split into a few large pieces
// per thread left one thread idle for a quarter of each pass.

/// Wall seconds each raw figure runs for at least: one pass over a frame's
/// rays takes ~0.1 s, too short for the 10 ms CPU clock to be read.
const MIN_RAW_S: f64 = 0.5;

/// The rate of `rays` per call of `f`, calling it until `MIN_RAW_S` passed.
fn rate(rays: usize, mut f: impl FnMut()) -> Rate {
    let t = Stopwatch::start();
    let mut passes = 0u64;
    loop {
        f();
        passes += 1;
        let span = t.stop();
        if span.wall_s >= MIN_RAW_S {
            return Rate::of(rays as u64 * passes, span, rayon::current_num_threads());
        }
    }
}

/// A uniform direction from the bits of a hash.
fn unit_from_hash(h: u64) -> Vec3 {
    let u = glam::Vec2::new(
        (h >> 40) as f32 / (1u64 << 24) as f32,
        ((h >> 16) & 0xff_ffff) as f32 / (1u64 << 24) as f32,
    );
    shaders_cpu::sampling::sample_uniform_sphere(u)
}

/// Measures raw rates on the left camera's primary rays and their bounces.
pub fn raw_throughput(accel: &impl Accel, scene: &Scene, rig: &StereoRig) -> RawThroughput {
    let cam = RenderCamera::new(&rig.left, scene.origin_world);
    let (w, h) = (
        cam.intrinsics.width as usize,
        cam.intrinsics.height as usize,
    );
    let o = cam.center_f32();
    let rows: Vec<Vec<Ray>> = (0..h)
        .map(|j| {
            (0..w)
                .map(|i| Ray::new(o, cam.dir(i as f64 + 0.5, j as f64 + 0.5).as_vec3()))
                .collect()
        })
        .collect();
    let n = w * h;
    let mut out = RawThroughput {
        primary_single_mrays: rate(n, || {
            rows.par_iter().with_max_len(1).for_each(|row| {
                for r in row {
                    std::hint::black_box(accel.intersect(r));
                }
            })
        }),
        ..Default::default()
    };
    let mut hits: Vec<Vec<Option<Hit>>> = vec![vec![None; w]; h];
    out.primary_packet_mrays = rate(n, || {
        rows.par_iter()
            .zip(hits.par_iter_mut())
            .with_max_len(1)
            .for_each(|(row, hit)| accel.intersect_batch(row, hit))
    });
    // The same rays regrouped into 4×2 tiles (pairs of rows, 4 columns at a time).
    let tiles: Vec<Vec<Ray>> = rows
        .chunks(2)
        .map(|band| {
            (0..w)
                .step_by(4)
                .flat_map(|i0| band.iter().flat_map(move |row| &row[i0..(i0 + 4).min(w)]))
                .copied()
                .collect()
        })
        .collect();
    let mut tile_hits: Vec<Vec<Option<Hit>>> = tiles.iter().map(|t| vec![None; t.len()]).collect();
    out.primary_tile_mrays = rate(n, || {
        tiles
            .par_iter()
            .zip(tile_hits.par_iter_mut())
            .with_max_len(1)
            .for_each(|(tile, hit)| accel.intersect_batch(tile, hit))
    });
    let secondary: Vec<Ray> = rows
        .iter()
        .zip(&hits)
        .flat_map(|(row, hit)| row.iter().zip(hit))
        .enumerate()
        .filter_map(|(k, (r, h))| {
            let si = surface_interaction(scene, r, h.as_ref()?);
            Some(si.spawn_ray(unit_from_hash(mix64(k as u64))))
        })
        .collect();
    if secondary.is_empty() {
        return out;
    }
    out.shading_packet_mrays = rate(n, || {
        rows.par_iter()
            .zip(hits.par_iter_mut())
            .with_max_len(1)
            .for_each(|(row, hit)| accel.intersect_batch_shading(row, hit))
    });
    // Alternate watertight and shading runs so load changes hit both alike.
    let shading = ShadingAccel(accel);
    out.incoherent_closest_mrays = incoherent_closest(accel, &secondary);
    out.shading_closest_mrays = incoherent_closest(&shading, &secondary);
    out.incoherent_any_mrays = incoherent_any(accel, &secondary);
    out.shading_any_mrays = incoherent_any(&shading, &secondary);
    out
}

fn incoherent_closest(accel: &impl Accel, rays: &[Ray]) -> Rate {
    rate(rays.len(), || {
        rays.par_chunks(1024).with_max_len(1).for_each(|c| {
            for r in c {
                std::hint::black_box(accel.intersect(r));
            }
        })
    })
}

fn incoherent_any(accel: &impl Accel, rays: &[Ray]) -> Rate {
    rate(rays.len(), || {
        rays.par_chunks(1024).with_max_len(1).for_each(|c| {
            for r in c {
                std::hint::black_box(accel.occluded(r));
            }
        })
    })
}
