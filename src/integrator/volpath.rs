//! Volumetric path tracing (pbrt-v4 `VolPathIntegrator`, §14.2, without null
//! collisions: our media have closed-form transmittance). Per segment:
//! free-flight sampling of the medium up to the segment end; a collision
//! weights the path by the albedo (σ_s·Tr / (σ_t·Tr)) and continues by phase
//! sampling. In-scattering is estimated on every segment, collided or not:
//! NEE (shadow rays carry transmittance, MIS against phase sampling) at one
//! point drawn ∝ σ_t·Tr on the segment, weighted by (1 − Tr)·albedo — the
//! same point free flight collides at when it collides, so the forward-lobe
//! sun glow no longer hangs on the binary collide-or-pass choice (about 20 %
//! lower RMSE in the foggy street at 16 spp). Point and spot lights are also
//! reached by equiangular sampling along each segment (Kulla & Fajardo
//! 2012), combined with the in-scattering points by the power heuristic over
//! the distance densities. A purely absorbing medium multiplies by Tr
//! instead of sampling (its expected value). After each medium collision a
//! second direction is drawn from the phase lobe around the sun and its
//! segment's sun NEE added, power-heuristic MIS against the phase-sampled
//! continuation's sun NEE (`SunLobe`): the forward lobe made that term a
//! rare spike (fireflies; in the foggy street RMSE 0.80 → 0.61 × mean at
//! 16 spp for about 25 % more time, about 15 % lower at equal time).
//! Roulette at medium vertices goes by the albedo only (analog absorption),
//! not by the throughput, so paths a surface dimmed are not boosted where
//! fog carries them to the sky.
//! Collisions estimate the sky's NEE, and those after the first draw the
//! sun lobe, each half the time (divided by 1/2: `Strategies::sky_nee_deep`,
//! `Strategies::lobe_deep`): about 16 % fewer rays in fog. The local
//! lights' in-scattering (NEE and equiangular) is rouletted too where they
//! bring little (`Strategies::local_per_opacity`, `local_nee_deep`), and in
//! thin haze the camera segment's sun shadow rays by its opacity
//! (`Strategies::sun_per_opacity`). The first two distant lights' shadow rays are
//! rouletted by their phase value and then by their transmittance
//! (`Strategies::shadow_per_phase`, `Strategies::shadow_per_tr`), before
//! the ray. A deep roulette
//! with a bounded boost (`Strategies::deep_survival`,
//! `Strategies::deep_max_boost`) is off by default.
//!
//! Sample dimensions of a segment start at `VOL_DIMS` + 16·bounce (the sun
//! lobe's at `LOBE_DIMS` + 2·bounce), apart from the surface dimensions, so
//! surface vertices see the streams they see without a medium. Rain is not
//! traced here: its streaks are composited per pixel (`rain.rs`).
//! The result is split by the camera ray's first event (`DenoiseSample`):
//! what the first segment's in-scattering and a collision on it bring is
//! `l_fog`, denoised in image space (`crate::denoise`); renders that filter
//! also split that first segment (`Strategies::split_first`) and split the
//! light of a first surface vertex x1 as medium-free scenes do: at a
//! Lambertian x1 its next-event estimates of sky and lamps (direct light)
//! and all that follows them (indirect light: fog light and light by way
//! of other surfaces, `surface_split.rs`); at a glossy x1 (paint, rough
//! metal) all the light the path gathers from x1 on, handed over as direct
//! light. The suns' next-event estimates stay as traced.
//! One segment's medium events are `segment.rs`.

use glam::{Vec2, Vec3};
use shaders_cpu::medium::{Equiangular, Medium};
use shaders_cpu::sampling::power_heuristic;

use super::denoise_parts;
use super::path::{LiSample, PathState, RayCone, ShadowTrRoulette};
use super::PathContext;
use crate::accel::{Accel, Hit, Ray};
use crate::light::LightSample;
use crate::sampler::SampleStream;
use surface_split::SurfaceSplit;

