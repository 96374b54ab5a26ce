//! The relief's height comes out of the colour pass (`Pat::h`): the same
//! bits as a height pass of its own under the relief's footprint, which
//! `Texture::shade` ran as a fourth pattern evaluation per textured hit.

use glam::{DVec3, Vec3};

use super::{Footprint, Texture, TextureKind};

/// Points of a 40 m square on a road (up) and on a wall.
fn points() -> impl Iterator<Item = (DVec3, Vec3)> {
    let planes = [
        (DVec3::new(1000.0, -20.0, 0.0), DVec3::X, DVec3::Y, Vec3::Z),
        (
            DVec3::new(-50.0, 30.0, 0.0),
            DVec3::new(-0.8, 0.6, 0.0),
            DVec3::Z,
            Vec3::new(0.6, 0.8, 0.0),
        ),
    ];
    let (g1, g2) = (0.754_877_666_246_692_8, 0.569_840_290_998_053_3);
    planes.into_iter().flat_map(move |(o, a, b, n)| {
        (0..3000).map(move |i| {
            let p = o
                + a * ((0.5 + g1 * i as f64).fract() * 40.0)
                + b * ((0.5 + g2 * i as f64).fract() * 40.0);
            (p, n)
        })
    })
}

#[test]
fn the_colour_pass_gives_the_relief_passs_height_bits() {
    // From sharp to wider than every noise's cell (2 m: the seams' 70 cm
    // wobble leaves its residual grain in the colour).
    let widths = [0.0f32, 1e-4, 0.002, 0.01, 0.05, 0.3, 2.0];
    let mut grain_differs = 0;
    for (k, kind) in TextureKind::ALL.into_iter().enumerate() {
        let t = Texture {
            scale: [1.0, 0.7, 1.6][k % 3],
            ..Texture::new(kind, 11 + k as u32)
        };
        for &w in &widths {
            let f = t.footprint(w);
            for (p_world, n) in points() {
                let p = p_world / t.scale;
                let colour = t.pat(Vec3::splat(0.4), p, n, f, true);
                let relief = t.pat(Vec3::ONE, p, n, f.relief(), false);
                assert_eq!(
                    colour.h.to_bits(),
                    relief.h.to_bits(),
                    "{kind:?} footprint {w} at {p_world}: {} vs {}",
                    colour.h,
                    relief.h
                );
                // Where the colour's footprint leaves residual grain, a
                // height term filtered by it would differ.
                let smooth = t.pat(Vec3::splat(0.4), p, n, f.relief(), true);
                grain_differs += usize::from(smooth.c != colour.c);
            }
        }
    }
    assert!(grain_differs > 1000, "{grain_differs}");
}

#[test]
fn shade_gives_the_normal_of_a_separate_height_pass() {
    for (k, kind) in TextureKind::ALL.into_iter().enumerate() {
        let t = Texture::new(kind, 5 + k as u32);
        for w in [0.0f32, 0.003, 0.04, 0.5] {
            for (p_world, n) in points().step_by(7) {
                let (s, normal) = t.shade(Vec3::splat(0.3), p_world, n, n, w);
                // As `shade` was: colour, then the height on its own.
                let f = t.footprint(w);
                let p = p_world / t.scale;
                let expect = if t.has_relief() {
                    let h0 = t.pat(Vec3::ONE, p, n, f.relief(), false).h;
                    t.tilt(p, n, n, f.relief(), h0)
                } else {
                    n
                };
                assert_eq!(normal, expect, "{kind:?} footprint {w} at {p_world}");
                let colour = t.sample_filtered(Vec3::splat(0.3), p_world, n, w);
                assert_eq!(s, colour);
            }
        }
    }
}

#[test]
fn relief_and_colour_runs_the_term_once_where_they_agree() {
    let calls = std::cell::Cell::new(0);
    let p = DVec3::new(0.31, 0.77, 0.0);
    let term = |f: Footprint| {
        calls.set(calls.get() + 1);
        f.value_noise(p, 0.01, 3)
    };
    // Below the cell: one call, both the same.
    let (a, b) = Footprint::new(0.005).relief_and_colour(0.01, term);
    assert_eq!((a, calls.get()), (b, 1));
    // Above it: the colour keeps its residual grain, the relief not.
    let (a, b) = Footprint::new(0.04).relief_and_colour(0.01, term);
    assert_eq!(calls.get(), 3);
    assert_eq!(a, Footprint::new(0.04).relief().value_noise(p, 0.01, 3));
    assert_eq!(b, Footprint::new(0.04).value_noise(p, 0.01, 3));
    assert_ne!(a, b);
    // Already the relief's footprint: once.
    let _ = Footprint::new(0.04).relief().relief_and_colour(0.01, term);
    assert_eq!(calls.get(), 4);
}
