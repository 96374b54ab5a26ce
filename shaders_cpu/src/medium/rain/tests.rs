//! Unit tests of the rain field: streak placement, capsule geometry and
//! coverage, drop sizes, traversal order.

use super::*;

/// Drops of 2.5 mm and up at 10 mm/h, 1/60 s, pixels of 1 mrad; `speed`
/// fixes the fall speed.
pub(crate) fn field(density: f64, seed: u64, speed: Option<f64>) -> Rain {
    let lambda = marshall_palmer_lambda(10.0);
    let rain = Rain::new(
        density,
        2.5,
        lambda,
        1.0 / 60.0,
        speed,
        30.0,
        DVec3::ZERO,
        1e-3,
    );
    Rain { seed, ..rain }
}

pub(crate) fn first(rain: &Rain, c: [i64; 3]) -> Streak {
    rain.streaks(c).next().expect("a streak")
}

#[test]
fn marshall_palmer_total_matches_n0_over_lambda() {
    let n = marshall_palmer_count(1.0, 0.0);
    assert!((n - 8000.0 / 4.1).abs() < 1e-9);
}

#[test]
fn atlas_fall_speed_is_about_4_m_per_s_at_1_mm_and_9_at_5_mm() {
    assert!((atlas_fall_speed(1.0) - 4.0).abs() < 0.05);
    assert!((atlas_fall_speed(5.0) - 9.16).abs() < 0.05);
}

#[test]
fn drawn_diameters_follow_the_truncated_exponential() {
    // Mean of D − d0 on [0, s] under e^{−Λx}: 1/Λ − s/(e^{Λs} − 1).
    let rain = field(20.0, 1, None);
    let (d0, lambda) = (rain.min_diameter_mm, rain.lambda_per_mm);
    let span = MAX_DROP_DIAMETER_MM - d0;
    let n = 100_000;
    let ds: Vec<f64> = (0..n)
        .map(|k| rain.diameter_mm((k as f64 + 0.5) / n as f64))
        .collect();
    assert!(ds.iter().all(|&d| (d0..=MAX_DROP_DIAMETER_MM).contains(&d)));
    let mean = ds.iter().map(|d| d - d0).sum::<f64>() / n as f64;
    let expected = 1.0 / lambda - span / ((lambda * span).exp() - 1.0);
    assert!((mean / expected - 1.0).abs() < 1e-3, "{mean} vs {expected}");
}

#[test]
fn streaks_are_a_pure_function_of_seed_and_cell() {
    let (a, b) = (field(50.0, 7, None), field(50.0, 7, None));
    let c = [3, -2, 0];
    let sa: Vec<_> = a.streaks(c).collect();
    assert!(!sa.is_empty());
    assert_eq!(sa, b.streaks(c).collect::<Vec<_>>());
    assert_ne!(sa, field(50.0, 8, None).streaks(c).collect::<Vec<_>>());
}

#[test]
fn capsules_lie_inside_their_cell() {
    let rain = field(50.0, 11, None);
    let (s, m) = (rain.cell_m, rain.max_radius());
    for c in [[2, -3, 0], [0, 0, -1], [-4, 1, 1]] {
        let lo = DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) * s;
        for st in rain.streaks(c) {
            let a = st.axis_top;
            assert!(a.x - m >= lo.x && a.x + m <= lo.x + s, "{a:?}");
            assert!(a.y - m >= lo.y && a.y + m <= lo.y + s, "{a:?}");
            let bottom = a.z - st.length_m - st.drop_radius_m;
            assert!(
                bottom >= lo.z && a.z + st.drop_radius_m <= lo.z + s,
                "{a:?}"
            );
        }
    }
}

#[test]
fn ray_through_a_streak_axis_hits_it() {
    let rain = field(20.0, 3, None);
    let s = first(&rain, [1, 1, 0]);
    let o = DVec3::new(s.axis_top.x - 5.0, s.axis_top.y, s.axis_top.z - 0.04);
    // Other streaks may come first; none after the aimed one.
    let h = rain.first_streak(o, DVec3::X, 0.0, 10.0, 0.0).expect("hit");
    assert!(h.t_axis <= 5.0 + 1e-9, "{h:?}");
    let h = rain
        .first_streak(o, DVec3::X, 4.99, 10.0, 0.0)
        .expect("hit");
    assert!((h.t_axis - 5.0).abs() < 1e-9, "{h:?}");
    assert_eq!(h.axis_top, s.axis_top);
}

