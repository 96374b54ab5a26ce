//! The outskirts of a town (`outskirts = true`): a street front on the far
//! side of every outer road, and a line of trees past the ends of the road
//! stubs, so that a view out of the town meets buildings and trees as in a
//! real street instead of an empty field up to the horizon.
//!
//! Lots lie beyond the outer sidewalks (a `SETBACK_M` gap, as on the
//! blocks): one row of plots along the south and the north outer x-roads
//! over the town's width and its stubs, its fronts facing the road, and a
//! block between each pair of stubs east and west of the town, with a row
//! along each stub. The river's row keeps its banks clear. Plots are filled
//! by the blocks' own plot rule (`buildings::row_of_plots`), so the
//! outskirts share the town's massing and styles, but every plot holds a
//! building. World frame, metres, z up.

use crate::scene::desc::ObjectDesc;

use super::buildings::{lot_rows, row_of_plots, SETBACK_M};
use super::desc::TownDesc;
use super::layout::{Layout, Rect, STUB_M};
use super::rng::{tag, Rng};
use super::vegetation::{self, Plant, Species};

/// Depth range of the outskirt rows along the outer x-roads, metres.
const ROW_DEPTH_M: [f64; 2] = [12.0, 20.0];
/// Distance of the tree line past the end of the road stubs, metres.
const TREE_LINE_M: f64 = 8.0;
/// Spacing of the trees along the tree line, metres.
const TREE_SPACING_M: f64 = 9.0;
/// Trees of the tree line.
const TREE_LINE: [Species; 3] = [Species::Plane, Species::Oak, Species::Spruce];

/// Every building and tree of the outskirts, building ids from `next_id`;
/// nothing unless `desc.outskirts`.
pub fn outskirt_objects(
    desc: &TownDesc,
    l: &Layout,
    seed: u64,
    next_id: &mut u16,
) -> Vec<ObjectDesc> {
    let mut out = Vec::new();
    if !desc.outskirts {
        return out;
    }
    // Every plot built (gaps only between plots), so that the view across
    // a T junction at the town's edge ends at a front.
    let desc = &TownDesc {
        building_density: 1.0,
        ..desc.clone()
    };
    let mut r = Rng::new(&[seed, tag::BLOCK, u64::MAX]);
    for lot in street_front_lots(l, &mut r) {
        let (y0, y1) = (lot.rect.min[1], lot.rect.max[1]);
        let xs = lot.rect.min[0]..lot.rect.max[0];
        row_of_plots(
            desc,
            l,
            xs,
            (y0, y1, lot.faces_south),
            &mut r,
            next_id,
            &mut out,
        );
    }
    for lot in stub_blocks(l) {
        for row in lot_rows(&lot, &mut r) {
            let xs = lot.min[0]..lot.max[0];
            row_of_plots(desc, l, xs, row, &mut r, next_id, &mut out);
        }
    }
    out.extend(tree_lines(l, seed));
    out
}

/// A row of plots along an outer x-road: its rectangle, and whether its
/// fronts face south (−y).
#[derive(Clone, Copy, Debug, PartialEq)]
struct FrontLot {
    rect: Rect,
    faces_south: bool,
}

/// The rows beyond the south and the north outer x-roads, over the town's
/// width and its stubs.
fn street_front_lots(l: &Layout, r: &mut Rng) -> [FrontLot; 2] {
    let edge = l.road_w_m / 2.0 + l.sidewalk_m + SETBACK_M;
    let (x0, x1) = (-STUB_M, l.len_x() + STUB_M);
    let south_depth = r.range(ROW_DEPTH_M[0], ROW_DEPTH_M[1]);
    let north_depth = r.range(ROW_DEPTH_M[0], ROW_DEPTH_M[1]);
    let top = l.len_y() + edge;
    [
        FrontLot {
            rect: Rect {
                min: [x0, -edge - south_depth],
                max: [x1, -edge],
            },
            faces_south: false,
        },
        FrontLot {
            rect: Rect {
                min: [x0, top],
                max: [x1, top + north_depth],
            },
            faces_south: true,
        },
    ]
}

/// The blocks between consecutive road stubs east and west of the town,
/// from the outer y-road's far sidewalk to 2 m short of the stubs' ends;
/// none in the river's row.
fn stub_blocks(l: &Layout) -> Vec<Rect> {
    let edge = l.road_w_m / 2.0 + l.sidewalk_m + SETBACK_M;
    let (p, e) = (l.pitch_m, l.len_x());
    let mut out = Vec::new();
    if STUB_M - 2.0 - edge < 6.0 {
        return out;
    }
    for j in (0..l.ny).filter(|&j| Some(j) != l.river_row) {
        let (y0, y1) = (j as f64 * p + edge, (j + 1) as f64 * p - edge);
        for (x0, x1) in [(-STUB_M + 2.0, -edge), (e + edge, e + STUB_M - 2.0)] {
            out.push(Rect {
                min: [x0, y0],
                max: [x1, y1],
            });
        }
    }
    out
}

