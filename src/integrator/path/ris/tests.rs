//! Resampling is unbiased and pays: over a Lambert point lit by a crowd of
//! point and spot lights (no occluders, so the estimate needs no shadow
//! ray), the mean of f·L·W over many draws equals the closed-form sum
//! Σ ρ/π·I·falloff·cosθ/d², with `CANDIDATES` candidates as with one, and M
//! candidates leave at most about (1/2 + 1/(2M)) of one candidate's
//! variance (resampling's share that falls as 1/M, and a margin).

use std::path::Path;

use glam::{DVec3, Vec3};

use super::{resample, RisSamples, CANDIDATES};
use crate::light::{spot_falloff, Light, LightSet};
use crate::scene::{build_scene, parse_scene_str};

const RHO: f32 = 0.5;

/// SplitMix64 numbers in [0, 1).
struct Rng(u64);

impl Rng {
    fn f(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
}

/// A plane under 40 lights: points and downward spots, 1–8 m up, of
/// intensities spread over two decades.
fn scene() -> crate::scene::Scene {
    scene_of(true)
}

/// [`scene`], its spots points too when `spots` is false.
fn scene_of(spots: bool) -> crate::scene::Scene {
    let mut rng = Rng(3);
    let mut text = String::from(
        "[camera]\nposition = [0.0, 0.0, 1.5]\n[[material]]\nname = \"m\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n[[object]]\nkind = \"quad\"\nsize = [60.0, 60.0]\nmaterial = \"m\"\n",
    );
    for k in 0..40 {
        let (x, y, z) = (
            40.0 * rng.f() - 20.0,
            40.0 * rng.f() - 20.0,
            1.0 + 7.0 * rng.f(),
        );
        let i = 10f32.powf(2.0 * rng.f());
        if k % 2 == 0 || !spots {
            text += &format!("[[light]]\nkind = \"point\"\nposition = [{x}, {y}, {z}]\nintensity = [{i}, {i}, {i}]\n");
        } else {
            let (dx, dy) = (rng.f() - 0.5, rng.f() - 0.5);
            text += &format!("[[light]]\nkind = \"spot\"\nposition = [{x}, {y}, {z}]\ndirection = [{dx}, {dy}, -1.0]\nintensity = [{i}, {i}, {i}]\ninner_deg = 20.0\nouter_deg = 45.0\n");
        }
    }
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
    let loaded = parse_scene_str(&text, &file).expect("scene parses");
    build_scene(&loaded, DVec3::ZERO).expect("scene builds")
}

/// ρ/π·cosθ toward `wi` from a Lambert point of normal `n`.
fn lambert(n: Vec3) -> impl Fn(Vec3) -> Vec3 + Copy {
    move |wi: Vec3| Vec3::splat(RHO / std::f32::consts::PI * wi.dot(n).max(0.0))
}

/// ρ/π·cosθ toward `wi` from an upward-facing Lambert point.
fn f_cos(wi: Vec3) -> Vec3 {
    lambert(Vec3::Z)(wi)
}

/// Reflected radiance at `p` in closed form.
fn exact(scene: &crate::scene::Scene, p: Vec3) -> f64 {
    exact_facing(scene, p, Vec3::Z)
}

/// Reflected radiance at `p` of normal `n` in closed form.
fn exact_facing(scene: &crate::scene::Scene, p: Vec3, n: Vec3) -> f64 {
    scene
        .lights
        .iter()
        .map(|l| {
            let (q, i, fall) = match *l {
                Light::Point { p: q, intensity } => (q, intensity.y, 1.0),
                Light::Spot {
                    p: q,
                    dir,
                    intensity,
                    cos_inner,
                    cos_outer,
                } => {
                    let wi = (q - p).normalize();
                    (
                        q,
                        intensity.y,
                        spot_falloff(-wi.dot(dir), cos_inner, cos_outer),
                    )
                }
                Light::Sun { .. } => unreachable!("no sun here"),
            };
            let d = q - p;
            (lambert(n)(d.normalize()).y * i * fall / d.length_squared()) as f64
        })
        .sum()
}

/// Mean and variance of the estimate at `p` over `n` draws of `m` candidates.
fn estimates(
    scene: &crate::scene::Scene,
    lights: &LightSet,
    p: Vec3,
    m: usize,
    n: usize,
) -> (f64, f64) {
    estimates_facing(scene, lights, (p, Vec3::ZERO), m, n, f_cos)
}

/// [`estimates`] at a receiver whose normal the light tree is given as
/// `at.1` (zero: none) and whose BSDF × cos is `f_cos`.
fn estimates_facing(
    scene: &crate::scene::Scene,
    lights: &LightSet,
    at: (Vec3, Vec3),
    m: usize,
    n: usize,
    f_cos: impl Fn(Vec3) -> Vec3 + Copy,
) -> (f64, f64) {
    let mut rng = Rng(11);
    let xs: Vec<f64> = (0..n)
        .map(|_| {
            let mut u = [[0.0; 4]; CANDIDATES];
            for c in &mut u {
                *c = [rng.f(), rng.f(), rng.f(), rng.f()];
            }
            let u = RisSamples { u, m, bounce: 0 };
            resample(lights, scene, at, &u, f_cos).map_or(0.0, |r| {
                let inv = r.inv_pdf.unwrap_or(1.0 / r.ls.pdf);
                (r.f * r.ls.li * inv).y as f64
            })
        })
        .collect();
    let mean = xs.iter().sum::<f64>() / n as f64;
    let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
    (mean, var)
}

#[test]
fn resampled_local_light_matches_the_closed_form_and_more_candidates_cut_its_variance() {
    let scene = scene();
    let lights = LightSet::build(&scene);
    assert_eq!(
        lights.local_candidates(),
        CANDIDATES,
        "no distant light: all local"
    );
    let n = 40_000;
    for p in [
        Vec3::ZERO,
        Vec3::new(7.0, -5.0, 0.0),
        Vec3::new(-12.0, 9.0, 0.0),
    ] {
        let e = exact(&scene, p);
        let (m1, v1) = estimates(&scene, &lights, p, 1, n);
        let (mm, vm) = estimates(&scene, &lights, p, CANDIDATES, n);
        eprintln!(
            "{p}: exact {e:.5}, M=1 {m1:.5} (var {v1:.4}), M={CANDIDATES} {mm:.5} (var {vm:.4})"
        );
        for (m, v) in [(m1, v1), (mm, vm)] {
            let se = (v / n as f64).sqrt();
            assert!((m - e).abs() <= 4.0 * se, "{p}: {m} vs exact {e} ± {se}");
            assert!((m - e).abs() <= 0.02 * e, "{p}: {m} vs exact {e}");
        }
        let bound = 0.5 + 0.5 / CANDIDATES as f64 + 0.1;
        assert!(
            vm < bound * v1,
            "{p}: variance {vm} with {CANDIDATES} candidates vs {v1} with 1 (bound {bound})"
        );
    }
}

#[test]
fn a_wall_given_its_normal_keeps_the_closed_form_with_less_variance() {
    // Points on a wall (normal along ±x or y) see about half the point
    // lights in front: the tree given the normal never picks the others.
    let scene = scene_of(false);
    let lights = LightSet::build(&scene);
    let n = 40_000;
    for (p, normal) in [
        (Vec3::new(0.0, 0.0, 0.5), Vec3::X),
        (Vec3::new(7.0, -5.0, 2.0), -Vec3::X),
        (Vec3::new(-3.0, 4.0, 1.0), Vec3::Y),
    ] {
        let e = exact_facing(&scene, p, normal);
        let f = lambert(normal);
        for m in [1, 2, CANDIDATES] {
            let (m0, v0) = estimates_facing(&scene, &lights, (p, Vec3::ZERO), m, n, f);
            let (mf, vf) = estimates_facing(&scene, &lights, (p, normal), m, n, f);
            eprintln!("{p} n {normal} M={m}: exact {e:.5}, plain {m0:.5} (var {v0:.5}), facing {mf:.5} (var {vf:.5})");
            for (mean, v) in [(m0, v0), (mf, vf)] {
                let se = (v / n as f64).sqrt();
                assert!(
                    (mean - e).abs() <= 4.0 * se,
                    "{p}: {mean} vs exact {e} ± {se}"
                );
                assert!((mean - e).abs() <= 0.02 * e, "{p}: {mean} vs exact {e}");
            }
            // The tree's own gain; stratified candidates already spread
            // over the lamps in front and take most of it (M=8: a twentieth
            // of one candidate's variance either way).
            if m == 1 {
                assert!(vf < 0.8 * v0, "{p}, M={m}: variance {vf} facing vs {v0}");
            }
        }
    }
}

/// A plane under `n` point lights of intensity 10 on a circle of radius 3,
/// 4 m up, centred over `RING_CENTRE`.
fn ring_scene(n: usize) -> crate::scene::Scene {
    let mut text = String::from(
        "[camera]\nposition = [0.0, 0.0, 1.5]\n[[material]]\nname = \"m\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n[[object]]\nkind = \"quad\"\nsize = [60.0, 60.0]\nmaterial = \"m\"\n",
    );
    for k in 0..n {
        let a = std::f32::consts::TAU * k as f32 / n as f32;
        let (x, y) = (RING_CENTRE.x + 3.0 * a.cos(), RING_CENTRE.y + 3.0 * a.sin());
        text += &format!("[[light]]\nkind = \"point\"\nposition = [{x}, {y}, 4.0]\nintensity = [10.0, 10.0, 10.0]\n");
    }
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
    let loaded = parse_scene_str(&text, &file).expect("scene parses");
    build_scene(&loaded, DVec3::ZERO).expect("scene builds")
}

/// The centre of the light tree's cells of a path's first vertex over
/// the origin's corner (`light::set::cuts`): the cell's cut weighs lamps
/// on a ring about it alike.
const RING_CENTRE: Vec3 = Vec3::new(1.0, 1.0, 0.0);

#[test]
fn stratified_candidates_see_every_lamp_the_tree_weighs_alike() {
    // Under the centre of a ring of M equal lamps, at the centre of its
    // cell, the tree gives each a pmf of 1/M: the M stratified candidates are the M lamps, one each,
    // so every draw's estimate is the closed form Σ f·I/d², here with a
    // BSDF that favours +x (the tree, given no normal, cannot see it).
    // Independent candidates repeat a lamp and miss another in most draws.
    let f = |wi: Vec3| Vec3::splat(RHO / std::f32::consts::PI * wi.z.max(0.0) * (1.0 + wi.x));
    for m in [2, 4] {
        let scene = ring_scene(m);
        let lights = LightSet::build(&scene);
        let e: f64 = scene
            .lights
            .iter()
            .map(|l| match *l {
                Light::Point { p: q, intensity } => {
                    let q = q - RING_CENTRE;
                    (f(q.normalize()).y * intensity.y / q.length_squared()) as f64
                }
                _ => unreachable!("points only"),
            })
            .sum();
        let mut rng = Rng(5);
        for draw in 0..2000 {
            let mut u = [[0.0; 4]; CANDIDATES];
            for c in &mut u {
                *c = [rng.f(), rng.f(), rng.f(), rng.f()];
            }
            let u = RisSamples { u, m, bounce: 0 };
            let r = resample(&lights, &scene, (RING_CENTRE, Vec3::ZERO), &u, f)
                .expect("every lamp lights the ring's centre");
            let x = (r.f * r.ls.li * r.inv_pdf.expect("resampled")).y as f64;
            assert!(
                (x - e).abs() <= 1e-4 * e,
                "M={m}, draw {draw}: {x} vs exact {e}"
            );
        }
    }
}
