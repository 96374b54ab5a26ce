//! Closed-form participating-media tests through the whole renderer:
//! Beer–Lambert through an absorbing slab (0.1 %), single scattering of the
//! sun in a thin slab (1 %), a conservative (albedo 1) slab under a constant
//! sky stays at the sky radiance (white furnace), and a point light in fog
//! (equiangular + free-flight MIS) against quadrature of the single-scatter
//! integral, and the sun's single scattering in exponential height fog with
//! fog's forward lobe (g = 0.85) against quadrature. Expected values are
//! averaged over each pixel's footprint. The single-scatter cases render
//! with the fog filter off and check each band of rows as well as the
//! whole image (the filter's own mean is tested in `denoise/fog.rs`; the
//! furnace keeps it on).

use crate::common;

use common::{camera_block, mean_stderr, render, scene_from_toml, Rendered};
use glam::DVec3;
use parallax::accel::Backend;
use parallax::integrator::RenderCamera;
use shaders_cpu::medium::hg;

const W: u32 = 32;
const H: u32 = 24;

/// [`render_text`] with the fog filter off (`body` ends in its `[medium]`
/// table): the plain path-traced estimate, pixel by pixel. The filter keeps
/// the image mean but moves fog light between neighbouring pixels, so
/// checks finer than the whole image need it off.
fn render_unfiltered(body: &str, spp: u32, max_depth: u32, pitch_deg: f64) -> Rendered {
    render_text(
        &format!("{body}filter_inscatter = false\n"),
        spp,
        max_depth,
        pitch_deg,
    )
}

fn render_text(body: &str, spp: u32, max_depth: u32, pitch_deg: f64) -> Rendered {
    let text = format!(
        "{}pitch_deg = {pitch_deg}\nbaselines_cm = [54.0]\n[render]\nspp = {spp}\nmax_depth = {max_depth}\nseed = 5\n{body}",
        camera_block(W, H, [0.0, 0.0, 0.0])
    );
    render(&scene_from_toml(&text), Backend::default_backend(), spp)
}

/// Mean of `f(unit dir)` over a 6×6 grid inside pixel (i, j) of the left view.
fn pixel_mean(r: &Rendered, i: u32, j: u32, f: &dyn Fn(DVec3) -> f64) -> f64 {
    let cam = RenderCamera::new(&r.rig.left, r.scene.origin_world);
    let n = 6;
    let mut s = 0.0;
    for a in 0..n {
        for b in 0..n {
            let u = i as f64 + (a as f64 + 0.5) / n as f64;
            let v = j as f64 + (b as f64 + 0.5) / n as f64;
            s += f(cam.dir(u, v).normalize());
        }
    }
    s / (n * n) as f64
}

/// (rendered green, expected) per pixel.
fn pairs(r: &Rendered, f: &dyn Fn(DVec3) -> f64) -> Vec<(f64, f64)> {
    let img = &r.out.images[0].rgb;
    let mut v = Vec::new();
    for j in 0..H {
        for i in 0..W {
            v.push((img[(j * W + i) as usize].y as f64, pixel_mean(r, i, j, f)));
        }
    }
    v
}

/// The whole-image mean of `p` within 1 % of the expected one, and each band
/// of 6 rows (directions from the top of the image to its bottom) within
/// 4 standard errors + 0.5 % of its own expected mean, so errors that vary
/// with direction cannot cancel over the image.
fn assert_means_match(name: &str, p: &[(f64, f64)]) {
    let got: Vec<f64> = p.iter().map(|x| x.0).collect();
    let (mean, se) = mean_stderr(&got);
    let want = p.iter().map(|x| x.1).sum::<f64>() / p.len() as f64;
    eprintln!("{name}: mean {mean:.6} ± {se:.1e}, expected {want:.6}");
    assert!(
        (mean - want).abs() < 0.01 * want,
        "{name}: {mean} vs {want}"
    );
    let band = 6 * W as usize;
    assert_eq!(p.len() % band, 0);
    for (b, rows) in p.chunks(band).enumerate() {
        // Per-pixel residuals: their spread is the noise, not the image's
        // variation across the band.
        let residuals: Vec<f64> = rows.iter().map(|x| x.0 - x.1).collect();
        let (bias, se) = mean_stderr(&residuals);
        let want = rows.iter().map(|x| x.1).sum::<f64>() / rows.len() as f64;
        eprintln!(
            "{name} rows {}–{}: expected {want:.6}, rendered − expected {bias:.2e} ± {se:.1e}",
            6 * b,
            6 * b + 5
        );
        assert!(
            bias.abs() <= 4.0 * se + 0.005 * want,
            "{name}, band {b}: {bias} ± {se} off {want}"
        );
    }
}