/// First 4D set of the volume dimensions (far above every surface dimension).
const VOL_DIMS: u32 = 1 << 20;
/// 4D sets per segment (five used; the spacing keeps the streams as they were).
const VOL_DIMS_PER_BOUNCE: u32 = 16;
/// The 4D set, among a bounce's volume sets, of the surface vertex's
/// shadow-ray roulette by transmittance (`Strategies::surface_per_tr`);
/// no segment draws it.
const SURFACE_TR_SET: u32 = 7;

mod segment;
mod strategies;
mod surface_split;
#[cfg(test)]
pub(super) mod tests;

use segment::{SegmentEnd, SegmentSamples, VolState, SPLIT_SET};
use strategies::{NeeRoulette, Strategies};

/// Collisions up to this many scattering events always draw the sun lobe
/// (`Strategies::lobe_deep` after).
const LOBE_ALWAYS: u32 = 1;

/// Collisions leaving a path with more scattering events than this pass
/// the deep roulette (`Strategies::deep_survival`).
const DEEP_FROM: u32 = 1;

/// First 4D set of the sun-lobe dimensions (two sets per bounce, above
/// every segment's volume dimensions).
const LOBE_DIMS: u32 = VOL_DIMS + (1 << 18);

/// Shadow ray from a medium point `p` along a light sample.
fn shadow_ray(p: Vec3, ls: &LightSample) -> Ray {
    if ls.dist.is_finite() {
        Ray::segment(p, ls.wi * ls.dist, 1.0 - 1e-4)
    } else {
        Ray::new(p, ls.wi)
    }
}

