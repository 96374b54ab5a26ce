//! Drawing a distant light's direction first and its radiance later
//! (`sample_distant_dir` + `distant_li`) must give the bits `sample_distant`
//! gives, for the sun seen through a cloud deck and for the sky, clear and
//! under fog; and the sky joins next-event estimation only without a sun or
//! under fog.

use std::path::Path;

use glam::{DVec3, Vec2, Vec3};

use crate::light::LightSet;
use crate::sampler::rng::Rng;
use crate::scene::{build_scene, parse_scene_str};

const BODY: &str = "[camera]\nposition = [0.0, 0.0, 1.5]\n[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n[[object]]\nkind = \"quad\"\nsize = [10.0, 10.0]\nmaterial = \"grey\"\n";
const CLOUDY: &str = "[sky]\nkind = \"physical\"\nsun_elevation_deg = 35.0\nsun_azimuth_deg = 20.0\ncloud_cover = 0.6\n";
const FOG: &str = "[medium]\nkind = \"homogeneous\"\nsigma_t = 0.02\nalbedo = [0.9, 0.9, 0.9]\ng = 0.5\nz_max_m = 40.0\n";
const OVERCAST: &str = "[sky]\nkind = \"overcast\"\nirradiance = [120.0, 120.0, 130.0]\n";
const GRADIENT: &str = "[sky]\nkind = \"gradient\"\nzenith = [0.3, 0.5, 1.0]\nhorizon = [1.0, 1.0, 1.0]\nground = [0.2, 0.2, 0.2]\n[[light]]\nkind = \"sun\"\nelevation_deg = 30.0\nazimuth_deg = 0.0\nirradiance = [900.0, 900.0, 900.0]\n";

fn scene_with(extra: &str) -> crate::scene::Scene {
    let text = format!("{BODY}{extra}");
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
    let loaded = parse_scene_str(&text, &file).expect("scene parses");
    build_scene(&loaded, DVec3::ZERO).expect("scene builds")
}

/// Checks every distant light of the scene with `extra`; returns how many
/// samples carried radiance.
fn check(extra: &str) -> usize {
    let scene = scene_with(extra);
    let lights = LightSet::build(&scene);
    let mut nonzero = 0;
    for k in 0..lights.distant_count() {
        for i in 0..64 {
            let u = Vec2::new((i % 8) as f32 / 8.0 + 0.03, (i / 8) as f32 / 8.0 + 0.07);
            let p = Vec3::new(i as f32 * 3.0 - 90.0, 2.0 * i as f32, 0.5);
            let whole = lights.sample_distant(&scene, k, p, u);
            let split = lights.sample_distant_dir(&scene, k, p, u).map(|mut ls| {
                assert_eq!(ls.li, Vec3::ZERO, "no radiance before distant_li");
                ls.li = lights.distant_li(&scene, k, p, ls.wi);
                ls
            });
            let bits = |ls: Option<crate::light::LightSample>| {
                ls.map(|l| {
                    let v = [l.wi.to_array(), l.li.to_array()].concat();
                    let v: Vec<u32> = v.into_iter().map(f32::to_bits).collect();
                    (v, l.pdf.to_bits(), l.dist, l.delta)
                })
            };
            let (a, b) = (bits(whole), bits(split));
            assert_eq!(a, b, "light {k}, sample {i}");
            nonzero += whole.is_some_and(|l| l.li != Vec3::ZERO) as usize;
        }
    }
    nonzero
}

#[test]
fn split_distant_sampling_gives_the_same_bits() {
    // 64 draws per distant light, most with radiance: the sun (through a
    // cloud deck or not), the sky under fog, the sky alone when overcast.
    for (extra, n_distant) in [
        (CLOUDY.to_string(), 1),
        (format!("{CLOUDY}{FOG}"), 2),
        (GRADIENT.to_string(), 1),
        (OVERCAST.to_string(), 1),
    ] {
        let n = check(&extra);
        assert!(
            n >= 32 * n_distant,
            "{n} samples with radiance for\n{extra}"
        );
    }
}

