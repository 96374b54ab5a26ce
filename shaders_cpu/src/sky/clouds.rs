//! A procedural cloud layer fixed in the world: a thin deck at a given
//! altitude whose opacity is fractal value noise of world (x, y). The sun's
//! transmittance through it depends only on the world position of the shaded
//! point and the sun direction, so every view of a frame sees the same shadows.
//! The same deck is drawn in the sky: a view ray from the frame's viewer
//! pierces it where a shadow ray towards that direction would, so the clouds
//! seen overhead are the ones that cast the shadows. Towards the horizon the
//! pierce point runs tens of km out and the pattern fades to its mean cover
//! (the distant deck is below a pixel and would only alias).
//!
//! World metres, z up; f64 positions so kilometres from the origin stay exact.

use glam::{DVec2, DVec3, Vec3};

/// The cloud deck.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CloudLayer {
    /// Fraction of the sky covered, 0–1.
    pub cover: f32,
    /// Height of the deck above world z = 0, m.
    pub altitude_m: f64,
    /// Size of the largest cloud features, m.
    pub feature_m: f64,
    /// Sun transmittance through a thick cloud, 0–1.
    pub min_transmittance: f32,
    /// Noise seed (one per sequence keeps the pattern fixed over a video).
    pub seed: u32,
    /// World position the sky is seen from (the frame's rig), metres.
    pub viewer_world: DVec3,
}

/// Below this |dir.z| the drawn deck is its mean cover; above `FADE_END` the
/// full pattern (sin⁻¹ 0.03 ≈ 1.7°, sin⁻¹ 0.12 ≈ 6.9°).
const FADE_START: f32 = 0.03;
const FADE_END: f32 = 0.12;

impl CloudLayer {
    /// A deck at 1500 m with ~1 km clouds passing 15% of the sun where thick.
    pub fn new(cover: f32, seed: u32) -> Self {
        CloudLayer {
            cover: cover.clamp(0.0, 1.0),
            altitude_m: 1500.0,
            feature_m: 1200.0,
            min_transmittance: 0.15,
            seed,
            viewer_world: DVec3::ZERO,
        }
    }

    /// The same deck seen from `viewer_world` (the frame's rig position).
    pub fn seen_from(self, viewer_world: DVec3) -> Self {
        CloudLayer {
            viewer_world,
            ..self
        }
    }

    /// Opacity of the deck drawn in the sky along world direction `dir`
    /// (unit, z up), 0–1: the deck's opacity where the ray from the viewer
    /// pierces it, blended to the mean `cover` near and below the horizon.
    pub fn sky_opacity(&self, dir: Vec3) -> f32 {
        let dz = dir.z;
        if self.cover <= 0.0 {
            return 0.0;
        }
        if dz <= FADE_START || self.viewer_world.z >= self.altitude_m {
            return self.cover;
        }
        let t = (self.altitude_m - self.viewer_world.z) / dz as f64;
        let q = self.viewer_world + dir.as_dvec3() * t;
        let w = ((dz - FADE_START) / (FADE_END - FADE_START)).clamp(0.0, 1.0);
        let w = w * w * (3.0 - 2.0 * w);
        self.cover + (self.opacity(q.truncate()) - self.cover) * w
    }

    /// Opacity of the deck at world (x, y), 0 (clear) – 1 (thick cloud).
    pub fn opacity(&self, xy: DVec2) -> f32 {
        if self.cover <= 0.0 {
            return 0.0;
        }
        let d = fbm(xy / self.feature_m, self.seed);
        // fbm is about normal with mean 0.5 and σ ≈ 0.12: a threshold linear
        // in `cover` makes roughly that fraction of the deck cloud, with soft
        // edges ±0.04.
        let threshold = 0.5 + 0.36 * (0.5 - self.cover as f64);
        let t = ((d - threshold + 0.04) / 0.08).clamp(0.0, 1.0);
        (t * t * (3.0 - 2.0 * t)) as f32
    }

    /// Transmittance of the sun towards `dir_to_sun` from world point
    /// `p_world`: where the ray pierces the deck, 1 − opacity·(1 − min).
    pub fn transmittance(&self, p_world: DVec3, dir_to_sun: Vec3) -> f32 {
        let dz = (dir_to_sun.z as f64).max(0.02);
        if p_world.z >= self.altitude_m {
            return 1.0;
        }
        let t = (self.altitude_m - p_world.z) / dz;
        let q = p_world + dir_to_sun.as_dvec3() * t;
        1.0 - self.opacity(q.truncate()) * (1.0 - self.min_transmittance)
    }
}

/// Four octaves of value noise in [0, 1].
fn fbm(p: DVec2, seed: u32) -> f64 {
    let (mut sum, mut amp, mut norm, mut q) = (0.0, 0.5, 0.0, p);
    for o in 0..4u32 {
        sum += amp * value_noise(q, seed.wrapping_add(o.wrapping_mul(0x9e37_79b9)));
        norm += amp;
        amp *= 0.5;
        q = q * 2.03 + DVec2::new(17.1, -9.7);
    }
    sum / norm
}

fn value_noise(p: DVec2, seed: u32) -> f64 {
    let (fx, fy) = (p.x.floor(), p.y.floor());
    let (tx, ty) = (p.x - fx, p.y - fy);
    let (sx, sy) = (tx * tx * (3.0 - 2.0 * tx), ty * ty * (3.0 - 2.0 * ty));
    let (ix, iy) = (fx as i64, fy as i64);
    let h = |x: i64, y: i64| hash(x, y, seed);
    let a = h(ix, iy) + (h(ix + 1, iy) - h(ix, iy)) * sx;
    let b = h(ix, iy + 1) + (h(ix + 1, iy + 1) - h(ix, iy + 1)) * sx;
    a + (b - a) * sy
}

/// Lattice hash → [0, 1) (a 64-bit mix; SplitMix64's finaliser).
pub(super) fn hash(x: i64, y: i64, seed: u32) -> f64 {
    let mut z = (x as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15)
        ^ (y as u64).wrapping_mul(0xc2b2_ae3d_27d4_eb4f)
        ^ (seed as u64).wrapping_mul(0x1656_67b1_9e37_79f9);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sky_opacity_is_the_shadow_casters_opacity() {
        // A point on the ground under the viewer's line of sight: its shadow
        // towards `dir` and the viewer's sky along `dir` meet the same cloud.
        let layer = CloudLayer::new(0.5, 9).seen_from(DVec3::new(3000.0, -700.0, 1.6));
        let mut cloudy = 0;
        for k in 0..64 {
            let a = k as f32 * 0.37;
            let dir = Vec3::new(0.5 * a.cos(), 0.5 * a.sin(), 0.866).normalize();
            let o = layer.sky_opacity(dir);
            let tr = layer.transmittance(layer.viewer_world, dir);
            let expect = 1.0 - o * (1.0 - layer.min_transmittance);
            assert!((tr - expect).abs() < 1e-6, "{dir}: {o} vs {tr}");
            cloudy += (o > 0.5) as i32;
        }
        assert!((5..59).contains(&cloudy), "{cloudy} of 64 cloudy");
    }

    #[test]
    fn sky_opacity_fades_to_cover_at_the_horizon_and_is_zero_when_clear() {
        let layer = CloudLayer::new(0.4, 2);
        assert_eq!(layer.sky_opacity(Vec3::X), 0.4);
        assert_eq!(layer.sky_opacity(-Vec3::Z), 0.4);
        assert_eq!(CloudLayer::new(0.0, 2).sky_opacity(Vec3::Z), 0.0);
    }
}