impl<A: Accel> PathContext<'_, A> {
    /// Radiance along `ray` in a scene with a medium.
    pub(super) fn li_volume(
        &self,
        ray: Ray,
        first_hit: Option<Hit>,
        cone: RayCone,
        stream: &mut SampleStream,
        rays: &mut u64,
    ) -> LiSample {
        let mut strategies = Strategies {
            split_first: self.scene.filter_inscatter,
            cone,
            ..Strategies::default()
        };
        // Where the local lights bring a large share of the light (night;
        // the light set then resamples them), their in-scattering is the
        // fog's light: always estimated.
        if self.lights.local_candidates() > 1 {
            strategies.local_per_opacity = f32::INFINITY;
            strategies.local_nee_deep = 1.0;
        }
        self.trace(ray, first_hit, stream, rays, strategies, None)
    }

    /// The volumetric path loop with the medium-vertex strategies chosen by
    /// `strategies` (renders use [`PathContext::li_volume`]'s). With
    /// `surface_beta` it is the surface part of a split camera ray
    /// (`Strategies::split_first`): the first segment's medium is skipped and
    /// the path starts at that throughput.
    fn trace(
        &self,
        ray: Ray,
        first_hit: Option<Hit>,
        stream: &mut SampleStream,
        rays: &mut u64,
        strategies: Strategies,
        surface_beta: Option<Vec3>,
    ) -> LiSample {
        let mut ray = ray;
        let mut known_hit = Some(first_hit);
        let scene = self.scene;
        let medium = scene.medium.as_ref();
        let sun_lobe = medium
            .filter(|m| strategies.sun_lobe && m.scatters())
            .and(self.sun_lobe);
        let st = PathState {
            cone: strategies.cone,
            ..PathState::new(ray.o)
        };
        let mut vs = VolState::new(st, strategies, sun_lobe);
        if let Some(beta) = surface_beta {
            vs.st.beta = beta;
        }
        loop {
            let first_segment = vs.st.bounces == 0;
            *rays += 1;
            let hit = match known_hit.take() {
                Some(hit) => hit,
                None => self.accel.intersect(&ray),
            };
            if vs.first.surface.is_split() && vs.first.openness.is_none() {
                // This ray is x1's bounce (a medium scatter on it is fog
                // light, not a wall).
                let distance = hit.as_ref().map(|h| h.t * ray.d.length());
                vs.first.openness = Some(denoise_parts::openness(distance));
            }
            let skip_medium = first_segment && surface_beta.is_some();
            if let Some(m) = medium.filter(|_| !skip_medium) {
                let u = SegmentSamples::draw(stream, vs.st.bounces);
                let seg = (&ray, hit, &u);
                match self.medium_segment(m, seg, &mut vs, stream, rays) {
                    SegmentEnd::Passed => {}
                    SegmentEnd::Scattered(next) => {
                        // Glass met after a medium scatter is not seen
                        // from the camera: its reflection is fog light.
                        vs.st.split.ahead = false;
                        ray = next;
                        continue;
                    }
                    SegmentEnd::Ended => break,
                }
            }
            if first_segment {
                vs.first.l_fog_passed = Some(vs.st.l);
            }
            let st = &mut vs.st;
            let Some(hit) = hit else {
                st.l += st.beta
                    * self
                        .lights
                        .escaped_at(scene, ray.o, ray.d, st.prev_pdf, st.prev_delta);
                break;
            };
            vs.lobe_wo = None;
            // The split vertex: x1, or behind x1's glass and mirrors (a
            // room through a window) while no medium scatter or glass
            // reflection came between; its albedo as its shading finds
            // it (the record is read and textured once).
            let split = (st.split.ahead && strategies.split_first && st.bounces < self.max_depth)
                .then_some((st.beta, st.bounces > 0));
            let l_at_x1 = st.l;
            let tr_roulette =
                (strategies.surface_per_tr.is_finite() && st.bounces < self.max_depth).then(|| {
                    stream.set_dimension(
                        VOL_DIMS + st.bounces * VOL_DIMS_PER_BOUNCE + SURFACE_TR_SET,
                    );
                    ShadowTrRoulette {
                        u: stream.next_4d(),
                        per_tr: strategies.surface_per_tr,
                    }
                });
            let (next, sun, before) =
                self.surface_vertex(&ray, &hit, st, stream, rays, tr_roulette);
            // Shaded, it is no longer ahead (a glass reflection ends the
            // search too, with no albedo).
            if let Some((beta, behind_delta)) = split.filter(|_| !st.split.ahead) {
                vs.first.behind_delta =
                    behind_delta && (st.split_albedo.is_some() || st.split_glossy.is_some());
                if let Some(albedo) = st.split_albedo {
                    vs.first.surface =
                        SurfaceSplit::at_first_vertex(albedo * beta, before, sun, st.l);
                }
                // A glossy split vertex (paint): everything it reflects,
                // fog light included, is filtered as direct light
                // (`l_direct`), but the suns' next-event estimate, left as
                // traced as in a clear scene (`path::split_direct`).
                vs.first.glossy = st.split_glossy.map(|a| (l_at_x1 + sun, a * beta));
                // A Lambertian x1's indirect light under its roulette
                // (`Strategies::x1_indirect_keep`): dropped, it is zero.
                let q = strategies.x1_indirect_keep(beta);
                if st.split_albedo.is_some() && next.is_some() && q < 1.0 {
                    stream.set_dimension(VOL_DIMS + SPLIT_SET);
                    if stream.next_4d()[1] >= q {
                        break;
                    }
                    st.beta /= q;
                }
            }
            match next {
                Some(next) => ray = next,
                None => break,
            }
        }
        vs.finish()
    }

    /// NEE from an in-scattering point `p` (ray parameter `t`, drawn with
    /// density `pdf_in` per metre): every distant light plus one selected local light,
    /// MIS against phase sampling, or against equiangular sampling for delta
    /// local lights.
    #[allow(clippy::too_many_arguments)]
    fn medium_nee(
        &self,
        m: &Medium,
        ray: &Ray,
        t_end: f32,
        t: f32,
        pdf_in: f32,
        p: Vec3,
        wo: Vec3,
        (u_sel, u_l): (f32, Option<Vec2>),
        u_distant: &[Vec2; 4],
        lobe_w: Option<(usize, f32)>,
        (rr, bounce): (NeeRoulette, u32),
        rays: &mut u64,
    ) -> Vec3 {
        let scene = self.scene;
        let mut l = Vec3::ZERO;
        // `distant`: the sample of that distant light, drawn without its
        // radiance (`LightSet::sample_distant_dir`), which is looked up only
        // for a shadow ray the roulette keeps and nothing stops (the sky's
        // is dear).
        let mut one =
            |ls: Option<LightSample>, distant: Option<usize>, equi: bool, u_keep: Option<f32>| {
                let Some(mut ls) = ls else { return Vec3::ZERO };
                if ls.pdf <= 0.0 || (distant.is_none() && ls.li == Vec3::ZERO) {
                    return Vec3::ZERO;
                }
                let f = m.phase.eval(wo, ls.wi);
                if f == 0.0 {
                    return Vec3::ZERO;
                }
                // Away from the forward lobe the shadow ray is rouletted by the
                // phase value (`NeeRoulette::shadow`; a sun's also by the
                // segment's opacity), divided by its survival.
                let sun = distant.is_some_and(|k| self.lights.distant_is_directional(k));
                let keep = u_keep.map_or(Some(1.0), |u| rr.shadow(f, u, sun));
                let Some(keep) = keep else { return Vec3::ZERO };
                // A kept one is rouletted again by its transmittance, by
                // the same number (`NeeRoulette::shadow_tr`), before its
                // radiance and its ray.
                let (keep, tr) = match u_keep {
                    Some(u) => {
                        let tr = m.tr(p, ls.wi, ls.dist);
                        let Some(keep) = rr.shadow_tr(keep, tr, u) else {
                            return Vec3::ZERO;
                        };
                        (keep, Some(tr))
                    }
                    None => (keep, None),
                };
                *rays += 1;
                if self.accel.occluded(&shadow_ray(p, &ls)) {
                    return Vec3::ZERO;
                }
                // After the ray: most of a distant light's cost is its
                // radiance (the sky's table and cloud deck, the sun's deck),
                // wasted on the rays the street's walls stop.
                if let Some(k) = distant {
                    ls.li = self.lights.distant_li(scene, k, p, ls.wi);
                    if ls.li == Vec3::ZERO {
                        return Vec3::ZERO;
                    }
                }
                let w = if ls.delta {
                    if equi {
                        let q = p + ls.wi * ls.dist;
                        let pdf_eq = equiangular_on(m, ray, t_end, q).map_or(0.0, |e| e.pdf(t));
                        power_heuristic(1.0, pdf_in, 1.0, pdf_eq)
                    } else {
                        1.0
                    }
                } else {
                    power_heuristic(1.0, ls.pdf, 1.0, m.phase.pdf(wo, ls.wi))
                };
                let tr = tr.unwrap_or_else(|| m.tr(p, ls.wi, ls.dist));
                ls.li * tr * (f * w / (ls.pdf * keep))
            };
        for (k, &u) in u_distant
            .iter()
            .enumerate()
            .take(self.lights.distant_count())
        {
            // The sky's NEE under roulette, divided by its survival
            // probability: its expected value, so phase-sampled sky hits
            // keep their MIS weights. Suns are always estimated.
            let sky_scale = if self.lights.distant_is_directional(k) {
                1.0
            } else {
                match rr.sky() {
                    Some(s) => s,
                    None => continue,
                }
            };
            let u_keep = rr.u_shadow.get(k).copied();
            // A sky-table row whose every direction the phase roulette
            // would drop (by the bound of the phase over the row) ends the
            // draw before the column search: the same numbers decide as
            // `one` would, so the same result.
            let sun = self.lights.distant_is_directional(k);
            let row_kept = |z_lo, z_hi| {
                !rr.sky_row_bound
                    || u_keep.is_none_or(|uk| {
                        let f_max = m.phase.max_in_z_band(wo, z_lo, z_hi);
                        rr.shadow(f_max, uk, sun).is_some()
                    })
            };
            let ls = self.lights.sample_distant_dir_if(scene, k, p, u, row_kept);
            let c = one(ls, Some(k), false, u_keep) * sky_scale;
            l += match lobe_w {
                Some((k_sun, w)) if k_sun == k => c * w,
                _ => c,
            };
        }
        // `u_l` is drawn exactly when the local lights' roulette keeps them.
        if let (Some(scale), Some(u_l)) = (rr.local(), u_l) {
            let ls = self.lights.sample(scene, p, u_sel, u_l, bounce);
            let equi = ls.is_some_and(|s| s.delta && s.dist.is_finite());
            l += one(ls, None, equi, None) * scale;
        }
        l
    }

    /// Equiangular sampling of a point on [0, t_end] toward one selected
    /// point or spot light, MIS-weighted against the in-scattering points
    /// (density σ_t·Tr / `p_point`: 1 − the segment's Tr when every
    /// segment draws one, 1 when only collisions do).
    #[allow(clippy::too_many_arguments)]
    fn equiangular(
        &self,
        m: &Medium,
        ray: &Ray,
        t_end: f32,
        p_point: f32,
        u_sel: f32,
        u_t: f32,
        u_l: Vec2,
        rays: &mut u64,
    ) -> Vec3 {
        let scene = self.scene;
        if !self.lights.has_delta_local() {
            return Vec3::ZERO;
        }
        // Selection does not depend on the point: the light chosen once is
        // the light lit from the sampled point. Distances are drawn around
        // its position even where a spot's cone leaves the ray origin dark
        // (the in-scattering points' NEE counts on this strategy there).
        let Some(light) = self.lights.select_global(u_sel) else {
            return Vec3::ZERO;
        };
        let Some(q) = self.lights.delta_position(light) else {
            return Vec3::ZERO;
        };
        let Some(e) = equiangular_on(m, ray, t_end, q) else {
            return Vec3::ZERO;
        };
        let (t, pdf_eq) = e.sample(u_t);
        if pdf_eq.is_nan() || pdf_eq <= 0.0 || !t.is_finite() {
            return Vec3::ZERO;
        }
        let x = ray.at(t);
        let Some(ls) = self.lights.sample_chosen(scene, light, x, u_l) else {
            return Vec3::ZERO;
        };
        let sigma_t = m.sigma_t(x) as f32;
        let f = m.phase.eval(-ray.d, ls.wi);
        if sigma_t == 0.0 || f == 0.0 || ls.li == Vec3::ZERO {
            return Vec3::ZERO;
        }
        *rays += 1;
        if self.accel.occluded(&shadow_ray(x, &ls)) {
            return Vec3::ZERO;
        }
        let pdf_in = m.distance_pdf(ray.o, ray.d, t) / p_point;
        let w = power_heuristic(1.0, pdf_eq, 1.0, pdf_in);
        let tr = m.tr(ray.o, ray.d, t) * m.tr(x, ls.wi, ls.dist);
        m.albedo * ls.li * (sigma_t * tr * f * w / (pdf_eq * ls.pdf))
    }
}

