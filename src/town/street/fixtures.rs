//! Street fixtures, class `static`: benches, bins, bollards, a hydrant, a
//! parking meter, a bus shelter with glass panels and lettered billboards.
//! Local frame: z up, origin on the ground; the user side (a bench's
//! seat, a shelter's open side, a meter's display, a billboard's print)
//! faces local −x, towards the road when placed like a sign.

use glam::{DQuat, DVec3};

use crate::scene::desc::{ObjectDesc, PrefabDesc};

use super::kit::{face_frame, prism, regular, Kit};
use super::names::SLOGANS;
use super::prefab;
use super::signs::{rect, FaceDesign};

const ST: &str = "static";

/// Wooden slatted bench with cast legs and a tilted backrest, 1.8 m.
fn bench_wood() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    for y in [-0.75, 0.75] {
        k.block("street_paint_black", ST, [0.45, 0.06, 0.42], [0.0, y, 0.21]);
        k.block("street_paint_black", ST, [0.06, 0.06, 0.5], [0.2, y, 0.65]);
    }
    for i in 0..4 {
        let x = -0.18 + 0.11 * i as f64;
        k.block("street_wood", ST, [0.09, 1.8, 0.035], [x, 0.0, 0.44]);
    }
    let tilt = DQuat::from_rotation_y(-0.26);
    for z in [0.62, 0.76] {
        k.block_turned(
            "street_wood",
            ST,
            [0.035, 1.8, 0.1],
            DVec3::new(0.22, 0.0, z),
            tilt,
        );
    }
    k.objects()
}

/// Backless steel bench: a slab on two legs, 1.6 m.
fn bench_steel() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    for y in [-0.65, 0.65] {
        k.block("street_steel_dark", ST, [0.4, 0.05, 0.42], [0.0, y, 0.21]);
    }
    k.block("street_galvanised", ST, [0.45, 1.6, 0.04], [0.0, 0.0, 0.44]);
    k.objects()
}

/// Round litter bin on a short post, with a rim and a lid.
fn bin_round() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let g = "street_paint_green";
    k.rod(g, ST, DVec3::ZERO, DVec3::Z * 0.2, 0.05, 8);
    k.rod(g, ST, DVec3::Z * 0.2, DVec3::Z * 0.95, 0.24, 16);
    k.rod(g, ST, DVec3::Z * 0.9, DVec3::Z * 0.95, 0.26, 16);
    k.rod(
        "street_paint_black",
        ST,
        DVec3::Z * 0.95,
        DVec3::Z * 1.0,
        0.2,
        16,
    );
    k.objects()
}

/// Square bin with a slot in its lid.
fn bin_box() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    k.block("street_paint_black", ST, [0.5, 0.5, 0.9], [0.0, 0.0, 0.45]);
    k.block(
        "street_paint_grey",
        ST,
        [0.54, 0.54, 0.05],
        [0.0, 0.0, 0.925],
    );
    k.block(
        "street_plastic_black",
        ST,
        [0.02, 0.3, 0.1],
        [-0.255, 0.0, 0.75],
    );
    k.objects()
}

/// Steel bollard with a reflective band and a cap.
fn bollard_steel() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    k.rod(
        "street_galvanised",
        ST,
        DVec3::ZERO,
        DVec3::Z * 0.9,
        0.1,
        12,
    );
    k.rod(
        "street_paint_yellow",
        ST,
        DVec3::Z * 0.72,
        DVec3::Z * 0.8,
        0.103,
        12,
    );
    k.rod(
        "street_galvanised",
        ST,
        DVec3::Z * 0.9,
        DVec3::Z * 0.94,
        0.112,
        12,
    );
    k.objects()
}

/// Squat concrete bollard with a chamfered top.
fn bollard_concrete() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let c = "street_concrete";
    k.add(
        c,
        ST,
        prism(&regular(8, 0.2, 0.0), 0.0, 0.6),
        Default::default(),
    );
    k.add(
        c,
        ST,
        prism(&regular(8, 0.15, 0.0), 0.6, 0.68),
        Default::default(),
    );
    k.objects()
}

/// A pillar hydrant: flange, barrel, bonnet, nut and three outlets.
fn hydrant() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let r = "street_paint_red";
    k.rod(r, ST, DVec3::ZERO, DVec3::Z * 0.06, 0.16, 12);
    k.rod(r, ST, DVec3::Z * 0.06, DVec3::Z * 0.6, 0.12, 12);
    k.rod(r, ST, DVec3::Z * 0.6, DVec3::Z * 0.68, 0.135, 12);
    k.rod(r, ST, DVec3::Z * 0.68, DVec3::Z * 0.74, 0.04, 5);
    for d in [DVec3::Y, DVec3::NEG_Y] {
        let a = DVec3::Z * 0.42;
        k.rod(r, ST, a, a + d * 0.19, 0.045, 8);
    }
    let a = DVec3::Z * 0.38;
    k.rod("street_paint_black", ST, a, a + DVec3::NEG_X * 0.2, 0.06, 8);
    k.objects()
}

