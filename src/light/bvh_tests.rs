//! Light BVH: the arc-cosine shortcuts keep libm's bits, the importance
//! set up per node keeps the direct formula's bits, and the
//! parallel build gives the serial tree.

use super::*;
use crate::sampler::rng::Rng;
use node::Packed;
use std::hint::black_box;

/// The cone union as written before its shortcut: three arc cosines.
fn cone_union_plain(wa: Vec3, cos_a: f32, wb: Vec3, cos_b: f32) -> (Vec3, f32) {
    if cos_a == -1.0 || cos_b == -1.0 {
        return (wa, -1.0);
    }
    let theta_a = cos_a.clamp(-1.0, 1.0).acos();
    let theta_b = cos_b.clamp(-1.0, 1.0).acos();
    let theta_d = wa.dot(wb).clamp(-1.0, 1.0).acos();
    if (theta_d + theta_b).min(std::f32::consts::PI) <= theta_a {
        return (wa, cos_a);
    }
    if (theta_d + theta_a).min(std::f32::consts::PI) <= theta_b {
        return (wb, cos_b);
    }
    let theta_o = 0.5 * (theta_a + theta_d + theta_b);
    if theta_o >= std::f32::consts::PI {
        return (wa, -1.0);
    }
    let theta_r = theta_o - theta_a;
    let axis = wa.cross(wb);
    if axis.length_squared() < 1e-12 {
        let theta = (theta_d + theta_b).max(theta_a).min(std::f32::consts::PI);
        return (wa, theta.cos());
    }
    let w = glam::Quat::from_axis_angle(axis.normalize(), theta_r) * wa;
    (w.normalize(), theta_o.cos())
}

#[test]
fn acos_shortcuts_are_the_libm_bits() {
    for c in [1.0f32, 0.0, -0.0] {
        assert_eq!(
            acos_clamped(c).to_bits(),
            black_box(c).acos().to_bits(),
            "acos {c}"
        );
    }
    assert_eq!(acos_clamped(1.5), 0.0);
    assert_eq!(acos_clamped(-0.25), (-0.25f32).acos());
}

#[test]
fn cone_union_gives_the_bits_of_three_arc_cosines() {
    let mut rng = Rng::new(&[0x9e37_79b9_7f4a_7c15]);
    let mut u = move || rng.f32();
    let axes = [Vec3::Z, -Vec3::Z, Vec3::X, Vec3::new(0.6, 0.0, 0.8)];
    let (mut shortcut, mut general) = (0, 0);
    for k in 0..20_000 {
        let mut dir = || {
            if u() < 0.5 {
                axes[(u() * 4.0) as usize % 4]
            } else {
                Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize()
            }
        };
        let (wa, wb) = (dir(), if k % 3 == 0 { Vec3::ZERO } else { dir() });
        let wb = if wb == Vec3::ZERO { wa } else { wb };
        let mut cos = || match (u() * 5.0) as u32 {
            0 => 1.0,
            1 => 0.0,
            2 => -1.0,
            _ => 2.0 * u() - 1.0,
        };
        let (ca, cb) = (cos(), cos());
        let cb = if k % 5 == 0 { ca } else { cb };
        let fast = cone_union(wa, ca, wb, cb);
        let plain = cone_union_plain(wa, ca, wb, cb);
        assert_eq!(
            (fast.0.to_array().map(f32::to_bits), fast.1.to_bits()),
            (plain.0.to_array().map(f32::to_bits), plain.1.to_bits()),
            "{wa} {ca} ∪ {wb} {cb}"
        );
        if wa.dot(wb) >= 1.0 && ca > -1.0 && cb > -1.0 && (cb == 1.0 || cb == ca) {
            shortcut += 1;
        } else {
            general += 1;
        }
    }
    // Both paths were exercised.
    assert!(shortcut > 1000 && general > 1000, "{shortcut} {general}");
}

#[test]
fn a_tree_built_in_parallel_is_the_serial_tree() {
    let mut rng = Rng::new(&[0x1234_5678_9abc_def1]);
    let mut u = move || rng.f32();
    let bounds: Vec<LightBounds> = (0..3000)
        .map(|k| {
            let p = Vec3::new(u() * 300.0, u() * 200.0, u() * 12.0);
            let w = [Vec3::Z, -Vec3::Z, Vec3::X, -Vec3::Y][k % 4];
            LightBounds {
                p_min: p,
                p_max: p + Vec3::new(u(), u(), 0.1),
                w,
                // Some lights off: left out of both trees.
                phi: if k % 17 == 0 { 0.0 } else { 0.1 + u() * 50.0 },
                cos_theta_o: 1.0,
                cos_theta_e: 0.0,
                two_sided: k % 5 == 0,
            }
        })
        .collect();
    let serial = LightBvh::build_with_grain(&bounds, usize::MAX);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    for grain in [1, 7, 300] {
        let parallel = pool.install(|| LightBvh::build_with_grain(&bounds, grain));
        assert!(parallel == serial, "grain {grain}");
    }
    // The trails lead to the lights: what sampling returns, pmf replays.
    let p = Vec3::new(150.0, 100.0, 1.5);
    let mut found = 0;
    for k in 0..200 {
        if let Some((light, pmf)) = serial.sample(p, (k as f32 + 0.5) / 200.0) {
            assert_eq!(
                serial.pmf(p, light).to_bits(),
                pmf.to_bits(),
                "light {light}"
            );
            assert!(bounds[light as usize].phi > 0.0);
            found += 1;
        }
    }
    assert!(found > 100, "{found}");
}

