//! An emitter's draw: its pmf recomputed bitwise, summing to one over the
//! triangles a point sees and zero for those turned away, drawn as often
//! as it says; and the grouping: small lamps whole, long strips cut into
//! pieces within the size bound, every triangle in one emitter.

use glam::Vec3;

use super::{group, EmissiveTriangle, Emitters, MAX_DIAGONAL_M};
use crate::sampler::rng::Rng;

/// A closed octahedron of radii `r` around `c`, faces outwards, with
/// unequal faces (eight triangles).
fn octahedron(c: Vec3, r: Vec3) -> Vec<EmissiveTriangle> {
    let axis = |i: usize, s: f32| {
        let mut v = Vec3::ZERO;
        v[i] = s * r[i];
        c + v
    };
    let mut tris = Vec::new();
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            for sz in [-1.0f32, 1.0] {
                let mut v = [axis(0, sx), axis(1, sy), axis(2, sz)];
                // Outward: (b − a) × (c − a) along the octant's diagonal.
                if (v[1] - v[0]).cross(v[2] - v[0]).dot(Vec3::new(sx, sy, sz)) < 0.0 {
                    v.swap(1, 2);
                }
                tris.push(EmissiveTriangle {
                    v,
                    prim: tris.len() as u32,
                });
            }
        }
    }
    tris
}

#[test]
fn draw_pmf_is_recomputed_bitwise_and_covers_the_faces_seen() {
    let mut e = Emitters::default();
    let lamp = octahedron(Vec3::new(1.0, -2.0, 3.0), Vec3::new(0.3, 0.2, 0.1));
    let range = e.push(&lamp, 7);
    assert_eq!(e.entry_of(range.start + 3), 7);
    let mut rng = Rng::new(&[0x9e37_79b9]);
    for two_sided in [false, true] {
        for k in 0..200 {
            let p = Vec3::new(rng.f32() - 0.5, rng.f32() - 0.5, rng.f32() - 0.5) * 8.0;
            let pmfs: Vec<f32> = range
                .clone()
                .map(|t| e.pmf(range.clone(), two_sided, p, t))
                .collect();
            let sum: f32 = pmfs.iter().sum();
            assert!((sum - 1.0).abs() < 1e-5, "Σ pmf {sum} at {p}");
            for (t, &pmf) in range.clone().zip(&pmfs) {
                let [a, b, c] = lamp[(t - range.start) as usize].v;
                let facing = (b - a).cross(c - a).dot(p - a) > 0.0;
                // One-sided: only faces the point sees; both: every face.
                assert_eq!(pmf > 0.0, facing || two_sided, "triangle {t} at {p}");
            }
            // Each draw's pmf is the recomputed one, bit for bit, and its
            // number rescaled stays in [0, 1).
            let mut counts = vec![0u32; lamp.len()];
            let n = if k < 4 { 40_000 } else { 50 };
            for i in 0..n {
                let u = (i as f32 + 0.5) / n as f32;
                let d = e
                    .draw(range.clone(), two_sided, p, u)
                    .expect("a face sees p");
                let t = lamp.iter().position(|l| l.v == d.v).unwrap();
                assert_eq!(d.pmf.to_bits(), pmfs[t].to_bits());
                assert!((0.0..1.0).contains(&d.u), "rescaled {}", d.u);
                counts[t] += 1;
            }
            if n > 1000 {
                for (t, &c) in counts.iter().enumerate() {
                    let f = c as f32 / n as f32;
                    assert!(
                        (f - pmfs[t]).abs() < 1e-3,
                        "triangle {t}: {f} vs {}",
                        pmfs[t]
                    );
                }
            }
        }
    }
    // A lone triangle is drawn whatever its facing, with pmf 1.
    let one = e.push(&lamp[..1], 8);
    let behind = lamp[0].v[0] - (lamp[0].v[1] - lamp[0].v[0]).cross(lamp[0].v[2] - lamp[0].v[0]);
    assert_eq!(
        e.draw(one.clone(), false, behind, 0.3).map(|d| d.pmf),
        Some(1.0)
    );
    assert_eq!(e.pmf(one.clone(), false, behind, one.start), 1.0);
}

/// The emitters `group` makes of `tris` (their triangles' `prim`s),
/// checked to hold every triangle once, in order, within the bound.
fn groups_of(tris: &mut [EmissiveTriangle]) -> Vec<Vec<u32>> {
    for (i, t) in tris.iter_mut().enumerate() {
        t.prim = i as u32;
    }
    let mut groups: Vec<Vec<u32>> = Vec::new();
    group(tris, &mut |g| {
        groups.push(g.iter().map(|t| t.prim).collect())
    });
    let mut seen: Vec<u32> = groups.concat();
    seen.sort_unstable();
    assert_eq!(seen, (0..tris.len() as u32).collect::<Vec<_>>());
    for g in &groups {
        let vs = g.iter().flat_map(|&i| tris[i as usize].v);
        let lo = vs.clone().fold(Vec3::INFINITY, Vec3::min);
        let hi = vs.fold(Vec3::NEG_INFINITY, Vec3::max);
        assert!((hi - lo).length() <= MAX_DIAGONAL_M, "{g:?}");
        assert!(g.windows(2).all(|w| w[0] < w[1]), "in mesh order: {g:?}");
    }
    groups
}

#[test]
fn grouping_keeps_lamps_whole_and_cuts_long_strips() {
    // Two lamps of one mesh 5 m apart: one emitter each.
    let mut lamps = octahedron(Vec3::ZERO, Vec3::splat(0.2));
    lamps.extend(octahedron(Vec3::new(5.0, 0.0, 0.0), Vec3::splat(0.2)));
    let groups = groups_of(&mut lamps);
    assert_eq!(groups, [(0..8).collect::<Vec<_>>(), (8..16).collect()]);
    // A 12 m strip of 60 triangles: in pieces within the bound.
    let mut strip: Vec<EmissiveTriangle> = (0..60)
        .map(|i| {
            let x = 0.2 * i as f32;
            EmissiveTriangle {
                v: [
                    Vec3::new(x, 3.0, 0.0),
                    Vec3::new(x + 0.2, 3.0, 0.0),
                    Vec3::new(x, 3.0, 0.3),
                ],
                prim: 0,
            }
        })
        .collect();
    let pieces = groups_of(&mut strip).len();
    assert!((12..=32).contains(&pieces), "{pieces} strip pieces");
}
