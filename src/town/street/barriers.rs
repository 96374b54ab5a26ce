//! Linear furniture, built as repeatable units along local +x from x = 0:
//! park palisade and farm post-and-rail fences and pedestrian railings
//! (class `fence`), W-beam guard rails on posts (class `guard_rail`, the
//! beam's face towards local −y, the traffic side), wooden utility poles
//! (class `pole`) and the overhead wires of one span between two of them
//! (class `static`), sagging as a catenary.
//!
//! A unit's first post stands at x = 0; the next unit, placed one length
//! further, brings the post at its own start.

use glam::{DQuat, DVec3};

use crate::scene::desc::{ObjectDesc, PrefabDesc};

use super::kit::Kit;
use super::prefab;

/// Length of one palisade panel, metres.
pub const PALISADE_M: f64 = 2.5;
/// Length of one farm-fence unit, metres.
pub const FARM_FENCE_M: f64 = 3.0;
/// Length of one pedestrian-railing panel, metres.
pub const RAILING_M: f64 = 2.0;
/// Panels of the kerb railing run at a junction corner (`railing_run`).
pub const RAILING_PANELS: usize = 3;
/// Guard-rail units: (prefab, length in metres), longest first.
pub const GUARD_RAILS: [(&str, f64); 2] = [("guard_rail_32", 32.0), ("guard_rail_4", 4.0)];
/// Distance between utility poles (one wire span), metres.
pub const WIRE_SPAN_M: f64 = 36.0;
/// Height of the wires at the insulators, metres.
pub const WIRE_Z_M: f64 = 9.1;
/// Sag of the wires at mid-span, metres.
pub const WIRE_SAG_M: f64 = 0.45;
/// Lateral positions of the three wires on the crossarm (local y), metres.
pub const WIRE_Y_M: [f64; 3] = [-0.8, 0.0, 0.8];
/// Radius of a wire, metres.
pub const WIRE_R_M: f64 = 0.012;
/// Straight pieces per wire span.
const WIRE_PIECES: usize = 24;

/// Park palisade: square post, two rails, pointed-top bars every 12.5 cm.
fn palisade() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let (m, f) = ("street_paint_black", "fence");
    k.block(m, f, [0.06, 0.06, 1.3], [0.0, 0.0, 0.65]);
    for z in [0.15, 1.05] {
        k.block(
            m,
            f,
            [PALISADE_M - 0.06, 0.03, 0.04],
            [PALISADE_M / 2.0, 0.0, z],
        );
    }
    for i in 1..20 {
        let x = i as f64 * PALISADE_M / 20.0;
        k.block(m, f, [0.016, 0.016, 1.1], [x, 0.0, 0.6]);
    }
    k.objects()
}

/// Farm fence: a wooden post and three rails on its −y side.
fn farm_fence() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let (m, f) = ("street_wood", "fence");
    k.block(m, f, [0.1, 0.1, 1.2], [0.0, 0.0, 0.6]);
    for z in [0.35, 0.7, 1.05] {
        k.block(
            m,
            f,
            [FARM_FENCE_M, 0.04, 0.1],
            [FARM_FENCE_M / 2.0, -0.07, z],
        );
    }
    k.objects()
}

/// Pedestrian railing of `panels` panels: per panel a round post, top
/// and bottom rails and eight square bars; a closing post at the end of a run.
fn railing(panels: usize) -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let (m, f) = ("street_galvanised", "fence");
    for p in 0..panels {
        let x0 = p as f64 * RAILING_M;
        let post = DVec3::X * x0;
        k.rod(m, f, post, post + DVec3::Z * 1.05, 0.03, 8);
        for z in [0.2, 1.0] {
            let a = DVec3::new(x0 + 0.03, 0.0, z);
            k.rod(m, f, a, a + DVec3::X * (RAILING_M - 0.06), 0.02, 6);
        }
        // Square bars between the rails (their ends inside the rails).
        for i in 1..9 {
            let x = x0 + i as f64 * RAILING_M / 9.0;
            k.block(m, f, [0.016, 0.016, 0.8], [x, 0.0, 0.6]);
        }
    }
    if panels > 1 {
        let end = DVec3::X * (panels as f64 * RAILING_M);
        k.rod(m, f, end, end + DVec3::Z * 1.05, 0.03, 8);
    }
    k.objects()
}

