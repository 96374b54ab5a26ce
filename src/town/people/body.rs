//! A person's body: seeded proportions of an adult or a child (bone
//! lengths, limb radii, shoulder and hip widths) and the skeleton's joints.
//!
//! Proportions follow the usual fractions of standing height H (leg 0.53 H,
//! thigh and shin 0.245 H each, upper arm 0.186 H, ...); a child's head is
//! larger and its legs shorter relative to H.

use super::super::rng::Rng;

/// Stream tag of the body and outfit draws (a variant's look never depends
/// on the town seed: variants are shared prefabs).
pub(super) const PERSON_TAG: u64 = 0x5045_5253_4f4e_0001;

/// The joints of the skeleton, each a point in the person's frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Joint {
    /// Centre of the hips.
    Pelvis,
    /// Lower back.
    Spine,
    /// Top of the chest, between the shoulders.
    Chest,
    /// Base of the skull.
    Neck,
    /// Centre of the head.
    Head,
    /// Left shoulder.
    ShoulderL,
    /// Left elbow.
    ElbowL,
    /// Left wrist.
    WristL,
    /// Right shoulder.
    ShoulderR,
    /// Right elbow.
    ElbowR,
    /// Right wrist.
    WristR,
    /// Left hip.
    HipL,
    /// Left knee.
    KneeL,
    /// Left ankle.
    AnkleL,
    /// Left toe tip.
    ToeL,
    /// Right hip.
    HipR,
    /// Right knee.
    KneeR,
    /// Right ankle.
    AnkleR,
    /// Right toe tip.
    ToeR,
}

/// Every joint, in `Joint` order (index = `joint as usize`).
pub const JOINTS: [Joint; 19] = [
    Joint::Pelvis,
    Joint::Spine,
    Joint::Chest,
    Joint::Neck,
    Joint::Head,
    Joint::ShoulderL,
    Joint::ElbowL,
    Joint::WristL,
    Joint::ShoulderR,
    Joint::ElbowR,
    Joint::WristR,
    Joint::HipL,
    Joint::KneeL,
    Joint::AnkleL,
    Joint::ToeL,
    Joint::HipR,
    Joint::KneeR,
    Joint::AnkleR,
    Joint::ToeR,
];

/// The bones: (parent joint, child joint); their lengths never change.
pub const BONES: [(Joint, Joint); 18] = [
    (Joint::Pelvis, Joint::Spine),
    (Joint::Spine, Joint::Chest),
    (Joint::Chest, Joint::Neck),
    (Joint::Neck, Joint::Head),
    (Joint::Chest, Joint::ShoulderL),
    (Joint::ShoulderL, Joint::ElbowL),
    (Joint::ElbowL, Joint::WristL),
    (Joint::Chest, Joint::ShoulderR),
    (Joint::ShoulderR, Joint::ElbowR),
    (Joint::ElbowR, Joint::WristR),
    (Joint::Pelvis, Joint::HipL),
    (Joint::HipL, Joint::KneeL),
    (Joint::KneeL, Joint::AnkleL),
    (Joint::AnkleL, Joint::ToeL),
    (Joint::Pelvis, Joint::HipR),
    (Joint::HipR, Joint::KneeR),
    (Joint::KneeR, Joint::AnkleR),
    (Joint::AnkleR, Joint::ToeR),
];

/// Proportions of one body, metres.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// Standing height, top of the head.
    pub height: f64,
    /// Whether this is a child.
    pub child: bool,
    /// Half the hip width (hip joints from the pelvis centre).
    pub hip_half: f64,
    /// Half the shoulder width.
    pub shoulder_half: f64,
    /// Thigh, shin and foot (ankle to toe tip) lengths.
    pub thigh: f64,
    /// Shin length.
    pub shin: f64,
    /// Foot length, ankle to toe tip.
    pub foot: f64,
    /// Ankle height above the sole.
    pub ankle_h: f64,
    /// Upper arm, forearm and hand lengths.
    pub upper_arm: f64,
    /// Forearm length.
    pub forearm: f64,
    /// Hand length.
    pub hand: f64,
    /// Pelvis to lower back, lower back to chest, chest to neck.
    pub lumbar: f64,
    /// Lower back to chest.
    pub thorax: f64,
    /// Chest to neck joint.
    pub neck: f64,
    /// Neck joint to head centre.
    pub skull: f64,
    /// Head radius (the head is an ellipsoid about this size).
    pub head_r: f64,
    /// Girth factor (1 = average build).
    pub girth: f64,
}

