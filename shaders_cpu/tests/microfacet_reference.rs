//! Absolute values of the rough conductor and rough dielectric BSDFs against an
//! independent textbook microfacet model written here in f64 (not copied from
//! `src/bsdf`):
//!
//! * D: GGX / Trowbridge–Reitz in Walter et al. 2007's form
//!   D = α² / (π ((α² − 1) cos²θm + 1)²);
//! * Λ: Heitz 2014 eq. 86, Λ = (−1 + √(1 + 1/a²))/2 with a = 1/(α tanθ), and
//!   the height-correlated G = 1/(1 + Λ(ωo) + Λ(ωi)) that `microfacet.rs`
//!   documents (pbrt-v4 eq. 9.27, used for reflection and transmission alike);
//! * conductor Fresnel: pbrt-v3 `FrConductor` (real-arithmetic closed form of
//!   the complex-IOR Fresnel equations), the code uses complex arithmetic;
//! * dielectric Fresnel: Walter 2007 eq. 22 (the g/c form);
//! * BTDF: Walter 2007 eq. 21 with η_o² in the numerator, which is pbrt-v4's
//!   radiance-mode BTDF (its 1/η'² scaling folded in), generalised half vector
//!   h ∝ η_o ωo + η_i ωi (pbrt-v4 eq. 9.34).
//!
//! Checks: (a) `eval` pointwise against the reference; (b) the directional
//! albedo ∫ f |cosθi| dωi of `eval` by deterministic quadrature over ωi against
//! the same albedo of the reference integrated over microfacet normals
//! (ωi = reflect/refract(ωo, ωm), with the Jacobians written out), and against
//! the mean sampling weight of `sample`; (c) physical sanity bounds.

use glam::{DVec3, Vec3};
use shaders_cpu::bsdf::Bsdf;
use shaders_cpu::stats::Pcg32;
use std::f64::consts::PI;

// ---------------------------------------------------------------------------
// Independent reference model (f64).
// ---------------------------------------------------------------------------

/// GGX normal distribution, Walter 2007 eq. 33 rewritten in cos θm.
fn ref_d(alpha: f64, m: DVec3) -> f64 {
    if m.z <= 0.0 {
        return 0.0;
    }
    let a2 = alpha * alpha;
    let c2 = m.z * m.z;
    let t = (a2 - 1.0) * c2 + 1.0;
    a2 / (PI * t * t)
}

/// Smith Λ for GGX (Heitz 2014 eq. 86).
fn ref_lambda(alpha: f64, w: DVec3) -> f64 {
    let c = w.z.abs();
    let s = (1.0 - c * c).max(0.0).sqrt();
    if s == 0.0 {
        return 0.0;
    }
    if c == 0.0 {
        return f64::INFINITY;
    }
    let a = c / (alpha * s); // 1 / (α tanθ)
    (-1.0 + (1.0 + 1.0 / (a * a)).sqrt()) / 2.0
}

/// Height-correlated masking-shadowing.
fn ref_g(alpha: f64, wo: DVec3, wi: DVec3) -> f64 {
    1.0 / (1.0 + ref_lambda(alpha, wo) + ref_lambda(alpha, wi))
}

/// Conductor Fresnel, pbrt-v3 `FrConductor` with η_i = 1.
fn ref_fr_conductor(cos_i: f64, eta: f64, k: f64) -> f64 {
    let c2 = cos_i * cos_i;
    let s2 = 1.0 - c2;
    let (eta2, k2) = (eta * eta, k * k);
    let t0 = eta2 - k2 - s2;
    let a2b2 = (t0 * t0 + 4.0 * eta2 * k2).sqrt();
    let t1 = a2b2 + c2;
    let a = (0.5 * (a2b2 + t0)).max(0.0).sqrt();
    let t2 = 2.0 * cos_i * a;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = c2 * a2b2 + s2 * s2;
    let t4 = t2 * s2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    0.5 * (rs + rp)
}