/// A line of trees across each end of the stubs (east and west), over the
/// depth of the outskirt rows; none in the river band.
fn tree_lines(l: &Layout, seed: u64) -> Vec<ObjectDesc> {
    let reach = l.road_w_m / 2.0 + l.sidewalk_m + SETBACK_M + ROW_DEPTH_M[1];
    let (y0, y1) = (-reach, l.len_y() + reach);
    let n = ((y1 - y0) / TREE_SPACING_M).floor() as usize;
    let band = l.river_band();
    let mut out = Vec::new();
    for x in [-STUB_M - TREE_LINE_M, l.len_x() + STUB_M + TREE_LINE_M] {
        let mut r = Rng::new(&[seed, tag::TREES, x.to_bits()]);
        for k in 0..=n {
            let y = y0 + k as f64 * TREE_SPACING_M + r.range(-1.5, 1.5);
            let x = x + r.range(-2.0, 2.0);
            let in_river = band.is_some_and(|b| y > b.min[1] - 4.0 && y < b.max[1] + 4.0);
            if in_river {
                continue;
            }
            let species = TREE_LINE[r.index(TREE_LINE.len())];
            let heading = r.range(0.0, 360.0);
            out.push(vegetation::place(
                Plant::Tree(species),
                [x, y, 0.0],
                heading,
                seed,
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::town::desc::RoadStyle;
    use crate::town::source::load_named_town;

    fn town(name: &str) -> (TownDesc, Layout) {
        let desc = load_named_town(name, None).unwrap().desc;
        let l = Layout::new(&desc);
        (desc, l)
    }

    /// Every lot of the outskirts lies outside the roads and sidewalks (the
    /// stubs included) and outside the town's blocks.
    #[test]
    fn outskirt_lots_keep_off_every_road_sidewalk_and_block() {
        let (_, l) = town("town10");
        let mut r = Rng::new(&[1]);
        let lots: Vec<Rect> = street_front_lots(&l, &mut r)
            .iter()
            .map(|f| f.rect)
            .chain(stub_blocks(&l))
            .collect();
        assert_eq!(lots.len(), 2 + 2 * l.ny);
        let walk = l.road_w_m / 2.0 + l.sidewalk_m;
        let grown = |r: Rect| Rect {
            min: [r.min[0], r.min[1] - l.sidewalk_m],
            max: [r.max[0], r.max[1] + l.sidewalk_m],
        };
        for lot in &lots {
            for j in 0..=l.ny {
                let y = j as f64 * l.pitch_m;
                let road = Rect {
                    min: [-STUB_M, y - walk],
                    max: [l.len_x() + STUB_M, y + walk],
                };
                assert!(!lot.overlaps(&road), "{lot:?} on x-road {j}");
            }
            for i in 0..=l.nx {
                assert!(!lot.overlaps(&grown(l.y_road(i))), "{lot:?} on y-road {i}");
            }
            let town = Rect {
                min: [-walk, -walk],
                max: [l.len_x() + walk, l.len_y() + walk],
            };
            assert!(!lot.overlaps(&town), "{lot:?} inside the town");
        }
    }

    /// The outskirts hold buildings on both sides and trees past the stubs,
    /// every building's footprint on an outskirt lot; a town without the
    /// key has none.
    #[test]
    fn outskirts_hold_buildings_beyond_the_outer_roads_only_when_asked() {
        let (mut desc, l) = town("town10");
        desc.outskirts = true;
        let mut id = 4000;
        let objects = outskirt_objects(&desc, &l, 3, &mut id);
        let walk = l.road_w_m / 2.0 + l.sidewalk_m;
        let at = |o: &ObjectDesc| o.transform.translate.unwrap_or_default();
        let buildings: Vec<_> = objects
            .iter()
            .filter(|o| o.semantic.as_deref() == Some("building"))
            .collect();
        let south = buildings.iter().filter(|o| at(o)[1] < -walk).count();
        let north = buildings
            .iter()
            .filter(|o| at(o)[1] > l.len_y() + walk)
            .count();
        let east = buildings
            .iter()
            .filter(|o| at(o)[0] > l.len_x() + walk)
            .count();
        assert!(
            south > 10 && north > 10 && east > 3,
            "{south} {north} {east}"
        );
        for b in &buildings {
            let [x, y, _] = at(b);
            let inside = x > -walk && x < l.len_x() + walk && y > -walk && y < l.len_y() + walk;
            assert!(!inside, "a building at ({x}, {y}) inside the town");
        }
        assert!(id > 4000 + 20, "ids {id}");
        let trees = objects
            .iter()
            .filter(|o| o.semantic.as_deref() == Some("vegetation"))
            .filter(|o| at(o)[0] > l.len_x() + STUB_M || at(o)[0] < -STUB_M)
            .count();
        assert!(
            trees >= 2 * (l.len_y() / TREE_SPACING_M) as usize,
            "{trees} trees"
        );
        desc.outskirts = false;
        assert!(outskirt_objects(&desc, &l, 3, &mut id).is_empty());
    }

    /// The river's row keeps both banks clear beyond the town.
    #[test]
    fn the_river_row_has_no_outskirt_block_and_no_tree_in_the_water() {
        let (mut desc, l) = town("town01");
        desc.outskirts = true;
        let band = l.river_band().expect("town01 has a river");
        for lot in stub_blocks(&l) {
            assert!(!lot.overlaps(&band), "{lot:?} in the river band {band:?}");
        }
        for t in tree_lines(&l, 9) {
            let y = t.transform.translate.unwrap()[1];
            assert!(
                y < band.min[1] || y > band.max[1],
                "a tree at y = {y} in the river"
            );
        }
    }

    /// The key is refused where the outskirts cannot lie level beside the
    /// outer roads (hills, highways, fields), with a message naming it, and
    /// allowed in a level grid or organic town (town03 is organic).
    #[test]
    fn outskirts_are_refused_on_hills_highways_and_fields() {
        for name in ["town04", "town06", "town07"] {
            let (mut desc, _) = town(name);
            desc.outskirts = true;
            let err = desc.validate().unwrap_err();
            assert!(
                err.starts_with("outskirts: needs a level grid or organic town"),
                "{name}: {err}"
            );
        }
        let (mut desc, _) = town("town02");
        desc.outskirts = true;
        desc.validate().unwrap();
        let (desc, _) = town("town03");
        assert_eq!(desc.road_style, RoadStyle::Organic);
        assert!(desc.outskirts);
        desc.validate().unwrap();
    }
}