#[test]
fn streak_is_hit_along_its_whole_length_and_missed_past_its_ends() {
    let rain = Rain {
        pixel_angle_rad: 0.0,
        ..field(20.0, 5, Some(9.0))
    };
    let s = first(&rain, [0, 2, 0]);
    let (a, len, r) = (s.axis_top, s.length_m, s.drop_radius_m);
    assert!((len - 0.15).abs() < 1e-12);
    // Horizontal rays aimed at the axis from 4 m away, at heights along it.
    for k in 0..=10 {
        let z = a.z + r - (len + 2.0 * r) * (0.01 + 0.98 * k as f64 / 10.0);
        let o = DVec3::new(a.x - 4.0, a.y, z);
        let h = rain.hit_streak(o, DVec3::X, &s, 0.0).expect("hit");
        assert!((h.t - (4.0 - r)).abs() < 1e-9);
        assert!((h.t_far - h.t - 2.0 * r).abs() < 1e-9);
    }
    for z in [a.z + r + 0.01, a.z - len - r - 0.01] {
        let o = DVec3::new(a.x - 4.0, a.y, z);
        assert!(rain.hit_streak(o, DVec3::X, &s, 0.0).is_none(), "z {z}");
    }
    // Aimed beside the axis by more than the radius: a miss.
    let o = DVec3::new(a.x - 4.0, a.y + 1.5 * r, a.z - 0.5 * len);
    assert!(rain.hit_streak(o, DVec3::X, &s, 0.0).is_none());
}

#[test]
fn capsule_widens_to_the_pixel_footprint_with_distance() {
    let rain = field(20.0, 1, Some(9.0));
    let streak = |x: f64| Streak {
        axis_top: DVec3::new(x, 0.0, 0.075),
        drop_radius_m: 0.00125,
        length_m: 0.15,
    };
    let (near, far) = (streak(1.0), streak(20.0));
    assert_eq!(rain.streak_radius(&near), 0.00125);
    assert!((rain.streak_radius(&far) - 0.5e-3 * 20.0).abs() < 1e-12);
    // A level drop at most 2.5 m away covers πr/(2 L_c) of its pixel.
    let w = rain.coverage(&near, rain.streak_radius(&near), 1.0, 0.0);
    assert!((w - PI * 0.00125 / (2.0 * 0.1525)).abs() < 1e-12);
}

#[test]
fn coverage_integrates_to_the_drop_cross_section() {
    // Parallel rays over a fine grid across one streak 12 m away seen
    // 30° below the horizontal: Σ w·dA is the drop's area π r².
    let rain = field(20.0, 4, None);
    let s = Streak {
        axis_top: DVec3::new(12.0, 0.4, 1.0),
        drop_radius_m: 0.001,
        length_m: 0.1,
    };
    let d = DVec3::new(30f64.to_radians().cos(), 0.0, -30f64.to_radians().sin());
    let (e1, e2) = (DVec3::Y, d.cross(DVec3::Y));
    let (n, half) = (400, 0.1);
    let step = 2.0 * half / n as f64;
    let mid = s.axis_top - DVec3::Z * 0.05;
    let mut sum = 0.0;
    for i in 0..n {
        for j in 0..n {
            let a = -half + (i as f64 + 0.5) * step;
            let b = -half + (j as f64 + 0.5) * step;
            let o = mid + e1 * a + e2 * b - d * 5.0;
            if let Some(h) = rain.hit_streak(o, d, &s, 0.0) {
                sum += h.coverage * step * step;
            }
        }
    }
    let area = PI * s.drop_radius_m.powi(2);
    assert!((sum / area - 1.0).abs() < 0.02, "{sum} vs {area}");
}

#[test]
fn streaks_along_lists_the_hits_first_streak_finds_one_by_one() {
    let rain = field(300.0, 9, None);
    let o = DVec3::new(0.3, -0.2, 1.6);
    for (k, d) in [DVec3::new(1.0, 0.1, 0.02), DVec3::new(-0.4, 1.0, -0.1)]
        .into_iter()
        .enumerate()
    {
        let d = d.normalize();
        let mut hits = [StreakHit::default(); 64];
        let n = rain.streaks_along(o, d, (0.0, 40.0), 0.0, &mut hits);
        let mut t0 = 0.0;
        let mut one_by_one = Vec::new();
        while let Some(h) = rain.first_streak(o, d, t0, 40.0, 0.0) {
            one_by_one.push(h);
            t0 = h.t_axis;
        }
        assert!(n > 3, "ray {k}: {n} hits");
        assert_eq!(&hits[..n], &one_by_one[..n.min(one_by_one.len())]);
        assert_eq!(n, one_by_one.len().min(64));
    }
}
