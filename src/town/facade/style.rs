//! The façade styles: each a parameter set (floor height, window rhythm and
//! proportions, materials, ground floor, ornament, roof), and the seeded
//! choice of a style per building from the town's character (rural, small
//! town, city) and the building's floor count.
//!
//! Lengths in metres; a window's sill height is measured from its floor.

use crate::town::desc::{TerrainKind, TownDesc};
use crate::town::rng::Rng;

/// What stands on the street front's ground floor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ground {
    /// Shop units: large glazing, a door, an awning and a lettered sign.
    Shops,
    /// A front door with steps and a canopy; windows either side.
    Door,
    /// A glazed lobby with a glazed door (offices).
    Lobby,
    /// A roller door for vehicles and a side door (warehouses).
    Industrial,
}

/// The roof over the top floor.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Roof {
    /// A flat roof (with parapet, cornice and roof units as the style says).
    Flat,
    /// A 45° gable on a shallow building (≤ 14 m deep), else flat.
    Gable,
}

/// One façade style.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Style {
    /// Name (prefab names derive from it).
    pub name: &'static str,
    /// Floor-to-floor height.
    pub floor_m: f64,
    /// Width of one window bay (window spacing).
    pub bay_m: f64,
    /// Window opening width and height.
    pub window_m: [f64; 2],
    /// Height of the window opening's bottom above its floor.
    pub sill_m: f64,
    /// Depth of the glass's front face behind the wall plane (0.10–0.25).
    pub recess_m: f64,
    /// Wall materials; the bay prefabs are built in the first.
    pub walls: &'static [&'static str],
    /// Window frame material.
    pub frame: &'static str,
    /// Sills, lintels, cornices and string courses.
    pub trim: &'static str,
    /// Panes across a window (mullions + 1).
    pub panes: u32,
    /// Whether a window has a transom bar.
    pub transom: bool,
    /// Street front's ground floor.
    pub ground: Ground,
    /// Chance that a building has balconies.
    pub balcony: f64,
    /// A cornice under the roof line.
    pub cornice: bool,
    /// A string course at every floor line.
    pub string_course: bool,
    /// Parapet height on a flat roof (0: none).
    pub parapet_m: f64,
    /// Roof kind.
    pub roof: Roof,
    /// Most roof units (AC boxes, vents, tanks, stair huts) on a flat roof.
    pub roof_units: u32,
    /// Drainpipes at the ends of the street front.
    pub drainpipe: bool,
    /// Floor counts the style suits (inclusive).
    pub floors: [u32; 2],
}

const BRICKS: &[&str] = &["brick_red", "brick_brown", "facade_brick_yellow"];
const PLASTERS: &[&str] = &[
    "plaster_cream",
    "plaster_white",
    "plaster_blue",
    "plaster_ochre",
    "facade_plaster_pink",
];

