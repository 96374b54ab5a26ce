//! Umbrellas in rain: a person walking or standing with the right forearm
//! raised to hold an umbrella whose shaft rises from the hand to a canopy
//! above the head. In a frame with rain, most pedestrians carry one
//! ([`add_umbrellas`]): their instance is switched to the umbrella twin of
//! its prefab (same variant, same walk phase, so the legs keep the walk
//! cycle), which keeps the person's class and instance id: the umbrella is
//! part of the pedestrian, as CARLA labels what a walker carries.

use std::collections::BTreeSet;
use std::sync::OnceLock;

use glam::DVec3;

use super::body::Joint;
use super::pose::{pose, stand_angles, walk_angles};
use super::{looks_and_poses, prefab_name, Person, PHASES, VARIANTS};
use crate::scene::desc::{ObjectDesc, PrefabDesc, SceneDesc, ShapeDesc};

/// Canopy colours (cloth materials of `clothing`), picked per variant.
const CANOPIES: [&str; 6] = [
    "person_black",
    "person_navy",
    "person_red",
    "person_black",
    "person_sky",
    "person_green",
];
/// Share of pedestrians with an umbrella in rain, in quarters: one person in
/// four walks without (hood, or just wet).
const WITH_UMBRELLA_QUARTERS: u32 = 3;
/// Canopy radius (m) and how far the rim hangs below the apex.
const CANOPY_RADIUS: f64 = 0.52;
const CANOPY_DEPTH: f64 = 0.2;

/// Prefab name of variant `v` in quantised phase `phase` (None: standing)
/// holding an umbrella.
pub fn umbrella_prefab_name(v: u32, phase: Option<u32>) -> String {
    format!("{}_umbrella", prefab_name(v, phase))
}

/// The umbrella twin of [`super::person_prefab`]: the right shoulder swung
/// forward a little and the elbow bent so the hand sits in front of the
/// chest; the shaft rises from the hand, leaning back, to a canopy over
/// the head.
pub fn umbrella_prefab(v: u32, phase: Option<u32>) -> PrefabDesc {
    let person = Person::variant(v);
    let mut a = match phase {
        Some(p) => walk_angles((p % PHASES) as f64 / PHASES as f64),
        None => stand_angles(),
    };
    a.shoulder[1] = 8f64.to_radians();
    a.elbow[1] = 135f64.to_radians();
    let k = pose(&person.body, &a);
    let mut parts = person.parts(&k);
    let hand = k.at(Joint::WristR) + DVec3::new(0.02, 0.0, 0.0);
    let head_top = k.at(Joint::Head).z + person.body.head_r;
    // The shaft leans back so the canopy centres over the head.
    let mid = 0.5 * (hand + k.at(Joint::Head));
    let apex = DVec3::new(mid.x, mid.y, head_top + CANOPY_DEPTH + 0.14);
    let shaft = "person_umbrella_shaft";
    parts.capsule(
        shaft,
        hand - DVec3::Z * 0.1,
        apex + DVec3::Z * 0.06,
        0.009,
        0.007,
        1.0,
    );
    // Curved handle: a short hook below the hand.
    parts.capsule(
        shaft,
        hand - DVec3::Z * 0.1,
        hand + DVec3::new(0.05, 0.0, -0.14),
        0.014,
        0.014,
        1.0,
    );
    let canopy = CANOPIES[(v % VARIANTS) as usize % CANOPIES.len()];
    parts.canopy(canopy, apex, CANOPY_RADIUS, CANOPY_DEPTH, 8);
    PrefabDesc {
        name: umbrella_prefab_name(v, phase),
        objects: parts.into_objects("pedestrian"),
    }
}

/// Every umbrella prefab, generated once per process.
fn umbrella_prefabs() -> &'static [PrefabDesc] {
    static PREFABS: OnceLock<Vec<PrefabDesc>> = OnceLock::new();
    PREFABS.get_or_init(|| {
        looks_and_poses()
            .map(|(v, p)| umbrella_prefab(v, p))
            .collect()
    })
}

/// Whether pedestrian instance `id` carries an umbrella in rain: a fixed
/// share by a hash of the id, the same in every frame of a sequence.
pub fn carries_umbrella(id: u16) -> bool {
    let h = (id as u32).wrapping_mul(0x9E37_79B9) >> 16;
    h % 4 < WITH_UMBRELLA_QUARTERS
}

/// Gives most of `desc`'s pedestrians an umbrella (a frame with rain):
/// switches their instances to the umbrella prefabs and adds those prefabs.
pub fn add_umbrellas(desc: &mut SceneDesc) {
    let mut used = BTreeSet::new();
    for o in desc.objects.iter_mut() {
        if let Some(name) = umbrella_name(o) {
            if let ShapeDesc::Instance { prefab, .. } = &mut o.shape {
                *prefab = name.clone();
            }
            used.insert(name);
        }
    }
    desc.prefabs.extend(
        umbrella_prefabs()
            .iter()
            .filter(|p| used.contains(&p.name))
            .cloned(),
    );
}

/// The umbrella prefab `o` switches to, if `o` is a person that carries one.
fn umbrella_name(o: &ObjectDesc) -> Option<String> {
    let ShapeDesc::Instance { prefab, .. } = &o.shape else {
        return None;
    };
    let is_person = prefab.starts_with("person_") && !prefab.ends_with("_umbrella");
    let carries = o.instance.is_some_and(carries_umbrella);
    (is_person && carries && o.semantic.as_deref() == Some("pedestrian"))
        .then(|| format!("{prefab}_umbrella"))
}
