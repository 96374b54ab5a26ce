//! Vehicle prefabs of six body types built from boxes and cylinders: body in
//! paint (material "car_paint", remapped per vehicle), glass cabin, dark
//! interior, wheels with chrome hubs, emissive head-lights (white) and
//! tail-lights (red), bumpers.
//!
//! Local frame: x forward, y left, z up, origin on the ground at the centre
//! of the footprint, so a vehicle's footprint is `length × width` about it.

use crate::scene::desc::{ObjectDesc, PrefabDesc};

use super::parts::{class, cuboid, wheel, Label};

/// A vehicle body type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BodyKind {
    /// Four-door saloon.
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
}

/// Every body type, in draw order (weights in `BODY_WEIGHTS`).
pub const BODIES: [BodyKind; 6] = [
    BodyKind::Sedan,
    BodyKind::Hatchback,
    BodyKind::Suv,
    BodyKind::Van,
    BodyKind::Bus,
    BodyKind::Truck,
];
/// Relative frequency of each body type in traffic.
pub const BODY_WEIGHTS: [f64; 6] = [0.32, 0.22, 0.2, 0.12, 0.06, 0.08];

/// Proportions of a body, metres.
struct Dims {
    length: f64,
    width: f64,
    /// Top of the painted lower body.
    belt_z: f64,
    /// Bottom of the lower body.
    floor_z: f64,
    /// Cabin (glass) length, its centre offset along x, and its top.
    cabin_len: f64,
    cabin_x: f64,
    roof_z: f64,
    wheel_r: f64,
    /// Axle positions along x (front, rear).
    axles: [f64; 2],
}

impl BodyKind {
    /// Prefab name.
    pub fn prefab(self) -> &'static str {
        match self {
            BodyKind::Sedan => "sedan",
            BodyKind::Hatchback => "hatchback",
            BodyKind::Suv => "suv",
            BodyKind::Van => "van",
            BodyKind::Bus => "bus",
            BodyKind::Truck => "truck",
        }
    }

    /// Semantic class (CARLA's): buses and trucks apart from cars.
    pub fn class(self) -> &'static str {
        match self {
            BodyKind::Bus => "bus",
            BodyKind::Truck => "truck",
            _ => "car",
        }
    }

    fn dims(self) -> Dims {
        let d = |length, width, floor_z, belt_z, cabin_len, cabin_x, roof_z, wheel_r, axles| Dims {
            length,
            width,
            floor_z,
            belt_z,
            cabin_len,
            cabin_x,
            roof_z,
            wheel_r,
            axles,
        };
        match self {
            BodyKind::Sedan => d(4.6, 1.8, 0.3, 0.95, 2.4, -0.2, 1.45, 0.33, [1.4, -1.4]),
            BodyKind::Hatchback => d(4.0, 1.75, 0.3, 0.95, 2.5, -0.5, 1.5, 0.31, [1.25, -1.25]),
            BodyKind::Suv => d(4.8, 1.95, 0.4, 1.15, 3.0, -0.4, 1.8, 0.38, [1.5, -1.45]),
            BodyKind::Van => d(5.3, 2.0, 0.4, 1.2, 4.3, -0.3, 2.3, 0.36, [1.9, -1.7]),
            BodyKind::Bus => d(11.5, 2.55, 0.45, 1.3, 10.8, 0.0, 3.1, 0.5, [3.9, -3.2]),
            BodyKind::Truck => d(8.0, 2.5, 0.55, 1.6, 1.6, 3.0, 2.8, 0.5, [2.9, -2.6]),
        }
    }

    /// Footprint length and width, metres, including lights, bumpers and
    /// hubs that stand a few centimetres proud of the body.
    pub fn footprint_m(self) -> [f64; 2] {
        let d = self.dims();
        [d.length + 0.1, d.width + 0.1]
    }
}

/// The prefabs of every body type.
pub fn vehicle_prefabs() -> Vec<PrefabDesc> {
    BODIES
        .iter()
        .map(|&b| PrefabDesc {
            name: b.prefab().to_string(),
            objects: body(b, class(b.class())),
        })
        .collect()
}

/// One body: the painted lower body, the cabin, a truck's cargo box,
/// bumpers, lights and wheels.
fn body(kind: BodyKind, l: Label) -> Vec<ObjectDesc> {
    let d = kind.dims();
    let lower_h = d.belt_z - d.floor_z;
    let mut o = vec![cuboid(
        [d.length, d.width, lower_h],
        [0.0, 0.0, d.floor_z + lower_h / 2.0],
        0.0,
        "car_paint",
        l,
    )];
    cabin(&d, l, &mut o);
    if kind == BodyKind::Truck {
        // Cargo box behind the cab.
        let (hl, box_len) = (d.length / 2.0, d.length - 2.4);
        o.push(cuboid(
            [box_len, d.width, 3.4 - d.belt_z + 0.3],
            [-hl + box_len / 2.0, 0.0, (3.4 + d.belt_z - 0.3) / 2.0],
            0.0,
            "cargo",
            l,
        ));
    }
    bumpers_and_lights(&d, l, &mut o);
    wheels(&d, l, &mut o);
    o
}

