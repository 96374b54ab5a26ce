//! Properties of the procedural textures: determinism, calibration of the
//! mean albedo, fine detail, brick geometry, range.

use glam::{DVec3, Vec3};
use shaders_cpu::texture::noise::{fbm, hash_cell, unit, value_noise};
use shaders_cpu::texture::{Texture, TextureKind};

/// A nominal albedo typical of each kind.
fn base_of(kind: TextureKind) -> Vec3 {
    match kind {
        TextureKind::Asphalt => Vec3::new(0.085, 0.085, 0.09),
        TextureKind::RoadPaint => Vec3::new(0.78, 0.78, 0.74),
        TextureKind::Paving | TextureKind::Kerb => Vec3::new(0.45, 0.44, 0.42),
        TextureKind::Concrete => Vec3::new(0.5, 0.5, 0.48),
        TextureKind::Brick | TextureKind::BrickFlemish | TextureKind::BrickEnglish => {
            Vec3::new(0.42, 0.17, 0.11)
        }
        TextureKind::Plaster => Vec3::new(0.72, 0.66, 0.52),
        TextureKind::Stone => Vec3::new(0.56, 0.52, 0.45),
        TextureKind::Glass => Vec3::new(0.9, 0.95, 0.95),
        TextureKind::MetalPainted => Vec3::new(0.1, 0.3, 0.15),
        TextureKind::MetalBrushed => Vec3::new(0.6, 0.6, 0.6),
        TextureKind::Wood => Vec3::new(0.35, 0.22, 0.12),
        TextureKind::Bark => Vec3::new(0.22, 0.15, 0.09),
        TextureKind::Leaves | TextureKind::Foliage => Vec3::new(0.1, 0.22, 0.06),
        TextureKind::Grass => Vec3::new(0.1, 0.22, 0.06),
        TextureKind::Soil => Vec3::new(0.15, 0.11, 0.07),
    }
}

fn tex(kind: TextureKind, seed: u32) -> Texture {
    Texture::new(kind, seed)
}

/// The i-th of n quasi-random points on a square of side `size_m` in the
/// plane spanned by `a`, `b` around `origin` (R2 sequence, Roberts 2018).
fn plane_point(i: usize, size_m: f64, origin: DVec3, a: DVec3, b: DVec3) -> DVec3 {
    let (g1, g2) = (0.754_877_666_246_692_8, 0.569_840_290_998_053_3);
    let s = (0.5 + g1 * i as f64).fract() * size_m;
    let t = (0.5 + g2 * i as f64).fract() * size_m;
    origin + a * s + b * t
}

#[test]
fn mean_albedo_over_large_area_matches_nominal() {
    let n = 200_000;
    // A road plane and a wall whose normal points along (0.6, 0.8, 0).
    let road = (DVec3::new(1000.0, -20.0, 0.0), DVec3::X, DVec3::Y, Vec3::Z);
    let wall_dir = DVec3::new(-0.8, 0.6, 0.0);
    let wall = (
        DVec3::new(-50.0, 30.0, 0.0),
        wall_dir,
        DVec3::Z,
        Vec3::new(0.6, 0.8, 0.0),
    );
    for kind in TextureKind::ALL.into_iter().filter(|k| k.mean_preserving()) {
        let base = base_of(kind);
        for (origin, a, b, normal) in [road, wall] {
            let t = tex(kind, 7);
            let mut sum = glam::DVec3::ZERO;
            for i in 0..n {
                let p = plane_point(i, 30.0, origin, a, b);
                sum += t.albedo(base, p, normal).as_dvec3();
            }
            let mean = (sum / n as f64).as_vec3();
            let rel = (mean / base - Vec3::ONE).abs();
            assert!(
                rel.max_element() < 0.03,
                "{kind:?} normal {normal}: mean {mean} vs nominal {base}"
            );
        }
    }
}

#[test]
fn textures_are_deterministic_and_seeded() {
    for kind in TextureKind::ALL {
        let base = base_of(kind);
        let (mut same, mut differ) = (true, 0);
        for i in 0..1000 {
            let p = plane_point(i, 5.0, DVec3::new(3.0, 4.0, 0.0), DVec3::X, DVec3::Y);
            let a = tex(kind, 1).albedo(base, p, Vec3::Z);
            same &= a == tex(kind, 1).albedo(base, p, Vec3::Z);
            differ += usize::from(a != tex(kind, 2).albedo(base, p, Vec3::Z));
        }
        assert!(same, "{kind:?} not deterministic");
        assert!(
            differ > 900,
            "{kind:?}: seed changes only {differ}/1000 points"
        );
    }
}

#[test]
fn detail_at_stereo_pixel_scale_far_from_origin() {
    // Neighbours 3 mm apart (one pixel at 5 m for 1600×900) must differ on
    // average by a visible fraction of the albedo, also 50 km from the origin.
    // Glass and metals carry their fine detail in roughness and relief.
    let smooth = [
        TextureKind::Glass,
        TextureKind::MetalBrushed,
        TextureKind::MetalPainted,
    ];
    for kind in TextureKind::ALL.into_iter().filter(|k| !smooth.contains(k)) {
        let base = base_of(kind);
        let t = tex(kind, 5);
        for origin in [
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(50_000.0, -30_000.0, 0.0),
        ] {
            let (mut diff, mut level) = (0.0f64, 0.0f64);
            for i in 0..20_000 {
                let p = plane_point(i, 10.0, origin, DVec3::X, DVec3::Y);
                let a = t.albedo(base, p, Vec3::Z).element_sum() as f64;
                let b = t.albedo(base, p + DVec3::X * 0.003, Vec3::Z).element_sum() as f64;
                diff += (a - b).abs();
                level += a;
            }
            let contrast = diff / level;
            let floor = if kind == TextureKind::Plaster {
                0.02
            } else {
                0.05
            };
            assert!(
                contrast > floor,
                "{kind:?} at {origin}: 3 mm contrast {contrast}"
            );
        }
    }
}

