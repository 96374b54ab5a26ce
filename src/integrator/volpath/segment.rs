//! One segment of a volumetric path (`volpath.rs`): its samples, its
//! medium events (in-scattering estimate, the first segment's split, a
//! collision and the scatter after it) and the path state they change.

use glam::{Vec2, Vec3};
use shaders_cpu::medium::Medium;
use shaders_cpu::sampling::power_heuristic;

use super::{
    InScatter, NeeRoulette, Strategies, SunLobe, DEEP_FROM, LOBE_ALWAYS, LOBE_DIMS, VOL_DIMS,
    VOL_DIMS_PER_BOUNCE,
};
use crate::accel::{Accel, Hit, Ray};
use crate::integrator::path::{LiSample, PathState};
use crate::integrator::{DenoiseSample, PathContext};
use crate::sampler::SampleStream;

use super::surface_split::SurfaceSplit;

/// The camera segment's 4D set (after `SegmentSamples`' five) whose first
/// number decides the split's roulette (`Strategies::split_per_tr`) and
/// second the roulette of x1's indirect light
/// (`Strategies::x1_indirect_per_beta`).
pub(super) const SPLIT_SET: u32 = 5;

/// The segment's 4D set whose first number decides the local lights' NEE
/// roulette (`NeeRoulette`).
const LOCAL_SET: u32 = 6;

/// A segment's samples, each 4D set drawn at its bounce's fixed
/// dimension only where the segment uses it (a number depends on its
/// dimension alone, so the same numbers as drawing them all): free flight,
/// phase direction and roulette at once; the in-scattering estimate's
/// roulettes, the local lights' numbers and the distant lights' samples
/// when it reaches them (the local lights' and the third and fourth
/// distant lights' seldom by day).
pub(super) struct SegmentSamples {
    /// The segment's first dimension.
    base: u32,
    /// Free flight (and the in-scattering point).
    pub u_ff: f32,
    /// Phase-function direction.
    pub u_phase: Vec2,
    /// Roulette at a collision.
    pub u_rr: f32,
}

/// The segment's 4D set of the equiangular distance and light choice and
/// the in-scattering NEE's local light sample.
const LOCAL_LIGHT_SET: u32 = 1;
/// The segment's 4D set of the in-scattering NEE's local light choice, the
/// equiangular light sample and the sky roulette.
const CHOICE_SET: u32 = 2;
/// The segment's first 4D set of the distant lights' samples (two each).
const DISTANT_SET: u32 = 3;

/// The numbers of a segment's in-scattering roulettes, and the local light
/// choice of its NEE (drawn in one set with the sky's roulette).
#[derive(Clone, Copy, Debug)]
pub(super) struct InScatterSamples {
    /// Roulette of the sky's NEE (`NeeRoulette`).
    pub u_sky: f32,
    /// Roulette of the local lights' NEE (`NeeRoulette`).
    pub u_local: f32,
    /// Roulettes of the first two distant lights' shadow rays (`NeeRoulette`).
    pub u_shadow: [f32; 2],
    /// Local light choice for the in-scattering NEE.
    pub u_sel: f32,
    /// Equiangular sampling's 2D light sample.
    pub u_eq_light: Vec2,
}

/// The local lights' numbers of a segment.
#[derive(Clone, Copy, Debug)]
pub(super) struct LocalSamples {
    /// Equiangular distance.
    pub u_eq: f32,
    /// Light choice for equiangular sampling.
    pub u_eq_sel: f32,
    /// The in-scattering NEE's 2D local light sample.
    pub u_light: Vec2,
}

impl SegmentSamples {
    /// The samples of the segment after `bounces` scattering events.
    pub fn draw(stream: &mut SampleStream, bounces: u32) -> Self {
        let base = VOL_DIMS + bounces * VOL_DIMS_PER_BOUNCE;
        stream.set_dimension(base);
        // Distance and continuation direction share one 4D set, so they
        // are stratified jointly across a pixel's samples: together they
        // decide where the path goes (its escape to the sky is most of
        // the foggy street's error); in separate padded sets they were
        // paired at random (about 1.5 % lower RMSE at 16 spp).
        let [u_ff, u_ph0, u_ph1, u_rr] = stream.next_4d();
        SegmentSamples {
            base,
            u_ff,
            u_phase: Vec2::new(u_ph0, u_ph1),
            u_rr,
        }
    }

    /// The segment's 4D set `set`.
    fn set(&self, stream: &mut SampleStream, set: u32) -> [f32; 4] {
        stream.set_dimension(self.base + set);
        stream.next_4d()
    }

