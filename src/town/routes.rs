//! Closed vehicle routes over the road grid: every lane of every road is
//! part of exactly one route, a rounded rectangle on the lane centreline.
//! Block loops circle one block clockwise on the lanes beside it (right
//! turns at every corner); the ring circles the whole town
//! counter-clockwise on the outer lanes of the outer roads (left turns at
//! the town corners, straight through the T junctions).
//!
//! Lane k of a road (counted from the centreline) is the band [k·w, (k+1)·w]
//! beside it, w = lane width. At a corner a route turns inside its own
//! L-shaped corridor (its lane band on both roads), so routes never share
//! road surface: a corner is an arc of radius w/2 + δ about a point δ
//! beyond the corridor's inner corner, and a body fits the turn when its
//! footprint stays inside the corridor for the whole arc (`fits_turn`,
//! checked numerically; the ladder-around-a-corner bound is 2√2·w − 2·width).

use std::f64::consts::{FRAC_PI_2, PI};

use super::layout::Layout;
use super::vehicles::{BodyKind, BODIES};

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
}

/// One closed route: a rounded rectangle on a lane centreline.
#[derive(Clone, Debug, PartialEq)]
pub struct Route {
    /// Which loop.
    pub kind: RouteKind,
    /// Lane number from the centreline, 0-based.
    pub lane: u32,
    /// Lower-left corner of the lane-centre rectangle, world metres.
    pub min: [f64; 2],
    /// Upper-right corner of the lane-centre rectangle, world metres.
    pub max: [f64; 2],
    /// Corner arc radius, metres.
    pub radius_m: f64,
    /// Clockwise (block loops) or counter-clockwise (the ring).
    pub clockwise: bool,
}

impl Route {
    fn straights(&self) -> [f64; 2] {
        let r2 = 2.0 * self.radius_m;
        [
            self.max[0] - self.min[0] - r2,
            self.max[1] - self.min[1] - r2,
        ]
    }

    /// Length of one straight side along x and along y, metres.
    pub fn side_m(&self) -> [f64; 2] {
        self.straights()
    }

    /// Perimeter, metres.
    pub fn length_m(&self) -> f64 {
        let [lx, ly] = self.straights();
        2.0 * (lx + ly) + 2.0 * PI * self.radius_m
    }

    /// Position (x, y) and heading (radians, counter-clockwise from +x) at
    /// arc length `s` (wrapped). s = 0 is the start of the south side; each
    /// side is a straight followed by its corner arc.
    pub fn pose(&self, s: f64) -> ([f64; 2], f64) {
        let [x0, y0] = self.min;
        let [x1, y1] = self.max;
        let r = self.radius_m;
        let [lx, ly] = self.straights();
        let mut rem = s.rem_euclid(self.length_m());
        // The counter-clockwise parametrisation; clockwise mirrors it in x.
        let sides = [lx, ly, lx, ly];
        let starts = [[x0 + r, y0], [x1, y0 + r], [x1 - r, y1], [x0, y1 - r]];
        let centres = [
            [x1 - r, y0 + r],
            [x1 - r, y1 - r],
            [x0 + r, y1 - r],
            [x0 + r, y0 + r],
        ];
        let mut out = (starts[0], 0.0);
        for q in 0..4 {
            let h = q as f64 * FRAC_PI_2;
            if rem < sides[q] {
                let p = starts[q];
                out = ([p[0] + rem * h.cos(), p[1] + rem * h.sin()], h);
                break;
            }
            rem -= sides[q];
            let arc = FRAC_PI_2 * r;
            if rem < arc || q == 3 {
                let a = rem.min(arc) / r;
                let phi = h - FRAC_PI_2 + a;
                let c = centres[q];
                out = ([c[0] + r * phi.cos(), c[1] + r * phi.sin()], h + a);
                break;
            }
            rem -= arc;
        }
        if self.clockwise {
            let (p, h) = out;
            out = ([x0 + x1 - p[0], p[1]], PI - h);
        }
        (out.0, out.1.rem_euclid(2.0 * PI))
    }
}

