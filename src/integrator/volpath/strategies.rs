//! The optional strategies at medium vertices (`Strategies`) and the
//! roulette of a medium NEE's terms (`NeeRoulette`): each changes only the
//! variance, never the expected value.

use glam::Vec3;

use crate::integrator::path::RayCone;

/// The optional strategies at medium vertices; each only changes the
/// variance, never the expected value.
#[derive(Clone, Copy, Debug)]
pub(super) struct Strategies {
    /// The sun-lobe direction and its MIS (`SunLobe`); off is plain phase
    /// sampling.
    pub(super) sun_lobe: bool,
    /// Roulette by the albedo (`PathState::survives_albedo_roulette`); off
    /// is the surface loop's throughput roulette.
    pub(super) albedo_roulette: bool,
    /// Segments after fewer scattering events than this estimate their
    /// in-scattering on every segment; later ones only at collisions
    /// (`u32::MAX`: every segment).
    pub(super) every_segment_bounces: u32,
    /// Split the camera ray's first segment: the surface (or sky) behind it
    /// always traced with weight Tr, the collision's continuation as drawn,
    /// so the binary collide-or-pass choice leaves no noise on surfaces
    /// (renders with the fog filter on; about a quarter of the variance
    /// the filter leaves in the foggy street).
    pub(super) split_first: bool,
    /// Probability that a collision estimates the sky's NEE (divided by
    /// it), the camera segment's in-scattering point excepted. Sky light
    /// through fog is smooth and the fog-weighted tables draw it well:
    /// half the sky's shadow rays at collisions cost about 0.03 dB in the
    /// foggy street (town03 frame 40) for 6 % fewer rays.
    pub(super) sky_nee_deep: f32,
    /// Probability that a collision after the first (`LOBE_ALWAYS`) draws
    /// the sun lobe (divided by it); the next sun NEE keeps its MIS weight
    /// whether or not it was drawn, so the pair's expected value stays.
    /// At 1/2: 10 % fewer rays in the foggy street for about 0.06 dB.
    pub(super) lobe_deep: f32,
    /// The sky's NEE at an every-segment in-scattering point (weighted by
    /// the segment's opacity 1 − Tr) is estimated with probability
    /// min(1, `inscatter_per_opacity`·(1 − Tr)) and divided by it
    /// (`NeeRoulette`): in thin haze a camera ray's NEE brought a few per
    /// cent of its light for a shadow ray. A kept term is at most 1/this
    /// of what an opaque segment would scatter, however thin the haze
    /// (`f32::INFINITY`: always).
    pub(super) inscatter_per_opacity: f32,
    /// The suns' shadow rays from an every-segment in-scattering point are
    /// rouletted by the phase value times min(1, `sun_per_opacity`·(1 − Tr))
    /// (`NeeRoulette::sun_opacity`): in thin haze (humid, storm, fog near
    /// the camera) a camera ray's sun NEE brings (1 − Tr) of a collision's
    /// for a long shadow ray. Where 1 − Tr ≥ 1/this nothing changes; below,
    /// a kept term is at most E_sun/(`shadow_per_phase`·this) (`f32::INFINITY`:
    /// the phase roulette alone).
    pub(super) sun_per_opacity: f32,
    /// The same for the local lights' in-scattering at an every-segment
    /// point, NEE and equiangular sampling together (their own number):
    /// min(1, `local_per_opacity`·(1 − Tr)). By day the lamps' light in
    /// the fog is nil beside the sun's and sky's (town05 frame 40 foggy:
    /// 0.003 % of the image mean), but each estimate walks the light BVH:
    /// at 0.25, and 0.1 for `local_nee_deep`, the foggy street costs about
    /// 30 % less CPU, the storm 20 %, at the same noise between two sample
    /// seeds. `li_volume` turns both off (always estimated) where the
    /// local lights matter.
    pub(super) local_per_opacity: f32,
    /// Probability that a segment after the camera's estimates the local
    /// lights' in-scattering (divided by it): NEE at its collision and
    /// equiangular sampling on it.
    pub(super) local_nee_deep: f32,
    /// Probability that a path survives a collision after
    /// `DEEP_FROM` scattering events (on top of the albedo roulette, divided
    /// by it; 1.0: off, the default) while `deep_max_boost` allows. Fog's
    /// deep chains cost most of its rays. Still off: even bounded at 2,
    /// `tests/denoise/fog.rs`'s surface-fog mean test (8 spp) sees the
    /// surface filter's firefly rule drop over 1 % of its component.
    pub(super) deep_survival: f32,
    /// The deep roulette runs only while the boost it has given the path
    /// (the product of 1/`deep_survival` over its survivals) stays at most
    /// this. Unbounded, survivors of k roulettes weigh 2^k times their
    /// neighbours: noise the filters do not remove (town03 frame 40 foggy
    /// against 256 spp: −1.0 dB for 23 % fewer rays) and spikes the
    /// surface filter drops as fireflies (−27 % of its component in
    /// `tests/denoise/fog.rs`). At 2 (one survival at 1/2) a survivor
    /// weighs at most twice its neighbours, well below the firefly rule's
    /// ratio (`denoise::surface`): town05 frame 40 foggy, 18 % fewer rays
    /// for 0.15 dB against 64 spp (unbounded: 23 %, 0.41 dB).
    pub(super) deep_max_boost: f32,
    /// The split camera ray's surface part after a collision
    /// (`split_first`) is traced with probability
    /// min(1, `split_per_tr`·Tr) and its weight Tr divided by it: behind
    /// dense fog the surface brings little (a kept part weighs at most
    /// 1/this) for a whole second path (`f32::INFINITY`: always). At 8:
    /// 4 % fewer rays in the foggy street; at 4 (7 %) the surface filter
    /// drops about 1 % of its component as fireflies.
    pub(super) split_per_tr: f32,
    /// A distant light's shadow ray from a medium point is traced with
    /// probability min(1, `shadow_per_phase`·f), f the phase value toward
    /// it, and divided by it (`NeeRoulette::shadow`): at g = 0.85 most
    /// medium points see the sun and most of the sky far outside the
    /// forward lobe, where f is a few per cent of its mean 1/4π. At 4π a
    /// kept term weighs at most what an isotropic medium's would
    /// (`f32::INFINITY`: always traced). The sun lobe (`sun_lobe_vertex`)
    /// is rouletted by the same rule on its phase value toward its direction.
    pub(super) shadow_per_phase: f32,
    /// A shadow ray the phase roulette keeps (`shadow_per_phase`) is kept
    /// again with probability min(1, `shadow_per_tr`·Tr), Tr the medium's
    /// transmittance along it (closed form, known before the ray), and
    /// divided by it (`NeeRoulette::shadow_tr`): deep in fog most shadow
    /// rays carry a few per cent of their light. A kept one brings
    /// 1/this of its light without the medium, the least that a ray with
    /// Tr ≥ 1/this (always traced) brings, so the roulette adds no term
    /// brighter than those already there: no new fireflies for the fog
    /// filter (`f32::INFINITY`: the phase roulette alone). The sun lobe's
    /// shadow ray (`sun_lobe_vertex`) is rouletted by the same rule.
    pub(super) shadow_per_tr: f32,
    /// A surface vertex's distant-light shadow ray in the medium is traced
    /// with probability min(1, `surface_per_tr`·Tr) and divided by it
    /// (`path::ShadowTrRoulette`), Tr its transmittance: the suns' and the
    /// sky's rays from the street in fog carry a few per cent of their
    /// light (town05 frame 40 foggy: mean Tr 0.13). At 2, 16 % fewer rays
    /// in the foggy street for 0.006 dB (320×180 against 256 spp), and
    /// the storm's haze (Tr mostly above 1/2) keeps nearly all of them
    /// (`f32::INFINITY`: always traced).
    pub(super) surface_per_tr: f32,
    /// The indirect light of a Lambertian split vertex x1 (all the path
    /// gathers after x1's next-event estimates: a whole second path for a
    /// collided camera ray's surface part) is traced with probability
    /// [`Strategies::x1_indirect_keep`], clamp(`x1_indirect_per_beta`·β,
    /// `x1_indirect_min`, 1) with β the throughput reaching x1 (about the
    /// camera segment's Tr), and divided by it. It is filtered as a ratio
    /// to β·ρ (`SurfaceSplit`), which smooths the added noise; a surface
    /// seen clearly (β ≥ 1/`x1_indirect_per_beta`) keeps all of it
    /// (`f32::INFINITY`: always traced, the default). At 2 and 1/2 (with
    /// `surface_per_tr`): town05 frame 40, 22 % fewer rays in fog for
    /// 0.02 dB, the storm 0.003 dB, but only about 5 % less CPU (the rays
    /// it saves are cheap), and `tests/denoise/fog.rs`'s depth step then
    /// sees the far wall's filtered row next to the edge 3.05 % below the
    /// reference (its bound is 3 %): still off.
    pub(super) x1_indirect_per_beta: f32,
    /// The least survival probability of x1's indirect light, in (0, 1].
    pub(super) x1_indirect_min: f32,
    /// The sky's NEE from a medium point stops its table draw at the row
    /// when the phase roulette (`shadow_per_phase`) would drop every
    /// direction of that row (`HenyeyGreenstein::max_in_z_band`): the same
    /// numbers decide, so the same bits, without the column search and pdf
    /// of most dropped draws (off: the whole draw, for tests).
    pub(super) sky_row_bound: bool,
    /// The camera ray's cone: textures seen through the medium are
    /// filtered by it as without one (`path::RayCone`).
    pub(super) cone: RayCone,
}

