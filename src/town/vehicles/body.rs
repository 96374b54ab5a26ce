//! A four-wheeled body from its `Spec`: the lofted lower body in paint,
//! the glass house as a thin glass shell with painted roof and pillars
//! lifted off it, panel seams, bumpers, grille, mirrors and wipers. Lamps,
//! wheels, the interior and plates come from their own modules.

use glam::{DAffine3, DVec3};
use std::f64::consts::PI;

use crate::scene::mesh::ellipsoid;
use crate::town::street::kit::Kit;

use super::bed::open_lower_body;
use super::loft::grid;
use super::spec::Spec;

/// The paint slot every body panel uses (remapped per vehicle).
pub const PAINT: &str = "car_paint";

/// Stations of the lower body along x per metre, and round its section.
const LOFT_PER_M: f64 = 16.0;
const SECTION_STEPS: usize = 40;

/// Body panels in paint into `paint`, glass, trim and seams into `parts`.
pub fn body(s: &Spec, class: &'static str, paint: &mut Kit, parts: &mut Kit) {
    let hl = s.hl();
    let id = DAffine3::IDENTITY;
    let nx = ((s.length * LOFT_PER_M) as usize).clamp(60, 110);
    let lower = |x: f64, th: f64| s.lower(x, th);
    match &s.bed {
        None => paint.add(
            PAINT,
            class,
            grid(
                &lower,
                (-hl, hl, nx),
                (0.0, 2.0 * PI, SECTION_STEPS),
                0.0,
                true,
            ),
            id,
        ),
        Some(bed) => {
            for m in open_lower_body(s, bed, SECTION_STEPS, LOFT_PER_M) {
                paint.add(PAINT, class, m, id);
            }
        }
    }
    glass_house(s, class, paint, parts);
    seams_and_trim(s, class, parts);
    mirrors_and_wipers(s, class, paint, parts);
    if let Some(x0) = s.cargo_front_x {
        // The box truck's cargo box on its frame behind the cab.
        let (z0, z1) = (s.top_z(x0) - 0.15, 3.3);
        let len = x0 + hl - 0.02;
        let c = [(x0 - hl + 0.02) / 2.0, 0.0, (z0 + z1) / 2.0];
        parts.block("cargo", class, [len, s.width, z1 - z0], c);
        parts.block(
            "trim_black",
            class,
            [len + 0.01, s.width - 0.1, 0.12],
            [c[0], 0.0, z0 - 0.04],
        );
    }
}

/// The glass shell (outer surface out, inner surface in, 6 mm apart) and
/// the painted roof and pillars just outside it.
fn glass_house(s: &Spec, class: &'static str, paint: &mut Kit, parts: &mut Kit) {
    let id = DAffine3::IDENTITY;
    let (x0, x1) = (s.rear_x, s.ws_x);
    let nx = (((x1 - x0) * 20.0) as usize).clamp(24, 110);
    let outer = |x: f64, th: f64| s.glass(x, th, 0.0);
    let inner = |x: f64, th: f64| s.glass(x, th, 0.006);
    parts.add(
        "car_glass",
        class,
        grid(&outer, (x0, x1, nx), (0.0, PI, 32), 0.0, true),
        id,
    );
    parts.add(
        "car_glass",
        class,
        grid(&inner, (x0, x1, nx), (0.0, PI, 32), 0.0, false),
        id,
    );

    let mut skin = |xa: f64, xb: f64, ta: f64, tb: f64| {
        let (xa, xb) = (xa.max(x0), xb.min(x1));
        if xb - xa < 0.01 {
            return;
        }
        let n = (((xb - xa) * 20.0) as usize).clamp(1, 160);
        let m = grid(&outer, (xa, xb, n), (ta * PI, tb * PI, 8), 0.004, true);
        paint.add(PAINT, class, m, id);
    };
    let edge = 0.3;
    // Roof, and the A pillars framing the windscreen.
    skin(
        s.roof_rear_x - 0.04,
        s.roof_front_x + 0.04,
        edge,
        1.0 - edge,
    );
    skin(s.roof_front_x - 0.05, x1, edge - 0.07, edge);
    skin(s.roof_front_x - 0.05, x1, 1.0 - edge, 1.0 - edge + 0.07);
    let side = |skin: &mut dyn FnMut(f64, f64, f64, f64), xa: f64, xb: f64| {
        skin(xa, xb, 0.0, edge);
        skin(xa, xb, 1.0 - edge, 1.0);
    };
    if s.cargo_front_x.is_some() {
        // The cab's back wall.
        skin(x0, s.roof_rear_x + 0.05, 0.0, 1.0);
        return;
    }
    let len = s.roof_front_x - s.roof_rear_x;
    if s.length > 9.0 {
        // Bus: a pillar every 1.25 m, rear wall painted.
        let mut x = s.roof_front_x - 0.6;
        while x > s.roof_rear_x + 0.5 {
            side(&mut skin, x - 0.05, x + 0.05);
            x -= 1.25;
        }
        skin(x0, s.roof_rear_x + 0.05, 0.0, 1.0);
        return;
    }
    // Rear pillars (C or D) round the rear window.
    side(&mut skin, s.roof_rear_x - 0.06, s.roof_rear_x + 0.2);
    skin(x0, s.roof_rear_x, edge - 0.1, edge);
    skin(x0, s.roof_rear_x, 1.0 - edge, 1.0 - edge + 0.1);
    match s.doors {
        1 => {
            // Van: windowless cargo sides behind the B pillar.
            side(&mut skin, x0, s.roof_front_x - 0.75);
        }
        2 => side(&mut skin, s.roof_rear_x + 0.2, s.roof_rear_x + 0.35),
        _ => {
            let xb = s.roof_rear_x + 0.5 * len + 0.05;
            side(&mut skin, xb - 0.06, xb + 0.06);
        }
    }
}