/// Corner geometry shared by every route of a town.
#[derive(Clone, Debug, PartialEq)]
pub struct Turns {
    /// Offset δ of the arc centre beyond the corridor's inner corner, metres.
    pub delta_m: f64,
    /// Arc radius w/2 + δ, metres.
    pub radius_m: f64,
    /// The body types whose footprint fits the turn.
    pub bodies: Vec<BodyKind>,
}

/// Clearance kept from the corridor's walls and inner corner, metres.
const TURN_MARGIN_M: f64 = 0.05;

/// Whether a `footprint` (length, width) driven through the canonical
/// corner stays inside its corridor: walls u ≥ 0 and v ≥ 0, inner corner
/// (w, w) with the quadrant beyond it forbidden; arriving along v = w/2
/// heading −u, leaving along u = w/2 heading +v.
pub fn fits_turn(footprint: [f64; 2], lane_w: f64, delta: f64) -> bool {
    let [len, wid] = footprint;
    let (m, w) = (TURN_MARGIN_M, lane_w);
    let r = w / 2.0 + delta;
    let c = w + delta;
    let steps = 48;
    // Poses: a body length of straight before and after the arc, and the arc.
    let mut poses = Vec::new();
    for k in 0..=steps {
        let t = k as f64 / steps as f64;
        poses.push(([c + len * (1.0 - t), w / 2.0], PI));
        poses.push(([w / 2.0, c + len * t], FRAC_PI_2));
        let phi = -FRAC_PI_2 - t * FRAC_PI_2;
        poses.push(([c + r * phi.cos(), c + r * phi.sin()], PI - t * FRAC_PI_2));
    }
    poses.iter().all(|&(p, h)| {
        let (f, s) = ([h.cos(), h.sin()], [-h.sin(), h.cos()]);
        // The inner corner must not lie inside the body.
        let d = [w - p[0], w - p[1]];
        let (a, b) = (d[0] * f[0] + d[1] * f[1], d[0] * s[0] + d[1] * s[1]);
        if a.abs() < len / 2.0 + m && b.abs() < wid / 2.0 + m {
            return false;
        }
        let n = 40;
        (0..4 * n).all(|q| {
            // Perimeter points, corner to corner.
            let (edge, t) = (q / n, (q % n) as f64 / n as f64);
            let (x, y) = match edge {
                0 => (-0.5 + t, -0.5),
                1 => (0.5, -0.5 + t),
                2 => (0.5 - t, 0.5),
                _ => (-0.5, 0.5 - t),
            };
            let (x, y) = (x * len, y * wid);
            let u = p[0] + x * f[0] + y * s[0];
            let v = p[1] + x * f[1] + y * s[1];
            u >= m && v >= m && !(u > w - m && v > w - m)
        })
    })
}

impl Turns {
    /// The δ (on a 10 cm grid, up to 1.3·w) that lets the most body types
    /// turn, preferring the larger δ (gentler arcs) on ties.
    /// Cached per lane width (the search takes tens of milliseconds).
    pub fn new(lane_w: f64) -> Self {
        use std::collections::BTreeMap;
        use std::sync::{Mutex, OnceLock};
        static CACHE: OnceLock<Mutex<BTreeMap<u64, Turns>>> = OnceLock::new();
        let cache = CACHE.get_or_init(|| Mutex::new(BTreeMap::new()));
        if let Some(t) = cache.lock().expect("turn cache").get(&lane_w.to_bits()) {
            return t.clone();
        }
        let t = Self::search(lane_w);
        cache
            .lock()
            .expect("turn cache")
            .insert(lane_w.to_bits(), t.clone());
        t
    }

