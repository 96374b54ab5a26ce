//! The ego's drive path: a seeded walk over the road grid, junction to
//! junction, on lane centrelines (right-hand traffic), grown on demand.
//!
//! A link is one direction of one road between adjacent junctions; at its
//! end junction the walk draws a move among the legal ones (right,
//! straight, left; no U-turns, no stubs): right turns from the outer lane
//! (L − 1), left turns from the inner lane (0), straight from any lane,
//! with lane changes (an S-curve of two arcs, `LANE_CHANGE_M` long) on the
//! link's straight. Geometry per move, a = where the move starts and ends,
//! measured along the lane from the junction centre, e = the lane's offset:
//! right turn a = e + r (r: the block loops' corner radius, so it rides the
//! block loop's corner), left turn a = road half-width (radius a + e),
//! straight a = half-width; a curved loop corner a = R (the arc concentric
//! with the road's, radius R ∓ e); the roundabout enters and leaves like a
//! block loop's turn (`ring_turn`) and rides 0, 1 or 2 more quarters of its
//! ring lane for right, straight, left.
//!
//! Each junction passed records a `Crossing`: the stop line for the
//! driver's front, the end of the zone that must be clear before its
//! approach turns red (past the departing crosswalk), and the approach's
//! direction, whose signal phase (`signals::until_red_s`) it waits for.
//!
//! At the underpass's crossing (`Layout::underpass`) the only move is
//! straight on, and no `Crossing` is recorded: the two roads' traffic
//! passes on two levels, without signals.
//!
//! Background vehicles (`traffic::sim`) walk without lane changes: from
//! lane 0 they go straight or left, from the outer lane straight or right
//! (one lane: any move), preferring moves whose next junction again offers
//! their lane a move; only where none is left do they change lanes. Buses
//! and trucks (lane 0) turn right only where nothing else is legal (a
//! town's corner), and then not from the kerb lane, whose tight corner
//! their ends would sweep over the kerb, but through all their side's
//! lanes on `Turns::merged`'s line, shifting onto it and back over
//! `WIDE_SHIFT_M`.

use std::f64::consts::{FRAC_PI_2, PI};

use super::{ring_fillet_m, ring_turn, Segment, CROSSWALK_CLEAR_M, RING_CLEAR_EXTRA_M};
use super::{Turns, STOP_LINE_AT_M};
use crate::town::layout::Layout;
use crate::town::rng::Rng;
use crate::town::roundabout::arm_start_m;

/// Length of one lane change along the road, metres.
pub const LANE_CHANGE_M: f64 = 30.0;
/// Length of the shift onto a long body's wide right turn and back, metres.
const WIDE_SHIFT_M: f64 = 15.0;
/// Chance of a lane change on a straight-through link with several lanes.
const CHANGE_P: f64 = 0.35;
/// Unit directions: east, north, west, south (index · 90° = heading).
const DIRS: [[i64; 2]; 4] = [[1, 0], [0, 1], [-1, 0], [0, -1]];

/// A move at a junction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Move {
    /// Turn right (clockwise).
    Right,
    /// Go straight on.
    Straight,
    /// Turn left.
    Left,
}

/// One junction on the path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// Junction (i, j).
    pub junction: (usize, usize),
    /// The move made there.
    pub turn: Move,
    /// Arc length where the ego's front stops (the stop line), metres.
    pub stop_m: f64,
    /// Arc length where the zone kept clear during stands ends, metres.
    pub clear_m: f64,
    /// Direction of the approach (0 east, 1 north, 2 west, 3 south).
    pub dir: usize,
    /// Whether the junction is the roundabout (no signals: first come).
    pub roundabout: bool,
    /// The lane the move is made from.
    pub lane: u32,
    /// At a right-in, right-out junction of a divided highway
    /// (`Layout::median_through`): `Some(true)` on the highway (no
    /// signals, right of way), `Some(false)` on the side street (gives
    /// way to the highway traffic it merges into); `None` elsewhere.
    pub major: Option<bool>,
}

