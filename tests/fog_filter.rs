//! The fog in-scattering filter (`film::filter_fog`, `[medium]
//! filter_inscatter`) through the whole renderer: it keeps the image mean,
//! cuts per-pixel variance in an analytic furnace (conservative fog under a
//! constant sky: every pixel's expected value is exactly 1), keeps a near/far
//! depth step a step, is bit-for-bit the plain estimate when off and the
//! filtered per-sample estimate when on (any thread count), and never
//! touches the ground truth.

mod common;

use common::{camera_block, mean_stderr, render, scene_from_toml, Rendered};
use glam::Vec3;
use parallax::accel::{Accel, Backend, ShadingAccel};
use parallax::film::{Film, FogLayer};
use parallax::geometry::SurfaceTable;
use parallax::integrator::path::PathContext;
use parallax::integrator::volpath::{filter_view_inscatter, SunLobe};
use parallax::integrator::RenderCamera;
use parallax::light::LightSet;
use parallax::sampler::{SampleStream, StreamKey};

/// Conservative fog slab under a white sky: L = 1 in every direction.
const FURNACE: &str = "[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n[medium]\nkind = \"homogeneous\"\nsigma_t = 0.15\nalbedo = [1.0, 1.0, 1.0]\ng = 0.85\nz_min_m = -3.0\nz_max_m = 3.0\n";

/// Sunlit fog over a grey ground, a near wall (x = 6 m) over the upper
/// half of the image and a far wall (x = 60 m) below it.
const STEP: &str = r#"
[sky]
kind = "gradient"
zenith = [0.3, 0.4, 0.8]
horizon = [0.8, 0.8, 0.9]
ground = [0.1, 0.1, 0.1]
[[light]]
kind = "sun"
elevation_deg = 25.0
azimuth_deg = 160.0
irradiance = [600.0, 580.0, 550.0]
[[material]]
name = "grey"
kind = "diffuse"
albedo = [0.5, 0.5, 0.5]
[[object]]
kind = "box"
size = [0.2, 80.0, 20.0]
material = "grey"
transform = { translate = [6.0, 0.0, 11.5] }
[[object]]
kind = "box"
size = [0.2, 200.0, 200.0]
material = "grey"
transform = { translate = [60.0, 0.0, 0.0] }
[medium]
kind = "homogeneous"
sigma_t = 0.02
albedo = [0.95, 0.95, 0.95]
g = 0.7
z_max_m = 25.0
"#;

const W: u32 = 48;
const H: u32 = 32;

/// `body` rendered at `spp` with seed `seed`, the filter on or off.
fn render_body(body: &str, spp: u32, seed: u64, filter: bool, backend: Backend) -> Rendered {
    let key = if filter {
        ""
    } else {
        "filter_inscatter = false\n"
    };
    let text = format!(
        "{}baselines_cm = [54.0]\n[render]\nspp = {}\nmax_depth = 8\nseed = {seed}\n{body}{key}",
        camera_block(W, H, [0.0, 0.0, 1.5]),
        spp.max(1)
    );
    render(&scene_from_toml(&text), backend, spp)
}

fn green(r: &Rendered) -> Vec<f64> {
    r.out.images[0].rgb.iter().map(|c| c.y as f64).collect()
}

#[test]
fn filtered_mean_equals_unfiltered_mean_in_fog() {
    for (body, name) in [(FURNACE, "furnace"), (STEP, "step")] {
        let on = green(&render_body(body, 16, 3, true, Backend::default_backend()));
        let off = green(&render_body(body, 16, 3, false, Backend::default_backend()));
        let (m_on, _) = mean_stderr(&on);
        let (m_off, se_off) = mean_stderr(&off);
        eprintln!("{name}: mean on {m_on:.5}, off {m_off:.5} ± {se_off:.1e}");
        // Same streams (on also splits the first segment: a different
        // estimator of the same mean).
        assert!(
            (m_on - m_off).abs() < 0.01 * m_off,
            "{name}: {m_on} vs {m_off}"
        );
        assert!(
            (m_on - m_off).abs() < 3.0 * se_off,
            "{name}: {m_on} vs {m_off} ± {se_off}"
        );
    }
}

#[test]
fn per_pixel_variance_drops_threefold_in_the_fog_furnace() {
    // Expected value exactly 1 everywhere; mean squared error over pixels
    // and two seeds at 16 spp. At 48 px across the kernel is the smallest
    // (one à-trous level, σ = 1 px): about 4.1× when written.
    let mse = |filter: bool| {
        let mut s = 0.0;
        let mut n = 0;
        for seed in [1, 2] {
            for v in green(&render_body(
                FURNACE,
                16,
                seed,
                filter,
                Backend::default_backend(),
            )) {
                s += (v - 1.0).powi(2);
                n += 1;
            }
        }
        s / n as f64
    };
    let (on, off) = (mse(true), mse(false));
    eprintln!(
        "furnace MSE: filtered {on:.3e}, plain {off:.3e}, ratio {:.1}",
        off / on
    );
    assert!(off > 0.0 && on * 3.0 < off, "{on} vs {off}");
}

