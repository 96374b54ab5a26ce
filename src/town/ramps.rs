//! Highway slip roads (`ramps = true`): beside every block segment of the two
//! outer x-roads, on their outer side, an off-ramp leaves the outer lane and
//! an on-ramp merges back. Each site is one continuous one-lane strip: a
//! taper (deceleration lane widening by a smoothstep against the highway
//! edge), an S-curve out to a parallel run `GAP_M` from the highway (lateral
//! offset by a quintic smootherstep, curvature continuous, close to a
//! clothoid pair at these angles), and the mirror image back in.
//!
//! Local coordinates of a site: `t` along the road from the site start
//! (world x = a0 + t) and `o` outward from the road centreline, so world
//! y = y_road + side · o. Everything lies flat at z = 0 (markings 8 mm above),
//! built as inline triangle meshes (`kind = "mesh"`: road, road_line,
//! terrain shoulders) that are validated like every scene mesh.

use glam::DVec3;

use crate::scene::desc::{ObjectDesc, TransformDesc};
use crate::scene::mesh::LocalMesh;
use crate::town::stations::stations;

use super::desc::TownDesc;
use super::layout::{Layout, Rect};

/// Length of the taper (deceleration / acceleration lane), metres.
pub const TAPER_M: f64 = 45.0;
/// Length of each S-curve between the taper and the parallel run, metres.
pub const CURVE_M: f64 = 60.0;
/// Lateral distance the ramp moves away from the highway edge, metres.
pub const GAP_M: f64 = 25.0;
/// Distance from a junction's asphalt to the start of a site, metres.
pub const END_MARGIN_M: f64 = 12.0;
/// Shortest parallel run between the two S-curves, metres.
pub const MIN_PARALLEL_M: f64 = 20.0;
/// Gap between the highway edge and the ramp at the gore nose, metres (the
/// painted gore ends there and grass begins).
pub const GORE_NOSE_M: f64 = 2.5;
/// Top of the painted markings above the road, metres.
const PAINT_TOP_M: f64 = 0.008;
/// Longest station step along a site, metres.
const STEP_M: f64 = 2.0;
/// Object names of the generated meshes, with their material and class.
pub const RAMP_MESHES: [(&str, &str, &str); 3] = [
    ("ramps_road", "asphalt", "road"),
    ("ramps_lane_marking", "paint_white_road", "road_line"),
    ("ramps_terrain", "gravel", "terrain"),
];

/// Shortest block that fits a ramp site (taper, curves and parallel run
/// twice plus the junction margins), metres.
pub fn min_ramp_block_m(desc: &TownDesc) -> f64 {
    desc.road_width_m() + 2.0 * (END_MARGIN_M + TAPER_M + CURVE_M) + MIN_PARALLEL_M
}

/// One pair of slip roads beside an outer x-road.
#[derive(Clone, Debug, PartialEq)]
pub struct RampSite {
    /// Centreline y of the x-road, world metres.
    pub y_road_m: f64,
    /// Outward direction: −1 south of the road (y < y_road), +1 north.
    pub side: f64,
    /// Start and end of the site along x, world metres (a0 < a1).
    pub a0: f64,
    /// End of the site along x, world metres.
    pub a1: f64,
    /// Half road width (the highway edge is at o = hw), metres.
    pub hw: f64,
    /// Ramp pavement width, metres.
    pub width_m: f64,
    /// Shoulder width, metres.
    pub shoulder_m: f64,
    /// Distance from each site end to its gore nose, metres.
    pub nose_m: f64,
}

/// The ramp sites of a town (empty unless `ramps = true`): every block
/// segment of x-road 0 (south side) and x-road ny (north side).
pub fn ramp_sites(desc: &TownDesc, l: &Layout) -> Vec<RampSite> {
    if !desc.ramps {
        return Vec::new();
    }
    let hw = l.road_w_m / 2.0;
    let mut out = Vec::new();
    for (j, side) in [(0, -1.0), (l.ny, 1.0)] {
        for i in 0..l.nx {
            let x = i as f64 * l.pitch_m;
            let mut s = RampSite {
                y_road_m: j as f64 * l.pitch_m,
                side,
                a0: x + hw + END_MARGIN_M,
                a1: x + l.pitch_m - hw - END_MARGIN_M,
                hw,
                width_m: l.lane_w_m + 1.0,
                shoulder_m: l.sidewalk_m,
                nose_m: 0.0,
            };
            s.nose_m = s.find_nose();
            out.push(s);
        }
    }
    out
}