    fn search(lane_w: f64) -> Self {
        let mut best = (0usize, 0.0, Vec::new());
        for k in 0..=(13.0 * lane_w) as usize {
            let delta = k as f64 * 0.1;
            let fit: Vec<BodyKind> = BODIES
                .iter()
                .copied()
                .filter(|b| fits_turn(b.footprint_m(), lane_w, delta))
                .collect();
            if fit.len() >= best.0 {
                best = (fit.len(), delta, fit);
            }
        }
        Turns {
            delta_m: best.1,
            radius_m: lane_w / 2.0 + best.1,
            bodies: best.2,
        }
    }
}

/// Every route of the town: block loops (by row, column, lane; none
/// around the four blocks with a corner at a roundabout), then the ring
/// lanes from the centreline out.
pub fn routes(l: &Layout, turns: &Turns) -> Vec<Route> {
    let mut out = Vec::new();
    let r = turns.radius_m;
    for j in 0..l.ny {
        for i in 0..l.nx {
            if l.block_touches_roundabout(i, j) {
                continue; // static roundabout: no route enters it
            }
            for k in 0..l.lanes {
                let e = (k as f64 + 0.5) * l.lane_w_m;
                let (x0, y0) = (i as f64 * l.pitch_m, j as f64 * l.pitch_m);
                out.push(Route {
                    kind: RouteKind::Block { i, j },
                    lane: k,
                    min: [x0 + e, y0 + e],
                    max: [x0 + l.pitch_m - e, y0 + l.pitch_m - e],
                    radius_m: r,
                    clockwise: true,
                });
            }
        }
    }
    for k in 0..l.lanes {
        let e = (k as f64 + 0.5) * l.lane_w_m;
        out.push(Route {
            kind: RouteKind::Ring,
            lane: k,
            min: [-e, -e],
            max: [l.len_x() + e, l.len_y() + e],
            radius_m: r,
            clockwise: false,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square() -> Route {
        Route {
            kind: RouteKind::Ring,
            lane: 0,
            min: [0.0, 0.0],
            max: [10.0, 10.0],
            radius_m: 2.0,
            clockwise: false,
        }
    }

    #[test]
    fn rounded_rectangle_is_continuous_and_turns_a_full_circle() {
        for clockwise in [false, true] {
            let route = Route {
                clockwise,
                ..square()
            };
            let len = route.length_m();
            assert!((len - (4.0 * 6.0 + 4.0 * PI)).abs() < 1e-12);
            let n = 4000;
            let mut turned = 0.0;
            let (mut prev_p, mut prev_h) = route.pose(0.0);
            for k in 1..=n {
                let (p, h) = route.pose(len * k as f64 / n as f64);
                let step = ((p[0] - prev_p[0]).powi(2) + (p[1] - prev_p[1]).powi(2)).sqrt();
                assert!(step <= len / n as f64 + 1e-9, "jump of {step} m at {k}");
                let mut dh = h - prev_h;
                dh -= (dh / (2.0 * PI)).round() * 2.0 * PI;
                turned += dh;
                (prev_p, prev_h) = (p, h);
            }
            let want = if clockwise { -2.0 * PI } else { 2.0 * PI };
            assert!((turned - want).abs() < 1e-9, "turned {turned}");
        }
        // s = 0: start of the south side, heading +x (counter-clockwise).
        assert_eq!(square().pose(0.0), ([2.0, 0.0], 0.0));
    }

    #[test]
    fn cars_fit_a_3_5_m_lane_corner_and_a_bus_does_not() {
        let t = Turns::new(3.5);
        assert!(t.bodies.contains(&BodyKind::Sedan), "{t:?}");
        assert!(!t.bodies.contains(&BodyKind::Bus));
        // The ladder bound: a 1 m-wide body longer than 2√2·3.5 − 2 never fits.
        assert!(!fits_turn(
            [2.0 * 2f64.sqrt() * 3.5 - 2.0 + 0.01, 1.0],
            3.5,
            1.0
        ));
        assert!(fits_turn([3.0, 1.0], 3.5, 1.0));
    }
}
