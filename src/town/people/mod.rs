//! People: articulated bodies (19 joints, `body`), posed by a walk cycle or
//! standing (`pose`), dressed in smooth parts (`clothing`, `mesh`), and
//! seated riders for two-wheelers (`rider`), and umbrellas in rain
//! (`umbrella`).
//!
//! Cost: a person is one of `VARIANTS` seeded looks (adults and children;
//! colours baked in, so no material map) in one of `PHASES` quantised walk
//! phases or standing; each (variant, phase) is a prefab, so people in the
//! same variant and phase share one prototype.

pub mod body;
pub mod clothing;
pub mod mesh;
pub mod pose;
pub mod rider;
pub mod umbrella;

use crate::scene::desc::{MaterialDesc, PrefabDesc};

use super::rng::Rng;
use body::{Body, PERSON_TAG};
use clothing::Outfit;
use mesh::Parts;
use pose::Skeleton;

pub use rider::rider_prefab;

/// Seeded looks (body and outfit); the first `CHILDREN` are children.
pub const VARIANTS: u32 = 16;
/// Variants that are children.
pub const CHILDREN: u32 = 3;
/// Quantised phases of the walk cycle.
pub const PHASES: u32 = 12;

/// One variant: its body and outfit.
#[derive(Clone, Debug, PartialEq)]
pub struct Person {
    /// Proportions.
    pub body: Body,
    /// Clothes and colours.
    pub outfit: Outfit,
}

impl Person {
    /// Variant `v` (taken modulo `VARIANTS`); the same on every call.
    pub fn variant(v: u32) -> Person {
        let v = v % VARIANTS;
        let mut r = Rng::new(&[PERSON_TAG, v as u64]);
        let child = v < CHILDREN;
        Person {
            body: Body::draw(&mut r, child),
            outfit: Outfit::draw(&mut r, child),
        }
    }

    /// The person dressed in pose `k`, as prefab objects of `class`.
    pub fn parts(&self, k: &Skeleton) -> Parts {
        let mut parts = Parts::default();
        clothing::dress(&self.body, k, &self.outfit, &mut parts);
        parts
    }
}

/// The quantised phase (0..PHASES) of walk phase `phase` (cycles).
pub fn phase_index(phase: f64) -> u32 {
    ((phase.rem_euclid(1.0) * PHASES as f64).floor() as u32).min(PHASES - 1)
}

/// Prefab name of variant `v` walking in quantised phase `phase`, or
/// standing (`None`).
pub fn prefab_name(v: u32, phase: Option<u32>) -> String {
    match phase {
        Some(p) => format!("person_{:02}_{:02}", v % VARIANTS, p % PHASES),
        None => format!("person_{:02}_stand", v % VARIANTS),
    }
}

/// The prefab of variant `v` in quantised phase `phase` (None: standing).
pub fn person_prefab(v: u32, phase: Option<u32>) -> PrefabDesc {
    let person = Person::variant(v);
    let k = match phase {
        Some(p) => pose::walk(&person.body, (p % PHASES) as f64 / PHASES as f64),
        None => pose::stand(&person.body),
    };
    PrefabDesc {
        name: prefab_name(v, phase),
        objects: person.parts(&k).into_objects("pedestrian"),
    }
}

/// Every person prefab: each variant in each phase and standing (generated
/// once per process: every town frame names the same set).
pub fn people_prefabs() -> Vec<PrefabDesc> {
    static PREFABS: std::sync::OnceLock<Vec<PrefabDesc>> = std::sync::OnceLock::new();
    PREFABS.get_or_init(generate_prefabs).clone()
}

pub(super) fn generate_prefabs() -> Vec<PrefabDesc> {
    looks_and_poses()
        .map(|(v, p)| person_prefab(v, p))
        .collect()
}

/// Every (variant, quantised phase or standing) a prefab exists for.
pub fn looks_and_poses() -> impl Iterator<Item = (u32, Option<u32>)> {
    (0..VARIANTS).flat_map(|v| (0..PHASES).map(Some).chain([None]).map(move |p| (v, p)))
}

/// The materials people wear.
pub fn people_materials() -> Vec<MaterialDesc> {
    clothing::people_materials()
}

#[cfg(test)]
mod tests;