#[test]
fn depth_step_stays_a_step() {
    // A halo would carry the far wall's thick fog onto the near wall's rows
    // or back: every row mean within 4 rows of the step, filtered at 64 spp,
    // within 3 % of the plain image at 256 spp (the plain image at 64 spp
    // is printed beside it for scale).
    let on = render_body(STEP, 64, 1, true, Backend::default_backend());
    let off = render_body(STEP, 64, 1, false, Backend::default_backend());
    let reference = render_body(STEP, 256, 2, false, Backend::default_backend());
    let depth = &on.out.left.depth_z;
    let edge = (0..H as usize - 1)
        .find(|&j| depth[j * W as usize] < 10.0 && depth[(j + 1) * W as usize] > 50.0)
        .expect("the near wall ends above the far wall");
    let row = |r: &Rendered, j: usize| {
        (0..W as usize)
            .map(|i| r.out.images[0].get(i, j).y)
            .sum::<f32>()
            / W as f32
    };
    let (near, far) = (row(&reference, edge), row(&reference, edge + 1));
    eprintln!("step at row {edge}: near {near:.3}, far {far:.3}");
    assert!(
        (near - far).abs() > 0.2 * near.min(far),
        "the scene has a step: {near} vs {far}"
    );
    for j in edge.saturating_sub(4)..(edge + 5).min(H as usize) {
        let (got, want) = (row(&on, j), row(&reference, j));
        eprintln!(
            "row {j}: filtered {got:.3}, plain {:.3}, reference {want:.3}",
            row(&off, j)
        );
        assert!((got - want).abs() < 0.03 * want, "row {j}: {got} vs {want}");
    }
}

/// The left view of `r` rebuilt sample by sample from `PathContext::li`
/// with the frame's streams (4 spp, seed 9): the plain film and its fog layer.
fn rebuild_left(r: &Rendered) -> (Film, FogLayer) {
    let scene = &r.scene;
    let lights = LightSet::build(scene);
    let surfaces = SurfaceTable::build(scene);
    let shading = ShadingAccel(&r.accel);
    let ctx = PathContext {
        scene,
        accel: &shading,
        lights: &lights,
        surfaces: &surfaces,
        max_depth: 8,
        sun_lobe: SunLobe::find(scene, &lights),
    };
    let cam = RenderCamera::new(&r.rig.left, scene.origin_world);
    let key = StreamKey {
        seed: 9,
        frame: 0,
        view: 0,
    };
    let (w, h) = (W as usize, H as usize);
    let mut film = Film::new(w, h);
    let mut fog = FogLayer::new(w, h);
    for j in 0..H {
        for i in 0..W {
            let (mut l, mut l_fog, mut opacity) = (Vec3::ZERO, Vec3::ZERO, 0.0f32);
            let mut rays = 0;
            for s in 0..4 {
                let mut stream = SampleStream::new(key, i, j, s);
                let jitter = stream.next_2d();
                let d = cam
                    .dir(i as f64 + jitter.x as f64, j as f64 + jitter.y as f64)
                    .as_vec3()
                    .normalize();
                let ray = parallax::accel::Ray::new(cam.center_f32(), d);
                let li = ctx.li_from_hit(ray, shading.intersect(&ray), &mut stream, &mut rays);
                if li.l.is_finite() {
                    l += li.l;
                    l_fog += li.l_fog;
                    opacity += li.opacity;
                }
            }
            let k = j as usize * w + i as usize;
            (film.rgb[k], fog.l_fog[k], fog.opacity[k]) = (l / 4.0, l_fog / 4.0, opacity / 4.0);
        }
    }
    (film, fog)
}

#[test]
fn filter_off_and_on_are_functions_of_the_samples() {
    // Off must equal the per-sample estimate bit for bit; on must equal the
    // filtered per-sample estimate (BVH backend: its packet query is the
    // single-ray one).
    let off = render_body(STEP, 4, 9, false, Backend::Bvh);
    let on = render_body(STEP, 4, 9, true, Backend::Bvh);
    let (film_off, _) = rebuild_left(&off);
    assert_eq!(
        off.out.images[0], film_off,
        "filter off is the plain estimate"
    );
    let (mut film, fog) = rebuild_left(&on);
    assert!(!fog.is_empty(), "the fog carries first-scatter light");
    let cam = RenderCamera::new(&on.rig.left, on.scene.origin_world);
    filter_view_inscatter(&on.scene, &cam, &on.out.left.depth_z_f32(), &mut film, &fog);
    assert_eq!(on.out.images[0], film, "filter on is the filtered estimate");
    assert_ne!(on.out.images[0], off.out.images[0]);
}

#[test]
fn filtered_frame_is_bitwise_identical_for_1_and_2_threads() {
    let on = |threads| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| render_body(STEP, 4, 5, true, Backend::default_backend()))
    };
    let (a, b) = (on(1), on(2));
    assert_eq!(a.out.images.len(), 2);
    for (x, y) in a.out.images.iter().zip(&b.out.images) {
        let bits = |f: &Film| {
            f.rgb
                .iter()
                .flat_map(|c| c.to_array().map(f32::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(x), bits(y));
    }
}

#[test]
fn ground_truth_is_the_same_with_the_filter_on_and_off() {
    let on = render_body(STEP, 2, 4, true, Backend::default_backend());
    let off = render_body(STEP, 2, 4, false, Backend::default_backend());
    let gt_only = render_body(STEP, 0, 4, true, Backend::default_backend());
    for other in [&off, &gt_only] {
        assert_eq!(on.out.left, other.out.left);
        assert_eq!(on.out.baselines, other.out.baselines);
    }
    // The right view is filtered too (guided by its own depth).
    assert_ne!(on.out.images[1], off.out.images[1]);
}