/// The equiangular set-up on the part of [0, t_end] inside the medium.
fn equiangular_on(m: &Medium, ray: &Ray, t_end: f32, q: Vec3) -> Option<Equiangular> {
    let (a, b) = m.clip(ray.o, ray.d, t_end)?;
    Some(Equiangular::new(ray.o, ray.d, a as f32, b as f32, q))
}

/// One in-scattering point of a segment.
#[derive(Clone, Copy, Debug)]
struct InScatter {
    /// Ray parameter of the point.
    t: f32,
    /// Its density per metre on the segment, σ_t·Tr(t) / (1 − `tr_seg`).
    pdf: f32,
    /// Transmittance of the whole segment.
    tr_seg: f32,
    /// Whether free flight with the same number collides (at `t`).
    collided: bool,
}

impl InScatter {
    /// Free flight with `u` either collides at t, which is then ∝ σ_t·Tr on
    /// the segment, or passes (u ≥ 1 − Tr); a passing u is rescaled onto the
    /// colliding range, so `t` is always ∝ σ_t·Tr and collides exactly when
    /// free flight does. None when the segment has no extinction.
    fn sample(m: &Medium, ray: &Ray, t_end: f32, u: f32) -> Option<InScatter> {
        // The segment's clip and optical depth serve both Tr and the draw.
        let span = m.span(ray.o, ray.d, t_end);
        let tr_seg = span.tr();
        let p_collide = 1.0 - tr_seg;
        if p_collide.is_nan() || p_collide <= 0.0 {
            return None;
        }
        let collided = u < p_collide;
        let u_in = if collided {
            u
        } else {
            ((u - p_collide) / tr_seg) * p_collide
        };
        let ds = m.sample_distance_on(&span, u_in.min(p_collide * (1.0 - 1e-7)));
        if !ds.scattered || ds.pdf.is_nan() || ds.pdf <= 0.0 {
            return None;
        }
        Some(InScatter {
            t: ds.t,
            pdf: ds.pdf / p_collide,
            tr_seg,
            collided,
        })
    }
}