/// The importance as written before its per-node set-up: everything
/// recomputed from the bounds at each call.
fn importance_plain(b: &LightBounds, p: Vec3) -> f32 {
    let pc = 0.5 * (b.p_min + b.p_max);
    let d2 = p
        .distance_squared(pc)
        .max(0.5 * (b.p_max - b.p_min).length());
    let wi = (p - pc).normalize_or_zero();
    let mut cos_w = b.w.dot(wi);
    if b.two_sided {
        cos_w = cos_w.abs();
    }
    let sin_w = safe_sqrt(1.0 - cos_w * cos_w);
    let r2 = (0.25 * (b.p_max - b.p_min).length_squared()).max(0.0);
    let dc2 = p.distance_squared(pc);
    let cos_b = if dc2 < r2 || dc2 == 0.0 {
        -1.0
    } else {
        safe_sqrt(1.0 - r2 / dc2)
    };
    let sin_b = safe_sqrt(1.0 - cos_b * cos_b);
    let sin_o = safe_sqrt(1.0 - b.cos_theta_o * b.cos_theta_o);
    let (cos_x, sin_x) = angle_sub_clamped(sin_w, cos_w, sin_o, b.cos_theta_o);
    let (cos_p, _) = angle_sub_clamped(sin_x, cos_x, sin_b, cos_b);
    if cos_p <= b.cos_theta_e {
        return 0.0;
    }
    (b.phi * cos_p / d2).max(0.0)
}

#[test]
fn importance_set_up_per_node_gives_the_direct_formulas_bits() {
    let mut rng = Rng::new(&[0x2545_f491_4f6c_dd1d]);
    let mut u = move || rng.f32();
    let (mut lit, mut dark) = (0, 0);
    for k in 0..20_000 {
        let (phi, cos_o) = (0.1 + 100.0 * u(), 2.0 * u() - 1.0);
        let mut v = |scale: f32| Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * scale;
        let c = v(40.0);
        // Points (zero box), small lamps and large clusters.
        let half = match k % 3 {
            0 => Vec3::ZERO,
            1 => v(0.5).abs(),
            _ => v(30.0).abs(),
        };
        let w = v(2.0).normalize_or(Vec3::Z);
        let b = LightBounds {
            p_min: c - half,
            p_max: c + half,
            w,
            phi,
            cos_theta_o: [1.0, -1.0, 0.3, cos_o][k % 4],
            cos_theta_e: [0.0, 0.5, 0.0][k % 3],
            two_sided: k % 5 == 0,
        };
        // Receivers far, near and inside the box, and at its centre.
        let p = match k % 7 {
            0 => c,
            1 => c + half * 0.3,
            _ => c + v(60.0),
        };
        let (fast, plain) = (b.importance(p), importance_plain(&b, p));
        assert_eq!(fast.to_bits(), plain.to_bits(), "bounds {b:?} at {p}");
        if plain > 0.0 {
            lit += 1;
        } else {
            dark += 1;
        }
    }
    // Both outcomes exercised.
    assert!(lit > 1000 && dark > 1000, "lit {lit}, dark {dark}");
}

