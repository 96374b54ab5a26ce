//! Cuts of the light tree for a region of receivers (`light::bvh::cut`):
//! every light that can reach a point of the region keeps a nonzero
//! probability there, the probabilities a walk from the cut returns are
//! the ones replayed for its light, and over all lights they sum to the
//! share of walks that find one.

use glam::Vec3;
use parallax::light::bvh::{LightBounds, LightBvh, Region};

use super::bvh::{random_lights, Rng};

/// A point of the ball (`c`, `r`).
fn in_ball(rng: &mut Rng, c: Vec3, r: f32) -> Vec3 {
    loop {
        let v = rng.v(2.0);
        if v.length() <= 1.0 {
            return c + v * r;
        }
    }
}

/// A unit normal within `spread` of unit `axis` (|n − axis| ≤ spread).
fn near(rng: &mut Rng, axis: Vec3, spread: f32) -> Vec3 {
    loop {
        let n = (axis + rng.v(2.0 * spread)).normalize();
        if (n - axis).length() <= spread {
            return n;
        }
    }
}

/// Regions of 1–2 m radius in the lights' box: no normal, or normals
/// within 0.25 of an axis.
fn regions(rng: &mut Rng, count: usize) -> Vec<Region> {
    let axes = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
    (0..count)
        .map(|k| Region {
            centre: rng.v(50.0),
            radius: 1.0 + rng.f(),
            facing: (k % 3 != 0).then(|| (axes[k % 6], 0.25)),
        })
        .collect()
}

/// A receiver of `region`: a point of its ball, and a normal of its bin
/// (zero where it has none).
fn receiver(rng: &mut Rng, region: &Region) -> (Vec3, Vec3) {
    let p = in_ball(rng, region.centre, region.radius);
    let n = match region.facing {
        Some((axis, spread)) => near(rng, axis, spread),
        None => Vec3::ZERO,
    };
    (p, n)
}

#[test]
fn a_cut_keeps_every_light_that_can_reach_a_point_of_its_region() {
    let mut rng = Rng(51);
    let lights = random_lights(1500, &mut rng);
    let bvh = LightBvh::build(&lights);
    let (mut reaching, mut culled_nodes) = (0, 0);
    for region in regions(&mut rng, 60) {
        let cut = bvh.cut(&region, 64);
        assert!(!cut.is_empty() && cut.len() <= 64, "{} nodes", cut.len());
        culled_nodes += (cut.len() < 64) as u32;
        for _ in 0..20 {
            let (p, n) = receiver(&mut rng, &region);
            for (i, l) in lights.iter().enumerate() {
                // The light's own bound at the receiver: zero only where
                // it cannot light it.
                if l.importance_facing(p, n) > 0.0 {
                    reaching += 1;
                    let pmf = bvh.pmf_in_cut(&cut, (p, n), i as u32);
                    assert!(pmf > 0.0, "light {i} reaches {p} (n {n}) of {region:?}");
                }
            }
        }
    }
    assert!(reaching > 500_000, "{reaching} reaching pairs");
    assert!(culled_nodes < 60, "every cut filled its 64 nodes");
}

#[test]
fn walks_from_a_cut_return_the_replayed_pmf_and_sum_to_the_found_share() {
    let mut rng = Rng(53);
    let lights = random_lights(1500, &mut rng);
    let bvh = LightBvh::build(&lights);
    let draws = 4000;
    for region in regions(&mut rng, 24) {
        let cut = bvh.cut(&region, 64);
        let (p, n) = receiver(&mut rng, &region);
        let sum: f64 = (0..lights.len() as u32)
            .map(|i| bvh.pmf_in_cut(&cut, (p, n), i) as f64)
            .sum();
        assert!(sum <= 1.0 + 1e-5, "Σ pmf {sum}");
        let mut found = 0;
        let mut counts = vec![0u32; lights.len()];
        for k in 0..draws {
            let u = (k as f32 + 0.5) / draws as f32;
            let us = [Some(u), None, Some(rng.f())];
            let walked = bvh.sample_in_cut(&cut, (p, n), us);
            assert_eq!(walked[1], None);
            for (i, pmf) in walked.into_iter().flatten() {
                assert_eq!(
                    pmf.to_bits(),
                    bvh.pmf_in_cut(&cut, (p, n), i).to_bits(),
                    "light {i} at {p}, n {n}"
                );
            }
            if let Some((i, _)) = walked[0] {
                found += 1;
                counts[i as usize] += 1;
            }
        }
        let share = found as f64 / draws as f64;
        assert!((share - sum).abs() < 2e-3, "found {share}, Σ pmf {sum}");
        // The most likely lights are drawn as often as their pmf says.
        for (i, &c) in counts.iter().enumerate() {
            let pmf = bvh.pmf_in_cut(&cut, (p, n), i as u32) as f64;
            if pmf > 0.02 {
                let got = c as f64 / draws as f64;
                assert!((got - pmf).abs() < 2e-3, "light {i}: {got} against {pmf}");
            }
        }
    }
}

#[test]
fn a_cut_of_one_leaf_or_of_an_empty_tree_still_answers() {
    let lamp = LightBounds {
        p_min: Vec3::new(0.0, 0.0, 4.0),
        p_max: Vec3::new(0.2, 0.2, 4.0),
        w: -Vec3::Z,
        phi: 3.0,
        cos_theta_o: 1.0,
        cos_theta_e: 0.0,
        two_sided: false,
    };
    let bvh = LightBvh::build(&[lamp]);
    let below = Region {
        centre: Vec3::ZERO,
        radius: 1.0,
        facing: Some((Vec3::Z, 0.1)),
    };
    let cut = bvh.cut(&below, 64);
    assert_eq!(cut.len(), 1);
    let [got] = bvh.sample_in_cut(&cut, (Vec3::ZERO, Vec3::Z), [Some(0.3)]);
    assert_eq!(got, Some((0, 1.0)));
    // Above the lamp it faces away: no node is left.
    let above = Region {
        centre: Vec3::new(0.0, 0.0, 8.0),
        ..below
    };
    let cut = bvh.cut(&above, 64);
    assert!(cut.is_empty());
    assert_eq!(bvh.pmf_in_cut(&cut, (above.centre, Vec3::Z), 0), 0.0);
    let empty = LightBvh::build(&[]);
    let cut = empty.cut(&below, 64);
    assert!(cut.is_empty());
    assert_eq!(
        empty.sample_in_cut(&cut, (Vec3::ZERO, Vec3::Z), [Some(0.5)]),
        [None]
    );
}
