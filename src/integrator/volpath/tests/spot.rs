//! Single scattering of a spot lamp in a homogeneous slab against numeric
//! quadrature, on camera rays that start outside its cone and cross it:
//! equiangular sampling draws its distances around the lamp whatever the
//! cone does at the ray's origin (the in-scattering points' NEE leaves
//! that part of the light to it by MIS).

use super::mean_var;
use super::shadow::radiance;
use crate::integrator::volpath::Strategies;

const SIGMA_T: f64 = 0.05;
const ALBEDO: f64 = 0.95;
const G: f64 = 0.6;
const Z_MAX: f64 = 40.0;
/// The camera (`radiance`'s ray origin).
const CAMERA: [f64; 3] = [0.0, 0.0, 1.5];
/// The lamp, pointing straight down; seen from it the camera is 57° off
/// its axis, outside the 30° cone.
const LAMP: [f64; 3] = [10.0, 0.0, 8.0];
const INTENSITY: f64 = 2000.0;
const INNER_DEG: f64 = 20.0;
const OUTER_DEG: f64 = 30.0;

/// The slab over a black ground (rays here go up and never meet it), the
/// lamp its only light.
fn scene() -> String {
    let [x, y, z] = LAMP;
    format!(
        r#"
[camera]
width = 4
height = 4
hfov_deg = 60.0
position = [0.0, 0.0, 1.5]
[[light]]
kind = "spot"
position = [{x}, {y}, {z}]
direction = [0.0, 0.0, -1.0]
intensity = [{INTENSITY}, {INTENSITY}, {INTENSITY}]
inner_deg = {INNER_DEG}
outer_deg = {OUTER_DEG}
[medium]
kind = "homogeneous"
sigma_t = {SIGMA_T}
albedo = [{ALBEDO}, {ALBEDO}, {ALBEDO}]
g = {G}
z_max_m = {Z_MAX}
[[material]]
name = "ground"
kind = "diffuse"
albedo = [0.0, 0.0, 0.0]
[[object]]
kind = "quad"
size = [2000.0, 2000.0]
material = "ground"
"#
    )
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The lamp's single-scattered radiance along unit direction `d` from the
/// camera: ∫ σ_s·e^{−σ_t t}·p(d·ω)·I·falloff·e^{−σ_t r}/r² dt up to the
/// slab's top, by Simpson's rule.
fn single_scatter(d: [f64; 3]) -> f64 {
    let (cos_in, cos_out) = (INNER_DEG.to_radians().cos(), OUTER_DEG.to_radians().cos());
    let f = |t: f64| {
        let x = [
            CAMERA[0] + t * d[0],
            CAMERA[1] + t * d[1],
            CAMERA[2] + t * d[2],
        ];
        let to_lamp = sub(LAMP, x);
        let r = dot(to_lamp, to_lamp).sqrt();
        let w = [to_lamp[0] / r, to_lamp[1] / r, to_lamp[2] / r];
        let s = ((w[2] - cos_out) / (cos_in - cos_out)).clamp(0.0, 1.0);
        let falloff = s * s * (3.0 - 2.0 * s);
        let cos = dot(d, w);
        let hg =
            (1.0 - G * G) / (4.0 * std::f64::consts::PI * (1.0 + G * G - 2.0 * G * cos).powf(1.5));
        let tr = (-SIGMA_T * (t + r)).exp();
        ALBEDO * SIGMA_T * hg * INTENSITY * falloff * tr / (r * r)
    };
    let t_out = (Z_MAX - CAMERA[2]) / d[2];
    let n = 200_000;
    let h = t_out / n as f64;
    let inner: f64 = (1..n)
        .map(|i| f(i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 })
        .sum();
    (f(0.0) + inner + f(t_out)) * h / 3.0
}

#[test]
fn single_scattered_spot_from_outside_its_cone_matches_quadrature() {
    // Under the lamp, beside it (grazing the cone) and past it; depth 1:
    // single scattering only, every in-scattering estimate taken.
    let always = Strategies {
        local_per_opacity: f32::INFINITY,
        local_nee_deep: 1.0,
        ..Strategies::default()
    };
    let dirs: [[f64; 3]; 3] = [[10.0, 0.0, 1.5], [10.0, 2.0, 2.0], [10.0, -1.0, 3.5]];
    for d in dirs {
        let n = dot(d, d).sqrt();
        let d = [d[0] / n, d[1] / n, d[2] / n];
        let dv = glam::Vec3::new(d[0] as f32, d[1] as f32, d[2] as f32);
        let (l, _) = radiance(&scene(), always, dv, 1, 16384);
        let (mean, var) = mean_var(&l);
        let se = (var / l.len() as f64).sqrt();
        let want = single_scatter(d);
        eprintln!("{d:?}: {mean:.6} ± {se:.6}, quadrature {want:.6}");
        assert!(want > 0.0, "the ray misses the cone");
        assert!(
            (mean - want).abs() <= 4.0 * se + 2e-3 * want,
            "{d:?}: {mean} vs {want} ± {se}"
        );
    }
}
