//! Gives back the light a filter dropped. The surface filter leaves
//! fireflies out of its sums and stops at bright noise, so it returns less
//! light than it was given: in haze and fog, where the light on a surface
//! is heavy-tailed, up to 1.4 % of the image (town10, in scene light against
//! plain renders of the same frame). Over a wide window the filtered light
//! is rescaled so that its sum there is the traced light's: what was
//! dropped comes back spread thin, as a gentle gain over the window, not as
//! specks. At night the loss is most of the light: between lamps a
//! surface's indirect light arrives as rare bright paths (lamp pools, cars
//! in head-light beams, seen by a diffuse bounce), which the firefly rule
//! leaves out in most pixels: over town03's night frame the filtered light
//! was a fifth of the traced (the median pixel's window). Such a loss,
//! carried by many pixels, comes back whole; one rare huge path (the sun in
//! a window) is held to [`MAX_GAIN`], so it cannot light up a whole window
//! ([`gain_bound`]).
//!
//! Fixed-order sums in f64 (summed-area tables): the same bytes on any
//! thread count.

use glam::Vec3;

/// Largest factor (and smallest, its inverse) by which the filtered light
/// is rescaled where few paths carry the loss: a few per cent is what the
/// filters lose on average by day; more would be one path's light spread
/// over a window.
pub(super) const MAX_GAIN: f64 = 1.1;

/// Half-width in pixels of each of the two box passes that make the window,
/// for a view `width` pixels wide: the window spans a tenth of the width
/// either way (a fixed angular size), so a dropped firefly's light is
/// shared by thousands of pixels.
pub(super) fn window_radius(width: usize) -> usize {
    (width / 20).max(1)
}

/// Rescales each pixel's filtered component `filtered` (what the film now
/// holds of it) by the ratio of the traced component's sum (`traced`) to
/// the filtered one's over the window around the pixel. The window is a
/// box of half-width `radius` applied twice: a tent-like weight, so a
/// bright path's gain fades out instead of ending in a square's edge. The
/// sums add the three channels, so the gain has no colour. The gain is
/// bounded by [`gain_bound`]. `film`, `filtered` and `traced` are
/// row-major views `w` pixels wide.
pub(super) fn restore(
    film: &mut [Vec3],
    filtered: &[Vec3],
    traced: &[Vec3],
    w: usize,
    radius: usize,
) {
    let n = film.len();
    assert!(filtered.len() == n && traced.len() == n && w > 0 && n.is_multiple_of(w));
    let h = n / w;
    let sum = |v: &[Vec3]| v.iter().map(|p| p.element_sum() as f64).collect::<Vec<_>>();
    let (traced_sum, filtered_sum) = (sum(traced), sum(filtered));
    let tent = |v: &[f64]| box_sums(&box_sums(v, w, h, radius), w, h, radius);
    let (sum_traced, sum_filtered) = (tent(&traced_sum), tent(&filtered_sum));
    // The light each pixel lost, and (over the window's square) how many
    // pixels' worth of paths carry the loss.
    let lost: Vec<f64> = (traced_sum.iter().zip(&filtered_sum))
        .map(|(t, f)| (t - f).max(0.0))
        .collect();
    let lost2: Vec<f64> = lost.iter().map(|d| d * d).collect();
    let (sum_lost, sum_lost2) = (
        box_sums(&lost, w, h, radius),
        box_sums(&lost2, w, h, radius),
    );
    for (k, px) in film.iter_mut().enumerate() {
        if filtered[k] == Vec3::ZERO || sum_filtered[k] <= 0.0 {
            continue;
        }
        let gain = sum_traced[k] / sum_filtered[k];
        let carriers = if sum_lost2[k] > 0.0 {
            sum_lost[k] * sum_lost[k] / sum_lost2[k]
        } else {
            0.0
        };
        let gain = gain.clamp(1.0 / MAX_GAIN, gain_bound(gain, carriers));
        *px += filtered[k] * (gain - 1.0) as f32;
    }
}