#[test]
fn the_sky_joins_nee_only_without_a_sun_or_under_fog() {
    // Escaping along a direction away from the sun after a BSDF sample of
    // pdf 1/π: the sky's full radiance when NEE does not sample it, less
    // (the BSDF share of the power heuristic) when it does.
    let dir = Vec3::new(0.0, -0.6, 0.8);
    let p = Vec3::new(0.0, 0.0, 0.5);
    for (extra, sampled) in [
        (GRADIENT.to_string(), false),
        (CLOUDY.to_string(), false),
        (OVERCAST.to_string(), true),
        (format!("{GRADIENT}{FOG}"), true),
        (format!("{CLOUDY}{FOG}"), true),
    ] {
        let scene = scene_with(&extra);
        let lights = LightSet::build(&scene);
        let suns = scene
            .lights
            .iter()
            .filter(|l| matches!(l, crate::light::Light::Sun { .. }))
            .count();
        assert_eq!(
            lights.distant_count(),
            suns + sampled as usize,
            "distant lights for\n{extra}"
        );
        let le = scene.sky.le(dir);
        assert!(le.min_element() > 0.0, "the sky shines along dir");
        let l = lights.escaped_at(&scene, p, dir, std::f32::consts::FRAC_1_PI, false);
        if sampled {
            let w = l / le;
            assert!(
                w.max_element() < 0.99 && w.min_element() > 0.01,
                "MIS weight {w} for\n{extra}"
            );
        } else {
            assert_eq!(l, le, "full weight for\n{extra}");
        }
    }
}

/// Three point lights of intensity `i` 2–4 m above the plane.
fn points(i: f32) -> String {
    [(1.0, 0.0, 2.0), (-2.0, 1.0, 3.0), (0.5, -3.0, 4.0)]
        .iter()
        .map(|(x, y, z)| {
            format!("[[light]]\nkind = \"point\"\nposition = [{x:?}, {y:?}, {z:?}]\nintensity = [{i:?}, {i:?}, {i:?}]\n")
        })
        .collect()
}

#[test]
fn local_lights_share_sets_candidates_and_the_probability_a_vertex_samples_them() {
    // Faint lamps under a 900 W/m² sun: sampled at a vertex with
    // probability 0.1, one candidate; alone (no sun): always, resampled
    // from more candidates at a path's first vertex than at later ones.
    let p = Vec3::new(0.3, 0.2, 0.0);
    for (extra, candidates, p_local) in [
        (format!("{GRADIENT}{}", points(1.0)), [1, 1], 0.1f32),
        (format!("{OVERCAST}{}", points(1e6)), [8, 2], 1.0),
    ] {
        let scene = scene_with(&extra);
        let lights = LightSet::build(&scene);
        assert_eq!(lights.len(), 3, "{extra}");
        assert_eq!(lights.local_candidates(), candidates[0], "{extra}");
        assert_eq!(lights.local_candidates_at(0), candidates[0], "{extra}");
        for bounce in [1, 3] {
            assert_eq!(lights.local_candidates_at(bounce), candidates[1], "{extra}");
        }
        let total: f32 = (0..3).map(|i| lights.pmf_at(p, Vec3::ZERO, i, 0)).sum();
        assert!((total - p_local).abs() < 1e-5, "Σ pmf {total} for\n{extra}");
        // select_at returns the pmf pmf_at recomputes, and declines for
        // the share 1 − p_local of the numbers.
        let n = 1000;
        let mut declined = 0;
        for k in 0..n {
            let u = (k as f32 + 0.5) / n as f32;
            match lights.select_at(p, Vec3::ZERO, u, 0) {
                Some((i, pmf)) => {
                    assert_eq!(pmf.to_bits(), lights.pmf_at(p, Vec3::ZERO, i, 0).to_bits())
                }
                None => declined += 1,
            }
        }
        let expect = ((1.0 - p_local) * n as f32).round() as i32;
        assert!(
            (declined - expect).abs() <= 1,
            "{declined} declined, {expect} expected"
        );
    }
}