/// Dielectric Fresnel for incidence cosine `c` ≥ 0 on the side of index n1,
/// `eta` = n2/n1 (Walter 2007 eq. 22); 1 under total internal reflection.
fn ref_fr_dielectric(c: f64, eta: f64) -> f64 {
    let g2 = eta * eta - 1.0 + c * c;
    if g2 < 0.0 {
        return 1.0;
    }
    let g = g2.sqrt();
    let x = (g - c) / (g + c);
    let y = (c * (g + c) - 1.0) / (c * (g - c) + 1.0);
    0.5 * x * x * (1.0 + y * y)
}

/// Torrance–Sparrow conductor, two-sided by mirroring through z = 0.
fn ref_conductor(eta: f64, k: f64, alpha: f64, wo: DVec3, wi: DVec3) -> f64 {
    if wo.z * wi.z <= 0.0 {
        return 0.0;
    }
    let flip = |v: DVec3| DVec3::new(v.x, v.y, v.z.abs());
    let (wo, wi) = (flip(wo), flip(wi));
    let h = (wo + wi).normalize();
    ref_d(alpha, h) * ref_fr_conductor(wo.dot(h), eta, k) * ref_g(alpha, wo, wi)
        / (4.0 * wo.z * wi.z)
}

/// Index of refraction of the side `w` is on (outside = +z has index 1).
fn side_ior(eta: f64, w: DVec3) -> f64 {
    if w.z > 0.0 {
        1.0
    } else {
        eta
    }
}

/// Rough dielectric in radiance mode; returns (reflection, transmission) with
/// exactly one of them possibly non-zero. `eta` is inside/outside.
fn ref_dielectric(eta: f64, alpha: f64, wo: DVec3, wi: DVec3) -> (f64, f64) {
    if wo.z == 0.0 || wi.z == 0.0 {
        return (0.0, 0.0);
    }
    let n_o = side_ior(eta, wo);
    let n_other = if wo.z > 0.0 { eta } else { 1.0 };
    let reflect = wo.z * wi.z > 0.0;
    let n_i = if reflect { n_o } else { n_other };
    let h = n_o * wo + n_i * wi;
    if h.length_squared() == 0.0 {
        return (0.0, 0.0);
    }
    let mut h = h.normalize();
    if h.z < 0.0 {
        h = -h;
    }
    // Microfacets must face both directions from their own side.
    if h.dot(wo) * wo.z <= 0.0 || h.dot(wi) * wi.z <= 0.0 {
        return (0.0, 0.0);
    }
    let f = ref_fr_dielectric(wo.dot(h).abs(), n_other / n_o);
    let (d, g) = (ref_d(alpha, h), ref_g(alpha, wo, wi));
    if reflect {
        (d * f * g / (4.0 * (wo.z * wi.z).abs()), 0.0)
    } else {
        let (ih, oh) = (wi.dot(h), wo.dot(h));
        let denom = (n_i * ih + n_o * oh).powi(2);
        let ft = (ih * oh).abs() / (wi.z * wo.z).abs() * n_o * n_o * (1.0 - f) * g * d / denom;
        (0.0, ft)
    }
}

/// Snell refraction of `wo` through a microfacet with normal `m` (either
/// orientation) from index `n1` (wo's side) into `n2`; `None` under TIR.
/// Tangential part scales by n1/n2, normal part from the unit length.
fn ref_refract(wo: DVec3, m: DVec3, n1: f64, n2: f64) -> Option<DVec3> {
    let m = if wo.dot(m) < 0.0 { -m } else { m };
    let c = wo.dot(m);
    let tangential = -(wo - c * m) * (n1 / n2);
    let t2 = tangential.length_squared();
    if t2 >= 1.0 {
        return None;
    }
    Some(tangential - (1.0 - t2).sqrt() * m)
}

fn ref_reflect(wo: DVec3, m: DVec3) -> DVec3 {
    2.0 * wo.dot(m) * m - wo
}

// ---------------------------------------------------------------------------
// Quadrature.
// ---------------------------------------------------------------------------

/// Orthonormal tangents of a unit vector.
fn tangents(p: DVec3) -> (DVec3, DVec3) {
    let helper = if p.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    let u = helper.cross(p).normalize();
    (u, p.cross(u))
}

