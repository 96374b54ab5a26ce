//! Textures filtered by the ray's footprint (`texture::Footprint`): under a
//! footprint wider than a kind's detail its grain fades and its area mean
//! stays; a footprint far below the finest detail changes nothing; a
//! stretcher-bond wall seen from afar is exactly its nominal albedo; the
//! filtered relief flattens and stays an energy-conserving normal map.

use glam::{DVec3, Vec2, Vec3};
use shaders_cpu::bsdf::{Bsdf, Facet};
use shaders_cpu::texture::{Texture, TextureKind};

/// A nominal albedo of each kind (as in `texture_properties`).
fn base_of(kind: TextureKind) -> Vec3 {
    use TextureKind as K;
    match kind {
        K::Asphalt => Vec3::new(0.085, 0.085, 0.09),
        K::RoadPaint => Vec3::new(0.78, 0.78, 0.74),
        K::Paving | K::Kerb => Vec3::new(0.45, 0.44, 0.42),
        K::Concrete => Vec3::new(0.5, 0.5, 0.48),
        K::Brick | K::BrickFlemish | K::BrickEnglish => Vec3::new(0.42, 0.17, 0.11),
        K::Plaster => Vec3::new(0.72, 0.66, 0.52),
        K::Stone => Vec3::new(0.56, 0.52, 0.45),
        K::Glass => Vec3::new(0.9, 0.95, 0.95),
        K::MetalPainted => Vec3::new(0.1, 0.3, 0.15),
        K::MetalBrushed => Vec3::new(0.6, 0.6, 0.6),
        K::Wood => Vec3::new(0.35, 0.22, 0.12),
        K::Bark => Vec3::new(0.22, 0.15, 0.09),
        K::Leaves | K::Foliage | K::Grass => Vec3::new(0.1, 0.22, 0.06),
        K::Soil => Vec3::new(0.15, 0.11, 0.07),
    }
}

/// The i-th quasi-random point (R2 sequence) of a `size_m` square in the
/// plane of `a`, `b` at `origin`.
fn plane_point(i: usize, size_m: f64, origin: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let (g1, g2) = (0.754_877_666_246_692_8, 0.569_840_290_998_053_3);
    origin
        + a * ((0.5 + g1 * i as f64).fract() * size_m)
        + b * ((0.5 + g2 * i as f64).fract() * size_m)
}

/// A road (up) and a wall (normal (0.6, 0.8, 0)): origin, axes, normal.
fn planes() -> [(DVec3, DVec3, DVec3, Vec3); 2] {
    [
        (DVec3::new(1000.0, -20.0, 0.0), DVec3::X, DVec3::Y, Vec3::Z),
        (
            DVec3::new(-50.0, 30.0, 0.0),
            DVec3::new(-0.8, 0.6, 0.0),
            DVec3::Z,
            Vec3::new(0.6, 0.8, 0.0),
        ),
    ]
}

/// Mean and standard deviation of the albedo's luminance-weighted sum
/// (channel sum) over `n` points of a 30 m square at footprint `fp`.
fn stats(t: &Texture, plane: (DVec3, DVec3, DVec3, Vec3), n: usize, fp: f32) -> (Vec3, f64) {
    let (origin, a, b, normal) = plane;
    let base = base_of(t.kind);
    let (mut sum, mut s1, mut s2) = (DVec3::ZERO, 0.0, 0.0);
    for i in 0..n {
        let c = t
            .sample_filtered(base, plane_point(i, 30.0, origin, a, b), normal, fp)
            .albedo;
        sum += c.as_dvec3();
        let y = c.element_sum() as f64;
        s1 += y;
        s2 += y * y;
    }
    let m = s1 / n as f64;
    (
        (sum / n as f64).as_vec3(),
        (s2 / n as f64 - m * m).max(0.0).sqrt(),
    )
}

#[test]
fn wide_footprints_keep_each_kinds_mean_and_shed_its_grain() {
    let n = 60_000;
    let mut bad = Vec::new();
    for kind in TextureKind::ALL {
        for plane in planes() {
            let t = Texture::new(kind, 7);
            let (m0, s0) = stats(&t, plane, n, 0.0);
            for fp in [0.02f32, 0.3] {
                let (m, s) = stats(&t, plane, n, fp);
                let rel = (m / m0 - Vec3::ONE).abs().max_element();
                if rel >= 0.025 {
                    bad.push(format!(
                        "{kind:?} n {}: mean {m} at {fp} m vs {m0} sharp",
                        plane.3
                    ));
                }
                if s > s0 * 1.001 {
                    bad.push(format!(
                        "{kind:?} n {}: std {s} at {fp} m above {s0} sharp",
                        plane.3
                    ));
                }
            }
            // At 30 cm only features of 15 cm and more are left: at least
            // a third of the spread is gone unless the kind's variation is
            // mostly coarse (asphalt's wear and patches, glass's tint,
            // painted and brushed metal's paint, grass's clumps and dry patches).
            use TextureKind as K;
            let coarse = matches!(
                kind,
                K::Asphalt | K::Glass | K::MetalPainted | K::MetalBrushed | K::Grass
            );
            let (_, s) = stats(&t, plane, n, 0.3);
            if !coarse && s0 > 1e-4 && s >= 0.67 * s0 {
                bad.push(format!(
                    "{kind:?} n {}: std {s} at 30 cm vs {s0} sharp",
                    plane.3
                ));
            }
        }
    }
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}

