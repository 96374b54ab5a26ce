//! Unit tests of the furniture prefabs: every part lies within its
//! prefab's envelope, standing items stand on the ground and mounted ones
//! above it; sign faces are readable (every print on the face, inside its
//! outline, raised above the sheet; the speed number's letters are there).

use glam::DVec3;

use crate::scene::desc::{ObjectDesc, ShapeDesc};
use crate::scene::transform::parent_from_local;
use crate::town::lettering::layout;

use super::furniture_prefabs;
use super::names::SPEED_LIMITS;
use super::signs::{faces, name_face, speed_face, FaceDesign, PRINT_TOP_M, PRINT_W0_M};

/// Every vertex of a prefab part in the prefab frame (merged parts are
/// stored in it; a lens is placed by its transform).
fn points(o: &ObjectDesc) -> Vec<DVec3> {
    let ShapeDesc::Mesh { positions, .. } = &o.shape else {
        panic!("unexpected part {:?}", o.shape);
    };
    let at = parent_from_local(&o.transform);
    positions
        .iter()
        .map(|&p| at.transform_point3(DVec3::from(p)))
        .collect()
}

/// (name prefix, envelope min, max, stands on the ground).
const ENVELOPES: [(&str, [f64; 3], [f64; 3], bool); 20] = [
    ("sign_post", [-0.05, -0.45, 0.0], [0.05, 0.45, 2.8], true),
    (
        "street_name_post",
        [-0.05, -0.05, 0.0],
        [0.05, 0.05, 2.8],
        true,
    ),
    (
        "sign_direction",
        [-0.1, -0.61, 2.29],
        [0.0, 0.61, 2.71],
        false,
    ),
    ("sign_", [-0.1, -0.53, 1.6], [0.0, 0.53, 2.6], false),
    ("street_name_", [-0.03, -0.7, 2.5], [0.03, 0.7, 2.7], false),
    ("lamp_cobra", [-0.25, -3.2, 0.0], [0.25, 0.2, 9.4], true),
    ("lamp_heritage", [-0.3, -0.3, 0.0], [0.3, 0.3, 4.7], true),
    ("lamp_highway", [-0.45, -3.1, 0.0], [0.45, 3.1, 12.5], true),
    (
        "traffic_light_mast_pole",
        [-0.25, -0.25, 0.0],
        [0.25, 7.1, 7.5],
        true,
    ),
    (
        "traffic_light_pole",
        [-0.2, -0.25, 0.0],
        [0.2, 4.7, 6.4],
        true,
    ),
    ("traffic_light", [-0.32, -0.6, 2.2], [0.15, 6.0, 6.3], false),
    ("bench", [-0.3, -0.95, 0.0], [0.3, 0.95, 0.9], true),
    ("bin", [-0.3, -0.3, 0.0], [0.3, 0.3, 1.05], true),
    ("bollard", [-0.25, -0.25, 0.0], [0.25, 0.25, 1.0], true),
    ("hydrant", [-0.3, -0.25, 0.0], [0.2, 0.25, 0.8], true),
    ("parking_meter", [-0.11, -0.12, 0.0], [0.1, 0.12, 1.5], true),
    ("bus_shelter", [-0.9, -1.96, 0.0], [0.86, 1.96, 2.8], true),
    ("billboard", [-0.7, -3.1, 0.0], [0.35, 3.1, 7.6], true),
    ("guard_rail", [0.0, -0.1, 0.0], [32.1, 0.33, 0.8], true),
    ("", [-0.15, -1.05, 0.0], [36.05, 1.05, 9.4], false),
];

#[test]
fn prefab_parts_lie_within_their_envelopes_standing_ones_on_the_ground() {
    for p in furniture_prefabs() {
        let (_, lo, hi, stands) = ENVELOPES
            .iter()
            .find(|(prefix, ..)| p.name.starts_with(prefix))
            .unwrap();
        let pts: Vec<DVec3> = p.objects.iter().flat_map(points).collect();
        assert!(!pts.is_empty(), "{}", p.name);
        let min_z = pts.iter().map(|q| q.z).fold(f64::INFINITY, f64::min);
        for q in &pts {
            let inside = (0..3).all(|a| q[a] >= lo[a] - 1e-9 && q[a] <= hi[a] + 1e-9);
            assert!(inside, "{}: {q} outside {lo:?}..{hi:?}", p.name);
        }
        // On the ground: the lowest point at z = 0 exactly; else above it.
        let standing = ["fence", "railing", "utility_pole"]
            .iter()
            .any(|n| p.name.starts_with(n));
        if *stands || standing {
            assert!(min_z.abs() < 1e-12, "{}: lowest point {min_z}", p.name);
        } else {
            assert!(min_z > 0.1, "{}: lowest point {min_z}", p.name);
        }
    }
}

/// Whether (u, v) lies in the convex counter-clockwise `poly` (ε 1e-9).
fn inside(poly: &[[f64; 2]], u: f64, v: f64) -> bool {
    (0..poly.len()).all(|k| {
        let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
        (b[0] - a[0]) * (v - a[1]) - (b[1] - a[1]) * (u - a[0]) >= -1e-9
    })
}

