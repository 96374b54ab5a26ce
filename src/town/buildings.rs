//! Buildings and parks on the blocks: rows of lots along the two streets of
//! each block, each lot holding a building (body, roof, floor ledges, windows
//! on every facade, a door and shop windows on the street side) or planting;
//! towers get a glass curtain wall with mullions. Some window runs show a
//! lit room (an always-on warm emitter). Some blocks are parks.
//!
//! A building's front faces the street its row lines (−y for the south row,
//! +y for the north row). Floor height 3.2 m; windows come from the "window"
//! prefab (facade in its local x–z plane, facing −y).

use std::ops::Range;

use crate::scene::desc::ObjectDesc;

use super::desc::{TerrainKind, TownDesc};
use super::layout::{Layout, Rect};
use super::materials::{TOWER_FRAMES, WALLS};
use super::parts::{class, cuboid, ground_quad, instance, repeated, slab, Label};
use super::rng::{tag, Rng};
use super::vegetation::{self, Plant};

/// Floor height, metres.
pub const FLOOR_M: f64 = 3.2;
/// Gap between a building and the sidewalk, metres.
const SETBACK_M: f64 = 1.0;
/// First instance id of buildings.
pub const BUILDING_ID_BASE: u16 = 1000;

/// Every building, park and lot planting of the town.
pub fn block_objects(desc: &TownDesc, l: &Layout, seed: u64) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    let mut next_id = BUILDING_ID_BASE;
    for j in (0..l.ny).filter(|&j| Some(j) != l.river_row) {
        for i in 0..l.nx {
            let mut r = Rng::new(&[seed, tag::BLOCK, i as u64, j as u64]);
            let a = l.block_interior(i, j);
            let lot = Rect {
                min: [a.min[0] + SETBACK_M, a.min[1] + SETBACK_M],
                max: [a.max[0] - SETBACK_M, a.max[1] - SETBACK_M],
            };
            if desc.terrain == TerrainKind::Field && !r.chance(desc.building_density) {
                super::farms::field_block(&lot, &mut r, &mut next_id, &mut out);
                continue;
            }
            if r.chance(desc.vegetation_density * 0.25) || desc.building_density == 0.0 {
                park(desc, l, &lot, &mut r, &mut out);
                continue;
            }
            for row in lot_rows(&lot, &mut r) {
                let ids = &mut next_id;
                row_of_plots(desc, l, lot.min[0]..lot.max[0], row, &mut r, ids, &mut out);
            }
        }
    }
    out
}

/// The rows of plots of a built block, as (y0, y1, south): one row facing
/// south on a shallow lot, else a row along each of its two streets.
fn lot_rows(lot: &Rect, r: &mut Rng) -> Vec<(f64, f64, bool)> {
    let depth_total = lot.size()[1];
    if depth_total < 24.0 {
        vec![(lot.min[1], lot.max[1], true)]
    } else {
        let d1 = r.range(10.0, 18.0).min(depth_total / 2.0 - 1.0);
        let d2 = r.range(10.0, 18.0).min(depth_total / 2.0 - 1.0);
        vec![
            (lot.min[1], lot.min[1] + d1, true),
            (lot.max[1] - d2, lot.max[1], false),
        ]
    }
}

/// Plots 10–24 m wide along one row over `xs` (sometimes with a gap), each
/// holding a building (ids from `next_id`), a bush or nothing; none where
/// the roundabout reaches.
fn row_of_plots(
    desc: &TownDesc,
    l: &Layout,
    xs: Range<f64>,
    (y0, y1, south): (f64, f64, bool),
    r: &mut Rng,
    next_id: &mut u16,
    out: &mut Vec<ObjectDesc>,
) {
    let mut x = xs.start;
    while xs.end - x > 6.0 {
        let mut w = r.range(10.0, 24.0);
        if xs.end - (x + w) < 8.0 {
            w = xs.end - x;
        }
        let plot = Rect {
            min: [x, y0],
            max: [x + w, y1],
        };
        if l.near_roundabout(&plot) {
            // The roundabout's ring and sidewalk reach here.
        } else if r.chance(desc.building_density) {
            let id = Label {
                class: "building",
                instance: *next_id,
            };
            *next_id = next_id.saturating_add(1);
            building(desc, &plot, south, r, id, out);
        } else if r.chance(desc.vegetation_density) {
            let c = plot.center();
            out.push(vegetation::place(Plant::Bush, [c[0], c[1], 0.0], 0.0, 0));
        }
        x += w + if r.chance(0.4) {
            r.range(1.5, 4.0)
        } else {
            0.0
        };
    }
}

