//! Bodies, poses, riders and prefabs of `people`.

use glam::DVec3;

use super::body::{Body, Joint, BONES, JOINTS};
use super::pose::{stand, walk, Skeleton};
use super::rider::{rider_prefab, seated, two_bone};
use super::*;
use crate::scene::desc::ShapeDesc;

fn bones_ok(body: &Body, k: &Skeleton, what: &str) {
    for b in BONES {
        let got = (k.at(b.1) - k.at(b.0)).length();
        let want = body.bone_length(b);
        assert!(
            (got - want).abs() < 1e-9,
            "{what}: bone {b:?} {got} ≠ {want}"
        );
    }
}

fn mesh_z_range(p: &PrefabDesc) -> (f64, f64) {
    let mut r = (f64::INFINITY, f64::NEG_INFINITY);
    for o in &p.objects {
        let ShapeDesc::Mesh { positions, .. } = &o.shape else {
            panic!("people are meshes");
        };
        for q in positions {
            r = (r.0.min(q[2]), r.1.max(q[2]));
        }
    }
    r
}

#[test]
fn skeleton_has_at_least_fifteen_distinct_joints() {
    assert!(JOINTS.len() >= 15);
    for (i, j) in JOINTS.iter().enumerate() {
        assert_eq!(*j as usize, i);
    }
    let k = walk(&Person::variant(5).body, 0.3);
    for (a, ja) in JOINTS.iter().enumerate() {
        for jb in &JOINTS[..a] {
            let d = (k.at(*ja) - k.at(*jb)).length();
            assert!(d > 0.02, "{ja:?} and {jb:?} coincide");
        }
    }
}

#[test]
fn bone_lengths_stay_constant_through_the_cycle_standing_and_seated() {
    for v in 0..VARIANTS {
        let body = Person::variant(v).body;
        for i in 0..=100 {
            bones_ok(&body, &walk(&body, i as f64 / 100.0), "walk");
        }
        bones_ok(&body, &stand(&body), "stand");
    }
}

#[test]
fn poses_are_periodic_and_continuous_in_the_phase() {
    let body = Person::variant(7).body;
    let (a, b) = (walk(&body, 0.0), walk(&body, 1.0));
    for (p, q) in a.joints.iter().zip(&b.joints) {
        assert!((*p - *q).length() < 1e-12);
    }
    // A step of 1/1000 cycle (about 1.4 mm walked) moves every joint by
    // less than 1 cm, and the limbs' ends by something.
    let dphi = 1e-3;
    for i in 0..200 {
        let phi = i as f64 / 200.0;
        let (k0, k1) = (walk(&body, phi), walk(&body, phi + dphi));
        for (n, (p, q)) in k0.joints.iter().zip(&k1.joints).enumerate() {
            let d = (*p - *q).length();
            assert!(d < 0.01, "{:?} jumps {d} m at φ = {phi}", JOINTS[n]);
        }
        for j in [Joint::WristL, Joint::WristR, Joint::AnkleL, Joint::AnkleR] {
            assert!(
                (k0.at(j) - k1.at(j)).length() > 1e-6,
                "{j:?} frozen at φ = {phi}"
            );
        }
    }
    // Half a cycle later the legs have swapped: left ankle ahead ↔ behind.
    let (k0, k1) = (walk(&body, 0.25), walk(&body, 0.75));
    assert!(k0.at(Joint::AnkleL).x > k0.at(Joint::AnkleR).x + 0.2);
    assert!(k1.at(Joint::AnkleR).x > k1.at(Joint::AnkleL).x + 0.2);
    // Each arm swings with the opposite leg.
    assert!(k0.at(Joint::WristR).x > k0.at(Joint::WristL).x + 0.1);
}

#[test]
fn feet_touch_the_ground_walking_and_both_soles_standing() {
    for v in 0..VARIANTS {
        let body = Person::variant(v).body;
        let sole = |k: &Skeleton, a: Joint, t: Joint| (k.at(a).z - body.ankle_h).min(k.at(t).z);
        for i in 0..50 {
            let k = walk(&body, i as f64 / 50.0);
            let s = sole(&k, Joint::AnkleL, Joint::ToeL).min(sole(&k, Joint::AnkleR, Joint::ToeR));
            assert!(s.abs() < 1e-12, "variant {v} floats or sinks {s} m");
        }
        let k = stand(&body);
        for (a, t) in [(Joint::AnkleL, Joint::ToeL), (Joint::AnkleR, Joint::ToeR)] {
            assert!(
                sole(&k, a, t).abs() < 1e-12,
                "a standing sole is off the ground"
            );
        }
        // Standing: feet side by side under the hips.
        assert!((k.at(Joint::AnkleL).x - k.at(Joint::AnkleR).x).abs() < 1e-9);
    }
}

