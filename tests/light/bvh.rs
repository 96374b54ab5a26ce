//! The light BVH's selection probabilities: the pmf returned with a sample is
//! the pmf recomputed for that light, the pmfs over all lights sum to one, and
//! a scene lit by ~1000 small emitters renders to the same mean image with the
//! BVH as with uniform selection (both unbiased; MIS at emitter hits uses the
//! recomputed pmf, so a mismatch would show as bias).

use crate::common::light;

use glam::Vec3;
use parallax::light::bvh::{LightBounds, LightBvh};
use parallax::light::{LightSelection, LightSet};
use parallax::scene::{parse_scene_str, LoadedScene};

/// A small deterministic generator (SplitMix64) for test inputs.
pub(crate) struct Rng(pub(crate) u64);

impl Rng {
    pub(crate) fn f(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
    pub(crate) fn v(&mut self, s: f32) -> Vec3 {
        Vec3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5) * s
    }
}

/// Points, spots and one- and two-sided triangles scattered in a 40 m box.
pub(crate) fn random_lights(n: usize, rng: &mut Rng) -> Vec<LightBounds> {
    (0..n)
        .map(|k| {
            let p = rng.v(40.0);
            let w = rng.v(2.0).normalize_or(Vec3::Z);
            let phi = 0.1 + 10.0 * rng.f();
            match k % 4 {
                0 => LightBounds {
                    p_min: p,
                    p_max: p,
                    w: Vec3::Z,
                    phi,
                    cos_theta_o: -1.0,
                    cos_theta_e: 0.0,
                    two_sided: false,
                },
                1 => LightBounds {
                    p_min: p,
                    p_max: p,
                    w,
                    phi,
                    cos_theta_o: 0.9,
                    cos_theta_e: 0.95,
                    two_sided: false,
                },
                _ => LightBounds {
                    p_min: p,
                    p_max: p + rng.v(0.5).abs(),
                    w,
                    phi,
                    cos_theta_o: 1.0,
                    cos_theta_e: 0.0,
                    two_sided: k % 4 == 3,
                },
            }
        })
        .collect()
}

#[test]
fn sampled_pmf_equals_recomputed_pmf_bitwise() {
    let mut rng = Rng(7);
    let lights = random_lights(2000, &mut rng);
    let bvh = LightBvh::build(&lights);
    let mut checked = 0;
    for _ in 0..2000 {
        let p = rng.v(60.0);
        if let Some((i, pmf)) = bvh.sample(p, rng.f()) {
            assert!(pmf > 0.0 && pmf <= 1.0, "pmf {pmf}");
            assert_eq!(pmf.to_bits(), bvh.pmf(p, i).to_bits(), "light {i} at {p}");
            checked += 1;
        }
    }
    // Some points lie where only part of the lights reach: None is allowed there.
    assert!(checked > 1500, "only {checked} samples");
}

#[test]
fn pmf_sums_to_one_over_all_lights() {
    // Point lights only: every light reaches every point.
    let mut rng = Rng(11);
    let lights: Vec<LightBounds> = random_lights(6000, &mut rng)
        .into_iter()
        .step_by(4)
        .collect();
    let bvh = LightBvh::build(&lights);
    for _ in 0..50 {
        let p = rng.v(60.0);
        let sum: f64 = (0..lights.len() as u32).map(|i| bvh.pmf(p, i) as f64).sum();
        assert!((sum - 1.0).abs() < 1e-5, "sum {sum} at {p}");
    }
}

