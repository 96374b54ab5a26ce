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

use crate::accel::Backend;
use crate::camera::StereoRig;
use crate::render::recipe::{BuiltScene, RecipeError};
use crate::render::{render_frame, RenderSettings};
use crate::scene::load::SceneErrorKind;
use crate::scene::{LoadedScene, SceneError};
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
    /// Every round's figures, in the order measured.
    pub rounds: Vec<BenchRound>,
}

/// One round: every throughput figure, measured back to back, so a round's
/// ratios compare figures taken under the same machine load.
#[derive(Clone, Debug)]
pub struct BenchRound {
    /// Ground-truth pass: rays.
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
    /// Rounds of measurements (at least 1) on the one scene and BVH.
    pub rounds: u32,
}

/// Seconds of GT-pass time the GT figure is measured over, at least.
const MIN_GT_S: f64 = 1.0;

/// Runs every measurement on `loaded` (must be called inside the thread pool to measure).
pub fn run_bench(loaded: &LoadedScene, s: &BenchSettings) -> Result<BenchReport, SceneError> {
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let mut built =
        BuiltScene::build_with(loaded, rig.left.center_world, s.backend, s.shading_twin).map_err(
            |e| match e {
                RecipeError::Scene(e) => e,
                e => SceneError::at(&loaded.path, SceneErrorKind::Resource, "", e.to_string()),
            },
        )?;
    // The path figures are the path tracer's: image-space filtering is
    // post-processing that none of the renderers compared with does (the
    // flags do not touch the geometry, so the built scene is switched).
    (built.scene.filter_indirect, built.scene.filter_inscatter) = (false, false);
    let (scene, accel) = (&built.scene, &built.accel);
    let (scene_build_s, accel_build_s) = (built.scene_seconds, built.accel_seconds);
    #[cfg(feature = "embree")]
    let embree_commit_s = match accel {
        crate::accel::AnyAccel::Embree(e) => Some(e.build_seconds()),
        _ => None,
    };
    #[cfg(not(feature = "embree"))]
    let embree_commit_s = None;
    let rounds = (0..s.rounds.max(1))
        .map(|_| measure_round(scene, accel, &rig, s))
        .collect();
    use crate::accel::Accel;
    Ok(BenchReport {
        triangles: scene.triangle_count(),
        scene_build_s,
        accel_build_s,
        embree_commit_s,
        backend: accel.backend_name(),
        rounds,
    })
}

