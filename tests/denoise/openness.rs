//! The openness of the first surface's bounce (`DenoiseSample::openness`),
//! which the indirect-light filter divides by: between a floor and a
//! ceiling `c` × `OPEN_RADIUS` apart, a cosine-distributed bounce ray
//! (μ = cos θ, density 2μ) meets the other plane at c·R/μ, so its openness
//! min(1, c/μ) has the mean ∫₀ᶜ 2μ dμ + ∫꜀¹ (c/μ)·2μ dμ = 2c − c². Both
//! path tracers (medium-free, and in a medium) must hand over that mean,
//! and 1 under an open sky.

use crate::common;

use common::{camera_block, rebuild_left, render, scene_from_toml};
use parallax::accel::Backend;
use parallax::integrator::OPEN_RADIUS;

/// The gap between floor and ceiling as a share of the radius.
const C: f32 = 0.5;
const SPP: u32 = 16;

/// A grey floor with its top at z = 0 and, when `ceiling`, a grey ceiling
/// whose underside is `C` × `OPEN_RADIUS` above it, both reaching 10 m
/// behind the camera and 60 m ahead (every pixel sees one of them, and no
/// bounce within the radius passes their ends); a camera at half the gap
/// looking along them; `medium` lines after.
fn slot(ceiling: bool, medium: &str) -> String {
    let gap = C * OPEN_RADIUS;
    let board = |z: f32| {
        format!(
            "[[object]]\nkind = \"box\"\nsize = [70.0, 60.0, 0.2]\nmaterial = \"grey\"\n\
             transform = {{ translate = [25.0, 0.0, {z:?}] }}\n"
        )
    };
    let mut s = camera_block(32, 16, [0.0, 0.0, (gap / 2.0) as f64]);
    s += "baselines_cm = [10.0]\n[render]\nspp = 1\nmax_depth = 3\nseed = 1\n";
    s += "[sky]\nkind = \"constant\"\nle = [1.0, 1.0, 1.0]\n";
    s += "[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n";
    s += &board(-0.1);
    if ceiling {
        s += &board(gap + 0.1);
    }
    s + medium
}

/// Mean and standard error, over the left view's pixels that see a
/// surface, of each pixel's mean openness at `SPP` samples, and the share
/// of the pixels that see one.
fn openness_of(text: &str) -> (f64, f64, f64) {
    let r = render(&scene_from_toml(text), Backend::default_backend(), 1);
    let (_, inputs) = rebuild_left(&r, SPP, 7, 3);
    let v: Vec<f64> = (inputs.openness.iter().zip(&inputs.rho))
        .filter(|(_, rho)| rho.y > 0.0)
        .map(|(&o, _)| o as f64)
        .collect();
    let (mean, se) = common::mean_stderr(&v);
    (mean, se, v.len() as f64 / inputs.rho.len() as f64)
}

#[test]
fn bounces_between_floor_and_ceiling_are_as_open_as_the_cosine_law_says() {
    let want = (2.0 * C - C * C) as f64;
    for (what, medium) in [
        ("clear", ""),
        (
            "thin haze",
            "[medium]\nkind = \"homogeneous\"\nsigma_t = 0.01\nalbedo = [0.9, 0.9, 0.9]\ng = 0.5\nz_max_m = 100.0\n",
        ),
    ] {
        let (mean, se, seen) = openness_of(&slot(true, medium));
        println!("{what}: mean openness {mean:.4} ± {se:.4}, want {want:.4}");
        assert_eq!(seen, 1.0, "{what}: a pixel missed the slot");
        assert!(
            (mean - want).abs() < 5.0 * se + 1e-3,
            "{what}: {mean} ± {se}, want {want}"
        );
        let (open, _, seen) = openness_of(&slot(false, medium));
        assert!(seen > 0.4, "{what}: {seen} of the pixels see the floor");
        assert_eq!(open, 1.0, "{what}: under the open sky");
    }
}
