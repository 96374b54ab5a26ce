//! The edge-stopping à-trous kernel of the direct, reflection and
//! first-surface components: a light [`Part`] filtered as a ratio to what
//! it is filtered against, with an edge-stopping weight on the signal
//! itself (SVGF, Schied et al. 2017): a neighbour counts only when its
//! demodulated luminance lies within a few standard deviations of the
//! pixel's own noise (per-pixel variance from the sample moments,
//! prefiltered over 3 × 3 and carried through every pass with the squared
//! weights). Within a region the test is symmetric, on the variance of the
//! difference, so fireflies are spread; between regions (robust 5 × 5
//! medians that disagree, `regions.rs`) it stops at the quieter side's
//! noise, so a lamp-lit surface's noisy light does not bleed into the dark
//! beside it. A step far above the noise on either side stays. Geometry
//! steers it as in `surface.rs`: relative depth, normals, never sky.

use glam::Vec3;
use rayon::prelude::*;

use super::atrous::soft_gaussian;
use super::regions::{regions, Region, Sample};
use super::surface::{SurfKey, SIGMA_NORMAL};
use super::{DepthGuide, ViewInputs, Widths};
use crate::film::Film;
use crate::integrator::luminance;

/// Width, in standard deviations of the quieter region's noise, within
/// which two regions' medians count as the same light ([`pair_var`]).
const REGION_SIGMA: f32 = 2.0;

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

/// One component the edge-stopping filter replaces: per pixel its mean
/// light, what it is filtered against, the variance of the light's
/// luminance as a pixel mean, and what the filtered ratio is modulated
/// back by (nonzero: the pixel is filtered).
pub(super) struct Part<'a> {
    pub(super) l: &'a [Vec3],
    pub(super) rho: &'a [Vec3],
    pub(super) var: &'a [f32],
    pub(super) remod: &'a [Vec3],
    /// The light the film holds for this part, replaced by the filtered
    /// estimate: `l`, but where a pixel is left out of the sums (the
    /// surface component's fireflies, `l` zero) its light as traced.
    pub(super) traced: &'a [Vec3],
    /// Edge-stopping width in standard deviations.
    pub(super) sigma_lum: f32,
    /// Whether the luminance test stops at the quieter side's noise
    /// between regions ([`pair_var`]); otherwise it is symmetric
    /// everywhere (light whose noise is not heavy-tailed, as indirect
    /// light on the first surface).
    pub(super) between_regions: bool,
    /// Per pixel, the openness of its first surface's bounce
    /// (`ViewInputs::openness`) as a further key, for light that depends
    /// on it; None: not a key.
    pub(super) openness: Option<&'a [f32]>,
}