/// ∫ g(ω) dω over the hemisphere on `pole`'s side of z = 0, in polar
/// coordinates (θ', φ') about `pole` (pole.z ≠ 0). Each φ' ray is integrated
/// exactly up to the horizon θ'_h(φ') so the cut at z = 0 is no discontinuity,
/// with θ' = θ'_h t² (midpoint in t) to resolve lobes peaked at the pole.
fn hemisphere_integral_about(pole: DVec3, nt: usize, np: usize, g: impl Fn(DVec3) -> f64) -> f64 {
    let (u, v) = tangents(pole);
    let s = pole.z.signum();
    let mut sum = 0.0;
    for j in 0..np {
        let phi = 2.0 * PI * (j as f64 + 0.5) / np as f64;
        let e = phi.cos() * u + phi.sin() * v;
        // s·z(θ') = |p.z| cosθ' + s e.z sinθ' vanishes at θ'_h.
        let theta_h = pole.z.abs().atan2(-s * e.z);
        let mut line = 0.0;
        for i in 0..nt {
            let t = (i as f64 + 0.5) / nt as f64;
            let th = theta_h * t * t;
            let w = th.cos() * pole + th.sin() * e;
            line += g(w) * th.sin() * 2.0 * theta_h * t;
        }
        sum += line / nt as f64;
    }
    sum * 2.0 * PI / np as f64
}

const NT: usize = 400;
const NP: usize = 128;

fn f32v(w: DVec3) -> Vec3 {
    w.as_vec3()
}

/// Albedo of the code's `eval`, channel `ch`, integrated over ωi:
/// (reflected, transmitted in radiance units).
fn code_albedo(bsdf: &Bsdf, wo: DVec3, ch: usize) -> (f64, f64) {
    let wo32 = f32v(wo);
    let integrand = |wi: DVec3| bsdf.eval(wo32, f32v(wi))[ch] as f64 * wi.z.abs();
    let mirror = DVec3::new(-wo.x, -wo.y, wo.z);
    let r = hemisphere_integral_about(mirror, NT, NP, integrand);
    let t = match *bsdf {
        Bsdf::Dielectric { eta, .. } => {
            let (n1, n2) = (
                side_ior(eta as f64, wo),
                if wo.z > 0.0 { eta as f64 } else { 1.0 },
            );
            let pole =
                ref_refract(wo, DVec3::Z, n1, n2).unwrap_or(DVec3::new(0.0, 0.0, -wo.z.signum()));
            hemisphere_integral_about(pole, NT, NP, integrand)
        }
        _ => 0.0,
    };
    (r, t)
}

/// Reference albedo integrated over microfacet normals ωm (upper hemisphere):
/// f |cosθi| dωi = D(ωm) |ωo·ωm| / |cosθo| · (F G, or (1−F) G / η'²) dωm,
/// from the reflection Jacobian dωi = 4|ωo·ωm| dωm and the refraction one
/// dωi = (η_o ωo·ωm + η_i ωi·ωm)² / (η_i² |ωi·ωm|) dωm (Walter 2007 eqs. 14, 17).
/// `fresnel(cos θ between ωo and ωm)` lets the conductor and the dielectric
/// share it.
fn reference_albedo_wm(
    alpha: f64,
    wo: DVec3,
    n1: f64,
    n2: f64,
    transmits: bool,
    fresnel: impl Fn(f64) -> f64,
) -> (f64, f64) {
    let visible = |m: DVec3| {
        let om = wo.dot(m);
        if om * wo.z <= 0.0 {
            return 0.0;
        }
        ref_d(alpha, m) * om.abs() / wo.z.abs()
    };
    let r = hemisphere_integral_about(DVec3::Z, NT, NP, |m| {
        let wi = ref_reflect(wo, m);
        if wi.z * wo.z <= 0.0 {
            return 0.0;
        }
        visible(m) * fresnel(wo.dot(m).abs()) * ref_g(alpha, wo, wi)
    });
    if !transmits {
        return (r, 0.0);
    }
    let t = hemisphere_integral_about(DVec3::Z, NT, NP, |m| {
        let Some(wi) = ref_refract(wo, m, n1, n2) else {
            return 0.0;
        };
        if wi.z * wo.z >= 0.0 {
            return 0.0;
        }
        visible(m) * (1.0 - fresnel(wo.dot(m).abs())) * ref_g(alpha, wo, wi)
    });
    (r, t * (n1 / n2).powi(2))
}

