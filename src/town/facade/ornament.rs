//! Ornament and roofscape: balconies with barred railings (prefabs, the
//! railing labelled `fence`), roof units (AC boxes, vents, water tanks,
//! stair huts; prefabs), and the per-building pieces sized to the building
//! — cornice, string courses, parapet, drainpipes — as a few boxes each.
//!
//! Balcony frame as the bay prefabs' (`bay`): wall plane y = 0, outside
//! −y, the slab's top at z = 0. Roof-unit frames: z up from the roof.

use crate::scene::desc::ObjectDesc;
use crate::town::layout::Rect;
use crate::town::parts::{class, cylinder, repeated, slab, Label};
use crate::town::rng::Rng;

use super::bay::boxed;
use super::style::Style;

/// Balcony depth out of the wall.
pub const BALCONY_DEPTH_M: f64 = 1.1;
/// Railing height above the slab.
const RAIL_M: f64 = 1.0;
/// Spacing of the railing's bars.
pub const BAR_STEP_M: f64 = 0.12;
/// Side of a bar's square section.
pub const BAR_M: f64 = 0.02;

/// A balcony slab one bay wide, its top at z = 0.
pub fn balcony(s: &Style) -> Vec<ObjectDesc> {
    let hw = s.bay_m / 2.0 - 0.2;
    let lo = [-hw, -BALCONY_DEPTH_M, -0.15];
    vec![boxed(lo, [hw, 0.0, 0.0], "concrete", class("building"))]
}

/// The railing of a balcony (`fence`): thin bars under a top rail on the
/// slab's three open sides.
pub fn railing(s: &Style) -> Vec<ObjectDesc> {
    let f = class("fence");
    let hw = s.bay_m / 2.0 - 0.2;
    let d = BALCONY_DEPTH_M;
    let mut out = Vec::new();
    let m = "facade_railing";
    // Top rails: front and two sides.
    out.push(boxed(
        [-hw, -d, RAIL_M - 0.04],
        [hw, -d + 0.04, RAIL_M],
        m,
        f,
    ));
    let side = boxed([-hw, -d, RAIL_M - 0.04], [-hw + 0.04, 0.0, RAIL_M], m, f);
    out.push(repeated(side, &[(2, [2.0 * hw - 0.04, 0.0, 0.0])]));
    // Bars along the front and down each side.
    let n_front = ((2.0 * hw - BAR_M) / BAR_STEP_M).floor() as u32 + 1;
    let bar = boxed(
        [-hw, -d, 0.0],
        [-hw + BAR_M, -d + BAR_M, RAIL_M - 0.04],
        m,
        f,
    );
    out.push(repeated(bar, &[(n_front, [BAR_STEP_M, 0.0, 0.0])]));
    let n_side = ((d - 0.1) / BAR_STEP_M).floor() as u32;
    let bar = boxed(
        [-hw, -d + BAR_STEP_M, 0.0],
        [-hw + BAR_M, -d + BAR_STEP_M + BAR_M, RAIL_M - 0.04],
        m,
        f,
    );
    out.push(repeated(
        bar,
        &[
            (2, [2.0 * hw - BAR_M, 0.0, 0.0]),
            (n_side, [0.0, BAR_STEP_M, 0.0]),
        ],
    ));
    out
}

/// The roof-unit prefabs: (name, objects).
pub fn roof_units() -> Vec<(&'static str, Vec<ObjectDesc>)> {
    let b = class("building");
    let ac = vec![
        boxed([-0.5, -0.4, 0.0], [0.5, 0.4, 0.9], "facade_metal_grey", b),
        cylinder(0.3, 0.05, 12, [0.0, 0.0, 0.9], "facade_metal_dark", b),
    ];
    let vent = vec![
        cylinder(0.15, 0.8, 10, [0.0, 0.0, 0.0], "facade_metal_grey", b),
        cylinder(0.25, 0.06, 10, [0.0, 0.0, 0.85], "facade_metal_grey", b),
    ];
    let mut tank = vec![cylinder(1.0, 1.8, 16, [0.0, 0.0, 0.8], "facade_wood", b)];
    let leg = boxed([-0.7, -0.7, 0.0], [-0.6, -0.6, 0.8], "facade_metal_dark", b);
    tank.push(repeated(leg, &[(2, [1.3, 0.0, 0.0]), (2, [0.0, 1.3, 0.0])]));
    tank.push(cylinder(
        1.05,
        0.1,
        16,
        [0.0, 0.0, 2.6],
        "facade_metal_dark",
        b,
    ));
    let hut = vec![
        boxed([-1.2, -1.5, 0.0], [1.2, 1.5, 2.4], "concrete", b),
        boxed([-1.3, -1.6, 2.4], [1.3, 1.6, 2.55], "roof", b),
        boxed([-0.45, -1.53, 0.0], [0.45, -1.5, 2.05], "door", b),
    ];
    vec![
        ("facade_roof_ac", ac),
        ("facade_roof_vent", vent),
        ("facade_roof_tank", tank),
        ("facade_roof_hut", hut),
    ]
}

