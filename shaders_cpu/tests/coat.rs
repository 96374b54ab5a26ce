//! The coated BSDF (clear coat, water film): chi-square of its non-delta
//! sampling against its pdf, white-base energy ≤ 1, reciprocity, and `sample`
//! agreeing with `eval`/`pdf` (pbrt-v4 `bsdfs_test.cpp` recipe).

mod common;

use common::{dir, wos};
use glam::{Vec2, Vec3};
use shaders_cpu::bsdf::fresnel::fr_dielectric;
use shaders_cpu::bsdf::{Bsdf, CoatBase};
use shaders_cpu::stats::{chi2_test, sidak_threshold, Pcg32};

const N_SAMPLES: usize = 1_000_000;

fn lambert(a: f32) -> CoatBase {
    CoatBase::Lambert {
        albedo: Vec3::splat(a),
    }
}

fn gold_base(alpha: f32) -> CoatBase {
    let Some(Bsdf::Conductor { eta, k, .. }) = Bsdf::conductor_preset("gold", alpha) else {
        unreachable!()
    };
    CoatBase::Conductor { eta, k, alpha }
}

fn coated(base: CoatBase, eta: f32, alpha: f32) -> Bsdf {
    Bsdf::Coated { base, eta, alpha }
}

/// Coats with at least one non-delta lobe.
fn line_up() -> Vec<(&'static str, Bsdf)> {
    vec![
        ("paint rough", coated(lambert(0.6), 1.5, 0.05)),
        ("paint smooth", coated(lambert(0.6), 1.5, 0.0)),
        ("water rough", coated(lambert(0.3), 1.33, 0.2)),
        ("metallic", coated(gold_base(0.3), 1.5, 0.02)),
        ("metallic smooth coat", coated(gold_base(0.3), 1.5, 0.0)),
    ]
}

#[test]
fn coat_sampling_matches_pdf_chi2() {
    let bsdfs = line_up();
    let alpha = sidak_threshold(0.01, bsdfs.len() * wos().len());
    let mut failures = Vec::new();
    for (name, bsdf) in &bsdfs {
        for wo in wos() {
            // Delta samples (smooth coat) are not in the pdf: drop them, so
            // the pdf must integrate to the non-delta fraction.
            let r = chi2_test(
                |u, l| bsdf.sample(wo, l, u).filter(|s| !s.delta).map(|s| s.wi),
                |wi| bsdf.pdf(wo, wi),
                N_SAMPLES,
            );
            let mass_ok = (r.pdf_integral - r.valid_fraction).abs() < 5e-3;
            if !r.passes(alpha) || !mass_ok {
                failures.push(format!("{name} wo={wo}: {r:?}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Mean throughput weight over `n` samples (delta and non-delta).
fn albedo(bsdf: &Bsdf, wo: Vec3, n: usize) -> Vec3 {
    let mut rng = Pcg32::new(9, 2);
    let mut sum = glam::DVec3::ZERO;
    for _ in 0..n {
        let u_lobe = rng.next_f32();
        if let Some(s) = bsdf.sample(wo, u_lobe, rng.next_vec2()) {
            sum += s.weight().as_dvec3();
        }
    }
    (sum / n as f64).as_vec3()
}

#[test]
fn white_base_coat_albedo_is_at_most_one() {
    for (eta, alpha) in [(1.5f32, 0.0f32), (1.5, 0.05), (1.33, 0.0), (1.33, 0.3)] {
        let bsdf = coated(lambert(1.0), eta, alpha);
        for wo in wos() {
            let a = albedo(&bsdf, wo, 200_000);
            assert!(a.max_element() <= 1.005, "η={eta} α={alpha} wo={wo}: {a}");
            // A white base loses only what the coat's Fresnel keeps out: more
            // than 85% comes back at all but grazing angles.
            if wo.z.abs() > 0.5 {
                assert!(a.min_element() > 0.85, "η={eta} α={alpha} wo={wo}: {a}");
            }
        }
    }
    // Smooth coat over a white Lambert, closed form: F(θo) + (1 − F(θo))·
    // ∫(1 − F(θi)) cosθi/π dωi, the integral by the midpoint rule in cos θi.
    let (eta, wo) = (1.5f32, dir(60.0, 0.0));
    let n = 100_000;
    let hemi: f64 = (0..n)
        .map(|i| {
            let c = (i as f64 + 0.5) / n as f64;
            2.0 * c * (1.0 - fr_dielectric(c as f32, eta) as f64) / n as f64
        })
        .sum();
    let f_o = fr_dielectric(wo.z, eta) as f64;
    let expect = f_o + (1.0 - f_o) * hemi;
    let a = albedo(&coated(lambert(1.0), eta, 0.0), wo, 400_000).x as f64;
    assert!((a - expect).abs() < 3e-3, "{a} vs {expect}");
}

#[test]
fn coat_is_reciprocal() {
    let mut rng = Pcg32::new(3, 7);
    for (name, bsdf) in line_up() {
        for _ in 0..2000 {
            let wo = shaders_cpu::sampling::sample_uniform_sphere(rng.next_vec2());
            let mut wi = shaders_cpu::sampling::sample_uniform_sphere(rng.next_vec2());
            if wi.z * wo.z < 0.0 {
                wi.z = -wi.z;
            }
            let (a, b) = (bsdf.eval(wo, wi), bsdf.eval(wi, wo));
            assert!(
                (a - b).length() <= 1e-4 * a.length().max(1.0),
                "{name} {wo} {wi}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn coat_sample_agrees_with_eval_and_pdf() {
    let mut rng = Pcg32::new(5, 9);
    for (name, bsdf) in line_up() {
        for wo in wos() {
            for _ in 0..5000 {
                let Some(s) = bsdf.sample(wo, rng.next_f32(), rng.next_vec2()) else {
                    continue;
                };
                assert!(s.wi.z * wo.z > 0.0, "{name}: coats only reflect");
                if s.delta {
                    // eval at the mirror direction is the base's part only.
                    continue;
                }
                let (f, pdf) = (bsdf.eval(wo, s.wi), bsdf.pdf(wo, s.wi));
                assert!((pdf - s.pdf).abs() <= 2e-3 * pdf + 1e-6, "{name}");
                assert!((f - s.f).abs().max_element() <= 2e-3 * f.max_element() + 1e-6);
            }
        }
    }
    // A smooth coat over a mirror is all delta; a rough one is not.
    assert!(coated(gold_base(0.0), 1.5, 0.0).is_delta());
    assert!(!coated(gold_base(0.0), 1.5, 0.1).is_delta());
    let s = coated(lambert(0.5), 1.33, 0.0)
        .sample(Vec3::Z, 0.0, Vec2::splat(0.5))
        .unwrap();
    assert!(s.delta && (s.wi - Vec3::Z).length() < 1e-6);
}