/// One round of raw traversal, the ground-truth pass and the path pass.
fn measure_round(
    scene: &crate::scene::Scene,
    accel: &crate::accel::AnyAccel,
    rig: &StereoRig,
    s: &BenchSettings,
) -> BenchRound {
    let raw = raw_throughput(accel, scene, rig);
    // GT: every view and baseline of the rig, no path pass.
    let gt_settings = RenderSettings {
        spp: 0,
        max_depth: s.max_depth,
        seed: 1,
        frame: 0,
        adaptive: false,
    };
    // One GT pass takes a fraction of a second: repeat it, as the raw figures
    // repeat theirs, so one slow moment of a noisy machine does not decide
    // the figure.
    let (mut gt_rays, mut gt_s) = (0, 0.0);
    let t = Stopwatch::start();
    while gt_s < MIN_GT_S {
        let gt = render_frame(scene, accel, rig, &gt_settings, &|_, _| {});
        gt_rays += gt.stats.gt_rays;
        gt_s += gt.stats.gt_seconds;
    }
    let gt = phase_span(t.stop(), gt_s);
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
    let path = render_frame(scene, accel, &left_only, &path_settings, &|_, _| {});
    BenchRound {
        gt_rays,
        gt,
        path_rays: path.stats.path_rays,
        path_samples: path.stats.samples,
        path: phase_span(t.stop(), path.stats.path_seconds),
        raw,
    }
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
    /// CPU-scaled figures. With several rounds each figure is the median over
    /// rounds, its CPU-scaled range follows in brackets, and each ratio is the
    /// median of the rounds' own ratios.
    pub fn render_text(&self, threads: usize) -> String {
        let n = self.rounds.len();
        let gt = |r: &BenchRound| Rate::of(r.gt_rays, r.gt, threads);
        let path = |r: &BenchRound| Rate::of(r.path_rays, r.path, threads);
        let samples = |r: &BenchRound| Rate::of(r.path_samples, r.path, threads);
        let figure = |f: &dyn Fn(&BenchRound) -> Rate| Figure::of(&self.rounds, f);
        let line = |name: &str, x: Figure| format!("{name:<20} {}", x.text("Mrays/s", 2));
        // A count summed over every round (beside median figures).
        let total = |f: fn(&BenchRound) -> u64| self.rounds.iter().map(f).sum::<u64>();
        let ratio = |a: &dyn Fn(&BenchRound) -> Rate, b: &dyn Fn(&BenchRound) -> Rate| {
            median(self.rounds.iter().map(|r| a(r).cpu / b(r).cpu.max(1e-9)))
        };
        let mut lines = vec![
            format!(
                "scene: {} triangles, {threads} threads, backend {}{}",
                self.triangles,
                self.backend,
                if n > 1 {
                    format!(", medians of {n} rounds")
                } else {
                    String::new()
                }
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
                "{} ({} rays in {:.3} s{})",
                line("GT pass", figure(&gt)),
                total(|r| r.gt_rays),
                self.rounds.iter().map(|r| r.gt.wall_s).sum::<f64>(),
                if n > 1 { ", all rounds" } else { "" }
            ),
            format!(
                "{} ({:.2} rays/sample)",
                line("path tracing", figure(&path)),
                total(|r| r.path_rays) as f64 / total(|r| r.path_samples).max(1) as f64
            ),
            format!(
                "path samples         {}",
                figure(&samples).text("Msamples/s", 3)
            ),
        ];
        let raw: [(&str, RawField); 8] = [
            ("raw primary single", |r| r.primary_single_mrays),
            ("raw primary packet8", |r| r.primary_packet_mrays),
            ("raw primary tile4x2", |r| r.primary_tile_mrays),
            ("raw incoherent hit", |r| r.incoherent_closest_mrays),
            ("raw incoherent any", |r| r.incoherent_any_mrays),
            ("raw shading packet8", |r| r.shading_packet_mrays),
            ("raw shading hit", |r| r.shading_closest_mrays),
            ("raw shading any", |r| r.shading_any_mrays),
        ];
        lines.extend(
            raw.iter()
                .map(|(name, f)| line(name, figure(&|r: &BenchRound| f(&r.raw)))),
        );
        lines.push(format!(
            "ratio GT / raw tile4x2        {:.2}",
            ratio(&gt, &|r| r.raw.primary_tile_mrays)
        ));
        lines.push(format!(
            "ratio path / raw incoherent   {:.2} (watertight), {:.2} (shading queries path uses)",
            ratio(&path, &|r| r.raw.incoherent_closest_mrays),
            ratio(&path, &|r| r.raw.shading_closest_mrays)
        ));
        lines.join("\n")
    }
}

/// Reads one raw figure.
type RawField = fn(&RawThroughput) -> Rate;

/// One figure over the rounds: medians of the wall and CPU-scaled rates and
/// the CPU-scaled range.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Figure {
    wall: f64,
    cpu: f64,
    cpu_min: f64,
    cpu_max: f64,
    rounds: usize,
}

impl Figure {
    fn of(rounds: &[BenchRound], f: impl Fn(&BenchRound) -> Rate) -> Figure {
        let rates: Vec<Rate> = rounds.iter().map(f).collect();
        let cpu = || rates.iter().map(|r| r.cpu);
        Figure {
            wall: median(rates.iter().map(|r| r.wall)),
            cpu: median(cpu()),
            cpu_min: cpu().fold(f64::INFINITY, f64::min),
            cpu_max: cpu().fold(f64::NEG_INFINITY, f64::max),
            rounds: rates.len(),
        }
    }

