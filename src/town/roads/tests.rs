//! Tests of the pieces along one road segment: lane lines, the stop or
//! yield line and crosswalk at a junction end, curbs and sidewalks.

use super::*;
use crate::scene::desc::ShapeDesc;

/// A 2 × 2 grid of 100 m blocks, 14 m roads of `lanes` lanes a direction.
fn layout(lanes: u32, sidewalks: bool) -> Layout {
    Layout {
        nx: 2,
        ny: 2,
        pitch_m: 100.0,
        road_w_m: 14.0,
        parking_m: 0.0,
        lane_w_m: 3.5,
        lanes,
        sidewalk_m: 3.0,
        sidewalks,
        river_row: None,
        roundabout: None,
        underpass: None,
        loop_radius_m: 0.0,
        median: false,
    }
}

/// An x-road at y = 0 between the junctions at x = 0 and x = 100.
fn between_junctions() -> Segment {
    Segment::new(Axis::X, 0.0, (7.0, 93.0), [true, true])
}

fn materials(o: &[ObjectDesc]) -> Vec<&str> {
    o.iter().map(|o| o.material.as_deref().unwrap()).collect()
}

/// Repeat levels of an object: (count, offset).
type Levels = Vec<(u32, [f64; 3])>;

/// Centre, size and repeat levels of a box.
fn boxed(o: &ObjectDesc) -> ([f64; 3], [f64; 3], Levels) {
    let ShapeDesc::Box { size } = o.shape else {
        panic!("not a box: {o:?}");
    };
    let rep = o.repeat.iter().map(|r| (r.count, r.offset)).collect();
    (o.transform.translate.unwrap(), size, rep)
}

fn close(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b).all(|(a, b)| (a - b).abs() < 1e-12)
}

#[test]
fn lane_lines_follow_the_lane_count_and_stop_short_of_short_segments() {
    let s = between_junctions();
    let mut one = Vec::new();
    lane_lines(&layout(1, true), &[], &s, &mut one);
    let white = "paint_white_road";
    assert_eq!(materials(&one), [white; 3], "dashed centre line, two edges");
    let mut two = Vec::new();
    lane_lines(&layout(2, true), &[], &s, &mut two);
    let yellow = "paint_yellow_road";
    assert_eq!(
        materials(&two),
        [yellow, yellow, white, white, white, white]
    );
    // The double centre line runs from 4.6 m past one junction's edge to
    // 4.6 m before the next (stop line at 4 m, plus 0.6 m).
    let (at, size, rep) = boxed(&two[0]);
    let (n, step) = rep[0];
    let (start, end) = (
        at[0] - size[0] / 2.0,
        at[0] - size[0] / 2.0 + n as f64 * step[0],
    );
    assert!(
        (start - 11.6).abs() < 1e-9 && (end - 88.4).abs() < 1e-9,
        "{start}..{end}"
    );
    // 9 m between the junction edges leaves under 1 m of line: none.
    let short = Segment::new(Axis::X, 0.0, (7.0, 16.0), [true, true]);
    let mut none = Vec::new();
    lane_lines(&layout(2, true), &[], &short, &mut none);
    assert!(none.is_empty(), "{none:?}");
}

#[test]
fn a_junction_end_has_a_stop_line_over_the_entering_lanes_then_a_crosswalk() {
    let s = between_junctions();
    let mut o = Vec::new();
    junction_end(&layout(2, true), &s, 0, &mut o);
    assert_eq!(materials(&o), ["paint_white_road"; 2]);
    // Stop line 4 m from the edge at x = 7, across the lanes entering the
    // junction (y from 0.2 to 6.8: traffic towards −x drives at y > 0).
    let (at, size, _) = boxed(&o[0]);
    assert!(close(at, [11.0, 3.5, 0.004]) && close(size, [0.4, 6.6, 0.008]));
    // Crosswalk: 13 stripes 0.5 m wide every 1 m from y = −6.5, 0.5 to
    // 3.5 m from the edge.
    let (at, size, rep) = boxed(&o[1]);
    assert!(close(at, [9.0, -6.25, 0.004]) && close(size, [3.0, 0.5, 0.008]));
    assert_eq!(rep, vec![(13, [0.0, 1.0, 0.0])]);
    // The other end: lanes at y < 0; no crosswalk on country roads.
    let mut o = Vec::new();
    junction_end(&layout(2, false), &s, 1, &mut o);
    assert_eq!(o.len(), 1);
    let (at, _, _) = boxed(&o[0]);
    assert!(close(at, [89.0, -3.5, 0.004]), "{at:?}");
}

#[test]
fn a_yield_end_has_a_dashed_line_at_the_ring_and_the_crosswalk_set_back() {
    let mut s = between_junctions();
    s.yield_end[0] = true;
    let mut o = Vec::new();
    junction_end(&layout(2, true), &s, 0, &mut o);
    // 0.6 m dashes every 1.2 m over the entering lanes, 0.5 m from the ring.
    let (at, size, rep) = boxed(&o[0]);
    assert!(close(at, [7.5, 0.5, 0.004]) && close(size, [0.4, 0.6, 0.008]));
    assert_eq!(rep, vec![(6, [0.0, 1.2, 0.0])]);
    // Crosswalk 6 m further back: 6.5 to 9.5 m from the ring's edge.
    let (at, _, _) = boxed(&o[1]);
    assert!((at[0] - 15.0).abs() < 1e-12, "{at:?}");
}

#[test]
fn roadsides_are_curb_and_sidewalk_in_town_and_gravel_in_the_country() {
    let s = between_junctions();
    let mut town = Vec::new();
    roadsides(&layout(2, true), &[], &s, &mut town);
    assert_eq!(materials(&town), ["curb", "sidewalk", "curb", "sidewalk"]);
    for (o, (y, w, h)) in town.iter().zip([
        (-7.125, 0.25, 0.15),
        (-8.625, 2.75, 0.14),
        (7.125, 0.25, 0.15),
        (8.625, 2.75, 0.14),
    ]) {
        let (at, size, _) = boxed(o);
        assert!(close(at, [50.0, y, h / 2.0]), "{at:?}");
        assert!(close(size, [86.0, w, h]), "{size:?}");
    }
    let mut country = Vec::new();
    roadsides(&layout(1, false), &[], &s, &mut country);
    assert_eq!(materials(&country), ["gravel", "gravel"]);
}
