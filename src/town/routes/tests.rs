//! Unit tests of the routes: continuity and total turning of every loop,
//! the roundabout turn's geometry, routes through curved loop corners, and
//! the turn and keep-clear distances at one lane corner.

use super::*;

fn town(roundabout: bool) -> Layout {
    Layout {
        nx: 3,
        ny: 3,
        pitch_m: 90.0,
        road_w_m: 14.0,
        parking_m: 0.0,
        lane_w_m: 3.5,
        lanes: 2,
        sidewalk_m: 4.0,
        sidewalks: true,
        river_row: None,
        roundabout: roundabout.then_some((1, 1)),
        underpass: None,
        loop_radius_m: 0.0,
        median: false,
    }
}

#[test]
fn every_route_is_continuous_and_turns_a_full_circle() {
    let l = town(true);
    let all = routes(&l, &Turns::new(l.lane_w_m));
    // The ring's two lanes are one long-vehicle route.
    assert_eq!(all.len(), 9 * 2 + 1);
    assert_eq!(all.iter().filter(|r| r.roundabout).count(), 4 * 2);
    for route in &all {
        assert_closed_loop(route);
    }
}

#[test]
fn loop_corner_routes_ride_arcs_concentric_with_the_road() {
    let l = Layout {
        loop_radius_m: 40.0,
        sidewalks: false,
        ..town(false)
    };
    let all = routes(&l, &Turns::new(l.lane_w_m));
    let corners = l.loop_corners();
    let mut arcs = 0;
    for route in &all {
        assert_closed_loop(route);
        for seg in &route.segments {
            let Segment::Arc {
                centre, radius_m, ..
            } = *seg
            else {
                continue;
            };
            let Some(c) = corners
                .iter()
                .find(|c| (c.centre[0] - centre[0]).hypot(c.centre[1] - centre[1]) < 1e-9)
            else {
                // Plain corners keep the small turn radius.
                assert!(radius_m < 10.0, "{radius_m}");
                continue;
            };
            // Ring: lane centre outside the road centreline; block
            // loop (corner blocks only): inside it.
            let e = (radius_m - l.loop_radius_m).abs();
            let w = l.lane_w_m;
            assert!(e > route.lane as f64 * w && e < (route.lane + 1) as f64 * w);
            match route.kind {
                RouteKind::Ring => assert!(radius_m > l.loop_radius_m),
                RouteKind::Block { i, j } => {
                    assert!(radius_m < l.loop_radius_m);
                    let (ci, cj) = c.ij;
                    assert!((ci == i || ci == i + 1) && (cj == j || cj == j + 1));
                }
                RouteKind::Overpass => panic!("routes() builds no overpass route"),
            }
            arcs += 1;
        }
        // A keep-clear zone per corner; a curve's covers the whole arc
        // and comes after the junctions' (the first is the lead's).
        if let RouteKind::Block { i, j } = route.kind {
            assert_eq!(route.keep_clear_m.len(), 4);
            let curved = [(i, j), (i + 1, j), (i, j + 1), (i + 1, j + 1)]
                .iter()
                .any(|&(a, b)| l.loop_corner_at(a, b));
            let last = route.keep_clear_m[3];
            let on_arc = route.curvature((last[0] + last[1]) / 2.0) > 0.0;
            assert_eq!(on_arc && last[1] - last[0] > 40.0, curved);
        }
    }
    // The ring's 4 curves, and 2 lanes × 4 corner blocks.
    assert_eq!(arcs, 4 + 2 * 4);
}

/// Position and heading are continuous along the loop (radii ≥ 3 m),
/// and it turns by one full circle (ring left, block loops right).
fn assert_closed_loop(route: &Route) {
    {
        let len = route.length_m();
        let n = 20000;
        let mut turned = 0.0;
        let (mut prev_p, mut prev_h) = route.pose(0.0);
        for k in 1..=n {
            let (p, h) = route.pose(len * k as f64 / n as f64);
            let step = (p[0] - prev_p[0]).hypot(p[1] - prev_p[1]);
            assert!(step <= len / n as f64 + 1e-9, "jump of {step} m at {k}");
            let mut dh = h - prev_h;
            dh -= (dh / (2.0 * PI)).round() * 2.0 * PI;
            // Radii are ≥ 3 m: a step turns by at most step / 3.
            assert!(
                dh.abs() <= len / n as f64 / 3.0 + 1e-9,
                "heading jump {dh} at {k}"
            );
            turned += dh;
            (prev_p, prev_h) = (p, h);
        }
        let want = match route.kind {
            RouteKind::Ring | RouteKind::Overpass => 2.0 * PI,
            RouteKind::Block { .. } => -2.0 * PI,
        };
        assert!((turned - want).abs() < 1e-9, "turned {turned}");
    }
}

