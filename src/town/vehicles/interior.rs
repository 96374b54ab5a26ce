//! The cabin seen through the glass: a dashboard under the windscreen, a
//! steering wheel on its column (driver on the left), seats with reclined
//! backs and head-rests in rows (a bus has many), a bulkhead behind a van's
//! or truck's front row.

use glam::{DAffine3, DQuat, DVec3};

use crate::town::street::kit::Kit;

use super::loft::lathe;
use super::spec::Spec;

/// One seat of `width` with its back's foot at (x, y, z).
fn seat(kit: &mut Kit, class: &'static str, x: f64, y: f64, z: f64, width: f64) {
    kit.block(
        "car_interior",
        class,
        [0.5, width, 0.12],
        [x + 0.25, y, z - 0.06],
    );
    let recline = DQuat::from_rotation_y(-0.25);
    let back = DVec3::new(x - 0.05, y, z + 0.3);
    kit.block_turned("car_interior", class, [0.1, width, 0.62], back, recline);
    let rest = DVec3::new(x - 0.13, y, z + 0.7);
    kit.block_turned(
        "car_interior",
        class,
        [0.09, width.min(0.28), 0.18],
        rest,
        recline,
    );
}

/// Everything inside the cabin into `parts`.
pub fn interior(s: &Spec, class: &'static str, parts: &mut Kit) {
    let hw = s.width / 2.0 - 0.12;
    let dash_x = s.ws_x - 0.22;
    let dash_z = s.glass_base_z(dash_x) + 0.03;
    parts.block(
        "plastic_black",
        class,
        [0.36, 2.0 * hw - 0.1, 0.16],
        [dash_x, 0.0, dash_z - 0.05],
    );
    // Seat backs rise above the waist so that they show through the glass.
    let seat_z = s.belt_z - 0.4;
    let front_x = dash_x - 0.85;
    let driver_y = 0.4 * s.width / 1.8;
    // Steering wheel: a torus on a column, facing the driver.
    let ring = [[0.17, -0.015], [0.19, -0.015], [0.19, 0.015], [0.17, 0.015]];
    let axis = DVec3::new(-0.8, 0.0, 0.6).normalize();
    let centre = DVec3::new(dash_x - 0.32, driver_y, dash_z + 0.12);
    let t = DAffine3::from_rotation_translation(DQuat::from_rotation_arc(DVec3::Y, axis), centre);
    parts.add("plastic_black", class, lathe(&ring, 32), t);
    parts.rod(
        "plastic_black",
        class,
        centre,
        centre - axis * 0.35,
        0.03,
        8,
    );
    for y in [driver_y, -driver_y] {
        seat(parts, class, front_x, y, seat_z, 0.5);
    }
    if s.doors == 1 {
        // Vans, trucks and buses.
        if s.length < 9.0 {
            let bx = front_x - 0.3;
            parts.block(
                "plastic_black",
                class,
                [0.04, 2.0 * hw, 0.9],
                [bx, 0.0, s.belt_z + 0.2],
            );
            return;
        }
        let mut x = front_x - 1.0;
        while x > s.rear_x + 0.6 {
            for y in [0.75, 0.3, -0.3, -0.75] {
                seat(parts, class, x, y * s.width / 2.45, seat_z, 0.42);
            }
            x -= 0.85;
        }
        return;
    }
    let rear_x = front_x - 0.9;
    if rear_x > s.rear_x + 0.15 {
        seat(parts, class, rear_x, 0.0, seat_z, 2.0 * hw - 0.2);
    }
}
