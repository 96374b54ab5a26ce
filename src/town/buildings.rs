//! Buildings and parks on the blocks: rows of lots along the two streets of
//! each block, each lot holding a building or planting; a building's
//! massing (tower or not, floor count) is drawn here and the façade
//! generator (`town::facade`) builds its style, walls, windows, ground
//! floor, roof and ornament. Some blocks are parks.
//!
//! A building's front faces the street its row lines (−y for the south row,
//! +y for the north row).

use std::ops::Range;

use crate::scene::desc::ObjectDesc;

use super::desc::{TerrainKind, TownDesc};
use super::layout::{Layout, Rect};
use super::parts::{class, cuboid, ground_quad, Label};
use super::rng::{tag, Rng};
use super::vegetation::{self, Plant};

/// Gap between a building and the sidewalk, metres.
pub(super) const SETBACK_M: f64 = 1.0;
/// First instance id of buildings.
pub const BUILDING_ID_BASE: u16 = 1000;

/// Every building, park and lot planting of the town's blocks, building
/// ids from `next_id` (normally `BUILDING_ID_BASE`).
pub fn block_objects(desc: &TownDesc, l: &Layout, seed: u64, next_id: &mut u16) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    for j in (0..l.ny).filter(|&j| Some(j) != l.river_row) {
        for i in 0..l.nx {
            let mut r = Rng::new(&[seed, tag::BLOCK, i as u64, j as u64]);
            let a = l.block_interior(i, j);
            let lot = Rect {
                min: [a.min[0] + SETBACK_M, a.min[1] + SETBACK_M],
                max: [a.max[0] - SETBACK_M, a.max[1] - SETBACK_M],
            };
            if desc.terrain == TerrainKind::Field && !r.chance(desc.building_density) {
                super::farms::field_block(&lot, &mut r, next_id, &mut out);
                continue;
            }
            if r.chance(desc.vegetation_density * 0.25) || desc.building_density == 0.0 {
                park(desc, l, &lot, &mut r, &mut out);
                continue;
            }
            for row in lot_rows(&lot, &mut r) {
                row_of_plots(
                    desc,
                    l,
                    lot.min[0]..lot.max[0],
                    row,
                    &mut r,
                    next_id,
                    &mut out,
                );
            }
        }
    }
    out
}

/// The rows of plots of a built block, as (y0, y1, south): one row facing
/// south on a shallow lot, else a row along each of its two streets.
pub(super) fn lot_rows(lot: &Rect, r: &mut Rng) -> Vec<(f64, f64, bool)> {
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
pub(super) fn row_of_plots(
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

/// One building on `plot`: its massing (tower or not, floor count), then
/// its style, walls, roof and ornament from the façade generator.
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
    super::facade::building(desc, plot, south, floors, tower, r, id, out);
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

#[cfg(test)]
mod tests {
    use super::*;

    fn town01() -> TownDesc {
        crate::town::source::load_named_town("town01", None)
            .unwrap()
            .desc
    }

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
}
