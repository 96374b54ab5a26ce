//! Licence plates: a white plate with raised black lettering front and
//! rear, `PLATE_VARIANTS` seeded registrations per model, each its own small
//! prefab (`<model>_plate<k>`) placed with the vehicle, so the body's
//! prototypes stay shared however many registrations there are.

use glam::{DAffine3, DVec3};

use crate::town::rng::Rng;
use crate::town::street::kit::{face_frame, turned, Kit};

/// Registrations per model.
pub const PLATE_VARIANTS: u32 = 4;
/// Stream tag of plate texts (apart from the generator's `rng::tag`s).
const PLATE_TAG: u64 = 0x706c_6174;
const PLATE_W: f64 = 0.52;
const PLATE_H: f64 = 0.12;
const PLATE_T: f64 = 0.01;

/// A registration like `AB12 CDE`, seeded by (model, variant).
pub fn plate_text(model: usize, variant: u32) -> String {
    let mut r = Rng::new(&[PLATE_TAG, model as u64, variant as u64]);
    let mut letter = || (b'A' + r.index(26) as u8) as char;
    let mut s: String = (0..2).map(|_| letter()).collect();
    let mut r2 = Rng::new(&[PLATE_TAG, model as u64, variant as u64, 1]);
    s.push_str(&format!("{:02} ", r2.index(100)));
    s.extend((0..3).map(|_| (b'A' + r2.index(26) as u8) as char));
    s
}

/// A plate whose back lies at `x0` facing +x (`front`) or −x, centred at
/// (y, z) = (0, `z`), into `kit`; `scale` shrinks it (two-wheelers).
pub fn plate(
    kit: &mut Kit,
    class: &'static str,
    text: &str,
    x0: f64,
    z: f64,
    front: bool,
    scale: f64,
) {
    let frame = if front {
        turned(face_frame(-x0, 0.0, z), 180.0)
    } else {
        face_frame(x0, 0.0, z)
    };
    let (w, h) = (PLATE_W * scale, PLATE_H * scale);
    let centre = frame.transform_point3(DVec3::new(0.0, 0.0, PLATE_T / 2.0));
    let t = DAffine3::from_mat3_translation(frame.matrix3, centre);
    kit.add(
        "plate",
        class,
        crate::scene::mesh::cuboid([w, h, PLATE_T]),
        t,
    );
    kit.text(
        "plate_ink",
        class,
        text,
        0.068 * scale,
        0.002,
        frame,
        [0.0, 0.0],
        PLATE_T,
    );
}
