//! Sky sampling: chi-square of `Sky::sample` against `Sky::pdf`, consistency of
//! the returned radiance/pdf, `le` finite and ≥ 0, and an importance-sampled
//! estimate of the mean radiance matching the closed form.

use glam::Vec3;
use shaders_cpu::sky::Sky;
use shaders_cpu::stats::{chi2_test, sidak_threshold, Pcg32};

fn skies() -> Vec<(&'static str, Sky)> {
    let gradient = |ground: Vec3| Sky::Gradient {
        zenith: Vec3::new(0.1, 0.3, 1.2),
        horizon: Vec3::new(0.9, 1.0, 1.1),
        ground,
    };
    vec![
        (
            "constant",
            Sky::Constant {
                le: Vec3::new(0.5, 0.6, 0.7),
            },
        ),
        ("gradient", gradient(Vec3::splat(0.2))),
        ("gradient, black ground", gradient(Vec3::ZERO)),
        (
            "black",
            Sky::Gradient {
                zenith: Vec3::ZERO,
                horizon: Vec3::ZERO,
                ground: Vec3::ZERO,
            },
        ),
    ]
}

#[test]
fn sky_sampling_matches_pdf_chi2() {
    let skies = skies();
    let alpha = sidak_threshold(0.01, skies.len());
    for (name, sky) in skies {
        let r = chi2_test(|u, _| Some(sky.sample(u).0), |d| sky.pdf(d), 500_000);
        assert!(r.passes(alpha), "{name}: {r:?}");
        assert!((r.pdf_integral - 1.0).abs() < 1e-3, "{name}: {r:?}");
    }
}

#[test]
fn chi2_rejects_sky_pdf_of_other_sky() {
    // Constant-sky (uniform) pdf does not describe the gradient's cosine lobe.
    let (_, gradient) = skies()[1];
    let (_, constant) = skies()[0];
    let r = chi2_test(
        |u, _| Some(gradient.sample(u).0),
        |d| constant.pdf(d),
        500_000,
    );
    assert!(!r.passes(1e-6), "{r:?}");
}

#[test]
fn sky_samples_are_consistent_and_le_is_finite() {
    let mut rng = Pcg32::new(11, 2);
    for (name, sky) in skies() {
        for _ in 0..20_000 {
            let (dir, le, pdf) = sky.sample(rng.next_vec2());
            assert!((dir.length() - 1.0).abs() < 1e-4, "{name}");
            assert!(le.is_finite() && le.min_element() >= 0.0, "{name}: {le}");
            assert_eq!(le, sky.le(dir));
            assert!(
                pdf > 0.0 && (pdf - sky.pdf(dir)).abs() <= 1e-6 * pdf,
                "{name}"
            );
        }
        // Wherever le > 0 the pdf must be positive, horizon included.
        for d in [Vec3::Z, Vec3::X, -Vec3::Z, Vec3::new(0.0, 1.0, -1e-7)] {
            assert!(sky.pdf(d) > 0.0, "{name} {d}");
        }
    }
}

#[test]
fn importance_sampled_mean_matches_closed_form() {
    // E[le/pdf] = ∫ le dω = 4π · mean_le.
    let mut rng = Pcg32::new(12, 3);
    for (name, sky) in skies() {
        let n = 200_000;
        let mut sum = Vec3::ZERO.as_dvec3();
        for _ in 0..n {
            let (_, le, pdf) = sky.sample(rng.next_vec2());
            sum += (le / pdf).as_dvec3();
        }
        let est = sum / n as f64 / (4.0 * std::f64::consts::PI);
        let exact = sky.mean_le().as_dvec3();
        assert!(
            (est - exact).length() < 5e-3 * exact.length().max(0.1),
            "{name}: {est} vs {exact}"
        );
    }
}
