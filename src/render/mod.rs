//! Rendering one frame: `render_frame`, every view, as data (DESIGN.md "One
//! frame, as data"; modelled on pbrt-v4's `RenderCPU` as one linear
//! set-up). This module owns the frame's passes and their order: ground
//! truth, the path pass per view (`view.rs`) with its denoising
//! (`crate::denoise`), the rain composite, and the frame's exposure.
//!
//! The geometry is built once and shared by every view. The ground-truth pass
//! runs first and independently of the path pass, so nothing the path pass
//! does (jitter, noise) can touch it. Views: 0 = left, 1 + b = right camera of
//! baseline b; each has its own sample stream.

mod adaptive;
pub mod recipe;
mod view;

use std::time::Instant;

use glam::Vec3;

use shaders_cpu::medium::Rain;

use crate::accel::Accel;
use crate::camera::StereoRig;
use crate::film::Film;
use crate::integrator::gt::{occlusion_mask, view_gt, ViewGt};
use crate::integrator::rain;
use crate::integrator::{RenderCamera, Shading};
use crate::sampler::StreamKey;
use crate::scene::Scene;

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
    /// Adaptive sampling: each view's `pixels × spp` samples go where a
    /// pilot pass saw error (`adaptive.rs`); off, `spp` in every pixel.
    pub adaptive: bool,
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
    /// The left view's first visible surfaces (`None` when spp = 0).
    pub aov: Option<AovImages>,
    /// Statistics.
    pub stats: RenderStats,
}

/// Auxiliary images of a view for an external denoiser (Open Image
/// Denoise's albedo and normal inputs): per pixel the mean of its samples'
/// `integrator::Aov`, the normal renormalised (zero where no sample saw a
/// surface: sky, or fog scattered first).
#[derive(Clone, Debug, PartialEq)]
pub struct AovImages {
    /// Mean throughput × albedo of the first visible surface, row-major.
    pub albedo: Vec<Vec3>,
    /// Unit mean world-space shading normal, row-major.
    pub normal: Vec<Vec3>,
}

impl AovImages {
    /// `n` pixels of zeros.
    pub fn new(n: usize) -> AovImages {
        AovImages {
            albedo: vec![Vec3::ZERO; n],
            normal: vec![Vec3::ZERO; n],
        }
    }
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
    /// Seconds in the path pass (the denoiser's included).
    pub path_seconds: f64,
    /// Seconds of the path pass spent denoising the views.
    pub denoise_seconds: f64,
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
    let mut stats = RenderStats::default();

    let t0 = Instant::now();
    // One rain field per frame: every view sees its streaks (opacity per
    // pixel, composited after the path pass) and the left mask marks them.
    let f_px = rig.left.intrinsics.f_px;
    let rain = crate::integrator::frame_rain(scene, settings.seed, settings.frame, f_px);
    let gt = gt_pass(scene, accel, rig, &cams, rain.as_ref(), settings.spp > 0);
    stats.gt_rays = gt.rays;
    stats.gt_seconds = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let (mut images, mut aov) = (Vec::new(), None);
    if settings.spp > 0 {
        (images, aov) = path_pass(scene, accel, &cams, &gt, settings, progress, &mut stats);
        composite_rain(&mut images, &gt.rain_alpha);
    }
    stats.path_seconds = t1.elapsed().as_secs_f64();
    let exposure_scale = images.first().map_or(1.0, crate::film::frame_exposure);
    FrameOutput {
        left: gt.left,
        baselines: gt.baselines,
        images,
        exposure_scale,
        aov,
        stats,
    }
}

/// The ground-truth pass's results, and the rain opacity per view the path
/// pass composites.
struct FrameGt {
    left: ViewGt,
    baselines: Vec<BaselineGt>,
    /// Per view (left first), where the frame has rain; right views only
    /// when there is a path pass.
    rain_alpha: Vec<Vec<f32>>,
    /// Rays traced (primary + occlusion).
    rays: u64,
}

