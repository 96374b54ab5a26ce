//! The façade generator: a building of a given massing (plot, floors,
//! tower or not) gets a style (`style`), a core box set back `SKIN_M`
//! behind its walls, and four façades tiled edge to edge with bay prefabs
//! (`bay`: windows with recessed glazing and a room behind, shopfronts,
//! doors with steps), solid wall at the ends, a ground floor planned by
//! `front` (shop units with signs and awnings), balconies, drainpipes, and
//! a roof with cornice, parapet and roof units (`ornament`).
//!
//! Façade frame: a façade is its wall line's centre `c` and the heading of
//! its bay prefabs (local +x along the wall, local −y out of the building);
//! z from the ground. Every part carries the building's instance id (so a
//! graded town moves the building as one); classes: walls, windows, doors,
//! signs and roof units `building`, balcony railings `fence`.

pub mod bay;
pub mod front;
pub mod materials;
pub mod merge;
pub mod ornament;
pub mod style;
#[cfg(test)]
mod tests;

use crate::scene::desc::{ObjectDesc, PrefabDesc};
use crate::town::desc::TownDesc;
use crate::town::layout::Rect;
use crate::town::parts::{cuboid, instance, repeated, slab, Label};
use crate::town::rng::{tag, Rng};

pub use bay::SKIN_M;
pub use materials::facade_materials;
pub use style::{Ground, Roof, Style, STYLES};

use front::{GroundBay, AWNINGS, BOARDS};

/// Shortest solid wall at each end of a façade.
pub const END_MIN_M: f64 = 0.5;

/// Name of a bay prefab (`kind`: "window_0", "light", "shop", ...) of `s`.
pub fn prefab_name(s: &Style, kind: &str) -> String {
    format!("facade_{}_{kind}", s.name)
}

/// Every façade prefab: per style its window variants, lit-room overlay,
/// door, and as the style needs shopfront, awnings, roller door and
/// balcony; the shop signs; the roof units.
pub fn facade_prefabs() -> Vec<PrefabDesc> {
    let mut out = Vec::new();
    let mut add = |name: String, objects: Vec<ObjectDesc>| {
        out.push(PrefabDesc {
            name,
            objects: merge::merge_boxes(objects),
        })
    };
    for s in &STYLES {
        for v in 0..bay::VARIANTS {
            add(
                prefab_name(s, &format!("window_{v}")),
                bay::window_bay(s, v),
            );
        }
        add(prefab_name(s, "light"), bay::room_light(s));
        let (n_steps, canopy) = door_steps(s);
        add(prefab_name(s, "door"), bay::door_bay(s, n_steps, canopy));
        if matches!(s.ground, Ground::Shops | Ground::Lobby) {
            add(prefab_name(s, "shop"), bay::shop_bay(s));
        }
        if s.ground == Ground::Shops {
            add(prefab_name(s, "awning"), front::awning(s, false));
            add(prefab_name(s, "awning_striped"), front::awning(s, true));
        }
        if s.ground == Ground::Industrial {
            add(prefab_name(s, "roller"), bay::roller_bay(s));
        }
        if s.balcony > 0.0 {
            add(prefab_name(s, "balcony"), ornament::balcony(s));
            add(prefab_name(s, "railing"), ornament::railing(s));
        }
    }
    for k in 0..front::SHOP_NAMES.len() {
        add(format!("facade_sign_{k}"), front::sign(k));
    }
    for (name, objects) in ornament::roof_units() {
        add(name.to_string(), objects);
    }
    out
}

/// Steps before a style's front door, and whether a canopy shelters it.
pub fn door_steps(s: &Style) -> (u32, bool) {
    match (s.ground, s.name) {
        (Ground::Lobby | Ground::Industrial, _) => (0, false),
        (Ground::Shops, _) => (1, false),
        (_, "stone_civic" | "stucco_townhouse") => (3, s.name == "stucco_townhouse"),
        (_, "concrete_slab") => (1, true),
        _ => (2, true),
    }
}

/// World point of façade-frame point `p` (x along, y into the building, z up).
fn place(c: [f64; 2], heading: f64, p: [f64; 3]) -> [f64; 3] {
    let (along, out) = (heading_dir(heading), normal_out(heading));
    [
        c[0] + along[0] * p[0] - out[0] * p[1],
        c[1] + along[1] * p[0] - out[1] * p[1],
        p[2],
    ]
}

/// Unit vector along a façade of bay heading `deg`.
pub fn heading_dir(deg: f64) -> [f64; 2] {
    let a = deg.to_radians();
    [a.cos().round(), a.sin().round()]
}

/// Outward normal of a façade of bay heading `deg` (the bays' local −y).
pub fn normal_out(deg: f64) -> [f64; 2] {
    let a = deg.to_radians();
    [a.sin().round(), -a.cos().round()]
}