/// The path driven so far and the walk that grows it.
#[derive(Clone, Debug)]
pub struct DrivePath {
    /// Pieces in driving order.
    pub segments: Vec<Segment>,
    /// Arc length at the start of each piece, metres.
    pub starts_m: Vec<f64>,
    /// Junctions passed, in order.
    pub crossings: Vec<Crossing>,
    len_m: f64,
    l: Layout,
    right_r: f64,
    rng: Rng,
    /// The walk's current link: from junction `from` in direction `dir`,
    /// on lane `lane`; the path ends `at_m` past `from` along it.
    from: [i64; 2],
    dir: usize,
    lane: u32,
    at_m: f64,
    /// Whether the walk changes lanes freely (the ego) or only when its
    /// lane has no move left (background vehicles).
    changes: bool,
    /// Whether it carries a long body (bus, truck): right turns only
    /// where no other move is legal.
    long: bool,
    /// A long body's right turn through all the lanes of its side
    /// (`Turns::merged`): the route's offset from the centreline and the
    /// arc's radius, metres.
    wide_right: (f64, f64),
}

/// Unit vector of direction `d`.
fn unit(d: usize) -> [f64; 2] {
    DIRS[d % 4].map(|c| c as f64)
}

/// The right-hand normal of direction `d`.
fn right(d: usize) -> [f64; 2] {
    let u = unit(d);
    [u[1], -u[0]]
}

/// An arc from `p` heading `h`, radius `r`, turning by `sweep` (> 0 left).
fn arc_from(p: [f64; 2], h: f64, r: f64, sweep: f64) -> Segment {
    let sg = sweep.signum();
    let n_left = [-h.sin(), h.cos()];
    Segment::Arc {
        centre: [p[0] + sg * r * n_left[0], p[1] + sg * r * n_left[1]],
        radius_m: r,
        phi0: h - sg * FRAC_PI_2,
        sweep,
    }
}

impl DrivePath {
    /// The drive starting on link `start` (index into `links(l)`), lane
    /// and moves drawn from `rng`; the path starts mid-link.
    pub fn new(l: &Layout, turns: &Turns, start: usize, mut rng: Rng) -> Self {
        let lane = rng.int(0, l.lanes - 1);
        let mut p = Self::on_link(l, turns, start, lane, None, rng);
        p.changes = true;
        p.extend();
        p
    }

    /// A background vehicle's walk from link `start`, lane `lane`, `at`
    /// metres past the link's start junction (None: mid-way along its
    /// straight), moves drawn from `rng`, without free lane changes;
    /// `long`: a bus or truck, turning right only where nothing else is
    /// legal.
    pub fn background(
        l: &Layout,
        turns: &Turns,
        start: usize,
        lane: u32,
        at: f64,
        rng: Rng,
        long: bool,
    ) -> Self {
        let mut p = Self::on_link(l, turns, start, lane, Some(at), rng);
        p.long = long;
        let wide = Turns::merged(l.lane_w_m, l.lanes);
        p.wide_right = (wide.offset_m, wide.radius_m);
        p.extend();
        p
    }

    fn on_link(
        l: &Layout,
        turns: &Turns,
        start: usize,
        lane: u32,
        at: Option<f64>,
        rng: Rng,
    ) -> Self {
        let all = links(l);
        let (from, dir) = all[start % all.len()];
        // Mid-way along the link's straight (between loop-corner curves).
        let to = [from.0 as i64 + DIRS[dir][0], from.1 as i64 + DIRS[dir][1]];
        let curve = |j: [i64; 2]| {
            if l.loop_corner_at(j[0] as usize, j[1] as usize) {
                l.loop_radius_m
            } else {
                0.0
            }
        };
        let mid = (curve([from.0 as i64, from.1 as i64]) + l.pitch_m - curve(to)) / 2.0;
        DrivePath {
            segments: Vec::new(),
            starts_m: Vec::new(),
            crossings: Vec::new(),
            len_m: 0.0,
            l: l.clone(),
            right_r: turns.radius_m,
            rng,
            from: [from.0 as i64, from.1 as i64],
            dir,
            lane,
            at_m: at.unwrap_or(mid),
            changes: false,
            long: false,
            wide_right: (0.0, 0.0),
        }
    }

    /// The layout it drives on.
    pub fn layout(&self) -> &Layout {
        &self.l
    }

    /// Length so far, metres.
    pub fn length_m(&self) -> f64 {
        self.len_m
    }

    /// Grows the path until it is at least `s` metres long.
    pub fn reach(&mut self, s: f64) {
        while self.len_m < s {
            self.extend();
        }
    }

