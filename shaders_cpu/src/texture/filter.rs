//! Texture filtering by the ray's footprint: a pixel's samples see the
//! texture inside the pixel's footprint on the surface, so detail smaller
//! than that footprint only adds noise (at 16 spp, the texture's variance
//! inside the pixel over 16) that converges to its mean. Each pattern term
//! of feature size `size` is faded to its mean as the footprint grows past
//! it (Ebert et al., *Texturing & Modeling*, ch. 2, "clamping" of
//! frequencies; an isotropic footprint, as a ray cone gives): kept whole
//! while the footprint is below half the feature, gone at twice it.
//!
//! Fading alone would leave a far surface flatter than its converged
//! image: a box filter as wide as the footprint leaves white noise of cell
//! c a noise of std c/w of the original's (the average of (w/c)² cells),
//! at the footprint's scale. Noise terms get that residual back
//! ([`Footprint::residual`]): cell noise on cells of the footprint's size,
//! the way a mipmap's coarser levels hold a fine texture's averages.
//!
//! Filtering is deterministic (no random numbers) and keeps each term's
//! mean, so a mean-preserving texture stays mean-preserving at every
//! footprint.

use glam::DVec3;

use super::noise::{cell_noise, value_noise};
use super::smoothstep;

/// Footprint below this fraction of a feature's size keeps it whole.
const KEEP_BELOW: f32 = 0.5;
/// Footprint above this multiple of a feature's size fades it to its mean.
const GONE_ABOVE: f32 = 2.0;
/// The standard deviation of value noise's box average over one of its
/// cells (white noise: 1/√3; value noise's interpolation halves it, about).
const VALUE_STD: f32 = 0.2;

/// A shading point's footprint: the width (texture-space metres) of the
/// surface patch one pixel sees around it. 0 keeps every detail.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    /// Width, texture-space metres.
    pub w: f32,
    /// Whether faded noise leaves its residual ([`Footprint::residual`]);
    /// off for relief, where the residual's cell edges would be steps.
    grain: bool,
}

impl Footprint {
    /// No filtering: every detail kept.
    pub const SHARP: Footprint = Footprint {
        w: 0.0,
        grain: true,
    };

    /// A footprint `w` metres wide (texture space) for colour.
    pub fn new(w: f32) -> Self {
        Footprint { w, grain: true }
    }

    /// The same footprint for relief: faded terms leave no residual.
    pub fn relief(self) -> Self {
        Footprint {
            grain: false,
            ..self
        }
    }

    /// A term evaluated under the relief's footprint and under this one
    /// (relief, colour), for a term both use: `term` runs once when they
    /// agree, i.e. when no faded noise finer than the footprint, at most
    /// `finest_m`, leaves a residual.
    #[inline]
    pub fn relief_and_colour<T: Copy>(
        self,
        finest_m: f64,
        term: impl Fn(Footprint) -> T,
    ) -> (T, T) {
        if self.grain && self.w as f64 > finest_m {
            (term(self.relief()), term(self))
        } else {
            let x = term(self);
            (x, x)
        }
    }

    /// The weight in [0, 1] a feature of `size_m` metres keeps: 1 while the
    /// footprint is below half of it, 0 above twice it, smooth between.
    #[inline]
    pub fn keep(self, size_m: f64) -> f32 {
        1.0 - smoothstep(KEEP_BELOW, GONE_ABOVE, self.w / size_m as f32)
    }

    /// `x` of mean `mean` at feature size `size_m`, faded towards its mean.
    #[inline]
    pub fn fade(self, size_m: f64, x: f32, mean: f32) -> f32 {
        mean + (x - mean) * self.keep(size_m)
    }