/// Replaces `part`'s light in `film` by its filtered estimate (as a ratio
/// to `part.rho`, modulated back by `part.remod`); pixels without it, or
/// with none in their filtered neighbourhood (per channel), keep their
/// radiance. `levels` à-trous levels.
pub(super) fn filter_part(
    film: &mut Film,
    part: &Part<'_>,
    inputs: &ViewInputs,
    guide: &DepthGuide<'_>,
    widths: &Widths,
    levels: u32,
) {
    let (w, h) = (film.width, film.height);
    let n = w * h;
    assert!(
        [
            part.l.len(),
            part.rho.len(),
            part.var.len(),
            part.remod.len(),
            part.traced.len()
        ]
        .iter()
        .all(|&len| len == n),
        "filtered light's inputs' size does not match the film"
    );
    if part.remod.iter().all(|&r| r == Vec3::ZERO) {
        return;
    }
    let normal = |k: usize| guide.normal.get(k).copied().unwrap_or(Vec3::ZERO);
    let keys: Vec<SurfKey> = (0..n)
        .into_par_iter()
        .map(|k| {
            let key = SurfKey::new(guide.depth_z[k], normal(k), inputs.behind_delta[k])
                .with_glossy(inputs.glossy[k]);
            part.openness.map_or(key, |o| key.with_openness(o[k]))
        })
        .collect();
    let geo = Geo {
        inv_rel2: 1.0 / widths.sigma_depth_rel.max(1e-6).powi(2),
        inv_n2: 1.0 / (SIGMA_NORMAL * SIGMA_NORMAL),
    };
    let mut cur: Vec<Est> = (0..n)
        .into_par_iter()
        .map(|k| {
            let (l, rho) = (part.l[k], part.rho[k]);
            let r = luminance(rho);
            let var = if r > 0.0 { part.var[k] / (r * r) } else { 0.0 };
            Est { l, rho, var }
        })
        .collect();
    let mut sd = prefiltered_sd(&cur, &keys, &geo, (w, h));
    let regions = part.between_regions.then(|| {
        let samples: Vec<Sample> = cur
            .par_iter()
            .zip(&sd)
            .map(|(est, &s)| {
                let lum = Lum::of(est);
                (lum.r != 0.0).then_some((lum.e, est.var, s * s))
            })
            .collect();
        regions(&samples, &keys, (geo.inv_rel2, geo.inv_n2), (w, h))
    });
    // Rows with a pixel to filter (a pixel without one keeps it zero and is
    // copied through every pass): glass reflections cover few rows.
    let rows: Vec<bool> = part
        .remod
        .par_chunks(w)
        .map(|r| r.iter().any(|&x| x != Vec3::ZERO))
        .collect();
    // Pixels to filter with nothing to filter against (no sample reflected):
    // they take their neighbours' ratio.
    let gather: Vec<bool> = part
        .rho
        .par_iter()
        .zip(part.remod)
        .map(|(&r, &m)| r == Vec3::ZERO && m != Vec3::ZERO)
        .collect();
    let mut tmp = vec![Est::default(); n];
    let grid = Grid {
        w,
        h,
        rows: &rows,
        gather: &gather,
        keys: &keys,
        geo: &geo,
        regions: regions.as_deref(),
        sigma_lum: part.sigma_lum,
    };
    for level in 0..levels {
        let step = 1usize << level;
        pass(&cur, &mut tmp, &sd, &grid, step, (1, 0));
        pass(&tmp, &mut cur, &sd, &grid, step, (0, 1));
        // Later levels stop at the filtered estimate's own (smaller) noise.
        cur.par_iter()
            .map(|e| e.var.max(0.0).sqrt())
            .collect_into_vec(&mut sd);
    }
    film.rgb.par_iter_mut().enumerate().for_each(|(k, px)| {
        let (s, remod) = (cur[k], part.remod[k]);
        if remod == Vec3::ZERO {
            return;
        }
        for c in 0..3 {
            // Below this the ratio is noise over nothing.
            if s.rho[c] > 1e-7 {
                px[c] += remod[c] * (s.l[c] / s.rho[c]) - part.traced[k][c];
            }
        }
    });
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
            // Only a pixel to filter reads its σ.
            if cur[k].rho == Vec3::ZERO {
                return 0.0;
            }
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

/// The variance the luminance test of two pixels allows for (of their
/// values' difference, before the width `sigma_lum`), from their variances
/// and regions. Within one region (their medians agree within the smaller
/// of the medians' noise) it is the sum of the two: under "same light"
/// e_c − e_q has that variance, and a test symmetric in the pair lets a
/// bright outlier and its dark neighbour see each other alike, so a
/// firefly's light is moved, not lost. Between regions it is twice the
/// smallest of the two variances and the two regions' pixel variances: a
/// dark region's pixel stops at its own region's noise, however noisy its
/// bright neighbour (a lamp-lit surface's edge does not bleed), even on the
/// edge, where its prefiltered variance took in the bright side's.
/// Between the two, blended by the medians' agreement.
#[inline]
fn pair_var(var_c: f32, var_q: f32, rc: Region, rq: Region) -> f32 {
    let dm = rc.level - rq.level;
    let apart = dm * dm
        / (REGION_SIGMA * REGION_SIGMA * 2.0 * rc.var.min(rq.var)
            + (REL_FLOOR * rc.level.max(rq.level)).powi(2)
            + 1e-20);
    let same = soft_gaussian(apart);
    let least = var_c.min(var_q).min(rc.pixel_var).min(rq.pixel_var);
    same * (var_c + var_q) + (1.0 - same) * 2.0 * least
}

/// The B3-spline taps at offsets −2..=2 (see `atrous.rs`).
const B3: [f32; 5] = [1.0 / 16.0, 0.25, 0.375, 0.25, 1.0 / 16.0];

/// A pixel's demodulated luminance and its rho's luminance, computed once
/// per pass instead of once per tap (`Est::ratio`).
#[derive(Clone, Copy, Debug, Default)]
struct Lum {
    /// luminance(l) / `r`; 0 without a ratio.
    e: f32,
    /// luminance(rho) when > 0, else 0 (no ratio).
    r: f32,
}

impl Lum {
    #[inline]
    fn of(est: &Est) -> Lum {
        let r = luminance(est.rho);
        if r > 0.0 {
            Lum {
                e: luminance(est.l) / r,
                r,
            }
        } else {
            // No ratio (NaN included): `r` 0 marks it.
            Lum::default()
        }
    }
}

/// What every pass of one component shares: the image size, which rows
/// hold a pixel to filter, the guide keys and range widths.
#[derive(Clone, Copy)]
struct Grid<'a> {
    w: usize,
    h: usize,
    rows: &'a [bool],
    /// Pixels with nothing to filter against that take their neighbours'
    /// ratio (`Part::remod` but no `Part::rho`).
    gather: &'a [bool],
    keys: &'a [SurfKey],
    geo: &'a Geo,
    /// Each pixel's region (`regions.rs`), from the unfiltered estimates;
    /// `None`: the test is symmetric everywhere.
    regions: Option<&'a [Region]>,
    /// `Part::sigma_lum`.
    sigma_lum: f32,
}