/// Door and lid shut lines (dark grooves), bumpers, grille and the cabin
/// floor seen through the glass.
fn seams_and_trim(s: &Spec, class: &'static str, parts: &mut Kit) {
    let id = DAffine3::IDENTITY;
    let hl = s.hl();
    let lower = |x: f64, th: f64| s.lower(x, th);
    let mut strip = |mat: &str, xa: f64, xb: f64, ta: f64, tb: f64, lift: f64, nt: usize| {
        let n = (((xb - xa) * 12.0) as usize).clamp(1, 80);
        let m = grid(&lower, (xa, xb, n), (ta * PI, tb * PI, nt), lift, true);
        parts.add(mat, class, m, id);
    };
    let len = s.roof_front_x - s.roof_rear_x;
    let mut doors = vec![s.ws_x - 0.06];
    match s.doors {
        1 => doors.push(s.roof_front_x - 0.75),
        2 => doors.push(s.roof_rear_x + 0.3),
        _ => doors.extend([s.roof_rear_x + 0.5 * len + 0.05, s.roof_rear_x + 0.1]),
    }
    if s.length > 9.0 {
        doors = vec![s.hl() - 0.6, s.hl() - 1.6, -0.2, -1.2];
    }
    for x in doors {
        strip("seam", x - 0.004, x + 0.004, -0.3, 0.28, 0.001, 12);
        strip("seam", x - 0.004, x + 0.004, 0.72, 1.3, 0.001, 12);
    }
    // Bonnet and boot shut lines across the top.
    strip("seam", s.ws_x - 0.1, s.ws_x - 0.092, 0.25, 0.75, 0.001, 12);
    if s.rear_x > -hl + 0.5 {
        strip(
            "seam",
            s.rear_x - 0.06,
            s.rear_x - 0.052,
            0.25,
            0.75,
            0.001,
            12,
        );
    }
    // Bumpers wrap the lower corners; the grille fills the nose.
    strip("trim_black", hl - 0.3, hl, 1.1, 1.9, 0.008, 24);
    strip("trim_black", -hl, -hl + 0.3, 1.1, 1.9, 0.008, 24);
    strip("grille", hl - 0.05, hl, -0.1, 0.06, 0.003, 6);
    strip("grille", hl - 0.05, hl, 0.94, 1.1, 0.003, 6);
    // The cabin floor under the glass (dark, hides the body's top skin).
    strip("car_interior", s.rear_x, s.ws_x, 0.4, 0.6, 0.003, 8);
}

/// Door mirrors (painted housing on a black stalk, a mirror glass facing
/// back) and two wipers at the windscreen base.
fn mirrors_and_wipers(s: &Spec, class: &'static str, paint: &mut Kit, parts: &mut Kit) {
    for (y, z) in mirror_points(s) {
        let x = s.ws_x - 0.12;
        let sy = y.signum();
        let at = DAffine3::from_translation(DVec3::new(x, y, z));
        paint.add(PAINT, class, ellipsoid([0.07, 0.085, 0.06], 16, 10), at);
        let glass = DAffine3::from_translation(DVec3::new(x - 0.066, y, z));
        parts.add(
            "mirror",
            class,
            ellipsoid([0.006, 0.075, 0.05], 16, 8),
            glass,
        );
        let root = DVec3::new(
            x + 0.02,
            sy * (s.lower_half_width_at(x, z - 0.05) - 0.02),
            z - 0.05,
        );
        parts.rod(
            "trim_black",
            class,
            root,
            DVec3::new(x, y - sy * 0.05, z - 0.02),
            0.015,
            6,
        );
    }
    let (x, z) = (s.ws_x - 0.04, s.glass_base_z(s.ws_x - 0.04) + 0.04);
    for yc in [0.35, -0.25] {
        let a = DVec3::new(x, yc + 0.3, z + 0.01);
        let b = DVec3::new(x - 0.03, yc - 0.22, z + 0.02);
        parts.rod("trim_black", class, a, b, 0.008, 6);
    }
}

/// The centres (y, z) of the left and right door mirror housings: just
/// outside the body at the windscreen base, reaching `MIRROR_REACH_M`.
pub fn mirror_points(s: &Spec) -> [(f64, f64); 2] {
    let (x, z) = (s.ws_x - 0.12, s.glass_base_z(s.ws_x) + 0.1);
    // Close to the door's top, but never past the footprint.
    let door = s.lower_half_width_at(x, z - 0.12);
    let y = (door + 0.1).min(s.width / 2.0 + MIRROR_REACH_M - 0.085);
    [(y, z), (-y, z)]
}

/// How far a mirror housing reaches beyond the body's width, metres.
pub const MIRROR_REACH_M: f64 = 0.11;
