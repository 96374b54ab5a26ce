//! The third denoiser component: direct light at the split vertex
//! (`ViewInputs::l_direct`: its next-event estimates of sky and lamps; the
//! sun's stays as traced),
//! filtered as a ratio to rho like the light on the first surface, with an
//! edge-stopping weight on the signal itself (SVGF, Schied et al. 2017):
//! a neighbour counts only when its demodulated luminance lies within a
//! few standard deviations of the pixel's own noise (per-pixel variance from
//! the sample moments, prefiltered over 3 × 3 and carried through every pass
//! with the squared weights; the test is symmetric, on the variance of the
//! difference). A sun shadow's edge, a step far above the
//! noise on either side, stays; the grain of sky and lamp sampling within a
//! lit or shaded region goes (at night every lit surface's grain). Glossy
//! first surfaces (paint, rough metal) hand over all their light the same
//! way, against an albedo estimate, kept apart from Lambertian pixels. Geometry steers it as in `surface.rs`:
//! relative depth, normals, never sky.

use glam::Vec3;
use rayon::prelude::*;

use super::atrous::soft_gaussian;
use super::surface::{SurfKey, SIGMA_NORMAL};
use super::{DepthGuide, ViewInputs, Widths};
use crate::film::Film;
use crate::integrator::luminance;

/// à-trous levels (dilations 1, 2, 4, 8: a 61-pixel footprint), as SVGF:
/// the luminance weight, not the footprint, bounds what is mixed.
pub(super) const DIRECT_LEVELS: u32 = 4;

/// Edge-stopping width in standard deviations of the difference of two
/// pixels' demodulated luminances (cut at 3 of these: `soft_gaussian`).
const SIGMA_LUM: f32 = 2.0;

/// Relative luminance step always allowed (a floor on the noise σ, so a
/// noise-free pixel still mixes with neighbours of equal light).
const REL_FLOOR: f32 = 0.05;

/// One pixel's running estimate: Σw·l, Σw·rho (normalised), and the variance
/// of the demodulated luminance lum(l)/lum(rho) it implies.
#[derive(Clone, Copy, Debug, Default)]
struct Est {
    l: Vec3,
    rho: Vec3,
    var: f32,
}

impl Est {
    /// Demodulated luminance, `None` without rho.
    #[inline]
    fn ratio(&self) -> Option<f32> {
        let r = luminance(self.rho);
        (r > 0.0).then(|| luminance(self.l) / r)
    }
}

/// Replaces `l_direct` in `film` by its filtered estimate (as a ratio to
/// `rho_direct`); pixels without it, or with none in their filtered
/// neighbourhood (per channel), keep their radiance. `levels` à-trous levels (normally [`DIRECT_LEVELS`]).
pub(super) fn filter_direct(
    film: &mut Film,
    inputs: &ViewInputs,
    guide: &DepthGuide<'_>,
    widths: &Widths,
    levels: u32,
) {
    let (w, h) = (film.width, film.height);
    let n = w * h;
    assert!(
        inputs.l_direct.len() == n && inputs.var_direct.len() == n,
        "direct-light inputs' size does not match the film"
    );
    if inputs.rho_direct.iter().all(|&r| r == Vec3::ZERO) {
        return;
    }
    let normal = |k: usize| guide.normal.get(k).copied().unwrap_or(Vec3::ZERO);
    let keys: Vec<SurfKey> = (0..n)
        .map(|k| {
            SurfKey::new(guide.depth_z[k], normal(k), inputs.behind_delta[k])
                .with_glossy(inputs.glossy[k])
        })
        .collect();
    let geo = Geo {
        inv_rel2: 1.0 / widths.sigma_depth_rel.max(1e-6).powi(2),
        inv_n2: 1.0 / (SIGMA_NORMAL * SIGMA_NORMAL),
    };
    let mut cur: Vec<Est> = (0..n)
        .map(|k| {
            let (l, rho) = (inputs.l_direct[k], inputs.rho_direct[k]);
            let r = luminance(rho);
            let var = if r > 0.0 {
                inputs.var_direct[k] / (r * r)
            } else {
                0.0
            };
            Est { l, rho, var }
        })
        .collect();
    let mut sd = prefiltered_sd(&cur, &keys, &geo, (w, h));
    let mut tmp = vec![Est::default(); n];
    for level in 0..levels {
        let step = 1usize << level;
        pass(&cur, &mut tmp, &keys, &sd, &geo, (w, h), step, (1, 0));
        pass(&tmp, &mut cur, &keys, &sd, &geo, (w, h), step, (0, 1));
        // Later levels stop at the filtered estimate's own (smaller) noise.
        sd = cur.iter().map(|e| e.var.max(0.0).sqrt()).collect();
    }
    for (k, px) in film.rgb.iter_mut().enumerate() {
        let (s, rho) = (cur[k], inputs.rho_direct[k]);
        if rho == Vec3::ZERO {
            continue;
        }
        for c in 0..3 {
            // Below this the ratio is noise over nothing.
            if s.rho[c] > 1e-7 {
                px[c] += rho[c] * (s.l[c] / s.rho[c]) - inputs.l_direct[k][c];
            }
        }
    }
}