impl Default for Strategies {
    fn default() -> Self {
        Strategies {
            sun_lobe: true,
            albedo_roulette: true,
            every_segment_bounces: 1,
            split_first: false,
            sky_nee_deep: 0.5,
            lobe_deep: 0.5,
            inscatter_per_opacity: 4.0,
            sun_per_opacity: 4.0,
            local_per_opacity: 0.25,
            local_nee_deep: 0.1,
            deep_survival: 1.0,
            deep_max_boost: 2.0,
            split_per_tr: 8.0,
            shadow_per_phase: 4.0 * std::f32::consts::PI,
            shadow_per_tr: 4.0,
            surface_per_tr: 2.0,
            x1_indirect_per_beta: f32::INFINITY,
            x1_indirect_min: 0.5,
            sky_row_bound: true,
            cone: RayCone::NONE,
        }
    }
}

impl Strategies {
    /// The survival probability of the indirect light of a Lambertian
    /// split vertex reached with throughput `beta`
    /// (`x1_indirect_per_beta`), in [`x1_indirect_min`, 1].
    pub(super) fn x1_indirect_keep(&self, beta: Vec3) -> f32 {
        if self.x1_indirect_per_beta.is_finite() {
            (self.x1_indirect_per_beta * beta.max_element()).clamp(self.x1_indirect_min, 1.0)
        } else {
            1.0
        }
    }
}