    /// The share of a window as wide as the footprint, centred `d` from
    /// the centre line of a band of half-width `hw` that repeats every
    /// `period` (d in [0, period / 2]), that lies inside a band: the band's
    /// indicator box-filtered across it (Apodaca and Gritz, *Advanced
    /// RenderMan*, "filtered pulse train"). A footprint wider than the
    /// period gives the band's area share, 2·hw / period, wherever it is.
    #[inline]
    pub fn band_cover(self, d: f32, hw: f32, period: f32) -> f32 {
        let w = self.w.min(period);
        if w <= 0.0 {
            return f32::from(u8::from(d < hw));
        }
        let (lo, hi) = (d - 0.5 * w, d + 0.5 * w);
        let inside = |c: f32| (hi.min(c + hw) - lo.max(c - hw)).max(0.0);
        (inside(0.0) + inside(period) + inside(-period)) / w
    }

    /// A band's profile `sharp` (1 inside, falling to 0 beyond half-width
    /// `hw`) at distance `d` from its centre line, every `period`: itself
    /// under a footprint below the band's width, its box-filtered cover
    /// ([`Footprint::band_cover`]) above.
    #[inline]
    pub fn band(self, sharp: f32, d: f32, hw: f32, period: f32) -> f32 {
        let k = self.keep(2.0 * hw as f64);
        if k >= 1.0 {
            sharp
        } else {
            let cover = self.band_cover(d, hw, period);
            cover + (sharp - cover) * k
        }
    }

    /// What a box filter as wide as the footprint leaves of a white noise
    /// of cell `cell_m` and unit standard deviation: 0 while the footprint
    /// is below the cell, else a white noise on cells of the footprint's
    /// width L (power-of-two multiples of the cell, the two nearest
    /// blended as a mipmap's levels, variance kept through the blend) of
    /// standard deviation `cell_m` / w for a footprint w wide.
    pub fn residual(self, p: DVec3, cell_m: f64, seed: u32) -> f32 {
        let ratio = self.w as f64 / cell_m;
        if ratio <= 1.0 || !self.grain {
            return 0.0;
        }
        let level = ratio.log2();
        let l0 = level.floor();
        let t = (level - l0) as f32;
        // Each level at unit std (uniform in [-1, 1) has std 1/√3).
        let at = |l: f64| {
            let s = seed ^ (l as u32 + 1).wrapping_mul(0x2C1B_3C6D);
            cell_noise(p, cell_m * l.exp2(), s) * 3f32.sqrt()
        };
        let (w0, w1) = (1.0 - t, t);
        (w0 * at(l0) + w1 * at(l0 + 1.0)) / (w0 * w0 + w1 * w1).sqrt() / ratio as f32
    }

    /// A per-cell value `x` (cells of `cell_m`, mean 0, standard deviation
    /// `std`) filtered: faded past its cell, with the residual of its
    /// average ([`Footprint::residual`]). `x` is only called while kept.
    #[inline]
    pub fn cells(self, x: impl FnOnce() -> f32, std: f32, p: DVec3, cell_m: f64, seed: u32) -> f32 {
        let k = self.keep(cell_m);
        let sharp = if k > 0.0 { k * x() } else { 0.0 };
        if k >= 1.0 {
            sharp
        } else {
            sharp + (1.0 - k) * std * self.residual(p, cell_m, seed)
        }
    }

    /// [`value_noise`] filtered: faded to its mean 0 past its cell, with
    /// the residual of its average ([`Footprint::residual`]; value noise
    /// has std ~0.37, its average over the cell about half of that).
    #[inline]
    pub fn value_noise(self, p: DVec3, cell_m: f64, seed: u32) -> f32 {
        self.cells(|| value_noise(p, cell_m, seed), VALUE_STD, p, cell_m, seed)
    }

    /// [`cell_noise`] filtered: faded to its mean 0 past its cell, with
    /// the residual of its average (std 1/√3 before averaging).
    #[inline]
    pub fn cell_noise(self, p: DVec3, cell_m: f64, seed: u32) -> f32 {
        let std = 1.0 / 3f32.sqrt();
        self.cells(|| cell_noise(p, cell_m, seed), std, p, cell_m, seed)
    }

