//! Closed vehicle routes over the road grid, on lane centrelines
//! (right-hand traffic), as loops of straights and circular arcs. Block
//! loops circle one block clockwise on the lanes beside it (right turns at
//! every corner); the ring circles the whole town counter-clockwise on the
//! outer lanes of the outer roads (left turns at the town corners, straight
//! through the T junctions).
//!
//! Lane k of a road (counted from the centreline) is the band [k·w, (k+1)·w]
//! beside it, w = lane width. At a corner a route turns inside its own
//! L-shaped corridor (its lane band on both roads), so routes never share
//! road surface: a corner is an arc about a point δ beyond the corridor's
//! inner corner, and a body fits when its footprint stays inside the
//! corridor for the whole arc (`turns`). One lane fits cars only; with two
//! or more lanes the ring's two outer lanes form one corridor for a route
//! on the outer lane that carries buses and trucks (lane L−2 of the ring
//! then carries no route of its own).
//!
//! At the roundabout a block loop's right turn becomes: a right-curving
//! fillet into ring lane k, a counter-clockwise arc round the quarter of
//! the ring between its two arms, and a mirrored fillet out (`ring_turn`).
//! The four blocks at the roundabout use the four quarters of the ring, and
//! lane 0 rides inside lane 1, so routes still share no surface.
//!
//! At a highway loop's curved outer corner (`Layout::loop_corners`) every
//! route through it (the ring and the corner block's loop) turns on the
//! arc concentric with the road's: radius R ± (its distance from the
//! centreline), so it keeps its lane; nobody stands on the curve.

use std::f64::consts::{FRAC_PI_2, PI, SQRT_2};

use super::layout::{Layout, LoopCorner};
use super::roundabout::arm_start_m;
use super::vehicles::BodyKind;

pub mod drive;
mod turns;

pub use turns::{fits_corridor, fits_turn, Turns};

/// Which loop a route is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RouteKind {
    /// Clockwise around block (i, j).
    Block {
        /// Block column.
        i: usize,
        /// Block row.
        j: usize,
    },
    /// Counter-clockwise around the whole town.
    Ring,
    /// Over the overpass and round its two turning loops (`overpass`).
    Overpass,
}

/// One piece of a route's centreline.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Segment {
    /// A straight from `from`, heading `heading` (radians from +x).
    Line {
        /// Start point, world metres.
        from: [f64; 2],
        /// Heading, radians counter-clockwise from +x.
        heading: f64,
        /// Length, metres.
        len_m: f64,
    },
    /// A circular arc about `centre`, from polar angle `phi0`, turning by
    /// `sweep` radians (positive: counter-clockwise, a left turn).
    Arc {
        /// Centre, world metres.
        centre: [f64; 2],
        /// Radius, metres.
        radius_m: f64,
        /// Polar angle of the start point about the centre, radians.
        phi0: f64,
        /// Signed turning angle, radians.
        sweep: f64,
    },
}

impl Segment {
    /// Length, metres.
    pub fn length_m(&self) -> f64 {
        match *self {
            Segment::Line { len_m, .. } => len_m,
            Segment::Arc {
                radius_m, sweep, ..
            } => radius_m * sweep.abs(),
        }
    }

    /// Curvature magnitude 1/r, 1/m (0 on straights).
    pub fn curvature(&self) -> f64 {
        match *self {
            Segment::Line { .. } => 0.0,
            Segment::Arc { radius_m, .. } => 1.0 / radius_m,
        }
    }

    /// Position and heading (radians) at distance `u` ∈ [0, length] along it.
    pub fn at(&self, u: f64) -> ([f64; 2], f64) {
        match *self {
            Segment::Line { from, heading, .. } => (
                [from[0] + u * heading.cos(), from[1] + u * heading.sin()],
                heading,
            ),
            Segment::Arc {
                centre,
                radius_m,
                phi0,
                sweep,
            } => {
                let phi = phi0 + sweep.signum() * u / radius_m;
                let p = [
                    centre[0] + radius_m * phi.cos(),
                    centre[1] + radius_m * phi.sin(),
                ];
                (p, phi + sweep.signum() * FRAC_PI_2)
            }
        }
    }