/// Effective number of pixels ((Σd)² / Σd² of the light d each lost) that
/// must carry a window's lost light before it is given back whole: one
/// path's light, however bright, stays within [`MAX_GAIN`]; light lost
/// all over a window (at night the light between lamps is mostly such
/// paths, and most of it is left out as fireflies) comes back.
pub(super) const CARRIERS_FOR_FULL_GAIN: f64 = 16.0;

/// The largest gain for a window whose unbounded gain is `gain` and whose
/// lost light `carriers` pixels' worth of paths carry: [`MAX_GAIN`] below
/// half of [`CARRIERS_FOR_FULL_GAIN`], `gain` itself from
/// [`CARRIERS_FOR_FULL_GAIN`] on, and between the two a smooth step, so no
/// edge shows where the count crosses.
fn gain_bound(gain: f64, carriers: f64) -> f64 {
    if gain <= MAX_GAIN {
        return MAX_GAIN;
    }
    let half = 0.5 * CARRIERS_FOR_FULL_GAIN;
    let t = ((carriers - half) / half).clamp(0.0, 1.0);
    let step = t * t * (3.0 - 2.0 * t);
    MAX_GAIN + (gain - MAX_GAIN) * step
}

/// Per pixel, the sum of `v` (row-major, `w × h`) over the square of
/// half-width `radius` around it, cut at the image's border; from a
/// summed-area table, in fixed order.
fn box_sums(v: &[f64], w: usize, h: usize, radius: usize) -> Vec<f64> {
    // Entry (j, i) of the (w + 1) × (h + 1) table: the sum over rows < j
    // and columns < i.
    let mut sat = vec![0.0f64; (w + 1) * (h + 1)];
    for j in 0..h {
        let mut row = 0.0f64;
        for i in 0..w {
            row += v[j * w + i];
            sat[(j + 1) * (w + 1) + i + 1] = sat[j * (w + 1) + i + 1] + row;
        }
    }
    let at = |i: usize, j: usize| sat[j * (w + 1) + i];
    (0..w * h)
        .map(|k| {
            let (i, j) = (k % w, k / w);
            let (x0, x1) = (i.saturating_sub(radius), (i + radius + 1).min(w));
            let (y0, y1) = (j.saturating_sub(radius), (j + radius + 1).min(h));
            at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `w × h` view of light 1 (a wall), a 20× firefly in every 9th
    /// pixel; the "filter" replaced each firefly by its neighbours' level.
    fn wall_with_fireflies(w: usize, h: usize) -> (Vec<Vec3>, Vec<Vec3>) {
        let n = w * h;
        let traced: Vec<Vec3> = (0..n)
            .map(|k| Vec3::splat(if k % 9 == 7 { 20.0 } else { 1.0 }))
            .collect();
        (traced, vec![Vec3::ONE; n])
    }

    #[test]
    fn fireflies_all_over_a_window_come_back_whole_and_spread_thin() {
        // At night most of the light between lamps is such paths.
        // A window (21 × 21) holds 49 fireflies.
        let (w, h) = (200, 100);
        let (traced, filtered) = wall_with_fireflies(w, h);
        let mut film = filtered.clone();
        restore(&mut film, &filtered, &traced, w, window_radius(w));
        let sum = |v: &[Vec3]| v.iter().map(|p| p.x as f64).sum::<f64>();
        // Before: 68 % of the light gone; after, within a few per cent of
        // all of it (the window is cut at the border, so the gain varies),
        // and no pixel is a speck: every gain lies near the loss's 3.1.
        let (t, f) = (sum(&traced), sum(&filtered));
        assert!(f / t < 0.35, "{}", f / t);
        let got = sum(&film) / t;
        assert!((got - 1.0).abs() < 0.03, "{got} of the traced light");
        for (k, p) in film.iter().enumerate() {
            assert!(p.x > 2.0 && p.x < 4.0, "pixel {k}: {p}");
        }
    }

    #[test]
    fn one_paths_light_stays_within_the_bound() {
        // One path of 10 000 units dropped in a flat field of 1: its window
        // would be lit ten times over; it gets at most MAX_GAIN.
        let w = 101;
        let centre = 50 * w + 50;
        let mut traced = vec![Vec3::ONE; w * w];
        traced[centre] = Vec3::splat(1e4);
        let filtered = vec![Vec3::ONE; w * w];
        let mut film = filtered.clone();
        restore(&mut film, &filtered, &traced, w, window_radius(w));
        assert!(
            (film[centre].x as f64 - MAX_GAIN).abs() < 1e-5,
            "{}",
            film[centre]
        );
        for p in &film {
            assert!(p.x >= 1.0 && p.x as f64 <= MAX_GAIN + 1e-6, "{p}");
        }
    }

    #[test]
    fn the_bound_rises_smoothly_with_the_lost_lights_carriers() {
        let full = CARRIERS_FOR_FULL_GAIN;
        assert_eq!(gain_bound(5.0, 1.0), MAX_GAIN);
        assert_eq!(gain_bound(5.0, 0.5 * full), MAX_GAIN);
        assert_eq!(gain_bound(5.0, full), 5.0);
        assert_eq!(gain_bound(1.05, full), MAX_GAIN);
        let mut last = MAX_GAIN;
        for i in 0..=100 {
            let b = gain_bound(5.0, full * (0.5 + 0.005 * i as f64));
            assert!(b >= last && b - last < 0.1, "step {i}: {last} -> {b}");
            last = b;
        }
    }

    #[test]
    fn a_small_loss_is_given_back_whole() {
        // Fireflies of 1.5× in every 40th pixel: 1.25 % lost, the loss in fog.
        let n = 80 * 40;
        let traced: Vec<Vec3> = (0..n)
            .map(|k| Vec3::splat(if k % 40 == 3 { 1.5 } else { 1.0 }))
            .collect();
        let filtered = vec![Vec3::ONE; n];
        let mut film: Vec<Vec3> = filtered.iter().map(|p| *p + Vec3::splat(0.5)).collect();
        restore(&mut film, &filtered, &traced, 80, window_radius(80));
        let total = |v: &[Vec3]| v.iter().map(|p| p.y as f64).sum::<f64>();
        let want = total(&traced) + 0.5 * n as f64;
        assert!(
            (total(&film) / want - 1.0).abs() < 2e-3,
            "{} against {want}",
            total(&film)
        );
    }

    #[test]
    fn light_the_filter_kept_is_left_as_it_is() {
        let (traced, _) = wall_with_fireflies(64, 32);
        let mut film: Vec<Vec3> = traced.iter().map(|p| *p * 2.0).collect();
        let before = film.clone();
        restore(&mut film, &traced, &traced, 64, 3);
        assert_eq!(film, before);
    }

    #[test]
    fn the_gain_stays_local() {
        // Left half lost 5 %, right half nothing: the right edge keeps its light.
        let (w, h) = (200, 10);
        let traced: Vec<Vec3> = (0..w * h)
            .map(|k| Vec3::splat(if k % w < 100 { 1.05 } else { 1.0 }))
            .collect();
        let filtered = vec![Vec3::ONE; w * h];
        let mut film = filtered.clone();
        restore(&mut film, &filtered, &traced, w, window_radius(w));
        assert!((film[0].x - 1.05).abs() < 1e-5, "{}", film[0]);
        assert_eq!(film[w - 1].x, 1.0);
    }

    #[test]
    fn a_dropped_paths_light_fades_out_without_an_edge() {
        // One pixel's path of 3 units dropped in a flat field of 1: the gain
        // is highest at it and falls step by step (a single box would hold
        // it flat to the window's edge, then drop it at once).
        let w = 101;
        let centre = 50 * w + 50;
        let mut traced = vec![Vec3::ONE; w * w];
        traced[centre] = Vec3::splat(4.0);
        let filtered = vec![Vec3::ONE; w * w];
        let mut film = filtered.clone();
        restore(&mut film, &filtered, &traced, w, window_radius(w));
        let row: Vec<f32> = film[50 * w..51 * w].iter().map(|p| p.x - 1.0).collect();
        let peak = row[50];
        assert!(peak > 0.0 && row[0] == 0.0, "{peak} {}", row[0]);
        for x in 50..w - 1 {
            let step = row[x] - row[x + 1];
            assert!(
                step >= 0.0 && step < 0.25 * peak,
                "x {x}: {} -> {}",
                row[x],
                row[x + 1]
            );
        }
    }
}
