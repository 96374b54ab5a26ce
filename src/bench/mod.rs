//! `parallax bench`: throughput on one scene, everything measured in one run so
//! ratios are meaningful on noisy machines. Figures: BVH build seconds, the
//! ground-truth pass and the path pass in Mrays/s (every closest-hit and any-hit
//! query counts) and Msamples/s, and raw traversal of the same accelerator with
//! no shading: coherent primary rays (single, 8-wide packets) and incoherent
//! secondary rays (closest-hit, any-hit).

pub mod clock;
mod raw;
pub mod scene;

pub use raw::{raw_throughput, Rate, RawThroughput};
pub use scene::{bench_scene_from_obj, ObjCamera};

use std::time::Instant;

use crate::accel::{build_accel, Backend};
use crate::camera::StereoRig;
use crate::render::{render_frame, RenderSettings};
use crate::scene::load::SceneErrorKind;
use crate::scene::{build_scene, LoadedScene, SceneError};
use clock::{Span, Stopwatch};

/// What one bench run measured.
#[derive(Clone, Debug)]
pub struct BenchReport {
    /// Triangles in the scene.
    pub triangles: usize,
    /// Seconds to build the scene from its description (tessellation, transforms).
    pub scene_build_s: f64,
    /// Seconds to build the chosen backend's BVH (all of it).
    pub accel_build_s: f64,
    /// Embree only: seconds of the watertight scene's and the shading twin's commits.
    pub embree_commit_s: Option<[f64; 2]>,
    /// Backend measured.
    pub backend: &'static str,
    /// Ground-truth pass: rays and seconds.
    pub gt_rays: u64,
    /// Wall and CPU seconds of the ground-truth pass.
    pub gt: Span,
    /// Path pass: rays.
    pub path_rays: u64,
    /// Path pass: camera samples.
    pub path_samples: u64,
    /// Wall and CPU seconds of the path pass.
    pub path: Span,
    /// Raw traversal figures on the same accelerator.
    pub raw: RawThroughput,
}

/// Settings of a bench run.
#[derive(Clone, Copy, Debug)]
pub struct BenchSettings {
    /// Samples per pixel of the path pass.
    pub spp: u32,
    /// Maximum path depth.
    pub max_depth: u32,
    /// Backend.
    pub backend: Backend,
    /// Embree: build the non-robust shading twin for the path pass (off: the
    /// path pass traces the watertight scene, as ground truth does).
    pub shading_twin: bool,
}

/// Seconds of GT-pass time the GT figure is measured over, at least.
const MIN_GT_S: f64 = 1.0;

/// Runs every measurement on `loaded` (must be called inside the thread pool to measure).
pub fn run_bench(loaded: &LoadedScene, s: &BenchSettings) -> Result<BenchReport, SceneError> {
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let t = Instant::now();
    let scene = build_scene(loaded, rig.left.center_world)?;
    let scene_build_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let accel = build_bench_accel(s, &scene.accel_geometry())
        .map_err(|e| SceneError::at(&loaded.path, SceneErrorKind::Resource, "", e.to_string()))?;
    let accel_build_s = t.elapsed().as_secs_f64();
    #[cfg(feature = "embree")]
    let embree_commit_s = match &accel {
        crate::accel::AnyAccel::Embree(e) => Some(e.build_seconds()),
        _ => None,
    };
    #[cfg(not(feature = "embree"))]
    let embree_commit_s = None;
    let raw = raw_throughput(&accel, &scene, &rig);
    // GT: every view and baseline of the rig, no path pass.
    let gt_settings = RenderSettings {
        spp: 0,
        max_depth: s.max_depth,
        seed: 1,
        frame: 0,
    };
    // One GT pass takes ~0.25 s: repeat it, as the raw figures repeat theirs,
    // so one slow moment of a noisy machine does not decide the figure.
    let (mut gt_rays, mut gt_s) = (0, 0.0);
    let t = Stopwatch::start();
    while gt_s < MIN_GT_S {
        let gt = render_frame(&scene, &accel, &rig, &gt_settings, &|_, _| {});
        gt_rays += gt.stats.gt_rays;
        gt_s += gt.stats.gt_seconds;
    }
    let gt_span = phase_span(t.stop(), gt_s);
    // Path: the left view only.
    let left_only = StereoRig {
        left: rig.left,
        baselines_m: Vec::new(),
    };
    let path_settings = RenderSettings {
        spp: s.spp,
        ..gt_settings
    };
    let t = Stopwatch::start();
    let path = render_frame(&scene, &accel, &left_only, &path_settings, &|_, _| {});
    let path_span = phase_span(t.stop(), path.stats.path_seconds);
    use crate::accel::Accel;
    Ok(BenchReport {
        triangles: scene.triangle_count(),
        scene_build_s,
        accel_build_s,
        embree_commit_s,
        backend: accel.backend_name(),
        gt_rays,
        gt: gt_span,
        path_rays: path.stats.path_rays,
        path_samples: path.stats.samples,
        path: path_span,
        raw,
    })
}