#[test]
fn a_reflecting_receivers_normal_skips_lights_behind_it_with_consistent_pmfs() {
    // Point lights only (every one reaches every point without a normal):
    // with a receiver normal, lights below its plane get pmf 0, those in
    // front share all of it, and sampling returns the pmf recomputed for its
    // light.
    let mut rng = Rng(29);
    let lights: Vec<LightBounds> = random_lights(6000, &mut rng)
        .into_iter()
        .step_by(4)
        .collect();
    let bvh = LightBvh::build(&lights);
    let mut behind = 0;
    for _ in 0..40 {
        let p = rng.v(60.0);
        let n = rng.v(2.0).normalize_or(Vec3::Z);
        let (mut sum, mut front) = (0.0f64, 0);
        for (i, l) in lights.iter().enumerate() {
            let (pf, plain) = (bvh.pmf_facing(p, n, i as u32), bvh.pmf(p, i as u32));
            if (l.p_min - p).dot(n) < 0.0 {
                assert_eq!(pf, 0.0, "light {i} behind the receiver at {p}, n {n}");
                behind += 1;
            } else {
                assert!(plain > 0.0, "light {i} reaches {p}");
                front += 1;
            }
            sum += pf as f64;
        }
        // The lights in front share all of the mass (a walk that ended
        // where both children of a node lie behind would lose some).
        if front > 0 {
            assert!((sum - 1.0).abs() < 1e-5, "sum {sum} at {p}, n {n}");
        } else {
            assert_eq!(sum, 0.0);
        }
        let draws = 4000;
        let mut none = 0;
        for k in 0..draws {
            let Some((i, pmf)) = bvh.sample_facing(p, n, (k as f32 + 0.5) / draws as f32) else {
                none += 1;
                continue;
            };
            assert!((lights[i as usize].p_min - p).dot(n) >= 0.0);
            assert_eq!(pmf.to_bits(), bvh.pmf_facing(p, n, i).to_bits());
        }
        let missing = 1.0 - sum;
        assert!(
            (none as f64 / draws as f64 - missing).abs() < 2e-3,
            "{none} vs {missing}"
        );
        // A zero normal is the plain tree, bit for bit.
        let u = rng.f();
        assert_eq!(bvh.sample_facing(p, Vec3::ZERO, u), bvh.sample(p, u));
    }
    assert!(behind > 20_000, "{behind} behind");
}

/// Share of walks (stratified `u`, `draws` per receiver) that return no
/// light at receivers with at least one light in front, and the largest
/// |Σ pmf − 1| over those receivers.
fn empty_walks(lights: &[LightBounds], receivers: &[(Vec3, Vec3)], draws: u32) -> (f64, f64) {
    let bvh = LightBvh::build(lights);
    let (mut empty, mut total, mut worst) = (0u64, 0u64, 0.0f64);
    for &(p, n) in receivers {
        let in_front = |l: &LightBounds| (l.p_min - p).dot(n) > 0.0 || (l.p_max - p).dot(n) > 0.0;
        if !lights.iter().any(in_front) {
            continue;
        }
        let sum: f64 = (0..lights.len() as u32)
            .map(|i| bvh.pmf_facing(p, n, i) as f64)
            .sum();
        worst = worst.max((sum - 1.0).abs());
        for k in 0..draws {
            let u = (k as f32 + 0.5) / draws as f32;
            empty += bvh.sample_facing(p, n, u).is_none() as u64;
            total += 1;
        }
    }
    (empty as f64 / total as f64, worst)
}

#[test]
fn walks_from_receivers_with_a_light_in_front_always_find_one() {
    // Point lights in a 40 m box seen from receivers of random normals (the
    // union of two children's boxes can cross a receiver's plane while both
    // lie behind it: 8–15 % of walks ended there), ...
    let mut rng = Rng(41);
    for count in [16, 200, 1500] {
        let lights: Vec<LightBounds> = random_lights(4 * count, &mut rng)
            .into_iter()
            .step_by(4)
            .collect();
        let receivers: Vec<(Vec3, Vec3)> = (0..150)
            .map(|_| (rng.v(60.0), rng.v(2.0).normalize_or(Vec3::Z)))
            .collect();
        let (empty, worst) = empty_walks(&lights, &receivers, 400);
        assert_eq!(empty, 0.0, "{count} lights: {empty} of walks empty");
        assert!(worst < 1e-5, "{count} lights: Σ pmf off by {worst}");
    }
    // ... and 30 cm lamps 5 m up on a 2 km grid seen from the lamps' height
    // facing up and down, where every lamp box crosses the plane at a
    // grazing angle far away (the bound on the receiver's cosine must not
    // round to zero there).
    let mut rng = Rng(43);
    let mut lamps = Vec::new();
    for i in 0..40 {
        for j in 0..40 {
            let c = Vec3::new(50.0 * i as f32, 50.0 * j as f32, 5.0) + rng.v(8.0).with_z(0.0);
            lamps.push(LightBounds {
                p_min: c,
                p_max: c + Vec3::splat(0.3),
                w: Vec3::Z,
                phi: 1.0 + rng.f(),
                cos_theta_o: -1.0,
                cos_theta_e: 0.0,
                two_sided: false,
            });
        }
    }
    let receivers: Vec<(Vec3, Vec3)> = (0..60)
        .map(|k| {
            let p = Vec3::new(2000.0 * rng.f(), 2000.0 * rng.f(), 5.0 + 0.3 * rng.f());
            (p, [Vec3::Z, -Vec3::Z, Vec3::X, -Vec3::Y][k % 4])
        })
        .collect();
    let (empty, worst) = empty_walks(&lamps, &receivers, 400);
    assert_eq!(empty, 0.0, "lamp grid: {empty} of walks empty");
    assert!(worst < 1e-5, "lamp grid: Σ pmf off by {worst}");
}

