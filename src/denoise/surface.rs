//! The second denoiser component: indirect light on the first surface
//! (`ViewInputs::l_surf`: all a Lambertian x1 reflects beyond its own
//! next-event estimates; with a medium, fog light included).
//! Its mean is rho·E with rho = throughput × albedo at x1 (texture included)
//! and E the indirect irradiance / π, smooth over a surface; per pixel
//! Ẽ = Σw·l_surf / Σw·rho per channel and pixel = L − l_surf + rho·Ẽ,
//! so texture and the first segment's Tr stay exact per pixel. Range
//! weights: relative depth_z, the pixel-centre normal, never sky. In
//! medium-free scenes x1 may also be the surface x1's glass and mirrors
//! show; pixels mix only with pixels whose share of the latter is alike
//! (`ViewInputs::behind_delta`). Renders filter it with `edge_stop.rs`'s
//! kernel, which also stops at the light's own noise, so corners and
//! recesses keep their shade (`Widths::surface_sigma_lum`; `None`: on
//! geometry alone). There rho also carries each pixel's bounce openness
//! (`ViewInputs::openness`, how freely its bounce rays leave): a window's
//! reveal, the shade under a balcony or a car is darker because its
//! bounces meet the walls around it, which neither the albedo nor the
//! noise-level test sees, so the ratio divides by it and pixels of unlike
//! openness stay apart. Fireflies (`FIREFLY_RATIO`) are left out of
//! the sums and take their neighbours' estimate.

use std::ops::{Add, Div, Mul};

use glam::Vec3;
use rayon::prelude::*;

use super::atrous::{atrous_levels, atrous_pass, ln_depth, soft_gaussian, Axis};
use super::conserve;
use super::direct::DIRECT_LEVELS;
use super::edge_stop::{filter_part, Part};
use super::{DepthGuide, ViewInputs, Widths};
use crate::film::Film;

/// Range σ on |Δn| between unit pixel-centre normals (about 17° at 1σ).
pub(super) const SIGMA_NORMAL: f32 = 0.3;

/// 1/σ² on the step in `ViewInputs::behind_delta` (σ = 0.15): a window's
/// pixels, lit through glass, and the wall around it, at the same depth,
/// stay apart.
const INV_BEHIND2: f32 = 1.0 / (0.15 * 0.15);

/// A pixel whose filtered light per unit albedo exceeds this multiple of
/// the median over its neighbourhood is a firefly: a rare path to a bright
/// source, mostly the sun reflected by a window or metal onto a shadowed
/// surface. Spread by the kernel it would become a bright blob, kept it is a
/// white speck, so it is left out of every neighbour's sum and takes their
/// estimate. The light it carried is dropped: in the street at 16 spp about
/// 0.35 % of the image's mean luminance.
const FIREFLY_RATIO: f32 = 6.0;
/// The share of a pixel's indirect light taken to reach it whatever its
/// bounce's openness (`ViewInputs::openness`): a hemmed-in surface still
/// gets light from the walls that hem it in.
const OPEN_FLOOR: f32 = 0.25;

/// 1/σ² on the step in `ViewInputs::openness` (σ = 0.25, about two
/// standard deviations of a 16-sample pixel's mean): a window's reveal and
/// the wall around it stay apart.
const INV_OPEN2: f32 = 1.0 / (0.25 * 0.25);

/// Half-width in pixels of the firefly test's square neighbourhood.
const FIREFLY_RADIUS: usize = 2;

/// Replaces `l_surf` in `film` by its filtered estimate (for a firefly,
/// its neighbours'), then gives back over wide windows the light the
/// filter dropped (`conserve.rs`); pixels with no rho in their
/// neighbourhood (per channel) keep their radiance.
pub(super) fn filter_surface(
    film: &mut Film,
    fog: &ViewInputs,
    guide: &DepthGuide<'_>,
    filter: &Widths,
) {
    let n = film.width * film.height;
    assert!(
        fog.l_surf.len() == n && fog.rho.len() == n,
        "surface inputs' size does not match the film"
    );
    if fog.rho.iter().all(|&r| r == Vec3::ZERO) {
        return;
    }
    let before = film.rgb.clone();
    filter_surface_light(film, fog, guide, filter);
    // What the film now holds of the light on the surface.
    let filtered: Vec<Vec3> = (film.rgb.par_iter().zip(&before).zip(&fog.l_surf))
        .map(|((&after, &before), &traced)| after - before + traced)
        .collect();
    let radius = conserve::window_radius(film.width);
    conserve::restore(&mut film.rgb, &filtered, &fog.l_surf, film.width, radius);
}