    /// Position and heading (radians in [0, 2π)) at arc length `s`.
    pub fn pose(&self, s: f64) -> ([f64; 2], f64) {
        let s = s.clamp(0.0, self.len_m);
        let k = self.starts_m.partition_point(|&a| a <= s).max(1) - 1;
        let (p, h) = self.segments[k].at((s - self.starts_m[k]).min(self.segments[k].length_m()));
        (p, h.rem_euclid(2.0 * PI))
    }

    /// The pieces overlapping [a, b]: (start arc length, piece).
    pub fn pieces(&self, a: f64, b: f64) -> impl Iterator<Item = (f64, &Segment)> {
        let k = self.starts_m.partition_point(|&x| x <= a).max(1) - 1;
        self.starts_m[k..]
            .iter()
            .copied()
            .zip(&self.segments[k..])
            .take_while(move |(s, _)| *s <= b)
    }

    fn push(&mut self, seg: Segment) {
        if seg.length_m() > 1e-9 {
            self.starts_m.push(self.len_m);
            self.len_m += seg.length_m();
            self.segments.push(seg);
        }
    }

    /// End point and heading of the path so far (or of the start).
    fn end(&self) -> ([f64; 2], f64) {
        match self.segments.last() {
            Some(s) => s.at(s.length_m()),
            None => {
                let p = self.point(self.from, self.dir, self.e(self.lane), self.at_m);
                (p, (self.dir as f64) * FRAC_PI_2)
            }
        }
    }

    /// Lane k's centre offset from the road centreline, metres.
    fn e(&self, k: u32) -> f64 {
        (k as f64 + 0.5) * self.l.lane_w_m
    }

    /// The point `along` metres from junction `j` in direction `d`, on the
    /// lane line at offset `e`.
    fn point(&self, j: [i64; 2], d: usize, e: f64, along: f64) -> [f64; 2] {
        let (u, r) = (unit(d), right(d));
        let c = [j[0] as f64 * self.l.pitch_m, j[1] as f64 * self.l.pitch_m];
        [
            c[0] + e * r[0] + along * u[0],
            c[1] + e * r[1] + along * u[1],
        ]
    }

    /// Whether the link from `j` in direction `d` lies on the grid.
    fn valid(&self, j: [i64; 2], d: usize) -> bool {
        let n = [j[0] + DIRS[d][0], j[1] + DIRS[d][1]];
        n[0] >= 0 && n[1] >= 0 && n[0] <= self.l.nx as i64 && n[1] <= self.l.ny as i64
    }

    /// Whether lane `lane` may make move `m` without changing lanes.
    fn lane_allows(&self, lane: u32, m: Move) -> bool {
        match m {
            Move::Straight => true,
            Move::Right => lane + 1 == self.l.lanes,
            Move::Left => lane == 0,
        }
    }

    /// The moves at junction `to` that the current lane makes without
    /// changing lanes, preferring those after which the next junction
    /// offers the lane a move too (all of `options` if none).
    fn lane_options(&self, to: [i64; 2], options: Vec<(Move, usize)>) -> Vec<(Move, usize)> {
        let lane = self.lane;
        let next_ok = |d: usize| {
            let n = [to[0] + DIRS[d][0], to[1] + DIRS[d][1]];
            let nu = (n[0] as usize, n[1] as usize);
            self.l.loop_corner_at(nu.0, nu.1)
                || [(Move::Right, 3), (Move::Straight, 0), (Move::Left, 1)]
                    .iter()
                    .any(|&(m, q)| self.valid(n, (d + q) % 4) && self.lane_allows(lane, m))
        };
        let own: Vec<_> = options
            .iter()
            .copied()
            .filter(|&(m, _)| self.lane_allows(lane, m))
            .collect();
        let good: Vec<_> = own.iter().copied().filter(|&(_, d)| next_ok(d)).collect();
        if !good.is_empty() {
            good
        } else if !own.is_empty() {
            own
        } else {
            options
        }
    }