/// Glass cabin with an interior inside, a painted roof on top and pillars
/// at its corners holding the roof.
fn cabin(d: &Dims, l: Label, o: &mut Vec<ObjectDesc>) {
    let hw = d.width / 2.0;
    let cabin_h = d.roof_z - 0.06 - d.belt_z;
    let cz = d.belt_z + cabin_h / 2.0;
    o.push(cuboid(
        [d.cabin_len, d.width - 0.14, cabin_h],
        [d.cabin_x, 0.0, cz],
        0.0,
        "glass",
        l,
    ));
    o.push(cuboid(
        [d.cabin_len - 0.3, d.width - 0.5, cabin_h - 0.1],
        [d.cabin_x, 0.0, cz - 0.03],
        0.0,
        "plastic_black",
        l,
    ));
    o.push(cuboid(
        [d.cabin_len - 0.2, d.width - 0.1, 0.06],
        [d.cabin_x, 0.0, d.roof_z - 0.03],
        0.0,
        "car_paint",
        l,
    ));
    for sx in [-1.0, 1.0] {
        for sy in [-1.0, 1.0] {
            let at = [
                d.cabin_x + sx * (d.cabin_len / 2.0 - 0.06),
                sy * (hw - 0.1),
                cz,
            ];
            o.push(cuboid([0.1, 0.1, cabin_h], at, 0.0, "car_paint", l));
        }
    }
}

/// Bumpers front and rear, then head-lights and tail-lights on the front
/// and rear faces.
fn bumpers_and_lights(d: &Dims, l: Label, o: &mut Vec<ObjectDesc>) {
    let (hl, hw) = (d.length / 2.0, d.width / 2.0);
    for sx in [-1.0, 1.0] {
        o.push(cuboid(
            [0.14, d.width + 0.04, 0.22],
            [sx * (hl - 0.02), 0.0, d.floor_z + 0.1],
            0.0,
            "plastic_black",
            l,
        ));
    }
    let lz = d.belt_z - 0.18;
    for sy in [-1.0, 1.0] {
        let y = sy * (hw - 0.3);
        o.push(cuboid(
            [0.06, 0.36, 0.14],
            [hl + 0.01, y, lz],
            0.0,
            "headlight_emit",
            l,
        ));
        o.push(cuboid(
            [0.06, 0.36, 0.14],
            [-hl - 0.01, y, lz],
            0.0,
            "taillight_emit",
            l,
        ));
    }
}

/// Wheels (inside the body's width) with chrome hubs on the outside.
fn wheels(d: &Dims, l: Label, o: &mut Vec<ObjectDesc>) {
    let hw = d.width / 2.0;
    let tyre_w = 0.24;
    for x in d.axles {
        for sy in [-1.0, 1.0] {
            let y = sy * (hw - tyre_w / 2.0 + 0.02);
            o.push(wheel(d.wheel_r, tyre_w, [x, y, d.wheel_r], "rubber", l));
            o.push(wheel(
                d.wheel_r * 0.6,
                0.02,
                [x, y + sy * (tyre_w / 2.0 + 0.01), d.wheel_r],
                "chrome",
                l,
            ));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::desc::ShapeDesc;

    /// Min and max corners of a part in the body's frame: boxes are not
    /// turned; a wheel's axis lies along y, from its translation down by
    /// its width (see `parts::wheel`).
    fn extent(o: &ObjectDesc) -> ([f64; 3], [f64; 3]) {
        let t = o.transform.translate.unwrap();
        match o.shape {
            ShapeDesc::Box { size } => (
                [0, 1, 2].map(|k| t[k] - size[k] / 2.0),
                [0, 1, 2].map(|k| t[k] + size[k] / 2.0),
            ),
            ShapeDesc::Cylinder { radius, height, .. } => (
                [t[0] - radius, t[1] - height, t[2] - radius],
                [t[0] + radius, t[1], t[2] + radius],
            ),
            _ => panic!("unexpected part {o:?}"),
        }
    }

    #[test]
    fn parts_stay_in_the_footprint_lights_face_out_and_hubs_sit_outside_the_tyres() {
        for kind in BODIES {
            let parts = body(kind, class(kind.class()));
            let [len, w] = kind.footprint_m();
            for o in &parts {
                let (lo, hi) = extent(o);
                let inside = lo[0] >= -len / 2.0 - 1e-9
                    && hi[0] <= len / 2.0 + 1e-9
                    && lo[1] >= -w / 2.0 - 1e-9
                    && hi[1] <= w / 2.0 + 1e-9
                    && lo[2] >= -1e-9;
                assert!(inside, "{kind:?}: {lo:?}..{hi:?} of {o:?}");
            }
            let with = |m: &str| -> Vec<([f64; 3], [f64; 3])> {
                let of = parts.iter().filter(|o| o.material.as_deref() == Some(m));
                of.map(extent).collect()
            };
            let front = len / 2.0 - 0.1;
            let head = with("headlight_emit");
            let tail = with("taillight_emit");
            assert_eq!((head.len(), tail.len()), (2, 2), "{kind:?}");
            assert!(head.iter().all(|(lo, _)| lo[0] > front), "{kind:?}");
            assert!(tail.iter().all(|(_, hi)| hi[0] < -front), "{kind:?}");
            let (tyres, hubs) = (with("rubber"), with("chrome"));
            assert_eq!((tyres.len(), hubs.len()), (4, 4), "{kind:?}");
            let centre_y = |(lo, hi): &([f64; 3], [f64; 3])| (lo[1] + hi[1]) / 2.0;
            for (t, h) in tyres.iter().zip(&hubs) {
                assert!(t.0[2].abs() < 1e-12, "{kind:?}: a tyre off the ground");
                assert!(centre_y(h).abs() > centre_y(t).abs() + 0.1, "{kind:?}");
            }
        }
    }
}