/// [`filter_surface`]'s filter alone.
fn filter_surface_light(
    film: &mut Film,
    fog: &ViewInputs,
    guide: &DepthGuide<'_>,
    filter: &Widths,
) {
    let (w, h) = (film.width, film.height);
    let n = w * h;
    let firefly = fireflies(&fog.l_surf, &fog.rho, (w, h));
    if let Some(sigma_lum) = filter.surface_sigma_lum {
        edge_stopped(film, fog, &firefly, guide, filter, sigma_lum);
        return;
    }
    let normal = |k: usize| guide.normal.get(k).copied().unwrap_or(Vec3::ZERO);
    let keys: Vec<SurfKey> = (0..n)
        .into_par_iter()
        .map(|k| SurfKey::new(guide.depth_z[k], normal(k), fog.behind_delta[k]))
        .collect();
    // A firefly's pair is zero: it adds to neither sum of a neighbour's
    // ratio (the weights cancel in the ratio).
    let mut cur: Vec<Pair> = fog
        .l_surf
        .par_iter()
        .zip(&fog.rho)
        .zip(&firefly)
        .map(|((&l, &rho), &f)| if f { Pair::default() } else { Pair { l, rho } })
        .collect();
    let mut tmp = vec![Pair::default(); n];
    let inv_rel2 = 1.0 / filter.sigma_depth_rel.max(1e-6).powi(2);
    let inv_n2 = 1.0 / (SIGMA_NORMAL * SIGMA_NORMAL);
    let weight = |a: SurfKey, b: SurfKey| a.weight(b, inv_rel2, inv_n2);
    for level in 0..atrous_levels(filter.sigma_px) {
        let step = 1usize << level;
        atrous_pass(&cur, &mut tmp, &keys, (w, h), step, &weight, Axis::Row);
        atrous_pass(&tmp, &mut cur, &keys, (w, h), step, &weight, Axis::Column);
    }
    film.rgb.par_iter_mut().enumerate().for_each(|(k, px)| {
        let (s, rho) = (cur[k], fog.rho[k]);
        if rho == Vec3::ZERO {
            return;
        }
        for c in 0..3 {
            // Below this the ratio is noise over nothing.
            if s.rho[c] > 1e-7 {
                px[c] += rho[c] * (s.l[c] / s.rho[c]) - fog.l_surf[k][c];
            }
        }
    });
}

/// [`filter_surface`] with `edge_stop.rs`'s kernel: edge-stopping on the
/// light's own noise (`ViewInputs::var_surf`) at `sigma_lum` standard
/// deviations. A firefly is left out of the sums as on geometry alone.
fn edge_stopped(
    film: &mut Film,
    inputs: &ViewInputs,
    firefly: &[bool],
    guide: &DepthGuide<'_>,
    widths: &Widths,
    sigma_lum: f32,
) {
    let kept = |v: &[Vec3]| -> Vec<Vec3> {
        v.par_iter()
            .zip(firefly)
            .map(|(&x, &f)| if f { Vec3::ZERO } else { x })
            .collect()
    };
    // The light is taken as the albedo times the bounce's openness times
    // a light smooth over the surface.
    let rho_open: Vec<Vec3> = (inputs.rho.par_iter().zip(&inputs.openness))
        .map(|(&rho, &open)| rho * (OPEN_FLOOR + (1.0 - OPEN_FLOOR) * open))
        .collect();
    let (l, rho) = (kept(&inputs.l_surf), kept(&rho_open));
    let part = Part {
        l: &l,
        rho: &rho,
        var: &inputs.var_surf,
        remod: &rho_open,
        traced: &inputs.l_surf,
        sigma_lum,
        between_regions: false,
        openness: Some(&inputs.openness),
    };
    filter_part(film, &part, inputs, guide, widths, DIRECT_LEVELS);
}

