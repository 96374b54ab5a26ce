//! Corner arcs and the bodies that fit them. A route turns 90° inside an
//! L-shaped corridor of width W (one lane band, or several merged ones):
//! outer walls u ≥ 0 and v ≥ 0, inner corner (W, W) with the quadrant
//! beyond it forbidden. The route arrives along v = e heading −u and leaves
//! along u = e heading +v (e: its lane centre's distance from the outer
//! wall) on an arc about (W + δ, W + δ), radius W + δ − e.
//!
//! A body fits when its footprint stays inside the corridor over the whole
//! turn (checked numerically on the outline); the ladder-around-a-corner
//! bound is length ≤ 2√2·W − 2·width, so a 11.6 m bus needs W ≈ 6 m: two
//! lanes, never one.

use std::f64::consts::{FRAC_PI_2, PI};

use super::super::vehicles::{BodyKind, BODIES};

/// Clearance kept from the corridor's walls and inner corner, metres.
const TURN_MARGIN_M: f64 = 0.05;

/// Whether a `footprint` (length, width) driven through the canonical
/// corner of a one-lane corridor (W = `lane_w`, e = W/2) stays inside it.
pub fn fits_turn(footprint: [f64; 2], lane_w: f64, delta: f64) -> bool {
    fits_corridor(footprint, lane_w, lane_w / 2.0, delta)
}

/// Whether a `footprint` (length, width) driven through the canonical
/// corner of a corridor of width `corridor_w`, on the lane whose centre is
/// `offset_m` from the outer walls, with arc-centre offset `delta`, stays
/// inside the corridor (to `TURN_MARGIN_M`).
pub fn fits_corridor(footprint: [f64; 2], corridor_w: f64, offset_m: f64, delta: f64) -> bool {
    let [len, wid] = footprint;
    let (m, w, e) = (TURN_MARGIN_M, corridor_w, offset_m);
    let c = w + delta;
    let r = c - e;
    let steps = 48;
    // Poses: a body length of straight before and after the arc, and the arc.
    let mut poses = Vec::new();
    for k in 0..=steps {
        let t = k as f64 / steps as f64;
        poses.push(([c + len * (1.0 - t), e], PI));
        poses.push(([e, c + len * t], FRAC_PI_2));
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

/// Corner geometry of a family of routes.
#[derive(Clone, Debug, PartialEq)]
pub struct Turns {
    /// Offset δ of the arc centre beyond the corridor's inner corner, metres.
    pub delta_m: f64,
    /// Arc radius W + δ − e, metres.
    pub radius_m: f64,
    /// Distance e of the route from the corridor's outer wall, metres.
    pub offset_m: f64,
    /// The body types whose footprint fits the turn.
    pub bodies: Vec<BodyKind>,
}

impl Turns {
    /// Turns inside one lane band of width `lane_w` (cars only).
    pub fn new(lane_w: f64) -> Self {
        Self::cached(lane_w, 1)
    }

    /// Turns of a route beside the outer wall of `lanes` merged lane bands:
    /// it rides the outer lane's centre (e = w/2) when every body fits
    /// there, else the least offset (on a 10 cm grid, up to W/2) where the
    /// most bodies fit (two 3.5 m lanes: e = 2.75 m, a metre left of the
    /// outer lane's centre, as buses keep off the kerb).
    pub fn merged(lane_w: f64, lanes: u32) -> Self {
        Self::cached(lane_w, lanes.max(1))
    }

    /// The δ (on a 10 cm grid, up to 1.3·W) that lets the most body types
    /// turn, preferring the larger δ (gentler arcs) on ties. Cached per
    /// (lane width, lanes): the search takes tens of milliseconds.
    fn cached(lane_w: f64, lanes: u32) -> Self {
        use std::collections::BTreeMap;
        use std::sync::{Mutex, OnceLock};
        static CACHE: OnceLock<Mutex<BTreeMap<(u64, u32), Turns>>> = OnceLock::new();
        let key = (lane_w.to_bits(), lanes);
        let cache = CACHE.get_or_init(|| Mutex::new(BTreeMap::new()));
        if let Some(t) = cache.lock().expect("turn cache").get(&key) {
            return t.clone();
        }
        let corridor_w = lane_w * lanes as f64;
        let mut t = Self::search(corridor_w, lane_w / 2.0);
        if lanes > 1 {
            for k in 1..=((corridor_w - lane_w) / 2.0 / 0.1) as usize {
                let u = Self::search(corridor_w, lane_w / 2.0 + k as f64 * 0.1);
                if u.bodies.len() > t.bodies.len() {
                    t = u;
                }
                if t.bodies.len() == BODIES.len() {
                    break;
                }
            }
        }
        cache.lock().expect("turn cache").insert(key, t.clone());
        t
    }

    fn search(corridor_w: f64, offset_m: f64) -> Self {
        let mut best = (0usize, 0.0, Vec::new());
        for k in 0..=(13.0 * corridor_w) as usize {
            let delta = k as f64 * 0.1;
            let fit: Vec<BodyKind> = BODIES
                .iter()
                .copied()
                .filter(|b| fits_corridor(b.footprint_m(), corridor_w, offset_m, delta))
                .collect();
            if fit.len() >= best.0 {
                best = (fit.len(), delta, fit);
            }
        }
        Turns {
            delta_m: best.1,
            radius_m: corridor_w + best.1 - offset_m,
            offset_m,
            bodies: best.2,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cars_fit_a_3_5_m_lane_corner_and_a_bus_does_not() {
        let t = Turns::new(3.5);
        assert!(t.bodies.contains(&BodyKind::Sedan), "{t:?}");
        assert!(!t.bodies.contains(&BodyKind::Bus));
        assert!((t.radius_m - (1.75 + t.delta_m)).abs() < 1e-12);
        // The ladder bound: a 1 m-wide body longer than 2√2·3.5 − 2 never fits.
        assert!(!fits_turn(
            [2.0 * 2f64.sqrt() * 3.5 - 2.0 + 0.01, 1.0],
            3.5,
            1.0
        ));
        assert!(fits_turn([3.0, 1.0], 3.5, 1.0));
    }

    #[test]
    fn every_body_fits_the_outer_lane_of_two_merged_lanes() {
        for w in [3.5, 3.75] {
            let t = Turns::merged(w, 2);
            assert_eq!(t.bodies, BODIES.to_vec(), "lane {w} m: {t:?}");
            // Centre (W + δ, W + δ), the route e from the outer wall.
            assert!((t.radius_m - (2.0 * w + t.delta_m - t.offset_m)).abs() < 1e-12);
            // Within the two lanes, a bus's half-width from either wall.
            let half = BodyKind::Bus.footprint_m()[1] / 2.0;
            assert!(t.offset_m >= half && t.offset_m <= 2.0 * w - half, "{t:?}");
            // Nothing fits nearer the kerb than the chosen offset.
            let nearer = t.offset_m - 0.1;
            assert!((0..=(26.0 * w) as usize).all(|k| !fits_corridor(
                BodyKind::Bus.footprint_m(),
                2.0 * w,
                nearer,
                k as f64 * 0.1
            )));
        }
        // The ladder bound holds for merged corridors too.
        assert!(!fits_corridor(
            [2.0 * 2f64.sqrt() * 7.0 - 2.0 + 0.01, 1.0],
            7.0,
            1.75,
            1.0
        ));
    }
}