    /// The in-scattering estimate's roulettes and local light choice.
    pub fn in_scatter(&self, stream: &mut SampleStream) -> InScatterSamples {
        let [u_sel, u_ex, u_ey, u_sky] = self.set(stream, CHOICE_SET);
        let [u_local, u_sh0, u_sh1, _] = self.set(stream, LOCAL_SET);
        InScatterSamples {
            u_sky,
            u_local,
            u_shadow: [u_sh0, u_sh1],
            u_sel,
            u_eq_light: Vec2::new(u_ex, u_ey),
        }
    }

    /// The local lights' numbers (equiangular and NEE).
    pub fn local(&self, stream: &mut SampleStream) -> LocalSamples {
        let [u_eq, u_eq_sel, u_lx, u_ly] = self.set(stream, LOCAL_LIGHT_SET);
        LocalSamples {
            u_eq,
            u_eq_sel,
            u_light: Vec2::new(u_lx, u_ly),
        }
    }

    /// One 2D sample for each of the first `n` (≤ 4) distant lights (the
    /// rest zero).
    pub fn distant(&self, stream: &mut SampleStream, n: usize) -> [Vec2; 4] {
        let mut u = [Vec2::ZERO; 4];
        for (k, pair) in u.chunks_mut(2).enumerate().take(n.div_ceil(2)) {
            let [a0, a1, a2, a3] = self.set(stream, DISTANT_SET + k as u32);
            pair.copy_from_slice(&[Vec2::new(a0, a1), Vec2::new(a2, a3)]);
        }
        u
    }
}

/// How a segment's medium events leave the path.
pub(super) enum SegmentEnd {
    /// No collision: the path goes on to the segment's surface or the sky.
    Passed,
    /// A collision scattered it: it continues along this ray.
    Scattered(Ray),
    /// It ends here.
    Ended,
}

/// The split of the sample by the camera ray's first event
/// (`DenoiseSample`), gathered along the path.
#[derive(Default)]
pub(super) struct FirstEvent {
    /// Radiance gathered when the camera ray's first segment passes its
    /// medium to the surface or sky (None while on it, and for good once
    /// it collides: then all is fog).
    pub l_fog_passed: Option<Vec3>,
    /// Opacity of the first segment.
    opacity: f32,
    /// A Lambertian first surface's direct and indirect light.
    pub surface: SurfaceSplit,
    /// At a glossy first vertex: the path radiance before it was shaded,
    /// plus its suns' next-event part, and β·`glossy_albedo` there
    /// (`DenoiseSample::l_direct`, `rho_direct`).
    pub glossy: Option<(Vec3, Vec3)>,
    /// The split camera ray's surface part, traced apart after a collision.
    split: LiSample,
    /// Whether the split vertex lies behind delta scatters
    /// (`DenoiseSample::split_behind_delta`).
    pub behind_delta: bool,
    /// A Lambertian x1's bounce: how freely its ray left
    /// (`DenoiseSample::openness`; None until traced).
    pub openness: Option<f32>,
}

/// The running state of one volumetric path.
pub(super) struct VolState {
    /// What the surface loop also tracks.
    pub st: PathState,
    /// The path's medium-vertex strategies.
    strategies: Strategies,
    /// The sun lobe, where the strategies use it and the medium scatters.
    sun_lobe: Option<SunLobe>,
    /// The last medium vertex's wo when it also drew a sun-lobe direction:
    /// this segment's sun NEE is then MIS-weighted against that strategy.
    pub lobe_wo: Option<Vec3>,
    /// The denoiser's split of the sample.
    pub first: FirstEvent,
    /// The boost the deep roulette has given the path
    /// (`Strategies::deep_max_boost`).
    deep_boost: f32,
}

impl VolState {
    /// A path starting in state `st`, taking `strategies` (the sun lobe
    /// `sun_lobe`).
    pub fn new(st: PathState, strategies: Strategies, sun_lobe: Option<SunLobe>) -> Self {
        VolState {
            st,
            strategies,
            sun_lobe,
            lobe_wo: None,
            first: FirstEvent::default(),
            deep_boost: 1.0,
        }
    }