#[test]
fn pmf_sum_plus_no_light_probability_is_one_for_mixed_lights() {
    // Points, spots and one- and two-sided emitters: where a whole subtree
    // cannot reach p, sampling returns None with exactly the missing mass.
    let mut rng = Rng(13);
    let lights = random_lights(1500, &mut rng);
    let bvh = LightBvh::build(&lights);
    let n = 100_000;
    for _ in 0..8 {
        let p = rng.v(60.0);
        let sum: f64 = (0..lights.len() as u32).map(|i| bvh.pmf(p, i) as f64).sum();
        assert!(sum <= 1.0 + 1e-5 && sum > 0.5, "sum {sum} at {p}");
        let none = (0..n)
            .filter(|&k| bvh.sample(p, (k as f32 + 0.5) / n as f32).is_none())
            .count();
        let missing = 1.0 - sum;
        assert!(
            (none as f64 / n as f64 - missing).abs() < 2e-3,
            "{none} vs {missing}"
        );
    }
}

#[test]
fn sampling_frequencies_match_pmf() {
    let mut rng = Rng(3);
    let lights = random_lights(12, &mut rng);
    let bvh = LightBvh::build(&lights);
    let p = Vec3::new(1.0, -2.0, 0.5);
    let n = 200_000;
    let mut counts = [0u32; 12];
    for k in 0..n {
        if let Some((i, _)) = bvh.sample(p, (k as f32 + 0.5) / n as f32) {
            counts[i as usize] += 1;
        }
    }
    assert!(counts.iter().sum::<u32>() > n / 2);
    for (i, &c) in counts.iter().enumerate() {
        let expected = bvh.pmf(p, i as u32) as f64;
        let got = c as f64 / n as f64;
        assert!(
            (got - expected).abs() < 1e-3,
            "light {i}: {got} vs {expected}"
        );
    }
}

#[test]
fn build_is_deterministic_across_thread_pools() {
    let lights = random_lights(3000, &mut Rng(5));
    let in_pool = |threads| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| LightBvh::build(&lights))
    };
    assert_eq!(in_pool(1), in_pool(2));
}

#[test]
fn lights_that_cannot_reach_a_point_get_zero_pmf() {
    // One-sided emitter facing +z and a point light: below the emitter only
    // the point light can be chosen.
    let tri = LightBounds {
        p_min: Vec3::new(-0.5, -0.5, 0.0),
        p_max: Vec3::new(0.5, 0.5, 0.0),
        w: Vec3::Z,
        phi: 100.0,
        cos_theta_o: 1.0,
        cos_theta_e: 0.0,
        two_sided: false,
    };
    let point = LightBounds {
        p_min: Vec3::new(5.0, 0.0, 0.0),
        p_max: Vec3::new(5.0, 0.0, 0.0),
        w: Vec3::Z,
        phi: 1.0,
        cos_theta_o: -1.0,
        cos_theta_e: 0.0,
        two_sided: false,
    };
    let bvh = LightBvh::build(&[tri, point]);
    let below = Vec3::new(0.0, 0.0, -3.0);
    assert_eq!(bvh.pmf(below, 0), 0.0);
    assert_eq!(bvh.pmf(below, 1), 1.0);
    let above = Vec3::new(0.0, 0.0, 3.0);
    assert!(bvh.pmf(above, 0) > 0.9, "{}", bvh.pmf(above, 0));
}