impl PathState {
    /// Scatters at medium point `p` into a direction of phase pdf `pdf`:
    /// the collision keeps the albedo (σ_s·Tr / (σ_t·Tr)).
    fn scatter(&mut self, m: &Medium, p: Vec3, pdf: f32) {
        self.beta *= m.albedo;
        self.prev_pdf = pdf;
        self.prev_delta = false;
        self.prev_p = p;
        self.prev_n = Vec3::ZERO;
        self.bounces += 1;
    }

    /// Russian roulette at a medium collision by the medium's albedo
    /// alone: survives with probability max(albedo) and divides β by it, so
    /// in a grey medium β leaves the collision as it entered (analog
    /// absorption). Throughput-based roulette (`survives_roulette`) killed
    /// paths dimmed by a surface and boosted the survivors (×2.5 after a
    /// 0.4 wall) right where fog sends them to the sky: in the foggy street
    /// about 13 % of the variance at 16 spp. Path length stays bounded by
    /// `max_depth`.
    ///
    /// It survives with a further probability `keep` ∈ (0, 1] (the deep
    /// roulette, `Strategies::deep_survival`; one number decides both, β
    /// is divided by both).
    fn survives_albedo_roulette(&mut self, m: &Medium, u_rr: f32, keep: f32) -> bool {
        let p = m.albedo.max_element().clamp(0.05, 1.0) * keep;
        if u_rr >= p {
            return false;
        }
        self.beta /= p;
        true
    }