#[test]
fn children_are_shorter_than_adults_and_heights_match_the_meshes() {
    let tops: Vec<(bool, f64)> = (0..VARIANTS)
        .map(|v| {
            let p = Person::variant(v);
            let (lo, hi) = mesh_z_range(&person_prefab(v, None));
            assert!(lo > -2e-3 && lo < 0.01, "variant {v} soles at {lo}");
            // The standing mesh is the drawn height within 6 % (knees and
            // lean shorten it; hair adds).
            assert!(
                (hi / p.body.height - 1.0).abs() < 0.06,
                "{hi} vs {}",
                p.body.height
            );
            (p.body.child, hi)
        })
        .collect();
    let child_max = tops.iter().filter(|t| t.0).map(|t| t.1).fold(0.0, f64::max);
    let adult_min = tops
        .iter()
        .filter(|t| !t.0)
        .map(|t| t.1)
        .fold(9.0, f64::min);
    assert!(tops.iter().any(|t| t.0) && child_max + 0.1 < adult_min);
}

#[test]
fn prefabs_are_deterministic_named_and_use_people_materials() {
    let all = people_prefabs();
    assert_eq!(all.len(), (VARIANTS * (PHASES + 1)) as usize);
    // A second generation (not the process's cached copy) gives the same.
    assert_eq!(all, super::generate_prefabs());
    let names: Vec<String> = people_materials().into_iter().map(|m| m.name).collect();
    let mut seen = std::collections::BTreeSet::new();
    for p in &all {
        assert!(seen.insert(p.name.clone()), "duplicate {}", p.name);
        for o in &p.objects {
            assert!(
                names.contains(o.material.as_ref().unwrap()),
                "{:?}",
                o.material
            );
            assert_eq!(o.semantic.as_deref(), Some("pedestrian"));
        }
    }
    assert_eq!(phase_index(0.999), PHASES - 1);
    assert_eq!(phase_index(1.0), 0);
    assert_eq!(phase_index(-0.01), PHASES - 1);
    // Variants differ (outfits or bodies).
    assert!(Person::variant(3) != Person::variant(4));
}

#[test]
fn two_bone_ik_reaches_targets_in_reach_with_exact_bones() {
    let root = DVec3::new(0.1, 0.2, 1.0);
    for (t, reachable) in [
        (DVec3::new(0.5, 0.3, 0.5), true),
        (DVec3::new(0.1, 0.2, 0.3), true),
        (DVec3::new(2.0, 0.0, 0.0), false),
    ] {
        let (m, e) = two_bone(root, t, 0.45, 0.42, DVec3::X);
        assert!(((m - root).length() - 0.45).abs() < 1e-9);
        assert!(((e - m).length() - 0.42).abs() < 1e-9);
        if reachable {
            assert!((e - t).length() < 1e-9, "end {e} misses {t}");
            // Bends towards the pole.
            assert!((m - (root + t) / 2.0).dot(DVec3::X) > 0.0);
        } else {
            // Stretched straight towards the target.
            assert!((e - root).normalize().dot((t - root).normalize()) > 1.0 - 1e-6);
        }
    }
}

#[test]
fn riders_sit_on_the_seat_with_hands_on_grips_and_feet_on_pegs() {
    // A bicycle and a motorcycle-like seat (hip, left grip, left peg).
    let seats = [
        [[-0.25, 0.0, 0.95], [0.35, 0.28, 1.05], [0.0, 0.16, 0.3]],
        [[-0.2, 0.0, 0.8], [0.45, 0.38, 0.98], [0.05, 0.2, 0.35]],
    ];
    for seat in seats {
        for v in 0..4 {
            let body = Person::variant(CHILDREN + v).body;
            let k = seated(&body, seat);
            bones_ok(&body, &k, "seated");
            let [hip, grip, peg] = seat.map(DVec3::from_array);
            let m = |p: DVec3| DVec3::new(p.x, -p.y, p.z);
            assert!((k.at(Joint::Pelvis) - hip).length() < 1e-12);
            assert!(
                (k.at(Joint::WristL) - grip).length() < 1e-9,
                "left hand off the grip"
            );
            assert!(
                (k.at(Joint::WristR) - m(grip)).length() < 1e-9,
                "right hand off the grip"
            );
            let up = DVec3::Z * body.ankle_h;
            assert!(
                (k.at(Joint::AnkleL) - (peg + up)).length() < 1e-9,
                "left foot off the peg"
            );
            assert!((k.at(Joint::AnkleR) - (m(peg) + up)).length() < 1e-9);
            // Leaning forward, head above the hips, knees ahead of them.
            assert!(k.at(Joint::Head).z > hip.z + 0.5);
            assert!(k.at(Joint::Chest).x > hip.x);
            assert!(k.at(Joint::KneeL).x > hip.x);
        }
        let p = rider_prefab("r", seat, 2);
        assert!(p
            .objects
            .iter()
            .all(|o| o.semantic.as_deref() == Some("rider")));
        assert_eq!(p, rider_prefab("r", seat, 2));
    }
}