/// A W-beam guard rail `len` m long: the beam (four 4 mm facets zig-zag
/// between y = 0 and the two peaks at y = −0.083 m, 0.40–0.71 m up) on
/// blocked-out posts every 2 m.
fn guard_rail(len: f64) -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let (m, g) = ("street_galvanised", "guard_rail");
    let (z0, dz, peak) = (0.4, 0.0775, -0.083);
    for i in 0..4 {
        let (ya, yb) = if i % 2 == 0 { (0.0, peak) } else { (peak, 0.0) };
        let (za, zb) = (z0 + dz * i as f64, z0 + dz * (i + 1) as f64);
        let l = ((yb - ya) * (yb - ya) + dz * dz).sqrt();
        // The facet's plane contains x and the profile segment.
        let rot = DQuat::from_rotation_x(-((yb - ya) / dz).atan());
        let c = DVec3::new(len / 2.0, (ya + yb) / 2.0, (za + zb) / 2.0);
        k.block_turned(m, g, [len, 0.004, l], c, rot);
    }
    let mut x = 0.0;
    while x < len - 1e-9 {
        k.block(
            "street_steel_dark",
            g,
            [0.1, 0.15, 0.8],
            [x + 0.05, 0.25, 0.4],
        );
        k.block(
            "street_steel_dark",
            g,
            [0.1, 0.17, 0.3],
            [x + 0.05, 0.09, 0.555],
        );
        x += 2.0;
    }
    k.objects()
}

/// A wooden utility pole with a crossarm along y and three insulators.
fn utility_pole() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    k.rod(
        "street_wood_pole",
        "pole",
        DVec3::ZERO,
        DVec3::Z * 9.4,
        0.13,
        10,
    );
    k.block("street_wood_pole", "pole", [0.1, 2.0, 0.1], [0.0, 0.0, 8.9]);
    for y in WIRE_Y_M {
        let a = DVec3::new(0.0, y, 8.95);
        k.rod(
            "street_insulator",
            "pole",
            a,
            a + DVec3::Z * (WIRE_Z_M - 8.95),
            0.04,
            8,
        );
    }
    k.objects()
}

/// Catenary parameter a of a span `s` with sag `sag`: a·(cosh(s/2a) − 1)
/// = sag, by bisection (the sag falls as a grows).
pub fn catenary_a(s: f64, sag: f64) -> f64 {
    let (mut lo, mut hi) = (s / 20.0, 1e6);
    for _ in 0..200 {
        let mid = (lo * hi).sqrt();
        if mid * ((s / (2.0 * mid)).cosh() - 1.0) > sag {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    (lo * hi).sqrt()
}

/// Height of a wire at x along a span, metres: the catenary through the
/// two insulator tops at x = 0 and x = `WIRE_SPAN_M`.
pub fn wire_z(x: f64) -> f64 {
    let (s, a) = (WIRE_SPAN_M, catenary_a(WIRE_SPAN_M, WIRE_SAG_M));
    WIRE_Z_M + a * (((x - s / 2.0) / a).cosh() - (s / (2.0 * a)).cosh())
}

/// The three wires of one span, straight pieces between catenary points.
fn wire_span() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    for y in WIRE_Y_M {
        let at = |i: usize| {
            let x = WIRE_SPAN_M * i as f64 / WIRE_PIECES as f64;
            DVec3::new(x, y, wire_z(x))
        };
        for i in 0..WIRE_PIECES {
            k.rod("street_wire", "static", at(i), at(i + 1), WIRE_R_M, 5);
        }
    }
    k.objects()
}

/// Every linear-furniture prefab.
pub fn barrier_prefabs() -> Vec<PrefabDesc> {
    let mut out = vec![
        prefab("fence_palisade", palisade()),
        prefab("fence_farm", farm_fence()),
        prefab("railing", railing(1)),
        prefab("railing_run", railing(RAILING_PANELS)),
        prefab("utility_pole", utility_pole()),
        prefab("wire_span", wire_span()),
    ];
    out.extend(GUARD_RAILS.map(|(name, len)| prefab(name, guard_rail(len))));
    out
}