// ---------------------------------------------------------------------------
// Fixtures.
// ---------------------------------------------------------------------------

fn dir(theta_deg: f64, phi_deg: f64) -> DVec3 {
    let (t, p) = (theta_deg.to_radians(), phi_deg.to_radians());
    DVec3::new(t.sin() * p.cos(), t.sin() * p.sin(), t.cos())
}

fn conductor_params(b: &Bsdf) -> (Vec3, Vec3, f32) {
    match *b {
        Bsdf::Conductor { eta, k, alpha } => (eta, k, alpha),
        _ => unreachable!(),
    }
}

/// A conductor with F ≡ 1 to < 1e-4: |η + iκ| huge.
fn perfect_conductor(alpha: f32) -> Bsdf {
    Bsdf::Conductor {
        eta: Vec3::ONE,
        k: Vec3::splat(1000.0),
        alpha,
    }
}

fn conductors() -> Vec<Bsdf> {
    let mut v = Vec::new();
    for alpha in [0.05f32, 0.2, 0.5, 0.9] {
        v.push(Bsdf::conductor_preset("gold", alpha).unwrap());
    }
    v.push(Bsdf::conductor_preset("iron", 0.3).unwrap());
    v.push(Bsdf::conductor_preset("aluminium", 0.15).unwrap());
    v.push(perfect_conductor(0.4));
    v
}

fn dielectrics() -> Vec<Bsdf> {
    let mut v = Vec::new();
    for (eta, alpha) in [
        (1.5f32, 0.05f32),
        (1.5, 0.3),
        (1.5, 0.7),
        (1.0 / 1.5, 0.3),
        (1.33, 0.15),
    ] {
        v.push(Bsdf::Dielectric {
            eta,
            alpha,
            tint: Vec3::new(1.0, 0.6, 0.25),
        });
    }
    v
}

/// Direction pairs that exercise the lobe: ωo uniform on the sphere (away
/// from grazing), ωi either uniform on the sphere or obtained by reflecting or
/// refracting ωo about a microfacet normal with GGX-distributed slope, so
/// that most pairs land where f is large. Rounded to f32 before use, so the
/// reference sees exactly the directions the code sees.
fn pairs(alpha: f64, eta: f64, n: usize, seed: u64) -> Vec<(Vec3, Vec3)> {
    let mut rng = Pcg32::new(seed, 17);
    let uniform = |rng: &mut Pcg32| {
        let z = 1.0 - 2.0 * rng.next_f32() as f64;
        let phi = 2.0 * PI * rng.next_f32() as f64;
        let r = (1.0 - z * z).max(0.0).sqrt();
        DVec3::new(r * phi.cos(), r * phi.sin(), z)
    };
    let mut out = Vec::with_capacity(n);
    while out.len() < n {
        let wo = uniform(&mut rng);
        if wo.z.abs() < 0.03 {
            continue;
        }
        let kind = out.len() % 3;
        let wi = if kind == 0 {
            uniform(&mut rng)
        } else {
            // tan²θm = α² u/(1−u) is GGX's marginal in θm.
            let u = (rng.next_f32() as f64).min(0.999);
            let tan_m = alpha * (u / (1.0 - u)).sqrt();
            let phi = 2.0 * PI * rng.next_f32() as f64;
            let m = DVec3::new(tan_m * phi.cos(), tan_m * phi.sin(), 1.0).normalize();
            // (A conductor is passed eta = 1: it gets reflections only.)
            if kind == 1 || eta == 1.0 {
                ref_reflect(wo, if wo.dot(m) < 0.0 { -m } else { m })
            } else {
                let n1 = side_ior(eta, wo);
                let n2 = if wo.z > 0.0 { eta } else { 1.0 };
                match ref_refract(wo, m, n1, n2) {
                    Some(wi) => wi,
                    None => continue,
                }
            }
        };
        if wi.z.abs() < 0.03 {
            continue;
        }
        out.push((f32v(wo), f32v(wi.normalize())));
    }
    out
}

