//! Resampled importance sampling (RIS, Talbot et al. 2005) of the local
//! light at a surface vertex: M light samples are drawn from the
//! light BVH as one-sample NEE draws them (source pdf p), each weighed by
//! its unshadowed contribution p̂ = luminance(f·cos·L) (BSDF, the spot's
//! falloff and the emitter's cosine included), and one is kept in
//! proportion to p̂/p; only that one traces a shadow ray. Its estimate is
//! f·cos·L·V / p̂ · (1/M)·Σ p̂ᵢ/pᵢ, unbiased wherever p̂ > 0 covers the
//! integrand (p̂ drops only the visibility). At night each surface point
//! sees dozens of lamps, windows and head-lights the tree cannot tell
//! apart (a lamp behind a wall, a spot facing away, a light under the
//! surface's horizon): candidates the BSDF or the profile zero out never
//! cost a shadow ray, and the kept one is nearly proportional to its light.
//!
//! The candidates' selection numbers are stratified: candidate k's lies in
//! [k/M, (k+1)/M), so a light the tree gives a pmf of at least 1/M is
//! always among them and the M candidates spread over the lamps as the
//! tree weighs them instead of crowding by chance onto a few. The
//! estimate stays unbiased: the candidates' marginal densities sum to M·p
//! (each slice of the selection's number is covered once), so with the
//! balance heuristic over the slices each candidate's resampling weight is
//! still p̂/(M·p).
//!
//! MIS with BSDF sampling stays the one-sample partition: the kept sample's
//! integrand carries w = p²/(p² + p_bsdf²) with the one-candidate pdf p,
//! the weight a BSDF ray that hits the emitter gets against it
//! (`LightSet::pdf_triangle`), so the two still sum to one.

use glam::{Vec2, Vec3};
use shaders_cpu::sampling::luminance;

use crate::light::{LightSample, LightSet};
use crate::sampler::SampleStream;
use crate::scene::Scene;

/// Most candidates per vertex (the light set says how many it uses:
/// `LightSet::local_candidates`).
const CANDIDATES: usize = crate::light::LOCAL_CANDIDATES;

/// First 4D set of the candidates beyond the first (one set each per
/// bounce; far from the surface and volume dimensions).
const RIS_DIMS: u32 = 1 << 19;

/// Every random number the resampling of one vertex uses: per candidate
/// (light choice, light u, light v, spare); the first candidate's spare is
/// the choice among the candidates.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct RisSamples {
    u: [[f32; 4]; CANDIDATES],
    /// Candidates used (1 ..= `CANDIDATES`).
    m: usize,
    /// Scattering events of the path before the vertex
    /// (`LightSet::p_local_at`).
    bounce: u32,
}

impl RisSamples {
    /// The samples of scattering event `bounces` for `m` candidates:
    /// `first` is the bounce's local-light set (the one-sample draw), the
    /// rest from their own fixed dimensions, offset by `dim_base`
    /// (`PathState::dim_base`).
    pub fn draw(
        stream: &mut SampleStream,
        (bounces, dim_base): (u32, u32),
        first: [f32; 4],
        m: usize,
    ) -> Self {
        let mut u = [first; CANDIDATES];
        stream.set_dimension(dim_base + RIS_DIMS + bounces * CANDIDATES as u32);
        for c in u.iter_mut().take(m).skip(1) {
            *c = stream.next_4d();
        }
        RisSamples {
            u,
            m,
            bounce: bounces,
        }
    }
}

/// The light sample RIS kept, with what its estimate needs.
#[derive(Clone, Copy, Debug)]
pub(super) struct Resampled {
    /// The sample (`pdf` its one-candidate pdf, for the MIS weight).
    pub ls: LightSample,
    /// BSDF × cosine toward it, evaluated once for the target.
    pub f: Vec3,
    /// Replaces 1/pdf in the estimate: (1/M)·Σ p̂ᵢ/pᵢ / p̂(kept); None
    /// with one candidate (then it is 1/pdf, left to the caller's division).
    pub inv_pdf: Option<f32>,
}

/// Resamples one of `u`'s candidate local-light samples seen from `p`
/// (receiver normal `n` for the light tree, `LightSet::select_at`);
/// `f_cos(wi)` is the vertex's BSDF × |cos| toward `wi` (zero where the
/// surface cannot receive it). None when every candidate's target is zero.
pub(super) fn resample(
    lights: &LightSet,
    scene: &Scene,
    (p, n): (Vec3, Vec3),
    u: &RisSamples,
    f_cos: impl Fn(Vec3) -> Vec3,
) -> Option<Resampled> {
    let mut kept: Option<(LightSample, Vec3, f32)> = None;
    let mut w_sum = 0.0f32;
    // Weighted reservoir over the candidates in order: candidate i replaces
    // the kept one with probability wᵢ/Σ_{j≤i} w_j, decided by one number
    // rescaled after each decision so it stays uniform.
    let mut u_pick = u.u[0][3];
    // Every candidate's light chosen first, in one walk of the light tree.
    // Stratified: candidate k's number lies in the k-th of m equal slices
    // of [0, 1) (module docs).
    let u_select: [Option<f32>; CANDIDATES] = std::array::from_fn(|k| {
        (k < u.m).then(|| match u.m {
            1 => u.u[0][0],
            m => ((k as f32 + u.u[k][0]) / m as f32).min(1.0 - f32::EPSILON),
        })
    });
    let chosen = lights.select_many((p, n), u_select, u.bounce);
    for (c, chosen) in u.u[..u.m].iter().zip(chosen) {
        let Some(ls) =
            chosen.and_then(|ch| lights.sample_picked(scene, ch, p, Vec2::new(c[1], c[2])))
        else {
            continue;
        };
        if ls.pdf <= 0.0 || ls.li == Vec3::ZERO {
            continue;
        }
        let f = f_cos(ls.wi);
        let target = luminance(f * ls.li);
        if target.is_nan() || target <= 0.0 {
            continue;
        }
        let w = target / ls.pdf;
        if !w.is_finite() {
            continue;
        }
        w_sum += w;
        let p_take = w / w_sum;
        if u_pick < p_take {
            kept = Some((ls, f, target));
            u_pick /= p_take;
        } else {
            u_pick = (u_pick - p_take) / (1.0 - p_take);
        }
        u_pick = u_pick.min(1.0 - f32::EPSILON);
    }
    let (ls, f, target) = kept?;
    Some(Resampled {
        ls,
        f,
        inv_pdf: (u.m > 1).then(|| w_sum / (u.m as f32 * target)),
    })
}

#[cfg(test)]
mod tests;
