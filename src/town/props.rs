//! Prefabs of the street scene: a pedestrian, the façade prefabs of
//! `facade` and the street furniture of `street` (lamps, traffic lights
//! whose lens materials are slots the frame's signal phase fills, see
//! `signals`, signs, fixtures, fences and wires). Trees and bushes are
//! `vegetation`'s.
//!
//! Local frames: z up, origin on the ground.

use crate::scene::desc::{ObjectDesc, PrefabDesc};

use super::parts::{blob, class, cuboid, Label};

/// Material slots of a traffic light's lenses, top to bottom (red, amber,
/// green); every head of the traffic-light prefabs uses them.
pub const LENS_SLOTS: [&str; 3] = ["signal_red", "signal_amber", "signal_green"];

fn prefab(name: &str, objects: Vec<ObjectDesc>) -> PrefabDesc {
    PrefabDesc {
        name: name.to_string(),
        objects,
    }
}

/// Every street prefab.
pub fn street_prefabs() -> Vec<PrefabDesc> {
    vec![prefab("pedestrian", pedestrian(class("pedestrian")))]
        .into_iter()
        .chain(super::facade::facade_prefabs())
        .chain(super::street::furniture_prefabs())
        .collect()
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