/// C¹ smoothstep on [0, 1].
fn smoothstep(x: f64) -> f64 {
    let x = x.clamp(0.0, 1.0);
    x * x * (3.0 - 2.0 * x)
}

/// C² smootherstep on [0, 1] and its derivative.
fn smootherstep(x: f64) -> (f64, f64) {
    let x = x.clamp(0.0, 1.0);
    (
        x * x * x * (x * (6.0 * x - 15.0) + 10.0),
        30.0 * x * x * (x - 1.0) * (x - 1.0),
    )
}

impl RampSite {
    /// Site length along the road, metres.
    pub fn len_m(&self) -> f64 {
        self.a1 - self.a0
    }

    /// World (x, y) of local (t, o).
    pub fn world(&self, [t, o]: [f64; 2]) -> [f64; 2] {
        [self.a0 + t, self.y_road_m + self.side * o]
    }

    /// Ramp centre offset o and do/dt at t, outside the tapers.
    fn centre(&self, t: f64) -> (f64, f64) {
        let (tm, sgn) = if t <= self.len_m() / 2.0 {
            (t, 1.0)
        } else {
            (self.len_m() - t, -1.0)
        };
        let (s, ds) = smootherstep((tm - TAPER_M) / CURVE_M);
        (
            self.hw + self.width_m / 2.0 + GAP_M * s,
            sgn * GAP_M * ds / CURVE_M,
        )
    }

    /// Local (t, o) of a ramp edge at station t, moved `inset` metres
    /// towards the ramp's middle (negative: away from it).
    pub fn edge(&self, t: f64, outer: bool, inset: f64) -> [f64; 2] {
        let tm = t.min(self.len_m() - t);
        if tm < TAPER_M {
            // The taper lies against the straight highway edge o = hw.
            let w = self.width_m * smoothstep(tm / TAPER_M);
            return if outer {
                [t, self.hw + w - inset]
            } else {
                [t, self.hw + inset]
            };
        }
        let (c, dc) = self.centre(t);
        let k = 1.0 / (1.0 + dc * dc).sqrt();
        let n = [-dc * k, k];
        let off = (self.width_m / 2.0 - inset) * if outer { 1.0 } else { -1.0 };
        [t + n[0] * off, c + n[1] * off]
    }

    /// The t in the first S-curve where the inner edge is `GORE_NOSE_M`
    /// from the highway edge (bisection; the gap grows monotonically).
    fn find_nose(&self) -> f64 {
        let (mut lo, mut hi) = (TAPER_M, TAPER_M + CURVE_M);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if self.edge(mid, false, 0.0)[1] - self.hw < GORE_NOSE_M {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }

    /// Stations along the site: every breakpoint, at most `STEP_M` apart.
    fn stations(&self, from: f64, to: f64) -> Vec<f64> {
        let len = self.len_m();
        let marks = [
            0.0,
            TAPER_M,
            self.nose_m,
            TAPER_M + CURVE_M,
            len - TAPER_M - CURVE_M,
            len - self.nose_m,
            len - TAPER_M,
            len,
        ];
        stations(from, to, &marks, STEP_M)
    }

    /// Plan rectangle that holds the whole site with its shoulders plus
    /// 3 m: kept free of furniture, vegetation, buildings and hills (by their
    /// anchors: a roadside tree's crown may overhang the 3 m margin, well
    /// above the ground, never the site itself).
    pub fn clear_zone(&self) -> Rect {
        let o_far = self.hw + self.width_m + GAP_M + self.shoulder_m + 3.0;
        let (y0, y1) = (
            self.y_road_m + self.side * self.hw,
            self.y_road_m + self.side * o_far,
        );
        Rect {
            min: [self.a0 - 3.0, y0.min(y1)],
            max: [self.a1 + 3.0, y0.max(y1)],
        }
    }

    /// Intervals along x where the highway's outer shoulder is replaced by
    /// the taper and gore (from each site end to its gore nose).
    pub fn shoulder_cuts(&self) -> [(f64, f64); 2] {
        [
            (self.a0, self.a0 + self.nose_m),
            (self.a1 - self.nose_m, self.a1),
        ]
    }
}

impl RampSite {
    /// Guard rails along the ramp's outer shoulder, 0.5 m inside its far
    /// edge, from the end of one taper to the start of the other: 4 m
    /// units (`street::barriers::GUARD_RAILS`) on the chords between
    /// stations 4 m apart, the beam towards the ramp.
    pub fn guard_rail_objects(&self) -> Vec<ObjectDesc> {
        let (name, len) = crate::town::street::barriers::GUARD_RAILS[1];
        let inset = -(self.shoulder_m - 0.5);
        let n = ((self.len_m() - 2.0 * TAPER_M) / len).floor() as usize;
        (0..n)
            .map(|k| {
                let t = TAPER_M + k as f64 * len;
                let p = [t, t + len].map(|t| self.world(self.edge(t, true, inset)));
                // The beam faces local −y, the right of the unit's run: run
                // east north of the road, west south of it.
                let (a, b) = if self.side > 0.0 {
                    (p[0], p[1])
                } else {
                    (p[1], p[0])
                };
                let heading = (b[1] - a[1]).atan2(b[0] - a[0]).to_degrees();
                let g = crate::town::parts::class("guard_rail");
                crate::town::parts::instance(name, [a[0], a[1], 0.0], heading, &[], g)
            })
            .collect()
    }
}

/// Triangle soup builder for flat meshes, wound counter-clockwise from above.
struct Flat<'a> {
    site: &'a RampSite,
    z: f64,
    g: LocalMesh,
}

