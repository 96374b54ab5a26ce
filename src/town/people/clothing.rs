//! What a person wears: an outfit drawn per variant (top and its sleeves,
//! trousers, shorts or a skirt, shoes, hair style and colour, skin tone, a
//! bag), the people's materials, and dressing a posed skeleton in smooth
//! parts (`mesh::Parts`).

use glam::DVec3;

use super::super::materials::diffuse;
use super::super::rng::Rng;
use super::body::{Body, Joint};
use super::mesh::Parts;
use super::pose::Skeleton;
use crate::scene::desc::MaterialDesc;

/// Skin tones, linear albedo.
const SKINS: [[f64; 3]; 4] = [
    [0.62, 0.45, 0.36],
    [0.5, 0.34, 0.24],
    [0.32, 0.2, 0.13],
    [0.16, 0.1, 0.07],
];
/// Cloth colours (tops, bottoms, bags), linear albedo.
const CLOTHS: [(&str, [f64; 3]); 12] = [
    ("navy", [0.03, 0.05, 0.15]),
    ("denim", [0.1, 0.15, 0.3]),
    ("black", [0.025, 0.025, 0.03]),
    ("grey", [0.25, 0.25, 0.26]),
    ("white", [0.7, 0.7, 0.68]),
    ("red", [0.45, 0.05, 0.05]),
    ("green", [0.08, 0.22, 0.08]),
    ("khaki", [0.35, 0.3, 0.18]),
    ("brown", [0.18, 0.1, 0.05]),
    ("yellow", [0.7, 0.55, 0.1]),
    ("sky", [0.3, 0.45, 0.65]),
    ("plum", [0.25, 0.06, 0.2]),
];
/// Hair colours: black, dark brown, light brown, blond, grey.
const HAIRS: [[f64; 3]; 5] = [
    [0.015, 0.012, 0.01],
    [0.06, 0.035, 0.02],
    [0.2, 0.11, 0.05],
    [0.5, 0.38, 0.18],
    [0.4, 0.4, 0.4],
];

/// Lower garment.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bottom {
    /// Full-length trousers.
    Trousers,
    /// Shorts to above the knee.
    Shorts,
    /// A skirt flaring to the knees.
    Skirt,
}

/// Hair style.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Hair {
    /// None.
    Bald,
    /// Short, close to the skull.
    Short,
    /// Long, down the back to the shoulders.
    Long,
    /// Tied in a bun at the back.
    Bun,
}

/// A bag, if any.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Bag {
    /// No bag.
    None,
    /// On the back.
    Backpack,
    /// Hanging at the left hip from the shoulder.
    Shoulder,
}

/// One variant's clothes and colours (material names).
#[derive(Clone, Debug, PartialEq)]
pub struct Outfit {
    /// Skin material.
    pub skin: String,
    /// Top material; long sleeves reach the wrists (a jacket).
    pub top: String,
    /// Whether the sleeves reach the wrists (a jacket).
    pub long_sleeves: bool,
    /// Lower garment and its material.
    pub bottom: Bottom,
    /// Lower garment material.
    pub bottom_mat: String,
    /// Shoe material.
    pub shoes: String,
    /// Hair style and material.
    pub hair: Hair,
    /// Hair material.
    pub hair_mat: String,
    /// Bag and its material.
    pub bag: Bag,
    /// Bag material.
    pub bag_mat: String,
}

fn cloth(r: &mut Rng) -> String {
    format!("person_{}", CLOTHS[r.index(CLOTHS.len())].0)
}

impl Outfit {
    /// Draws an outfit from the variant stream `r`.
    pub fn draw(r: &mut Rng, child: bool) -> Outfit {
        let skin = format!("person_skin_{}", r.index(SKINS.len()));
        let top = cloth(r);
        let long_sleeves = r.chance(0.55);
        let bottom = match r.f64() {
            x if x < 0.65 => Bottom::Trousers,
            x if x < 0.82 => Bottom::Shorts,
            _ => Bottom::Skirt,
        };
        let mut bottom_mat = cloth(r);
        if bottom_mat == top {
            bottom_mat = "person_denim".into();
        }
        let shoes = ["person_black", "person_white", "person_brown"][r.index(3)].to_string();
        let hair = [Hair::Bald, Hair::Short, Hair::Short, Hair::Long, Hair::Bun][r.index(5)];
        let hair = if child && hair == Hair::Bald {
            Hair::Short
        } else {
            hair
        };
        // Grey hair on adults only.
        let hair_n = if child { 4 } else { HAIRS.len() };
        let hair_mat = format!("person_hair_{}", r.index(hair_n));
        let bag = [Bag::None, Bag::None, Bag::Backpack, Bag::Shoulder][r.index(4)];
        Outfit {
            skin,
            top,
            long_sleeves,
            bottom,
            bottom_mat,
            shoes,
            hair,
            hair_mat,
            bag,
            bag_mat: cloth(r),
        }
    }
}

/// Every material an outfit names.
pub fn people_materials() -> Vec<MaterialDesc> {
    let skins = SKINS
        .iter()
        .enumerate()
        .map(|(k, c)| diffuse(&format!("person_skin_{k}"), *c));
    let hairs = HAIRS
        .iter()
        .enumerate()
        .map(|(k, c)| diffuse(&format!("person_hair_{k}"), *c));
    let cloths = CLOTHS
        .iter()
        .map(|(n, c)| diffuse(&format!("person_{n}"), *c));
    skins
        .chain(hairs)
        .chain(cloths)
        .chain([diffuse("person_umbrella_shaft", [0.05, 0.05, 0.05])])
        .collect()
}