    /// [`super::noise::fbm`] with each octave faded by its own cell size
    /// (normalised by the unfaded amplitude sum, so it stays in [-1, 1]
    /// and equals `fbm` at [`Footprint::SHARP`]); octaves past the first
    /// one gone are not evaluated.
    pub fn fbm(self, p: DVec3, largest_m: f64, octaves: u32, gain: f32, seed: u32) -> f32 {
        let (mut sum, mut norm, mut amp, mut cell) = (0.0f32, 0.0f32, 1.0f32, largest_m);
        // The faded octaves' residuals, as one noise of their summed variance
        // relative to the finest faded cell (σ_o ∝ c_o, so each octave's
        // share is amp · c_o / c_min).
        let (mut faded, mut fine_cell) = (0.0f32, 0.0f64);
        for o in 0..octaves {
            let k = self.keep(cell);
            if k > 0.0 {
                let s = seed.wrapping_add(o.wrapping_mul(0x68E3_1DA4));
                sum += amp * k * value_noise(p, cell, s);
            }
            if k < 1.0 && self.w as f64 > cell {
                let share = (1.0 - k) * amp * (cell / largest_m) as f32;
                faded += share * share;
                fine_cell = cell;
            }
            norm += amp;
            amp *= gain;
            cell *= 0.5;
        }
        if faded > 0.0 {
            // Residual of the finest faded octave, scaled back to the sum.
            let r = self.residual(p, fine_cell, seed ^ 0x0F1B);
            sum += VALUE_STD * faded.sqrt() * (largest_m / fine_cell) as f32 * r;
        }
        sum / norm
    }
}

#[cfg(test)]
mod tests {
    use super::super::noise::fbm;
    use super::*;

    #[test]
    fn sharp_footprint_gives_the_unfiltered_bits() {
        for k in 0..200 {
            let p = DVec3::new(0.37, -1.3, 0.2) * (1.0 + k as f64 * 0.013);
            let f = Footprint::SHARP;
            assert_eq!(f.value_noise(p, 0.01, 7), value_noise(p, 0.01, 7));
            assert_eq!(f.cell_noise(p, 0.003, 7), cell_noise(p, 0.003, 7));
            assert_eq!(f.fbm(p, 0.3, 4, 0.6, 7), fbm(p, 0.3, 4, 0.6, 7));
        }
    }

    #[test]
    fn keep_is_whole_below_half_gone_above_twice_and_monotone() {
        let f = |w: f32| Footprint::new(w).keep(0.01);
        assert_eq!(f(0.0049), 1.0);
        assert_eq!(f(0.0201), 0.0);
        let mut last = 1.0;
        for k in 0..100 {
            let v = f(0.004 + k as f32 * 0.0002);
            assert!(v <= last && (0.0..=1.0).contains(&v));
            last = v;
        }
        // At the feature's own size: smoothstep(0.5, 2, 1) = 7/27 gone.
        assert!((f(0.01) - 20.0 / 27.0).abs() < 1e-6);
    }