impl Flat<'_> {
    fn vertex(&mut self, p_local: [f64; 2]) -> u32 {
        let [x, y] = self.site.world(p_local);
        self.g.positions.push(DVec3::new(x, y, self.z));
        self.g.positions.len() as u32 - 1
    }
    /// A triangle (dropped when degenerate), turned to face +z.
    fn tri(&mut self, p: [[f64; 2]; 3]) {
        let w = p.map(|q| self.site.world(q));
        let area =
            (w[1][0] - w[0][0]) * (w[2][1] - w[0][1]) - (w[2][0] - w[0][0]) * (w[1][1] - w[0][1]);
        if area.abs() < 1e-9 {
            return;
        }
        let ids = p.map(|q| self.vertex(q));
        self.g.triangles.push(if area > 0.0 {
            ids
        } else {
            [ids[0], ids[2], ids[1]]
        });
    }
    /// The strip between two polylines of equal length.
    fn strip(&mut self, a: &[[f64; 2]], b: &[[f64; 2]]) {
        for k in 1..a.len().min(b.len()) {
            self.tri([a[k - 1], a[k], b[k]]);
            self.tri([a[k - 1], b[k], b[k - 1]]);
        }
    }
}

impl RampSite {
    /// The edge polyline over stations in [from, to].
    fn line(&self, from: f64, to: f64, outer: bool, inset: f64) -> Vec<[f64; 2]> {
        self.stations(from, to)
            .into_iter()
            .map(|t| self.edge(t, outer, inset))
            .collect()
    }

    /// Ramp lane and the gore pavement between it and the highway edge.
    fn road(&self, f: &mut Flat) {
        let len = self.len_m();
        f.strip(
            &self.line(0.0, len, false, 0.0),
            &self.line(0.0, len, true, 0.0),
        );
        for (from, to) in [(TAPER_M, self.nose_m), (len - self.nose_m, len - TAPER_M)] {
            let inner = self.line(from, to, false, 0.0);
            // Projected straight onto the highway edge: shares its line exactly.
            let base: Vec<[f64; 2]> = inner.iter().map(|p| [p[0], self.hw]).collect();
            f.strip(&base, &inner);
        }
    }