/// Relative error of `code` against `reference`, with an absolute floor far
/// below any value that matters for rendering.
fn rel_err(code: f64, reference: f64) -> f64 {
    (code - reference).abs() / reference.abs().max(1e-4)
}

/// Asserts `code` matches `reference` to 1e-3 relative (`what` names the
/// case in the message) and keeps the worst error seen in `worst`.
fn assert_eval_close(code: f32, reference: f64, worst: &mut f64, what: impl Fn() -> String) {
    let e = rel_err(code as f64, reference);
    assert!(e < 1e-3, "{}: {code} vs ref {reference}", what());
    *worst = worst.max(e);
}

// ---------------------------------------------------------------------------
// Self-tests of the reference and the quadrature.
// ---------------------------------------------------------------------------

#[test]
fn reference_model_matches_closed_forms() {
    // Conductor Fresnel at normal incidence: ((η−1)² + κ²)/((η+1)² + κ²);
    // κ = 0 is the dielectric; huge κ reflects everything at every angle.
    let (eta, k) = (0.2f64, 3.9f64);
    let f0 = ((eta - 1.0).powi(2) + k * k) / ((eta + 1.0).powi(2) + k * k);
    assert!((ref_fr_conductor(1.0, eta, k) - f0).abs() < 1e-12);
    for c in [0.05, 0.3, 0.7, 1.0] {
        assert!((ref_fr_conductor(c, 1.5, 0.0) - ref_fr_dielectric(c, 1.5)).abs() < 1e-12);
        assert!(ref_fr_conductor(c, 1.0, 1000.0) > 0.999);
    }
    assert!((ref_fr_dielectric(1.0, 1.5) - 0.04).abs() < 1e-12);
    // Total internal reflection beyond asin(1/1.5) from inside.
    let c_crit = (1.0f64 - 1.0 / 2.25).sqrt();
    assert_eq!(ref_fr_dielectric(c_crit - 1e-6, 1.0 / 1.5), 1.0);
    assert!(ref_fr_dielectric(c_crit + 1e-3, 1.0 / 1.5) < 1.0);
    // Snell: n1 sinθ1 = n2 sinθ2.
    let wo = dir(50.0, 30.0);
    let wt = ref_refract(wo, DVec3::Z, 1.0, 1.5).unwrap();
    assert!((wt.length() - 1.0).abs() < 1e-12 && wt.z < 0.0);
    assert!((wo.truncate().length() - 1.5 * wt.truncate().length()).abs() < 1e-12);
    // ∫ D cosθm dωm = 1, and ∫ D_ωo(ωm) dωm = 1 with D_ωo = G1 D max(0, ωo·ωm)/cosθo.
    for alpha in [0.05, 0.3, 0.9] {
        let proj = hemisphere_integral_about(DVec3::Z, NT, NP, |m| ref_d(alpha, m) * m.z);
        assert!((proj - 1.0).abs() < 1e-4, "α {alpha}: {proj}");
        for theta in [0.0, 45.0, 85.0] {
            let wo = dir(theta, 20.0);
            let g1 = 1.0 / (1.0 + ref_lambda(alpha, wo));
            let vis = hemisphere_integral_about(DVec3::Z, NT, NP, |m| {
                g1 * ref_d(alpha, m) * wo.dot(m).max(0.0) / wo.z
            });
            assert!((vis - 1.0).abs() < 1e-3, "α {alpha} θ {theta}: {vis}");
        }
    }
}

#[test]
fn quadrature_integrates_known_functions() {
    // Hemisphere solid angle 2π and projected solid angle π about tilted poles.
    for pole in [
        dir(0.0, 0.0),
        dir(60.0, 10.0),
        dir(88.0, 200.0),
        dir(150.0, 45.0),
    ] {
        let a = hemisphere_integral_about(pole, NT, NP, |_| 1.0);
        let b = hemisphere_integral_about(pole, NT, NP, |w| w.z.abs());
        assert!((a - 2.0 * PI).abs() < 1e-4, "{pole}: {a}");
        assert!((b - PI).abs() < 1e-4, "{pole}: {b}");
    }
}

