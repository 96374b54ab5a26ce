//! A clipped hedge: a 2 m segment (placed end to end) of a dense dark core
//! under a skin of individual leaves standing just proud of its sides and
//! top, each tilted at random so the surface reads leafy at close range.

use glam::DVec3;

use super::mesh::{perpendicular, Blade, PlantMesh};
use crate::sampler::rng::Rng;

/// Segment length along local x, metres (the placement pitch).
pub const HEDGE_LEN_M: f64 = 2.0;
/// Depth along local y, metres.
pub const HEDGE_DEPTH_M: f64 = 0.8;
/// Height, metres.
pub const HEDGE_HEIGHT_M: f64 = 1.3;
/// Leaves per square metre of hedge face.
const LEAVES_PER_M2: f64 = 260.0;
/// How far the core sits inside the outer size, metres.
const SKIN_M: f64 = 0.05;

/// Size of the core box (centred on x and y, standing on z = 0).
pub fn core_size() -> [f64; 3] {
    [
        HEDGE_LEN_M,
        HEDGE_DEPTH_M - 2.0 * SKIN_M,
        HEDGE_HEIGHT_M - SKIN_M,
    ]
}

/// The leaves of one segment: on both long sides and the top, each based
/// within the skin and facing out.
pub fn hedge_leaves(mut r: Rng) -> (PlantMesh, usize) {
    let mut m = PlantMesh::default();
    let [l, d, h] = core_size();
    // (face normal, two in-face axes with their extents, face centre)
    let faces = [
        (
            DVec3::Y,
            [(DVec3::X, l), (DVec3::Z, h)],
            DVec3::new(0.0, d / 2.0, h / 2.0),
        ),
        (
            -DVec3::Y,
            [(DVec3::X, l), (DVec3::Z, h)],
            DVec3::new(0.0, -d / 2.0, h / 2.0),
        ),
        (
            DVec3::Z,
            [(DVec3::X, l), (DVec3::Y, d)],
            DVec3::new(0.0, 0.0, h),
        ),
    ];
    let mut n = 0;
    for (normal, [(a, la), (b, lb)], centre) in faces {
        let count = (la * lb * LEAVES_PER_M2).round() as usize;
        for _ in 0..count {
            let s = r.range(-0.5, 0.5) * la;
            // Keep whole leaves inside the segment's length so neighbours
            // never interpenetrate at the joint.
            let s = if a == DVec3::X {
                s.clamp(-la / 2.0 + 0.06, la / 2.0 - 0.06)
            } else {
                s
            };
            let t = r.range(-0.5, 0.5) * lb;
            let base = centre + a * s + b * t + normal * r.range(0.0, 0.6 * SKIN_M);
            let tilt = DVec3::new(r.range(-0.6, 0.6), r.range(-0.6, 0.6), r.range(-0.6, 0.6));
            let up = (normal + tilt).normalize();
            let axis = perpendicular(up);
            let spin = r.range(0.0, std::f64::consts::TAU);
            let axis = (axis * spin.cos() + up.cross(axis) * spin.sin()).normalize();
            let blade = Blade {
                len: r.range(0.045, 0.07),
                width: r.range(0.03, 0.045),
                widest: 0.45,
            };
            m.leaf(base - axis * (blade.len / 2.0), axis, up, blade, 0.004);
            n += 1;
        }
    }
    (m, n)
}