/// A 20 m floor under a 32 × 32 grid of small one-sided emitters facing down
/// (2048 triangles, 1024 emitters) at random heights and radiances, plus one
/// point light.
fn many_emitters_scene() -> LoadedScene {
    let mut rng = Rng(17);
    let mut t = String::from(
        "[camera]\nwidth = 48\nheight = 36\nhfov_deg = 70.0\nbaselines_cm = [10.0]\n\
position = [0.0, 0.0, 6.0]\npitch_deg = 90.0\n\
[render]\nspp = 16\nmax_depth = 2\nseed = 3\n\
[[light]]\nkind = \"point\"\nposition = [3.0, 2.0, 1.5]\nintensity = [2.0, 2.0, 2.0]\n\
[[material]]\nname = \"floor\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n\
[[object]]\nkind = \"quad\"\nsize = [20.0, 20.0]\nmaterial = \"floor\"\n",
    );
    for k in 0..4 {
        let le = 5.0 + 20.0 * k as f32;
        t += &format!(
            "[[material]]\nname = \"lamp{k}\"\nkind = \"emissive\"\nradiance = [{le:?}, {le:?}, {le:?}]\n"
        );
    }
    for i in 0..32 {
        for j in 0..32 {
            let (x, y) = (-9.0 + 18.0 * i as f32 / 31.0, -9.0 + 18.0 * j as f32 / 31.0);
            let z = 0.5 + 2.0 * rng.f();
            let m = (rng.f() * 4.0) as usize % 4;
            t += &format!(
                "[[object]]\nkind = \"quad\"\nsize = [0.1, 0.1]\nmaterial = \"lamp{m}\"\n\
transform = {{ translate = [{x:?}, {y:?}, {z:?}], rotate_deg = [180.0, 0.0, 0.0] }}\n"
            );
        }
    }
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
    parse_scene_str(&t, &path).unwrap_or_else(|e| panic!("scene: {e}"))
}

#[test]
fn light_set_pmf_is_consistent_on_many_emitters() {
    let b = light::build(&many_emitters_scene());
    let set = LightSet::build(&b.scene);
    // Each lamp's two triangles are one emitter (`light::emitter`).
    assert_eq!(set.len(), 32 * 32 + 1);
    let mut rng = Rng(23);
    // Floor points in render space (centred on the camera, 6 m up).
    let z_floor = -b.scene.origin_world.z as f32;
    for _ in 0..20 {
        let p = Vec3::new(0.0, 0.0, z_floor + 1e-3) + rng.v(18.0) * Vec3::new(1.0, 1.0, 0.0);
        let sum: f64 = (0..set.len())
            .map(|i| set.pmf_at(p, Vec3::ZERO, i, 0) as f64)
            .sum();
        assert!((sum - 1.0).abs() < 1e-5, "sum {sum}");
        for _ in 0..50 {
            let (i, pmf) = set
                .select_at(p, Vec3::ZERO, rng.f(), 0)
                .expect("a light reaches the floor");
            assert_eq!(pmf.to_bits(), set.pmf_at(p, Vec3::ZERO, i, 0).to_bits());
        }
    }
}

#[test]
fn bvh_and_uniform_selection_render_the_same_mean_image() {
    let b = light::build(&many_emitters_scene());
    let bvh = light::render_left(&b, LightSelection::Bvh, 64, 2, 1);
    let uni = light::render_left(&b, LightSelection::Uniform, 64, 2, 2);
    let ((mb, sb), (mu, su)) = (bvh.image_mean(), uni.image_mean());
    let z = (mb - mu).abs() / (sb * sb + su * su).sqrt();
    eprintln!("bvh {mb:.5} ± {sb:.5}, uniform {mu:.5} ± {su:.5}, z = {z:.2}");
    assert!(mb > 0.01, "image is lit");
    assert!(z < 4.0, "means differ: z = {z}");
    // The BVH should also be the less noisy estimator here.
    assert!(sb < su, "bvh error {sb} vs uniform {su}");
}
