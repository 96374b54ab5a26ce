//! Motorcycles and bicycles (riders are placed on `BodyKind::seat`): a
//! motorcycle's tank, tail and mudguards in paint over a tube frame, an
//! engine, exhaust, fork, handlebar and lamps (its rear plate is the
//! model's plate prefab); a bicycle's diamond frame in paint, wire wheels,
//! saddle, crank and pedals.
//!
//! Body frame as for cars: x forward, y left, z up, on the ground.

use glam::{DAffine3, DVec3};

use crate::scene::mesh::ellipsoid;
use crate::town::street::kit::Kit;

use super::body::PAINT;
use super::wheels::{car_wheel, wire_wheel};

/// Motorcycle wheelbase half and wheel radius, metres.
pub const MOTO_AXLE_X: f64 = 0.68;
const MOTO_R: f64 = 0.3;
/// Bicycle wheelbase half and wheel radius, metres.
pub const BIKE_AXLE_X: f64 = 0.525;
const BIKE_R: f64 = 0.34;
/// Front lamp of a motorcycle and of a bicycle (body frame).
pub const MOTO_LAMP: [f64; 3] = [0.62, 0.0, 0.95];
/// The bicycle's front lamp on the handlebar.
pub const BIKE_LAMP: [f64; 3] = [0.5, 0.0, 0.92];

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

fn at(x: f64, y: f64, z: f64) -> DAffine3 {
    DAffine3::from_translation(v(x, y, z))
}

/// A motorcycle: paint into `paint`, everything else into `parts`.
pub fn motorcycle(class: &'static str, paint: &mut Kit, parts: &mut Kit) {
    let (ax, r) = (MOTO_AXLE_X, MOTO_R);
    // Wheels: centred on y = 0 (their outer face is +y: shift by half).
    car_wheel(
        parts,
        class,
        r,
        0.13,
        5,
        at(ax, -0.065, r) * DAffine3::IDENTITY,
    );
    car_wheel(parts, class, r, 0.16, 5, at(-ax, -0.08, r));
    let head = v(0.45, 0.0, 0.98);
    for y in [-0.09, 0.09] {
        parts.rod(
            "chrome",
            class,
            head + v(0.0, y, 0.0),
            v(ax, y, r),
            0.022,
            10,
        );
        parts.rod(
            "frame_dark",
            class,
            v(-0.1, y, 0.45),
            v(-ax, y, r),
            0.025,
            8,
        );
    }
    parts.rod("frame_dark", class, head, v(-0.25, 0.0, 0.78), 0.03, 10);
    parts.rod("frame_dark", class, head, v(0.05, 0.0, 0.3), 0.03, 10);
    parts.rod(
        "frame_dark",
        class,
        v(0.05, 0.0, 0.3),
        v(-0.12, 0.0, 0.45),
        0.03,
        10,
    );
    parts.block("engine", class, [0.42, 0.3, 0.34], [0.08, 0.0, 0.48]);
    parts.rod(
        "chrome",
        class,
        v(0.2, -0.16, 0.35),
        v(-0.7, -0.18, 0.5),
        0.045,
        14,
    );
    paint.add(
        PAINT,
        class,
        ellipsoid([0.3, 0.16, 0.13], 24, 12),
        at(0.18, 0.0, 0.92),
    );
    paint.add(
        PAINT,
        class,
        ellipsoid([0.3, 0.1, 0.07], 20, 10),
        at(-0.55, 0.0, 0.84),
    );
    paint.add(
        PAINT,
        class,
        ellipsoid([0.3, 0.075, 0.05], 20, 8),
        at(ax - 0.02, 0.0, r + 0.22),
    );
    parts.add(
        "seat_leather",
        class,
        ellipsoid([0.33, 0.15, 0.06], 20, 10),
        at(-0.22, 0.0, 0.86),
    );
    parts.rod(
        "trim_black",
        class,
        v(0.42, -0.36, 1.06),
        v(0.42, 0.36, 1.06),
        0.014,
        8,
    );
    parts.add(
        "headlight_emit",
        class,
        // Its back half would sit inside the reflector.
        super::lamps::dome([0.05, 0.085, 0.085], 8, 4, 1.0),
        at(MOTO_LAMP[0], 0.0, MOTO_LAMP[2]),
    );
    parts.add(
        "chrome",
        class,
        ellipsoid([0.06, 0.1, 0.1], 16, 8),
        at(MOTO_LAMP[0] - 0.03, 0.0, MOTO_LAMP[2]),
    );
    parts.add(
        "taillight_emit",
        class,
        ellipsoid([0.02, 0.06, 0.03], 8, 4),
        at(-0.83, 0.0, 0.84),
    );
    for y in [-0.15, 0.15] {
        parts.add(
            "lamp_amber",
            class,
            ellipsoid([0.03, 0.02, 0.02], 8, 4),
            at(0.55, y, 0.9),
        );
    }
}

/// A bicycle: frame into `paint`, everything else into `parts`.
pub fn bicycle(class: &'static str, paint: &mut Kit, parts: &mut Kit) {
    let (ax, r) = (BIKE_AXLE_X, BIKE_R);
    wire_wheel(parts, class, r, at(ax, 0.0, r));
    wire_wheel(parts, class, r, at(-ax, 0.0, r));
    let bb = v(0.0, 0.0, 0.3);
    let seat = v(-0.17, 0.0, 0.85);
    let (head_top, head_low) = (v(0.42, 0.0, 0.88), v(0.45, 0.0, 0.72));
    let tube = |paint: &mut Kit, a: DVec3, b: DVec3| paint.rod(PAINT, class, a, b, 0.016, 10);
    tube(paint, seat, head_top);
    tube(paint, bb, head_low);
    tube(paint, bb, seat);
    tube(paint, head_low, head_top);
    for y in [-0.05, 0.05] {
        tube(paint, bb, v(-ax, y, r));
        tube(paint, seat, v(-ax, y, r));
        parts.rod("chrome", class, head_low, v(ax, y, r), 0.011, 8);
    }
    parts.rod("chrome", class, head_top, v(0.4, 0.0, 0.98), 0.012, 8);
    parts.rod(
        "trim_black",
        class,
        v(0.42, -0.28, 0.98),
        v(0.42, 0.28, 0.98),
        0.012,
        8,
    );
    parts.rod("chrome", class, seat, v(-0.2, 0.0, 0.93), 0.012, 8);
    parts.add(
        "seat_leather",
        class,
        ellipsoid([0.13, 0.07, 0.03], 16, 8),
        at(-0.19, 0.0, 0.95),
    );
    // Crank and pedals (left pedal forward-down).
    for (s, a) in [(1.0, 0.6f64), (-1.0, 0.6 + std::f64::consts::PI)] {
        let p = v(0.17 * a.cos(), s * 0.09, 0.3 - 0.17 * a.sin());
        parts.rod("trim_black", class, bb + v(0.0, s * 0.05, 0.0), p, 0.01, 6);
        parts.block("trim_black", class, [0.09, 0.07, 0.02], p.to_array());
    }
    parts.add(
        "headlight_emit",
        class,
        ellipsoid([0.025, 0.03, 0.025], 8, 4),
        at(BIKE_LAMP[0], 0.0, BIKE_LAMP[2]),
    );
    parts.add(
        "taillight_emit",
        class,
        ellipsoid([0.01, 0.025, 0.015], 8, 4),
        at(-0.2, 0.0, 0.8),
    );
}
