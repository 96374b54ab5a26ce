//! Prefabs of the street scene: a facade window (and the lit room that
//! some windows show), trees of two shapes, a bush, a pedestrian, and the
//! street furniture of `street` (lamps, traffic lights whose lens
//! materials are slots the frame's signal phase fills, see `signals`,
//! signs, fixtures, fences and wires).
//!
//! Local frames: z up, origin on the ground; a window's facade is the local
//! x–z plane with the window standing out towards −y.

use crate::scene::desc::{ObjectDesc, PrefabDesc};

use super::parts::{blob, class, cuboid, cylinder, repeated, Label};

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
    vec![
        prefab("window", window()),
        prefab("window_light", window_light()),
        prefab("tree_round", tree_round()),
        prefab("tree_cone", tree_cone()),
        prefab("bush", bush()),
        prefab("pedestrian", pedestrian(class("pedestrian"))),
    ]
    .into_iter()
    .chain(super::street::furniture_prefabs())
    .collect()
}

/// A facade window: a dark interior panel on the wall behind a glass pane,
/// the frame proud of it.
fn window() -> Vec<ObjectDesc> {
    let b = class("building");
    vec![
        cuboid([1.2, 0.02, 1.6], [0.0, -0.02, 0.0], 0.0, "interior", b),
        cuboid([1.2, 0.02, 1.6], [0.0, -0.05, 0.0], 0.0, "glass", b),
        cuboid(
            [1.4, 0.15, 0.1],
            [0.0, -0.075, 0.85],
            0.0,
            "window_frame",
            b,
        ),
        cuboid(
            [1.55, 0.25, 0.1],
            [0.0, -0.125, -0.85],
            0.0,
            "window_frame",
            b,
        ),
        repeated(
            cuboid(
                [0.1, 0.15, 1.6],
                [-0.65, -0.075, 0.0],
                0.0,
                "window_frame",
                b,
            ),
            &[(2, [1.3, 0.0, 0.0])],
        ),
    ]
}

/// A warm lit room behind a window pane: between the interior panel
/// (front at y = −0.03) and the glass (back at y = −0.04).
fn window_light() -> Vec<ObjectDesc> {
    vec![cuboid(
        [1.16, 0.004, 1.56],
        [0.0, -0.035, 0.0],
        0.0,
        "window_lit",
        class("building"),
    )]
}

/// A broad tree: a trunk under three foliage blobs.
fn tree_round() -> Vec<ObjectDesc> {
    let v = class("vegetation");
    vec![
        cylinder(0.16, 3.4, 10, [0.0, 0.0, 0.0], "bark", v),
        blob([1.9, 1.9, 1.6], [0.0, 0.0, 4.5], "foliage", v),
        blob([1.3, 1.3, 1.2], [0.8, 0.5, 5.5], "foliage_light", v),
        blob([1.2, 1.2, 1.1], [-0.8, -0.6, 5.3], "foliage", v),
    ]
}

/// A conifer: a short trunk under three stacked, narrowing blobs.
fn tree_cone() -> Vec<ObjectDesc> {
    let v = class("vegetation");
    vec![
        cylinder(0.18, 2.0, 10, [0.0, 0.0, 0.0], "bark", v),
        blob([1.8, 1.8, 1.5], [0.0, 0.0, 3.2], "foliage_dark", v),
        blob([1.4, 1.4, 1.3], [0.0, 0.0, 4.7], "foliage_dark", v),
        blob([0.9, 0.9, 1.1], [0.0, 0.0, 6.0], "foliage", v),
    ]
}

/// A bush of two blobs.
fn bush() -> Vec<ObjectDesc> {
    let v = class("vegetation");
    vec![
        blob([0.9, 0.9, 0.6], [0.0, 0.0, 0.5], "foliage", v),
        blob([0.6, 0.6, 0.5], [0.5, 0.3, 0.6], "foliage_light", v),
    ]
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
