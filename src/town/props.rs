//! Prefabs of the street scene (people are `people`'s): the façade prefabs of
//! `facade` and the street furniture of `street` (lamps, traffic lights
//! whose lens materials are slots the frame's signal phase fills, see
//! `signals`, signs, fixtures, fences and wires). Trees and bushes are
//! `vegetation`'s.
//!
//! Local frames: z up, origin on the ground.

use crate::scene::desc::PrefabDesc;

/// Material slots of a traffic light's lenses, top to bottom (red, amber,
/// green); every head of the traffic-light prefabs uses them.
pub const LENS_SLOTS: [&str; 3] = ["signal_red", "signal_amber", "signal_green"];

/// Every street prefab.
pub fn street_prefabs() -> Vec<PrefabDesc> {
    super::facade::facade_prefabs()
        .into_iter()
        .chain(super::street::furniture_prefabs())
        .collect()
}
