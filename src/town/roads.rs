//! The road network of a grid town: asphalt per segment and junction, lane
//! markings (dashed or double solid centre lines, dashed lane dividers, solid
//! edge lines, stop lines and zebra crosswalks at junctions), curbs, sidewalks
//! and corner pieces (flat gravel shoulders on country roads), and the
//! terrain around everything. A highway loop's curved outer corners are
//! built in `corners`; the outer roads' straights end at the arcs. A
//! divided highway's outer roads get a median barrier (`median`, a mesh)
//! with a solid yellow line on either side of it, and gravel shoulders.
//!
//! A road segment is described in (along, across) coordinates: `along` runs
//! with the road's positive direction (+x or +y), `across` points to its left
//! (+y for x-roads, −x for y-roads), so right-hand traffic in the positive
//! direction drives at across < 0. Markings are 8 mm boxes lying on the road
//! and split into pieces ≤ 10 m (long slivers are ill-conditioned in f32).

use crate::scene::desc::ObjectDesc;

use super::layout::{Layout, Rect, GROUND_MARGIN_M, STUB_M};
use super::parts::{class, ground_quad, repeated, slab, Label};
use super::ramps::{RampSite, TAPER_M};
use super::roundabout::{arm_start_m, roundabout_objects};
use super::underpass::{underpass_objects, Underpass};

mod corners;
pub mod median;

use corners::loop_corner_objects;

/// Along which world axis a road runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// East–west (along x).
    X,
    /// North–south (along y).
    Y,
}

/// One straight piece of road between two ends.
struct Segment {
    axis: Axis,
    /// Centreline coordinate (y for x-roads, x for y-roads).
    c: f64,
    /// Extent along the road.
    a0: f64,
    a1: f64,
    /// Whether each end meets a junction (crosswalk and stop line there).
    junction: [bool; 2],
    /// Whether each end meets the roundabout ring (a dashed yield line at
    /// the ring, the crosswalk a car length back).
    yield_end: [bool; 2],
    /// Whether its asphalt and lane lines sink into the underpass's cut
    /// (built by `underpass`; its kerbs and sidewalks stay at grade).
    sunk: bool,
}

impl Segment {
    /// The piece of the `axis` road at centreline `c` from `a0` to `a1`,
    /// with junctions at the ends `junction` marks and no yield line.
    fn new(axis: Axis, c: f64, (a0, a1): (f64, f64), junction: [bool; 2]) -> Segment {
        Segment {
            axis,
            c,
            a0,
            a1,
            junction,
            yield_end: [false; 2],
            sunk: false,
        }
    }

    /// World (x, y) of road coordinates.
    fn xy(&self, along: f64, across: f64) -> [f64; 2] {
        match self.axis {
            Axis::X => [along, self.c + across],
            Axis::Y => [self.c - across, along],
        }
    }
    /// A box over along ∈ [a, b], across ∈ [u, v], between two heights.
    fn slab(
        &self,
        (a, b): (f64, f64),
        (u, v): (f64, f64),
        z: (f64, f64),
        m: &str,
        l: Label,
    ) -> ObjectDesc {
        let (p, q) = (self.xy(a, u), self.xy(b, v));
        let min = [p[0].min(q[0]), p[1].min(q[1])];
        let max = [p[0].max(q[0]), p[1].max(q[1])];
        slab(min, max, z.0, z.1, m, l)
    }
    /// World offset of one step `d` along the road.
    fn step(&self, d: f64) -> [f64; 3] {
        match self.axis {
            Axis::X => [d, 0.0, 0.0],
            Axis::Y => [0.0, d, 0.0],
        }
    }
}

const PAINT_Z: (f64, f64) = (0.0, 0.008);
const CROSSWALK_M: (f64, f64) = (0.5, 3.5);
const STOP_LINE_AT_M: f64 = 4.0;
/// How far back from the ring a roundabout arm's crosswalk starts, metres.
const YIELD_CROSSWALK_M: f64 = 6.0;