    /// "W unit wall C cpu", with "[min–max]" of the CPU figure over several rounds.
    fn text(&self, unit: &str, decimals: usize) -> String {
        let d = decimals;
        let mut s = format!("{:8.d$} {unit} wall {:8.d$} cpu", self.wall, self.cpu);
        if self.rounds > 1 {
            s += &format!("  [{:.d$}–{:.d$}]", self.cpu_min, self.cpu_max);
        }
        s
    }
}

/// The median (the mean of the middle two for an even count; NaN for none).
fn median(xs: impl Iterator<Item = f64>) -> f64 {
    let mut v: Vec<f64> = xs.collect();
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A round whose every figure is `rays` over `span`.
    fn round(rays: u64, span: Span) -> BenchRound {
        let r = Rate::of(rays, span, 1);
        BenchRound {
            gt_rays: rays,
            gt: span,
            path_rays: rays,
            path_samples: rays / 4,
            path: span,
            raw: RawThroughput {
                primary_tile_mrays: Rate {
                    wall: r.wall * 2.0,
                    cpu: r.cpu * 2.0,
                },
                incoherent_closest_mrays: r,
                shading_closest_mrays: r,
                ..RawThroughput::default()
            },
        }
    }

    fn report(rounds: Vec<BenchRound>) -> BenchReport {
        BenchReport {
            triangles: 12,
            scene_build_s: 0.0,
            accel_build_s: 0.0,
            embree_commit_s: None,
            backend: "test",
            rounds,
        }
    }

    fn line<'a>(text: &'a str, start: &str) -> &'a str {
        text.lines().find(|l| l.starts_with(start)).unwrap()
    }

    #[test]
    fn cpu_figures_scale_by_the_threads_the_run_used() {
        // One thread busy for all of 2 wall seconds: 4M rays is 2 Mrays/s
        // both ways. (Scaling by the global pool, as the report once did,
        // doubled the CPU figure on a two-core machine.)
        let span = Span {
            wall_s: 2.0,
            cpu_s: 2.0,
        };
        let text = report(vec![round(4_000_000, span)]).render_text(1);
        assert!(
            line(&text, "GT pass").contains("2.00 Mrays/s wall     2.00 cpu"),
            "{text}"
        );
        assert!(!text.contains("rounds"), "{text}");
        assert!(
            line(&text, "GT pass").ends_with("(4000000 rays in 2.000 s)"),
            "{text}"
        );
        assert!(line(&text, "ratio GT").ends_with("0.50"), "{text}");
    }

    #[test]
    fn several_rounds_give_medians_ranges_and_median_ratios() {
        let span = |wall_s| Span {
            wall_s,
            cpu_s: wall_s,
        };
        // 4M rays in 1, 4 and 2 s: 4, 1 and 2 Mrays/s; median 2.
        let rounds = vec![
            round(4_000_000, span(1.0)),
            round(4_000_000, span(4.0)),
            round(4_000_000, span(2.0)),
        ];
        let text = report(rounds).render_text(1);
        assert!(text.contains("medians of 3 rounds"), "{text}");
        let gt = line(&text, "GT pass");
        assert!(
            gt.contains("2.00 Mrays/s wall     2.00 cpu  [1.00–4.00]"),
            "{gt}"
        );
        // The counts after it are every round's, not the first's.
        assert!(
            gt.ends_with("(12000000 rays in 7.000 s, all rounds)"),
            "{gt}"
        );
        let samples = line(&text, "path samples");
        assert!(samples.contains("0.500 Msamples/s"), "{samples}");
        assert!(samples.contains("[0.250–1.000]"), "{samples}");
        // Every round's GT ran at half its tile rate.
        assert!(line(&text, "ratio GT").ends_with("0.50"), "{text}");
        assert_eq!(median([3.0, 1.0, 2.0, 10.0].into_iter()), 2.5);
        assert!(median(std::iter::empty()).is_nan());
    }
}
