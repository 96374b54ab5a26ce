//! Poses: the skeleton's joint positions for a walk-cycle phase or
//! standing, by forward kinematics from joint angles that are periodic
//! functions of the phase φ ∈ [0, 1) (distance walked / stride length), so
//! φ = 0 and φ = 1 give the same pose and a small change of φ moves every
//! joint a little. Bone lengths are the body's whatever the angles.
//!
//! Person frame: x forward, y left, z up, origin on the ground under the
//! pelvis; the lower sole touches z = 0.

use std::f64::consts::TAU;

use glam::DVec3;

use super::body::{Body, Joint, JOINTS};

/// Joint positions of one pose, indexed by `Joint as usize`.
#[derive(Clone, Debug, PartialEq)]
pub struct Skeleton {
    /// Positions, metres.
    pub joints: [DVec3; JOINTS.len()],
}

impl Skeleton {
    /// Position of joint `j`.
    pub fn at(&self, j: Joint) -> DVec3 {
        self.joints[j as usize]
    }

    fn set(&mut self, j: Joint, p: DVec3) {
        self.joints[j as usize] = p;
    }
}

/// Joint angles, radians: flexion forward is positive.
#[derive(Clone, Copy, Debug, Default)]
pub struct Angles {
    /// Forward lean of the torso.
    pub lean: f64,
    /// Turn of the hips about z (the shoulders turn the other way).
    pub twist: f64,
    /// Per side [left, right]: hip flexion, knee flexion (≥ 0), foot pitch
    /// (toe up), shoulder swing forward, elbow flexion (≥ 0).
    pub hip: [f64; 2],
    /// Knee flexion per side (≥ 0).
    pub knee: [f64; 2],
    /// Foot pitch per side (toe up).
    pub foot: [f64; 2],
    /// Shoulder swing forward per side.
    pub shoulder: [f64; 2],
    /// Elbow flexion per side (≥ 0).
    pub elbow: [f64; 2],
}

/// Joint angles of the walk cycle at phase `phase` (cycles; period 1).
/// The left leg swings forward over φ ∈ (−¼, ¼), the right half a cycle
/// later; each arm swings with the opposite leg.
pub fn walk_angles(phase: f64) -> Angles {
    let deg = f64::to_radians;
    let mut a = Angles {
        lean: deg(4.0),
        twist: deg(-5.0) * (TAU * phase).sin(),
        ..Angles::default()
    };
    for (s, w) in [(0, TAU * phase), (1, TAU * phase + TAU / 2.0)] {
        a.hip[s] = deg(3.0) + deg(22.0) * w.sin();
        // Most bend mid-swing, when the leg passes under the body.
        a.knee[s] = deg(6.0) + deg(55.0) * w.cos().max(0.0).powi(2);
        // Toe up reaching forward, heel off pushing back.
        a.foot[s] = deg(14.0) * w.sin();
        a.shoulder[s] = -deg(20.0) * w.sin();
        a.elbow[s] = deg(14.0) + deg(22.0) * (-w.sin()).max(0.0);
    }
    a
}

/// Joint angles of a person standing still.
pub fn stand_angles() -> Angles {
    let deg = f64::to_radians;
    Angles {
        lean: deg(1.0),
        twist: 0.0,
        hip: [deg(1.0); 2],
        knee: [deg(3.0); 2],
        foot: [0.0; 2],
        shoulder: [deg(2.0); 2],
        elbow: [deg(9.0); 2],
    }
}

/// A unit vector in the sagittal plane at `angle` forward of straight down,
/// tilted out sideways by `out` (towards `side` y).
fn down(angle: f64, out: f64, side: f64) -> DVec3 {
    DVec3::new(
        angle.sin() * out.cos(),
        side * out.sin(),
        -angle.cos() * out.cos(),
    )
}

fn turn_z(v: DVec3, a: f64) -> DVec3 {
    let (s, c) = a.sin_cos();
    DVec3::new(c * v.x - s * v.y, s * v.x + c * v.y, v.z)
}

/// The skeleton of `body` posed by `a`, standing on z = 0.
pub fn pose(body: &Body, a: &Angles) -> Skeleton {
    let mut k = Skeleton {
        joints: [DVec3::ZERO; JOINTS.len()],
    };
    let up = DVec3::new(a.lean.sin(), 0.0, a.lean.cos());
    k.set(Joint::Spine, up * body.lumbar);
    k.set(Joint::Chest, k.at(Joint::Spine) + up * body.thorax);
    let neck_dir = DVec3::new((a.lean * 0.5).sin(), 0.0, (a.lean * 0.5).cos());
    k.set(Joint::Neck, k.at(Joint::Chest) + neck_dir * body.neck);
    k.set(Joint::Head, k.at(Joint::Neck) + DVec3::Z * body.skull);
    let sides = [
        (0, 1.0, Joint::ShoulderL, Joint::ElbowL, Joint::WristL),
        (1, -1.0, Joint::ShoulderR, Joint::ElbowR, Joint::WristR),
    ];
    for (s, y, sh, el, wr) in sides {
        let p = k.at(Joint::Chest) + turn_z(DVec3::Y * (y * body.shoulder_half), -a.twist);
        k.set(sh, p);
        let out = 6f64.to_radians();
        let e = p + down(a.shoulder[s], out, y) * body.upper_arm;
        k.set(el, e);
        k.set(
            wr,
            e + down(a.shoulder[s] + a.elbow[s], out, y) * body.forearm,
        );
    }
    let legs = [
        (
            0,
            1.0,
            Joint::HipL,
            Joint::KneeL,
            Joint::AnkleL,
            Joint::ToeL,
        ),
        (
            1,
            -1.0,
            Joint::HipR,
            Joint::KneeR,
            Joint::AnkleR,
            Joint::ToeR,
        ),
    ];
    for (s, y, hip, knee, ankle, toe) in legs {
        let h = turn_z(DVec3::Y * (y * body.hip_half), a.twist);
        k.set(hip, h);
        let kn = h + down(a.hip[s], 0.0, y) * body.thigh;
        k.set(knee, kn);
        let an = kn + down(a.hip[s] - a.knee[s], 0.0, y) * body.shin;
        k.set(ankle, an);
        // Sole vector (foot forward, ankle height down) pitched toe-up.
        let (sf, cf) = a.foot[s].sin_cos();
        let (fx, fz) = (body.foot, -body.ankle_h);
        k.set(
            toe,
            an + DVec3::new(fx * cf - fz * sf, 0.0, fx * sf + fz * cf),
        );
    }
    // Stand on the lower of the four sole points (heels under the ankles).
    let sole = [
        k.at(Joint::AnkleL).z - body.ankle_h,
        k.at(Joint::AnkleR).z - body.ankle_h,
        k.at(Joint::ToeL).z,
        k.at(Joint::ToeR).z,
    ]
    .into_iter()
    .fold(f64::INFINITY, f64::min);
    for p in &mut k.joints {
        p.z -= sole;
    }
    k
}

/// The walking skeleton of `body` at phase `phase` (cycles).
pub fn walk(body: &Body, phase: f64) -> Skeleton {
    pose(body, &walk_angles(phase))
}

/// The standing skeleton of `body`.
pub fn stand(body: &Body) -> Skeleton {
    pose(body, &stand_angles())
}