/// Every road, marking, curb, sidewalk and terrain object of the town;
/// beside the ramp `sites` the outer edge line turns dashed along the tapers
/// and the outer shoulder (or sidewalk) leaves room for taper and gore.
pub fn road_objects(l: &Layout, sites: &[RampSite]) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    let b = l.bounds();
    let m = GROUND_MARGIN_M;
    let (lo, hi) = ([b.min[0] - m, b.min[1] - m], [b.max[0] + m, b.max[1] + m]);
    match l.river_band() {
        None => out.extend(ground_around_cut(l, lo, hi)),
        Some(band) => {
            let t = class("terrain");
            out.push(ground_quad(lo, [hi[0], band.min[1]], -0.02, "ground", t));
            out.push(ground_quad([lo[0], band.max[1]], hi, -0.02, "ground", t));
            river_objects(l, &band, &mut out);
        }
    }
    let (p, hw) = (l.pitch_m, l.road_w_m / 2.0);
    for j in 0..=l.ny {
        let y = j as f64 * p;
        // An outer x-road with loop corners has no stubs.
        let curved = l.loop_corner_at(0, j);
        if !curved {
            let stub = Segment::new(Axis::X, y, (-STUB_M, -hw), [false, true]);
            out.extend(segment_objects(l, sites, &stub));
        }
        for i in 0..l.nx {
            let x = i as f64 * p;
            // Over the underpass the x-road runs straight on through.
            let (under, next) = (Some((i, j)) == l.underpass, Some((i + 1, j)) == l.underpass);
            if under {
                continue;
            }
            let end = if next { x + 2.0 * p - hw } else { x + p - hw };
            let s = Segment::new(Axis::X, y, (x + hw, end), [true, true]);
            let s = roundabout_arm(l, s);
            let s = to_loop_arcs(l, s, (i == 0, i + 1 == l.nx), l.len_x(), curved);
            out.extend(segment_objects(l, sites, &s));
        }
        let e = l.len_x();
        if !curved {
            let stub = Segment::new(Axis::X, y, (e + hw, e + STUB_M), [true, false]);
            out.extend(segment_objects(l, sites, &stub));
        }
    }
    for i in 0..=l.nx {
        let x = i as f64 * p;
        let curved = l.loop_corner_at(i, 0);
        for j in 0..l.ny {
            let y = j as f64 * p;
            // The two pieces either side of the underpass's crossing sink.
            let (from, to) = (Some((i, j)) == l.underpass, Some((i, j + 1)) == l.underpass);
            let mut s = Segment::new(Axis::Y, x, (y + hw, y + p - hw), [!from, !to]);
            s.sunk = from || to;
            let s = roundabout_arm(l, s);
            let s = to_loop_arcs(l, s, (j == 0, j + 1 == l.ny), l.len_y(), curved);
            out.extend(segment_objects(l, sites, &s));
        }
    }
    for j in 0..=l.ny {
        for i in 0..=l.nx {
            let special = l.roundabout == Some((i, j)) || l.underpass == Some((i, j));
            if !special && !l.loop_corner_at(i, j) {
                junction_objects(l, i, j, &mut out);
            }
        }
    }
    out.extend(roundabout_objects(l));
    out.extend(loop_corner_objects(l));
    out.extend(underpass_objects(l));
    out
}

/// The ground quad from `lo` to `hi`, in four pieces round the
/// underpass's cut (whose road lies below it) if the town has one; the
/// hole's sides lie under the kerbs (so a warp's chords stay hidden).
fn ground_around_cut(l: &Layout, lo: [f64; 2], hi: [f64; 2]) -> Vec<ObjectDesc> {
    let g = |a: [f64; 2], b: [f64; 2]| ground_quad(a, b, -0.02, "ground", class("terrain"));
    let Some(u) = Underpass::of(l) else {
        return vec![g(lo, hi)];
    };
    let (x0, x1) = (u.x_m - u.half_w_m - 0.25, u.x_m + u.half_w_m + 0.25);
    let (y0, y1) = u.ends;
    vec![
        g(lo, [x0, hi[1]]),
        g([x1, lo[1]], hi),
        g([x0, lo[1]], [x1, y0]),
        g([x0, y1], [x1, hi[1]]),
    ]
}

