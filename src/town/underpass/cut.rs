//! The underpass's objects: the sunken y-road's asphalt and lane lines on
//! the profile (world meshes, lines 8 mm above the road), the retaining
//! walls from the road up to grade below its kerbs, a parapet on each
//! sidewalk along the cut, and the deck under the x-road (its underside
//! and end faces) with a parapet on each of its sidewalks' outer edges.
//! Meshes are cut into pieces ≤ `ACROSS_M` across, so that an organic
//! town's warp bends them vertex by vertex like its roads. Stations are ≤ `STEP_M` apart
//! and include the profile's knots, so the meshes' chords leave the
//! profile by < 0.5 mm (exact on the level and constant-grade runs).

use glam::DVec3;

use crate::scene::desc::ObjectDesc;
use crate::scene::mesh::LocalMesh;
use crate::town::layout::Layout;
use crate::town::parts::{class, slab, world_mesh};
use crate::town::stations::stations;

use super::{Underpass, DECK_M, TRANSITION_M};

/// Longest station step along the road, metres.
const STEP_M: f64 = 0.5;
/// Longest side of a piece across the road or the deck, metres.
const ACROSS_M: f64 = 5.0;
/// Height of painted lines above the road, metres.
const PAINT_M: f64 = 0.008;
/// Parapets: thickness and top above grade, metres.
const PARAPET_M: (f64, f64) = (0.2, 1.1);
/// Top of the sidewalks the parapets stand on, metres.
const WALK_TOP_M: f64 = 0.14;
/// Where lane lines stop short of a junction's edge (past its stop line).
const LINES_CLEAR_M: f64 = 4.6;

impl Underpass {
    /// The profile's knots: ends of the level runs and vertical curves.
    fn knots(&self) -> Vec<f64> {
        let (t, l) = (TRANSITION_M, self.fall_m);
        let (a, b) = self.ends;
        vec![a, a + t, a + l - t, a + l, b - l, b - l + t, b - t, b]
    }

    /// Stations from `y0` to `y1`, ≤ `STEP_M` apart, through the knots.
    fn stations(&self, y0: f64, y1: f64) -> Vec<f64> {
        stations(y0, y1, &self.knots(), STEP_M)
    }

    /// A strip on the road between x offsets `u0` < `u1` from the
    /// centreline, `lift` above it, from `y0` to `y1` (cut across into
    /// pieces ≤ `ACROSS_M`, so an organic warp bends it like the roads).
    fn strip(&self, m: &mut LocalMesh, (u0, u1): (f64, f64), lift: f64, (y0, y1): (f64, f64)) {
        let p = |u: f64, y: f64| DVec3::new(self.x_m + u, y, self.profile(y).0 + lift);
        let n = ((u1 - u0) / ACROSS_M).ceil().max(1.0) as usize;
        let us: Vec<f64> = (0..=n)
            .map(|k| u0 + (u1 - u0) * k as f64 / n as f64)
            .collect();
        for w in self.stations(y0, y1).windows(2) {
            let (a, b) = (w[0], w[1]);
            for c in us.windows(2) {
                let (c0, c1) = (c[0], c[1]);
                m.push_quad_facing([p(c0, a), p(c1, a), p(c1, b), p(c0, b)], DVec3::Z);
            }
        }
    }

    /// The deck's faces seen from the cut: its underside `DECK_M` below
    /// grade and its two ends down to it, in pieces ≤ `ACROSS_M` (its top
    /// lies under the x-road's asphalt and sidewalks).
    fn deck_mesh(&self) -> LocalMesh {
        let mut m = LocalMesh::default();
        let (x0, x1) = (self.x_m - self.half_w_m, self.x_m + self.half_w_m);
        let split = |a: f64, b: f64| {
            let n = ((b - a) / ACROSS_M).ceil().max(1.0) as usize;
            (0..=n)
                .map(|k| a + (b - a) * k as f64 / n as f64)
                .collect::<Vec<f64>>()
        };
        let (xs, ys) = (split(x0, x1), split(self.deck.0, self.deck.1));
        let z = -DECK_M;
        for a in xs.windows(2) {
            for b in ys.windows(2) {
                let v = [
                    DVec3::new(a[0], b[0], z),
                    DVec3::new(a[1], b[0], z),
                    DVec3::new(a[1], b[1], z),
                    DVec3::new(a[0], b[1], z),
                ];
                m.push_quad_facing(v, DVec3::NEG_Z);
            }
            for (y, face) in [(self.deck.0, DVec3::NEG_Y), (self.deck.1, DVec3::Y)] {
                let v = [
                    DVec3::new(a[0], y, z),
                    DVec3::new(a[1], y, z),
                    DVec3::new(a[1], y, 0.0),
                    DVec3::new(a[0], y, 0.0),
                ];
                m.push_quad_facing(v, face);
            }
        }
        m
    }