    /// This segment rotated by `rot` radians about the origin, then moved by `by`.
    fn moved(self, rot: f64, by: [f64; 2]) -> Self {
        let turn = |p: [f64; 2]| {
            let (s, c) = rot.sin_cos();
            [c * p[0] - s * p[1] + by[0], s * p[0] + c * p[1] + by[1]]
        };
        match self {
            Segment::Line {
                from,
                heading,
                len_m,
            } => Segment::Line {
                from: turn(from),
                heading: heading + rot,
                len_m,
            },
            Segment::Arc {
                centre,
                radius_m,
                phi0,
                sweep,
            } => Segment::Arc {
                centre: turn(centre),
                radius_m,
                phi0: phi0 + rot,
                sweep,
            },
        }
    }
}

/// One closed route: straights and arcs on a lane centreline.
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    /// Which loop.
    pub kind: RouteKind,
    /// Lane number from the centreline, 0-based.
    pub lane: u32,
    /// The pieces in driving order; each starts where the previous ends.
    pub segments: Vec<Segment>,
    /// Arc length at the start of each segment, metres.
    pub starts_m: Vec<f64>,
    /// Arc-length intervals [a, b] (b may exceed the length: wrapped)
    /// where no standing body may reach: from each stop line through the
    /// junction to past the departing crosswalk, then (block loops at a
    /// loop corner) the whole curve.
    pub keep_clear_m: Vec<[f64; 2]>,
    /// Whether the route passes the roundabout.
    pub roundabout: bool,
    /// The body types that fit its corners.
    pub bodies: Vec<BodyKind>,
}

impl Route {
    /// A route of `segments` (each starting where the previous ends).
    pub(crate) fn new(
        kind: RouteKind,
        lane: u32,
        segments: Vec<Segment>,
        keep_clear_m: Vec<[f64; 2]>,
        bodies: Vec<BodyKind>,
    ) -> Self {
        let mut starts_m = Vec::with_capacity(segments.len());
        let mut s = 0.0;
        for seg in &segments {
            starts_m.push(s);
            s += seg.length_m();
        }
        let roundabout = segments.len() > 8;
        Route {
            kind,
            lane,
            segments,
            starts_m,
            keep_clear_m,
            roundabout,
            bodies,
        }
    }

    /// Longest body that fits its corners, metres.
    pub fn max_len_m(&self) -> f64 {
        self.bodies
            .iter()
            .map(|b| b.footprint_m()[0])
            .fold(0.0, f64::max)
    }

    /// Perimeter, metres.
    pub fn length_m(&self) -> f64 {
        let n = self.segments.len() - 1;
        self.starts_m[n] + self.segments[n].length_m()
    }

    /// The segment index and distance into it at arc length `s` (wrapped).
    fn locate(&self, s: f64) -> (usize, f64) {
        let s = s.rem_euclid(self.length_m());
        let k = self.starts_m.partition_point(|&a| a <= s).max(1) - 1;
        (k, (s - self.starts_m[k]).min(self.segments[k].length_m()))
    }

    /// Position (x, y) and heading (radians in [0, 2π), counter-clockwise
    /// from +x) at arc length `s` (wrapped).
    pub fn pose(&self, s: f64) -> ([f64; 2], f64) {
        let (k, u) = self.locate(s);
        let (p, h) = self.segments[k].at(u);
        (p, h.rem_euclid(2.0 * PI))
    }

    /// Curvature magnitude 1/r at arc length `s`, 1/m.
    pub fn curvature(&self, s: f64) -> f64 {
        self.segments[self.locate(s).0].curvature()
    }