#[test]
fn a_footprint_below_the_finest_detail_changes_nothing() {
    // The finest detail is the brushed streak, 0.2 mm: 0.1 mm keeps all.
    for kind in TextureKind::ALL {
        let t = Texture::new(kind, 3);
        let base = base_of(kind);
        for (origin, a, b, normal) in planes() {
            for i in 0..2000 {
                let p = plane_point(i, 5.0, origin, a, b);
                let (s, f) = (
                    t.sample(base, p, normal),
                    t.sample_filtered(base, p, normal, 1e-4),
                );
                let d = (s.albedo - f.albedo)
                    .abs()
                    .max_element()
                    .max((s.roughness - f.roughness).abs());
                assert!(d < 1e-5, "{kind:?} at {p}: {s:?} vs {f:?}");
                let dh = (t.height(p, normal) - t.height_filtered(p, normal, 1e-4)).abs();
                assert!(dh < 1e-8, "{kind:?} height at {p}: {dh}");
            }
        }
    }
}

#[test]
fn stretcher_brick_from_afar_is_its_nominal_albedo() {
    // Under a 1 m footprint every brick, joint and grain is averaged: the
    // mortar's cover is its area share at every point, so each point is
    // f·brick + (1 − f)·mortar = the nominal albedo (what the mortar colour
    // was solved for) times the residual grain of the averaged bricks
    // (std 0.127 · 7.5 cm / 1 m ≈ 1 %), and the wall is flat.
    let t = Texture::new(TextureKind::Brick, 11);
    let base = base_of(TextureKind::Brick);
    let (origin, a, b, normal) = planes()[1];
    let (mut worst, mut sharp_spread, mut sum) = (0.0f32, 0.0f32, Vec3::ZERO);
    let n = 3000;
    for i in 0..n {
        let p = plane_point(i, 20.0, origin, a, b);
        let far = t.sample_filtered(base, p, normal, 1.0).albedo;
        sum += far;
        worst = worst.max((far / base - Vec3::ONE).abs().max_element());
        let sharp = t.sample(base, p, normal).albedo;
        sharp_spread = sharp_spread.max((sharp / base - Vec3::ONE).abs().max_element());
        let (_, n) = t.shade(base, p, normal, normal, 1.0);
        assert_eq!(n, normal, "relief left under a 1 m footprint at {p}");
    }
    let mean_err = (sum / n as f32 / base - Vec3::ONE).abs().max_element();
    assert!(worst < 0.04, "far brick off its nominal albedo by {worst}");
    assert!(mean_err < 0.002, "far brick's mean off by {mean_err}");
    assert!(
        sharp_spread > 0.3,
        "sharp brick varies by {sharp_spread} only"
    );
}

/// Sample weights of a normal-mapped white Lambertian surface seen from
/// `wo`: each must be exactly 1 (the furnace of `normal_map`).
fn furnace_weights(wp: Vec3, wo: Vec3) -> f32 {
    let bsdf = Bsdf::NormalMapped {
        facet: Facet::Lambert { albedo: Vec3::ONE },
        wp,
    };
    let mut worst = 0.0f32;
    for k in 0..64 {
        let u = Vec2::new((k as f32 + 0.5) / 64.0, (k as f32 * 0.618_034).fract());
        if let Some(s) = bsdf.sample(wo, (k as f32 * 0.414_213_6).fract(), u) {
            let w = s.f * s.wi.z.abs() / s.pdf;
            worst = worst.max((w - Vec3::ONE).abs().max_element());
        }
    }
    worst
}

#[test]
fn filtered_relief_flattens_with_the_footprint_and_conserves_energy() {
    // Bark's relief (8 mm furrows) at footprints from none to 10 cm: the
    // mean tilt of the shading normal shrinks, and the normal map built on
    // it returns every furnace sample with weight 1.
    let t = Texture::new(TextureKind::Bark, 5);
    let (origin, a, b, normal) = planes()[1];
    let mut last = f32::INFINITY;
    for fp in [0.0f32, 0.01, 0.03, 0.1] {
        let mut tilt = 0.0f32;
        for i in 0..400 {
            let p = plane_point(i, 3.0, origin, a, b);
            let (_, n) = t.shade(Vec3::splat(0.3), p, normal, normal, fp);
            tilt += 1.0 - n.dot(normal);
            // In the geometric frame (z = normal): the furnace.
            let frame = shaders_cpu::sampling::Frame::from_z(normal);
            let wp = frame.to_local(n);
            for wo in [
                Vec3::Z,
                Vec3::new(0.6, 0.0, 0.8),
                Vec3::new(-0.3, 0.9, 0.3).normalize(),
            ] {
                let e = furnace_weights(wp, wo);
                assert!(e < 1e-3, "furnace weight off by {e} at footprint {fp}");
            }
        }
        assert!(
            tilt < last || tilt == 0.0,
            "tilt {tilt} at {fp} m not below {last}"
        );
        last = tilt;
    }
    assert_eq!(last, 0.0, "bark relief left under a 10 cm footprint");
}
