//! The roundabout of a town (town03): a ring road around a raised central
//! island with grass, a mound and trees, lane markings on the ring (edge
//! lines, a dashed divider), curbs and a sidewalk ring between the four
//! approach arms. The arms end where their kerbs meet the ring and carry a
//! dashed yield line there (see `roads`).
//!
//! The block loops with a corner here drive a quarter of the ring each
//! (`routes::ring_turn`: lane k of the road on ring lane k), so routes
//! still share no surface. Ring pieces are boxes or quads turned about z,
//! so road surfaces stay exactly at z = 0 (the GT tests rely on it).

use std::f64::consts::{FRAC_PI_2, PI};

use crate::scene::desc::ObjectDesc;

use super::layout::Layout;
use super::parts::{class, cuboid, cylinder, turned_quad, Label};
use super::vegetation::{self, Plant, Species};

/// Distance from the roundabout centre at which each approach arm's
/// straight road ends (its kerbs meet the ring's outer kerb), metres.
pub fn arm_start_m(l: &Layout) -> f64 {
    let (_, r_out) = l.roundabout_radii();
    let hw = l.road_w_m / 2.0;
    (r_out * r_out - hw * hw).sqrt()
}

/// Half-angle (radians) of each arm's opening in the ring's outer kerb:
/// the arm's kerb lines y = ±hw meet that circle there.
fn opening_half_angle(l: &Layout) -> f64 {
    let (_, r_out) = l.roundabout_radii();
    (l.road_w_m / 2.0 / r_out).asin()
}

/// Angular intervals [θ0, θ1] (radians) of a circle: the whole circle, or
/// the four arcs between the arm openings of half-angle `open`.
fn arcs(open: Option<f64>) -> Vec<(f64, f64)> {
    match open {
        None => vec![(0.0, 2.0 * PI)],
        Some(a) => (0..4)
            .map(|q| {
                let t = q as f64 * FRAC_PI_2;
                (t + a, t + FRAC_PI_2 - a)
            })
            .collect(),
    }
}

/// Boxes covering the annulus r0..r1 between heights z over the given
/// arcs, in pieces of about `piece_m` at r1; with `dash`, every other piece
/// at half length (a dashed line).
#[allow(clippy::too_many_arguments)]
fn ring(
    c: [f64; 2],
    (r0, r1): (f64, f64),
    z: (f64, f64),
    open: Option<f64>,
    piece_m: f64,
    dash: bool,
    mat: &str,
    l: Label,
    out: &mut Vec<ObjectDesc>,
) {
    for (t0, t1) in arcs(open) {
        let n = ((t1 - t0) * r1 / piece_m).ceil().max(1.0) as usize;
        let dt = (t1 - t0) / n as f64;
        // The chord at r1 covers the outer arc; neighbours overlap inside.
        let mut len = 2.0 * r1 * (dt / 2.0).tan();
        if dash {
            len /= 2.0;
        }
        for k in (0..n).filter(|k| !dash || k % 2 == 0) {
            let t = t0 + (k as f64 + 0.5) * dt;
            let rc = (r0 + r1) / 2.0;
            let at = [c[0] + rc * t.cos(), c[1] + rc * t.sin(), (z.0 + z.1) / 2.0];
            let size = [r1 - r0, len, z.1 - z.0];
            out.push(cuboid(size, at, t.to_degrees(), mat, l));
        }
    }
}

/// Every object of the roundabout (none if the town has none): ring
/// asphalt, markings, the outer curb and sidewalk, the central island.
pub fn roundabout_objects(l: &Layout) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    let Some(c) = l.roundabout_center() else {
        return out;
    };
    let (r_in, r_out) = l.roundabout_radii();
    let open = Some(opening_half_angle(l));
    ring_asphalt(c, (r_in, r_out), &mut out);
    ring_markings(l, c, open, &mut out);
    ring_roadside(l, c, open, &mut out);
    island(c, r_in, &mut out);
    out
}

/// Ring asphalt: radial quads at z = 0 from under the island to under the
/// outer curb.
fn ring_asphalt(c: [f64; 2], (r_in, r_out): (f64, f64), out: &mut Vec<ObjectDesc>) {
    let n = 96;
    let (q0, q1) = (r_in - 0.5, r_out + 0.2);
    let width = 2.0 * q1 * (PI / n as f64).tan();
    for k in 0..n {
        let t = (k as f64 + 0.5) * 2.0 * PI / n as f64;
        let rc = (q0 + q1) / 2.0;
        let at = [c[0] + rc * t.cos(), c[1] + rc * t.sin(), 0.0];
        out.push(turned_quad(
            [q1 - q0, width],
            at,
            t.to_degrees(),
            "asphalt",
            class("road"),
        ));
    }
}

