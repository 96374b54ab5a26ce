//! Lamps of a four-wheeled body: domed head-lamp lenses (emitters) in a
//! chrome reflector, red tail lamps (emitters) in black housings, amber
//! indicator lenses front and rear and a high-mounted brake lens, each
//! set into the body's surface where `Spec::end_x` finds it. The brake
//! lens and each side's indicators have their own material slots, which a
//! frame maps to an emitter while lit (`town::dynamic_objects`). Lenses
//! are the outer half of an ellipsoid (`dome`): the inner half would sit in
//! the body, emit into it and give light sampling twice the triangles.

use glam::{DAffine3, DVec3};

use crate::scene::mesh::{ellipsoid, LocalMesh};
use crate::town::street::kit::Kit;

use super::spec::Spec;

/// Head-lamp lens centres (left, right) in the body frame: set 3 cm into
/// the nose under the bonnet line, 30 cm in from each side.
pub fn headlamp_points(s: &Spec) -> [[f64; 3]; 2] {
    let z = s.nose_z - 0.1;
    let y = s.width / 2.0 - 0.3;
    let x = s.end_x(1.0, y, z) - 0.03;
    [[x, y, z], [x, -y, z]]
}

/// Tail-lamp centres (left, right): 20 cm in from each side, 10 cm under
/// the boot deck.
pub fn taillamp_points(s: &Spec) -> [[f64; 3]; 2] {
    let z = s.deck_z - 0.12;
    let y = s.width / 2.0 - 0.22;
    let x = s.end_x(-1.0, y, z) + 0.025;
    [[x, y, z], [x, -y, z]]
}

/// Material slot of the brake lamps (the tail lamps glow brighter too).
pub const BRAKE_SLOT: &str = "lamp_red";
/// Material slots of the left and right indicators.
pub const INDICATOR_SLOTS: [&str; 2] = ["indicator_left", "indicator_right"];
/// Every lens slot a frame may light: they live in the lamps prefab.
pub const LIT_SLOTS: [&str; 3] = [BRAKE_SLOT, INDICATOR_SLOTS[0], INDICATOR_SLOTS[1]];

/// The indicator slot of the side at body-frame `y` (> 0: left).
fn indicator(y: f64) -> &'static str {
    INDICATOR_SLOTS[usize::from(y < 0.0)]
}

/// The half of an ellipsoid (`radii`, `segments` around z, `rings` pole to
/// pole) on the side `outward` (±1) along x, its rim in the yz plane.
/// `segments` is a multiple of 4, so the rim runs along vertex columns
/// and every kept triangle is whole.
pub fn dome(radii: [f64; 3], segments: u32, rings: u32, outward: f64) -> LocalMesh {
    assert!(segments.is_multiple_of(4), "{segments} segments");
    let full = ellipsoid(radii, segments, rings);
    let kept: Vec<[u32; 3]> = full
        .triangles
        .iter()
        .copied()
        .filter(|t| t.iter().map(|&i| full.positions[i as usize].x).sum::<f64>() * outward > 0.0)
        .collect();
    // Only the vertices the kept triangles use, in their first order.
    let mut index = vec![u32::MAX; full.positions.len()];
    let mut m = LocalMesh::default();
    for &i in kept.iter().flatten() {
        if index[i as usize] == u32::MAX {
            index[i as usize] = m.positions.len() as u32;
            m.positions.push(full.positions[i as usize]);
            m.normals.push(full.normals[i as usize]);
        }
    }
    m.triangles = kept.iter().map(|t| t.map(|i| index[i as usize])).collect();
    m
}

fn at(p: [f64; 3]) -> DAffine3 {
    DAffine3::from_translation(DVec3::from(p))
}

/// Every lamp of the body into `parts`.
pub fn lamps(s: &Spec, class: &'static str, parts: &mut Kit) {
    for p in headlamp_points(s) {
        parts.add(
            "headlight_emit",
            class,
            dome([0.05, 0.15, 0.055], 8, 4, 1.0),
            at(p),
        );
        parts.add(
            "chrome",
            class,
            ellipsoid([0.035, 0.17, 0.07], 20, 8),
            at(p),
        );
        // The indicator beside it, towards the corner.
        let y = p[1].signum() * (s.width / 2.0 - 0.09);
        let x = s.end_x(1.0, y, p[2]) - 0.02;
        parts.add(
            indicator(y),
            class,
            dome([0.03, 0.045, 0.03], 12, 6, 1.0),
            at([x, y, p[2]]),
        );
    }
    for p in taillamp_points(s) {
        parts.add(
            "taillight_emit",
            class,
            dome([0.04, 0.14, 0.05], 8, 4, -1.0),
            at(p),
        );
        parts.add(
            "trim_black",
            class,
            ellipsoid([0.03, 0.16, 0.065], 20, 8),
            at(p),
        );
        let y = p[1].signum() * (s.width / 2.0 - 0.42);
        let x = s.end_x(-1.0, y, p[2]) + 0.02;
        parts.add(
            indicator(y),
            class,
            dome([0.03, 0.06, 0.03], 12, 6, -1.0),
            at([x, y, p[2]]),
        );
    }
    // The high-mounted brake lens on the boot or tailgate top.
    let z = s.deck_z - 0.03;
    let x = s.end_x(-1.0, 0.0, z) + 0.01;
    parts.add(
        "lamp_red",
        class,
        dome([0.02, 0.12, 0.018], 12, 6, -1.0),
        at([x, 0.0, z]),
    );
}