/// Ground truth of every view at pixel centres (left, then per baseline the
/// right view and the left view's occlusion), with the rain streaks' opacity
/// of the left view and, when `path_pass` follows to composite them, of
/// the right views.
fn gt_pass(
    scene: &Scene,
    accel: &impl Accel,
    rig: &StereoRig,
    cams: &[RenderCamera],
    rain: Option<&Rain>,
    path_pass: bool,
) -> FrameGt {
    let f_px = rig.left.intrinsics.f_px;
    let mut rain_alpha = Vec::new();
    let mut left = view_gt(scene, accel, &cams[0], true);
    if let Some(rain) = rain {
        let alpha = rain::rain_opacity(scene, rain, &cams[0], &left.depth_z);
        rain::mark_rain(&mut left.mask, &alpha);
        rain_alpha.push(alpha);
    }
    let mut rays = left.depth_z.len() as u64;
    let mut baselines = Vec::with_capacity(rig.baselines_m.len());
    for (b, &baseline_m) in rig.baselines_m.iter().enumerate() {
        let right = view_gt(scene, accel, &cams[1 + b], false);
        // Right views need rain only to composite their images.
        if let Some(rain) = rain.filter(|_| path_pass) {
            rain_alpha.push(rain::rain_opacity(
                scene,
                rain,
                &cams[1 + b],
                &right.depth_z,
            ));
        }
        let (occlusion, occ_rays) =
            occlusion_mask(scene, accel, &cams[0], &cams[1 + b], &left, baseline_m);
        rays += right.depth_z.len() as u64 + occ_rays;
        baselines.push(BaselineGt {
            baseline_m,
            disparity_left: left.disparity(f_px, baseline_m),
            depth_right: right.depth_z_f32(),
            disparity_right: right.disparity(f_px, baseline_m),
            occlusion,
        });
    }
    FrameGt {
        left,
        baselines,
        rain_alpha,
        rays,
    }
}

/// Path-traces every view (`settings.spp` > 0) and denoises it where the
/// scene asks, guided by the view's exact depth from `gt`; counts rays and
/// samples into `stats`. Returns the images and the left view's AOVs.
fn path_pass(
    scene: &Scene,
    accel: &impl Accel,
    cams: &[RenderCamera],
    gt: &FrameGt,
    settings: &RenderSettings,
    progress: &(dyn Fn(usize, usize) + Sync),
    stats: &mut RenderStats,
) -> (Vec<Film>, Option<AovImages>) {
    let n_views = cams.len();
    let shading = Shading::new(scene, accel);
    let ctx = shading.context(settings.max_depth);
    let mut images = Vec::with_capacity(n_views);
    let mut left_aov = None;
    for (view, cam) in cams.iter().enumerate() {
        progress(view, n_views);
        let key = StreamKey {
            seed: settings.seed,
            frame: settings.frame,
            view: view as u32,
        };
        let view::ViewRender {
            mut film,
            denoise,
            rays,
            samples,
            non_finite,
            aov: view_aov,
        } = view::render_view(&ctx, cam, key, settings.spp, settings.adaptive);
        // Fog light, or indirect light on first surfaces, denoised per
        // view, guided by this view's exact pixel-centre depth (left, or
        // baseline b's right view).
        if let Some(inputs) = denoise {
            let left_depth;
            let depth_z: &[f32] = match view {
                0 => {
                    left_depth = gt.left.depth_z_f32();
                    &left_depth
                }
                v => &gt.baselines[v - 1].depth_right,
            };
            let t = Instant::now();
            let aux = crate::denoise::SurfaceAux {
                albedo: &view_aov.albedo,
                normal: &view_aov.normal,
            };
            crate::denoise::denoise_view(scene, cam, depth_z, &mut film, &inputs, aux);
            stats.denoise_seconds += t.elapsed().as_secs_f64();
        }
        stats.path_rays += rays;
        stats.non_finite_samples += non_finite;
        stats.samples += samples;
        images.push(film);
        if view == 0 {
            left_aov = Some(view_aov);
        }
    }
    progress(n_views, n_views);
    (images, left_aov)
}

/// Composites the frame's rain streaks (opacity per view, `rain_alpha`;
/// empty without rain) over the views' images, the drops' radiance taken
/// from the left view.
fn composite_rain(images: &mut [Film], rain_alpha: &[Vec<f32>]) {
    if let Some(left_film) = images.first().filter(|_| !rain_alpha.is_empty()) {
        let l_drop = rain::drop_radiance(left_film);
        for (film, alpha) in images.iter_mut().zip(rain_alpha) {
            rain::composite(film, alpha, l_drop);
        }
    }
}
