//! Measured metals as RGB complex IORs, and the roughness → α mapping.
//!
//! RGB η/κ are spectral measurements (Palik's Handbook of Optical Constants,
//! via refractiveindex.info) reduced to linear sRGB primaries; the table is the
//! widely used one shipped with Tungsten (`ComplexIorData.hpp`), except iron,
//! whose fit (η ≈ 2.9, κ ≈ 3.0, F0 ≈ 0.53/0.51/0.50) is the commonly circulated
//! one and is flagged as approximate.

use super::Bsdf;
use glam::Vec3;

/// GGX alpha from perceptual roughness r ∈ [0, 1] (α = r², Burley 2012).
pub fn roughness_to_alpha(r: f32) -> f32 {
    r * r
}

/// (name, η, κ) of every preset; names are lower-case English.
const METALS: [(&str, [f32; 3], [f32; 3]); 6] = [
    (
        "aluminium",
        [1.657_46, 0.880_369, 0.521_229],
        [9.223_869, 6.269_523, 4.837_001],
    ),
    (
        "chrome",
        [4.369_683, 2.916_702, 1.654_701],
        [5.206_434, 4.231_365, 3.754_947],
    ),
    (
        "copper",
        [0.200_438, 0.924_033, 1.102_212],
        [3.912_949, 2.452_848, 2.142_188],
    ),
    (
        "gold",
        [0.143_119, 0.374_957, 1.442_479],
        [3.983_16, 2.385_721, 1.603_215],
    ),
    (
        "silver",
        [0.155_265, 0.116_723, 0.138_381],
        [4.828_343, 3.122_246, 2.146_95],
    ),
    ("iron", [2.9114, 2.9497, 2.5845], [3.0893, 2.9318, 2.7670]),
];

impl Bsdf {
    /// A GGX conductor of a named metal ("aluminium"/"aluminum", "chrome",
    /// "copper", "gold", "silver", "iron"; case-insensitive) with roughness
    /// `alpha`; `None` for an unknown name.
    pub fn conductor_preset(name: &str, alpha: f32) -> Option<Bsdf> {
        let lower = name.to_ascii_lowercase();
        let key = match lower.as_str() {
            "aluminum" => "aluminium",
            "chromium" => "chrome",
            other => other,
        };
        METALS
            .iter()
            .find(|(n, _, _)| *n == key)
            .map(|(_, eta, k)| Bsdf::Conductor {
                eta: Vec3::from(*eta),
                k: Vec3::from(*k),
                alpha,
            })
    }

    /// Names accepted by [`Bsdf::conductor_preset`] (canonical spellings).
    pub fn conductor_preset_names() -> impl Iterator<Item = &'static str> {
        METALS.iter().map(|(n, _, _)| *n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bsdf::fresnel::fr_complex_rgb;

    #[test]
    fn metal_presets_have_plausible_normal_reflectance() {
        // F0 of real metals lies in ~[0.45, 0.99]; gold and copper are red-heavy.
        for name in Bsdf::conductor_preset_names() {
            let Some(Bsdf::Conductor { eta, k, .. }) = Bsdf::conductor_preset(name, 0.1) else {
                panic!("{name}");
            };
            let f0 = fr_complex_rgb(1.0, eta, k);
            assert!(
                f0.min_element() > 0.2 && f0.max_element() < 1.0,
                "{name}: {f0}"
            );
        }
        let Some(Bsdf::Conductor { eta, k, .. }) = Bsdf::conductor_preset("Gold", 0.0) else {
            panic!()
        };
        let f0 = fr_complex_rgb(1.0, eta, k);
        assert!(f0.x > f0.z + 0.3, "gold F0 {f0}");
        assert!(Bsdf::conductor_preset("aluminum", 0.0).is_some());
        assert!(Bsdf::conductor_preset("unobtainium", 0.0).is_none());
        assert_eq!(roughness_to_alpha(0.5), 0.25);
    }
}