// ---------------------------------------------------------------------------
// (a) Pointwise eval against the reference.
// ---------------------------------------------------------------------------

#[test]
fn rough_conductor_eval_matches_textbook_reference() {
    for bsdf in conductors() {
        let (eta, k, alpha) = conductor_params(&bsdf);
        let (mut worst, mut big) = (0.0f64, 0);
        for (wo, wi) in pairs(alpha as f64, 1.0, 3000, 1) {
            let f = bsdf.eval(wo, wi);
            for ch in 0..3 {
                let r = ref_conductor(
                    eta[ch] as f64,
                    k[ch] as f64,
                    alpha as f64,
                    wo.as_dvec3(),
                    wi.as_dvec3(),
                );
                assert_eval_close(f[ch], r, &mut worst, || {
                    format!("{bsdf:?} wo={wo} wi={wi} ch{ch}")
                });
                big += (r > 0.01) as usize;
            }
        }
        // Over 2000 of the 9000 values must test the lobe, not two zeros.
        assert!(big > 2000, "{bsdf:?}: only {big} significant values");
        eprintln!("{bsdf:?}: worst rel err {worst:.2e}");
    }
}

#[test]
fn rough_dielectric_eval_matches_textbook_reference() {
    for bsdf in dielectrics() {
        let Bsdf::Dielectric { eta, alpha, tint } = bsdf else {
            unreachable!()
        };
        let (mut worst, mut n_r, mut n_t) = (0.0f64, 0, 0);
        for (wo, wi) in pairs(alpha as f64, eta as f64, 3000, 2) {
            let f = bsdf.eval(wo, wi);
            let (r, t) = ref_dielectric(eta as f64, alpha as f64, wo.as_dvec3(), wi.as_dvec3());
            for ch in 0..3 {
                let reference = r + t * tint[ch] as f64;
                assert_eval_close(f[ch], reference, &mut worst, || {
                    format!("{bsdf:?} wo={wo} wi={wi} ch{ch} (R {r}, T {t})")
                });
            }
            n_r += (r > 0.05) as usize;
            n_t += (t > 0.05) as usize;
        }
        assert!(
            n_r > 300 && n_t > 300,
            "{bsdf:?}: {n_r} R / {n_t} T significant pairs"
        );
        eprintln!("{bsdf:?}: worst rel err {worst:.2e} ({n_r} R, {n_t} T pairs)");
    }
}

// ---------------------------------------------------------------------------
// (b) Directional albedo by quadrature.
// ---------------------------------------------------------------------------

