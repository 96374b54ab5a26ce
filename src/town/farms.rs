//! Rural blocks (terrain `field`): a ploughed field with crop ridges
//! running along x, a grass verge and a clipped hedge along its south edge and, on some fields, a
//! barn with a gable roof in a corner of the lot.
//!
//! Ridges are 0.7 m wide, 0.25 m high boxes every 1.6 m: relief a stereo
//! matcher sees at a distance. Units: metres, world frame z up.

use crate::scene::desc::ObjectDesc;

use super::buildings::gable_roof;
use super::layout::Rect;
use super::parts::{class, ground_quad, instance, repeated, slab, Label};
use super::rng::Rng;
use super::vegetation::{self, hedge::HEDGE_LEN_M};

/// Ridge pitch across the field, metres.
const RIDGE_PITCH_M: f64 = 1.6;

/// The field, hedge and barn of one rural block lot.
pub fn field_block(lot: &Rect, r: &mut Rng, next_id: &mut u16, out: &mut Vec<ObjectDesc>) {
    let t = class("terrain");
    let inner = Rect {
        min: [lot.min[0] + 2.0, lot.min[1] + 3.0],
        max: [lot.max[0] - 2.0, lot.max[1] - 2.0],
    };
    let rows = (inner.size()[1] / RIDGE_PITCH_M).floor() as u32;
    if rows > 0 {
        let ridge = slab(
            inner.min,
            [inner.max[0], inner.min[1] + 0.7],
            -0.02,
            0.25,
            "crop",
            t,
        );
        out.push(repeated(ridge, &[(rows, [0.0, RIDGE_PITCH_M, 0.0])]));
    }
    // A grass verge along the road side, and on it a clipped hedge of
    // segments laid end to end.
    out.push(ground_quad(
        lot.min,
        [lot.max[0], lot.min[1] + 2.8],
        0.005,
        vegetation::VERGE,
        t,
    ));
    let n = (lot.size()[0] / HEDGE_LEN_M).floor() as u32;
    if n > 0 {
        let at = [lot.min[0] + HEDGE_LEN_M / 2.0, lot.min[1] + 1.0, 0.0];
        let hedge = instance(vegetation::HEDGE, at, 0.0, &[], class("vegetation"));
        out.push(repeated(hedge, &[(n, [HEDGE_LEN_M, 0.0, 0.0])]));
    }
    if r.chance(0.6) {
        let (w, d) = (r.range(14.0, 22.0), r.range(9.0, 12.0));
        let x0 = if r.chance(0.5) {
            inner.min[0] + 4.0
        } else {
            inner.max[0] - 4.0 - w
        };
        let y0 = inner.max[1] - 4.0 - d;
        let plot = Rect {
            min: [x0, y0],
            max: [x0 + w, y0 + d],
        };
        let id = Label {
            class: "building",
            instance: *next_id,
        };
        *next_id = next_id.saturating_add(1);
        let h = r.range(4.5, 6.5);
        out.push(slab(plot.min, plot.max, 0.0, h, "barn_red", id));
        out.push(gable_roof(&plot, h, id));
    }
}