/// Markings: solid edge lines (the outer one open at the arms) and a
/// dashed divider between the ring lanes.
fn ring_markings(l: &Layout, c: [f64; 2], open: Option<f64>, out: &mut Vec<ObjectDesc>) {
    let (r_in, r_out) = l.roundabout_radii();
    let (mark, paint, pz) = (class("road_line"), "paint_white_road", (0.0, 0.008));
    let edge_in = (r_in + 0.25, r_in + 0.4);
    ring(c, edge_in, pz, None, 2.0, false, paint, mark, out);
    let edge_out = (r_out - 0.4, r_out - 0.25);
    ring(c, edge_out, pz, open, 2.0, false, paint, mark, out);
    let lane_w = (r_out - r_in) / l.lanes as f64;
    for k in 1..l.lanes {
        let r = r_in + k as f64 * lane_w;
        ring(
            c,
            (r - 0.06, r + 0.06),
            pz,
            None,
            3.0,
            true,
            paint,
            mark,
            out,
        );
    }
}

/// Outer curb and sidewalk ring between the arms (a gravel shoulder on
/// country roads).
fn ring_roadside(l: &Layout, c: [f64; 2], open: Option<f64>, out: &mut Vec<ObjectDesc>) {
    let (_, r_out) = l.roundabout_radii();
    if l.sidewalks {
        let side = class("sidewalk");
        let (curb, walk) = ((r_out, r_out + 0.25), (r_out + 0.25, r_out + l.sidewalk_m));
        ring(c, curb, (0.0, 0.15), open, 2.0, false, "curb", side, out);
        ring(
            c,
            walk,
            (0.0, 0.14),
            open,
            2.0,
            false,
            "sidewalk",
            side,
            out,
        );
    } else {
        let t = class("terrain");
        let shoulder = (r_out, r_out + l.sidewalk_m);
        ring(
            c,
            shoulder,
            (-0.01, 0.0),
            open,
            2.0,
            false,
            "gravel",
            t,
            out,
        );
    }
}

