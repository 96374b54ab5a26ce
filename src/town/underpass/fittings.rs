//! What makes the cut read as built concrete rather than clean CG: sealed
//! expansion joints down both retaining walls every `JOINT_STEP_M`, and
//! the lighting an underpass has — luminaires on the walls where the cut
//! is deep, and on the deck's underside over the lanes. The luminaires are
//! lit by the always-on `lamp_emit` emitter (a panel under a grey
//! housing, as the street lamps' heads), so at night the sunken road is
//! lit from within. Every piece is short, so an organic town's warp moves
//! it rigidly to its place on the bent wall or deck.

use crate::scene::desc::ObjectDesc;
use crate::town::parts::{class, cuboid};

use super::{Underpass, DECK_M};

/// Spacing of the walls' expansion joints along the road, metres.
pub const JOINT_STEP_M: f64 = 10.0;
/// Joint: sealant strip width along the wall, and how far it stands
/// proud of the wall's face, metres.
const JOINT_M: (f64, f64) = (0.025, 0.006);
/// Wall luminaire: length along the wall, depth out from it, height of the
/// housing; the panel sits under it, metres.
const LUMINAIRE_M: [f64; 3] = [1.2, 0.16, 0.14];
/// Top of a wall luminaire below grade, metres.
const WALL_LAMP_TOP_M: f64 = 1.0;
/// Least clear height under a wall luminaire above the road, metres (a
/// bus is 3.2 m).
const LAMP_CLEAR_M: f64 = 3.3;

impl Underpass {
    /// Stations of the joints: every `JOINT_STEP_M` from the deck's ends
    /// outward while the wall is at least half a metre high.
    fn joint_stations(&self) -> Vec<f64> {
        let mut out = Vec::new();
        for (from, dir) in [(self.deck.0, -1.0), (self.deck.1, 1.0)] {
            let mut y = from;
            while -self.profile(y).0 >= 0.5 {
                out.push(y);
                y += dir * JOINT_STEP_M;
            }
        }
        out
    }

    /// The sealant strips, from the road up to grade.
    fn joints(&self) -> Vec<ObjectDesc> {
        let (w, proud) = JOINT_M;
        let mut out = Vec::new();
        for y in self.joint_stations() {
            let z = self.profile(y).0;
            for sign in [-1.0, 1.0] {
                // Centred on the wall's face: half its thickness stands
                // in front, half is inside the wall.
                let x = self.x_m + sign * self.half_w_m;
                out.push(cuboid(
                    [2.0 * proud, w, -z],
                    [x, y, z / 2.0],
                    0.0,
                    "rubber",
                    class("wall"),
                ));
            }
        }
        out
    }

    /// A luminaire: housing over a 1 mm gap over its lit panel; `at` is
    /// the housing's top centre, `along_y` whether it runs along y.
    fn luminaire(out: &mut Vec<ObjectDesc>, at: [f64; 3], along_y: bool) {
        let [len, depth, h] = LUMINAIRE_M;
        let heading = if along_y { 90.0 } else { 0.0 };
        let pole = class("pole");
        out.push(cuboid(
            [len, depth, h],
            [at[0], at[1], at[2] - h / 2.0],
            heading,
            "street_paint_grey",
            pole,
        ));
        out.push(cuboid(
            [len - 0.1, depth - 0.06, 0.01],
            [at[0], at[1], at[2] - h - 0.001 - 0.005],
            heading,
            "lamp_emit",
            pole,
        ));
    }

    /// Wall luminaires half way between joints where the road lies at
    /// least `LAMP_CLEAR_M` below them; two rows on the deck's underside,
    /// over the lane dividers of each direction.
    fn lamps(&self, lane_w: f64) -> Vec<ObjectDesc> {
        let mut out = Vec::new();
        let top = -WALL_LAMP_TOP_M;
        let bottom = top - LUMINAIRE_M[2] - 0.016;
        for y in self.joint_stations() {
            let y = y + JOINT_STEP_M / 2.0 * (y - self.y_m).signum();
            if self.profile(y).0 > bottom - LAMP_CLEAR_M {
                continue;
            }
            for sign in [-1.0, 1.0] {
                let x = self.x_m + sign * (self.half_w_m - LUMINAIRE_M[1] / 2.0);
                Self::luminaire(&mut out, [x, y, top], true);
            }
        }
        let quarter = (self.deck.1 - self.deck.0) / 4.0;
        for y in [self.deck.0 + quarter, self.deck.1 - quarter] {
            for sign in [-1.0, 1.0] {
                let x = self.x_m + sign * lane_w;
                Self::luminaire(&mut out, [x, y, -DECK_M], true);
            }
        }
        out
    }

    /// The joints and the luminaires.
    pub fn fittings(&self, lane_w: f64) -> Vec<ObjectDesc> {
        let mut out = self.joints();
        out.extend(self.lamps(lane_w));
        out
    }
}