fn park(desc: &TownDesc, l: &Layout, lot: &Rect, r: &mut Rng, out: &mut Vec<ObjectDesc>) {
    out.push(ground_quad(
        lot.min,
        lot.max,
        -0.01,
        "lawn",
        class("terrain"),
    ));
    let [w, h] = lot.size();
    let n = ((w * h / 120.0) * desc.vegetation_density).round() as usize;
    for _ in 0..n {
        let at = [
            r.range(lot.min[0] + 2.0, lot.max[0] - 2.0),
            r.range(lot.min[1] + 2.0, lot.max[1] - 2.0),
            0.0,
        ];
        let plant = vegetation::PARK[r.index(vegetation::PARK.len())];
        if l.near_roundabout(&Rect::centered([at[0], at[1]], [3.0, 3.0])) {
            continue;
        }
        out.push(vegetation::place(plant, at, r.range(0.0, 360.0), 0));
    }
}

/// One building on `plot`: body, roof, balconies, floor ledges, then each
/// facade's windows (or a tower's curtain wall) and the street front.
fn building(
    desc: &TownDesc,
    plot: &Rect,
    south: bool,
    r: &mut Rng,
    id: Label,
    out: &mut Vec<ObjectDesc>,
) {
    let tower = r.chance(desc.tower_fraction);
    let floors = floor_count(desc, tower, r);
    let h = floors as f64 * FLOOR_M;
    let [w, d] = plot.size();
    let (cx, cy) = (plot.center()[0], plot.center()[1]);
    let wall = if tower {
        TOWER_FRAMES[r.index(TOWER_FRAMES.len())]
    } else {
        WALLS[r.index(WALLS.len())]
    };
    out.push(slab(plot.min, plot.max, 0.0, h, wall, id));
    out.push(roof(plot, h, tower, floors, r, id));
    if !tower && floors >= 3 && r.chance(0.4) {
        balconies(plot, south, floors, id, out);
    }
    if floors > 1 {
        let ledge = cuboid(
            [w + 0.3, d + 0.3, 0.2],
            [cx, cy, FLOOR_M],
            0.0,
            "window_frame",
            id,
        );
        out.push(repeated(ledge, &[(floors - 1, [0.0, 0.0, FLOOR_M])]));
    }
    // Facades: (centre of the wall line, heading of the window prefab, length).
    let facades = [
        ([cx, plot.min[1]], 0.0, w, south),
        ([plot.max[0], cy], 90.0, d, false),
        ([cx, plot.max[1]], 180.0, w, !south),
        ([plot.min[0], cy], 270.0, d, false),
    ];
    // Lit rooms: a per-building fraction of window rows shows a lit run.
    let mut lit = Rng::new(&[r.next_u64(), tag::LIT_WINDOWS]);
    let lit_fraction = lit.range(0.0, 0.35);
    for (c, heading, len, front) in facades {
        if tower {
            curtain_wall(c, heading, len, floors, id, out);
            continue;
        }
        let first_row = if front { 1 } else { 0 };
        let lit = (&mut lit, lit_fraction);
        facade_windows(c, heading, len, first_row..floors, lit, id, out);
        if front {
            shop_front(c, heading, len, id, out);
        }
    }
}

/// Floors of a building (a tower's from the tower range), skewed towards
/// the low end: most buildings are short.
fn floor_count(desc: &TownDesc, tower: bool, r: &mut Rng) -> u32 {
    let [lo, hi] = if tower {
        desc.tower_floors
    } else {
        desc.floors
    };
    lo + ((hi - lo + 1) as f64 * r.f64().powf(1.6))
        .floor()
        .min((hi - lo) as f64) as u32
}

/// The roof at height `h`: mostly a gable on low, shallow houses, else a
/// flat slab overhanging the walls by 0.2 m.
fn roof(plot: &Rect, h: f64, tower: bool, floors: u32, r: &mut Rng, id: Label) -> ObjectDesc {
    let d = plot.size()[1];
    if !tower && floors <= 2 && d <= 14.0 && r.chance(0.7) {
        gable_roof(plot, h, id)
    } else {
        let roof = [plot.min[0] - 0.2, plot.min[1] - 0.2];
        let roof_max = [plot.max[0] + 0.2, plot.max[1] + 0.2];
        slab(roof, roof_max, h, h + 0.4, "roof", id)
    }
}

