//! Ray cones (Akenine-Möller et al., "Texture Level of Detail Strategies
//! for Real-Time Ray Tracing", Ray Tracing Gems 2019, ch. 20): the pixel a
//! camera ray stands for, carried along the path as a cone of width `width`
//! at its last vertex and spread angle `spread`, so a textured hit knows
//! the surface patch its pixel covers (`shaders_cpu::texture::Footprint`).
//!
//! A camera ray starts at the pinhole (width 0) with the spread of its
//! pixel: the side of a square of the pixel's solid angle, cos^1.5 θ / f
//! for a ray θ off the optical axis of a camera of focal length f pixels
//! (a pixel subtends cos³ θ / f² sr). At a hit t away the cone is
//! t·spread wide; the surface patch it covers, seen at incidence cosine
//! cos_i, has area (t·spread)² / cos_i, and its width — the side of a
//! square of that area — is the footprint: t·spread / √cos_i. On a wall
//! facing the camera that is depth / f, the pixel's exact footprint, at
//! every pixel. Only hits seen through delta bounces are textured, and a
//! flat mirror or pane keeps the cone's spread, so a delta bounce keeps
//! it too (curved glass would widen it: the footprint there stays small,
//! never too wide).

/// The smallest incidence cosine a footprint is computed at (grazing hits
/// would otherwise ask for a footprint of unbounded width).
const MIN_COS: f32 = 0.02;

/// A ray's cone: its width at its origin (metres) and its spread (radians).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RayCone {
    /// Width of the cone at the ray's origin, metres.
    pub width: f32,
    /// Growth of the width per metre travelled (spread angle, radians).
    pub spread: f32,
}

impl RayCone {
    /// No cone: every footprint 0 (textures unfiltered).
    pub const NONE: RayCone = RayCone {
        width: 0.0,
        spread: 0.0,
    };

    /// A camera ray's cone: width 0 at the pinhole, `spread` radians.
    pub fn primary(spread: f32) -> Self {
        RayCone { width: 0.0, spread }
    }

    /// The cone's width after travelling `dist` metres.
    #[inline]
    pub fn width_at(&self, dist: f32) -> f32 {
        self.width + self.spread * dist
    }

    /// The width of the surface patch the cone covers `dist` along the ray
    /// at a hit of incidence cosine `cos_i` (either sign).
    #[inline]
    pub fn footprint(&self, dist: f32, cos_i: f32) -> f32 {
        self.width_at(dist) / cos_i.abs().max(MIN_COS).sqrt()
    }

    /// The cone leaving a hit `dist` along the ray by a delta bounce.
    #[inline]
    pub fn through_delta(&self, dist: f32) -> Self {
        RayCone {
            width: self.width_at(dist),
            spread: self.spread,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn footprint_grows_with_distance_and_obliquity() {
        let c = RayCone::primary(0.002);
        assert!((c.footprint(10.0, 1.0) - 0.02).abs() < 1e-8);
        // At 60° incidence the patch is twice the area: √2 times as wide.
        assert!((c.footprint(10.0, 0.5) - 0.02 * 2f32.sqrt()).abs() < 1e-7);
        // Grazing hits are bounded, and the sign of the cosine is ignored.
        assert_eq!(c.footprint(10.0, 0.0), c.footprint(10.0, -MIN_COS));
        // A delta bounce 10 m on keeps the spread: 5 m further the width
        // is that of 15 m from the pinhole.
        let d = c.through_delta(10.0);
        assert!((d.footprint(5.0, 1.0) - c.footprint(15.0, 1.0)).abs() < 1e-7);
        assert_eq!(RayCone::NONE.footprint(100.0, 0.1), 0.0);
    }
}