/// Russian roulette of a medium NEE's smooth terms: the sky's, kept with
/// probability `keep_sky`, and the local lights' (their selection walks
/// the light BVH), kept with probability `keep_local`, each by its own
/// number and divided by its probability. Suns are never dropped by the
/// opacity (their forward-lobe peak would become Bernoulli noise); the
/// first two distant lights' shadow rays are rouletted by their phase
/// value instead (`shadow`), which keeps every ray in the lobe.
#[derive(Clone, Copy, Debug)]
pub(super) struct NeeRoulette {
    /// The sky roulette's uniform number.
    pub(super) u_sky: f32,
    /// The sky's survival probability in (0, 1].
    pub(super) keep_sky: f32,
    /// The local lights' roulette's uniform number.
    pub(super) u_local: f32,
    /// The local lights' survival probability in (0, 1].
    pub(super) keep_local: f32,
    /// The first distant lights' shadow-ray roulettes' uniform numbers.
    pub(super) u_shadow: [f32; 2],
    /// Survival per unit phase value of a distant light's shadow ray
    /// (`Strategies::shadow_per_phase`).
    pub(super) shadow_per_phase: f32,
    /// Survival per unit transmittance of a shadow ray the phase roulette
    /// kept (`Strategies::shadow_per_tr`).
    pub(super) shadow_per_tr: f32,
    /// The suns' factor on that survival, in (0, 1]: the segment's
    /// min(1, `Strategies::sun_per_opacity`·(1 − Tr)) at an every-segment
    /// point, 1 at a collision (which stands for itself, not for 1 − Tr).
    pub(super) sun_opacity: f32,
    /// Whether the sky's table draw may stop at a row the shadow roulette
    /// drops whole (`Strategies::sky_row_bound`).
    pub(super) sky_row_bound: bool,
}

impl NeeRoulette {
    /// The factor of a kept sky estimate (1/`keep_sky`), None when dropped.
    pub(super) fn sky(&self) -> Option<f32> {
        (self.u_sky < self.keep_sky).then(|| 1.0 / self.keep_sky)
    }

    /// The factor of a kept local-light estimate (1/`keep_local`), None
    /// when dropped.
    pub(super) fn local(&self) -> Option<f32> {
        (self.u_local < self.keep_local).then(|| 1.0 / self.keep_local)
    }

    /// The survival probability of a shadow ray toward a light of phase
    /// value `f` > 0 by the uniform number `u`, None when dropped; `sun`:
    /// toward a sun, also by the segment's opacity (`sun_opacity`).
    pub(super) fn shadow(&self, f: f32, u: f32, sun: bool) -> Option<f32> {
        let scale = if sun { self.sun_opacity } else { 1.0 };
        let keep = (self.shadow_per_phase * f * scale).min(1.0);
        (u < keep).then_some(keep)
    }

    /// The survival probability of a shadow ray that [`NeeRoulette::shadow`]
    /// kept with probability `keep` by the number `u`, once its
    /// transmittance `tr` is known: kept by the same `u` (uniform below
    /// `keep` once kept) with probability `keep`·min(1, `shadow_per_tr`·`tr`);
    /// None when dropped.
    pub(super) fn shadow_tr(&self, keep: f32, tr: f32, u: f32) -> Option<f32> {
        let keep = keep * (self.shadow_per_tr * tr).min(1.0);
        (u < keep).then_some(keep)
    }
}
