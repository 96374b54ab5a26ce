//! Riders: a person seated on a two-wheeler, hips on the seat's hip point,
//! hands on the grips and feet on the pegs by two-bone IK, torso leaned
//! forward as far as the arms need (class `rider`).
//!
//! A seat is (hip point, left grip, left foot peg) in the vehicle's frame
//! (x forward, y left, z up); the right side mirrors y.

use glam::DVec3;

use crate::scene::desc::PrefabDesc;

use super::body::{Body, Joint, JOINTS};
use super::pose::Skeleton;
use super::Person;

/// Places the middle joint of a two-bone chain from `root` towards
/// `target` (lengths `l1`, `l2`), bending towards `pole`; returns (middle,
/// end). The end reaches the target when it is within reach, else stops on
/// the line to it; both bone lengths are exact.
pub fn two_bone(root: DVec3, target: DVec3, l1: f64, l2: f64, pole: DVec3) -> (DVec3, DVec3) {
    let to = target - root;
    let u = to.try_normalize().unwrap_or(DVec3::NEG_Z);
    let d = to.length().clamp((l1 - l2).abs() + 1e-9, l1 + l2 - 1e-9);
    let cos_a = ((l1 * l1 + d * d - l2 * l2) / (2.0 * l1 * d)).clamp(-1.0, 1.0);
    let mut v = pole - u * pole.dot(u);
    if v.length() < 1e-9 {
        v = u.any_orthonormal_vector();
    }
    let v = v.normalize();
    let mid = root + (u * cos_a + v * (1.0 - cos_a * cos_a).sqrt()) * l1;
    let end = mid + (root + u * d - mid).normalize() * l2;
    (mid, end)
}

/// The seated skeleton of `body` on `seat`.
pub fn seated(body: &Body, seat: [[f64; 3]; 3]) -> Skeleton {
    let [hip, grip, peg] = seat.map(DVec3::from_array);
    let mirror = |p: DVec3| DVec3::new(p.x, -p.y, p.z);
    let reach = 0.92 * (body.upper_arm + body.forearm);
    // The lean (0..70°, whole degrees) whose left shoulder is nearest the
    // comfortable reach from the grip.
    let chest_at =
        |lean: f64| hip + DVec3::new(lean.sin(), 0.0, lean.cos()) * (body.lumbar + body.thorax);
    let lean = (0..=70)
        .map(|d| (d as f64).to_radians())
        .min_by(|a, b| {
            let err = |l: f64| {
                ((chest_at(l) + DVec3::Y * body.shoulder_half - grip).length() - reach).abs()
            };
            err(*a).total_cmp(&err(*b))
        })
        .expect("a lean");
    let up = DVec3::new(lean.sin(), 0.0, lean.cos());
    let mut j = [DVec3::ZERO; JOINTS.len()];
    let mut set = |k: Joint, p: DVec3| j[k as usize] = p;
    set(Joint::Pelvis, hip);
    set(Joint::Spine, hip + up * body.lumbar);
    let chest = hip + up * (body.lumbar + body.thorax);
    set(Joint::Chest, chest);
    // Head up: the neck bends back to look ahead.
    let neck_dir = DVec3::new((lean * 0.4).sin(), 0.0, (lean * 0.4).cos());
    let neck = chest + neck_dir * body.neck;
    set(Joint::Neck, neck);
    set(Joint::Head, neck + DVec3::Z * body.skull);
    let sides = [
        (1.0, grip, [Joint::ShoulderL, Joint::ElbowL, Joint::WristL]),
        (
            -1.0,
            mirror(grip),
            [Joint::ShoulderR, Joint::ElbowR, Joint::WristR],
        ),
    ];
    for (y, g, [sh, el, wr]) in sides {
        let s = chest + DVec3::Y * (y * body.shoulder_half);
        set(sh, s);
        // Elbows out and down.
        let (e, w) = two_bone(s, g, body.upper_arm, body.forearm, DVec3::new(0.0, y, -1.0));
        set(el, e);
        set(wr, w);
    }
    let legs = [
        (
            1.0,
            peg,
            [Joint::HipL, Joint::KneeL, Joint::AnkleL, Joint::ToeL],
        ),
        (
            -1.0,
            mirror(peg),
            [Joint::HipR, Joint::KneeR, Joint::AnkleR, Joint::ToeR],
        ),
    ];
    for (y, peg_at, [h, kn, an, toe]) in legs {
        let hp = hip + DVec3::Y * (y * body.hip_half);
        set(h, hp);
        // Sole on the peg: the ankle sits ankle height above it; knees
        // forward and up.
        let target = peg_at + DVec3::Z * body.ankle_h;
        let (k, a) = two_bone(hp, target, body.thigh, body.shin, DVec3::new(1.0, 0.0, 0.6));
        set(kn, k);
        set(an, a);
        set(toe, a + DVec3::new(body.foot, 0.0, -body.ankle_h));
    }
    Skeleton { joints: j }
}

/// A person of variant `variant` seated on `seat`, class `rider`.
pub fn rider_prefab(name: &str, seat: [[f64; 3]; 3], variant: u32) -> PrefabDesc {
    // Adults only ride (children's variants come first).
    let v = super::CHILDREN + variant % (super::VARIANTS - super::CHILDREN);
    let mut person = Person::variant(v);
    if person.outfit.bottom == super::clothing::Bottom::Skirt {
        person.outfit.bottom = super::clothing::Bottom::Trousers;
    }
    let k = seated(&person.body, seat);
    PrefabDesc {
        name: name.to_string(),
        objects: person.parts(&k).into_objects("rider"),
    }
}
