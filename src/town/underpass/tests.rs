use super::*;

/// A 4 × 4 grid of 90 m blocks with four-lane avenues and 4 m sidewalks.
fn layout() -> Layout {
    Layout {
        nx: 4,
        ny: 4,
        pitch_m: 90.0,
        road_w_m: 14.0,
        parking_m: 0.0,
        lane_w_m: 3.5,
        lanes: 2,
        sidewalk_m: 4.0,
        sidewalks: true,
        river_row: None,
        roundabout: None,
        underpass: Some(site(4, 4)),
        loop_radius_m: 0.0,
        median: false,
    }
}

#[test]
fn profile_matches_its_closed_form_and_is_c1() {
    let u = Underpass::of(&layout()).unwrap();
    assert_eq!(u.ij, (1, 2));
    assert_eq!((u.x_m, u.y_m), (90.0, 180.0));
    // Fall: from 90 + 7 + 5 = 102 to the deck's end 180 − 11 less 1 m.
    assert_eq!(u.ends, (102.0, 258.0));
    assert_eq!(u.fall_m, 66.0);
    let g = 5.5 / 56.0;
    assert!((u.grade - g).abs() < 1e-15);
    // Independent closed form, south side: u metres into the fall.
    let z = |y: f64| {
        let s = (y - 102.0).clamp(0.0, 66.0);
        -if s < 10.0 {
            g * s * s / 20.0
        } else if s < 56.0 {
            g * (s - 5.0)
        } else {
            5.5 - g * (66.0 - s).powi(2) / 20.0
        }
    };
    let mut steepest: f64 = 0.0;
    let mut y = 95.0;
    while y <= 265.0 {
        let (zy, s) = u.profile(y);
        let want = if y <= 180.0 { z(y) } else { z(360.0 - y) };
        assert!((zy - want).abs() < 1e-12, "z at {y}: {zy} vs {want}");
        let e = 1e-5;
        let fd = (u.profile(y + e).0 - u.profile(y - e).0) / (2.0 * e);
        assert!((fd - s).abs() < 1e-6, "slope at {y}: {s} vs {fd}");
        steepest = steepest.max(s.abs());
        y += 0.25;
    }
    assert!(
        steepest <= MAX_GRADE && (steepest - g).abs() < 1e-12,
        "{steepest}"
    );
    // Level at the ends, DEPTH_M under the whole deck.
    assert_eq!(u.profile(101.0), (0.0, 0.0));
    assert_eq!(u.profile(259.0), (0.0, 0.0));
    for y in [u.deck.0 - 1.0, 175.0, 180.0, 185.0, u.deck.1 + 1.0] {
        assert!((u.profile(y).0 + DEPTH_M).abs() < 1e-12, "{y}");
    }
}

#[test]
fn only_bodies_along_the_sunken_road_go_down() {
    let u = Underpass::of(&layout()).unwrap();
    let north = std::f64::consts::FRAC_PI_2;
    // Northbound south of the deck, on the constant grade: nose down.
    let (z, pitch) = u.pose([88.25, 130.0], north);
    assert!((z - u.profile(130.0).0).abs() < 1e-15 && z < -2.0);
    assert!((pitch - (-u.grade).atan().to_degrees()).abs() < 1e-12);
    let (_, back) = u.pose([91.75, 130.0], -north);
    assert!((back + pitch).abs() < 1e-12, "{back} vs {pitch}");
    // On the deck, an x-road body crosses at grade.
    assert_eq!(u.pose([90.0, 178.25], 0.0), (0.0, 0.0));
    // Beside the cut, and on another y-road: at grade.
    assert_eq!(u.pose([99.0, 130.0], north), (0.0, 0.0));
    assert_eq!(u.pose([180.0, 130.0], north), (0.0, 0.0));
}