/// Dresses skeleton `k` of `body` in `o`: smooth parts per material.
pub fn dress(body: &Body, k: &Skeleton, o: &Outfit, parts: &mut Parts) {
    use Joint::*;
    let r = |j| body.radius(j);
    let p = |j| k.at(j);
    // Torso: hips in the bottom's material (skin under a skirt is hidden),
    // chest in the top's, flattened front to back.
    parts.capsule(
        &o.bottom_mat,
        p(Pelvis),
        p(Spine),
        r(Pelvis),
        r(Spine),
        0.62,
    );
    parts.capsule(&o.top, p(Spine), p(Chest), r(Spine) * 1.02, r(Chest), 0.6);
    parts.capsule(&o.skin, p(Chest), p(Neck), r(Neck), r(Neck), 1.0);
    // Head: a little deeper than wide; hair an offset shell behind the face.
    let hr = body.head_r;
    let head = p(Head);
    parts.ellipsoid(&o.skin, head, DVec3::new(0.92, 0.8, 1.0) * hr, 10, 6);
    let shell = DVec3::new(0.9, 0.84, 0.98) * hr * 1.04;
    match o.hair {
        Hair::Bald => {}
        Hair::Short | Hair::Long | Hair::Bun => {
            let c = head + DVec3::new(-0.12 * hr, 0.0, 0.1 * hr);
            parts.ellipsoid(&o.hair_mat, c, shell, 10, 6);
        }
    }
    if o.hair == Hair::Long {
        let top = head + DVec3::new(-0.45 * hr, 0.0, 0.2 * hr);
        let low = p(Neck) + DVec3::new(-0.7 * hr, 0.0, -0.9 * hr);
        parts.capsule(&o.hair_mat, top, low, 0.6 * hr, 0.45 * hr, 0.6);
    }
    if o.hair == Hair::Bun {
        parts.ellipsoid(
            &o.hair_mat,
            head + DVec3::new(-hr, 0.0, 0.35 * hr),
            DVec3::splat(0.35 * hr),
            8,
            4,
        );
    }
    for (sh, el, wr) in [(ShoulderL, ElbowL, WristL), (ShoulderR, ElbowR, WristR)] {
        parts.capsule(&o.top, p(Chest), p(sh), r(Chest) * 0.5, r(sh) * 1.25, 0.8);
        parts.capsule(&o.top, p(sh), p(el), r(sh) * 1.1, r(el) * 1.1, 1.0);
        let forearm = if o.long_sleeves { &o.top } else { &o.skin };
        parts.capsule(forearm, p(el), p(wr), r(el), r(wr), 1.0);
        let along = (p(wr) - p(el)).normalize();
        parts.capsule(
            &o.skin,
            p(wr),
            p(wr) + along * body.hand * 0.75,
            r(wr),
            r(wr) * 0.8,
            0.55,
        );
    }
    for (hip, knee, ankle, toe) in [(HipL, KneeL, AnkleL, ToeL), (HipR, KneeR, AnkleR, ToeR)] {
        let thigh = if o.bottom == Bottom::Trousers || o.bottom == Bottom::Shorts {
            &o.bottom_mat
        } else {
            &o.skin
        };
        let shin = if o.bottom == Bottom::Trousers {
            &o.bottom_mat
        } else {
            &o.skin
        };
        parts.capsule(thigh, p(hip), p(knee), r(hip), r(knee), 1.0);
        parts.capsule(shin, p(knee), p(ankle), r(knee) * 0.95, r(ankle), 1.0);
        // Shoe: heel under the ankle to the toe tip, sole at the ground.
        let sole_r = body.ankle_h * 0.5;
        let heel = p(ankle) - DVec3::Z * sole_r;
        let tip = p(toe) + (heel - p(toe)).normalize() * sole_r + DVec3::Z * sole_r;
        parts.capsule(&o.shoes, heel, tip, sole_r, sole_r, 1.0);
    }
    if o.bottom == Bottom::Skirt {
        let top = p(Spine) - DVec3::Z * (0.2 * body.lumbar);
        let len = top.z - (p(KneeL).z.max(p(KneeR).z) + 0.04 * body.height);
        // A skirt hangs: only over legs below the waist (never seated).
        if len > 0.1 * body.height {
            parts.frustum(
                &o.bottom_mat,
                top,
                len,
                r(Pelvis) * 1.03,
                r(Pelvis) * 1.45,
                0.75,
            );
        }
    }
    match o.bag {
        Bag::None => {}
        Bag::Backpack => {
            let back = (p(Spine) + p(Chest)) / 2.0 - DVec3::X * (r(Chest) * 0.6 + 0.07);
            parts.capsule(
                &o.bag_mat,
                back - DVec3::Z * 0.1,
                back + DVec3::Z * 0.1,
                0.11,
                0.1,
                0.55,
            );
        }
        Bag::Shoulder => {
            let side = p(HipL) + DVec3::new(-0.02, r(Pelvis) * 0.9, 0.12 * body.height / 1.75);
            parts.capsule(
                &o.bag_mat,
                side - DVec3::X * 0.09,
                side + DVec3::X * 0.09,
                0.07,
                0.07,
                1.0,
            );
            parts.capsule(
                &o.bag_mat,
                side,
                p(ShoulderR) + DVec3::Z * 0.02,
                0.008,
                0.008,
                1.0,
            );
        }
    }
}