    /// Where a move at junction `j` starts (= ends) from the centre, and
    /// its segments from the entry point `p` heading `h` on lane offset `e`.
    /// `wide`: a long body's right turn (`wide_right`).
    fn move_geometry(&self, j: [i64; 2], m: Move, e: f64, lane: u32, wide: bool) -> (f64, Kind) {
        let l = &self.l;
        let hw = l.road_w_m / 2.0;
        let ju = (j[0] as usize, j[1] as usize);
        if l.loop_corner_at(ju.0, ju.1) {
            return (l.loop_radius_m, Kind::Plain);
        }
        if l.roundabout == Some(ju) {
            let (_, cut) = ring_turn(l, lane, ring_fillet_m(l));
            return (cut + e, Kind::Ring);
        }
        let a = match m {
            Move::Right if wide => e + self.wide_right.1,
            Move::Right => e + self.right_r,
            Move::Straight | Move::Left => hw,
        };
        (a, Kind::Plain)
    }

    /// Appends one link's remaining straight (with lane changes) and the
    /// move at its end junction.
    fn extend(&mut self) {
        let to = [
            self.from[0] + DIRS[self.dir][0],
            self.from[1] + DIRS[self.dir][1],
        ];
        let lanes = self.l.lanes;
        let ju = (to[0] as usize, to[1] as usize);
        // Legal moves at `to` (no U-turns, no stubs, no left turn across a
        // highway's median barrier, only straight on where one road
        // passes under the other).
        let under = self.l.underpass == Some(ju);
        let options: Vec<(Move, usize)> = [(Move::Right, 3), (Move::Straight, 0), (Move::Left, 1)]
            .into_iter()
            .filter(|&(m, _)| m != Move::Left || !self.l.median_through(ju.0, ju.1))
            .filter(|&(m, _)| m == Move::Straight || !under)
            .map(|(m, q)| (m, (self.dir + q) % 4))
            .filter(|&(_, d)| self.valid(to, d))
            .collect::<Vec<_>>();
        // A long body turns right only where nothing else is legal: its
        // wide turn sweeps across the kerb lane.
        let options: Vec<(Move, usize)> = if self.long && options.iter().any(|o| o.0 != Move::Right)
        {
            options.into_iter().filter(|o| o.0 != Move::Right).collect()
        } else {
            options
        };
        let curve = self.l.loop_corner_at(ju.0, ju.1);
        let free = self.changes;
        let need = |m: Move, cur: u32, r: &mut Rng| match m {
            _ if curve => cur,
            Move::Right => lanes - 1,
            Move::Left => 0,
            Move::Straight if free && lanes > 1 && r.chance(CHANGE_P) => r.int(0, lanes - 1),
            Move::Straight => cur,
        };
        let legal = options.clone();
        let options = if free || curve {
            options
        } else {
            self.lane_options(to, options)
        };
        let (mut m, mut d_out) = options[self.rng.index(options.len())];
        let mut target = need(m, self.lane, &mut self.rng);
        // A long body's forced right turn sweeps through its side's lanes
        // from its own lane instead of the kerb lane's tight corner.
        let wide = self.long && m == Move::Right && !curve && self.l.roundabout != Some(ju);
        if wide {
            target = self.lane;
        }
        let straight_m = |s: &Self, m: Move, k: u32| {
            let (a, _) = s.move_geometry(to, m, s.e(k), k, false);
            s.l.pitch_m - s.at_m - a
        };
        let changes = self.lane.abs_diff(target) as f64;
        if !wide && straight_m(self, m, target) < changes * LANE_CHANGE_M + 2.0 {
            // No room to change lanes: a move from the current lane
            // (straight on where that is legal at all).
            target = self.lane;
            if let Some(&o) = legal.iter().find(|o| o.0 == Move::Straight) {
                (m, d_out) = o;
            }
        }
        // The offset the move is made at: the target lane's centre, or the
        // wide turn's line, reached and left by a shift of `WIDE_SHIFT_M`.
        let e_move = if wide {
            self.wide_right.0
        } else {
            self.e(target)
        };
        let off_lane = (e_move - self.e(target)).abs() > 1e-9;
        let shift_m = if off_lane { WIDE_SHIFT_M } else { 0.0 };
        // The straight, changing lanes in its middle.
        let (a_in, kind) = self.move_geometry(to, m, e_move, target, wide);
        let run = self.l.pitch_m - self.at_m - a_in;
        let steps = self.lane.abs_diff(target) as f64;
        let lead = ((run - steps * LANE_CHANGE_M - shift_m) / 2.0).max(0.0);
        let (p, h) = self.end();
        self.push(Segment::Line {
            from: p,
            heading: h,
            len_m: lead,
        });
        while self.lane != target {
            let next = if target > self.lane {
                self.lane + 1
            } else {
                self.lane - 1
            };
            self.shift(self.e(next) - self.e(self.lane), LANE_CHANGE_M);
            self.lane = next;
        }
        if off_lane {
            self.shift(e_move - self.e(self.lane), shift_m);
        }
        let e = e_move;
        let entry = self.point(to, (self.dir + 2) % 4, -e, a_in);
        let (p, h) = self.end();
        let rest = (entry[0] - p[0]).hypot(entry[1] - p[1]);
        self.push(Segment::Line {
            from: p,
            heading: h,
            len_m: rest,
        });
        // The move.
        let s_entry = self.len_m;
        let h_in = self.dir as f64 * FRAC_PI_2;
        let q = match m {
            Move::Right => 0,
            Move::Straight => 1,
            Move::Left => 2,
        };
        match kind {
            Kind::Ring => {
                let c = [to[0] as f64 * self.l.pitch_m, to[1] as f64 * self.l.pitch_m];
                let (arcs, _) = ring_turn(&self.l, self.lane, ring_fillet_m(&self.l));
                let [fi, mut ring, fo] = arcs;
                if let Segment::Arc { sweep, .. } = &mut ring {
                    *sweep += q as f64 * FRAC_PI_2;
                }
                let fo = fo.moved(q as f64 * FRAC_PI_2, [0.0, 0.0]);
                for a in [fi, ring, fo] {
                    self.push(a.moved(h_in, c));
                }
            }
            Kind::Plain => match m {
                Move::Straight => self.push(Segment::Line {
                    from: entry,
                    heading: h_in,
                    len_m: 2.0 * a_in,
                }),
                Move::Right => self.push(arc_from(entry, h_in, a_in - e, -FRAC_PI_2)),
                Move::Left => self.push(arc_from(entry, h_in, a_in + e, FRAC_PI_2)),
            },
        }
        let s_exit = self.len_m;
        if !curve && !under {
            let hw = self.l.road_w_m / 2.0;
            let (stop, clear) = match kind {
                Kind::Ring => {
                    let edge = arm_start_m(&self.l) + RING_CLEAR_EXTRA_M;
                    (edge, edge)
                }
                Kind::Plain => (hw + STOP_LINE_AT_M, hw + CROSSWALK_CLEAR_M),
            };
            self.crossings.push(Crossing {
                junction: ju,
                turn: m,
                stop_m: s_entry - (stop - a_in),
                clear_m: s_exit + (clear - a_in),
                dir: self.dir,
                roundabout: kind == Kind::Ring,
                lane: self.lane,
                major: self.l.median_through(ju.0, ju.1).then(|| {
                    if self.dir.is_multiple_of(2) {
                        self.l.median_x(ju.1)
                    } else {
                        self.l.median_y(ju.0)
                    }
                }),
            });
        }
        if off_lane {
            self.shift(self.e(self.lane) - e_move, shift_m);
        }
        self.from = to;
        self.dir = d_out;
        self.at_m = a_in + shift_m;
    }

    /// An S-curve of two arcs moving the path `shift` metres to the right
    /// (to the left if negative) over `len` metres of road.
    fn shift(&mut self, shift: f64, len: f64) {
        let theta = 2.0 * (shift.abs() / len).atan();
        let rho = len / (2.0 * theta.sin());
        // Moving right (larger offset) turns clockwise first.
        let sg = -shift.signum();
        let (p, h) = self.end();
        self.push(arc_from(p, h, rho, sg * theta));
        let (p, h) = self.end();
        self.push(arc_from(p, h, rho, -sg * theta));
    }
}

/// How a move is built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Kind {
    /// Straight line or one arc.
    Plain,
    /// Round the roundabout.
    Ring,
}

/// Every directed link of the grid: (start junction, direction index),
/// x-roads first.
pub fn links(l: &Layout) -> Vec<((usize, usize), usize)> {
    let mut out = Vec::new();
    for j in 0..=l.ny {
        for i in 0..l.nx {
            out.push(((i, j), 0));
            out.push(((i + 1, j), 2));
        }
    }
    for i in 0..=l.nx {
        for j in 0..l.ny {
            out.push(((i, j), 1));
            out.push(((i, j + 1), 3));
        }
    }
    out
}