    #[test]
    fn band_cover_is_the_box_filtered_band() {
        // A 1 cm band every 10 cm under a 4 cm window: on the band's centre
        // line the window holds the whole band (1/4), 3 cm off half of it
        // (the window [1, 5] cm meets [−0.5, 0.5] not at all, [9.5, 10.5]
        // not at all): 0; 2 cm off: [0, 4] ∩ [−0.5, 0.5] = 0.5 cm → 1/8.
        let f = Footprint::new(0.04);
        let close = |a: f32, b: f32| (a - b).abs() < 1e-5;
        assert!(close(f.band_cover(0.0, 0.005, 0.1), 0.25));
        assert!(close(f.band_cover(0.02, 0.005, 0.1), 0.125));
        assert!(close(f.band_cover(0.03, 0.005, 0.1), 0.0));
        // Wider than the period: the area share anywhere.
        for d in [0.0, 0.013, 0.05] {
            assert!(close(Footprint::new(0.3).band_cover(d, 0.005, 0.1), 0.1));
        }
        // The mean over a period is the area share at any footprint (a
        // box filter keeps the mean).
        for w in [0.001f32, 0.007, 0.02, 0.05, 0.099] {
            let n = 2000;
            let mean: f32 = (0..n)
                .map(|k| {
                    Footprint::new(w).band_cover((k as f32 + 0.5) / n as f32 * 0.05, 0.005, 0.1)
                })
                .sum::<f32>()
                / n as f32;
            assert!(
                close(mean, 0.1) || (mean - 0.1).abs() < 2e-4,
                "w {w}: {mean}"
            );
        }
        // Sharp: the indicator.
        assert_eq!(Footprint::SHARP.band_cover(0.004, 0.005, 0.1), 1.0);
        assert_eq!(Footprint::SHARP.band_cover(0.006, 0.005, 0.1), 0.0);
    }

    #[test]
    fn fbm_sheds_fine_octaves_first() {
        // A 20 cm footprint on a 1 m, five-octave fBm: the 1 m and 50 cm
        // octaves whole, 25 cm and 12.5 cm partly, 6.25 cm gone.
        let fp = Footprint::new(0.2);
        assert_eq!(
            (fp.keep(1.0), fp.keep(0.5), fp.keep(0.0625)),
            (1.0, 1.0, 0.0)
        );
        let (k2, k3) = (fp.keep(0.25), fp.keep(0.125));
        assert!(k2 > k3 && k3 > 0.0 && k2 < 1.0);
        let s = |o: u32| o.wrapping_mul(0x68E3_1DA4).wrapping_add(3);
        let mut worst = 0.0f32;
        for k in 0..500 {
            let p = DVec3::new(k as f64 * 0.0071, (k % 17) as f64 * 0.013, 0.5);
            let expect = (value_noise(p, 1.0, s(0))
                + 0.5 * value_noise(p, 0.5, s(1))
                + 0.25 * k2 * value_noise(p, 0.25, s(2))
                + 0.125 * k3 * value_noise(p, 0.125, s(3)))
                / (1.0 + 0.5 + 0.25 + 0.125 + 0.0625);
            // What is left over is the faded octaves' residual: cell noise
            // at the footprint's scale, bounded by its amplitude.
            worst = worst.max((fp.fbm(p, 1.0, 5, 0.5, 3) - expect).abs());
        }
        assert!(worst > 0.0 && worst < 0.02, "worst {worst}");
    }

    #[test]
    fn residual_has_the_std_of_a_box_average_of_white_noise() {
        // White noise of 1 cm cells, unit std, seen through footprints of
        // 4 cm and 11 cm: a noise of std 1/4 and 1/11 (the average of 16
        // and 121 cells), mean 0; nothing below the cell.
        for (w, expect) in [(0.04f32, 0.25f64), (0.11, 1.0 / 11.0)] {
            let n = 40_000;
            let (mut s1, mut s2) = (0.0f64, 0.0f64);
            for k in 0..n {
                let p = DVec3::new((k % 200) as f64 * 0.0517, (k / 200) as f64 * 0.0491, 0.3);
                let r = Footprint::new(w).residual(p, 0.01, 9) as f64;
                s1 += r;
                s2 += r * r;
            }
            let (m, sd) = (
                s1 / n as f64,
                (s2 / n as f64 - (s1 / n as f64).powi(2)).sqrt(),
            );
            assert!(m.abs() < 0.1 * expect, "w {w}: mean {m}");
            assert!(
                (sd / expect - 1.0).abs() < 0.1,
                "w {w}: std {sd} vs {expect}"
            );
        }
        assert_eq!(Footprint::new(0.009).residual(DVec3::ONE, 0.01, 9), 0.0);
    }
}
