//! Prefabs of the street scene: the façade prefabs (`town::facade`), a
//! street light with an emissive lamp panel, a traffic light (two
//! heads whose lens materials are slots the frame's signal phase fills,
//! see `signals`), a stop sign, a pedestrian.
//!
//! Local frames: z up, origin on the ground; a street light's arm
//! reaches towards local −y, a traffic light's towards local +y (over the road).

use crate::scene::desc::{ObjectDesc, PrefabDesc};

use super::parts::{blob, class, cuboid, cylinder, Label};

/// Material slots of a traffic light's lenses, top to bottom (red, amber,
/// green); both heads of the prefab use them.
pub const LENS_SLOTS: [&str; 3] = ["signal_red", "signal_amber", "signal_green"];

fn prefab(name: &str, objects: Vec<ObjectDesc>) -> PrefabDesc {
    PrefabDesc {
        name: name.to_string(),
        objects,
    }
}

/// Every street prefab.
pub fn street_prefabs() -> Vec<PrefabDesc> {
    let street = vec![
        prefab("street_light", street_light()),
        prefab("traffic_light", traffic_light()),
        prefab("stop_sign", stop_sign()),
        prefab("info_sign", info_sign()),
        prefab("pedestrian", pedestrian(class("pedestrian"))),
    ];
    street
        .into_iter()
        .chain(super::facade::facade_prefabs())
        .collect()
}

/// An 8 m pole with an arm towards local −y and a lamp housing over an
/// emitting panel.
fn street_light() -> Vec<ObjectDesc> {
    let p = class("pole");
    vec![
        cylinder(0.09, 8.0, 12, [0.0, 0.0, 0.0], "pole_metal", p),
        cuboid([0.1, 2.2, 0.1], [0.0, -1.1, 7.9], 0.0, "pole_metal", p),
        cuboid([0.35, 0.6, 0.14], [0.0, -2.1, 7.8], 0.0, "pole_metal", p),
        // The emitting panel under the housing (1 mm gap, no shared faces).
        cuboid([0.3, 0.5, 0.02], [0.0, -2.1, 7.719], 0.0, "lamp_emit", p),
    ]
}

/// Pole on the corner, mast arm over the approach lanes (local +y), heads
/// facing −x (towards the traffic that approaches along +x).
fn traffic_light() -> Vec<ObjectDesc> {
    let (p, tl) = (class("pole"), class("traffic_light"));
    let mut traffic_light = vec![
        cylinder(0.11, 6.0, 12, [0.0, 0.0, 0.0], "pole_paint", p),
        cuboid([0.14, 4.5, 0.14], [0.0, 2.25, 5.8], 0.0, "pole_paint", p),
        cuboid([0.3, 0.4, 1.1], [0.0, 4.0, 5.15], 0.0, "signal_housing", tl),
        cuboid([0.3, 0.4, 1.1], [0.0, -0.3, 2.8], 0.0, "signal_housing", tl),
    ];
    // Lenses top to bottom, 1 mm proud of the housing (no shared faces).
    // Their materials are slots: dark glass here, and `signals` maps the
    // lit one of each frame to its emitter on the instance.
    for (k, m) in LENS_SLOTS.iter().enumerate() {
        let z = 5.5 - 0.33 * k as f64;
        for (y, dz) in [(4.0, 0.0), (-0.3, -2.35)] {
            traffic_light.push(cuboid([0.03, 0.24, 0.24], [-0.166, y, z + dz], 0.0, m, tl));
        }
    }
    traffic_light
}

/// An octagonal stop sign facing −x.
fn stop_sign() -> Vec<ObjectDesc> {
    let (p, ts) = (class("pole"), class("traffic_sign"));
    vec![
        cylinder(0.04, 2.3, 8, [0.0, 0.0, 0.0], "pole_metal", p),
        sign_disc(0.38, [-0.05, 0.0, 2.3], "sign_red", ts),
        sign_disc(0.3, [-0.07, 0.0, 2.3], "sign_white", ts),
    ]
}

/// A square blue information sign facing −x.
fn info_sign() -> Vec<ObjectDesc> {
    let (p, ts) = (class("pole"), class("traffic_sign"));
    vec![
        cylinder(0.04, 2.4, 8, [0.0, 0.0, 0.0], "pole_metal", p),
        cuboid([0.04, 0.6, 0.6], [-0.05, 0.0, 2.3], 0.0, "sign_blue", ts),
    ]
}

/// An octagon (8-sided cylinder) facing −x, centred at `at`.
fn sign_disc(r: f64, at: [f64; 3], mat: &str, l: Label) -> ObjectDesc {
    let mut o = cylinder(r, 0.02, 8, [0.0; 3], mat, l);
    o.transform.translate = Some(at);
    o.transform.rotate_deg = Some([0.0, 90.0, 0.0]);
    o
}

/// A walking figure about 1.75 m tall facing +x; shirt material "shirt".
fn pedestrian(l: Label) -> Vec<ObjectDesc> {
    vec![
        cuboid([0.16, 0.14, 0.85], [0.12, -0.1, 0.43], 0.0, "cloth_dark", l),
        cuboid([0.16, 0.14, 0.85], [-0.1, 0.1, 0.43], 0.0, "cloth_dark", l),
        cuboid([0.26, 0.42, 0.62], [0.0, 0.0, 1.17], 0.0, "shirt", l),
        cuboid([0.1, 0.1, 0.6], [0.05, -0.26, 1.15], 0.0, "shirt", l),
        cuboid([0.1, 0.1, 0.6], [-0.05, 0.26, 1.15], 0.0, "shirt", l),
        blob([0.1, 0.09, 0.12], [0.0, 0.0, 1.62], "skin", l),
    ]
}