#[test]
fn brick_mortar_repeats_at_module_period() {
    let base = base_of(TextureKind::Brick);
    let t = tex(TextureKind::Brick, 3);
    let n = Vec3::new(0.6, 0.8, 0.0);
    let along = DVec3::new(-0.8, 0.6, 0.0);
    let is_mortar = |p: DVec3, n: Vec3| {
        let a = t.albedo(base, p, n);
        // Mortar is grey (g ≈ r); brick is red (g ≪ r).
        a.y > 0.7 * a.x
    };
    // Horizontal scan at mid-course height (course 10 spans 0.75..0.825 m,
    // mortar 0.75..0.76): joints start every 0.225 m.
    let origin = DVec3::new(5.0, -2.0, 0.79);
    let step = 0.0005;
    let mut starts = Vec::new();
    let mut prev = is_mortar(origin, n);
    for i in 1..4000 {
        let p = origin + along * (i as f64 * step);
        let m = is_mortar(p, n);
        assert_eq!(m, is_mortar(p, -n), "both faces see one pattern");
        if m && !prev {
            starts.push(i as f64 * step);
        }
        prev = m;
    }
    assert!(starts.len() >= 7, "joints found: {starts:?}");
    for w in starts.windows(2) {
        assert!(
            (w[1] - w[0] - 0.225).abs() < 0.0011,
            "joint spacing {:?}",
            w
        );
    }
    // Vertical scan: bed joints every 0.075 m, each 10 mm thick.
    let mut runs = Vec::new();
    let (mut start, mut prev) = (0.0, false);
    for i in 0..3000 {
        let z = i as f64 * 0.0002;
        let m = is_mortar(DVec3::new(5.0, -2.0, z) + along * 0.11, n);
        if m && !prev {
            start = z;
        }
        if !m && prev {
            runs.push((start, z - start));
        }
        prev = m;
    }
    assert!(runs.len() >= 6, "bed joints: {runs:?}");
    for w in runs.windows(2) {
        let period = w[1].0 - w[0].0;
        // A head joint may merge with a bed joint; bed joints alone are periodic.
        assert!(
            (period - 0.075).abs() < 0.0005 || (period - 0.15).abs() < 0.0005,
            "bed joint period {period}"
        );
    }
    assert!(
        runs.iter().any(|r| (r.1 - 0.01).abs() < 0.0005),
        "joint width: {runs:?}"
    );
}

#[test]
fn albedo_stays_in_unit_range_for_bright_bases() {
    for kind in TextureKind::ALL {
        for base in [Vec3::ZERO, Vec3::splat(0.95), Vec3::new(1.0, 0.0, 0.5)] {
            for i in 0..5000 {
                let p = plane_point(i, 3.0, DVec3::new(-7.0, 2.0, 1.0), DVec3::X, DVec3::Z);
                let a = tex(kind, 9).albedo(base, p, Vec3::Y);
                assert!(a.is_finite() && a.min_element() >= 0.0 && a.max_element() <= 0.99);
            }
        }
    }
}

#[test]
fn value_noise_and_fbm_have_zero_mean_and_unit_bound() {
    let (mut sv, mut sf) = (0.0f64, 0.0f64);
    let n = 100_000;
    for i in 0..n {
        let p = plane_point(i, 40.0, DVec3::new(0.0, 0.0, 0.3), DVec3::X, DVec3::Y);
        let v = value_noise(p, 0.1, 4);
        let f = fbm(p, 0.5, 6, 0.55, 4);
        assert!(v.abs() <= 1.0 && f.abs() <= 1.0);
        sv += v as f64;
        sf += f as f64;
    }
    assert!(
        (sv / n as f64).abs() < 0.01,
        "value noise mean {}",
        sv / n as f64
    );
    assert!((sf / n as f64).abs() < 0.02, "fbm mean {}", sf / n as f64);
    // Hash cells far apart (2³² cells) still decorrelate.
    let a = unit(hash_cell([5, 7, 1], 0));
    let b = unit(hash_cell([5 + (1 << 32), 7, 1], 0));
    assert_ne!(a, b);
}

#[test]
fn asphalt_holds_sparse_drains_and_iron_covers_on_roads_only() {
    // One million points over a 1 km square: drain slots (3 cm deep, the
    // only relief below 2 cm) cover 1/3 of 22 m cells × ~0.08 m², about
    // 5.5e-5 of the road; iron (covers and gratings: albedo ~0.07 whatever
    // the base) about 6e-4. Walls of asphalt get neither.
    let t = tex(TextureKind::Asphalt, 11);
    let base = Vec3::splat(0.9);
    let n = 1_000_000;
    let (mut slots, mut iron, mut wall_slots) = (0usize, 0usize, 0usize);
    for i in 0..n {
        let p = plane_point(
            i,
            1000.0,
            DVec3::new(-300.0, 200.0, 0.0),
            DVec3::X,
            DVec3::Y,
        );
        slots += usize::from(t.height(p, Vec3::Z) < -0.02);
        iron += usize::from(t.albedo(base, p, Vec3::Z).max_element() < 0.1);
        wall_slots += usize::from(t.height(p, Vec3::X) < -0.02);
    }
    let (fs, fi) = (slots as f64 / n as f64, iron as f64 / n as f64);
    assert!((2.5e-5..1.2e-4).contains(&fs), "slot fraction {fs}");
    assert!((3e-4..1.2e-3).contains(&fi), "iron fraction {fi}");
    assert_eq!(wall_slots, 0);
}