/// One edge-stopping à-trous pass along `(di, dj)` with dilation `step`:
/// weights B3 × geometry × luminance; l and rho as weighted means, the
/// variance of the ratio through the squared rho-weighted weights. Rows
/// without a pixel to filter are copied.
fn pass(
    data: &[Est],
    out: &mut [Est],
    sd: &[f32],
    grid: &Grid<'_>,
    step: usize,
    (di, dj): (isize, isize),
) {
    let Grid {
        w,
        h,
        rows,
        gather,
        keys,
        geo,
        regions,
        sigma_lum,
    } = *grid;
    // Zero (no ratio) outside the active rows, whose pixels have no rho.
    let mut lum = vec![Lum::default(); data.len()];
    lum.par_chunks_mut(w).enumerate().for_each(|(j, lr)| {
        if rows[j] {
            for (x, est) in lr.iter_mut().zip(&data[j * w..(j + 1) * w]) {
                *x = Lum::of(est);
            }
        }
    });
    out.par_chunks_mut(w).enumerate().for_each(|(j, row)| {
        if !rows[j] {
            row.copy_from_slice(&data[j * w..(j + 1) * w]);
            return;
        }
        for (i, o) in row.iter_mut().enumerate() {
            let c = j * w + i;
            let centre = data[c];
            let Lum { e: e_c, r: r_c } = lum[c];
            // Without a ratio of its own, a pixel to filter gathers its
            // neighbours' on geometry alone.
            let own = r_c != 0.0;
            if !own && !gather[c] {
                *o = centre;
                continue;
            }
            let var_c = sd[c] * sd[c];
            let key_c = keys[c];
            let (mut l, mut rho, mut wsum) = (Vec3::ZERO, Vec3::ZERO, 0.0f32);
            let (mut var, mut asum) = (0.0f32, 0.0f32);
            for (t, &b3) in B3.iter().enumerate() {
                let d = (t as isize - 2) * step as isize;
                let (ii, jj) = (i as isize + d * di, j as isize + d * dj);
                if ii < 0 || jj < 0 || ii >= w as isize || jj >= h as isize {
                    continue;
                }
                let q = jj as usize * w + ii as usize;
                let Lum { e: e_q, r: r_q } = lum[q];
                if r_q == 0.0 {
                    continue;
                }
                let Some(g) = key_c.geo_energy(keys[q], geo.inv_rel2, geo.inv_n2) else {
                    continue;
                };
                let nb = &data[q];
                let stop = if own {
                    let de = e_c - e_q;
                    let sigma2 = sigma_lum
                        * sigma_lum
                        * match regions {
                            Some(r) => pair_var(var_c, sd[q] * sd[q], r[c], r[q]),
                            None => var_c + sd[q] * sd[q],
                        }
                        + (REL_FLOOR * e_c.max(e_q)).powi(2)
                        + 1e-20;
                    de * de / sigma2
                } else {
                    0.0
                };
                let wt = b3 * soft_gaussian(g + stop);
                l += nb.l * wt;
                rho += nb.rho * wt;
                wsum += wt;
                let a = wt * r_q;
                var += a * a * nb.var;
                asum += a;
            }
            // The centre tap counts (weight 3/8) when it has a ratio; a
            // gathering pixel without neighbours keeps its nothing.
            if wsum == 0.0 {
                *o = centre;
                continue;
            }
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