fn check_face(name: &str, f: &FaceDesign) {
    assert!(!f.prints.is_empty(), "{name}: nothing printed");
    for (mat, m) in &f.prints {
        for p in &m.positions {
            assert!(
                inside(&f.outline, p.x, p.y),
                "{name}: {mat} at {p} off the face"
            );
            // On the face: from inside the sheet to at most 1.5 mm above
            // the print top (the walker on the crossing's triangle).
            assert!(
                p.z >= PRINT_W0_M - 1e-12 && p.z <= PRINT_TOP_M + 0.0015 + 1e-12,
                "{name}: {p}"
            );
        }
    }
}

#[test]
fn sign_prints_lie_on_the_face_inside_the_outline() {
    for (name, f, _) in faces() {
        check_face(&name, &f);
    }
    for n in super::names::street_names() {
        check_face(&n, &name_face(&n));
    }
}

#[test]
fn speed_signs_print_their_number_centred() {
    for kmh in SPEED_LIMITS {
        let text = kmh.to_string();
        let f = speed_face(kmh);
        let (_, ink) = f
            .prints
            .iter()
            .find(|(m, _)| *m == "sign_ink_black")
            .unwrap();
        let cap = if text.len() > 2 { 0.16 } else { 0.2 };
        // One box (12 triangles) per laid-out rectangle of the number.
        assert_eq!(
            ink.triangles.len(),
            12 * layout(&text, cap).rects.len(),
            "{kmh}"
        );
        let (lo, hi) = ink
            .positions
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(*p), hi.max(*p))
            });
        // Centred by its layout box (a glyph may leave its edge columns
        // empty, as "1" does): ink within ± width / 2, less than a cell in.
        let (half, cell) = (layout(&text, cap).width / 2.0, cap / 7.0);
        assert!(
            lo.x >= -half - 1e-9 && lo.x <= -half + cell + 1e-9,
            "{kmh}: {lo}"
        );
        assert!(
            hi.x <= half + 1e-9 && hi.x >= half - cell - 1e-9,
            "{kmh}: {hi}"
        );
        assert!((lo.y + hi.y).abs() < 1e-9, "{kmh}: {lo} {hi}");
        assert!((hi.y - lo.y - cap).abs() < 1e-9, "{kmh}");
    }
}

#[test]
fn cobra_lamp_panels_face_down_and_sideways_never_up() {
    // The panel's top would shine into the gap under its housing.
    for name in [super::lights::LAMP_COBRA, super::lights::LAMP_HIGHWAY] {
        let prefabs = furniture_prefabs();
        let p = prefabs.iter().find(|p| p.name == name).unwrap();
        let mut down_m2 = 0.0;
        for o in p
            .objects
            .iter()
            .filter(|o| o.material.as_deref() == Some("lamp_emit"))
        {
            let ShapeDesc::Mesh {
                positions,
                triangles,
                ..
            } = &o.shape
            else {
                panic!("a mesh panel");
            };
            for t in triangles {
                let [a, b, c] = t.map(|i| DVec3::from(positions[i as usize]));
                let n = (b - a).cross(c - a);
                assert!(n.z <= 0.0, "{name}: a lit face up, {n:?}");
                if n.z < 0.0 {
                    down_m2 += n.length() / 2.0;
                }
            }
        }
        // 0.3 m × 0.5 m per head: one on the cobra, two on the mast.
        let heads = if name == super::lights::LAMP_COBRA {
            1.0
        } else {
            2.0
        };
        assert!((down_m2 - 0.15 * heads).abs() < 1e-9, "{name}: {down_m2}");
    }
}

#[test]
fn signal_lenses_shine_out_of_the_housing_never_into_it() {
    // A head faces −x; its housing lies behind the lenses, towards +x.
    let prefabs = furniture_prefabs();
    let mut lenses = 0;
    for p in prefabs
        .iter()
        .filter(|p| p.name.starts_with("traffic_light"))
    {
        for o in p.objects.iter().filter(|o| {
            crate::town::props::LENS_SLOTS.contains(&o.material.as_deref().unwrap_or(""))
        }) {
            let ShapeDesc::Mesh {
                positions,
                triangles,
                ..
            } = &o.shape
            else {
                panic!("{}: a lens mesh", p.name);
            };
            let at = parent_from_local(&o.transform);
            let mut front_m2 = 0.0;
            for t in triangles {
                let [a, b, c] = t.map(|i| at.transform_point3(DVec3::from(positions[i as usize])));
                let n = (b - a).cross(c - a);
                assert!(
                    n.x <= 1e-12,
                    "{}: a lens face towards the housing, {n:?}",
                    p.name
                );
                if n.x < -1e-12 && n.y.abs() < 1e-12 && n.z.abs() < 1e-12 {
                    front_m2 += n.length() / 2.0;
                }
            }
            // The front cap: a 12-gon of circumradius 0.1 m.
            let disc = 6.0 * 0.1f64.powi(2) * (std::f64::consts::TAU / 12.0).sin();
            assert!(
                (front_m2 - disc).abs() < 1e-9,
                "{}: front {front_m2}",
                p.name
            );
            lenses += 1;
        }
    }
    assert!(lenses >= 6, "{lenses} lenses");
}