/// Positions of a prefab's meshes of material `mat`.
fn mesh_points(p: &PrefabDesc, mat: &str) -> Vec<DVec3> {
    p.objects
        .iter()
        .filter(|o| o.material.as_deref() == Some(mat))
        .flat_map(|o| match &o.shape {
            ShapeDesc::Mesh { positions, .. } => positions.clone(),
            _ => panic!("people are meshes"),
        })
        .map(DVec3::from_array)
        .collect()
}

#[test]
fn an_umbrella_canopy_covers_the_head_from_the_raised_hand() {
    use super::umbrella::{umbrella_prefab, umbrella_prefab_name};
    for v in 0..VARIANTS {
        for phase in [Some(0), Some(5), None] {
            let p = umbrella_prefab(v, phase);
            assert_eq!(p.name, umbrella_prefab_name(v, phase));
            let person = Person::variant(v);
            let head = walk(&person.body, 0.0).at(Joint::Head);
            let canopy: Vec<DVec3> = p
                .objects
                .iter()
                .filter(|o| {
                    o.material
                        .as_deref()
                        .is_some_and(|m| m.starts_with("person_"))
                        && o.material.as_deref() != Some("person_umbrella_shaft")
                })
                .flat_map(|o| match &o.shape {
                    ShapeDesc::Mesh { positions, .. } => positions.clone(),
                    _ => unreachable!(),
                })
                .map(DVec3::from_array)
                .filter(|q| q.z > head.z + person.body.head_r)
                .collect();
            assert!(!canopy.is_empty(), "variant {v}: nothing above the head");
            // The canopy's reach in the ground plane covers the head.
            let shaft = mesh_points(&p, "person_umbrella_shaft");
            let top = shaft.iter().fold(
                DVec3::splat(f64::MIN),
                |a, q| {
                    if q.z > a.z {
                        *q
                    } else {
                        a
                    }
                },
            );
            let reach = canopy
                .iter()
                .map(|q| (q.truncate() - top.truncate()).length())
                .fold(0.0, f64::max);
            let head_off = (head.truncate() - top.truncate()).length() + person.body.head_r;
            assert!(
                reach > head_off + 0.1,
                "variant {v}: canopy reach {reach} vs head at {head_off}"
            );
            // The shaft rises in front of the face, from hand height up.
            let low = shaft.iter().map(|q| q.z).fold(f64::MAX, f64::min);
            assert!(top.x > head.x && low > 0.6 * head.z, "shaft {low}..{top}");
        }
    }
}

#[test]
fn a_canopy_faces_up_and_sits_on_its_dome() {
    let mut parts = Parts::default();
    let apex = DVec3::new(0.2, -0.1, 2.0);
    parts.canopy("c", apex, 0.5, 0.2, 8);
    let objects = parts.into_objects("pedestrian");
    let ShapeDesc::Mesh {
        positions,
        triangles,
        ..
    } = &objects[0].shape
    else {
        panic!("a mesh");
    };
    for t in triangles {
        let [a, b, c] = t.map(|k| DVec3::from_array(positions[k as usize]));
        assert!((b - a).cross(c - a).z > 0.0, "downward face {t:?}");
    }
    for q in positions.iter().map(|q| DVec3::from_array(*q)) {
        let rho = (q - apex).truncate().length();
        assert!(rho <= 0.5 + 1e-12);
        assert!((apex.z - q.z - 0.2 * (rho / 0.5).powi(2)).abs() < 1e-12);
    }
}