#[test]
fn roundabout_turn_circles_the_ring_counter_clockwise_in_its_quarter() {
    let l = town(true);
    let c = l.roundabout_center().unwrap();
    for k in 0..l.lanes {
        let big_r = ring_lane_radius_m(&l, k);
        for route in routes(&l, &Turns::new(l.lane_w_m))
            .iter()
            .filter(|r| r.roundabout && r.lane == k)
        {
            let on_ring: Vec<f64> = (0..4000)
                .map(|n| route.pose(route.length_m() * n as f64 / 4000.0).0)
                .filter(|p| ((p[0] - c[0]).hypot(p[1] - c[1]) - big_r).abs() < 1e-9)
                .map(|p| (p[1] - c[1]).atan2(p[0] - c[0]))
                .collect();
            assert!(on_ring.len() > 20, "{} points on the ring", on_ring.len());
            let spread = on_ring.iter().fold(f64::NEG_INFINITY, |a, &b| a.max(b))
                - on_ring.iter().fold(f64::INFINITY, |a, &b| a.min(b));
            assert!(spread > 0.3 && spread < FRAC_PI_2, "spread {spread}");
        }
    }
    // The canonical turn is tangent where its pieces meet.
    let (arcs, cut) = ring_turn(&l, 0, ring_fillet_m(&l));
    let e = 0.5 * l.lane_w_m;
    assert!((arcs[0].at(0.0).0[0] - (-e - cut)).abs() < 1e-9);
    for w in arcs.windows(2) {
        let (p, h) = w[0].at(w[0].length_m());
        let (q, g) = w[1].at(0.0);
        assert!((p[0] - q[0]).hypot(p[1] - q[1]) < 1e-9);
        assert!((h - g).sin().abs() < 1e-9 && (h - g).cos() > 0.0);
    }
    let (p, h) = arcs[2].at(arcs[2].length_m());
    assert!((p[0] + e).abs() < 1e-9 && (p[1] + e + cut).abs() < 1e-9);
    assert!((h + FRAC_PI_2).sin().abs() < 1e-9);
}

#[test]
fn a_corner_turns_on_a_quarter_arc_or_round_the_ring_and_keeps_its_junction_clear() {
    let l = town(true);
    let r = Turns::new(l.lane_w_m).radius_m;
    let (hw, e) = (l.road_w_m / 2.0, 0.5 * l.lane_w_m);
    let at = CornerTurns::new(&l, 0, r, l.roundabout_center());
    // A plain right turn at the lane corner by junction (2, 1): heading +y,
    // then +x (clockwise).
    let c = [180.0 - e, 90.0 - e];
    let mut segs = Vec::new();
    let zone = at.turn(c, ([0.0, 1.0], [1.0, 0.0]), FRAC_PI_2, &mut segs);
    assert_eq!(zone, (hw - e + STOP_LINE_AT_M, hw - e + CROSSWALK_CLEAR_M));
    assert_eq!(at.cut(c), r);
    let [arc] = segs[..] else { panic!("{segs:?}") };
    assert!((arc.length_m() - r * FRAC_PI_2).abs() < 1e-9);
    // It starts r before the corner and ends r after it, heading +x.
    let (p, _) = arc.at(0.0);
    assert!((p[0] - c[0]).abs() < 1e-9 && (p[1] - (c[1] - r)).abs() < 1e-9);
    let (q, h) = arc.at(arc.length_m());
    assert!((q[0] - (c[0] + r)).abs() < 1e-9 && (q[1] - c[1]).abs() < 1e-9);
    assert!(h.sin().abs() < 1e-9 && h.cos() > 0.0);
    // At the roundabout (centre (90, 90)): the three arcs of the ring turn,
    // the zone from the arm's keep-clear start on both sides.
    let o = l.roundabout_center().unwrap();
    let c = [o[0] - e, o[1] - e];
    let mut segs = Vec::new();
    let zone = at.turn(c, ([1.0, 0.0], [0.0, -1.0]), 0.0, &mut segs);
    let arm = arm_start_m(&l) + RING_CLEAR_EXTRA_M - e;
    assert_eq!(zone, (arm, arm));
    assert_eq!(segs.len(), 3);
    assert_eq!(at.cut(c), ring_turn(&l, 0, ring_fillet_m(&l)).1);
}