#[test]
fn walks_stepped_together_give_each_walks_own_choice() {
    let mut rng = Rng::new(&[0x5851_f42d_4c95_7f2d]);
    let mut u = move || rng.f32();
    let bounds = town_like_bounds(&mut u, 500);
    let tree = LightBvh::build(&bounds);
    let (mut shared, mut apart, mut none) = (0, 0, 0);
    for k in 0..4000 {
        let p = Vec3::new(u() * 140.0 - 10.0, u() * 100.0 - 10.0, u() * 12.0);
        let n = match k % 3 {
            0 => Vec3::ZERO,
            1 => Vec3::Z,
            _ => Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize(),
        };
        let u0 = u();
        // Equal and nearby numbers walk the same nodes for a while.
        let u1 = match k % 4 {
            0 => u0,
            1 => (u0 + 1e-3 * u()).min(0.999),
            _ => u(),
        };
        let us = [Some(u0), None, Some(u1)];
        let together = tree.sample_facing_many(p, n, us);
        let alone = us.map(|u| u.and_then(|u| tree.sample_facing(p, n, u)));
        let bits = |r: [Option<(u32, f32)>; 3]| r.map(|c| c.map(|(l, pmf)| (l, pmf.to_bits())));
        assert_eq!(bits(together), bits(alone), "p {p}, n {n}, u {us:?}");
        // And what the trail replays.
        for (light, pmf) in together.into_iter().flatten() {
            assert_eq!(tree.pmf_facing(p, n, light).to_bits(), pmf.to_bits());
        }
        match together {
            [Some(a), _, Some(b)] if a.0 == b.0 => shared += 1,
            [Some(_), _, Some(_)] => apart += 1,
            _ => none += 1,
        }
    }
    // Walks that end together, apart, and walks that find nothing.
    assert!(
        shared > 500 && apart > 500 && none > 50,
        "{shared} {apart} {none}"
    );
}

/// Street lamps, windows on facades and some spots.
fn town_like_bounds(u: &mut impl FnMut() -> f32, count: usize) -> Vec<LightBounds> {
    (0..count)
        .map(|k| {
            let p = Vec3::new(u() * 120.0, u() * 80.0, u() * 10.0);
            LightBounds {
                p_min: p,
                p_max: p + Vec3::new(u(), u(), 0.1) * (k % 3) as f32,
                w: [Vec3::Z, -Vec3::Z, Vec3::X, -Vec3::Y][k % 4],
                phi: 0.1 + u() * 50.0,
                cos_theta_o: [1.0, -1.0, 0.9][k % 3],
                cos_theta_e: [0.0, 0.0, 0.8][k % 3],
                two_sided: k % 5 == 0,
            }
        })
        .collect()
}

#[test]
fn nodes_weighed_together_give_each_nodes_own_importance() {
    let mut rng = Rng::new(&[0x94d0_49bb_1331_11eb]);
    let mut u = move || rng.f32();
    let nodes: Vec<Packed> = town_like_bounds(&mut u, 700)
        .iter()
        .enumerate()
        .map(|(k, b)| Packed::new(b, 0, k % 2 == 0))
        .collect();
    let mut lit = 0;
    for (k, group) in nodes.chunks_exact(7).enumerate() {
        let p = Vec3::new(u() * 140.0 - 10.0, u() * 100.0 - 10.0, u() * 12.0);
        let n = match k % 3 {
            0 => Vec3::ZERO,
            1 => Vec3::Z,
            _ => Vec3::new(u() - 0.5, u() - 0.5, u() - 0.5).normalize(),
        };
        let group: [&Packed; 7] = std::array::from_fn(|i| &group[i]);
        let together = node::at_unculled_many(&group, p, n);
        for (b, at) in group.iter().zip(together) {
            assert_eq!(
                at.to_bits(),
                b.at_unculled(p, n).to_bits(),
                "{b:?} at {p}, n {n}"
            );
            lit += (at > 0.0) as usize;
        }
    }
    assert!(lit > 100, "{lit} lit");
}

#[test]
fn more_walks_than_a_levels_lanes_give_each_walks_own_choice() {
    let mut rng = Rng::new(&[0x2f3c_1a5e_77d1_0b43]);
    let mut u = move || rng.f32();
    let tree = LightBvh::build(&town_like_bounds(&mut u, 3000));
    let mut distinct = 0;
    for k in 0..1500 {
        let p = Vec3::new(u() * 140.0 - 10.0, u() * 100.0 - 10.0, u() * 12.0);
        let n = if k % 2 == 0 { Vec3::ZERO } else { Vec3::Z };
        // Eleven walks: 22 children a level once they part, more than
        // `LANES`; stratified as RIS draws them, one missing.
        let us: [Option<f32>; 11] =
            std::array::from_fn(|i| (i != 4).then(|| (i as f32 + u()) / 11.0));
        let together = tree.sample_facing_many(p, n, us);
        let alone = us.map(|u| u.and_then(|u| tree.sample_facing(p, n, u)));
        let bits = |r: [Option<(u32, f32)>; 11]| r.map(|c| c.map(|(l, pmf)| (l, pmf.to_bits())));
        assert_eq!(bits(together), bits(alone), "p {p}, n {n}, u {us:?}");
        let mut lights: Vec<u32> = together.iter().flatten().map(|c| c.0).collect();
        lights.sort_unstable();
        lights.dedup();
        distinct += lights.len();
    }
    // The walks part: most levels weigh more children than one pass holds.
    assert!(distinct > 1500 * 7, "{distinct} lights");
}
