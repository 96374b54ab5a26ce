//! Next-event estimation at a surface vertex: each distant light's sample
//! (`direct`), the local lights' resampled one (`direct_local`, `ris.rs`),
//! and the shadow ray each leaves pending with its MIS-weighted
//! contribution. In a medium the distant lights' shadow rays may be
//! rouletted by their transmittance (`ShadowTrRoulette`), known in closed
//! form before the ray.

use glam::Vec3;
use shaders_cpu::sampling::power_heuristic;

use super::ris::{self, RisSamples};
use super::shadows::PendingShadows;
use super::{is_two_sided, receiver_normal, Vertex};
use crate::accel::Accel;
use crate::integrator::PathContext;

/// Russian roulette of a surface vertex's distant-light shadow rays in a
/// medium by their transmittance Tr: light k's ray is traced with
/// probability min(1, `per_tr`·Tr) and its term divided by it. Behind
/// dense fog most of them carry a few per cent of their light (town05
/// frame 40 foggy: the sun's Tr from the street is below 0.1 for nine rays
/// in ten); a kept term brings at most 1/`per_tr` of the light without the
/// medium, no more than a ray with Tr ≥ 1/`per_tr` (always traced) brings.
#[derive(Clone, Copy, Debug)]
pub(in crate::integrator) struct ShadowTrRoulette {
    /// One uniform number per distant light.
    pub u: [f32; crate::light::MAX_DISTANT],
    /// Survival per unit transmittance (> 0).
    pub per_tr: f32,
}

impl ShadowTrRoulette {
    /// The survival probability of light `k`'s shadow ray of
    /// transmittance `tr`, None when dropped.
    pub fn keep(&self, k: usize, tr: f32) -> Option<f32> {
        let keep = (self.per_tr * tr).min(1.0);
        (self.u[k] < keep).then_some(keep)
    }
}

impl<A: Accel> PathContext<'_, A> {
    /// Next-event estimation for a sample of distant light `k`: MIS-weighted,
    /// its shadow ray and contribution `beta · f · li · w / pdf` left in
    /// `pending`. `ls` carries no radiance ([`LightSet::sample_distant_dir`]):
    /// it is evaluated here, after the checks that may reject the sample.
    /// With `rr` (in a medium) the ray is first rouletted by its
    /// transmittance.
    pub(super) fn direct(
        &self,
        vertex: &Vertex,
        (k, rr): (usize, Option<ShadowTrRoulette>),
        ls: Option<crate::light::LightSample>,
        beta: Vec3,
        pending: &mut PendingShadows,
        rays: &mut u64,
    ) {
        let Vertex {
            si,
            bsdf,
            frame,
            wo_local,
            ..
        } = *vertex;
        let Some(mut ls) = ls else {
            return;
        };
        if ls.pdf <= 0.0 {
            return;
        }
        if is_two_sided(bsdf) && ls.wi.dot(si.n_geo) <= 0.0 {
            return;
        }
        let wi_local = frame.to_local(ls.wi);
        // The pdf (for the MIS weight) with f: a relief builds its groove once.
        let (f, bsdf_pdf) = bsdf.eval_pdf(wo_local, wi_local);
        let mut f = f * wi_local.z.abs();
        if f == Vec3::ZERO {
            return;
        }
        // Rouletted before its radiance (the sky's and the cloud deck's are
        // dear) and its ray; a kept term is divided by its survival.
        let mut tr = None;
        if let (Some(rr), Some(m)) = (rr, &self.scene.medium) {
            let t = m.tr(si.p, ls.wi, ls.dist);
            let Some(keep) = rr.keep(k, t) else {
                return;
            };
            f /= keep;
            tr = Some(t);
        }
        ls.li = self.lights.distant_li(self.scene, k, si.p, ls.wi);
        if ls.li == Vec3::ZERO {
            return;
        }
        let coherent = self.lights.distant_is_directional(k);
        self.push_shadow(
            vertex,
            &ls,
            (f, Some(bsdf_pdf)),
            (None, tr),
            coherent,
            beta,
            pending,
            rays,
        );
    }

    /// Next-event estimation of the local lights: one light sample kept by
    /// resampling ([`ris::resample`]) and its shadow ray left in `pending`.
    pub(super) fn direct_local(
        &self,
        vertex: &Vertex,
        u: &RisSamples,
        beta: Vec3,
        pending: &mut PendingShadows,
        rays: &mut u64,
    ) {
        let Vertex {
            si,
            bsdf,
            frame,
            wo_local,
            ..
        } = *vertex;
        let two_sided = is_two_sided(bsdf);
        let f_cos = |wi: Vec3| {
            if two_sided && wi.dot(si.n_geo) <= 0.0 {
                return Vec3::ZERO;
            }
            let wi_local = frame.to_local(wi);
            bsdf.eval(wo_local, wi_local) * wi_local.z.abs()
        };
        let n = receiver_normal(bsdf, si.n_geo);
        let Some(r) = ris::resample(self.lights, self.scene, (si.p, n), u, f_cos) else {
            return;
        };
        self.push_shadow(
            vertex,
            &r.ls,
            (r.f, None),
            (r.inv_pdf, None),
            false,
            beta,
            pending,
            rays,
        );
    }

    /// Leaves the shadow ray of light sample `ls` in `pending` with its
    /// contribution `beta · f · li · w / pdf` (`f` = BSDF × cosine, `w`
    /// the MIS weight against BSDF sampling by `ls.pdf`, with the BSDF's pdf
    /// toward the light when the caller has it); `inv_pdf`, when
    /// given, replaces 1/pdf (resampling's weight); `tr`, the medium's
    /// transmittance along the ray when the caller has it.
    #[allow(clippy::too_many_arguments)]
    fn push_shadow(
        &self,
        vertex: &Vertex,
        ls: &crate::light::LightSample,
        (f, bsdf_pdf): (Vec3, Option<f32>),
        (inv_pdf, tr): (Option<f32>, Option<f32>),
        coherent: bool,
        beta: Vec3,
        pending: &mut PendingShadows,
        rays: &mut u64,
    ) {
        let Vertex {
            si,
            bsdf,
            frame,
            wo_local,
            front,
        } = *vertex;
        let shadow = if ls.dist.is_finite() {
            front.spawn_ray_to(si, si.p + ls.wi * ls.dist)
        } else {
            front.spawn_ray(si, ls.wi)
        };
        *rays += 1;
        let w = if ls.delta {
            1.0
        } else {
            let bsdf_pdf = bsdf_pdf.unwrap_or_else(|| bsdf.pdf(wo_local, frame.to_local(ls.wi)));
            power_heuristic(1.0, ls.pdf, 1.0, bsdf_pdf)
        };
        let li = match (&self.scene.medium, tr) {
            // Shadow rays through a medium carry its transmittance.
            (Some(_), Some(tr)) => ls.li * tr,
            (Some(m), None) => ls.li * m.tr(si.p, ls.wi, ls.dist),
            (None, _) => ls.li,
        };
        // Delta local lights seen from a medium-free surface need no MIS with
        // equiangular sampling (that only covers medium vertices).
        let scale = match inv_pdf {
            Some(inv) => w * inv,
            None => w / ls.pdf,
        };
        pending.push(shadow, beta * (f * li * scale), coherent);
    }
}
