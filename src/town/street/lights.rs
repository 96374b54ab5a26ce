//! Street lights and traffic lights. Three lamp-post styles (a modern
//! cobra head, a heritage lantern, a twin-arm highway mast), each lit by
//! the always-on `lamp_emit` emitter as the old street light was: a panel
//! under the head (open at the top, which faces the housing), or the
//! lantern's core. Traffic lights: signal heads
//! (back plate, housing, three lenses with visors) on a corner pole with a
//! short arm, or on a mast arm with one head over each of two lanes.
//!
//! Local frames (z up, origin at the foot): a lamp's arm reaches along
//! −y (the highway mast's both ways); a traffic light's arm along +y over
//! the approach lanes, its heads facing −x (the approaching traffic). The
//! lenses are separate objects with the material slots of
//! `props::LENS_SLOTS`, so `signals` can light one per frame; the lenses of
//! one head share their local y.

use glam::{DAffine3, DQuat, DVec3};

use crate::scene::desc::{ObjectDesc, PrefabDesc, TransformDesc};
use crate::scene::mesh::{self, cuboid, LocalMesh};
use crate::town::parts::{class, object};
use crate::town::props::LENS_SLOTS;

use super::kit::{prism, regular, Kit};
use super::prefab;

const POLE: &str = "pole";
const TL: &str = "traffic_light";
/// Names of the lamp-post prefabs, by style.
pub const LAMP_COBRA: &str = "lamp_cobra";
/// Heritage lantern on a fluted post.
pub const LAMP_HERITAGE: &str = "lamp_heritage";
/// Twin-arm highway mast.
pub const LAMP_HIGHWAY: &str = "lamp_highway";
/// Traffic light whose arm carries one head per lane of a two-lane
/// approach (`lanes_per_direction` ≥ 2).
pub const SIGNAL_MAST: &str = "traffic_light_mast";
/// Sides of a lens disc (a cylinder capped at the front: 3 triangles per
/// side).
pub const LENS_SEGMENTS: u32 = 12;
/// Vertical spacing of a head's lenses, metres.
const LENS_STEP_M: f64 = 0.33;

/// A box of `size` without its top face: a lamp panel's top would shine
/// into the gap under its housing, lighting nothing, and its upward
/// normal would keep the light tree from culling the lamp for points
/// above it.
fn open_top(size: [f64; 3]) -> LocalMesh {
    let mut m = cuboid(size);
    m.retain_triangles(|[a, b, c]| (b - a).cross(c - a).z <= 0.0);
    m
}

/// A signal lens: a disc of radius 0.1 m, 2 cm deep along local +z (its
/// front cap at z = 0), without its back cap. The back half sits in the
/// housing, so a back cap, lit, would shine inside the housing: light
/// nobody sees, which the light tree would still offer to the points
/// behind the head.
pub fn lens_mesh() -> LocalMesh {
    const DEPTH: f64 = 0.02;
    let mut m = mesh::cylinder(0.1, DEPTH, LENS_SEGMENTS, true);
    m.retain_triangles(|corners| corners.iter().any(|p| p.z != DEPTH));
    m
}

/// A cobra head at the end of an arm `reach` m along −y at height `z`:
/// housing over a 1 mm gap over the emitting panel.
fn cobra_head(kit: &mut Kit, y: f64, z: f64) {
    let housing = DQuat::from_rotation_x(0.05_f64.copysign(-y));
    kit.block_turned(
        "street_paint_grey",
        POLE,
        [0.42, 0.8, 0.16],
        DVec3::new(0.0, y, z),
        housing,
    );
    let panel_z = z - 0.08 - 0.03 - 0.011;
    let at = DAffine3::from_translation(DVec3::new(0.0, y, panel_z));
    kit.add("lamp_emit", POLE, open_top([0.3, 0.5, 0.02]), at);
    kit.block(
        "street_paint_grey",
        POLE,
        [0.34, 0.54, 0.03],
        [0.0, y, panel_z + 0.026],
    );
}