/// Windows every 3 m along the facade centred at `c` (window prefab heading
/// `heading`, wall length `len`) over the floors `rows`; in each row, with
/// the building's chance, a run of up to four lit rooms (`lit`: the
/// building's lit-room stream and fraction).
fn facade_windows(
    c: [f64; 2],
    heading: f64,
    len: f64,
    rows: Range<u32>,
    (lit, lit_fraction): (&mut Rng, f64),
    id: Label,
    out: &mut Vec<ObjectDesc>,
) {
    let cols = ((len - 1.5) / 3.0).floor().max(0.0) as u32;
    if cols == 0 || rows.is_empty() {
        return;
    }
    let along = heading_dir(heading);
    let start = -(cols as f64 - 1.0) * 3.0 / 2.0;
    let at = [
        c[0] + along[0] * start,
        c[1] + along[1] * start,
        rows.start as f64 * FLOOR_M + 1.7,
    ];
    let win = instance("window", at, heading, &[], id);
    let step = [along[0] * 3.0, along[1] * 3.0, 0.0];
    let floors = rows.end - rows.start;
    out.push(repeated(
        win,
        &[(cols, step), (floors, [0.0, 0.0, FLOOR_M])],
    ));
    for row in rows {
        if !lit.chance(lit_fraction) {
            continue;
        }
        let c0 = lit.int(0, cols - 1);
        let run = lit.int(1, (cols - c0).min(4));
        let a = start + c0 as f64 * 3.0;
        let at = [
            c[0] + along[0] * a,
            c[1] + along[1] * a,
            row as f64 * FLOOR_M + 1.7,
        ];
        let light = instance("window_light", at, heading, &[], id);
        out.push(repeated(light, &[(run, step)]));
    }
}

/// The street front of the facade centred at `c`: a door in the middle,
/// shop windows (glass before a dark interior) either side where the wall
/// is long enough, and a canopy over the door.
fn shop_front(c: [f64; 2], heading: f64, len: f64, id: Label, out: &mut Vec<ObjectDesc>) {
    let along = heading_dir(heading);
    let n = normal_out(heading);
    let door_at = [c[0] + n[0] * 0.03, c[1] + n[1] * 0.03, 1.25];
    out.push(cuboid([1.6, 0.1, 2.5], door_at, heading, "door", id));
    for side in [-1.0, 1.0] {
        let off = side * (len / 4.0 + 0.4);
        if len / 2.0 - 1.6 > 2.0 {
            let shop_w = (len / 2.0 - 2.4).min(6.0);
            let at = [
                c[0] + along[0] * off + n[0] * 0.05,
                c[1] + along[1] * off + n[1] * 0.05,
                1.6,
            ];
            out.push(cuboid([shop_w, 0.04, 2.0], at, heading, "glass", id));
            let back = [at[0] - n[0] * 0.035, at[1] - n[1] * 0.035, 1.6];
            out.push(cuboid([shop_w, 0.02, 2.0], back, heading, "interior", id));
        }
    }
    let canopy = [c[0] + n[0] * 0.6, c[1] + n[1] * 0.6, 2.85];
    out.push(cuboid(
        [2.4, 1.2, 0.12],
        canopy,
        heading,
        "window_frame",
        id,
    ));
}

/// A 45° gable roof with its ridge along x (houses and barns): a square
/// prism turned 45° about x whose upper half (a triangle of half-width d/2) stands on the walls; the
/// lower half lies inside the body (or below the ground).
pub fn gable_roof(plot: &Rect, h: f64, id: Label) -> ObjectDesc {
    let [w, d] = plot.size();
    let c = plot.center();
    let side = d / std::f64::consts::SQRT_2;
    let mut o = cuboid([w + 0.3, side, side], [c[0], c[1], h], 0.0, "roof_tile", id);
    o.transform.rotate_deg = Some([45.0, 0.0, 0.0]);
    o
}