/// The ten styles, in a fixed order (indices are stable).
pub const STYLES: [Style; 10] = [
    Style {
        name: "brick_terrace",
        floor_m: 3.0,
        bay_m: 2.6,
        window_m: [1.0, 1.5],
        sill_m: 0.85,
        recess_m: 0.15,
        walls: BRICKS,
        frame: "window_frame",
        trim: "stone",
        panes: 2,
        transom: true,
        ground: Ground::Door,
        balcony: 0.0,
        cornice: false,
        string_course: false,
        parapet_m: 0.6,
        roof: Roof::Gable,
        roof_units: 1,
        drainpipe: true,
        floors: [1, 4],
    },
    Style {
        name: "stucco_townhouse",
        floor_m: 3.4,
        bay_m: 2.8,
        window_m: [1.1, 2.0],
        sill_m: 0.7,
        recess_m: 0.2,
        walls: PLASTERS,
        frame: "window_frame",
        trim: "plaster_white",
        panes: 2,
        transom: false,
        ground: Ground::Door,
        balcony: 0.6,
        cornice: true,
        string_course: true,
        parapet_m: 0.5,
        roof: Roof::Flat,
        roof_units: 1,
        drainpipe: true,
        floors: [2, 5],
    },
    Style {
        name: "glass_office",
        floor_m: 3.8,
        bay_m: 3.0,
        window_m: [2.9, 2.9],
        sill_m: 0.55,
        recess_m: 0.12,
        walls: &["concrete", "facade_concrete_dark", "steel_dark"],
        frame: "facade_metal_dark",
        trim: "facade_metal_dark",
        panes: 2,
        transom: false,
        ground: Ground::Lobby,
        balcony: 0.0,
        cornice: false,
        string_course: false,
        parapet_m: 1.0,
        roof: Roof::Flat,
        roof_units: 5,
        drainpipe: false,
        floors: [6, 99],
    },
    Style {
        name: "concrete_slab",
        floor_m: 2.9,
        bay_m: 3.6,
        window_m: [2.0, 1.4],
        sill_m: 0.9,
        recess_m: 0.1,
        walls: &["concrete", "facade_concrete_dark", "plaster_white"],
        frame: "facade_metal_dark",
        trim: "concrete",
        panes: 3,
        transom: false,
        ground: Ground::Door,
        balcony: 0.7,
        cornice: false,
        string_course: false,
        parapet_m: 0.4,
        roof: Roof::Flat,
        roof_units: 4,
        drainpipe: false,
        floors: [4, 99],
    },
    Style {
        name: "art_deco",
        floor_m: 3.6,
        bay_m: 2.4,
        window_m: [0.9, 2.2],
        sill_m: 0.75,
        recess_m: 0.22,
        walls: &["stone", "facade_sandstone", "plaster_cream"],
        frame: "facade_metal_dark",
        trim: "facade_sandstone",
        panes: 1,
        transom: true,
        ground: Ground::Shops,
        balcony: 0.0,
        cornice: true,
        string_course: true,
        parapet_m: 1.2,
        roof: Roof::Flat,
        roof_units: 2,
        drainpipe: false,
        floors: [4, 99],
    },
    Style {
        name: "shop_row",
        floor_m: 3.2,
        bay_m: 3.0,
        window_m: [1.2, 1.6],
        sill_m: 0.85,
        recess_m: 0.14,
        walls: &[
            "brick_red",
            "plaster_cream",
            "plaster_ochre",
            "facade_brick_yellow",
        ],
        frame: "window_frame",
        trim: "plaster_white",
        panes: 2,
        transom: true,
        ground: Ground::Shops,
        balcony: 0.2,
        cornice: true,
        string_course: false,
        parapet_m: 0.7,
        roof: Roof::Flat,
        roof_units: 2,
        drainpipe: true,
        floors: [1, 4],
    },
    Style {
        name: "warehouse",
        floor_m: 4.5,
        bay_m: 4.0,
        window_m: [2.4, 1.2],
        sill_m: 2.6,
        recess_m: 0.12,
        walls: &["brick_brown", "facade_cladding", "concrete"],
        frame: "facade_metal_dark",
        trim: "concrete",
        panes: 4,
        transom: false,
        ground: Ground::Industrial,
        balcony: 0.0,
        cornice: false,
        string_course: false,
        parapet_m: 0.3,
        roof: Roof::Flat,
        roof_units: 4,
        drainpipe: true,
        floors: [1, 2],
    },
    Style {
        name: "suburban_house",
        floor_m: 2.9,
        bay_m: 3.0,
        window_m: [1.3, 1.25],
        sill_m: 0.9,
        recess_m: 0.1,
        walls: &[
            "facade_wood_siding",
            "plaster_white",
            "plaster_cream",
            "brick_red",
        ],
        frame: "window_frame",
        trim: "window_frame",
        panes: 2,
        transom: false,
        ground: Ground::Door,
        balcony: 0.0,
        cornice: false,
        string_course: false,
        parapet_m: 0.0,
        roof: Roof::Gable,
        roof_units: 0,
        drainpipe: true,
        floors: [1, 2],
    },
    Style {
        name: "stone_civic",
        floor_m: 4.2,
        bay_m: 3.2,
        window_m: [1.4, 2.6],
        sill_m: 0.8,
        recess_m: 0.25,
        walls: &["stone", "facade_sandstone"],
        frame: "facade_wood",
        trim: "facade_sandstone",
        panes: 2,
        transom: true,
        ground: Ground::Door,
        balcony: 0.0,
        cornice: true,
        string_course: true,
        parapet_m: 0.9,
        roof: Roof::Flat,
        roof_units: 1,
        drainpipe: false,
        floors: [2, 5],
    },
    Style {
        name: "modern_mixed",
        floor_m: 3.3,
        bay_m: 2.7,
        window_m: [1.8, 2.1],
        sill_m: 0.5,
        recess_m: 0.18,
        walls: &[
            "plaster_white",
            "facade_concrete_dark",
            "facade_wood_siding",
        ],
        frame: "facade_metal_dark",
        trim: "facade_metal_dark",
        panes: 1,
        transom: false,
        ground: Ground::Shops,
        balcony: 0.5,
        cornice: false,
        string_course: false,
        parapet_m: 0.8,
        roof: Roof::Flat,
        roof_units: 3,
        drainpipe: false,
        floors: [3, 99],
    },
];

/// Style weights (same order as `STYLES`) of a town's character: rural
/// (fields or sparse), small town (low buildings), city.
fn town_weights(desc: &TownDesc) -> [f64; 10] {
    if desc.terrain == TerrainKind::Field || desc.building_density < 0.2 {
        [2.0, 1.0, 0.0, 0.0, 0.0, 0.5, 3.0, 4.0, 0.5, 0.0]
    } else if desc.floors[1] <= 3 && desc.tower_fraction == 0.0 {
        [3.0, 2.0, 0.0, 0.0, 0.0, 3.0, 1.0, 3.0, 1.0, 0.5]
    } else {
        [2.0, 2.0, 3.0, 2.0, 2.0, 3.0, 0.5, 0.5, 1.0, 3.0]
    }
}

/// The style of a building with `floors` floors in the town `desc` (a
/// tower prefers the office styles): a weighted draw among the styles that
/// suit the floor count, falling back to every style that suits it.
pub fn choose(desc: &TownDesc, floors: u32, tower: bool, r: &mut Rng) -> &'static Style {
    let fits = |s: &Style| (s.floors[0]..=s.floors[1]).contains(&floors);
    let mut w = town_weights(desc);
    if tower {
        w[2] += 6.0;
    }
    for (wi, s) in w.iter_mut().zip(&STYLES) {
        if !fits(s) {
            *wi = 0.0;
        }
    }
    if w.iter().sum::<f64>() == 0.0 {
        for (wi, s) in w.iter_mut().zip(&STYLES) {
            *wi = if fits(s) { 1.0 } else { 0.0 };
        }
    }
    let mut u = r.f64() * w.iter().sum::<f64>();
    for (wi, s) in w.iter().zip(&STYLES) {
        if *wi > 0.0 && u < *wi {
            return s;
        }
        u -= wi;
    }
    // Rounding at the top of the range: the last style that fits.
    STYLES.iter().rev().find(|s| fits(s)).unwrap_or(&STYLES[0])
}