    /// The path's sample once it has ended.
    pub fn finish(self) -> LiSample {
        let VolState { st, first, .. } = self;
        let split = first.split.denoise;
        // Only one of the path and its split surface part reaches x1.
        let (l_direct, rho_direct) = match first.glossy {
            Some((l_at_x1, rho)) => (st.l - l_at_x1, rho),
            None if first.surface.is_split() => (first.surface.direct, first.surface.rho),
            None => (split.l_direct, split.rho_direct),
        };
        // Light along the reflection of glass seen from the camera
        // (`SplitVertex::at_glass`), from the path or its split surface part.
        let l_refl = st.split.refl_from.map_or(Vec3::ZERO, |l0| st.l - l0) + split.l_refl;
        let rho_refl = st.split.rho_refl + split.rho_refl;
        let rho_refl_hit = st.split.rho_refl_hit + split.rho_refl_hit;
        LiSample {
            l: st.l + first.split.l,
            denoise: DenoiseSample {
                l_fog: first.l_fog_passed.unwrap_or(st.l),
                opacity: first.opacity,
                l_surf: first.surface.l_surf(st.l) + split.l_surf,
                rho: first.surface.rho + split.rho,
                split_behind_delta: first.behind_delta || split.split_behind_delta,
                // Direct light at x1: at a glossy one all its light, at a
                // Lambertian one its next-event estimates; the suns' left
                // out of both.
                l_direct,
                rho_direct,
                glossy: first.glossy.is_some() || split.glossy,
                l_refl,
                // Media keep one lobe of glass by chance, no branch.
                l_refl_sharp: Vec3::ZERO,
                rho_refl,
                rho_refl_hit,
                openness: if first.surface.is_split() {
                    first.openness.unwrap_or(1.0)
                } else {
                    split.openness
                },
            },
            aov: st.aov.aov,
        }
    }
}