/// Modern: tapered galvanised pole, rising arm, cobra head 2.7 m out.
fn lamp_cobra() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let m = "street_galvanised";
    k.rod(m, POLE, DVec3::ZERO, DVec3::Z * 0.6, 0.16, 12);
    k.rod(m, POLE, DVec3::Z * 0.6, DVec3::Z * 5.0, 0.1, 12);
    k.rod(m, POLE, DVec3::Z * 5.0, DVec3::Z * 8.8, 0.075, 12);
    let (a, b, c) = (
        DVec3::new(0.0, 0.0, 8.6),
        DVec3::new(0.0, -1.3, 9.05),
        DVec3::new(0.0, -2.35, 9.2),
    );
    k.rod(m, POLE, a, b, 0.045, 8);
    k.rod(m, POLE, b, c, 0.045, 8);
    cobra_head(&mut k, -2.75, 9.25);
    k.objects()
}

/// Heritage: octagonal plinth, fluted dark-green post with collars and a
/// four-barred lantern round a glowing core under a pyramid cap.
fn lamp_heritage() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let g = "street_paint_green";
    k.add(
        g,
        POLE,
        prism(&regular(8, 0.2, 0.0), 0.0, 0.55),
        Default::default(),
    );
    k.rod(g, POLE, DVec3::Z * 0.55, DVec3::Z * 3.7, 0.07, 16);
    for z in [0.55, 1.2, 3.55] {
        k.rod(g, POLE, DVec3::Z * z, DVec3::Z * (z + 0.08), 0.1, 16);
    }
    k.add(
        g,
        POLE,
        prism(&regular(4, 0.17, 0.785), 3.7, 3.78),
        Default::default(),
    );
    for c in regular(4, 0.17, 0.785) {
        let p = DVec3::new(c[0] * 0.85, c[1] * 0.85, 3.78);
        k.rod(g, POLE, p, p + DVec3::Z * 0.52, 0.012, 6);
    }
    k.block("lamp_emit", POLE, [0.16, 0.16, 0.36], [0.0, 0.0, 4.04]);
    k.add(
        g,
        POLE,
        prism(&regular(4, 0.25, 0.785), 4.3, 4.36),
        Default::default(),
    );
    k.add(
        g,
        POLE,
        prism(&regular(4, 0.16, 0.785), 4.36, 4.46),
        Default::default(),
    );
    k.rod(g, POLE, DVec3::Z * 4.46, DVec3::Z * 4.62, 0.02, 6);
    k.objects()
}

/// Highway: a 12 m mast with two arms (along ∓y) and a head on each.
fn lamp_highway() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let m = "street_galvanised";
    k.add(
        "street_concrete",
        POLE,
        prism(&regular(4, 0.42, 0.785), 0.0, 0.4),
        Default::default(),
    );
    k.rod(m, POLE, DVec3::Z * 0.4, DVec3::Z * 7.0, 0.13, 12);
    k.rod(m, POLE, DVec3::Z * 7.0, DVec3::Z * 12.1, 0.09, 12);
    for s in [-1.0, 1.0] {
        let (a, b) = (DVec3::new(0.0, 0.0, 11.6), DVec3::new(0.0, s * 2.2, 12.3));
        k.rod(m, POLE, a, b, 0.05, 8);
        cobra_head(&mut k, s * 2.6, 12.35);
    }
    k.objects()
}

/// One signal head centred at (0, y, z): black back plate, housing, three
/// lens slots (separate objects) and a visor over each lens.
fn head(kit: &mut Kit, y: f64, z: f64) {
    let h = "signal_housing";
    kit.block("street_paint_black", TL, [0.02, 0.48, 1.16], [0.13, y, z]);
    kit.block(h, TL, [0.22, 0.32, 1.0], [0.0, y, z]);
    for (k, slot) in LENS_SLOTS.iter().enumerate() {
        let lz = z + LENS_STEP_M * (1.0 - k as f64);
        // A lens disc 1.5 cm proud of the housing's face at x = −0.11,
        // facing −x.
        let at = TransformDesc {
            translate: Some([-0.125, y, lz]),
            rotate_deg: Some([0.0, 90.0, 0.0]),
            scale: None,
        };
        kit.object(object(lens_mesh().into_shape(), Some(slot), class(TL), at));
        kit.block(h, TL, [0.2, 0.26, 0.012], [-0.21, y, lz + 0.125]);
        for s in [-1.0, 1.0] {
            kit.block(
                h,
                TL,
                [0.2, 0.012, 0.14],
                [-0.21, y + s * 0.124, lz + 0.063],
            );
        }
    }
}

