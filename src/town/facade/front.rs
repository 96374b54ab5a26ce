//! The street front's ground floor: which bay stands in each column (shop
//! units of shopfronts and a door, a front door among windows, a lobby, a
//! roller door), and the shop signs (procedural lettering on a board, one
//! prefab per shop name) and awnings (plain or striped, one prefab per
//! style, coloured per shop by material renames).
//!
//! Sign and awning frames as the bay prefabs' (`bay`): wall plane y = 0,
//! outside −y. Shop names come from a fixed word list, picked by seed.

use crate::scene::desc::ObjectDesc;
use crate::town::lettering::{layout, text_mesh};
use crate::town::parts::{class, cuboid, repeated};
use crate::town::rng::Rng;

use super::bay::boxed;
use super::style::{Ground, Style};

/// Shop names the signs draw from.
pub const SHOP_NAMES: [&str; 24] = [
    "BAKERY",
    "CAFE ROMA",
    "PHARMACY",
    "24 HOUR",
    "BOOKS",
    "FLOWERS",
    "DELI",
    "BARBER",
    "HARDWARE",
    "OPTICIAN",
    "LAUNDRY",
    "PIZZA",
    "BAR",
    "HOTEL",
    "BANK",
    "MARKET",
    "SHOES",
    "NEWS",
    "FISH",
    "TOYS",
    "GELATO",
    "BISTRO",
    "TAILOR",
    "SUSHI",
];
/// Cap height of a sign's letters.
pub const CAP_M: f64 = 0.3;
/// Height of a sign board.
pub const BOARD_M: f64 = 0.5;
/// Board material renames of a shop (the prefabs use the first).
pub const BOARDS: [&str; 3] = ["facade_sign_green", "facade_sign_red", "facade_sign_navy"];
/// Awning colours of a shop (the prefabs use the first).
pub const AWNINGS: [&str; 4] = [
    "facade_awning_red",
    "facade_awning_green",
    "facade_awning_blue",
    "facade_awning_ochre",
];
/// How far an awning reaches out from the wall, and how far it drops.
pub const AWNING_REACH_M: f64 = 1.2;
const AWNING_DROP_M: f64 = 0.5;

/// One ground-floor column of the street front.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroundBay {
    /// A window bay of the given variant.
    Window(u32),
    /// A shopfront (or lobby glazing).
    Shop,
    /// A door (with steps).
    Door,
    /// A roller door.
    Roller,
}

/// A shop unit: its first column, its number of columns, and its name.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShopUnit {
    /// First column.
    pub first: u32,
    /// Columns (door included).
    pub cols: u32,
    /// Index into `SHOP_NAMES`, if a name fits over the unit.
    pub name: Option<usize>,
}

/// The ground floor of a street front of `cols` columns: one bay per
/// column, and the shop units (empty unless the style has shops).
pub fn ground_plan(s: &Style, cols: u32, r: &mut Rng) -> (Vec<GroundBay>, Vec<ShopUnit>) {
    let mid = cols / 2;
    let mut plan: Vec<GroundBay> = (0..cols).map(|_| GroundBay::Window(r.int(0, 2))).collect();
    let mut units = Vec::new();
    match s.ground {
        _ if cols == 0 => {}
        Ground::Door => plan[mid as usize] = GroundBay::Door,
        Ground::Lobby => {
            plan.iter_mut().for_each(|b| *b = GroundBay::Shop);
            plan[mid as usize] = GroundBay::Door;
        }
        Ground::Industrial => {
            plan[mid as usize] = GroundBay::Roller;
            if cols > 1 {
                plan[(mid as usize + 1) % cols as usize] = GroundBay::Door;
            }
        }
        Ground::Shops => {
            let mut first = 0;
            while first < cols {
                let mut n = r.int(2, 4).min(cols - first);
                if cols - first - n == 1 {
                    n += 1; // no one-column unit at the end
                }
                let door = if r.chance(0.5) { first } else { first + n - 1 };
                for c in first..first + n {
                    plan[c as usize] = if c == door {
                        GroundBay::Door
                    } else {
                        GroundBay::Shop
                    };
                }
                let fits: Vec<usize> = (0..SHOP_NAMES.len())
                    .filter(|&k| sign_width(k) <= n as f64 * s.bay_m - 0.3)
                    .collect();
                let name = (!fits.is_empty()).then(|| fits[r.index(fits.len())]);
                units.push(ShopUnit {
                    first,
                    cols: n,
                    name,
                });
                first += n;
            }
        }
    }
    (plan, units)
}

/// Width of the board of shop name `k`.
pub fn sign_width(k: usize) -> f64 {
    layout(SHOP_NAMES[k], CAP_M).width + 0.4
}

/// The sign of shop name `k`: a board 5 cm proud of the wall (bottom at
/// z = 0, centred on x = 0) with raised letters 3 cm deep on its face.
pub fn sign(k: usize) -> Vec<ObjectDesc> {
    let b = class("building");
    let w = sign_width(k);
    let board = boxed(
        [-w / 2.0, -0.05, 0.0],
        [w / 2.0, 0.0, BOARD_M],
        BOARDS[0],
        b,
    );
    let text = text_mesh(SHOP_NAMES[k], CAP_M, 0.03);
    let x0 = -(w - 0.4) / 2.0;
    let z0 = (BOARD_M - CAP_M) / 2.0;
    // Text plane (x right, y up, z out) → bay frame (x, −y out, z up): a
    // quarter turn about x, which keeps the winding.
    let positions = text
        .positions
        .iter()
        .map(|p| [x0 + p.x, -0.05 - p.z, z0 + p.y])
        .collect();
    let letters = ObjectDesc {
        name: None,
        material: Some("facade_letter".to_string()),
        semantic: Some("building".to_string()),
        instance: None,
        transform: Default::default(),
        repeat: Vec::new(),
        shape: crate::scene::desc::ShapeDesc::Mesh {
            positions,
            normals: Vec::new(),
            triangles: text.triangles,
        },
    };
    vec![board, letters]
}

/// An awning one bay wide of style `s`, its top edge on the wall at z = 0
/// sloping out and down, with a valance: plain, or striped with white.
pub fn awning(s: &Style, striped: bool) -> Vec<ObjectDesc> {
    let b = class("building");
    let w = s.bay_m - 0.1;
    let (reach, drop) = (AWNING_REACH_M, AWNING_DROP_M);
    let len = reach.hypot(drop);
    let tilt = drop.atan2(reach).to_degrees();
    let (a, white) = (AWNINGS[0], "facade_awning_white");
    let n = 8u32;
    let sw = w / n as f64;
    let stripe = |k: u32, count: u32, m: &str| {
        let x = -w / 2.0 + sw * (k as f64 + 0.5);
        let mut o = cuboid([sw, len, 0.02], [x, -reach / 2.0, -drop / 2.0], 0.0, m, b);
        o.transform.rotate_deg = Some([tilt, 0.0, 0.0]);
        repeated(o, &[(count, [2.0 * sw, 0.0, 0.0])])
    };
    let mut out = if striped {
        vec![stripe(0, n / 2, a), stripe(1, n / 2, white)]
    } else {
        let mut o = cuboid([w, len, 0.02], [0.0, -reach / 2.0, -drop / 2.0], 0.0, a, b);
        o.transform.rotate_deg = Some([tilt, 0.0, 0.0]);
        vec![o]
    };
    out.push(boxed(
        [-w / 2.0, -reach - 0.02, -drop - 0.25],
        [w / 2.0, -reach, -drop],
        a,
        b,
    ));
    out
}
