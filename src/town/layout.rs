//! The grid layout of a town: road centrelines, widths, blocks, and the road
//! surface rectangles (used by tests to check that the ego stays on the road).
//!
//! x-roads (east–west) lie at y = j·P for j = 0..=ny and run past the town
//! edge by `stub_m` on both ends; y-roads (north–south) lie at x = i·P for
//! i = 0..=nx and end at the outer x-roads (T junctions there). P = block pitch.
//! With a loop corner radius R > 0 the four outer corners are quarter
//! circles of radius R (on the centreline) about points R in from both outer
//! centrelines; the outer roads then end at the arcs' tangent points (no
//! stubs on the outer x-roads) and the corner blocks' lots keep clear.
//! In a `highway` town the outer roads are divided: a median barrier runs
//! on their centrelines (`median_x`, `median_y`), through the T junctions
//! where town streets meet them (right in, right out: `median_through`).

use std::f64::consts::FRAC_PI_4;

use super::desc::{RoadStyle, TownDesc};

/// Length of the road stubs past the east and west town edges, metres.
pub const STUB_M: f64 = 40.0;
/// How far the terrain (and a river) reaches past the town, metres.
pub const GROUND_MARGIN_M: f64 = 400.0;

/// An axis-aligned rectangle in the ground plane, world metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// Minimum corner (x, y).
    pub min: [f64; 2],
    /// Maximum corner (x, y).
    pub max: [f64; 2],
}

impl Rect {
    /// The rectangle centred at `c` with side lengths `size`.
    pub fn centered(c: [f64; 2], size: [f64; 2]) -> Self {
        Rect {
            min: [c[0] - size[0] / 2.0, c[1] - size[1] / 2.0],
            max: [c[0] + size[0] / 2.0, c[1] + size[1] / 2.0],
        }
    }
    /// Centre (x, y).
    pub fn center(&self) -> [f64; 2] {
        [
            (self.min[0] + self.max[0]) / 2.0,
            (self.min[1] + self.max[1]) / 2.0,
        ]
    }
    /// Side lengths.
    pub fn size(&self) -> [f64; 2] {
        [self.max[0] - self.min[0], self.max[1] - self.min[1]]
    }
    /// Whether the interiors overlap (touching edges do not count).
    pub fn overlaps(&self, o: &Rect) -> bool {
        self.min[0] < o.max[0]
            && o.min[0] < self.max[0]
            && self.min[1] < o.max[1]
            && o.min[1] < self.max[1]
    }
    /// Whether `o` lies inside this rectangle (within `eps`).
    pub fn contains(&self, o: &Rect, eps: f64) -> bool {
        o.min[0] >= self.min[0] - eps
            && o.min[1] >= self.min[1] - eps
            && o.max[0] <= self.max[0] + eps
            && o.max[1] <= self.max[1] + eps
    }
}

/// Derived grid dimensions of a town.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// Blocks along x.
    pub nx: usize,
    /// Blocks along y.
    pub ny: usize,
    /// Centreline pitch P, metres.
    pub pitch_m: f64,
    /// Road width kerb to kerb, metres (parking lanes included).
    pub road_w_m: f64,
    /// Width of the parking lane on each side, metres (0: none).
    pub parking_m: f64,
    /// Lane width, metres.
    pub lane_w_m: f64,
    /// Lanes per direction.
    pub lanes: u32,
    /// Sidewalk (or shoulder) width, metres.
    pub sidewalk_m: f64,
    /// Raised sidewalks with curbs (false: flat shoulders).
    pub sidewalks: bool,
    /// The block row replaced by a river, if any.
    pub river_row: Option<usize>,
    /// The cross junction (i, j) replaced by a roundabout, if any.
    pub roundabout: Option<(usize, usize)>,
    /// The junction (i, j) where the y-road i passes under the x-road j
    /// (`underpass`), if the town has one.
    pub underpass: Option<(usize, usize)>,
    /// Radius of the loop's curved outer corners on the centreline, metres
    /// (0: square corners with junctions).
    pub loop_radius_m: f64,
    /// Whether the outer roads (the loop) are divided by a median barrier
    /// (`road_style = "highway"`).
    pub median: bool,
}

/// One curved outer corner of the loop: a quarter circle on the road
/// centreline about `centre`, replacing the junction at grid corner `ij`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LoopCorner {
    /// Grid junction (i, j) the arc replaces.
    pub ij: (usize, usize),
    /// The junction's position, world (x, y), metres.
    pub corner: [f64; 2],
    /// Arc centre, world (x, y), metres: R in from the corner along x and y.
    pub centre: [f64; 2],
    /// Direction signs (±1, ±1) from the corner towards the centre.
    pub inward: [f64; 2],
    /// Polar angles about the centre of the arc's ends, radians, θ0 < θ1 =
    /// θ0 + π/2 (counter-clockwise).
    pub theta: (f64, f64),
}

