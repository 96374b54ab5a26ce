//! Traffic signs with printed faces and street-name plates. A face is
//! designed in face coordinates (`FaceDesign`: u right, v up, w out of the
//! face, see `kit`): a grey metal plate, a coloured face sheet on it and
//! the printed parts (rings, bars, arrows, letters from
//! `town::lettering`) raised a few millimetres above the sheet, inside the
//! outline. Signs stand on galvanised posts (class `pole`), faces towards
//! local −x (class `traffic_sign`).

use glam::{DAffine3, DVec3};

use crate::scene::desc::PrefabDesc;
use crate::scene::mesh::LocalMesh;
use crate::town::lettering::text_mesh;

use super::kit::{face_frame, prism, regular, ring_prism, turned, Kit};
use super::names::{street_names, PLACES, SPEED_LIMITS};
use super::prefab;

/// Plate thickness (grey metal), metres.
pub const PLATE_M: f64 = 0.015;
/// Face sheet: from the plate's front to `SHEET_M`.
pub const SHEET_M: f64 = 0.018;
/// Prints start half a millimetre inside the sheet (no coplanar faces)
/// and rise to `PRINT_TOP_M`.
pub const PRINT_W0_M: f64 = 0.0175;
/// Top of the printed parts above the plate's back, metres.
pub const PRINT_TOP_M: f64 = 0.021;
const POST_R: f64 = 0.035;
const TS: &str = "traffic_sign";
const POLE: &str = "pole";

/// One sign face in face coordinates.
pub struct FaceDesign {
    /// Convex outline, counter-clockwise, metres.
    pub outline: Vec<[f64; 2]>,
    /// Material of the face sheet.
    pub sheet: &'static str,
    /// Printed parts: (material, mesh in face coordinates).
    pub prints: Vec<(&'static str, LocalMesh)>,
}

impl FaceDesign {
    /// A face of `outline` with a `sheet` and nothing printed yet.
    pub fn new(outline: Vec<[f64; 2]>, sheet: &'static str) -> Self {
        FaceDesign {
            outline,
            sheet,
            prints: Vec::new(),
        }
    }

    /// A printed band between two scalings of the outline.
    pub fn border(mut self, mat: &'static str, outer: f64, inner: f64) -> Self {
        let s = |k: f64| {
            self.outline
                .iter()
                .map(|p| [p[0] * k, p[1] * k])
                .collect::<Vec<_>>()
        };
        let (o, i) = (s(outer), s(inner));
        self.prints
            .push((mat, ring_prism(&o, Some(&i), PRINT_W0_M, PRINT_TOP_M)));
        self
    }

    /// A printed convex polygon.
    pub fn shape(mut self, mat: &'static str, poly: Vec<[f64; 2]>) -> Self {
        self.prints
            .push((mat, prism(&poly, PRINT_W0_M, PRINT_TOP_M)));
        self
    }

    /// Printed text of cap height `cap` centred at `centre`.
    pub fn text(mut self, mat: &'static str, text: &str, cap: f64, centre: [f64; 2]) -> Self {
        let width = crate::town::lettering::layout(text, cap).width;
        let shift = DVec3::new(centre[0] - width / 2.0, centre[1] - cap / 2.0, PRINT_W0_M);
        let mut m = text_mesh(text, cap, PRINT_TOP_M - PRINT_W0_M);
        m.positions.iter_mut().for_each(|p| *p += shift);
        self.prints.push((mat, m));
        self
    }

    /// Plate, sheet and prints placed by `frame` (see `kit::face_frame`),
    /// class `traffic_sign`.
    pub fn build(&self, kit: &mut Kit, frame: DAffine3) {
        self.build_as(kit, frame, TS, "sign_back_grey");
    }

    /// Plate (of material `back`), sheet and prints placed by `frame`,
    /// labelled `class`.
    pub fn build_as(&self, kit: &mut Kit, frame: DAffine3, class: &'static str, back: &str) {
        kit.add(back, class, prism(&self.outline, 0.0, PLATE_M), frame);
        let sheet: Vec<[f64; 2]> = self
            .outline
            .iter()
            .map(|p| [p[0] * 0.985, p[1] * 0.985])
            .collect();
        kit.add(
            self.sheet,
            class,
            prism(&sheet, PLATE_M - 0.0005, SHEET_M),
            frame,
        );
        for (mat, m) in &self.prints {
            kit.add(mat, class, m.clone(), frame);
        }
    }
}

/// A `w` × `h` rectangle centred at `c`, counter-clockwise.
pub fn rect(w: f64, h: f64, c: [f64; 2]) -> Vec<[f64; 2]> {
    let (x0, x1, y0, y1) = (
        c[0] - w / 2.0,
        c[0] + w / 2.0,
        c[1] - h / 2.0,
        c[1] + h / 2.0,
    );
    vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]]
}