    /// Whether a standing body covering [s − half, s + half] stays out of
    /// every keep-clear interval (to within 5 cm: a front exactly at the
    /// stop line stands).
    pub fn may_stand(&self, s: f64, half_m: f64) -> bool {
        let len = self.length_m();
        let tol = 0.05;
        self.keep_clear_m.iter().all(|&[a, b]| {
            // Distance from the interval's start to the body's rear, wrapped.
            let rear = (s - half_m - a + tol).rem_euclid(len);
            rear >= b - a && rear + 2.0 * (half_m - tol) <= len
        })
    }
}

/// Stop line distance before a junction edge (painted at 4 m), metres.
pub const STOP_LINE_AT_M: f64 = 4.2;
/// Past a junction edge, the end of the departing crosswalk plus 0.5 m.
const CROSSWALK_CLEAR_M: f64 = 4.0;
/// From the roundabout centre, where an arm's keep-clear zone begins: the
/// arm end plus its set-back crosswalk (6–9 m) plus 1 m.
const RING_CLEAR_EXTRA_M: f64 = 10.0;

/// Radius of ring lane k's centre line (lane 0 innermost), metres.
pub fn ring_lane_radius_m(l: &Layout, k: u32) -> f64 {
    let (r_in, _) = l.roundabout_radii();
    r_in + (k as f64 + 0.5) * (l.lane_w_m + 1.0)
}

/// The canonical roundabout turn of block lane `k`, roundabout centre at
/// the origin: arriving along y = −e heading +x, leaving along x = −e
/// heading −y (e = (k + ½)·w). Returns the three arcs and the cut a: the
/// turn starts and ends a metres from the lane corner (−e, −e).
///
/// A fillet of radius ρ about F = (−√((R+ρ)² − (e+ρ)²), −e−ρ) touches the
/// line and, externally, the ring circle of radius R at polar angle
/// θ_in = atan2(F); the exit mirrors it about y = x (θ → π/2 − θ).
pub fn ring_turn(l: &Layout, k: u32, rho: f64) -> ([Segment; 3], f64) {
    let e = (k as f64 + 0.5) * l.lane_w_m;
    let big_r = ring_lane_radius_m(l, k);
    let fx = -((big_r + rho).powi(2) - (e + rho).powi(2)).sqrt();
    let theta_in = (-e - rho).atan2(fx).rem_euclid(2.0 * PI);
    let alpha = 1.5 * PI - theta_in;
    let theta_out = 2.5 * PI - theta_in;
    let segs = [
        Segment::Arc {
            centre: [fx, -e - rho],
            radius_m: rho,
            phi0: FRAC_PI_2,
            sweep: -alpha,
        },
        Segment::Arc {
            centre: [0.0, 0.0],
            radius_m: big_r,
            phi0: theta_in,
            sweep: theta_out - theta_in,
        },
        Segment::Arc {
            centre: [-e - rho, fx],
            radius_m: rho,
            phi0: theta_out + PI,
            sweep: -alpha,
        },
    ];
    (segs, -fx - e)
}

/// Fillet radius of the roundabout turns, metres: as gentle as leaves
/// both fillets on the ring for a stretch.
pub fn ring_fillet_m(l: &Layout) -> f64 {
    l.lane_w_m * 1.6
}