impl Layout {
    /// The layout of a (validated) town description.
    pub fn new(desc: &TownDesc) -> Self {
        let p = desc.block_size_m;
        Layout {
            nx: ((desc.extent_m[0] / p).round() as usize).max(1),
            ny: ((desc.extent_m[1] / p).round() as usize).max(1),
            pitch_m: p,
            road_w_m: desc.road_width_m(),
            parking_m: desc.parking_lane_m,
            lane_w_m: desc.lane_width_m,
            lanes: desc.lanes_per_direction,
            sidewalk_m: desc.sidewalk_width_m,
            sidewalks: desc.sidewalks,
            river_row: None,
            roundabout: None,
            underpass: None,
            loop_radius_m: desc.loop_corner_radius_m,
            median: desc.road_style == RoadStyle::Highway,
        }
        .with_river(desc.river)
        .with_roundabout(desc.roundabout)
        .with_underpass(desc.underpass)
    }
    fn with_river(mut self, river: bool) -> Self {
        self.river_row = river.then_some(self.ny / 2);
        self
    }
    fn with_underpass(mut self, on: bool) -> Self {
        self.underpass = on.then(|| super::underpass::site(self.nx, self.ny));
        self
    }
    fn with_roundabout(mut self, on: bool) -> Self {
        self.roundabout = on.then_some((self.nx / 2, self.ny / 2));
        self
    }
    /// Distance from the centreline to the outer driving lane's edge, metres:
    /// the road edge less the parking lane.
    pub fn drive_hw(&self) -> f64 {
        self.road_w_m / 2.0 - self.parking_m
    }
    /// Centre of the roundabout, world (x, y), if the town has one.
    pub fn roundabout_center(&self) -> Option<[f64; 2]> {
        let (i, j) = self.roundabout?;
        Some([i as f64 * self.pitch_m, j as f64 * self.pitch_m])
    }
    /// Radii of the roundabout: (central island, ring road's outer kerb),
    /// metres. The ring has one lane per approach lane, 1 m wider each.
    pub fn roundabout_radii(&self) -> (f64, f64) {
        let r_in = 10.0;
        (r_in, r_in + self.lanes as f64 * (self.lane_w_m + 1.0))
    }
    /// Radius around the roundabout centre kept free of buildings, lots,
    /// furniture, pedestrians and routes: ring, sidewalk and 1 m, metres.
    pub fn roundabout_clear_m(&self) -> f64 {
        self.roundabout_radii().1 + self.sidewalk_m + 1.0
    }
    /// Whether block (i, j) has a corner at the roundabout.
    pub fn block_touches_roundabout(&self, i: usize, j: usize) -> bool {
        self.roundabout
            .is_some_and(|(ri, rj)| (i == ri || i + 1 == ri) && (j == rj || j + 1 == rj))
    }
    /// Whether a rectangle reaches into the roundabout's clear disc.
    pub fn near_roundabout(&self, r: &Rect) -> bool {
        self.roundabout_center().is_some_and(|c| {
            let dx = (r.min[0] - c[0]).max(c[0] - r.max[0]).max(0.0);
            let dy = (r.min[1] - c[1]).max(c[1] - r.max[1]).max(0.0);
            dx.hypot(dy) < self.roundabout_clear_m()
        })
    }
    /// The river's water surface in plan (between the sidewalks of its two
    /// x-roads, past the town on both sides), if the town has one.
    pub fn river_band(&self) -> Option<Rect> {
        let j = self.river_row?;
        let a = self.block_interior(0, j);
        let b = self.bounds();
        Some(Rect {
            min: [b.min[0] - GROUND_MARGIN_M, a.min[1]],
            max: [b.max[0] + GROUND_MARGIN_M, a.max[1]],
        })
    }
    /// Height of the sidewalk top (0 for shoulders), metres.
    pub fn walk_z(&self) -> f64 {
        if self.sidewalks {
            0.14
        } else {
            0.0
        }
    }
    /// Length of the grid along x (west to east edge junctions), metres.
    pub fn len_x(&self) -> f64 {
        self.nx as f64 * self.pitch_m
    }
    /// Length of the grid along y, metres.
    pub fn len_y(&self) -> f64 {
        self.ny as f64 * self.pitch_m
    }
    /// Road surface of x-road j (stubs included); the straight part only
    /// of an outer x-road with loop corners (between the arcs' ends).
    pub fn x_road(&self, j: usize) -> Rect {
        let y = j as f64 * self.pitch_m;
        let (a0, a1) = if self.loop_corner_at(0, j) {
            (self.loop_radius_m, self.len_x() - self.loop_radius_m)
        } else {
            (-STUB_M, self.len_x() + STUB_M)
        };
        Rect {
            min: [a0, y - self.road_w_m / 2.0],
            max: [a1, y + self.road_w_m / 2.0],
        }
    }
    /// Road surface of y-road i (ending at the outer x-roads' far kerbs);
    /// the straight part only of an outer y-road with loop corners.
    pub fn y_road(&self, i: usize) -> Rect {
        let x = i as f64 * self.pitch_m;
        let hw = self.road_w_m / 2.0;
        let (a0, a1) = if self.loop_corner_at(i, 0) {
            (self.loop_radius_m, self.len_y() - self.loop_radius_m)
        } else {
            (-hw, self.len_y() + hw)
        };
        Rect {
            min: [x - hw, a0],
            max: [x + hw, a1],
        }
    }
    /// Whether x-road j carries a median barrier (an outer road of a
    /// divided-highway town).
    pub fn median_x(&self, j: usize) -> bool {
        self.median && (j == 0 || j == self.ny)
    }
    /// Whether y-road i carries a median barrier.
    pub fn median_y(&self, i: usize) -> bool {
        self.median && (i == 0 || i == self.nx)
    }
    /// Whether the median barrier runs straight through junction (i, j):
    /// exactly one of its roads is divided (a town street or stub meets the
    /// highway; at the loop's corners the barriers end at the junction).
    /// No move there may cross the highway: left turns are barred.
    pub fn median_through(&self, i: usize, j: usize) -> bool {
        self.median_x(j) != self.median_y(i)
    }
    /// Whether grid junction (i, j) is a curved loop corner (an outer
    /// corner of a town with `loop_radius_m` > 0).
    pub fn loop_corner_at(&self, i: usize, j: usize) -> bool {
        self.loop_radius_m > 0.0 && (i == 0 || i == self.nx) && (j == 0 || j == self.ny)
    }
    /// The curved corners of the loop (none with square corners), in the
    /// order (0, 0), (nx, 0), (0, ny), (nx, ny).
    pub fn loop_corners(&self) -> Vec<LoopCorner> {
        if self.loop_radius_m <= 0.0 {
            return Vec::new();
        }
        let r = self.loop_radius_m;
        [(0, 0), (self.nx, 0), (0, self.ny), (self.nx, self.ny)]
            .into_iter()
            .map(|(i, j)| {
                let corner = [i as f64 * self.pitch_m, j as f64 * self.pitch_m];
                let inward: [f64; 2] = [
                    if i == 0 { 1.0 } else { -1.0 },
                    if j == 0 { 1.0 } else { -1.0 },
                ];
                // The arc faces the corner: ±45° about the diagonal to it.
                let mid = (-inward[1]).atan2(-inward[0]);
                LoopCorner {
                    ij: (i, j),
                    corner,
                    centre: [corner[0] + r * inward[0], corner[1] + r * inward[1]],
                    inward,
                    theta: (mid - FRAC_PI_4, mid + FRAC_PI_4),
                }
            })
            .collect()
    }
    /// Whether (x, y) lies on the asphalt of a curved loop corner: within
    /// half the road width of the arc, in the quarter the arc spans.
    pub fn on_loop_curve(&self, p: [f64; 2]) -> bool {
        self.loop_corners().iter().any(|c| {
            let d = [p[0] - c.centre[0], p[1] - c.centre[1]];
            let facing = d[0] * c.inward[0] <= 0.0 && d[1] * c.inward[1] <= 0.0;
            facing && (d[0].hypot(d[1]) - self.loop_radius_m).abs() <= self.road_w_m / 2.0
        })
    }
    /// Whether (x, y) lies in the square between a curved loop corner's
    /// junction (and the bounds beyond it) and its arc centre, or within
    /// 5 m past the arc's ends (a street tree's crown would reach over the
    /// curve): the arc, its shoulders and the cut-off corner, where no
    /// furniture stands.
    pub fn in_loop_corner(&self, p: [f64; 2]) -> bool {
        let b = self.bounds();
        self.loop_corners().iter().any(|c| {
            (0..2).all(|k| {
                let edge = if c.inward[k] > 0.0 {
                    b.min[k]
                } else {
                    b.max[k]
                };
                // Distance inward from 1 m beyond the bounds' edge.
                let d = (p[k] - edge) * c.inward[k] + 1.0;
                d >= 0.0 && d <= (c.centre[k] - edge).abs() + 6.0
            })
        })
    }
    /// Every straight road surface rectangle (x-roads, then y-roads; they
    /// overlap at junctions); curved loop corners are `on_loop_curve`.
    pub fn road_rects(&self) -> Vec<Rect> {
        (0..=self.ny)
            .map(|j| self.x_road(j))
            .chain((0..=self.nx).map(|i| self.y_road(i)))
            .collect()
    }
    /// Lot area of block (i, j) inside the sidewalks; at a curved loop
    /// corner, cut back to the square whose near corner is 1 m inside the
    /// arc's inner shoulder (the lots never reach the curve).
    pub fn block_interior(&self, i: usize, j: usize) -> Rect {
        let edge = self.road_w_m / 2.0 + self.sidewalk_m;
        let (x0, y0) = (i as f64 * self.pitch_m, j as f64 * self.pitch_m);
        let mut a = Rect {
            min: [x0 + edge, y0 + edge],
            max: [x0 + self.pitch_m - edge, y0 + self.pitch_m - edge],
        };
        let r = self.loop_radius_m;
        // The near corner at distance ρ from the arc centre on the diagonal.
        let cut = r - (r - edge - 1.0) / std::f64::consts::SQRT_2;
        for c in self.loop_corners() {
            let (ci, cj) = c.ij;
            if !((ci == i || ci == i + 1) && (cj == j || cj == j + 1)) {
                continue;
            }
            for k in 0..2 {
                let at = c.corner[k] + c.inward[k] * cut;
                if c.inward[k] > 0.0 {
                    a.min[k] = a.min[k].max(at);
                } else {
                    a.max[k] = a.max[k].min(at);
                }
            }
        }
        a
    }
    /// Bounds of everything generated (roads, sidewalks, lots), metres.
    pub fn bounds(&self) -> Rect {
        let e = self.road_w_m / 2.0 + self.sidewalk_m;
        Rect {
            min: [-STUB_M, -e],
            max: [self.len_x() + STUB_M, self.len_y() + e],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn looped(r: f64) -> Layout {
        Layout {
            nx: 3,
            ny: 2,
            pitch_m: 200.0,
            road_w_m: 14.0,
            parking_m: 0.0,
            lane_w_m: 3.5,
            lanes: 2,
            sidewalk_m: 2.0,
            sidewalks: false,
            river_row: None,
            roundabout: None,
            underpass: None,
            loop_radius_m: r,
            median: true,
        }
    }

    #[test]
    fn corner_lots_stay_inside_the_curves_inner_shoulder() {
        let l = looped(120.0);
        let clear = l.loop_radius_m - l.road_w_m / 2.0 - l.sidewalk_m - 1.0;
        // All four outer corners of the 3 × 2 grid curve, in the documented order.
        let ij: Vec<_> = l.loop_corners().iter().map(|c| c.ij).collect();
        assert_eq!(ij, vec![(0, 0), (3, 0), (0, 2), (3, 2)]);
        for c in l.loop_corners() {
            let (i, j) = (c.ij.0.min(l.nx - 1), c.ij.1.min(l.ny - 1));
            let a = l.block_interior(i, j);
            // The lot corner nearest the junction is exactly `clear` from
            // the arc centre (every other lot point in the arc's quarter is
            // nearer).
            let near = [0, 1].map(|k| {
                if c.inward[k] > 0.0 {
                    a.min[k]
                } else {
                    a.max[k]
                }
            });
            let d = (near[0] - c.centre[0]).hypot(near[1] - c.centre[1]);
            assert!((d - clear).abs() < 1e-9, "{:?}: {d} vs {clear}", c.ij);
            // The arc is road, the old junction and its corner are not.
            let t = (c.theta.0 + c.theta.1) / 2.0;
            let r = l.loop_radius_m;
            let on = |r: f64| [c.centre[0] + r * t.cos(), c.centre[1] + r * t.sin()];
            assert!(l.on_loop_curve(on(r)) && l.on_loop_curve(on(r + 6.9)));
            assert!(!l.on_loop_curve(on(r + 7.1)) && !l.on_loop_curve(c.corner));
            assert!(l.in_loop_corner(c.corner) && l.in_loop_corner(on(r)));
            assert!(!l.in_loop_corner(l.bounds().center()));
        }
        // Lots away from the corners keep their size; square corners cut nothing.
        assert_eq!(l.block_interior(1, 0), looped(0.0).block_interior(1, 0));
        assert!(looped(0.0).loop_corners().is_empty());
    }
}
