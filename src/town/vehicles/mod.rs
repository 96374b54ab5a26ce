//! Vehicle prefabs of eleven body types generated from parameters: cars,
//! vans, a box truck and a bus as smooth lofted bodies (`spec`, `loft`,
//! `body`) with glass, lamps, wheels with spoked rims, an interior and
//! plates; motorcycles and bicycles (`two_wheel`). Head-lights at night
//! are spot lights (`lights`).
//!
//! Each type is two prefabs placed together: `<model>` holds the painted
//! panels (material "car_paint", remapped per vehicle, so one prototype
//! per model and paint) and `<model>_parts` everything else (one
//! prototype per model); `<model>_plate<k>` adds one of the registrations.
//!
//! Local frame: x forward, y left, z up, origin on the ground at the centre
//! of the footprint, so a vehicle's footprint is `length × width` about it.

pub mod bed;
pub mod body;
pub mod interior;
pub mod lamps;
pub mod lights;
pub mod loft;
pub mod plates;
pub mod spec;
pub mod two_wheel;
pub mod wheels;

use glam::{DAffine3, DQuat, DVec3};

use crate::scene::desc::PrefabDesc;
use crate::town::street::kit::Kit;

pub use lights::{add_headlights, headlights, needs_headlights};

/// A vehicle body type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodyKind {
    /// Four-door saloon with a boot.
    Sedan,
    /// Short car with a steep tailgate.
    Hatchback,
    /// Tall sport-utility vehicle.
    Suv,
    /// Delivery van.
    Van,
    /// City bus.
    Bus,
    /// Box truck.
    Truck,
    /// Estate (station wagon): a sedan's nose, a long roof to the tail.
    Estate,
    /// Low two-door coupé with a fast roof line.
    Coupe,
    /// Pickup: a tall cab and an open load bed.
    Pickup,
    /// Motorcycle.
    Motorcycle,
    /// Bicycle.
    Bicycle,
}

/// Every body type, in draw order (weights in `BODY_WEIGHTS`).
pub const BODIES: [BodyKind; 11] = [
    BodyKind::Sedan,
    BodyKind::Hatchback,
    BodyKind::Suv,
    BodyKind::Van,
    BodyKind::Bus,
    BodyKind::Truck,
    BodyKind::Estate,
    BodyKind::Coupe,
    BodyKind::Pickup,
    BodyKind::Motorcycle,
    BodyKind::Bicycle,
];
/// Relative frequency of each body type in traffic (cars mostly; vans,
/// trucks and buses some; two-wheelers rare).
pub const BODY_WEIGHTS: [f64; 11] = [
    0.24, 0.2, 0.18, 0.07, 0.03, 0.05, 0.08, 0.04, 0.05, 0.04, 0.02,
];

impl BodyKind {
    /// Prefab name of the painted panels (`parts_prefab` holds the rest).
    pub fn prefab(self) -> &'static str {
        match self {
            BodyKind::Sedan => "sedan",
            BodyKind::Hatchback => "hatchback",
            BodyKind::Suv => "suv",
            BodyKind::Van => "van",
            BodyKind::Bus => "bus",
            BodyKind::Truck => "truck",
            BodyKind::Estate => "estate",
            BodyKind::Coupe => "coupe",
            BodyKind::Pickup => "pickup",
            BodyKind::Motorcycle => "motorcycle",
            BodyKind::Bicycle => "bicycle",
        }
    }

    /// Prefab name of the unpainted parts (glass, wheels, lamps, interior).
    pub fn parts_prefab(self) -> String {
        format!("{}_parts", self.prefab())
    }

    /// Prefab name of the glowing lamp lenses (emitters, kept flat).
    pub fn lamps_prefab(self) -> String {
        format!("{}_lamps", self.prefab())
    }

    /// Prefab name of registration `k` (< `plates::PLATE_VARIANTS`), or
    /// none for a bicycle.
    pub fn plate_prefab(self, k: u32) -> Option<String> {
        (self != BodyKind::Bicycle).then(|| format!("{}_plate{k}", self.prefab()))
    }

    /// Semantic class (CARLA's): buses, trucks and two-wheelers apart
    /// from cars (vans and pickups are cars).
    pub fn class(self) -> &'static str {
        match self {
            BodyKind::Bus => "bus",
            BodyKind::Truck => "truck",
            BodyKind::Motorcycle => "motorcycle",
            BodyKind::Bicycle => "bicycle",
            _ => "car",
        }
    }

    /// Footprint length and width, metres: the body, mirrors, bumpers and
    /// plates (a two-wheeler's wheels, lamps and rider) all stay inside it.
    pub fn footprint_m(self) -> [f64; 2] {
        match self {
            BodyKind::Motorcycle => [MOTORCYCLE_LEN_M, 1.0],
            BodyKind::Bicycle => [BICYCLE_LEN_M, 0.8],
            k => {
                let s = spec::spec_of(k).expect("a four-wheeled body");
                [s.length + 0.1, s.width + 2.0 * body::MIRROR_REACH_M + 0.02]
            }
        }
    }

    /// For a two-wheeler, where its rider sits, in the body frame: (hip
    /// point, left hand grip, left foot peg or pedal); the right side
    /// mirrors y. None for cars, vans, trucks and buses.
    pub fn seat(self) -> Option<[[f64; 3]; 3]> {
        match self {
            BodyKind::Motorcycle => {
                Some([[-0.25, 0.0, 0.92], [0.42, 0.33, 1.06], [-0.05, 0.2, 0.38]])
            }
            BodyKind::Bicycle => Some([[-0.2, 0.0, 0.98], [0.42, 0.26, 0.98], [0.13, 0.12, 0.2]]),
            _ => None,
        }
    }

    fn index(self) -> usize {
        BODIES.iter().position(|&b| b == self).expect("listed")
    }
}