#[test]
fn scene_radius_is_the_farthest_point_within_its_clamp() {
    let quad = |size: f64| {
        let text = format!(
            "[camera]\nposition = [0.0, 0.0, 1.5]\n[[material]]\nname = \"grey\"\nkind = \"diffuse\"\nalbedo = [0.5, 0.5, 0.5]\n[[object]]\nkind = \"quad\"\nsize = [{size}, {size}]\nmaterial = \"grey\"\n{OVERCAST}"
        );
        let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/inline.toml");
        let loaded = parse_scene_str(&text, &file).expect("scene parses");
        super::weights::scene_radius(&build_scene(&loaded, DVec3::ZERO).expect("scene builds"))
    };
    // Corners at half the diagonal; below 1 m and beyond 100 m it is clamped
    // (the walk stops at the first corner past 100 m).
    assert!((quad(10.0) - 50f32.sqrt()).abs() < 1e-5, "{}", quad(10.0));
    assert_eq!(quad(1.0), 1.0);
    assert_eq!(quad(300.0), 100.0);
}

#[test]
fn deeper_vertices_sample_faint_lamps_less_often_and_keep_their_mean() {
    // Lamps with a few percent of the power under an overcast sky: every
    // first vertex samples them, later ones with a probability below 1.
    // At both, the selection's pmf is the one pmf_at recomputes, and the
    // irradiance estimate from stratified numbers is the closed form
    // Σ I·cos θ / d² of the three points.
    let found = [30.0f32, 100.0, 300.0, 1e3, 3e3].into_iter().find_map(|i| {
        let scene = scene_with(&format!("{OVERCAST}{}", points(i)));
        let lights = LightSet::build(&scene);
        let deep = lights.p_local_at(1);
        (lights.p_local_at(0) == 1.0 && deep > 0.1 && deep < 0.9).then_some((i, scene, lights))
    });
    let (i, scene, lights) = found.expect("an intensity with 0.1 < p_local_at(1) < 0.9");
    let (p, n) = (Vec3::new(0.3, 0.2, 0.0), Vec3::Z);
    let exact: f32 = [(1.0, 0.0, 2.0), (-2.0, 1.0, 3.0), (0.5, -3.0, 4.0)]
        .iter()
        .map(|&(x, y, z)| {
            let d = Vec3::new(x, y, z) - p;
            i * n.dot(d.normalize()) / d.length_squared()
        })
        .sum();
    for bounce in [0, 1, 5] {
        let m = 20_000;
        let mut sum = 0.0f64;
        let mut taken = 0;
        for k in 0..m {
            let u = (k as f32 + 0.5) / m as f32;
            if let Some((idx, pmf)) = lights.select_at(p, n, u, bounce) {
                assert_eq!(pmf.to_bits(), lights.pmf_at(p, n, idx, bounce).to_bits());
                taken += 1;
            }
            if let Some(ls) = lights.sample_facing(&scene, (p, n), u, Vec2::splat(0.5), bounce) {
                sum += (ls.li.y * n.dot(ls.wi) / ls.pdf) as f64;
            }
        }
        let share = taken as f32 / m as f32;
        assert!(
            (share - lights.p_local_at(bounce)).abs() < 1e-3,
            "bounce {bounce}: sampled at {share} of the vertices"
        );
        let mean = (sum / m as f64) as f32;
        assert!(
            (mean - exact).abs() < 2e-3 * exact,
            "bounce {bounce}: mean {mean}, exact {exact}"
        );
    }
}