    /// Whether the throughput can still carry radiance.
    fn alive(&self) -> bool {
        self.beta.is_finite() && self.beta != Vec3::ZERO
    }
}

/// The sun as a second strategy for the in-scattering after a medium
/// vertex: fog's forward lobe makes the next segment's sun NEE a spike
/// p(d·ω_sun) (≈ 6.5/sr at g = 0.85 against a mean of 1/4π) in the
/// direction d that phase sampling draws; drawing d ∝ the same lobe around
/// ω_sun and combining both by the power heuristic bounds it.
#[derive(Clone, Copy, Debug)]
pub struct SunLobe {
    /// Index of the sun among the distant lights.
    k: usize,
    /// Unit direction toward the sun's centre.
    axis: Vec3,
}

impl SunLobe {
    /// The first sun of `scene` that the light set samples as a distant light.
    pub fn find(scene: &crate::scene::Scene, lights: &crate::light::LightSet) -> Option<SunLobe> {
        let (axis, cone) = scene.lights.iter().find_map(|l| match *l {
            crate::light::Light::Sun {
                dir_to_sun,
                angular_radius_rad,
                ..
            } => Some((dir_to_sun, crate::light::SunCone::new(angular_radius_rad))),
            _ => None,
        })?;
        (0..lights.distant_count())
            .find(|&k| {
                lights
                    .sample_distant(scene, k, Vec3::ZERO, Vec2::splat(0.5))
                    .is_some_and(|ls| ls.dist.is_infinite() && cone.contains(axis, ls.wi))
            })
            .map(|k| SunLobe { k, axis })
    }