    /// Lane lines as the roads draw them (`roads::lane_lines`): a double
    /// yellow centre line (dashed white on one-lane roads), dashed lane
    /// dividers (3 m every 6 m) and solid edge lines, running on through
    /// the crossing.
    fn lines(&self, l: &Layout) -> (LocalMesh, LocalMesh) {
        let (mut white, mut yellow) = (LocalMesh::default(), LocalMesh::default());
        let (a, b) = (self.edges.0 + LINES_CLEAR_M, self.edges.1 - LINES_CLEAR_M);
        // The edge lines bound the driving lanes (a parking lane lies beyond).
        let hw = l.drive_hw();
        let dashed = |m: &mut LocalMesh, u: f64| {
            let n = ((b - a + 3.0) / 6.0).floor() as u32;
            let start = a + ((b - a) - (n as f64 * 6.0 - 3.0)) / 2.0;
            for k in 0..n {
                let y = start + k as f64 * 6.0;
                self.strip(m, (u - 0.06, u + 0.06), PAINT_M, (y, y + 3.0));
            }
        };
        if l.lanes == 1 {
            dashed(&mut white, 0.0);
        } else {
            for k in 1..l.lanes {
                for sign in [-1.0, 1.0] {
                    dashed(&mut white, sign * k as f64 * l.lane_w_m);
                }
            }
            for u in [-0.12, 0.12] {
                self.strip(&mut yellow, (u - 0.06, u + 0.06), PAINT_M, (a, b));
            }
        }
        for u in [-(hw - 0.25), hw - 0.25] {
            self.strip(&mut white, (u - 0.075, u + 0.075), PAINT_M, (a, b));
        }
        (white, yellow)
    }

    /// The two retaining walls: from the road up to grade at x_m ± the
    /// half width, facing the road.
    fn walls(&self) -> LocalMesh {
        let mut m = LocalMesh::default();
        for sign in [-1.0, 1.0] {
            let x = self.x_m + sign * self.half_w_m;
            let front = DVec3::new(-sign, 0.0, 0.0);
            for w in self.stations(self.ends.0, self.ends.1).windows(2) {
                let (a, b) = (w[0], w[1]);
                let (za, zb) = (self.profile(a).0, self.profile(b).0);
                let v = [
                    DVec3::new(x, a, za),
                    DVec3::new(x, b, zb),
                    DVec3::new(x, b, 0.0),
                    DVec3::new(x, a, 0.0),
                ];
                m.push_quad_facing(v, front);
            }
        }
        m
    }

    /// Parapets on the sidewalks along the cut (behind the kerbs, where
    /// the cut is deeper than half a metre) and on the deck's edges.
    fn parapets(&self) -> Vec<ObjectDesc> {
        let (hw, (t, top)) = (self.half_w_m, PARAPET_M);
        let mut out = Vec::new();
        let runs = [
            (self.ends.0 + TRANSITION_M, self.deck.0),
            (self.deck.1, self.ends.1 - TRANSITION_M),
        ];
        for sign in [-1.0, 1.0] {
            let (u0, u1) = (sign * (hw + 0.25), sign * (hw + 0.25 + t));
            let (x0, x1) = (self.x_m + u0.min(u1), self.x_m + u0.max(u1));
            for (y0, y1) in runs {
                out.push(slab(
                    [x0, y0],
                    [x1, y1],
                    WALK_TOP_M,
                    top,
                    "concrete",
                    class("wall"),
                ));
            }
        }
        let (x0, x1) = (self.x_m - hw - 0.25 - t, self.x_m + hw + 0.25 + t);
        for (y0, y1) in [
            (self.deck.0, self.deck.0 + t),
            (self.deck.1 - t, self.deck.1),
        ] {
            out.push(slab(
                [x0, y0],
                [x1, y1],
                WALK_TOP_M,
                top,
                "concrete",
                class("bridge"),
            ));
        }
        out
    }
}

/// Every object of the town's underpass (none without one): the sunken
/// road, its lines, walls, parapets and the deck, and the walls' joints
/// and the luminaires (`fittings`).
pub fn underpass_objects(l: &Layout) -> Vec<ObjectDesc> {
    let Some(u) = Underpass::of(l) else {
        return Vec::new();
    };
    let hw = u.half_w_m;
    let mut road = LocalMesh::default();
    u.strip(&mut road, (-hw, hw), 0.0, u.edges);
    let (white, yellow) = u.lines(l);
    let mark = class("road_line");
    let mut out = vec![
        world_mesh(road, "asphalt", class("road")),
        world_mesh(white, "paint_white_road", mark),
        world_mesh(u.walls(), "concrete", class("wall")),
    ];
    if !yellow.triangles.is_empty() {
        out.push(world_mesh(yellow, "paint_yellow_road", mark));
    }
    out.extend(u.parapets());
    out.push(world_mesh(u.deck_mesh(), "concrete", class("bridge")));
    out.extend(u.fittings(l.lane_w_m));
    out
}