/// Stop: a red octagon, white border and white STOP.
pub fn stop_face() -> FaceDesign {
    let oct = regular(8, 0.38, std::f64::consts::PI / 8.0);
    FaceDesign::new(oct, "sign_face_red")
        .border("sign_face_white", 0.95, 0.89)
        .text("sign_face_white", "STOP", 0.16, [0.0, 0.0])
}

/// Give way: an inverted white triangle with a red border.
pub fn give_way_face() -> FaceDesign {
    let tri = regular(3, 0.52, -std::f64::consts::FRAC_PI_2);
    FaceDesign::new(tri, "sign_face_white").border("sign_face_red", 0.97, 0.6)
}

/// A speed limit: white disc, red ring, black number.
pub fn speed_face(kmh: u32) -> FaceDesign {
    let disc = regular(32, 0.3, 0.0);
    let text = kmh.to_string();
    let cap = if text.len() > 2 { 0.16 } else { 0.2 };
    FaceDesign::new(disc, "sign_face_white")
        .border("sign_face_red", 0.97, 0.78)
        .text("sign_ink_black", &text, cap, [0.0, 0.0])
}

/// No entry: a red disc with a white bar.
pub fn no_entry_face() -> FaceDesign {
    FaceDesign::new(regular(32, 0.3, 0.0), "sign_face_red")
        .shape("sign_face_white", rect(0.4, 0.09, [0.0, 0.0]))
}

/// Pedestrian crossing: a blue square, a white triangle and a black walker.
pub fn crossing_face() -> FaceDesign {
    let tri = regular(3, 0.26, std::f64::consts::FRAC_PI_2);
    let ink = "sign_ink_black";
    let mut f = FaceDesign::new(rect(0.6, 0.6, [0.0, 0.0]), "sign_face_blue")
        .shape("sign_face_white", tri)
        .shape(ink, rect(0.04, 0.04, [0.0, 0.06]))
        .shape(ink, rect(0.035, 0.09, [0.0, -0.005]))
        .shape(ink, rect(0.025, 0.07, [-0.025, -0.075]))
        .shape(ink, rect(0.025, 0.07, [0.025, -0.075]));
    // The walker lies on the white triangle: lift it above the white print.
    for (_, m) in f.prints.iter_mut().skip(1) {
        m.positions.iter_mut().for_each(|p| p.z += 0.001);
    }
    f
}

/// A direction sign: green board, white border, place name and an arrow
/// pointing right (`right`) or left.
pub fn direction_face(place: &str, right: bool) -> FaceDesign {
    let s = if right { 1.0 } else { -1.0 };
    let head = vec![[s * 0.44, 0.1], [s * 0.44, -0.1], [s * 0.55, 0.0]];
    let head = if right {
        head
    } else {
        head.into_iter().rev().collect()
    };
    FaceDesign::new(rect(1.2, 0.4, [0.0, 0.0]), "sign_face_green")
        .border("sign_face_white", 0.975, 0.94)
        .shape("sign_face_white", rect(0.15, 0.05, [s * 0.37, 0.0]))
        .shape("sign_face_white", head)
        .text("sign_face_white", place, 0.12, [-s * 0.12, 0.0])
}

/// A street-name plate: green, white border and name, as wide as the name.
pub fn name_face(name: &str) -> FaceDesign {
    let w = crate::town::lettering::layout(name, 0.09).width + 0.14;
    FaceDesign::new(rect(w, 0.17, [0.0, 0.0]), "sign_face_green")
        .border("sign_face_white", 0.985, 0.95)
        .text("sign_face_white", name, 0.09, [0.0, 0.0])
}