/// The head on the pole's side below the arm (its bracket is the pole's).
const POLE_HEAD: (f64, f64) = (-0.3, 2.9);

/// Corner pole with a 4.6 m arm (class `pole`), and its heads (class
/// `traffic_light`): one over the road at y = 4 m, one on the pole.
fn traffic_light() -> (Vec<ObjectDesc>, Vec<ObjectDesc>) {
    let mut k = Kit::default();
    let m = "street_paint_grey";
    k.rod(m, POLE, DVec3::ZERO, DVec3::Z * 0.5, 0.15, 12);
    k.rod(m, POLE, DVec3::Z * 0.5, DVec3::Z * 6.3, 0.1, 12);
    k.rod(
        m,
        POLE,
        DVec3::new(0.0, 0.0, 5.95),
        DVec3::new(0.0, 4.6, 5.95),
        0.06,
        8,
    );
    k.rod(
        m,
        POLE,
        DVec3::new(0.0, 4.0, 5.95),
        DVec3::new(0.0, 4.0, 5.7),
        0.03,
        6,
    );
    k.block(m, POLE, [0.06, 0.12, 0.06], [0.0, -0.14, 3.2]);
    let mut h = Kit::default();
    head(&mut h, 4.0, 5.2);
    head(&mut h, POLE_HEAD.0, POLE_HEAD.1);
    (k.objects(), h.objects())
}

/// Mast-arm signal for two-lane approaches: a 7 m arm with a tie rod
/// (class `pole`), one head over the middle of each lane (3.5 m lanes
/// from 0.5 m past the pole) and one on the pole (class `traffic_light`).
fn traffic_light_mast() -> (Vec<ObjectDesc>, Vec<ObjectDesc>) {
    let mut k = Kit::default();
    let mut h = Kit::default();
    let m = "street_paint_grey";
    k.rod(m, POLE, DVec3::ZERO, DVec3::Z * 0.6, 0.2, 12);
    k.rod(m, POLE, DVec3::Z * 0.6, DVec3::Z * 7.4, 0.13, 12);
    k.rod(
        m,
        POLE,
        DVec3::new(0.0, 0.0, 6.4),
        DVec3::new(0.0, 7.0, 6.4),
        0.075,
        10,
    );
    k.rod(
        m,
        POLE,
        DVec3::new(0.0, 0.0, 7.3),
        DVec3::new(0.0, 4.2, 6.45),
        0.03,
        6,
    );
    k.block(m, POLE, [0.06, 0.14, 0.06], [0.0, -0.15, 3.2]);
    for y in [2.25, 5.75] {
        k.rod(
            m,
            POLE,
            DVec3::new(0.0, y, 6.4),
            DVec3::new(0.0, y, 6.2),
            0.03,
            6,
        );
        head(&mut h, y, 5.7);
    }
    head(&mut h, POLE_HEAD.0, POLE_HEAD.1);
    (k.objects(), h.objects())
}

/// Name of the pole prefab that carries the heads of signal prefab `heads`.
pub fn signal_pole(heads: &str) -> String {
    format!("{heads}_pole")
}

/// Every lamp-post and traffic-light prefab (heads named as in
/// `signals::PREFABS`, their poles by `signal_pole`).
pub fn light_prefabs() -> Vec<PrefabDesc> {
    let mut out = vec![
        prefab(LAMP_COBRA, lamp_cobra()),
        prefab(LAMP_HERITAGE, lamp_heritage()),
        prefab(LAMP_HIGHWAY, lamp_highway()),
    ];
    for (name, (pole, heads)) in [
        (crate::town::signals::PREFAB, traffic_light()),
        (SIGNAL_MAST, traffic_light_mast()),
    ] {
        out.push(prefab(&signal_pole(name), pole));
        out.push(prefab(name, heads));
    }
    out
}