    /// Pdf per solid angle of drawing direction `d` (the medium's lobe around the sun).
    fn pdf(&self, m: &Medium, d: Vec3) -> f32 {
        m.phase.pdf(-self.axis, d)
    }
}

impl<A: Accel> PathContext<'_, A> {
    /// The sun-lobe strategy at medium vertex `p` (incoming `wo`): a
    /// direction d drawn around the sun, its segment's in-scattering point
    /// drawn as every segment's, and that point's sun NEE, weighted by
    /// p(wo, d)/pdf_lobe(d) and the power heuristic against phase sampling.
    /// Throughput after `p` not included. Its rays are rouletted by the
    /// phase value toward d times w (`Strategies::shadow_per_phase`, by
    /// `u1[3]`): the term is about the sun's NEE at that phase value; a
    /// kept shadow ray again by its transmittance (`Strategies::shadow_per_tr`).
    #[allow(clippy::too_many_arguments)]
    fn sun_lobe_vertex(
        &self,
        m: &Medium,
        sl: SunLobe,
        p: Vec3,
        wo: Vec3,
        (u0, u1): ([f32; 4], [f32; 4]),
        (shadow_per_phase, shadow_per_tr): (f32, f32),
        rays: &mut u64,
    ) -> Vec3 {
        let s = m.phase.sample(-sl.axis, Vec2::new(u0[0], u0[1]));
        let d = s.wi;
        let pdf_phase = m.phase.pdf(wo, d);
        if s.pdf <= 0.0 || pdf_phase <= 0.0 {
            return Vec3::ZERO;
        }
        let w = power_heuristic(1.0, s.pdf, 1.0, pdf_phase);
        let keep = (shadow_per_phase * pdf_phase * w).min(1.0);
        if u1[3] >= keep {
            return Vec3::ZERO;
        }
        let ray = Ray::new(p, d);
        *rays += 1;
        let t_end = self.accel.intersect(&ray).map_or(f32::INFINITY, |h| h.t);
        let Some(seg) = InScatter::sample(m, &ray, t_end, u0[2]) else {
            return Vec3::ZERO;
        };
        let x = ray.at(seg.t);
        // The sun's radiance (its cloud deck) only once the ray is clear.
        let Some(mut ls) =
            self.lights
                .sample_distant_dir(self.scene, sl.k, x, Vec2::new(u1[0], u1[1]))
        else {
            return Vec3::ZERO;
        };
        let f = m.phase.eval(-d, ls.wi);
        if ls.pdf <= 0.0 || f == 0.0 {
            return Vec3::ZERO;
        }
        // Kept by the phase roulette (`u1[3]` uniform below `keep`), the
        // shadow ray is kept again by its transmittance, known before the
        // ray, as `medium_nee`'s (`NeeRoulette::shadow_tr`).
        let tr = m.tr(x, ls.wi, ls.dist);
        let keep = keep * (shadow_per_tr * tr).min(1.0);
        if u1[3] >= keep {
            return Vec3::ZERO;
        }
        *rays += 1;
        if self.accel.occluded(&shadow_ray(x, &ls)) {
            return Vec3::ZERO;
        }
        ls.li = self.lights.distant_li(self.scene, sl.k, x, ls.wi);
        if ls.li == Vec3::ZERO {
            return Vec3::ZERO;
        }
        // The same weight as the NEE of `medium_nee` against phase sampling.
        let w_sun = power_heuristic(1.0, ls.pdf, 1.0, m.phase.pdf(-d, ls.wi));
        let seg_w = m.albedo * (1.0 - seg.tr_seg);
        let weight = pdf_phase / s.pdf * w * f * w_sun / (ls.pdf * keep);
        seg_w * ls.li * tr * weight
    }
}