/// Balconies (slab and railing) on the street facade, every other window
/// column, from the second floor up.
fn balconies(plot: &Rect, south: bool, floors: u32, id: Label, out: &mut Vec<ObjectDesc>) {
    let w = plot.size()[0];
    let cols = ((w - 1.5) / 6.0).floor() as u32;
    if cols == 0 || floors < 3 {
        return;
    }
    let (wall_y, sign) = if south {
        (plot.min[1], -1.0)
    } else {
        (plot.max[1], 1.0)
    };
    let x0 = plot.center()[0] - (cols as f64 - 1.0) * 3.0;
    let slab_at = [x0, wall_y + sign * 0.6, 2.0 * FLOOR_M + 0.08];
    let rail_at = [x0, wall_y + sign * 1.17, 2.0 * FLOOR_M + 0.6];
    let levels = [(cols, [6.0, 0.0, 0.0]), (floors - 2, [0.0, 0.0, FLOOR_M])];
    out.push(repeated(
        cuboid([2.4, 1.2, 0.15], slab_at, 0.0, "concrete", id),
        &levels,
    ));
    out.push(repeated(
        cuboid([2.4, 0.05, 0.9], rail_at, 0.0, "steel_dark", id),
        &levels,
    ));
}

/// A tower facade: a glass band over the upper floors with mullions every 1.5 m.
fn curtain_wall(
    c: [f64; 2],
    heading: f64,
    len: f64,
    floors: u32,
    id: Label,
    out: &mut Vec<ObjectDesc>,
) {
    let n = normal_out(heading);
    let along = heading_dir(heading);
    let h = (floors - 1) as f64 * FLOOR_M;
    let z = FLOOR_M + h / 2.0;
    let glass_at = [c[0] + n[0] * 0.06, c[1] + n[1] * 0.06, z];
    out.push(cuboid(
        [len - 1.0, 0.04, h - 0.4],
        glass_at,
        heading,
        "glass_tower",
        id,
    ));
    let cols = ((len - 1.0) / 1.5).floor() as u32;
    if cols > 1 {
        let start = -(cols as f64 - 1.0) * 1.5 / 2.0;
        let at = [
            c[0] + along[0] * start + n[0] * 0.1,
            c[1] + along[1] * start + n[1] * 0.1,
            z,
        ];
        let mullion = cuboid([0.08, 0.12, h - 0.4], at, heading, "steel_dark", id);
        out.push(repeated(
            mullion,
            &[(cols, [along[0] * 1.5, along[1] * 1.5, 0.0])],
        ));
    }
    // Ground floor: a glazed lobby.
    let lobby = [c[0] + n[0] * 0.03, c[1] + n[1] * 0.03, 1.5];
    out.push(cuboid(
        [len - 2.0, 0.04, 2.6],
        lobby,
        heading,
        "glass_tower",
        id,
    ));
}

/// Unit vector along a facade whose window prefab has heading `deg` (the
/// prefab's local +x in the world).
fn heading_dir(deg: f64) -> [f64; 2] {
    let a = deg.to_radians();
    [a.cos().round(), a.sin().round()]
}