#[test]
fn candidates_chosen_together_get_each_ones_own_choice() {
    // Faint lamps under a sun (most vertices skip them), lamps alone, and
    // five suns, the faint last of which the local lights hold (skipped
    // by most vertices too).
    let sun = |(az, e): (f32, f32)| {
        format!("[[light]]\nkind = \"sun\"\nelevation_deg = 40.0\nazimuth_deg = {az:?}\nirradiance = [{e:?}, {e:?}, {e:?}]\n")
    };
    let five_suns: String = [(60.0, 50.0), (120.0, 50.0), (180.0, 50.0), (240.0, 0.5)]
        .map(sun)
        .concat();
    let mut rng = Rng::new(&[0x2545_f491_4f6c_dd1d]);
    let mut u = move || rng.f32();
    for extra in [
        format!("{GRADIENT}{}", points(1.0)),
        format!("{OVERCAST}{}", points(1e6)),
        format!("{GRADIENT}{five_suns}{}", points(1.0)),
    ] {
        let lights = LightSet::build(&scene_with(&extra));
        assert!(lights.p_local_at(0) > 0.0, "{extra}");
        let mut chosen = 0;
        for k in 0..3000 {
            let p = Vec3::new(6.0 * u() - 3.0, 6.0 * u() - 3.0, 3.0 * u());
            let n = if k % 2 == 0 { Vec3::ZERO } else { Vec3::Z };
            let u0 = u();
            let u1 = if k % 3 == 0 { u0 } else { u() };
            let us = [Some(u0), Some(u1), None];
            for bounce in [0, 2] {
                let together = lights.select_many((p, n), us, bounce);
                let alone = us.map(|u| u.and_then(|u| lights.select_at(p, n, u, bounce)));
                let bits =
                    |r: [Option<(usize, f32)>; 3]| r.map(|c| c.map(|(i, pmf)| (i, pmf.to_bits())));
                assert_eq!(bits(together), bits(alone), "{extra}\np {p}, u {us:?}");
                chosen += together.iter().flatten().count();
            }
        }
        assert!(chosen > 1000, "{chosen} chosen for\n{extra}");
    }
}

#[test]
fn a_cells_choice_is_the_same_from_any_thread_and_after_its_cut_was_evicted() {
    // Lamps over a wide floor: choices at points spread over far more
    // cells than a thread's cache holds, asked in one thread in one order
    // and in a fresh thread in the other, give the same lights and bits.
    let lamps: String = (0..40)
        .map(|k| {
            let (x, y) = ((k % 8) as f32 * 12.0 - 42.0, (k / 8) as f32 * 12.0 - 24.0);
            format!("[[light]]\nkind = \"point\"\nposition = [{x:?}, {y:?}, 5.0]\nintensity = [1e6, 1e6, 1e6]\n")
        })
        .collect();
    let lights = LightSet::build(&scene_with(&format!("{OVERCAST}{lamps}")));
    assert_eq!(lights.budget.candidates, crate::light::LOCAL_CANDIDATES);
    let mut rng = Rng::new(&[0x0c07_5eed]);
    let asks: Vec<(Vec3, Vec3, f32)> = (0..30_000)
        .map(|k| {
            let p = Vec3::new(rng.f32() - 0.5, rng.f32() - 0.5, 0.2 * rng.f32()) * 400.0;
            let n = [Vec3::Z, Vec3::ZERO, Vec3::new(0.6, 0.0, 0.8)][k % 3];
            (p, n, rng.f32())
        })
        .collect();
    let answer = |&(p, n, u): &(Vec3, Vec3, f32)| {
        let pick = lights.select_at(p, n, u, 0);
        let pmf = pick.map(|(i, _)| lights.pmf_at(p, n, i, 0).to_bits());
        (pick.map(|(i, pmf)| (i, pmf.to_bits())), pmf)
    };
    let here: Vec<_> = asks.iter().map(answer).collect();
    let there: Vec<_> = std::thread::scope(|s| {
        s.spawn(|| asks.iter().rev().map(answer).collect::<Vec<_>>())
            .join()
            .unwrap()
    });
    let there: Vec<_> = there.into_iter().rev().collect();
    assert_eq!(here, there);
    let chosen = here.iter().filter(|(pick, _)| pick.is_some()).count();
    assert!(chosen > 20_000, "{chosen} chosen");
    for (pick, pmf) in &here {
        assert_eq!(pick.map(|(_, bits)| bits), *pmf);
    }
}
