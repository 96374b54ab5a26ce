//! The overpass's meshes (world coordinates, inline `kind = "mesh"`): its
//! asphalt on the height profile with the two turning-loop discs, the
//! double yellow centre line and white edge lines 8 mm above it, and the
//! concrete structure: side walls from the ground (over the approaches) or
//! from the deck's underside (over the span) up to the parapets' tops,
//! parapets, the deck's underside, an abutment wall at each deck end and a
//! pier line (two columns under a cap beam) between the highway and its
//! slip road. Stations along the road are ≤ `STEP_M` apart and include the
//! deck ends, so the chord error of the profile stays < 1 mm.

use glam::DVec3;

use crate::scene::desc::{ObjectDesc, TransformDesc};
use crate::scene::mesh::LocalMesh;
use crate::town::stations::stations;

use super::{Overpass, APPROACH_M, DECK_M, DISC_R_M, HALF_WIDTH_M, LANE_M, PARAPET_M, TOP_M};

/// Longest station step along the road, metres.
const STEP_M: f64 = 2.0;
/// Top of the painted markings above the road, metres.
const PAINT_M: f64 = 0.008;
/// The ground's height (the flat ground quad lies 2 cm below the roads).
const GROUND_Z: f64 = -0.02;

impl Overpass {
    /// The profile's knots: approach feet and deck ends.
    fn knots(&self) -> [f64; 4] {
        let (d0, d1) = self.deck;
        [d0 - APPROACH_M, d0, d1, d1 + APPROACH_M]
    }

    /// A strip on the road surface between offsets `u0` < `u1` from the
    /// centreline, `lift` above it, from `y0` to `y1`.
    fn strip(&self, m: &mut LocalMesh, (u0, u1): (f64, f64), lift: f64, (y0, y1): (f64, f64)) {
        let ys = stations(y0, y1, &self.knots(), STEP_M);
        let p = |u: f64, y: f64| DVec3::new(self.x_m + u, y, self.profile(y).0 + lift);
        for w in ys.windows(2) {
            let (a, b) = (w[0], w[1]);
            m.push_quad_facing([p(u0, a), p(u1, a), p(u1, b), p(u0, b)], DVec3::Z);
        }
    }

    fn road(&self) -> LocalMesh {
        let mut m = LocalMesh::default();
        let [s, n] = self.loop_centres();
        self.strip(&mut m, (-HALF_WIDTH_M, HALF_WIDTH_M), 0.0, (s[1], n[1]));
        for c in [s, n] {
            let segs = 48;
            let base = m.positions.len() as u32;
            m.positions.push(DVec3::new(c[0], c[1], 0.0));
            for k in 0..segs {
                let t = std::f64::consts::TAU * k as f64 / segs as f64;
                let r = DISC_R_M;
                m.positions
                    .push(DVec3::new(c[0] + r * t.cos(), c[1] + r * t.sin(), 0.0));
            }
            for k in 0..segs {
                let (a, b) = (base + 1 + k, base + 1 + (k + 1) % segs);
                m.triangles.push([base, a, b]);
            }
        }
        m
    }

    fn markings(&self) -> (LocalMesh, LocalMesh) {
        let (mut yellow, mut white) = (LocalMesh::default(), LocalMesh::default());
        let span = self.ends;
        for sign in [-1.0f64, 1.0] {
            let (u0, u1) = (sign * 0.06, sign * 0.18);
            self.strip(&mut yellow, (u0.min(u1), u0.max(u1)), PAINT_M, span);
            let (e0, e1) = (sign * LANE_M, sign * (LANE_M + 0.15));
            self.strip(&mut white, (e0.min(e1), e0.max(e1)), PAINT_M, span);
        }
        (yellow, white)
    }

    /// The concrete structure: side walls and parapets, the deck's
    /// underside and abutments, the pier line.
    fn structure(&self) -> LocalMesh {
        let mut m = LocalMesh::default();
        for sx in [-1.0, 1.0] {
            self.side(&mut m, sx);
        }
        self.underside_and_abutments(&mut m);
        self.pier(&mut m);
        m
    }

