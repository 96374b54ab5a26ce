//! The microfacet-based normal map (`bsdf::normal_map`, Schüssler et al.
//! 2017) as a furnace: a white Lambertian facet under any perturbed normal
//! reflects all light (every sample's weight is exactly the albedo; the
//! eval integrates to it), half of it at albedo 0.5; the sampling matches
//! the pdf (chi-square); nothing leaves below the geometric surface.

use glam::{Vec2, Vec3};
use shaders_cpu::bsdf::{Bsdf, Facet};
use shaders_cpu::sampling::{sample_uniform_hemisphere, uniform_hemisphere_pdf};
use shaders_cpu::stats::{chi2_test, sidak_threshold};

/// A unit vector at polar angle `theta_deg` from z and azimuth `phi_deg`.
fn dir(theta_deg: f32, phi_deg: f32) -> Vec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    Vec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

fn lambert_mapped(albedo: f32, wp: Vec3) -> Bsdf {
    Bsdf::NormalMapped {
        facet: Facet::Lambert {
            albedo: Vec3::splat(albedo),
        },
        wp,
    }
}

/// Perturbed normals: none, moderate, strong and past the 72° limit.
fn normals() -> Vec<Vec3> {
    vec![
        Vec3::Z,
        dir(15.0, 30.0),
        dir(35.0, 200.0),
        dir(60.0, 100.0),
        dir(80.0, 0.0),
    ]
}

/// Views: normal, oblique, grazing on the normal's side and the far side.
fn views() -> Vec<Vec3> {
    vec![
        dir(0.0, 0.0),
        dir(40.0, 10.0),
        dir(75.0, 100.0),
        dir(85.0, 180.0),
    ]
}

/// A 2D low-discrepancy point (R2 sequence) and a lobe number.
fn r2(i: usize) -> (Vec2, f32) {
    let (g1, g2, g3) = (0.754_877_7_f64, 0.569_840_3_f64, 0.438_579_f64);
    let f = |g: f64| ((0.5 + g * i as f64).fract()) as f32;
    (Vec2::new(f(g1), f(g2)), f(g3))
}

#[test]
fn white_lambert_under_any_normal_returns_every_sample_with_weight_one() {
    for albedo in [1.0f32, 0.5] {
        for wp in normals() {
            for wo in views() {
                let bsdf = lambert_mapped(albedo, wp);
                let n = 20_000;
                let (mut sum, mut lost) = (0.0f64, 0usize);
                for i in 0..n {
                    let (u, l) = r2(i);
                    match bsdf.sample(wo, l, u) {
                        Some(s) => {
                            assert!(s.wi.z > 0.0, "below the surface: {s:?}");
                            let w = s.weight().x;
                            assert!(
                                (w - albedo).abs() < 2e-4 * albedo.max(1.0),
                                "weight {w} wp {wp} wo {wo}"
                            );
                            sum += w as f64;
                        }
                        None => lost += 1,
                    }
                }
                assert!(
                    lost * 1000 < n,
                    "wp {wp} wo {wo}: {lost} of {n} samples lost"
                );
                let mean = sum / n as f64;
                assert!(
                    (mean - albedo as f64).abs() < 2e-3,
                    "wp {wp} wo {wo}: {mean}"
                );
            }
        }
    }
}

#[test]
fn eval_and_pdf_integrate_to_the_albedo_and_one() {
    // ∫ f cosθ dω and ∫ pdf dω over the upper hemisphere, uniform samples.
    let n = 400_000;
    for wp in normals() {
        for wo in views() {
            let bsdf = lambert_mapped(0.5, wp);
            let (mut e, mut p) = (0.0f64, 0.0f64);
            for i in 0..n {
                let wi = sample_uniform_hemisphere(r2(i).0);
                e += (bsdf.eval(wo, wi).x * wi.z) as f64;
                p += bsdf.pdf(wo, wi) as f64;
            }
            let inv = 1.0 / (n as f64 * uniform_hemisphere_pdf() as f64);
            let (e, p) = (e * inv, p * inv);
            assert!((e - 0.5).abs() < 5e-3, "wp {wp} wo {wo}: reflectance {e}");
            assert!((p - 1.0).abs() < 1e-2, "wp {wp} wo {wo}: pdf mass {p}");
            // Nothing below the geometric surface.
            let below = -dir(30.0, 40.0);
            assert_eq!(bsdf.eval(wo, below), Vec3::ZERO);
            assert_eq!(bsdf.pdf(wo, below), 0.0);
        }
    }
}