/// A parking meter: post, head and display facing −x.
fn parking_meter() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    k.rod(
        "street_paint_grey",
        ST,
        DVec3::ZERO,
        DVec3::Z * 1.1,
        0.04,
        8,
    );
    k.block(
        "street_steel_dark",
        ST,
        [0.18, 0.22, 0.34],
        [0.0, 0.0, 1.27],
    );
    k.block(
        "street_plastic_black",
        ST,
        [0.01, 0.13, 0.07],
        [-0.095, 0.0, 1.36],
    );
    k.block(
        "street_galvanised",
        ST,
        [0.01, 0.05, 0.02],
        [-0.095, 0.0, 1.22],
    );
    k.objects()
}

/// A bus shelter open towards −x: four posts, a roof, glass back and side
/// panels in rails, a bench inside and a route sign on the roof edge.
fn bus_shelter() -> Vec<ObjectDesc> {
    let mut k = Kit::default();
    let m = "street_galvanised";
    let (hx, hy, h) = (0.7, 1.8, 2.45);
    for (x, y) in [(-hx, -hy), (-hx, hy), (hx, -hy), (hx, hy)] {
        let a = DVec3::new(x, y, 0.0);
        k.rod(m, ST, a, a + DVec3::Z * h, 0.04, 8);
    }
    k.block(
        "street_paint_grey",
        ST,
        [1.7, 3.9, 0.1],
        [0.0, 0.0, h + 0.05],
    );
    // Glass panels between a bottom and a top rail (no shared faces).
    k.block("street_glass", ST, [0.012, 3.5, 1.8], [hx, 0.0, 1.2]);
    for z in [0.25, 2.15] {
        k.block(m, ST, [0.05, 3.56, 0.06], [hx, 0.0, z]);
    }
    for s in [-1.0, 1.0] {
        k.block("street_glass", ST, [1.3, 0.012, 1.8], [0.0, s * hy, 1.2]);
        for z in [0.25, 2.15] {
            k.block(m, ST, [1.36, 0.05, 0.06], [0.0, s * hy, z]);
        }
    }
    k.block("street_wood", ST, [0.35, 2.2, 0.04], [0.45, 0.0, 0.47]);
    for y in [-0.9, 0.9] {
        k.block(m, ST, [0.05, 0.05, 0.45], [0.5, y, 0.225]);
    }
    let sign = FaceDesign::new(rect(0.9, 0.22, [0.0, 0.0]), "sign_face_white").text(
        "sign_ink_black",
        "BUS",
        0.12,
        [0.0, 0.0],
    );
    sign.build_as(
        &mut k,
        face_frame(-0.85, -1.2, h + 0.2),
        ST,
        "sign_back_grey",
    );
    k.objects()
}

/// A 6 × 3 m billboard on two legs with a walkway, printed with slogan
/// `k` (`names::SLOGANS`) over a coloured band.
fn billboard(k: usize) -> Vec<ObjectDesc> {
    let mut kit = Kit::default();
    let m = "street_steel_dark";
    for y in [-1.8, 1.8] {
        let a = DVec3::new(0.2, y, 0.0);
        kit.rod(m, ST, a, a + DVec3::Z * 6.3, 0.14, 10);
    }
    kit.block("street_paint_grey", ST, [0.25, 6.2, 3.2], [0.15, 0.0, 6.0]);
    kit.block("street_galvanised", ST, [0.7, 6.0, 0.05], [-0.3, 0.0, 4.35]);
    let band = ["sign_print_orange", "sign_print_teal", "sign_print_purple"][k % 3];
    let face = FaceDesign::new(rect(6.0, 3.0, [0.0, 0.0]), "sign_print_cream")
        .shape(band, rect(5.8, 0.7, [0.0, -1.0]))
        .text("sign_ink_black", SLOGANS[k], 0.45, [0.0, 0.35]);
    face.build_as(
        &mut kit,
        face_frame(0.025, 0.0, 6.0),
        ST,
        "street_paint_grey",
    );
    kit.objects()
}

/// Every fixture prefab.
pub fn fixture_prefabs() -> Vec<PrefabDesc> {
    let mut out = vec![
        prefab("bench_wood", bench_wood()),
        prefab("bench_steel", bench_steel()),
        prefab("bin_round", bin_round()),
        prefab("bin_box", bin_box()),
        prefab("bollard_steel", bollard_steel()),
        prefab("bollard_concrete", bollard_concrete()),
        prefab("hydrant", hydrant()),
        prefab("parking_meter", parking_meter()),
        prefab("bus_shelter", bus_shelter()),
    ];
    for k in 0..SLOGANS.len() {
        out.push(prefab(&format!("billboard_{k}"), billboard(k)));
    }
    out
}
