//! Wheels: a tyre lathed from a rounded section (tread, shoulders,
//! bulging sidewalls), a rim barrel, a hub and spokes on the outer face,
//! a dark brake disc behind them; and the thin wheels of bicycles (a
//! narrow tyre, a rim ring and wire spokes).
//!
//! Wheel frame: centre at the origin, axle along y, outer face at +y.

use glam::{DAffine3, DQuat, DVec3};
use std::f64::consts::{PI, TAU};

use crate::town::street::kit::Kit;

use super::loft::lathe;
use super::spec::spow;

/// A rounded tyre section (r, y) between `rim_r` and `r`, `w` wide.
fn tyre_profile(r: f64, rim_r: f64, w: f64, n: usize) -> Vec<[f64; 2]> {
    let (rc, a, b) = ((r + rim_r) / 2.0, (r - rim_r) / 2.0, w / 2.0);
    (0..n)
        .map(|k| {
            let phi = TAU * k as f64 / n as f64;
            [rc + a * spow(phi.cos(), 0.5), b * spow(phi.sin(), 0.6)]
        })
        .collect()
}

/// A car wheel of radius `r` and tyre width `w`, placed by `t`.
pub fn car_wheel(kit: &mut Kit, class: &'static str, r: f64, w: f64, spokes: usize, t: DAffine3) {
    let rim_r = 0.66 * r;
    kit.add(
        "rubber",
        class,
        lathe(&tyre_profile(r, rim_r - 0.01, w, 24), 48),
        t,
    );
    let (y0, y1) = (-w / 2.0 + 0.02, w / 2.0 - 0.012);
    let barrel = [
        [rim_r - 0.012, y0],
        [rim_r, y0],
        [rim_r, y1],
        [rim_r - 0.012, y1],
    ];
    kit.add("rim", class, lathe(&barrel, 48), t);
    // Brake disc and caliper behind the spokes: the dark inside of the wheel.
    let disc = [
        [0.01, -0.03],
        [rim_r - 0.02, -0.03],
        [rim_r - 0.02, -0.005],
        [0.01, -0.005],
    ];
    kit.add("trim_black", class, lathe(&disc, 32), t);
    let hub = [
        [0.005, y1 - 0.05],
        [0.055, y1 - 0.05],
        [0.055, y1 - 0.01],
        [0.005, y1 - 0.01],
    ];
    kit.add("rim", class, lathe(&hub, 20), t);
    // Spokes: pairs of bars from the hub to the barrel on the outer face.
    let len = rim_r - 0.06;
    for k in 0..spokes {
        for d in [-0.09, 0.09] {
            let a = TAU * k as f64 / spokes as f64 + d;
            let rot = DQuat::from_rotation_y(-a);
            let c = rot * DVec3::new(0.05 + len / 2.0, y1 - 0.025, 0.0);
            let part = DAffine3::from_rotation_translation(rot, c);
            kit.add(
                "rim",
                class,
                crate::scene::mesh::cuboid([len, 0.02, 0.026]),
                t * part,
            );
        }
    }
}

/// A bicycle wheel of radius `r`: a narrow tyre, a rim ring, 32 wire
/// spokes laced from a hub 6 cm wide.
pub fn wire_wheel(kit: &mut Kit, class: &'static str, r: f64, t: DAffine3) {
    let tyre = tyre_profile(r, r - 0.04, 0.035, 16);
    kit.add("rubber", class, lathe(&tyre, 48), t);
    let rim = [
        [r - 0.06, -0.01],
        [r - 0.038, -0.01],
        [r - 0.038, 0.01],
        [r - 0.06, 0.01],
    ];
    kit.add("rim", class, lathe(&rim, 48), t);
    let hub = [[0.005, -0.04], [0.02, -0.04], [0.02, 0.04], [0.005, 0.04]];
    kit.add("rim", class, lathe(&hub, 12), t);
    for k in 0..32 {
        let a = TAU * k as f64 / 32.0;
        let side = if k % 2 == 0 { 0.03 } else { -0.03 };
        let h = DVec3::new(
            0.02 * (a + PI / 8.0).cos(),
            side,
            0.02 * (a + PI / 8.0).sin(),
        );
        let e = DVec3::new((r - 0.058) * a.cos(), 0.0, (r - 0.058) * a.sin());
        kit.rod(
            "rim",
            class,
            t.transform_point3(h),
            t.transform_point3(e),
            0.0012,
            4,
        );
    }
}