#[test]
fn without_perturbation_it_is_the_facet_itself() {
    let plain = Bsdf::Lambert {
        albedo: Vec3::splat(0.4),
    };
    let mapped = plain.normal_mapped(Vec3::Z);
    for wo in views() {
        for k in 0..50 {
            let wi = sample_uniform_hemisphere(r2(k).0);
            let (a, b) = (plain.eval(wo, wi), mapped.eval(wo, wi));
            assert!((a - b).abs().max_element() < 1e-6, "{a} {b}");
            assert!((plain.pdf(wo, wi) - mapped.pdf(wo, wi)).abs() < 1e-5);
        }
    }
    // Glass and mirrors keep their own model.
    let glass = Bsdf::Dielectric {
        eta: 1.5,
        alpha: 0.0,
        tint: Vec3::ONE,
    };
    assert_eq!(glass.normal_mapped(dir(20.0, 0.0)), glass);
}

#[test]
fn sampling_matches_pdf_chi2_for_lambert_and_rough_metal_facets() {
    let facets = [
        Facet::Lambert {
            albedo: Vec3::splat(0.7),
        },
        Facet::Conductor {
            eta: Vec3::splat(1.5),
            k: Vec3::splat(3.0),
            alpha: 0.3,
        },
    ];
    let cases: Vec<(Facet, Vec3, Vec3)> = facets
        .iter()
        .flat_map(|f| {
            [
                (*f, dir(30.0, 0.0), dir(50.0, 180.0)),
                (*f, dir(50.0, 90.0), dir(20.0, 60.0)),
            ]
        })
        .collect();
    let alpha = sidak_threshold(0.01, cases.len());
    for (facet, wp, wo) in cases {
        let bsdf = Bsdf::NormalMapped { facet, wp };
        let r = chi2_test(
            |u, l| bsdf.sample(wo, l, u).map(|s| s.wi),
            |wi| bsdf.pdf(wo, wi),
            1_000_000,
        );
        assert!(r.passes(alpha), "{facet:?} wp {wp} wo {wo}: {r:?}");
        assert!((r.pdf_integral - r.valid_fraction).abs() < 5e-3, "{r:?}");
    }
}

#[test]
fn fused_eval_pdf_gives_the_bits_of_eval_and_pdf() {
    // Every facet model under every normal and view, directions over the
    // hemisphere: one groove walk must give what the two separate ones do.
    let facets = [
        Facet::Lambert {
            albedo: Vec3::new(0.7, 0.4, 0.2),
        },
        Facet::Conductor {
            eta: Vec3::new(0.2, 0.9, 1.1),
            k: Vec3::new(3.9, 2.4, 2.2),
            alpha: 0.2,
        },
    ];
    let mut nonzero = 0;
    for facet in facets {
        for wp in normals() {
            for wo in views() {
                let bsdf = Bsdf::NormalMapped { facet, wp };
                for i in 0..64 {
                    let wi = sample_uniform_hemisphere(r2(i).0);
                    let (f, pdf) = bsdf.eval_pdf(wo, wi);
                    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
                    assert_eq!(bits(f), bits(bsdf.eval(wo, wi)), "{wp} {wo} {wi}");
                    assert_eq!(pdf.to_bits(), bsdf.pdf(wo, wi).to_bits(), "{wp} {wo} {wi}");
                    nonzero += (pdf > 0.0) as usize;
                }
            }
        }
    }
    assert!(nonzero > 1000, "{nonzero} directions with a pdf");
}

#[test]
fn sampled_directions_are_unit_for_normals_a_hair_off_z() {
    // Tilts of a few milliradians: cos θp rounds to within an ulp or two
    // of 1, where sin θp = √(1 − cos²) loses most of its digits. The
    // groove's tangent facet ωt must still be a unit vector, or its
    // mirror lengthens the directions it reflects (a phase function then
    // sees a cosine above 1).
    let mut worst = 0.0f32;
    for k in 1..=60 {
        let theta_deg = 0.004 * k as f32;
        let wp = dir(theta_deg, 37.0 * k as f32);
        for wo in views() {
            let bsdf = lambert_mapped(0.8, wp);
            for i in 0..2_000 {
                let (u, l) = r2(i);
                if let Some(s) = bsdf.sample(wo, l, u) {
                    worst = worst.max((s.wi.length() - 1.0).abs());
                }
            }
        }
    }
    assert!(worst < 1e-5, "|wi| off 1 by up to {worst}");
}
