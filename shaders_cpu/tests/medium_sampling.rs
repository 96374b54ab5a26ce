//! Medium sampling: HG chi-square and ∫pdf = 1, height-fog optical depth and
//! free-flight sampling against numerical integration, equiangular pdf
//! normalisation.

use glam::Vec3;
use shaders_cpu::medium::{Density, Equiangular, HenyeyGreenstein, Medium};
use shaders_cpu::stats::{chi2_sf, chi2_test, sidak_threshold, Pcg32};

fn height_fog(z_min: f64, z_max: f64) -> Medium {
    Medium {
        density: Density::HeightExp {
            sigma0: 0.08,
            z0: 0.5,
            height_scale: 6.0,
        },
        albedo: Vec3::splat(0.99),
        phase: HenyeyGreenstein { g: 0.85 },
        z_min,
        z_max,
    }
}

#[test]
fn hg_sampling_matches_pdf_chi2() {
    let gs = [-0.5f32, 0.0, 0.3, 0.85];
    let alpha = sidak_threshold(0.01, gs.len());
    let wo = Vec3::new(0.3, -0.2, 0.9).normalize();
    for g in gs {
        let p = HenyeyGreenstein { g };
        let r = chi2_test(|u, _| Some(p.sample(wo, u).wi), |wi| p.pdf(wo, wi), 500_000);
        assert!(r.passes(alpha), "g = {g}: {r:?}");
        assert!((r.pdf_integral - 1.0).abs() < 2e-3, "g = {g}: {r:?}");
    }
}

#[test]
fn hg_sample_pdf_equals_eval() {
    let p = HenyeyGreenstein { g: 0.85 };
    let wo = Vec3::new(0.0, 0.6, 0.8);
    let mut rng = Pcg32::new(7, 1);
    for _ in 0..1000 {
        let s = p.sample(wo, rng.next_vec2());
        let e = p.eval(wo, s.wi);
        assert!((s.pdf - e).abs() <= 1e-3 * e, "{} vs {e}", s.pdf);
    }
}

/// Composite Simpson of σ_t along the ray.
fn tau_numeric(m: &Medium, o: Vec3, d: Vec3, t_max: f32) -> f64 {
    let n = 20_000;
    let h = t_max as f64 / n as f64;
    let f = |k: usize| m.sigma_t(o + d * (k as f64 * h) as f32);
    let mut s = f(0) + f(n);
    for k in 1..n {
        s += if k % 2 == 1 { 4.0 } else { 2.0 } * f(k);
    }
    s * h / 3.0
}

#[test]
fn height_fog_transmittance_matches_quadrature() {
    let m = height_fog(f64::NEG_INFINITY, f64::INFINITY);
    let o = Vec3::new(0.0, 0.0, 1.5);
    for d in [
        Vec3::new(1.0, 0.0, 0.0),
        Vec3::new(0.8, 0.0, 0.6),
        Vec3::new(0.6, 0.0, -0.08),
        Vec3::new(0.0, 0.0, 1.0),
        Vec3::new(0.99, 0.0, 1e-4),
    ] {
        let d = d.normalize();
        for t in [0.5f32, 10.0, 80.0] {
            let exact = m.optical_depth(o, d, t);
            let num = tau_numeric(&m, o, d, t);
            assert!(
                (exact - num).abs() <= 1e-6 * num.max(1e-3),
                "d {d} t {t}: {exact} vs {num}"
            );
        }
    }
}

/// Outcome of a free-flight Pearson test (all fields are reported through
/// `Debug` in failure messages).
#[derive(Debug)]
#[allow(dead_code)]
struct FreeFlightChi2 {
    statistic: f64,
    /// Categories used − 1.
    dof: usize,
    p_value: f64,
    /// Fraction of rays that passed without a collision.
    passed: f64,
}

