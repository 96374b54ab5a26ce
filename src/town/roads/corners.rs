//! The curved corners of a highway loop (`loop_corner_radius_m`): where the
//! outer roads meet, a quarter circle of radius R about a centre R in from
//! both outer centrelines replaces the corner junction. Asphalt, markings
//! (centre line, lane dividers and edge lines as on the straights) and
//! gravel shoulders (asphalt to the shoulders' edges on a divided
//! highway) follow the arc; the straights end at its tangent points
//! (see `roads`), so the corner square outside the arc is left to the ground.
//!
//! Pieces are quads and boxes turned about z (road surfaces stay exactly at
//! z = 0), one per angular step: each is as wide as the step's chord at the
//! band's outer radius, so neighbours overlap on the inside and the band is
//! covered. Shoulders lie 5 mm low: the asphalt's few-millimetre overhang
//! past its outer radius never shares a plane with them.

use crate::scene::desc::ObjectDesc;

use super::super::layout::{Layout, LoopCorner};
use super::super::parts::{class, cuboid, turned_quad, Label};

/// Length of a piece of asphalt or shoulder along the arc, metres.
const SURFACE_PIECE_M: f64 = 4.0;
/// Length of a piece of a solid line along the arc, metres (a 12 cm line
/// then bends by under 1 cm per piece on a 120 m arc).
const LINE_PIECE_M: f64 = 3.0;
/// Height of the shoulders' top, metres (just below the asphalt).
const SHOULDER_Z: f64 = -0.005;
/// Paint: 8 mm boxes lying on the road, as on the straights.
const PAINT_Z: (f64, f64) = (0.0, 0.008);

/// How a band of the arc is cut into pieces.
#[derive(Clone, Copy)]
enum Cut {
    /// Flat quads at height z.
    Quads(f64),
    /// Boxes between two heights, end to end (a solid line).
    Solid((f64, f64)),
    /// 3 m boxes every 6 m along the band's middle (a dashed line).
    Dashed((f64, f64)),
}

/// The pieces covering radii [r0, r1] of corner `c`'s quarter circle.
fn band(c: &LoopCorner, (r0, r1): (f64, f64), cut: Cut, mat: &str, l: Label) -> Vec<ObjectDesc> {
    let (t0, t1) = c.theta;
    let rc = (r0 + r1) / 2.0;
    let piece_m = match cut {
        Cut::Quads(_) => SURFACE_PIECE_M,
        Cut::Solid(_) => LINE_PIECE_M,
        Cut::Dashed(_) => 6.0,
    };
    let reach = match cut {
        Cut::Dashed(_) => rc,
        _ => r1,
    };
    let n = ((t1 - t0) * reach / piece_m).ceil().max(1.0) as usize;
    let dt = (t1 - t0) / n as f64;
    // The chord of one step at the outer radius covers the outer arc.
    let chord = 2.0 * r1 * (dt / 2.0).tan();
    (0..n)
        .map(|k| {
            let t = t0 + (k as f64 + 0.5) * dt;
            let at = |z: f64| [c.centre[0] + rc * t.cos(), c.centre[1] + rc * t.sin(), z];
            let heading = t.to_degrees();
            match cut {
                Cut::Quads(z) => turned_quad([r1 - r0, chord], at(z), heading, mat, l),
                Cut::Solid(z) | Cut::Dashed(z) => {
                    let len = match cut {
                        Cut::Dashed(_) => 3.0,
                        _ => chord,
                    };
                    let size = [r1 - r0, len, z.1 - z.0];
                    cuboid(size, at((z.0 + z.1) / 2.0), heading, mat, l)
                }
            }
        })
        .collect()
}

/// Every object of the loop's curved corners (none with square corners):
/// per corner the asphalt, the markings at the same offsets from the
/// centreline as on the straights, and a gravel shoulder on both sides.
pub fn loop_corner_objects(l: &Layout) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    let hw = l.road_w_m / 2.0;
    let (paint, mark) = (PAINT_Z, class("road_line"));
    for c in l.loop_corners() {
        let r = l.loop_radius_m;
        // The asphalt reaches 1 cm inside its inner edge: a chord piece's
        // inner corners fall a hair short of the inner circle.
        // A divided highway's hard shoulders are part of the asphalt.
        let paved = if l.median { l.sidewalk_m } else { 0.0 };
        let asphalt = (r - hw - paved - 0.01, r + hw + paved);
        out.extend(band(&c, asphalt, Cut::Quads(0.0), "asphalt", class("road")));
        // Lines at offset u from the centreline (positive outward).
        let line = |u: f64, w: f64, cut: Cut, m: &str| {
            band(&c, (r + u - w / 2.0, r + u + w / 2.0), cut, m, mark)
        };
        if l.lanes == 1 {
            out.extend(line(0.0, 0.12, Cut::Dashed(paint), "paint_white_road"));
        } else {
            // Either side of a divided highway's median barrier.
            let u = if l.median { 0.45 } else { 0.12 };
            for u in [-u, u] {
                out.extend(line(u, 0.12, Cut::Solid(paint), "paint_yellow_road"));
            }
            for k in 1..l.lanes {
                for sign in [-1.0, 1.0] {
                    let u = sign * k as f64 * l.lane_w_m;
                    out.extend(line(u, 0.12, Cut::Dashed(paint), "paint_white_road"));
                }
            }
        }
        for sign in [-1.0, 1.0] {
            out.extend(line(
                sign * (hw - 0.25),
                0.15,
                Cut::Solid(paint),
                "paint_white_road",
            ));
        }
        // Gravel shoulders, reaching 5 cm under the asphalt's edges.
        let sw = l.sidewalk_m;
        for (r0, r1) in [(r - hw - sw, r - hw + 0.05), (r + hw - 0.05, r + hw + sw)] {
            if !l.median {
                let (m, label) = ("gravel", class("terrain"));
                out.extend(band(&c, (r0, r1), Cut::Quads(SHOULDER_Z), m, label));
            }
        }
    }
    out
}