/// The segment ending at the tangent point of a curved loop corner (R from
/// the grid corner, no junction there) at a first or last end of an outer
/// road of length `len`; unchanged elsewhere.
fn to_loop_arcs(
    l: &Layout,
    mut s: Segment,
    (first, last): (bool, bool),
    len: f64,
    curved: bool,
) -> Segment {
    if curved && first {
        (s.a0, s.junction[0]) = (l.loop_radius_m, false);
    }
    if curved && last {
        (s.a1, s.junction[1]) = (len - l.loop_radius_m, false);
    }
    s
}

/// The segment shortened to the ring where it is an arm of the roundabout.
fn roundabout_arm(l: &Layout, mut s: Segment) -> Segment {
    let Some(ctr) = l.roundabout_center() else {
        return s;
    };
    let (cc, ca) = match s.axis {
        Axis::X => (ctr[1], ctr[0]),
        Axis::Y => (ctr[0], ctr[1]),
    };
    if s.c != cc {
        return s;
    }
    let (hw, arm) = (l.road_w_m / 2.0, arm_start_m(l));
    if (s.a0 - (ca + hw)).abs() < 1e-9 {
        (s.a0, s.yield_end[0]) = (ca + arm, true);
    }
    if (s.a1 - (ca - hw)).abs() < 1e-9 {
        (s.a1, s.yield_end[1]) = (ca - arm, true);
    }
    s
}

/// The ramp sites beside segment `s` on its side `sign` (x-roads only).
fn sites_beside<'a>(s: &Segment, sign: f64, sites: &'a [RampSite]) -> Vec<&'a RampSite> {
    let mut v: Vec<&RampSite> = sites
        .iter()
        .filter(|r| s.axis == Axis::X && (r.y_road_m - s.c).abs() < 1e-9 && r.side == sign)
        .filter(|r| r.a0 >= s.a0 && r.a1 <= s.a1)
        .collect();
    v.sort_by(|a, b| a.a0.total_cmp(&b.a0));
    v
}

/// [a0, a1] without the `cuts` (sorted, disjoint, inside it).
fn uncut(a0: f64, a1: f64, cuts: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut at = a0;
    for &(c0, c1) in cuts {
        if c0 > at {
            out.push((at, c0));
        }
        at = at.max(c1);
    }
    if a1 > at {
        out.push((at, a1));
    }
    out
}

/// The solid edge line on one side, dashed along the ramp tapers (there it
/// divides the through lane from the deceleration or acceleration lane).
fn edge_line(s: &Segment, (s0, s1): (f64, f64), u: f64, ramps: &[&RampSite]) -> Vec<ObjectDesc> {
    let (m, mark) = ("paint_white_road", class("road_line"));
    let mut o = Vec::new();
    let tapers: Vec<(f64, f64)> = ramps
        .iter()
        .flat_map(|r| [(r.a0, r.a0 + TAPER_M), (r.a1 - TAPER_M, r.a1)])
        .collect();
    for &(a, b) in &tapers {
        o.extend(dashed(s, a, b, u, 0.15, m, mark));
    }
    for (a, b) in uncut(s0, s1, &tapers) {
        if b - a > 0.05 {
            o.extend(solid(s, a, b, u, 0.15, m, mark));
        }
    }
    o
}

