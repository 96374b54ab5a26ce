//! Colours for maps: the turbo colormap (Google's, as the 5th-order polynomial
//! fit of Ruofei Du), the CARLA/Cityscapes palette for semantic classes, a
//! hashed palette for instance ids and one colour per mask bit.

use crate::scene::mask_bits::{MIRROR, RAIN, SKY, TRANSPARENT};

/// Colour of invalid pixels in every colour-coded map (sky, no value).
pub const INVALID: [u8; 3] = [0, 0, 0];

/// Turbo at `t` ∈ [0, 1] (clamped): near-black → blue → green → yellow → dark red.
pub fn turbo(t: f64) -> [u8; 3] {
    let t = t.clamp(0.0, 1.0);
    let poly = |c: [f64; 6]| {
        let v = c[0] + t * (c[1] + t * (c[2] + t * (c[3] + t * (c[4] + t * c[5]))));
        (v.clamp(0.0, 1.0) * 255.0).round() as u8
    };
    [
        poly([
            0.13572138,
            4.61539260,
            -42.66032258,
            132.13108234,
            -152.94239396,
            59.28637943,
        ]),
        poly([
            0.09140261,
            2.19418839,
            4.84296658,
            -14.18503333,
            4.27729857,
            2.82956604,
        ]),
        poly([
            0.10667330,
            12.64194608,
            -60.58204836,
            110.36276771,
            -89.90310912,
            27.34824973,
        ]),
    ]
}

/// CARLA's colour of a semantic class id (`scene::semantic::CLASSES`);
/// white for an id beyond the table.
pub fn semantic_colour(id: u8) -> [u8; 3] {
    crate::scene::semantic::class_of(id).map_or([255, 255, 255], |c| c.colour)
}

/// A bright colour per instance id from a hash of the id (black for 0 = none),
/// so neighbouring ids differ.
pub fn instance_colour(id: u16) -> [u8; 3] {
    if id == 0 {
        return INVALID;
    }
    // splitmix64's finaliser: every bit of the id moves every output bit.
    let z = crate::sampler::mix64(id as u64);
    [0, 1, 2].map(|k| 64 + ((z >> (16 * k)) % 192) as u8)
}

/// The mask bits with their names and colours.
pub const MASK_COLOURS: [(u8, &str, [u8; 3]); 4] = [
    (SKY, "sky", [70, 130, 180]),
    (RAIN, "rain", [0, 255, 255]),
    (TRANSPARENT, "transparent", [255, 200, 0]),
    (MIRROR, "mirror", [255, 0, 255]),
];

/// The colour of a mask value: the mean of its set bits' colours, black for none.
pub fn mask_colour(m: u8) -> [u8; 3] {
    let set: Vec<[u8; 3]> = MASK_COLOURS
        .iter()
        .filter(|(bit, _, _)| m & bit != 0)
        .map(|&(_, _, c)| c)
        .collect();
    if set.is_empty() {
        return INVALID;
    }
    [0, 1, 2].map(|k| (set.iter().map(|c| c[k] as usize).sum::<usize>() / set.len()) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turbo_runs_from_dark_through_green_to_red_and_palettes_keep_black_for_none() {
        // Dark at 0, green in the middle, red at 1 (and never pure black).
        let (lo, mid, hi) = (turbo(0.0), turbo(0.5), turbo(1.0));
        assert!(lo.iter().map(|&v| v as u32).sum::<u32>() < 100, "{lo:?}");
        assert!(mid[1] > mid[0] && mid[1] > mid[2], "{mid:?}");
        assert!(hi[0] > hi[1] && hi[0] > hi[2], "{hi:?}");
        assert_ne!(turbo(0.0), INVALID);
        assert_eq!(semantic_colour(11), [70, 130, 180]);
        assert_eq!(instance_colour(0), INVALID);
        assert_ne!(instance_colour(1), instance_colour(2));
        assert_eq!(mask_colour(SKY | MIRROR), [162, 65, 217]);
    }
}