/// Roof units on the flat roof over `roof` (top at `z`): up to `max`
/// units on distinct cells of a 4 m grid inset 1.5 m from the edge.
pub fn place_roof_units(roof: &Rect, z: f64, max: u32, r: &mut Rng, id: Label) -> Vec<ObjectDesc> {
    let [w, d] = roof.size();
    let (nx, ny) = (((w - 3.0) / 4.0).floor(), ((d - 3.0) / 4.0).floor());
    if max == 0 || nx < 1.0 || ny < 1.0 {
        return Vec::new();
    }
    let cells = (nx * ny) as usize;
    let mut taken = vec![false; cells];
    let names = roof_units();
    let mut out = Vec::new();
    for _ in 0..r.int(1, max) {
        let k = r.index(cells);
        if std::mem::replace(&mut taken[k], true) {
            continue;
        }
        let (i, j) = ((k % nx as usize) as f64, (k / nx as usize) as f64);
        let at = [
            roof.min[0] + 1.5 + 4.0 * i + 2.0,
            roof.min[1] + 1.5 + 4.0 * j + 2.0,
            z,
        ];
        let name = names[r.index(names.len())].0;
        let heading = [0.0, 90.0][r.index(2)];
        out.push(crate::town::parts::instance(name, at, heading, &[], id));
    }
    out
}

/// Cornice, string courses and parapet of a flat-roofed building on
/// `plot`, `floors` floors of style `s` (height `h`), walls of `wall`.
pub fn bands(
    s: &Style,
    wall: &str,
    plot: &Rect,
    floors: u32,
    flat: bool,
    id: Label,
) -> Vec<ObjectDesc> {
    let h = floors as f64 * s.floor_m;
    let grow = |e: f64| {
        (
            [plot.min[0] - e, plot.min[1] - e],
            [plot.max[0] + e, plot.max[1] + e],
        )
    };
    let mut out = Vec::new();
    if s.string_course && floors > 1 {
        let (lo, hi) = grow(0.08);
        let z = s.floor_m - 0.08;
        let band = slab(lo, hi, z, z + 0.16, s.trim, id);
        out.push(repeated(band, &[(floors - 1, [0.0, 0.0, s.floor_m])]));
    }
    if s.cornice && flat {
        let (lo, hi) = grow(0.25);
        out.push(slab(lo, hi, h - 0.35, h, s.trim, id));
    }
    if flat && s.parapet_m > 0.0 {
        let t = 0.25;
        let (x0, y0, x1, y1) = (plot.min[0], plot.min[1], plot.max[0], plot.max[1]);
        let top = h + s.parapet_m;
        out.push(slab([x0, y0], [x1, y0 + t], h, top, wall, id));
        out.push(slab([x0, y1 - t], [x1, y1], h, top, wall, id));
        out.push(slab([x0, y0 + t], [x0 + t, y1 - t], h, top, wall, id));
        out.push(slab([x1 - t, y0 + t], [x1, y1 - t], h, top, wall, id));
        // Coping: a 4 cm trim on the parapet's top edge.
        out.push(slab([x0, y0], [x1, y0 + t], top, top + 0.04, s.trim, id));
        out.push(slab([x0, y1 - t], [x1, y1], top, top + 0.04, s.trim, id));
    }
    out
}

/// A drainpipe 5 cm in radius from the ground to `top`, 8 cm out from
/// the wall at world point `at` (on the wall plane), `out_dir` the wall's
/// outward normal.
pub fn drainpipe(at: [f64; 2], out_dir: [f64; 2], top: f64, id: Label) -> Vec<ObjectDesc> {
    let c = [at[0] + out_dir[0] * 0.08, at[1] + out_dir[1] * 0.08];
    vec![
        cylinder(0.05, top, 8, [c[0], c[1], 0.0], "facade_pipe", id),
        cylinder(0.08, 0.2, 8, [c[0], c[1], top - 0.2], "facade_pipe", id),
    ]
}