/// A closed loop through the lane-centre rectangle's `corners` (driving
/// order; the route starts on the straight into `corners[0]`), with plain
/// arcs of radius `r`, or a roundabout turn at the corner nearest `ring`.
/// `keep_clear`: record keep-clear zones at the corners (block loops).
fn loop_route(
    l: &Layout,
    kind: RouteKind,
    lane: u32,
    corners: [[f64; 2]; 4],
    turns: &Turns,
    ring: Option<[f64; 2]>,
    keep_clear: bool,
) -> Route {
    let at = CornerTurns::new(l, lane, turns.radius_m, ring);
    let mut segs = Vec::new();
    let mut clear = Vec::new();
    // Nobody stands on a loop corner's curve; these zones go after the
    // junctions' (the first zone is where the lead vehicle stands).
    let mut curves = Vec::new();
    let mut s = 0.0;
    for q in 0..4 {
        let (prev, c, next) = (corners[(q + 3) % 4], corners[q], corners[(q + 1) % 4]);
        let (d_in, side) = unit(prev, c);
        let (d_out, _) = unit(c, next);
        let (a0, a1) = (at.cut(prev), at.cut(c));
        let from = [prev[0] + a0 * d_in[0], prev[1] + a0 * d_in[1]];
        let heading = d_in[1].atan2(d_in[0]);
        let len_m = side - a0 - a1;
        segs.push(Segment::Line {
            from,
            heading,
            len_m,
        });
        s += len_m;
        let before = segs.len();
        let (edge, depart) = at.turn(c, (d_in, d_out), heading, &mut segs);
        let turn_m: f64 = segs[before..].iter().map(Segment::length_m).sum();
        if keep_clear && at.curve(c).is_some() {
            curves.push([s, s + turn_m]);
        } else if keep_clear {
            clear.push([s + a1 - edge, s + turn_m - a1 + depart]);
        }
        s += turn_m;
    }
    clear.extend(curves);
    Route::new(kind, lane, segs, clear, turns.bodies.clone())
}

/// Unit vector from `a` to `b`, and the distance.
fn unit(a: [f64; 2], b: [f64; 2]) -> ([f64; 2], f64) {
    let d = [b[0] - a[0], b[1] - a[1]];
    let n = d[0].hypot(d[1]);
    ([d[0] / n, d[1] / n], n)
}

/// How a loop route in lane `lane` turns at a lane corner: a plain arc, an
/// arc concentric with a curved loop corner, or a roundabout turn.
struct CornerTurns<'a> {
    l: &'a Layout,
    lane: u32,
    /// Lane centre's distance from the road centreline, metres.
    e: f64,
    /// Radius of a plain turn, metres.
    r: f64,
    /// Fillet radius of a roundabout turn, metres.
    rho: f64,
    /// Roundabout centre, if the route may pass it.
    ring: Option<[f64; 2]>,
    curves: Vec<LoopCorner>,
}

impl<'a> CornerTurns<'a> {
    fn new(l: &'a Layout, lane: u32, r: f64, ring: Option<[f64; 2]>) -> Self {
        CornerTurns {
            l,
            lane,
            e: (lane as f64 + 0.5) * l.lane_w_m,
            r,
            rho: ring_fillet_m(l),
            ring,
            curves: l.loop_corners(),
        }
    }

    /// The roundabout centre if lane corner `c` turns round it.
    fn at_ring(&self, c: [f64; 2]) -> Option<[f64; 2]> {
        let near = |o: &[f64; 2]| (c[0] - o[0]).hypot(c[1] - o[1]) < self.l.road_w_m;
        self.ring.filter(near)
    }

    /// The curved loop corner lane corner `c` lies on, if any.
    fn curve(&self, c: [f64; 2]) -> Option<&LoopCorner> {
        self.curves
            .iter()
            .find(|o| (c[0] - o.corner[0]).hypot(c[1] - o.corner[1]) < self.l.road_w_m)
    }

    /// A plain turn's radius: on a loop corner the arc about the road's
    /// centre (the lane corner lies on its diagonal, √2·radius away).
    fn radius(&self, c: [f64; 2]) -> f64 {
        match self.curve(c) {
            Some(o) => (c[0] - o.centre[0]).hypot(c[1] - o.centre[1]) / SQRT_2,
            None => self.r,
        }
    }

    /// How far before (and after) lane corner `c` its turn starts (ends).
    fn cut(&self, c: [f64; 2]) -> f64 {
        match self.at_ring(c) {
            Some(_) => ring_turn(self.l, self.lane, self.rho).1,
            None => self.radius(c),
        }
    }

