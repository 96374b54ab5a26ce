//! `parallax bench`: throughput on one scene, everything measured in one run so
//! ratios are meaningful on noisy machines. Figures: BVH build seconds, the
//! ground-truth pass and the path pass in Mrays/s (every closest-hit and any-hit
//! query counts) and Msamples/s, and raw traversal of the same accelerator with
//! no shading: coherent primary rays (single, 8-wide packets) and incoherent
//! secondary rays (closest-hit, any-hit).

mod raw;
pub mod scene;

pub use raw::{raw_throughput, RawThroughput};
pub use scene::{bench_scene_from_obj, ObjCamera};

use std::time::Instant;

use crate::accel::{build_accel, Backend};
use crate::camera::StereoRig;
use crate::render::{render_frame, RenderSettings};
use crate::scene::load::SceneErrorKind;
use crate::scene::{build_scene, LoadedScene, SceneError};

/// What one bench run measured.
#[derive(Clone, Debug)]
pub struct BenchReport {
    /// Triangles in the scene.
    pub triangles: usize,
    /// Seconds to build the scene from its description (tessellation, transforms).
    pub scene_build_s: f64,
    /// Seconds to build the chosen backend's BVH.
    pub accel_build_s: f64,
    /// Backend measured.
    pub backend: &'static str,
    /// Ground-truth pass: rays and seconds.
    pub gt_rays: u64,
    /// Seconds of the ground-truth pass.
    pub gt_s: f64,
    /// Path pass: rays.
    pub path_rays: u64,
    /// Path pass: camera samples.
    pub path_samples: u64,
    /// Seconds of the path pass.
    pub path_s: f64,
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
}

/// Runs every measurement on `loaded` (must be called inside the thread pool to measure).
pub fn run_bench(loaded: &LoadedScene, s: &BenchSettings) -> Result<BenchReport, SceneError> {
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let t = Instant::now();
    let scene = build_scene(loaded, rig.left.center_world)?;
    let scene_build_s = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let accel = build_accel(s.backend, &scene.accel_geometry())
        .map_err(|e| SceneError::at(&loaded.path, SceneErrorKind::Resource, "", e.to_string()))?;
    let accel_build_s = t.elapsed().as_secs_f64();
    let raw = raw_throughput(&accel, &scene, &rig);
    // GT: every view and baseline of the rig, no path pass.
    let gt_settings = RenderSettings {
        spp: 0,
        max_depth: s.max_depth,
        seed: 1,
        frame: 0,
    };
    let gt = render_frame(&scene, &accel, &rig, &gt_settings, &|_, _| {});
    // Path: the left view only.
    let left_only = StereoRig {
        left: rig.left,
        baselines_m: Vec::new(),
    };
    let path_settings = RenderSettings {
        spp: s.spp,
        ..gt_settings
    };
    let path = render_frame(&scene, &accel, &left_only, &path_settings, &|_, _| {});
    use crate::accel::Accel;
    Ok(BenchReport {
        triangles: scene.triangle_count(),
        scene_build_s,
        accel_build_s,
        backend: accel.backend_name(),
        gt_rays: gt.stats.gt_rays,
        gt_s: gt.stats.gt_seconds,
        path_rays: path.stats.path_rays,
        path_samples: path.stats.samples,
        path_s: path.stats.path_seconds,
        raw,
    })
}

impl BenchReport {
    /// The human-readable report, one figure per line, with ratios.
    pub fn render_text(&self, threads: usize) -> String {
        let m = |rays: u64, s: f64| rays as f64 / s.max(1e-9) / 1e6;
        let gt = m(self.gt_rays, self.gt_s);
        let path = m(self.path_rays, self.path_s);
        let samples = m(self.path_samples, self.path_s);
        let r = &self.raw;
        [
            format!(
                "scene: {} triangles, {threads} threads, backend {}",
                self.triangles, self.backend
            ),
            format!("scene build          {:8.3} s", self.scene_build_s),
            format!("BVH build            {:8.3} s", self.accel_build_s),
            format!(
                "GT pass              {gt:8.2} Mrays/s ({} rays in {:.3} s)",
                self.gt_rays, self.gt_s
            ),
            format!(
                "path tracing         {path:8.2} Mrays/s, {samples:.3} Msamples/s ({} rays/sample)",
                format_args!(
                    "{:.2}",
                    self.path_rays as f64 / self.path_samples.max(1) as f64
                )
            ),
            format!(
                "raw primary single   {:8.2} Mrays/s",
                r.primary_single_mrays
            ),
            format!(
                "raw primary packet8  {:8.2} Mrays/s",
                r.primary_packet_mrays
            ),
            format!(
                "raw incoherent hit   {:8.2} Mrays/s",
                r.incoherent_closest_mrays
            ),
            format!(
                "raw incoherent any   {:8.2} Mrays/s",
                r.incoherent_any_mrays
            ),
            format!(
                "ratio GT / raw packet8        {:.2}",
                gt / r.primary_packet_mrays.max(1e-9)
            ),
            format!(
                "ratio path / raw incoherent   {:.2}",
                path / r.incoherent_closest_mrays.max(1e-9)
            ),
        ]
        .join("\n")
    }
}