/// The backend's accelerator, Embree without its twin if so asked.
fn build_bench_accel(
    s: &BenchSettings,
    geo: &crate::accel::AccelGeometry,
) -> Result<crate::accel::AnyAccel, crate::accel::AccelError> {
    #[cfg(feature = "embree")]
    if s.backend == Backend::Embree && !s.shading_twin {
        return crate::accel::EmbreeAccel::build_with(geo, false)
            .map(crate::accel::AnyAccel::Embree);
    }
    build_accel(s.backend, geo)
}

/// The span of a phase of `wall_s` seconds inside a call measured as `call`,
/// assuming the call's CPU share held throughout.
fn phase_span(call: Span, wall_s: f64) -> Span {
    Span {
        wall_s,
        cpu_s: call.cpu_s * wall_s / call.wall_s.max(1e-9),
    }
}

impl BenchReport {
    /// The human-readable report, one figure per line, with ratios. Every rate
    /// is given per wall second and "cpu": per CPU second the phase got, spread
    /// over `threads` (what they would do alone on the machine); ratios use the
    /// CPU-scaled figures.
    pub fn render_text(&self, threads: usize) -> String {
        let gt = Rate::of(self.gt_rays, self.gt);
        let path = Rate::of(self.path_rays, self.path);
        let samples = Rate::of(self.path_samples, self.path);
        let r = &self.raw;
        let line = |name: &str, x: Rate| {
            format!("{name:<20} {:8.2} Mrays/s wall {:8.2} cpu", x.wall, x.cpu)
        };
        let ratio = |a: Rate, b: Rate| a.cpu / b.cpu.max(1e-9);
        [
            format!(
                "scene: {} triangles, {threads} threads, backend {}",
                self.triangles, self.backend
            ),
            format!("scene build          {:8.3} s", self.scene_build_s),
            format!(
                "BVH build            {:8.3} s{}",
                self.accel_build_s,
                self.embree_commit_s.map_or(String::new(), |[w, s]| format!(
                    " (watertight commit {w:.3} s, shading twin {s:.3} s)"
                ))
            ),
            format!(
                "{} ({} rays in {:.3} s)",
                line("GT pass", gt),
                self.gt_rays,
                self.gt.wall_s
            ),
            format!(
                "{} ({:.2} rays/sample)",
                line("path tracing", path),
                self.path_rays as f64 / self.path_samples.max(1) as f64
            ),
            format!(
                "path samples         {:8.3} Msamples/s wall {:8.3} cpu",
                samples.wall, samples.cpu
            ),
            line("raw primary single", r.primary_single_mrays),
            line("raw primary packet8", r.primary_packet_mrays),
            line("raw primary tile4x2", r.primary_tile_mrays),
            line("raw incoherent hit", r.incoherent_closest_mrays),
            line("raw incoherent any", r.incoherent_any_mrays),
            line("raw shading packet8", r.shading_packet_mrays),
            line("raw shading hit", r.shading_closest_mrays),
            line("raw shading any", r.shading_any_mrays),
            format!(
                "ratio GT / raw tile4x2        {:.2}",
                ratio(gt, r.primary_tile_mrays)
            ),
            format!(
                "ratio path / raw incoherent   {:.2} (watertight), {:.2} (shading queries path uses)",
                ratio(path, r.incoherent_closest_mrays),
                ratio(path, r.shading_closest_mrays)
            ),
        ]
        .join("\n")
    }
}