/// The geometric range weights (as the surface component's).
struct Geo {
    inv_rel2: f32,
    inv_n2: f32,
}

/// Per pixel, the σ its luminance weight starts from: the square root of its
/// demodulated variance averaged over the 3 × 3 pixels of its surface
/// (geometric weights), so that a pixel whose few samples happened to agree
/// does not pass for noise-free.
fn prefiltered_sd(cur: &[Est], keys: &[SurfKey], geo: &Geo, (w, h): (usize, usize)) -> Vec<f32> {
    (0..w * h)
        .into_par_iter()
        .map(|k| {
            let (i, j) = (k % w, k / w);
            let (mut s, mut ws) = (0.0f32, 0.0f32);
            for jj in j.saturating_sub(1)..(j + 2).min(h) {
                for ii in i.saturating_sub(1)..(i + 2).min(w) {
                    let q = jj * w + ii;
                    if cur[q].rho == Vec3::ZERO {
                        continue;
                    }
                    let b = if ii == i { 2.0 } else { 1.0 } * if jj == j { 2.0 } else { 1.0 };
                    let wt = b * keys[k].weight(keys[q], geo.inv_rel2, geo.inv_n2);
                    s += wt * cur[q].var;
                    ws += wt;
                }
            }
            if ws > 0.0 {
                (s / ws).max(0.0).sqrt()
            } else {
                0.0
            }
        })
        .collect()
}

/// The B3-spline taps at offsets −2..=2 (see `atrous.rs`).
const B3: [f32; 5] = [1.0 / 16.0, 0.25, 0.375, 0.25, 1.0 / 16.0];

/// One edge-stopping à-trous pass along `(di, dj)` with dilation `step`:
/// weights B3 × geometry × luminance; l and rho as weighted means, the
/// variance of the ratio through the squared rho-weighted weights.
#[allow(clippy::too_many_arguments)]
fn pass(
    data: &[Est],
    out: &mut [Est],
    keys: &[SurfKey],
    sd: &[f32],
    geo: &Geo,
    (w, h): (usize, usize),
    step: usize,
    (di, dj): (isize, isize),
) {
    out.par_chunks_mut(w).enumerate().for_each(|(j, row)| {
        for (i, o) in row.iter_mut().enumerate() {
            let c = j * w + i;
            let centre = data[c];
            let Some(e_c) = centre.ratio() else {
                *o = centre;
                continue;
            };
            let var_c = sd[c] * sd[c];
            let (mut l, mut rho, mut wsum) = (Vec3::ZERO, Vec3::ZERO, 0.0f32);
            let (mut var, mut asum) = (0.0f32, 0.0f32);
            for (t, &b3) in B3.iter().enumerate() {
                let d = (t as isize - 2) * step as isize;
                let (ii, jj) = (i as isize + d * di, j as isize + d * dj);
                if ii < 0 || jj < 0 || ii >= w as isize || jj >= h as isize {
                    continue;
                }
                let q = jj as usize * w + ii as usize;
                let nb = data[q];
                let Some(e_q) = nb.ratio() else {
                    continue;
                };
                let g = keys[c].geo_energy(keys[q], geo.inv_rel2, geo.inv_n2);
                let Some(g) = g else {
                    continue;
                };
                // Under "same light", e_c − e_q has variance var_c + var_q:
                // a symmetric test, so a bright outlier and its dark
                // neighbour see each other alike and light is moved, not lost.
                let de = e_c - e_q;
                let sigma2 = SIGMA_LUM * SIGMA_LUM * (var_c + sd[q] * sd[q])
                    + (REL_FLOOR * e_c.max(e_q)).powi(2)
                    + 1e-20;
                let wt = b3 * soft_gaussian(g + de * de / sigma2);
                l += nb.l * wt;
                rho += nb.rho * wt;
                wsum += wt;
                let a = wt * luminance(nb.rho);
                var += a * a * nb.var;
                asum += a;
            }
            // The centre tap always counts (weight 3/8), so wsum > 0.
            *o = Est {
                l: l / wsum,
                rho: rho / wsum,
                var: if asum > 0.0 {
                    var / (asum * asum)
                } else {
                    centre.var
                },
            };
        }
    });
}