#[test]
fn beer_lambert_through_absorbing_slab_matches_exp() {
    let sigma = 0.3;
    let body = "[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n[medium]\nkind = \"homogeneous\"\nsigma_t = 0.3\nalbedo = [0.0, 0.0, 0.0]\nz_min_m = 2.0\nz_max_m = 5.0\n";
    let r = render_text(body, 64, 4, -60.0);
    let mut worst = 0.0f64;
    for (got, want) in pairs(&r, &|d| (-sigma * 3.0 / d.z).exp()) {
        worst = worst.max((got - want).abs() / want);
    }
    eprintln!("worst relative error {worst:.2e}");
    assert!(worst < 1e-3, "worst relative error {worst}");
}

#[test]
fn single_scatter_thin_slab_matches_closed_form() {
    // Sun behind and above, slab z ∈ [2, 4], τ = 0.5 vertically; one event.
    let (sigma, albedo, g) = (0.25, 0.8, 0.5);
    let (elev, az) = (60f64.to_radians(), 180f64.to_radians());
    let sun = DVec3::new(elev.cos() * az.cos(), elev.cos() * az.sin(), elev.sin());
    let e_sun = 2.0;
    let body = "[[light]]\nkind = \"sun\"\nelevation_deg = 60.0\nazimuth_deg = 180.0\nirradiance = [2.0, 2.0, 2.0]\n[medium]\nkind = \"homogeneous\"\nsigma_t = 0.25\nalbedo = [0.8, 0.8, 0.8]\ng = 0.5\nz_min_m = 2.0\nz_max_m = 4.0\n";
    let r = render_unfiltered(body, 256, 1, -45.0);
    let expected = |d: DVec3| {
        // L = ∫ σ_s p(θ) E e^{−σ(s − s0)} e^{−σ(4 − s d_z)/μ_sun} ds over the slab.
        let (s0, s1) = (2.0 / d.z, 4.0 / d.z);
        let k = sigma * (1.0 - d.z / sun.z);
        let c = (sigma * s0 - sigma * 4.0 / sun.z).exp();
        let integral = if k.abs() < 1e-9 {
            s1 - s0
        } else {
            ((-k * s0).exp() - (-k * s1).exp()) / k
        };
        albedo * sigma * hg(d.dot(sun) as f32, g as f32) as f64 * e_sun * c * integral
    };
    assert_means_match("single scatter", &pairs(&r, &expected));
}

#[test]
fn white_furnace_conservative_slab_stays_at_sky_radiance() {
    let body = "[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n[medium]\nkind = \"homogeneous\"\nsigma_t = 0.15\nalbedo = [1.0, 1.0, 1.0]\ng = 0.85\nz_min_m = -3.0\nz_max_m = 3.0\n";
    let r = render_text(body, 64, 512, 0.0);
    let v: Vec<f64> = r.out.images[0].rgb.iter().map(|c| c.y as f64).collect();
    let (mean, se) = mean_stderr(&v);
    eprintln!("furnace: mean {mean:.5} ± {se:.1e}");
    assert!((mean - 1.0).abs() < 0.01, "mean {mean}");
    assert!((mean - 1.0).abs() < 4.0 * se + 1e-3, "mean {mean} ± {se}");
}