/// A motorcycle's footprint length, metres: its wheels (axles ±0.68 m,
/// radius 0.3 m) and a few centimetres.
pub const MOTORCYCLE_LEN_M: f64 = 2.1;
/// A bicycle's footprint length, metres: its wheels (axles ±0.525 m,
/// radius 0.34 m) and a few centimetres.
pub const BICYCLE_LEN_M: f64 = 1.85;

/// The emissive materials of vehicle lamps.
pub const EMITTERS: [&str; 2] = ["headlight_emit", "taillight_emit"];

/// The prefabs of every body type: panels, parts, lamps and
/// registrations (generated once per process: they depend on nothing).
pub fn vehicle_prefabs() -> Vec<PrefabDesc> {
    static PREFABS: std::sync::OnceLock<Vec<PrefabDesc>> = std::sync::OnceLock::new();
    PREFABS.get_or_init(generate_prefabs).clone()
}

fn generate_prefabs() -> Vec<PrefabDesc> {
    let mut out = Vec::new();
    for b in BODIES {
        let (paint, parts) = build(b);
        out.push(PrefabDesc {
            name: b.prefab().to_string(),
            objects: paint.objects(),
        });
        // Emitters go apart: a prefab holding one stays flat (the light
        // set finds emitters among flat meshes only), so it must be small.
        // The brake and indicator lenses go with them: a frame maps them to
        // emitters while lit (`town::dynamic_objects`).
        let (lamps, rest): (Vec<_>, Vec<_>) = parts.objects().into_iter().partition(|o| {
            o.material
                .as_deref()
                .is_some_and(|m| EMITTERS.contains(&m) || lamps::LIT_SLOTS.contains(&m))
        });
        out.push(PrefabDesc {
            name: b.parts_prefab(),
            objects: rest,
        });
        out.push(PrefabDesc {
            name: b.lamps_prefab(),
            objects: lamps,
        });
        for k in 0..plates::PLATE_VARIANTS {
            if let Some(name) = b.plate_prefab(k) {
                let mut kit = Kit::default();
                plate_kit(b, k, &mut kit);
                out.push(PrefabDesc {
                    name,
                    objects: kit.objects(),
                });
            }
        }
    }
    out
}

/// The painted panels and the other parts of body type `kind`.
pub fn build(kind: BodyKind) -> (Kit, Kit) {
    let class = kind.class();
    let (mut paint, mut parts) = (Kit::default(), Kit::default());
    match kind {
        BodyKind::Motorcycle => two_wheel::motorcycle(class, &mut paint, &mut parts),
        BodyKind::Bicycle => two_wheel::bicycle(class, &mut paint, &mut parts),
        k => {
            let s = spec::spec_of(k).expect("a four-wheeled body");
            body::body(&s, class, &mut paint, &mut parts);
            lamps::lamps(&s, class, &mut parts);
            interior::interior(&s, class, &mut parts);
            let yw = s.width / 2.0 - s.tyre_w / 2.0 - 0.04;
            let spokes = if s.length > 7.0 { 8 } else { 5 };
            for x in s.axles {
                for sy in [1.0, -1.0] {
                    // Right wheels are left wheels turned half round z.
                    let turn =
                        DQuat::from_rotation_z(if sy > 0.0 { 0.0 } else { std::f64::consts::PI });
                    let t = DAffine3::from_rotation_translation(
                        turn,
                        DVec3::new(x, sy * yw, s.wheel_r),
                    );
                    wheels::car_wheel(&mut parts, class, s.wheel_r, s.tyre_w, spokes, t);
                }
            }
        }
    }
    (paint, parts)
}

/// Registration `k` of `kind`: plates front and rear (rear only on a
/// motorcycle).
fn plate_kit(kind: BodyKind, k: u32, kit: &mut Kit) {
    let text = plates::plate_text(kind.index(), k);
    let class = kind.class();
    if kind == BodyKind::Motorcycle {
        plates::plate(kit, class, &text, -0.84, 0.7, false, 0.4);
        return;
    }
    let s = spec::spec_of(kind).expect("a four-wheeled body");
    let zf = s.floor_z + 0.25;
    plates::plate(
        kit,
        class,
        &text,
        s.end_x(1.0, 0.0, zf) + 0.008,
        zf,
        true,
        1.0,
    );
    let zr = if s.cargo_front_x.is_some() {
        s.deck_z - 0.25
    } else {
        s.deck_z - 0.3
    };
    plates::plate(
        kit,
        class,
        &text,
        s.end_x(-1.0, 0.0, zr) - 0.002,
        zr,
        false,
        1.0,
    );
}

#[cfg(test)]
mod gallery;
#[cfg(test)]
mod tests;