    /// One side (`sx` = ±1 across x) over the whole profile: the outer wall
    /// from the ground (or, over the span, the deck's underside) up to the
    /// parapet's top, then the parapet's inner face and top, station by
    /// station.
    fn side(&self, m: &mut LocalMesh, sx: f64) {
        let (d0, d1) = self.deck;
        let under = TOP_M - DECK_M;
        let (pw, ph) = PARAPET_M;
        let out = HALF_WIDTH_M + pw;
        let x = self.x_m;
        let ys = stations(d0 - APPROACH_M, d1 + APPROACH_M, &self.knots(), STEP_M);
        let on_span = |y: f64| y >= d0 && y <= d1;
        let side = DVec3::new(sx, 0.0, 0.0);
        for w in ys.windows(2) {
            let (a, b) = (w[0], w[1]);
            let (za, zb) = (self.profile(a).0, self.profile(b).0);
            // Stations include the deck ends: a piece is on the span or off it.
            let bottom = if on_span(a) && on_span(b) {
                under
            } else {
                GROUND_Z
            };
            let (ba, bb) = (bottom, bottom);
            // Outer wall up to the parapet's top.
            let p = |u: f64, y: f64, z: f64| DVec3::new(x + sx * u, y, z);
            m.push_quad_facing(
                [
                    p(out, a, ba),
                    p(out, b, bb),
                    p(out, b, zb + ph),
                    p(out, a, za + ph),
                ],
                side,
            );
            // Parapet: inner face and top.
            m.push_quad_facing(
                [
                    p(HALF_WIDTH_M, a, za),
                    p(HALF_WIDTH_M, b, zb),
                    p(HALF_WIDTH_M, b, zb + ph),
                    p(HALF_WIDTH_M, a, za + ph),
                ],
                -side,
            );
            m.push_quad_facing(
                [
                    p(HALF_WIDTH_M, a, za + ph),
                    p(out, a, za + ph),
                    p(out, b, zb + ph),
                    p(HALF_WIDTH_M, b, zb + ph),
                ],
                DVec3::Z,
            );
        }
    }

    /// The deck's underside and the abutment walls facing the span.
    fn underside_and_abutments(&self, m: &mut LocalMesh) {
        let (d0, d1) = self.deck;
        let under = TOP_M - DECK_M;
        let out = HALF_WIDTH_M + PARAPET_M.0;
        let c = |u: f64, y: f64, z: f64| DVec3::new(self.x_m + u, y, z);
        m.push_quad_facing(
            [
                c(-out, d0, under),
                c(out, d0, under),
                c(out, d1, under),
                c(-out, d1, under),
            ],
            DVec3::NEG_Z,
        );
        for (y, facing) in [(d0, DVec3::Y), (d1, DVec3::NEG_Y)] {
            m.push_quad_facing(
                [
                    c(-out, y, GROUND_Z),
                    c(out, y, GROUND_Z),
                    c(out, y, under),
                    c(-out, y, under),
                ],
                facing,
            );
        }
    }

    /// The pier line: two columns under a cap beam.
    fn pier(&self, m: &mut LocalMesh) {
        let under = TOP_M - DECK_M;
        let (x, yp) = (self.x_m, self.pier_y_m);
        for u in [-2.5, 2.5] {
            boxed(
                m,
                [x + u - 0.6, yp - 0.6, GROUND_Z],
                [x + u + 0.6, yp + 0.6, under - 0.8],
            );
        }
        boxed(
            m,
            [x - HALF_WIDTH_M, yp - 0.7, under - 0.8],
            [x + HALF_WIDTH_M, yp + 0.7, under],
        );
    }
}

/// Appends an axis-aligned box (all six faces facing out).
fn boxed(m: &mut LocalMesh, lo: [f64; 3], hi: [f64; 3]) {
    let v = |i: usize, j: usize, k: usize| {
        DVec3::new([lo[0], hi[0]][i], [lo[1], hi[1]][j], [lo[2], hi[2]][k])
    };
    for axis in 0..3 {
        for side in 0..2 {
            let mut f = [DVec3::ZERO; 4];
            for (n, (a, b)) in [(0, 0), (1, 0), (1, 1), (0, 1)].into_iter().enumerate() {
                f[n] = match axis {
                    0 => v(side, a, b),
                    1 => v(a, side, b),
                    _ => v(a, b, side),
                };
            }
            let mut front = DVec3::ZERO;
            front[axis] = if side == 1 { 1.0 } else { -1.0 };
            m.push_quad_facing(f, front);
        }
    }
}

/// The overpass's meshes as scene objects: road, markings, structure.
pub fn overpass_meshes(o: &Overpass) -> Vec<ObjectDesc> {
    let mesh = |name: &str, mat: &str, class: &str, m: LocalMesh| ObjectDesc {
        name: Some(name.to_string()),
        material: Some(mat.to_string()),
        semantic: Some(class.to_string()),
        instance: None,
        transform: TransformDesc::default(),
        repeat: Vec::new(),
        shape: m.into_shape(),
    };
    let (yellow, white) = o.markings();
    vec![
        mesh("overpass_road", "asphalt", "road", o.road()),
        mesh(
            "overpass_centre_line",
            "paint_yellow_road",
            "road_line",
            yellow,
        ),
        mesh(
            "overpass_edge_lines",
            "paint_white_road",
            "road_line",
            white,
        ),
        mesh("overpass_structure", "concrete", "bridge", o.structure()),
    ]
}