/// Outward normal of a facade (the prefab's local −y in the world).
fn normal_out(deg: f64) -> [f64; 2] {
    let a = deg.to_radians();
    [a.sin().round(), -a.cos().round()]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn town01() -> TownDesc {
        crate::town::source::load_named_town("town01", None)
            .unwrap()
            .desc
    }

    const ID: Label = Label {
        class: "building",
        instance: 1001,
    };

    #[test]
    fn floors_stay_in_their_range_and_most_buildings_are_short() {
        let mut desc = town01();
        (desc.floors, desc.tower_floors) = ([2, 6], [10, 30]);
        for (tower, [lo, hi]) in [(false, [2, 6]), (true, [10, 30])] {
            let mut r = Rng::new(&[1, 2]);
            let n: Vec<u32> = (0..2000)
                .map(|_| floor_count(&desc, tower, &mut r))
                .collect();
            assert_eq!(n.iter().min(), Some(&lo), "tower {tower}");
            assert_eq!(n.iter().max(), Some(&hi), "tower {tower}");
            // u^1.6 has mean 1/2.6: the mean lies well below the midpoint.
            let mean = n.iter().sum::<u32>() as f64 / n.len() as f64;
            let skewed = (lo + hi) as f64 / 2.0 - 0.1 * (hi - lo) as f64;
            assert!(mean < skewed, "tower {tower}: mean {mean} ≥ {skewed}");
        }
    }

    #[test]
    fn a_shallow_lot_holds_one_south_row_and_a_deep_lot_one_row_per_street() {
        let mut r = Rng::new(&[3]);
        let shallow = Rect {
            min: [0.0, 0.0],
            max: [50.0, 20.0],
        };
        assert_eq!(lot_rows(&shallow, &mut r), vec![(0.0, 20.0, true)]);
        for (deep, gap) in [(60.0, 24.0), (24.0, 2.0)] {
            let lot = Rect {
                min: [0.0, 10.0],
                max: [50.0, 10.0 + deep],
            };
            for _ in 0..50 {
                let rows = lot_rows(&lot, &mut r);
                let [(s0, s1, south), (n0, n1, north_faces_south)] = rows[..] else {
                    panic!("{deep} m deep: {rows:?}");
                };
                assert!(south && !north_faces_south);
                assert_eq!((s0, n1), (10.0, 10.0 + deep));
                for d in [s1 - s0, n1 - n0] {
                    assert!(d <= 18.0 && d >= 10.0_f64.min(deep / 2.0 - 1.0), "{d}");
                }
                assert!(n0 - s1 >= gap - 1e-9, "rows {rows:?}");
            }
        }
    }

    #[test]
    fn facade_windows_fill_the_wall_and_lit_runs_stay_in_their_row() {
        // A 10 m wall facing −y centred at (20, 5): two columns 3 m apart
        // ((10 − 1.5) / 3 = 2.8), rows on floors 1, 2 and 3.
        let (c, len) = ([20.0, 5.0], 10.0);
        let mut out = Vec::new();
        let mut dark = Rng::new(&[7]);
        facade_windows(c, 0.0, len, 1..4, (&mut dark, 0.0), ID, &mut out);
        assert_eq!(out.len(), 1);
        let counts: Vec<u32> = out[0].repeat.iter().map(|r| r.count).collect();
        assert_eq!(counts, vec![2, 3]);
        assert_eq!(out[0].repeat[0].offset, [3.0, 0.0, 0.0]);
        assert_eq!(out[0].transform.translate, Some([18.5, 5.0, FLOOR_M + 1.7]));
        // Every row lit: one run per row, at its height, inside the columns.
        let mut out = Vec::new();
        let mut lit = Rng::new(&[7]);
        facade_windows(c, 0.0, len, 1..4, (&mut lit, 1.0), ID, &mut out);
        assert_eq!(out.len(), 4);
        for (row, o) in (1..4).zip(&out[1..]) {
            let t = o.transform.translate.unwrap();
            assert_eq!(t[2], row as f64 * FLOOR_M + 1.7);
            let run = o.repeat.first().map_or(1, |r| r.count);
            assert!(
                t[0] >= 18.5 && t[0] + 3.0 * (run - 1) as f64 <= 21.5,
                "{t:?} × {run}"
            );
        }
        // No rows (a one-floor front) or a wall too short for a column: nothing.
        for (rows, len) in [(1..1, 10.0), (0..3, 4.0)] {
            let mut out = Vec::new();
            facade_windows(c, 0.0, len, rows, (&mut lit, 1.0), ID, &mut out);
            assert!(out.is_empty(), "{len} m: {out:?}");
        }
    }

    #[test]
    fn shop_windows_stand_only_on_a_long_front_with_glass_before_the_interior() {
        let front = |len: f64| {
            let mut out = Vec::new();
            shop_front([0.0, 5.0], 0.0, len, ID, &mut out);
            out
        };
        let long = front(20.0);
        let names: Vec<&str> = long
            .iter()
            .map(|o| o.material.as_deref().unwrap())
            .collect();
        assert_eq!(
            names,
            [
                "door",
                "glass",
                "interior",
                "glass",
                "interior",
                "window_frame"
            ]
        );
        // Heading 0: the wall faces −y, so the glass lies further out (lower y).
        let y = |o: &ObjectDesc| o.transform.translate.unwrap()[1];
        assert!(y(&long[1]) < y(&long[2]) && y(&long[2]) < 5.0);
        // The canopy stands 0.6 m out over the door.
        assert!((y(&long[5]) - 4.4).abs() < 1e-12);
        let short = front(6.0);
        let names: Vec<&str> = short
            .iter()
            .map(|o| o.material.as_deref().unwrap())
            .collect();
        assert_eq!(names, ["door", "window_frame"]);
    }
}