#[test]
fn point_light_in_fog_matches_single_scatter_quadrature() {
    // Equiangular and free-flight collisions combined by MIS, one event.
    let (sigma, albedo, g, intensity) = (0.08, 0.9, 0.3, 50.0);
    let q = DVec3::new(6.0, 1.0, 0.5);
    let body = "[[light]]\nkind = \"point\"\nposition = [6.0, 1.0, 0.5]\nintensity = [50.0, 50.0, 50.0]\n[medium]\nkind = \"homogeneous\"\nsigma_t = 0.08\nalbedo = [0.9, 0.9, 0.9]\ng = 0.3\nz_max_m = 1000.0\n";
    let r = render_unfiltered(body, 64, 1, 0.0);
    let expected = |d: DVec3| {
        // Simpson on t ∈ [0, 300] in the variable t = x³ (dense near the camera).
        let f = |t: f64| {
            let x = d * t;
            let to_l = q - x;
            let r2 = to_l.length_squared();
            let wi = to_l / r2.sqrt();
            albedo * sigma * hg(d.dot(wi) as f32, g as f32) as f64 * intensity / r2
                * (-sigma * (t + r2.sqrt())).exp()
        };
        let n = 4000;
        let x_max = 300f64.cbrt();
        let h = x_max / n as f64;
        let g_ = |k: usize| {
            let x = k as f64 * h;
            f(x * x * x) * 3.0 * x * x
        };
        let mut s = g_(0) + g_(n);
        for k in 1..n {
            s += if k % 2 == 1 { 4.0 } else { 2.0 } * g_(k);
        }
        s * h / 3.0
    };
    assert_means_match("point light in fog", &pairs(&r, &expected));
}

#[test]
fn single_scatter_height_fog_forward_lobe_matches_quadrature() {
    // Exponential fog σ(z) = 0.1·e^{−z/3} from the camera's height, strong
    // forward lobe (fog's g = 0.85), sun ahead and above: every segment's
    // in-scattering point is drawn ∝ σ_t·Tr in closed form; one event.
    let (sigma0, h, albedo, g, e_sun) = (0.1, 3.0, 0.9, 0.85, 2.0);
    let (elev, az) = (50f64.to_radians(), 0f64.to_radians());
    let sun = DVec3::new(elev.cos() * az.cos(), elev.cos() * az.sin(), elev.sin());
    let body = "[[light]]\nkind = \"sun\"\nelevation_deg = 50.0\nazimuth_deg = 0.0\nirradiance = [2.0, 2.0, 2.0]\n[medium]\nkind = \"height_fog\"\nsigma_t = 0.1\nbase_height_m = 0.0\nheight_scale_m = 3.0\nalbedo = [0.9, 0.9, 0.9]\ng = 0.85\n";
    let r = render_unfiltered(body, 128, 1, 30.0);
    let expected = |d: DVec3| {
        let f = |t: f64| {
            let z = d.z * t;
            let s = sigma0 * (-z / h).exp();
            let tau_cam = if d.z.abs() < 1e-9 {
                sigma0 * t
            } else {
                sigma0 * h / d.z * (1.0 - (-z / h).exp())
            };
            let tau_sun = s * h / sun.z;
            albedo * s * hg(d.dot(sun) as f32, g as f32) as f64 * e_sun * (-tau_cam - tau_sun).exp()
        };
        // Simpson on t ∈ [0, 400] in the variable t = x³.
        let n = 4000;
        let x_max = 400f64.cbrt();
        let step = x_max / n as f64;
        let g_ = |k: usize| {
            let x = k as f64 * step;
            f(x * x * x) * 3.0 * x * x
        };
        let mut s = g_(0) + g_(n);
        for k in 1..n {
            s += if k % 2 == 1 { 4.0 } else { 2.0 } * g_(k);
        }
        s * step / 3.0
    };
    assert_means_match("height fog single scatter", &pairs(&r, &expected));
}