/// Per pixel (row-major), whether its light per unit albedo, summed over
/// channels, exceeds `FIREFLY_RATIO` times the median of that ratio over
/// the pixels within `FIREFLY_RADIUS` that have a rho (itself included),
/// and at least that multiple of the median over those of them with light.
fn fireflies(l: &[Vec3], rho: &[Vec3], (w, h): (usize, usize)) -> Vec<bool> {
    let ratio: Vec<Option<f32>> = l
        .par_iter()
        .zip(rho)
        .map(|(l, r)| (r.element_sum() > 0.0).then(|| l.element_sum() / r.element_sum()))
        .collect();
    (0..w * h)
        .into_par_iter()
        .map(|k| {
            let Some(e) = ratio[k].filter(|&e| e > 0.0) else {
                return false;
            };
            let (i, j) = (k % w, k / w);
            // e > FIREFLY_RATIO × the window's median (its element `mid`
            // in order) exactly when more than `mid` of its values v have
            // FIREFLY_RATIO · v < e (v ↦ FIREFLY_RATIO · v is monotone):
            // a count, no sort.
            // Also against the median of the lit others alone: where most
            // neighbours saw none of a sparse light (a dark room behind a
            // window) the median is zero, and the lit ones are its level.
            let (mut len, mut below, mut lit, mut lit_below) = (0usize, 0usize, 0usize, 0usize);
            for jj in j.saturating_sub(FIREFLY_RADIUS)..(j + FIREFLY_RADIUS + 1).min(h) {
                let row = &ratio[jj * w..(jj + 1) * w];
                let cols = i.saturating_sub(FIREFLY_RADIUS)..(i + FIREFLY_RADIUS + 1).min(w);
                for v in row[cols].iter().flatten() {
                    len += 1;
                    let dim = FIREFLY_RATIO * v < e;
                    below += dim as usize;
                    if *v > 0.0 {
                        lit += 1;
                        lit_below += dim as usize;
                    }
                }
            }
            // `lit` counts the pixel itself, never below itself.
            below > len / 2 && lit_below >= lit / 2
        })
        .collect()
}

/// The filtered pair: light on the surface and its rho.
#[derive(Clone, Copy, Debug, Default)]
struct Pair {
    l: Vec3,
    rho: Vec3,
}

impl Add for Pair {
    type Output = Pair;
    fn add(self, o: Pair) -> Pair {
        Pair {
            l: self.l + o.l,
            rho: self.rho + o.rho,
        }
    }
}

impl Mul<f32> for Pair {
    type Output = Pair;
    fn mul(self, s: f32) -> Pair {
        Pair {
            l: self.l * s,
            rho: self.rho * s,
        }
    }
}

impl Div<f32> for Pair {
    type Output = Pair;
    fn div(self, s: f32) -> Pair {
        Pair {
            l: self.l / s,
            rho: self.rho / s,
        }
    }
}

/// A pixel's guide values for the surface component.
#[derive(Clone, Copy, Debug)]
pub(super) struct SurfKey {
    /// ln depth_z, +inf for sky.
    ln_z: f32,
    /// Unit normal, zero when unknown.
    n: Vec3,
    /// Share of samples split behind delta scatters (`ViewInputs::behind_delta`).
    behind: f32,
    /// Share of samples split at a glossy vertex (`ViewInputs::glossy`;
    /// zero for the indirect light, which has none).
    glossy: f32,
    /// The first surface's bounce openness (`ViewInputs::openness`; zero
    /// where it is not a key).
    open: f32,
}

impl SurfKey {
    pub(super) fn new(z: f32, n: Vec3, behind: f32) -> SurfKey {
        SurfKey {
            ln_z: ln_depth(z),
            n: if n.is_finite() { n } else { Vec3::ZERO },
            behind,
            glossy: 0.0,
            open: 0.0,
        }
    }

    /// The key with bounce openness `open`: pixels whose openness differs
    /// are kept apart.
    pub(super) fn with_openness(self, open: f32) -> SurfKey {
        SurfKey { open, ..self }
    }

    /// The key with glossy share `glossy`: pixels whose shares differ are
    /// kept apart as `behind` ones are.
    pub(super) fn with_glossy(self, glossy: f32) -> SurfKey {
        SurfKey { glossy, ..self }
    }

    /// Weight of neighbour `b`, in [0, 1]: zero between sky and surface,
    /// Gaussian-like in relative depth and (both known) the normal step.
    #[inline]
    pub(super) fn weight(self, b: SurfKey, inv_rel2: f32, inv_n2: f32) -> f32 {
        self.geo_energy(b, inv_rel2, inv_n2)
            .map_or(0.0, soft_gaussian)
    }

    /// The exponent of [`SurfKey::weight`] (squared steps over squared
    /// widths, summed), `None` between sky and surface.
    #[inline]
    pub(super) fn geo_energy(self, b: SurfKey, inv_rel2: f32, inv_n2: f32) -> Option<f32> {
        let sky = self.ln_z.is_infinite();
        if sky != b.ln_z.is_infinite() {
            return None;
        }
        if sky {
            return Some(0.0);
        }
        let rel = self.ln_z - b.ln_z;
        let behind = self.behind - b.behind;
        let glossy = self.glossy - b.glossy;
        let open = self.open - b.open;
        let mut e = rel * rel * inv_rel2
            + (behind * behind + glossy * glossy) * INV_BEHIND2
            + open * open * INV_OPEN2;
        if self.n != Vec3::ZERO && b.n != Vec3::ZERO {
            e += (self.n - b.n).length_squared() * inv_n2;
        }
        Some(e)
    }
}