impl Body {
    /// Draws the body of variant stream `r`: an adult 1.55–1.92 m, or a
    /// child 1.0–1.4 m.
    pub fn draw(r: &mut Rng, child: bool) -> Body {
        let height = if child {
            r.range(1.0, 1.4)
        } else {
            r.range(1.55, 1.92)
        };
        let girth = r.range(0.85, 1.2);
        Body::new(height, child, girth)
    }

    /// The body of standing height `height` (metres) and build `girth`.
    pub fn new(height: f64, child: bool, girth: f64) -> Body {
        let h = height;
        // A child's head is a larger share of its height, legs shorter.
        let (head_r, leg) = if child {
            (0.085 * h, 0.47 * h)
        } else {
            (0.062 * h, 0.53 * h)
        };
        let ankle_h = 0.04 * h;
        let thigh = (leg - ankle_h) / 2.0;
        // Head centre sits one head radius below the top; neck below it.
        let head_z = h - head_r;
        let neck_z = head_z - 1.05 * head_r;
        let chest_z = neck_z - 0.035 * h;
        let torso = chest_z - leg;
        Body {
            height: h,
            child,
            hip_half: 0.055 * h * girth.sqrt(),
            shoulder_half: if child { 0.12 * h } else { 0.125 * h },
            thigh,
            shin: thigh,
            foot: 0.13 * h,
            ankle_h,
            upper_arm: 0.186 * h,
            forearm: 0.146 * h,
            hand: 0.09 * h,
            lumbar: 0.45 * torso,
            thorax: 0.55 * torso,
            neck: neck_z - chest_z,
            skull: head_z - neck_z,
            head_r,
            girth,
        }
    }

    /// Hip height of the standing pose: ankle height plus thigh and shin.
    pub fn leg(&self) -> f64 {
        self.ankle_h + self.thigh + self.shin
    }

    /// Length walked in one full walk cycle (two steps), metres.
    pub fn stride_m(&self) -> f64 {
        0.8 * self.height
    }

    /// Length of every bone of `BONES` at rest (the skeleton keeps them).
    pub fn bone_length(&self, b: (Joint, Joint)) -> f64 {
        use Joint::*;
        match b.1 {
            Spine => self.lumbar,
            Chest => self.thorax,
            Neck => self.neck,
            Head => self.skull,
            ShoulderL | ShoulderR => self.shoulder_half,
            ElbowL | ElbowR => self.upper_arm,
            WristL | WristR => self.forearm,
            HipL | HipR => self.hip_half,
            KneeL | KneeR => self.thigh,
            AnkleL | AnkleR => self.shin,
            ToeL | ToeR => (self.foot.powi(2) + self.ankle_h.powi(2)).sqrt(),
            Pelvis => 0.0,
        }
    }

    /// Limb radius at a joint, metres (flesh, under clothes).
    pub fn radius(&self, j: Joint) -> f64 {
        use Joint::*;
        let h = self.height;
        let g = self.girth;
        let r = match j {
            Pelvis => 0.095 * g,
            Spine => 0.085 * g,
            Chest => 0.1 * g,
            Neck => 0.03,
            Head => self.head_r / h,
            ShoulderL | ShoulderR => 0.03 * g,
            ElbowL | ElbowR => 0.022 * g,
            WristL | WristR => 0.017,
            HipL | HipR => 0.05 * g,
            KneeL | KneeR => 0.032 * g,
            AnkleL | AnkleR => 0.022,
            ToeL | ToeR => 0.02,
        };
        r * h
    }
}