/// Pearson chi-square of `n` collision distances sampled from `sampled` along
/// (o, d, t_max) against the exact probabilities of `model`: one category per
/// distance bin, ∫pdf = Tr(a) − Tr(b), plus the pass-through category Tr(t_max).
/// Bins `model` cannot reach (expected count 0, below the slab) must stay
/// empty and are not categories; the degrees of freedom are the categories
/// actually used minus one, and the p-value is the χ² survival function.
fn free_flight_chi2(
    sampled: &Medium,
    model: &Medium,
    o: Vec3,
    d: Vec3,
    t_max: f32,
    bins: usize,
    n: usize,
) -> FreeFlightChi2 {
    let mut hist = vec![0u64; bins];
    let mut passed = 0u64;
    let mut rng = Pcg32::new(11, 3);
    for _ in 0..n {
        let s = sampled.sample_distance(o, d, t_max, rng.next_f32());
        if s.scattered {
            assert!(s.t >= 0.0 && s.t <= t_max);
            let pdf = sampled.distance_pdf(o, d, s.t);
            assert!((s.pdf - pdf).abs() <= 1e-4 * pdf, "{} vs {pdf}", s.pdf);
            hist[((s.t / t_max * bins as f32) as usize).min(bins - 1)] += 1;
        } else {
            passed += 1;
        }
    }
    let width = t_max / bins as f32;
    let cdf = |t: f32| 1.0 - model.tr(o, d, t) as f64;
    let mut categories = vec![(passed, n as f64 * model.tr(o, d, t_max) as f64)];
    for (k, &h) in hist.iter().enumerate() {
        let e = n as f64 * (cdf((k + 1) as f32 * width) - cdf(k as f32 * width));
        if e < 1e-9 {
            assert_eq!(h, 0, "bin {k} cannot be reached but holds {h} samples");
            continue;
        }
        categories.push((h, e));
    }
    // Pearson's χ² approximation needs ≥ 5 expected per category.
    assert!(categories.iter().all(|&(_, e)| e >= 5.0), "{categories:?}");
    let statistic: f64 = categories
        .iter()
        .map(|&(h, e)| (h as f64 - e).powi(2) / e)
        .sum();
    let dof = categories.len() - 1;
    FreeFlightChi2 {
        statistic,
        dof,
        p_value: chi2_sf(statistic, dof),
        passed: passed as f64 / n as f64,
    }
}

/// The free-flight test's ray: from z = 8 down through bounded height fog,
/// leaving the slab (z_min = −2) at t = 10/|d_z| ≈ 31.6 < t_max = 40.
fn free_flight_setup() -> (Medium, Vec3, Vec3, f32) {
    let m = height_fog(-2.0, 30.0);
    let o = Vec3::new(0.0, 0.0, 8.0);
    let d = Vec3::new(0.9, 0.0, -0.3).normalize();
    (m, o, d, 40.0)
}

const FREE_FLIGHT_BINS: usize = 40;
const FREE_FLIGHT_SAMPLES: usize = 400_000;

#[test]
fn free_flight_histogram_matches_pdf() {
    // Collision distances of a downward-slanting ray in bounded height fog:
    // histogram vs ∫pdf per bin (exact), plus the pass-through probability.
    let (m, o, d, t_max) = free_flight_setup();
    let r = free_flight_chi2(&m, &m, o, d, t_max, FREE_FLIGHT_BINS, FREE_FLIGHT_SAMPLES);
    // Bins of width 1 reach the slab exit at t ≈ 31.6: bins 0..=31 plus the
    // pass-through category are 33 categories, 32 degrees of freedom.
    assert_eq!(r.dof, 32, "{r:?}");
    assert!(r.p_value >= 1e-3, "{r:?}");
    let p_pass = m.tr(o, d, t_max) as f64;
    let se = (p_pass * (1.0 - p_pass) / FREE_FLIGHT_SAMPLES as f64).sqrt();
    assert!((r.passed - p_pass).abs() < 4.0 * se, "{r:?} vs {p_pass}");
}

#[test]
fn free_flight_chi2_rejects_wrong_density() {
    // Self-test: the same samples checked against a medium whose extinction
    // is 5% too high, or whose scale height is 5% too large, must fail.
    let (m, o, d, t_max) = free_flight_setup();
    let mut denser = m;
    let mut taller = m;
    let Density::HeightExp {
        sigma0,
        z0,
        height_scale,
    } = m.density
    else {
        unreachable!()
    };
    denser.density = Density::HeightExp {
        sigma0: sigma0 * 1.05,
        z0,
        height_scale,
    };
    taller.density = Density::HeightExp {
        sigma0,
        z0,
        height_scale: height_scale * 1.05,
    };
    for wrong in [denser, taller] {
        let r = free_flight_chi2(
            &m,
            &wrong,
            o,
            d,
            t_max,
            FREE_FLIGHT_BINS,
            FREE_FLIGHT_SAMPLES,
        );
        assert!(r.p_value < 1e-6, "{:?}: {r:?}", wrong.density);
    }
}

#[test]
fn equiangular_pdf_integrates_to_one() {
    for (a, b, q) in [
        (0.0f32, 30.0f32, Vec3::new(5.0, 2.0, 0.0)),
        (1.0, 200.0, Vec3::new(-3.0, 0.5, 0.2)),
        (0.0, 10.0, Vec3::new(4.0, 1e-3, 0.0)),
    ] {
        let e = Equiangular::new(Vec3::ZERO, Vec3::X, a, b, q);
        let n = 200_000;
        let h = (b - a) as f64 / n as f64;
        let sum: f64 = (0..n)
            .map(|k| e.pdf(a + ((k as f64 + 0.5) * h) as f32) as f64 * h)
            .sum();
        assert!((sum - 1.0).abs() < 2e-3, "[{a}, {b}] {q}: {sum}");
        let (t, pdf) = e.sample(0.37);
        assert!(t > a && t < b && (pdf - e.pdf(t)).abs() < 1e-6);
    }
}
