//! An underpass (`underpass = true`): the y-road of block column 1 passes
//! under the middle x-road (row ⌊ny/2⌋) instead of meeting it at a junction.
//! The x-road runs straight over a short deck at grade (parapets on both
//! sides); the y-road falls in a cut from the junction before to `DEPTH_M`
//! below grade under the deck and rises to the junction after, between
//! retaining walls (class `wall`) below its kerbs, with a parapet along
//! each sidewalk above the cut. Nobody turns at the crossing: it has no
//! signals, stop lines or crosswalks, and its two roads' traffic goes
//! straight through on two levels (`VehiclePose::same_level`).
//!
//! Profile along the y-road, on each side of the deck: level for
//! `LEVEL_M` past the junction's edge (its crosswalk and stop line), then a
//! fall of length L whose slope ramps linearly from 0 to g over
//! `TRANSITION_M`, holds g and ramps back to 0 (C¹, vertical curves of
//! radius `TRANSITION_M`/g), with g·(L − `TRANSITION_M`) = `DEPTH_M`; then
//! level under the deck. World frame z up, metres, in the level grid (an
//! organic town's warp bends it like every road). Meshes: `underpass/cut.rs`.

mod cut;
mod fittings;

use super::desc::TownDesc;
use super::layout::{Layout, Rect};

pub use cut::underpass_objects;

/// Depth of the cut's road under the deck, metres.
pub const DEPTH_M: f64 = 5.5;
/// Depth of the deck (road surface to underside), metres.
pub const DECK_M: f64 = 0.9;
/// Steepest grade the cut may have.
pub const MAX_GRADE: f64 = 0.10;
/// Level run past the junction's edge before the fall, metres.
pub const LEVEL_M: f64 = 5.0;
/// Length of each vertical curve (slope ramp), metres.
pub const TRANSITION_M: f64 = 10.0;
/// Level run at the bottom beyond each deck end, metres.
const BOTTOM_MARGIN_M: f64 = 1.0;

/// The underpass of a town: where it lies and its profile.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Underpass {
    /// Junction (i, j) the x-road crosses over.
    pub ij: (usize, usize),
    /// Centreline x of the sunken y-road, world metres.
    pub x_m: f64,
    /// Centreline y of the x-road on the deck, world metres.
    pub y_m: f64,
    /// Half width of the y-road's asphalt (walls at x_m ± it), metres.
    pub half_w_m: f64,
    /// The deck's south and north ends (the x-road's sidewalks' outer
    /// edges), world y, metres.
    pub deck: (f64, f64),
    /// Where the south fall starts and the north rise ends, world y.
    pub ends: (f64, f64),
    /// The edges of the junctions before and after (where the y-road's
    /// sunken pieces begin and end), world y.
    pub edges: (f64, f64),
    /// Length of each fall, metres.
    pub fall_m: f64,
    /// The steepest grade (held between the vertical curves).
    pub grade: f64,
}

/// The crossing (i, j) of a town with `underpass`: the y-road of block
/// column 1 under the middle x-road.
pub fn site(nx: usize, ny: usize) -> (usize, usize) {
    debug_assert!(nx >= 2 && ny >= 2);
    (1, ny / 2)
}

/// Why a town cannot hold an underpass, if it cannot.
pub fn check(desc: &TownDesc) -> Result<(), String> {
    let l = Layout::new(&TownDesc {
        underpass: false,
        ..desc.clone()
    });
    if l.nx < 2 || l.ny < 2 {
        return Err("underpass: needs 2 × 2 blocks or more".into());
    }
    if let Some((ri, _)) = l.roundabout {
        if ri < 3 {
            return Err("underpass: with a roundabout needs 6 block columns or more".into());
        }
    }
    let u = Underpass::of(&Layout {
        underpass: Some(site(l.nx, l.ny)),
        ..l
    })
    .expect("set");
    if u.fall_m < 2.0 * TRANSITION_M || u.grade > MAX_GRADE {
        return Err(format!(
            "underpass: blocks too short for a {DEPTH_M} m cut (steepest grade {:.1} %, at most {} %)",
            u.grade * 100.0,
            MAX_GRADE * 100.0
        ));
    }
    Ok(())
}

impl Underpass {
    /// The underpass of a layout, `None` without one.
    pub fn of(l: &Layout) -> Option<Self> {
        let (i, j) = l.underpass?;
        let (p, hw, sw) = (l.pitch_m, l.road_w_m / 2.0, l.sidewalk_m);
        let (x_m, y_m) = (i as f64 * p, j as f64 * p);
        let deck = (y_m - hw - sw, y_m + hw + sw);
        let ends = (y_m - p + hw + LEVEL_M, y_m + p - hw - LEVEL_M);
        let fall_m = (deck.0 - BOTTOM_MARGIN_M) - ends.0;
        Some(Underpass {
            ij: (i, j),
            x_m,
            y_m,
            half_w_m: hw,
            deck,
            ends,
            edges: (y_m - p + hw, y_m + p - hw),
            fall_m,
            grade: DEPTH_M / (fall_m - TRANSITION_M),
        })
    }

    /// Depth below grade and slope (d depth / du) at `u` metres into a fall.
    fn depth(&self, u: f64) -> (f64, f64) {
        let (g, t, l) = (self.grade, TRANSITION_M, self.fall_m);
        let u = u.clamp(0.0, l);
        if u <= t {
            (g * u * u / (2.0 * t), g * u / t)
        } else if u <= l - t {
            (g * (u - t / 2.0), g)
        } else {
            let r = l - u;
            (DEPTH_M - g * r * r / (2.0 * t), g * r / t)
        }
    }

    /// Height of the sunken road at world y, metres (≤ 0), and dz/dy.
    pub fn profile(&self, y: f64) -> (f64, f64) {
        if y <= self.y_m {
            let (d, s) = self.depth(y - self.ends.0);
            (-d, -s)
        } else {
            let (d, s) = self.depth(self.ends.1 - y);
            (-d, s)
        }
    }

    /// Whether world (x, y) lies over the cut (between its walls, where
    /// its road is below grade).
    pub fn over_cut(&self, p: [f64; 2]) -> bool {
        (p[0] - self.x_m).abs() <= self.half_w_m && p[1] > self.ends.0 && p[1] < self.ends.1
    }

    /// Whether `r` reaches the cut or the sidewalks beside it.
    pub fn beside(&self, r: &Rect) -> bool {
        let m = self.deck.1 - self.y_m;
        r.overlaps(&Rect {
            min: [self.x_m - m, self.ends.0],
            max: [self.x_m + m, self.ends.1],
        })
    }

    /// Height and nose-up pitch (degrees) of a body at level-grid (x, y)
    /// heading `heading` (radians): on the profile when it drives along
    /// the sunken y-road, else at grade (the x-road over the deck).
    pub fn pose(&self, p: [f64; 2], heading: f64) -> (f64, f64) {
        if !self.over_cut(p) || heading.sin().abs() < 0.5 {
            return (0.0, 0.0);
        }
        let (z, dz_dy) = self.profile(p[1]);
        (z, (dz_dy * heading.sin()).atan().to_degrees())
    }
}

/// Height and pitch (degrees) of a body at level-grid `p` heading
/// `heading` (radians) in layout `l`: 0 without an underpass.
pub fn level_pose(l: &Layout, p: [f64; 2], heading: f64) -> (f64, f64) {
    Underpass::of(l).map_or((0.0, 0.0), |u| u.pose(p, heading))
}

#[cfg(test)]
mod tests;
