//! Chi-square goodness-of-fit of every rough BSDF's `sample` against its `pdf`
//! over the whole sphere (Mitsuba 3 `chi2.py` recipe, pbrt-v4 `bsdfs_test.cpp`),
//! plus self-tests that the harness rejects a wrong pdf.

mod common;

use common::{rough_bsdfs, wos};
use shaders_cpu::bsdf::Bsdf;
use shaders_cpu::stats::{chi2_test, sidak_threshold, Chi2Result};

/// Chi-square runs in this file (5 BSDFs × 4 outgoing directions).
const N_TESTS: usize = 20;
const N_SAMPLES: usize = 1_000_000;

fn run(bsdf: &Bsdf, wo: glam::Vec3) -> Chi2Result {
    chi2_test(
        |u, u_lobe| bsdf.sample(wo, u_lobe, u).map(|s| s.wi),
        |wi| bsdf.pdf(wo, wi),
        N_SAMPLES,
    )
}

/// Runs the chi-square test for every BSDF whose name starts with `family`
/// and every outgoing direction; panics with all failures listed.
fn check_family(family: &str) {
    let alpha = sidak_threshold(0.01, N_TESTS);
    let mut failures = Vec::new();
    for (name, bsdf) in rough_bsdfs()
        .into_iter()
        .filter(|(n, _)| n.starts_with(family))
    {
        for wo in wos() {
            let r = run(&bsdf, wo);
            // The pdf must integrate to the fraction of successful samples.
            let mass_ok = (r.pdf_integral - r.valid_fraction).abs() < 5e-3;
            if !r.passes(alpha) || !mass_ok {
                failures.push(format!("{name} wo={wo}: {r:?}"));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn lambert_sampling_matches_pdf_chi2() {
    check_family("lambert");
}

#[test]
fn rough_conductor_sampling_matches_pdf_chi2() {
    check_family("conductor");
}

#[test]
fn rough_dielectric_sampling_matches_pdf_chi2() {
    check_family("dielectric");
}

#[test]
fn chi2_rejects_pdf_scaled_by_1_1() {
    let bsdf = common::gold(0.5);
    let wo = common::dir(30.0, 0.0);
    let r = chi2_test(
        |u, l| bsdf.sample(wo, l, u).map(|s| s.wi),
        |wi| 1.1 * bsdf.pdf(wo, wi),
        N_SAMPLES,
    );
    assert!(!r.passes(1e-6), "{r:?}");
}

#[test]
fn chi2_rejects_conductor_checked_against_other_roughness() {
    // A subtly wrong model: samples of α = 0.5 against the pdf of α = 0.45.
    let (a, b) = (common::gold(0.5), common::gold(0.45));
    let wo = common::dir(60.0, 0.0);
    let r = chi2_test(
        |u, l| a.sample(wo, l, u).map(|s| s.wi),
        |wi| b.pdf(wo, wi),
        N_SAMPLES,
    );
    assert!(!r.passes(1e-6), "{r:?}");
}