/// Everything along one straight piece of road: its asphalt, lane lines,
/// the stop or yield line and crosswalk at each junction end, then curbs
/// and sidewalks (or shoulders).
fn segment_objects(l: &Layout, sites: &[RampSite], s: &Segment) -> Vec<ObjectDesc> {
    let hw = l.road_w_m / 2.0;
    let mut o = Vec::new();
    if s.sunk {
        for end in 0..2 {
            if s.junction[end] {
                junction_end(l, s, end, &mut o);
            }
        }
        roadsides(l, sites, s, &mut o);
        return o;
    }
    let (p, q) = (s.xy(s.a0, -hw), s.xy(s.a1, hw));
    o.push(ground_quad(
        [p[0].min(q[0]), p[1].min(q[1])],
        [p[0].max(q[0]), p[1].max(q[1])],
        0.0,
        "asphalt",
        class("road"),
    ));
    lane_lines(l, sites, s, &mut o);
    for end in 0..2 {
        if s.junction[end] {
            junction_end(l, s, end, &mut o);
        }
    }
    roadsides(l, sites, s, &mut o);
    o
}

/// The centre line (dashed on one-lane roads, else double solid yellow),
/// dashed lane dividers and the edge lines, stopping short of crosswalks
/// and stop lines at junction ends.
fn lane_lines(l: &Layout, sites: &[RampSite], s: &Segment, o: &mut Vec<ObjectDesc>) {
    let mark = class("road_line");
    let clear = |end: usize| match (s.junction[end], s.yield_end[end]) {
        (_, true) => YIELD_CROSSWALK_M + CROSSWALK_M.1 + 0.6,
        (true, false) => STOP_LINE_AT_M + 0.6,
        _ => 0.0,
    };
    let s0 = s.a0 + clear(0);
    let s1 = s.a1 - clear(1);
    if s1 - s0 > 1.0 {
        if l.lanes == 1 {
            o.extend(dashed(s, s0, s1, 0.0, 0.12, "paint_white_road", mark));
        } else {
            // Either side of a median barrier, else a double centre line.
            let u = if divided(l, s) { 0.45 } else { 0.12 };
            for u in [-u, u] {
                o.extend(solid(s, s0, s1, u, 0.12, "paint_yellow_road", mark));
            }
            for k in 1..l.lanes {
                for sign in [-1.0, 1.0] {
                    let u = sign * k as f64 * l.lane_w_m;
                    o.extend(dashed(s, s0, s1, u, 0.12, "paint_white_road", mark));
                }
            }
        }
        // The edge lines bound the driving lanes: a parking lane lies beyond.
        let edge = l.drive_hw() - 0.25;
        for sign in [-1.0, 1.0] {
            let ramps = sites_beside(s, sign, sites);
            o.extend(edge_line(s, (s0, s1), sign * edge, &ramps));
        }
    }
}

/// Whether segment `s` lies on a divided highway (a median barrier runs
/// on its centreline).
fn divided(l: &Layout, s: &Segment) -> bool {
    let k = (s.c / l.pitch_m).round() as usize;
    match s.axis {
        Axis::X => l.median_x(k),
        Axis::Y => l.median_y(k),
    }
}

/// At junction end `end` (0: a0, 1: a1): the stop line across the lanes
/// entering the junction (a dashed yield line at the roundabout ring), then
/// on town roads the crosswalk's stripes (parallel to traffic, 0.5 m wide
/// every 1 m; set back from the ring at a yield end).
fn junction_end(l: &Layout, s: &Segment, end: usize, o: &mut Vec<ObjectDesc>) {
    let mark = class("road_line");
    let hw = l.road_w_m / 2.0;
    let (dir, edge) = if end == 0 { (1.0, s.a0) } else { (-1.0, s.a1) };
    // Traffic entering at a0 drives in −along, on the left (across > 0).
    let lanes = if end == 0 {
        (0.2, hw - 0.2)
    } else {
        (-hw + 0.2, -0.2)
    };
    let across = match s.axis {
        Axis::X => [0.0, 1.0, 0.0],
        Axis::Y => [-1.0, 0.0, 0.0],
    };
    let back = if s.yield_end[end] {
        // Yield line: 0.6 m dashes every 1.2 m along the ring's edge.
        let a = edge + dir * 0.5;
        let n = ((lanes.1 - lanes.0 + 0.6) / 1.2).floor() as u32;
        let u = (lanes.0, lanes.0 + 0.6);
        let dash = s.slab((a - 0.2, a + 0.2), u, PAINT_Z, "paint_white_road", mark);
        o.push(repeated(dash, &[(n, across.map(|v| v * 1.2))]));
        YIELD_CROSSWALK_M
    } else {
        let a = edge + dir * STOP_LINE_AT_M;
        o.push(s.slab((a - 0.2, a + 0.2), lanes, PAINT_Z, "paint_white_road", mark));
        0.0
    };
    if !l.sidewalks {
        return; // no crosswalks on country roads
    }
    let (c0, c1) = (
        edge + dir * (back + CROSSWALK_M.0),
        edge + dir * (back + CROSSWALK_M.1),
    );
    let n = ((2.0 * hw - 0.5) / 1.0).floor() as u32;
    let first = -hw + 0.5;
    let stripe = s.slab(
        (c0.min(c1), c0.max(c1)),
        (first, first + 0.5),
        PAINT_Z,
        "paint_white_road",
        mark,
    );
    o.push(repeated(stripe, &[(n, across)]));
}

