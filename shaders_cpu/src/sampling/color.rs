//! Colour helpers on linear RGB (Rec.709 primaries, D65 white).

use glam::Vec3;

/// Relative luminance Y of a linear Rec.709 RGB colour (ITU-R BT.709 weights).
#[inline]
pub fn luminance(rgb: Vec3) -> f32 {
    rgb.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn luminance_of_white_is_one() {
        assert!((luminance(Vec3::ONE) - 1.0).abs() < 1e-6);
        assert!((luminance(Vec3::new(0.0, 2.0, 0.0)) - 1.4304).abs() < 1e-6);
    }
}