/// Columns of bays on a wall `len` long, and the solid end width.
pub fn columns(s: &Style, len: f64) -> (u32, f64) {
    let cols = ((len - 2.0 * END_MIN_M) / s.bay_m).floor().max(0.0) as u32;
    (cols, (len - cols as f64 * s.bay_m) / 2.0)
}

/// One façade: its wall line's centre, bay heading, length, and whether it
/// is the street front.
#[derive(Clone, Copy, Debug)]
pub struct Facade {
    /// Centre of the wall line.
    pub c: [f64; 2],
    /// Heading of the bay prefabs.
    pub heading: f64,
    /// Length of the wall.
    pub len: f64,
    /// The street front (ground floor shops or door, balconies).
    pub front: bool,
}

/// The four façades of `plot`; the street front faces −y (`south`) or +y.
/// The side walls run between the front and back skins.
pub fn facades(plot: &Rect, south: bool) -> [Facade; 4] {
    let [w, d] = plot.size();
    let [cx, cy] = plot.center();
    let side = (d - 2.0 * SKIN_M).max(0.0);
    let f = |c, heading, len, front| Facade {
        c,
        heading,
        len,
        front,
    };
    [
        f([cx, plot.min[1]], 0.0, w, south),
        f([plot.max[0], cy], 90.0, side, false),
        f([cx, plot.max[1]], 180.0, w, !south),
        f([plot.min[0], cy], 270.0, side, false),
    ]
}

/// One building on `plot` with `floors` floors (a tower if `tower`): its
/// style, core, façades, roof and ornament, every part labelled `id`.
#[allow(clippy::too_many_arguments)]
pub fn building(
    desc: &TownDesc,
    plot: &Rect,
    south: bool,
    floors: u32,
    tower: bool,
    r: &mut Rng,
    id: Label,
    out: &mut Vec<ObjectDesc>,
) -> &'static Style {
    let s = style::choose(desc, floors, tower, r);
    let wall = s.walls[r.index(s.walls.len())];
    let h = floors as f64 * s.floor_m;
    let core = [plot.min[0] + SKIN_M, plot.min[1] + SKIN_M];
    let core_max = [plot.max[0] - SKIN_M, plot.max[1] - SKIN_M];
    if core[0] < core_max[0] && core[1] < core_max[1] {
        out.push(slab(core, core_max, 0.0, h, wall, id));
    }
    let mut lit = Rng::new(&[r.next_u64(), tag::LIT_WINDOWS]);
    let lit_fraction = lit.range(0.0, 0.35);
    let balconies = r.chance(s.balcony) && floors >= 2;
    for f in facades(plot, south) {
        facade(s, wall, f, floors, r, (&mut lit, lit_fraction), id, out);
        if f.front && balconies {
            balcony_columns(s, f, floors, r, id, out);
        }
    }
    let d = plot.size()[1];
    let flat = !(s.roof == Roof::Gable && floors <= 2 && d <= 14.0);
    if flat {
        let grow = if s.parapet_m > 0.0 { 0.0 } else { 0.2 };
        let lo = [plot.min[0] - grow, plot.min[1] - grow];
        let hi = [plot.max[0] + grow, plot.max[1] + grow];
        out.push(slab(lo, hi, h, h + 0.2, "roof", id));
        let inner = Rect {
            min: [plot.min[0] + 0.3, plot.min[1] + 0.3],
            max: [plot.max[0] - 0.3, plot.max[1] - 0.3],
        };
        out.extend(ornament::place_roof_units(
            &inner,
            h + 0.2,
            s.roof_units,
            r,
            id,
        ));
    } else {
        out.push(crate::town::buildings::gable_roof(plot, h, id));
    }
    out.extend(ornament::bands(s, wall, plot, floors, flat, id));
    s
}