/// Curbs and sidewalks (or flat gravel shoulders on country roads and
/// divided highways) on both sides, leaving room beside
/// ramp sites for their tapers and gores.
fn roadsides(l: &Layout, sites: &[RampSite], s: &Segment, o: &mut Vec<ObjectDesc>) {
    let side = class("sidewalk");
    let hw = l.road_w_m / 2.0;
    let sw = l.sidewalk_m;
    for sign in [-1.0f64, 1.0] {
        let sorted = |(a, b): (f64, f64)| (a.min(b), a.max(b));
        let cuts: Vec<(f64, f64)> = sites_beside(s, sign, sites)
            .iter()
            .flat_map(|r| r.shoulder_cuts())
            .collect();
        for (a0, a1) in uncut(s.a0, s.a1, &cuts) {
            if !l.sidewalks {
                let shoulder = sorted((sign * hw, sign * (hw + sw)));
                let (p, q) = (s.xy(a0, shoulder.0), s.xy(a1, shoulder.1));
                let (min, max) = (
                    [p[0].min(q[0]), p[1].min(q[1])],
                    [p[0].max(q[0]), p[1].max(q[1])],
                );
                // Gravel on divided roads too: a paved (road) shoulder lay
                // coplanar with the junctions' gravel corners, so which of
                // road or terrain was seen there depended on traversal.
                o.push(ground_quad(min, max, 0.0, "gravel", class("terrain")));
                continue;
            }
            let curb = (sign * hw, sign * (hw + 0.25));
            let walk = (sign * (hw + 0.25), sign * (hw + sw));
            o.push(s.slab((a0, a1), sorted(curb), (0.0, 0.15), "curb", side));
            o.push(s.slab((a0, a1), sorted(walk), (0.0, 0.14), "sidewalk", side));
        }
    }
}

/// River bed, water surface, stone embankments and, where each y-road
/// crosses, a bridge deck under the road and sidewalks with parapets.
fn river_objects(l: &Layout, band: &Rect, out: &mut Vec<ObjectDesc>) {
    let (bed_z, water_z) = (-3.0, -1.2);
    out.push(ground_quad(
        band.min,
        band.max,
        bed_z,
        "mud",
        class("terrain"),
    ));
    out.push(ground_quad(
        band.min,
        band.max,
        water_z,
        "water",
        class("water"),
    ));
    for y in [band.min[1], band.max[1]] {
        let (y0, y1) = if y == band.min[1] {
            (y, y + 0.4)
        } else {
            (y - 0.4, y)
        };
        out.push(slab(
            [band.min[0], y0],
            [band.max[0], y1],
            bed_z,
            0.0,
            "stone",
            class("terrain"),
        ));
    }
    let reach = l.road_w_m / 2.0 + l.sidewalk_m;
    for i in 0..=l.nx {
        let x = i as f64 * l.pitch_m;
        let (min, max) = ([x - reach, band.min[1]], [x + reach, band.max[1]]);
        // The deck and its parapets are a structure (their sides are seen
        // across the river), labelled like the overpass's; only the asphalt
        // on top of the deck is road.
        out.push(slab(min, max, -0.8, -0.005, "concrete", class("bridge")));
        for sx in [-1.0, 1.0] {
            let xe = x + sx * (reach - 0.1);
            let parapet = slab(
                [xe - 0.1, band.min[1]],
                [xe + 0.1, band.max[1]],
                0.0,
                1.1,
                "concrete",
                class("bridge"),
            );
            out.push(parapet);
        }
    }
}