/// Height of a post-mounted sign face's centre, metres.
pub const FACE_Z_M: f64 = 2.2;
/// Height of a direction sign's centre (on two posts), metres.
pub const DIRECTION_Z_M: f64 = 2.5;
/// Posts (class `pole`): one for a sign, two 0.8 m apart for a direction
/// sign, one for the name plates.
pub const POSTS: [&str; 3] = ["sign_post", "sign_post_pair", "street_name_post"];

/// A face alone (class `traffic_sign`), its centre `z` m up, its back
/// 6 cm in front of the post axis (`face_frame`).
fn face_prefab(name: &str, face: &FaceDesign, z: f64) -> PrefabDesc {
    let mut kit = Kit::default();
    face.build(&mut kit, face_frame(-0.06, 0.0, z));
    if z == FACE_Z_M {
        // The clamps that hold it to the post.
        for dz in [-0.15, 0.15] {
            kit.block(
                "street_galvanised",
                TS,
                [0.025, 0.09, 0.05],
                [-0.0475, 0.0, z + dz],
            );
        }
    }
    prefab(name, kit.objects())
}

/// The sign posts (`POSTS`), galvanised.
fn post_prefabs() -> Vec<PrefabDesc> {
    let g = "street_galvanised";
    let mut one = Kit::default();
    one.rod(
        g,
        POLE,
        DVec3::ZERO,
        DVec3::Z * (FACE_Z_M + 0.35),
        POST_R,
        10,
    );
    let mut pair = Kit::default();
    for y in [-0.4, 0.4] {
        let a = DVec3::new(0.0, y, 0.0);
        pair.rod(
            g,
            POLE,
            a,
            a + DVec3::Z * (DIRECTION_Z_M + 0.25),
            POST_R,
            10,
        );
    }
    let mut name = Kit::default();
    name.rod(g, POLE, DVec3::ZERO, DVec3::Z * 2.75, 0.03, 10);
    name.rod(g, POLE, DVec3::Z * 2.75, DVec3::Z * 2.8, 0.04, 10);
    [one, pair, name]
        .into_iter()
        .zip(POSTS)
        .map(|(k, n)| prefab(n, k.objects()))
        .collect()
}

/// Prefab name of the speed-limit sign showing `kmh`.
pub fn speed_prefab(kmh: u32) -> String {
    format!("sign_speed_{kmh}")
}

/// Prefab name of direction sign `k` (`names::PLACES`).
pub fn direction_prefab(k: usize) -> String {
    format!("sign_direction_{k}")
}

/// Prefab name of name plate `k` of the pool (`names::street_names`).
pub fn name_plate_prefab(k: usize) -> String {
    format!("street_name_{k}")
}

/// Every sign face: stop, give way, no entry, crossing, the speed limits,
/// then the direction signs (arrow right for even k), with their prefab
/// names and centre heights.
pub fn faces() -> Vec<(String, FaceDesign, f64)> {
    let mut out = vec![
        ("sign_stop".to_string(), stop_face(), FACE_Z_M),
        ("sign_give_way".to_string(), give_way_face(), FACE_Z_M),
        ("sign_no_entry".to_string(), no_entry_face(), FACE_Z_M),
        ("sign_crossing".to_string(), crossing_face(), FACE_Z_M),
    ];
    out.extend(SPEED_LIMITS.map(|s| (speed_prefab(s), speed_face(s), FACE_Z_M)));
    for (k, place) in PLACES.iter().enumerate() {
        out.push((
            direction_prefab(k),
            direction_face(place, k % 2 == 0),
            DIRECTION_Z_M,
        ));
    }
    out
}

/// Every sign prefab: the posts, the faces (`faces`) and one double-sided
/// plate per pooled street name, centred on the name post's axis at 2.6 m
/// (front towards −x, back towards +x).
pub fn sign_prefabs() -> Vec<PrefabDesc> {
    let mut out = post_prefabs();
    for (name, face, z) in faces() {
        out.push(face_prefab(&name, &face, z));
    }
    for (k, name) in street_names().iter().enumerate() {
        let face = name_face(name);
        let mut kit = Kit::default();
        let h = 0.004;
        face.build(&mut kit, face_frame(-h, 0.0, 2.6));
        face.build(&mut kit, turned(face_frame(-h, 0.0, 2.6), 180.0));
        out.push(prefab(&name_plate_prefab(k), kit.objects()));
    }
    out
}