    /// Edge lines of the ramp and the hatched gores.
    fn markings(&self, f: &mut Flat) {
        let len = self.len_m();
        let (inset, half) = (0.25, 0.075);
        f.strip(
            &self.line(0.0, len, true, inset - half),
            &self.line(0.0, len, true, inset + half),
        );
        let (t0, t1) = (TAPER_M, len - TAPER_M);
        f.strip(
            &self.line(t0, t1, false, inset - half),
            &self.line(t0, t1, false, inset + half),
        );
        // Gore hatching: 0.45 m stripes every 2.5 m slanting ahead by 1.2 m
        // from the highway edge line to the ramp's inner edge line.
        let mut t = TAPER_M + 1.0;
        while t + 1.65 < self.nose_m {
            for mirror in [false, true] {
                let at = |u: f64| if mirror { len - u } else { u };
                let (ia, ib) = (
                    self.edge(at(t + 1.2), false, 0.15),
                    self.edge(at(t + 1.65), false, 0.15),
                );
                if ia[1] - self.hw < 0.4 {
                    continue;
                }
                let (ha, hb) = ([at(t), self.hw], [at(t + 0.45), self.hw]);
                f.tri([ha, hb, ib]);
                f.tri([ha, ib, ia]);
            }
            t += 2.5;
        }
    }

    /// Gravel shoulders: outside the ramp all along, inside past the noses.
    fn shoulders(&self, f: &mut Flat) {
        let (len, sw) = (self.len_m(), self.shoulder_m);
        f.strip(
            &self.line(0.0, len, true, 0.0),
            &self.line(0.0, len, true, -sw),
        );
        let (t0, t1) = (self.nose_m, len - self.nose_m);
        f.strip(
            &self.line(t0, t1, false, 0.0),
            &self.line(t0, t1, false, -sw),
        );
    }
}

/// The ramp meshes of a town (none without sites): inline mesh objects
/// for road, markings and shoulders, in `RAMP_MESHES` order.
pub fn ramp_meshes(sites: &[RampSite]) -> Vec<ObjectDesc> {
    if sites.is_empty() {
        return Vec::new();
    }
    let mut out = Vec::new();
    for (k, (name, material, class)) in RAMP_MESHES.iter().enumerate() {
        let mut mesh = LocalMesh::default();
        for s in sites {
            let z = if k == 1 { PAINT_TOP_M } else { 0.0 };
            let mut f = Flat {
                site: s,
                z,
                g: LocalMesh::default(),
            };
            match k {
                0 => s.road(&mut f),
                1 => s.markings(&mut f),
                _ => s.shoulders(&mut f),
            }
            let base = mesh.positions.len() as u32;
            mesh.positions.extend(f.g.positions);
            mesh.triangles
                .extend(f.g.triangles.iter().map(|t| t.map(|i| i + base)));
        }
        out.push(ObjectDesc {
            name: Some(name.to_string()),
            material: Some(material.to_string()),
            semantic: Some(class.to_string()),
            instance: None,
            transform: TransformDesc::default(),
            repeat: Vec::new(),
            shape: mesh.into_shape(),
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn site() -> RampSite {
        let mut s = RampSite {
            y_road_m: 0.0,
            side: -1.0,
            a0: 23.25,
            a1: 276.75,
            hw: 11.25,
            width_m: 4.75,
            shoulder_m: 2.0,
            nose_m: 0.0,
        };
        s.nose_m = s.find_nose();
        s
    }

    #[test]
    fn ramp_width_is_constant_past_the_taper_and_meets_the_highway_at_the_ends() {
        let s = site();
        for t in [TAPER_M, 60.0, 80.0, 120.0, 200.0] {
            let (a, b) = (s.edge(t, false, 0.0), s.edge(t, true, 0.0));
            let w = (a[0] - b[0]).hypot(a[1] - b[1]);
            assert!((w - s.width_m).abs() < 1e-9, "t {t}: width {w}");
        }
        for t in [0.0, s.len_m()] {
            assert_eq!(s.edge(t, false, 0.0), [t, s.hw]);
            assert_eq!(s.edge(t, true, 0.0), [t, s.hw]);
        }
        let mid = s.edge(s.len_m() / 2.0, false, 0.0);
        assert!((mid[1] - (s.hw + GAP_M)).abs() < 1e-9);
    }

    #[test]
    fn nose_gap_is_the_gore_width() {
        let s = site();
        let gap = s.edge(s.nose_m, false, 0.0)[1] - s.hw;
        assert!((gap - GORE_NOSE_M).abs() < 1e-6, "{gap}");
        assert!(s.nose_m > TAPER_M && s.nose_m < TAPER_M + CURVE_M);
    }
}