/// A raised sidewalk piece, or a flat gravel shoulder on country roads.
fn walk_piece(l: &Layout, min: [f64; 2], max: [f64; 2]) -> ObjectDesc {
    if l.sidewalks {
        slab(min, max, 0.0, 0.14, "sidewalk", class("sidewalk"))
    } else {
        ground_quad(min, max, 0.0, "gravel", class("terrain"))
    }
}

/// A solid line split into equal pieces of at most 10 m.
fn solid(s: &Segment, a: f64, b: f64, u: f64, w: f64, m: &str, l: Label) -> Vec<ObjectDesc> {
    let n = ((b - a) / 10.0).ceil().max(1.0);
    let piece = (b - a) / n;
    let first = s.slab((a, a + piece), (u - w / 2.0, u + w / 2.0), PAINT_Z, m, l);
    vec![repeated(first, &[(n as u32, s.step(piece))])]
}

/// A dashed line: 3 m dashes every 6 m, centred in [a, b].
fn dashed(s: &Segment, a: f64, b: f64, u: f64, w: f64, m: &str, l: Label) -> Vec<ObjectDesc> {
    let n = ((b - a + 3.0) / 6.0).floor() as u32;
    if n == 0 {
        return Vec::new();
    }
    let start = a + ((b - a) - (n as f64 * 6.0 - 3.0)) / 2.0;
    let first = s.slab(
        (start, start + 3.0),
        (u - w / 2.0, u + w / 2.0),
        PAINT_Z,
        m,
        l,
    );
    vec![repeated(first, &[(n, s.step(6.0))])]
}

/// Junction asphalt, sidewalk corners and, where an arm is missing (T
/// junctions on the outer x-roads), a sidewalk with curb across it.
fn junction_objects(l: &Layout, i: usize, j: usize, out: &mut Vec<ObjectDesc>) {
    let (hw, sw) = (l.road_w_m / 2.0, l.sidewalk_m);
    let (x, y) = (i as f64 * l.pitch_m, j as f64 * l.pitch_m);
    out.push(ground_quad(
        [x - hw, y - hw],
        [x + hw, y + hw],
        0.0,
        "asphalt",
        class("road"),
    ));
    let side = class("sidewalk");
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            let (cx, cy) = (x + sx * (hw + sw / 2.0), y + sy * (hw + sw / 2.0));
            out.push(walk_piece(
                l,
                [cx - sw / 2.0, cy - sw / 2.0],
                [cx + sw / 2.0, cy + sw / 2.0],
            ));
        }
    }
    let missing: Option<f64> = if j == 0 {
        Some(-1.0)
    } else if j == l.ny {
        Some(1.0)
    } else {
        None
    };
    if let Some(sy) = missing {
        if !l.sidewalks {
            let (w0, w1) = (y + sy * hw, y + sy * (hw + sw));
            out.push(walk_piece(l, [x - hw, w0.min(w1)], [x + hw, w0.max(w1)]));
            return;
        }
        let (c0, c1) = (y + sy * hw, y + sy * (hw + 0.25));
        out.push(slab(
            [x - hw, c0.min(c1)],
            [x + hw, c0.max(c1)],
            0.0,
            0.15,
            "curb",
            side,
        ));
        let (w0, w1) = (y + sy * (hw + 0.25), y + sy * (hw + sw));
        out.push(walk_piece(l, [x - hw, w0.min(w1)], [x + hw, w0.max(w1)]));
    }
}

#[cfg(test)]
mod tests;