impl<A: Accel> PathContext<'_, A> {
    /// The medium events on the segment `ray` up to `hit` (the surface, or
    /// none: the sky) with samples `u`: in-scattering estimated on the whole
    /// segment (not only at collisions), the first segment's split, and a
    /// collision's scatter.
    pub(super) fn medium_segment(
        &self,
        m: &Medium,
        (ray, hit, u): (&Ray, Option<Hit>, &SegmentSamples),
        vs: &mut VolState,
        stream: &mut SampleStream,
        rays: &mut u64,
    ) -> SegmentEnd {
        let strategies = vs.strategies;
        let first_segment = vs.st.bounces == 0;
        let t_end = hit.map_or(f32::INFINITY, |h| h.t);
        if !m.scatters() {
            vs.st.beta *= m.tr(ray.o, ray.d, t_end);
            return SegmentEnd::Passed;
        }
        let Some(seg) = InScatter::sample(m, ray, t_end, u.u_ff) else {
            return SegmentEnd::Passed;
        };
        if first_segment {
            vs.first.opacity = 1.0 - seg.tr_seg;
        }
        // Early segments estimate their in-scattering whether or not they
        // collide; later ones only where they collide (the collision
        // estimator: same mean, no shadow rays on the segments that pass).
        // Equiangular sampling runs on every segment either way.
        let every = vs.st.bounces < strategies.every_segment_bounces;
        if vs.st.bounces < self.max_depth {
            self.in_scatter(m, (ray, t_end), &seg, every, (u, stream), vs, rays);
        }
        let split = first_segment && strategies.split_first;
        if split && seg.collided {
            // Both continuations: the surface's with its expected weight
            // Tr (under `split_per_tr`'s roulette, by a number of the
            // segment's sixth set), the fog's as drawn.
            let keep = (strategies.split_per_tr * seg.tr_seg).min(1.0);
            stream.set_dimension(VOL_DIMS + SPLIT_SET);
            if stream.next_1d() < keep {
                let beta_surf = vs.st.beta * (seg.tr_seg / keep);
                vs.first.split = self.trace(*ray, hit, stream, rays, strategies, Some(beta_surf));
            }
        } else if split {
            vs.st.beta *= seg.tr_seg;
        }
        if !seg.collided {
            return SegmentEnd::Passed;
        }
        self.collide(m, ray.at(seg.t), -ray.d, u, vs, stream, rays)
    }

    /// In-scattering along the whole segment: equiangular sampling toward a
    /// point or spot light, and NEE at the segment's in-scattering point
    /// (drawn ∝ σ_t·Tr), weighted by (1 − Tr)·albedo when estimated on
    /// `every` segment, else only where the segment collides, by the albedo
    /// alone (the collision estimator); both added to the path.
    #[allow(clippy::too_many_arguments)]
    fn in_scatter(
        &self,
        m: &Medium,
        (ray, t_end): (&Ray, f32),
        seg: &InScatter,
        every: bool,
        (u, stream): (&SegmentSamples, &mut SampleStream),
        vs: &mut VolState,
        rays: &mut u64,
    ) {
        let (p, wo) = (ray.at(seg.t), -ray.d);
        let ui = u.in_scatter(stream);
        // The roulettes of the sky's and the local lights' terms: on every
        // segment by its opacity (`inscatter_per_opacity`,
        // `local_per_opacity`), at collisions `sky_nee_deep` and
        // `local_nee_deep`.
        let s = vs.strategies;
        let (keep_sky, keep_local, sun_opacity) = if every {
            let opacity = 1.0 - seg.tr_seg;
            (
                (s.inscatter_per_opacity * opacity).min(1.0),
                (s.local_per_opacity * opacity).min(1.0),
                (s.sun_per_opacity * opacity).min(1.0),
            )
        } else {
            (s.sky_nee_deep, s.local_nee_deep, 1.0)
        };
        let rr = NeeRoulette {
            u_sky: ui.u_sky,
            keep_sky,
            u_local: ui.u_local,
            keep_local,
            u_shadow: ui.u_shadow,
            shadow_per_phase: s.shadow_per_phase,
            shadow_per_tr: s.shadow_per_tr,
            sun_opacity,
            sky_row_bound: s.sky_row_bound,
        };
        // The in-scattering point's density per metre: σ_t·Tr / (1 − Tr)
        // drawn on every segment, σ_t·Tr as a collision.
        let p_point = if every { 1.0 - seg.tr_seg } else { 1.0 };
        // Equiangular sampling toward the local lights shares their
        // roulette (on every segment, collided or not).
        let local = rr.local().map(|scale| (scale, u.local(stream)));
        if let Some((scale, ul)) = local {
            let c = self.equiangular(
                m,
                ray,
                t_end,
                p_point,
                ul.u_eq_sel,
                ul.u_eq,
                ui.u_eq_light,
                rays,
            );
            vs.st.l += vs.st.beta * c * scale;
        }
        let st = &mut vs.st;
        if !every && !seg.collided {
            return;
        }
        let lobe_w = vs.lobe_wo.zip(vs.sun_lobe).map(|(wo_prev, sl)| {
            (
                sl.k,
                power_heuristic(1.0, m.phase.pdf(wo_prev, ray.d), 1.0, sl.pdf(m, ray.d)),
            )
        });
        let nee = self.medium_nee(
            m,
            ray,
            t_end,
            seg.t,
            if every {
                seg.pdf
            } else {
                seg.pdf * (1.0 - seg.tr_seg)
            },
            p,
            wo,
            (ui.u_sel, local.map(|(_, ul)| ul.u_light)),
            &u.distant(stream, self.lights.distant_count()),
            lobe_w,
            (rr, st.bounces),
            rays,
        );
        // Every segment: the point stands for the collision it is with
        // probability 1 − Tr; a collision's estimate is its own.
        let w_seg = if every { 1.0 - seg.tr_seg } else { 1.0 };
        st.l += st.beta * m.albedo * (nee * w_seg);
    }

    /// A collision at medium point `p` (incoming `wo`): the phase-sampled
    /// direction, the sun-lobe strategy's contribution, and roulette.
    #[allow(clippy::too_many_arguments)]
    fn collide(
        &self,
        m: &Medium,
        p: Vec3,
        wo: Vec3,
        u: &SegmentSamples,
        vs: &mut VolState,
        stream: &mut SampleStream,
        rays: &mut u64,
    ) -> SegmentEnd {
        let st = &mut vs.st;
        if st.bounces == self.max_depth {
            return SegmentEnd::Ended;
        }
        let ph = m.phase.sample(wo, u.u_phase);
        st.scatter(m, p, ph.pdf);
        vs.lobe_wo = None;
        if let Some(sl) = vs.sun_lobe.filter(|_| st.bounces < self.max_depth) {
            stream.set_dimension(LOBE_DIMS + 2 * st.bounces);
            let (u0, u1) = (stream.next_4d(), stream.next_4d());
            // Deep collisions draw the lobe with probability `lobe_deep`
            // (divided by it); the next sun NEE keeps its MIS weight either
            // way, so the pair's expected value is unchanged.
            let keep = if st.bounces > LOBE_ALWAYS {
                vs.strategies.lobe_deep
            } else {
                1.0
            };
            if u1[2] < keep {
                let per = (vs.strategies.shadow_per_phase, vs.strategies.shadow_per_tr);
                let c = self.sun_lobe_vertex(m, sl, p, wo, (u0, u1), per, rays);
                st.l += st.beta * c / keep;
            }
            vs.lobe_wo = Some(wo);
        }
        let survives = if vs.strategies.albedo_roulette {
            let q = vs.strategies.deep_survival;
            let deep = st.bounces > DEEP_FROM && vs.deep_boost / q <= vs.strategies.deep_max_boost;
            let keep = if deep { q } else { 1.0 };
            vs.deep_boost /= keep;
            st.survives_albedo_roulette(m, u.u_rr, keep)
        } else {
            st.survives_roulette(u.u_rr)
        };
        if ph.pdf <= 0.0 || !st.alive() || !survives {
            return SegmentEnd::Ended;
        }
        SegmentEnd::Scattered(Ray::new(p, ph.wi))
    }
}
