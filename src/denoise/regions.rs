//! The direct filter's robust view of a pixel's surroundings: the median
//! of the demodulated luminance over the 5 × 5 pixels of its surface, and
//! how far that median can move by noise alone. Isolated fireflies leave
//! the median alone, while a region lit or dark as a whole sets it, so two
//! pixels whose medians differ beyond that noise sit in different regions
//! even when one of them is so noisy (a lamp's light sampled by a few of
//! its samples) that its own value proves nothing (`edge_stop.rs`).

use rayon::prelude::*;

use super::surface::SurfKey;

/// Half the window's side: 5 × 5 pixels.
const RADIUS: usize = 2;

/// Window size.
const TAPS: usize = (2 * RADIUS + 1) * (2 * RADIUS + 1);

/// Neighbours whose geometric weight reaches this are on the pixel's
/// surface.
const SAME_SURFACE: f32 = 0.5;

/// One pixel's region: the median demodulated luminance of its window, the
/// median of their variances (a pixel's noise there, not raised by a
/// brighter region next door) and the variance of the median (from their
/// prefiltered variances: sparse lamp light leaves many pixels without a
/// hit, whose own variance of zero would make the median look certain).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Region {
    pub(super) level: f32,
    pub(super) pixel_var: f32,
    pub(super) var: f32,
}

/// A pixel's luminance, its variance and its prefiltered variance (over
/// 3 × 3), `None` without a ratio.
pub(super) type Sample = Option<(f32, f32, f32)>;

/// Per pixel, its [`Region`] (default without a sample): over the window's
/// samples on its surface (the pixel's own included), the median value and
/// variance, and as the median's variance π/2 times the median prefiltered
/// variance over their count (a median of n Gaussian values; medians of
/// the variances, so a bright region's noise beside a dark one does not
/// leak into its own).
pub(super) fn regions(
    samples: &[Sample],
    keys: &[SurfKey],
    (inv_rel2, inv_n2): (f32, f32),
    (w, h): (usize, usize),
) -> Vec<Region> {
    (0..w * h)
        .into_par_iter()
        .map(|k| {
            if samples[k].is_none() {
                return Region::default();
            }
            let (i, j) = (k % w, k / w);
            let (mut vals, mut vars, mut pre) = ([0.0f32; TAPS], [0.0f32; TAPS], [0.0f32; TAPS]);
            let mut n = 0;
            for jj in j.saturating_sub(RADIUS)..(j + RADIUS + 1).min(h) {
                for ii in i.saturating_sub(RADIUS)..(i + RADIUS + 1).min(w) {
                    let q = jj * w + ii;
                    let Some((e, v, p)) = samples[q] else {
                        continue;
                    };
                    if keys[k].weight(keys[q], inv_rel2, inv_n2) < SAME_SURFACE {
                        continue;
                    }
                    (vals[n], vars[n], pre[n]) = (e, v, p);
                    n += 1;
                }
            }
            // The pixel itself always counts (weight 1), so n ≥ 1.
            Region {
                level: median(&mut vals[..n]),
                pixel_var: median(&mut vars[..n]).max(0.0),
                var: std::f32::consts::FRAC_PI_2 * median(&mut pre[..n]).max(0.0) / n as f32,
            }
        })
        .collect()
}

/// The middle value (the upper one of an even count); NaN sorts last.
fn median(v: &mut [f32]) -> f32 {
    let m = v.len() / 2;
    *v.select_nth_unstable_by(m, |a, b| a.total_cmp(b)).1
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn flat(n: usize) -> Vec<SurfKey> {
        vec![SurfKey::new(10.0, Vec3::Z, 0.0); n]
    }

    #[test]
    fn a_firefly_leaves_the_median_and_a_step_sets_it() {
        // 7 × 7: left 3 columns 1.0, the rest 0.1, one firefly of 50 at
        // (5, 3); variances 0.01 (left) and 0.0001.
        let (w, h) = (7, 7);
        let samples: Vec<Sample> = (0..w * h)
            .map(|k| {
                let (i, j) = (k % w, k / w);
                Some(match (i, j) {
                    (5, 3) => (50.0, 0.0001, 0.0001),
                    (i, _) if i < 3 => (1.0, 0.01, 0.01),
                    _ => (0.1, 0.0001, 0.0001),
                })
            })
            .collect();
        let r = regions(&samples, &flat(w * h), (1.0, 1.0), (w, h));
        // Beside the firefly: the dark side's level.
        assert_eq!(r[3 * w + 5].level, 0.1);
        assert_eq!(r[3 * w + 4].level, 0.1);
        // Column 1: its window (columns 0..=3) holds 15 lit pixels and 5
        // dark ones.
        assert_eq!(r[3 * w + 1].level, 1.0);
        // 25 taps in the interior: π/2 · 0.0001 / 25.
        let want = std::f32::consts::FRAC_PI_2 * 0.0001 / 25.0;
        assert!((r[3 * w + 4].var - want).abs() < 1e-12);
    }

    #[test]
    fn another_surface_and_pixels_without_a_ratio_do_not_count() {
        // 7 × 1: pixels 0..=3 at 10 m (0.2, variances 0.01), pixel 1
        // without a ratio, pixels 4..=6 at 40 m (9.0, variances 1).
        let (w, h) = (7, 1);
        let samples: Vec<Sample> = (0..w)
            .map(|k| match k {
                1 => None,
                k if k < 4 => Some((0.2, 0.01, 0.01)),
                _ => Some((9.0, 1.0, 1.0)),
            })
            .collect();
        let keys: Vec<SurfKey> = (0..w)
            .map(|k| SurfKey::new(if k < 4 { 10.0 } else { 40.0 }, Vec3::Z, 0.0))
            .collect();
        let r = regions(&samples, &keys, (1.0 / 0.09, 1.0), (w, h));
        // Pixel 3's window holds pixels 1..=5: only 2 and 3 count.
        assert_eq!(r[3].level, 0.2);
        assert_eq!(r[3].pixel_var, 0.01);
        assert!((r[3].var - std::f32::consts::FRAC_PI_2 * 0.01 / 2.0).abs() < 1e-9);
        assert_eq!(r[1], Region::default());
        assert_eq!(r[4].level, 9.0);
    }
}