/// Central island of radius `r_in`: a curb drum, a lawn top, a low grass
/// mound, a tree in the middle and four smaller plants round it.
fn island(c: [f64; 2], r_in: f64, out: &mut Vec<ObjectDesc>) {
    let at = [c[0], c[1], 0.0];
    out.push(cylinder(r_in, 0.15, 64, at, "curb", class("sidewalk")));
    let top = [c[0], c[1], 0.15];
    out.push(cylinder(r_in - 0.3, 0.1, 64, top, "lawn", class("terrain")));
    let mound = super::parts::blob(
        [r_in - 2.5, r_in - 2.5, 0.9],
        [c[0], c[1], 0.25],
        "lawn",
        class("terrain"),
    );
    out.push(mound);
    let centre = Plant::Tree(Species::Plane);
    out.push(vegetation::place(centre, [c[0], c[1], 1.1], 0.0, 0));
    for q in 0..4 {
        let t = (q as f64 + 0.5) * FRAC_PI_2;
        let r = 0.6 * r_in;
        let p = [c[0] + r * t.cos(), c[1] + r * t.sin(), 0.5];
        let plant = if q % 2 == 0 {
            Plant::Tree(Species::Birch)
        } else {
            Plant::Bush
        };
        out.push(vegetation::place(plant, p, 45.0 * q as f64, 0));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arcs_leave_four_equal_openings() {
        let a = 0.3;
        let arcs4 = arcs(Some(a));
        assert_eq!(arcs4.len(), 4);
        // Arc q runs counter-clockwise from a past the axis direction q·90°
        // to a before the next one.
        for (q, &(t0, t1)) in arcs4.iter().enumerate() {
            let axis = q as f64 * PI / 2.0;
            assert!((t0 - (axis + a)).abs() < 1e-12, "arc {q} starts at {t0}");
            assert!(
                (t1 - (axis + PI / 2.0 - a)).abs() < 1e-12,
                "arc {q} ends at {t1}"
            );
        }
        // Each opening, from the previous arc's end to this arc's start, is
        // 2a wide and centred on its axis direction (0°, 90°, 180°, 270°).
        for q in 0..4 {
            let prev_end = arcs4[(q + 3) % 4].1 - if q == 0 { 2.0 * PI } else { 0.0 };
            let start = arcs4[q].0;
            assert!((start - prev_end - 2.0 * a).abs() < 1e-12, "opening {q}");
            let centre = (start + prev_end) / 2.0;
            assert!(
                (centre - q as f64 * PI / 2.0).abs() < 1e-12,
                "opening {q} at {centre}"
            );
        }
        let total: f64 = arcs4.iter().map(|(t0, t1)| t1 - t0).sum();
        assert!((total - (2.0 * PI - 8.0 * a)).abs() < 1e-12);
        assert_eq!(arcs(None), vec![(0.0, 2.0 * PI)]);
    }

    #[test]
    fn openings_meet_the_arm_kerbs_on_the_outer_kerb() {
        // With the half-angle roundabout_objects uses, the east opening's
        // edges on the outer kerb lie on the arm's kerb lines y = ±hw, at
        // x = arm_start_m.
        let l = Layout {
            nx: 2,
            ny: 2,
            pitch_m: 100.0,
            road_w_m: 14.0,
            lane_w_m: 3.5,
            lanes: 2,
            sidewalk_m: 2.0,
            sidewalks: true,
            river_row: None,
            roundabout: Some((1, 1)),
            loop_radius_m: 0.0,
            median: false,
        };
        // r_out = 10 + 2 · (3.5 + 1) = 19 m, hw = 7 m.
        let (r_out, hw): (f64, f64) = (19.0, 7.0);
        assert_eq!(l.roundabout_radii().1, r_out);
        let arcs4 = arcs(Some(opening_half_angle(&l)));
        let (start, end) = (arcs4[0].0, arcs4[3].1);
        assert!((r_out * start.sin() - hw).abs() < 1e-12);
        assert!((r_out * end.sin() + hw).abs() < 1e-12);
        let x = (19.0f64 * 19.0 - 7.0 * 7.0).sqrt();
        assert!((arm_start_m(&l) - x).abs() < 1e-12);
        assert!((r_out * start.cos() - x).abs() < 1e-12);
    }

    #[test]
    fn the_ring_is_edged_by_curb_and_sidewalk_between_the_arms_and_gravel_in_the_country() {
        let mut l = Layout {
            nx: 2,
            ny: 2,
            pitch_m: 100.0,
            road_w_m: 14.0,
            lane_w_m: 3.5,
            lanes: 2,
            sidewalk_m: 3.0,
            sidewalks: true,
            river_row: None,
            roundabout: Some((1, 1)),
            loop_radius_m: 0.0,
            median: false,
        };
        let (c, r_out) = ([100.0, 100.0], 19.0);
        let open = Some(opening_half_angle(&l));
        for (sidewalks, want) in [(true, vec!["curb", "sidewalk"]), (false, vec!["gravel"])] {
            l.sidewalks = sidewalks;
            let mut out = Vec::new();
            ring_roadside(&l, c, open, &mut out);
            let mut kinds: Vec<&str> = out.iter().map(|o| o.material.as_deref().unwrap()).collect();
            kinds.dedup();
            assert_eq!(kinds, want);
            for o in &out {
                let t = o.transform.translate.unwrap();
                let (d, a) = (
                    (t[0] - c[0]).hypot(t[1] - c[1]),
                    (t[1] - c[1]).atan2(t[0] - c[0]),
                );
                assert!(d > r_out && d < r_out + 3.0, "{d}");
                // Nothing in an arm's opening (about each axis direction).
                let off_axis = (a - (a / FRAC_PI_2).round() * FRAC_PI_2).abs();
                assert!(off_axis > opening_half_angle(&l), "{a}");
                let top = t[2] + if sidewalks { 0.0 } else { 0.005 };
                assert!((0.0..=0.075).contains(&top), "{t:?}");
            }
        }
        // The island: curb drum, lawn, mound, then five plants.
        let mut out = Vec::new();
        island(c, 10.0, &mut out);
        let classes: Vec<&str> = out.iter().map(|o| o.semantic.as_deref().unwrap()).collect();
        let veg = "vegetation";
        assert_eq!(
            classes,
            ["sidewalk", "terrain", "terrain", veg, veg, veg, veg, veg]
        );
    }
}