    /// Appends the turn at lane corner `c` from direction `d_in` (heading
    /// `heading`) to `d_out`. Returns the distances along the lane from the
    /// lane corner to where the keep-clear zone begins before the turn (the
    /// stop line, or the roundabout arm's keep-clear start) and ends after
    /// it (past the departing crosswalk, or the arm's zone).
    fn turn(
        &self,
        c: [f64; 2],
        (d_in, d_out): ([f64; 2], [f64; 2]),
        heading: f64,
        segs: &mut Vec<Segment>,
    ) -> (f64, f64) {
        let (l, e) = (self.l, self.e);
        let hw = l.road_w_m / 2.0;
        match self.at_ring(c) {
            Some(o) => {
                let (arcs, _) = ring_turn(l, self.lane, self.rho);
                segs.extend(arcs.map(|a| a.moved(heading, o)));
                let edge = arm_start_m(l) + RING_CLEAR_EXTRA_M - e;
                (edge, edge)
            }
            None => {
                let r = self.radius(c);
                let sigma = (d_in[0] * d_out[1] - d_in[1] * d_out[0]).signum();
                let n_left = [-d_in[1], d_in[0]];
                let start = [c[0] - r * d_in[0], c[1] - r * d_in[1]];
                segs.push(Segment::Arc {
                    centre: [
                        start[0] + sigma * r * n_left[0],
                        start[1] + sigma * r * n_left[1],
                    ],
                    radius_m: r,
                    phi0: heading - sigma * FRAC_PI_2,
                    sweep: sigma * FRAC_PI_2,
                });
                (hw - e + STOP_LINE_AT_M, hw - e + CROSSWALK_CLEAR_M)
            }
        }
    }
}

/// Every route of the town: block loops (by row, column, lane), then the
/// ring lanes from the centreline out. Block loops with a corner at the
/// roundabout take their right turn round the ring. With two or more lanes
/// the ring's two outer lanes are one long-vehicle route: it drives the
/// outer lane and swings through both at the town corners
/// (`Turns::merged`), so buses and trucks fit. At curved loop corners the
/// ring and the corner blocks' loops follow the arcs in their lanes.
pub fn routes(l: &Layout, turns: &Turns) -> Vec<Route> {
    let mut out = Vec::new();
    let ring = l.roundabout_center();
    for j in 0..l.ny {
        for i in 0..l.nx {
            for k in 0..l.lanes {
                let e = (k as f64 + 0.5) * l.lane_w_m;
                let (x0, y0) = (i as f64 * l.pitch_m + e, j as f64 * l.pitch_m + e);
                let (x1, y1) = (x0 + l.pitch_m - 2.0 * e, y0 + l.pitch_m - 2.0 * e);
                // Clockwise: west along the south side first.
                let corners = [[x0, y0], [x0, y1], [x1, y1], [x1, y0]];
                let kind = RouteKind::Block { i, j };
                out.push(loop_route(l, kind, k, corners, turns, ring, true));
            }
        }
    }
    let merged = Turns::merged(l.lane_w_m, 2);
    for k in 0..l.lanes {
        let long_vehicles = l.lanes >= 2 && k + 2 >= l.lanes;
        if long_vehicles && k + 2 == l.lanes {
            // Lane L−2 belongs to the long-vehicle route's corners.
            continue;
        }
        let t = if long_vehicles { &merged } else { turns };
        // The corridor's outer wall is lane k's outer edge.
        let e = (k + 1) as f64 * l.lane_w_m - t.offset_m;
        let (x0, y0, x1, y1) = (-e, -e, l.len_x() + e, l.len_y() + e);
        let corners = [[x1, y0], [x1, y1], [x0, y1], [x0, y0]];
        out.push(loop_route(l, RouteKind::Ring, k, corners, t, None, false));
    }
    out
}

#[cfg(test)]
mod tests;