/// The bays and end walls of one façade, the lit rooms of its window
/// rows, and on the street front the ground floor and drainpipes.
#[allow(clippy::too_many_arguments)]
fn facade(
    s: &Style,
    wall: &str,
    f: Facade,
    floors: u32,
    r: &mut Rng,
    (lit, lit_fraction): (&mut Rng, f64),
    id: Label,
    out: &mut Vec<ObjectDesc>,
) {
    if f.len <= 0.0 {
        return;
    }
    let h = floors as f64 * s.floor_m;
    let (cols, end) = columns(s, f.len);
    // Solid wall at both ends, full height and skin depth.
    for side in [-1.0, 1.0] {
        let at = place(
            f.c,
            f.heading,
            [side * (f.len - end) / 2.0, SKIN_M / 2.0, h / 2.0],
        );
        out.push(cuboid([end, SKIN_M, h], at, f.heading, wall, id));
    }
    if cols == 0 {
        return;
    }
    let map: &[(&str, &str)] = if wall == s.walls[0] {
        &[]
    } else {
        &[(s.walls[0], wall)]
    };
    let x0 = -(cols as f64 - 1.0) * s.bay_m / 2.0;
    let along = heading_dir(f.heading);
    let step = [along[0] * s.bay_m, along[1] * s.bay_m, 0.0];
    let first_row = u32::from(f.front);
    for row in first_row..floors {
        let v = r.int(0, bay::VARIANTS - 1);
        let at = place(f.c, f.heading, [x0, 0.0, row as f64 * s.floor_m]);
        let name = prefab_name(s, &format!("window_{v}"));
        out.push(repeated(
            instance(&name, at, f.heading, map, id),
            &[(cols, step)],
        ));
        if lit.chance(lit_fraction) {
            let c0 = lit.int(0, cols - 1);
            let run = lit.int(1, (cols - c0).min(4));
            let x = x0 + c0 as f64 * s.bay_m;
            let at = place(f.c, f.heading, [x, 0.0, row as f64 * s.floor_m]);
            let light = instance(&prefab_name(s, "light"), at, f.heading, &[], id);
            out.push(repeated(light, &[(run, step)]));
        }
    }
    if f.front {
        ground_floor(s, f, cols, map, r, id, out);
        if s.drainpipe {
            for side in [-1.0, 1.0] {
                let at = place(f.c, f.heading, [side * (f.len / 2.0 - 0.25), 0.0, 0.0]);
                let n = normal_out(f.heading);
                out.extend(ornament::drainpipe([at[0], at[1]], n, h + 0.1, id));
            }
        }
    }
}

/// The street front's ground floor: one bay per column from
/// `front::ground_plan`, a sign over each named shop unit, and awnings
/// over its shop windows.
fn ground_floor(
    s: &Style,
    f: Facade,
    cols: u32,
    map: &[(&str, &str)],
    r: &mut Rng,
    id: Label,
    out: &mut Vec<ObjectDesc>,
) {
    let (plan, units) = front::ground_plan(s, cols, r);
    let x_of = |c: u32| -(cols as f64 - 1.0) * s.bay_m / 2.0 + c as f64 * s.bay_m;
    for (c, b) in plan.iter().enumerate() {
        let kind = match b {
            GroundBay::Window(v) => format!("window_{v}"),
            GroundBay::Shop => "shop".to_string(),
            GroundBay::Door => "door".to_string(),
            GroundBay::Roller => "roller".to_string(),
        };
        let at = place(f.c, f.heading, [x_of(c as u32), 0.0, 0.0]);
        out.push(instance(&prefab_name(s, &kind), at, f.heading, map, id));
    }
    let top = bay::shop_opening(s).z1;
    for u in units {
        let mid = (x_of(u.first) + x_of(u.first + u.cols - 1)) / 2.0;
        if let Some(k) = u.name {
            let board = [(BOARDS[0], BOARDS[r.index(BOARDS.len())])];
            let at = place(f.c, f.heading, [mid, 0.0, top + 0.05]);
            out.push(instance(
                &format!("facade_sign_{k}"),
                at,
                f.heading,
                &board,
                id,
            ));
        }
        let colour = [(AWNINGS[0], AWNINGS[r.index(AWNINGS.len())])];
        let kind = if r.chance(0.5) {
            "awning_striped"
        } else {
            "awning"
        };
        for c in u.first..u.first + u.cols {
            if plan[c as usize] == GroundBay::Shop {
                let at = place(f.c, f.heading, [x_of(c), 0.0, top]);
                out.push(instance(&prefab_name(s, kind), at, f.heading, &colour, id));
            }
        }
    }
}

/// Balconies on every other column of the street front, floors 1 and up:
/// the slab (`building`) and its railing (`fence`, the building's id).
fn balcony_columns(
    s: &Style,
    f: Facade,
    floors: u32,
    r: &mut Rng,
    id: Label,
    out: &mut Vec<ObjectDesc>,
) {
    let (cols, _) = columns(s, f.len);
    let parity = r.int(0, 1);
    let fence = Label {
        class: "fence",
        instance: id.instance,
    };
    for c in (0..cols).filter(|c| c % 2 == parity) {
        let x = -(cols as f64 - 1.0) * s.bay_m / 2.0 + c as f64 * s.bay_m;
        let at = place(f.c, f.heading, [x, 0.0, s.floor_m]);
        let up = [(floors - 1, [0.0, 0.0, s.floor_m])];
        for (kind, l) in [("balcony", id), ("railing", fence)] {
            out.push(repeated(
                instance(&prefab_name(s, kind), at, f.heading, &[], l),
                &up,
            ));
        }
    }
}