/// Mean sampling weight of `sample` (transmission in radiance units), channel
/// `ch`, with its standard error.
fn sampled_albedo(bsdf: &Bsdf, wo: DVec3, ch: usize, n: usize) -> (f64, f64) {
    let mut rng = Pcg32::new(9, 9);
    let (mut s1, mut s2) = (0.0, 0.0);
    for _ in 0..n {
        let u_lobe = rng.next_f32();
        let w = bsdf
            .sample(f32v(wo), u_lobe, rng.next_vec2())
            .map_or(0.0, |s| s.weight()[ch] as f64);
        s1 += w;
        s2 += w * w;
    }
    let mean = s1 / n as f64;
    (
        mean,
        ((s2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt(),
    )
}

#[test]
fn rough_conductor_albedo_matches_reference_quadrature() {
    let mut cases = Vec::new();
    for alpha in [0.05f32, 0.2, 0.5, 0.9] {
        cases.push(Bsdf::conductor_preset("gold", alpha).unwrap());
    }
    cases.push(perfect_conductor(0.6));
    for bsdf in cases {
        let (eta, k, alpha) = conductor_params(&bsdf);
        for theta in [0.0, 40.0, 75.0, 140.0] {
            let wo = dir(theta, 33.0);
            for ch in [0usize, 2] {
                let (e, kk) = (eta[ch] as f64, k[ch] as f64);
                let wo_up = DVec3::new(wo.x, wo.y, wo.z.abs());
                let (reference, _) =
                    reference_albedo_wm(alpha as f64, wo_up, 1.0, 1.0, false, |c| {
                        ref_fr_conductor(c, e, kk)
                    });
                let (code, _) = code_albedo(&bsdf, wo, ch);
                assert!(
                    rel_err(code, reference) < 0.01,
                    "{bsdf:?} θo={theta} ch{ch}: ∫f cos = {code}, reference {reference}"
                );
                let (mc, se) = sampled_albedo(&bsdf, wo, ch, 50_000);
                assert!(
                    (mc - code).abs() < 5.0 * se + 0.01 * code,
                    "{bsdf:?} θo={theta} ch{ch}: sampled {mc} ± {se}, quadrature {code}"
                );
            }
        }
    }
}

#[test]
fn rough_dielectric_albedo_matches_reference_quadrature() {
    for bsdf in dielectrics() {
        let Bsdf::Dielectric { eta, alpha, tint } = bsdf else {
            unreachable!()
        };
        let eta = eta as f64;
        for theta in [0.0, 35.0, 70.0, 120.0, 170.0] {
            let wo = dir(theta, -20.0);
            let (n1, n2) = (side_ior(eta, wo), if wo.z > 0.0 { eta } else { 1.0 });
            let (ref_r, ref_t) = reference_albedo_wm(alpha as f64, wo, n1, n2, true, |c| {
                ref_fr_dielectric(c, n2 / n1)
            });
            for ch in [0usize, 2] {
                let (code_r, code_t) = code_albedo(&bsdf, wo, ch);
                let ref_t = ref_t * tint[ch] as f64;
                assert!(
                    rel_err(code_r, ref_r) < 0.01 && rel_err(code_t, ref_t) < 0.01,
                    "{bsdf:?} θo={theta} ch{ch}: R {code_r} vs {ref_r}, T {code_t} vs {ref_t}"
                );
                let (mc, se) = sampled_albedo(&bsdf, wo, ch, 50_000);
                let code = code_r + code_t;
                assert!(
                    (mc - code).abs() < 5.0 * se + 0.01 * code,
                    "{bsdf:?} θo={theta} ch{ch}: sampled {mc} ± {se}, quadrature {code}"
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------
// (c) Physical sanity of the absolute scale.
// ---------------------------------------------------------------------------

#[test]
fn rough_glass_conserves_energy_at_normal_incidence() {
    // α = 0.3 glass loses only the little energy single scattering drops:
    // R + T (T with the 1/η² radiance scaling undone) is close to one.
    let eta = 1.5f32;
    let glass = Bsdf::Dielectric {
        eta,
        alpha: 0.3,
        tint: Vec3::ONE,
    };
    let (r, t) = code_albedo(&glass, DVec3::Z, 0);
    let energy = r + t * (eta as f64).powi(2);
    assert!(
        energy > 0.95 && energy <= 1.0 + 1e-3,
        "R {r} T {t}: {energy}"
    );
    // Reflection near normal incidence is close to the smooth F0 = 0.04.
    assert!((0.035..0.06).contains(&r), "R {r}");
}

#[test]
fn near_perfect_conductor_reflects_almost_everything() {
    let mirror = perfect_conductor(0.05);
    for theta in [0.0, 10.0, 30.0] {
        let wo = dir(theta, 70.0);
        let (a, _) = code_albedo(&mirror, wo, 1);
        assert!(a > 0.97 && a <= 1.0 + 1e-3, "θo={theta}: albedo {a}");
    }
    // Rougher surfaces lose energy to masking, monotonically in α.
    let wo = dir(60.0, 0.0);
    let albedos: Vec<f64> = [0.05f32, 0.3, 0.6, 1.0]
        .iter()
        .map(|&a| code_albedo(&perfect_conductor(a), wo, 0).0)
        .collect();
    assert!(albedos.windows(2).all(|w| w[1] < w[0]), "{albedos:?}");
}