#[test]
fn short_blocks_or_sloped_towns_refuse_it() {
    let text = |extra: &str| {
        format!(
            "name = \"t\"\nextent_m = [360.0, 360.0]\nblock_size_m = 90.0\n\
             lanes_per_direction = 2\nlane_width_m = 3.5\nsidewalk_width_m = 4.0\n\
             building_density = 0.8\nfloors = [2, 4]\nvegetation_density = 0.3\n\
             terrain = \"grass\"\ntraffic_density = 0.5\nspeed_kmh = 40.0\n\
             sun_elevation_deg = 45.0\nsun_azimuth_deg = 160.0\n\
             underpass = true\n{extra}"
        )
    };
    let parse = |t: String| crate::town::parse_town_str(&t, "t.toml".as_ref());
    parse(text("")).unwrap();
    let short = parse(text("block_size_m = 80.0\n").replace("block_size_m = 90.0\n", ""));
    assert!(short.unwrap_err().to_string().contains("10 %"));
    let graded = parse(text("road_grade_m = 4.0\n"));
    assert!(graded.unwrap_err().to_string().contains("level town"));
}

/// (centre, size, heading) of a box object.
fn box_of(o: &crate::scene::desc::ObjectDesc) -> ([f64; 3], [f64; 3], f64) {
    let crate::scene::desc::ShapeDesc::Box { size } = o.shape else {
        panic!("not a box: {o:?}");
    };
    let t = o.transform.translate.unwrap();
    let heading = o.transform.rotate_deg.map_or(0.0, |r| r[2]);
    (t, size, heading)
}

#[test]
fn joints_run_down_both_walls_and_lamps_clear_the_traffic() {
    let l = layout();
    let u = Underpass::of(&l).unwrap();
    let things = u.fittings(l.lane_w_m);
    let of = |m: &'static str| {
        things
            .iter()
            .filter(move |o| o.material.as_deref() == Some(m))
    };
    // Joints: from the road at their station up to grade, on the walls'
    // faces, 10 m apart from each deck end outward, as far as the wall is
    // half a metre high.
    let mut ys: Vec<f64> = Vec::new();
    for o in of("rubber") {
        let (c, size, _) = box_of(o);
        let bottom = c[2] - size[2] / 2.0;
        assert!((bottom - u.profile(c[1]).0).abs() < 1e-12 && (c[2] + size[2] / 2.0).abs() < 1e-12);
        assert!(((c[0] - u.x_m).abs() - u.half_w_m).abs() < 1e-12, "{c:?}");
        ys.push(c[1]);
    }
    ys.sort_by(f64::total_cmp);
    ys.dedup();
    assert_eq!(of("rubber").count(), 2 * ys.len());
    let south: Vec<f64> = ys.iter().copied().filter(|&y| y <= u.deck.0).collect();
    let north: Vec<f64> = ys.iter().copied().filter(|&y| y >= u.deck.1).collect();
    for side in [south, north] {
        for w in side.windows(2) {
            assert!((w[1] - w[0] - 10.0).abs() < 1e-9, "{side:?}");
        }
        let outer = if side[0] < u.y_m {
            side[0] - 10.0
        } else {
            side[side.len() - 1] + 10.0
        };
        assert!(-u.profile(outer).0 < 0.5, "{outer}");
    }
    assert!(ys.contains(&u.deck.0) && ys.contains(&u.deck.1));
    // Lit panels: inside the cut, over the road by at least 3.3 m (a
    // bus is 3.2 m), under the deck's underside there; on both walls.
    let panels: Vec<_> = of("lamp_emit").map(box_of).collect();
    let (mut west, mut east, mut under) = (0, 0, 0);
    for (c, size, heading) in &panels {
        assert!((heading - 90.0).abs() < 1e-12);
        let half_x = size[1] / 2.0;
        assert!((c[0] - u.x_m).abs() + half_x <= u.half_w_m, "{c:?}");
        let clear = c[2] - size[2] / 2.0 - u.profile(c[1]).0;
        assert!(clear >= 3.3, "{c:?}: {clear} m over the road");
        let deck = c[1] > u.deck.0 && c[1] < u.deck.1;
        if deck {
            assert!(c[2] + size[2] / 2.0 < -DECK_M);
            under += 1;
        } else if c[0] < u.x_m {
            west += 1;
        } else {
            east += 1;
        }
    }
    assert!(
        west >= 2 && west == east && under == 4,
        "{west} {east} {under}"
    );
}
