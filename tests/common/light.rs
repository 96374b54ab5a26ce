//! Shared by the light tests: a frame's left view path-traced with a chosen
//! light selection, keeping each pixel's per-sample variance so image means
//! come with an error bar.

use glam::Vec3;
use parallax::accel::{AnyAccel, Backend};
use parallax::camera::StereoRig;
use parallax::integrator::{RenderCamera, Shading};
use parallax::light::{LightSelection, LightSet};
use parallax::render::recipe::BuiltScene;
use parallax::sampler::{SampleStream, StreamKey};
use parallax::scene::{LoadedScene, Scene};
use rayon::prelude::*;

/// Per-pixel luminance mean and variance of the mean, plus seconds spent.
pub struct Pass {
    pub mean: Vec<f64>,
    pub var_of_mean: Vec<f64>,
    pub seconds: f64,
}

impl Pass {
    /// Image mean and its standard error.
    pub fn image_mean(&self) -> (f64, f64) {
        let n = self.mean.len() as f64;
        let m = self.mean.iter().sum::<f64>() / n;
        let v = self.var_of_mean.iter().sum::<f64>() / (n * n);
        (m, v.sqrt())
    }

    /// Root-mean-square difference to a reference image.
    pub fn rmse(&self, reference: &[f64]) -> f64 {
        let s: f64 = self
            .mean
            .iter()
            .zip(reference)
            .map(|(a, b)| (a - b).powi(2))
            .sum();
        (s / reference.len() as f64).sqrt()
    }
}

/// A built scene, its accelerator and its rig.
pub struct Built {
    pub scene: Scene,
    pub accel: AnyAccel,
    pub rig: StereoRig,
}

/// Builds `loaded` around its left camera.
pub fn build(loaded: &LoadedScene) -> Built {
    let rig = StereoRig::from_desc(&loaded.desc.camera);
    let BuiltScene { scene, accel, .. } =
        BuiltScene::build(loaded, rig.left.center_world, Backend::default_backend())
            .expect("scene builds");
    Built { scene, accel, rig }
}

/// Path-traces the left view with `spp` samples, local lights chosen by
/// `selection`; sample streams keyed by `seed`.
pub fn render_left(
    b: &Built,
    selection: LightSelection,
    spp: u32,
    max_depth: u32,
    seed: u64,
) -> Pass {
    let scene = &b.scene;
    let t0 = std::time::Instant::now();
    let shading = Shading::with_lights(scene, &b.accel, LightSet::build_with(scene, selection));
    let ctx = shading.context(max_depth);
    let cam = RenderCamera::new(&b.rig.left, scene.origin_world);
    let (w, h) = (cam.intrinsics.width, cam.intrinsics.height);
    let key = StreamKey {
        seed,
        frame: 0,
        view: 0,
    };
    let px: Vec<(f64, f64)> = (0..w * h)
        .into_par_iter()
        .map(|k| {
            let (i, j) = (k % w, k / w);
            let (mut s1, mut s2) = (0.0f64, 0.0f64);
            let mut rays = 0;
            for s in 0..spp {
                let mut stream = SampleStream::new(key, i, j, s);
                let ray = cam.jittered_ray(i, j, &mut stream);
                let li = ctx.li(ray, cam.cone(ray.d), &mut stream, &mut rays).l;
                assert!(li.is_finite(), "non-finite sample {s} at pixel ({i}, {j})");
                let y = li.dot(Vec3::new(0.2126, 0.7152, 0.0722)) as f64;
                s1 += y;
                s2 += y * y;
            }
            let n = spp as f64;
            let mean = s1 / n;
            let var = (s2 / n - mean * mean).max(0.0) / (n - 1.0).max(1.0);
            (mean, var)
        })
        .collect();
    Pass {
        mean: px.iter().map(|p| p.0).collect(),
        var_of_mean: px.iter().map(|p| p.1).collect(),
        seconds: t0.elapsed().as_secs_f64(),
    }
}
