//! Unidirectional path tracing with next-event estimation and multiple
//! importance sampling (power heuristic, Veach 1997 §9.2), Russian roulette,
//! and error-bounded secondary-ray origins (pbrt-v4 `PathIntegrator`, §13.4).
//!
//! Every random number comes from the pixel's `SampleStream`; each bounce
//! starts at a fixed dimension so the streams of different bounces never shift,
//! which also lets a vertex's samples (`BounceSamples`) be drawn as soon as its
//! hit is known, before the previous vertex's shadow rays are traced.
//! `max_depth` counts scattering events: 1 is direct lighting only.
//! The surface loop traces a vertex's continuation ray before its shadow rays
//! and prefetches the next hit's surface record, so that cache miss overlaps
//! the shadow traversals; contributions are added in the original order.
//! Scenes with a medium take the volumetric loop of `volpath.rs`;
//! without one this loop runs unchanged (same bytes).

use glam::Vec3;
use shaders_cpu::bsdf::{Bsdf, BsdfSample};
use shaders_cpu::sampling::{power_heuristic, Frame};

use super::aov::Aov;
use super::denoise_parts::{self, glossy_albedo, DenoiseSample, DenoiseSum};
use super::PathContext;
use crate::accel::{Accel, Hit, Ray};
use crate::geometry::{FrontOrigin, SurfaceInteraction};
use crate::light::LightSet;
use crate::sampler::SampleStream;

mod cone;
mod nee;
mod ris;
mod shadows;
mod state;
pub use cone::RayCone;
pub(super) use nee::ShadowTrRoulette;
use ris::RisSamples;
use shadows::PendingShadows;
pub(super) use state::PathState;
use state::{GlassBranch, GLASS_BRANCH_DIMS};

/// 4D sample sets per bounce: (BSDF u, BSDF v, lobe, roulette), two 2D
/// samples for distant lights 0 and 1, (light choice, light u, light v,
/// unused) for the local light, two 2D samples for distant lights 2 and 3
/// (`MAX_DISTANT` = 4). A set no light needs is not drawn.
const DIMS_PER_BOUNCE: u32 = 4;
/// Offsets in the bounce of the sets of distant lights (0, 1) and (2, 3).
const DISTANT_SETS: [u32; 2] = [1, 3];
/// Offset in the bounce of the local light's set.
const LOCAL_SET: u32 = 2;
/// 4D sets used by the camera before the first bounce (pixel jitter).
pub const CAMERA_DIMS: u32 = 1;
/// The least GGX alpha of a metal or clear-coat lobe after a rough bounce
/// when the scene regularises (`Scene::regularize`): the sun reflected in
/// it then spans about ±6° and next-event estimation finds it.
pub const REGULARIZE_ALPHA: f32 = 0.1;
/// The largest f32 below 1: a lobe number past every lobe's probability.
const ONE_MINUS_EPS: f32 = 1.0 - f32::EPSILON / 2.0;
/// Shadow rays one vertex may leave pending: every distant light plus the
/// sampled light.
const MAX_SHADOW: usize = crate::light::MAX_DISTANT + 1;

/// A camera path stopped after its first surface vertex with that vertex's
/// shadow rays untraced ([`PathContext::start_path`]), so that a chunk of
/// neighbouring paths can trace their coherent shadow rays (the sun's: one
/// direction, nearby origins) as packets before each path goes on
/// ([`PathContext::finish_path`]).
pub struct PathStart {
    st: PathState,
    pending: PendingShadows,
    /// The continuation ray; None once the path has ended.
    next: Option<Ray>,
    /// The whole volumetric path's result, in scenes with a medium.
    volume: Option<LiSample>,
}

impl PathStart {
    /// Appends the path's coherent shadow rays not yet answered to `rays`,
    /// with (`path`, item) to `slots`.
    pub fn collect_coherent(&self, path: usize, rays: &mut Vec<Ray>, slots: &mut Vec<(u32, u8)>) {
        for (k, ray) in self.pending.coherent_rays() {
            rays.push(*ray);
            slots.push((path as u32, k as u8));
        }
    }

    /// Records the answer for the path's shadow ray `item` (from `collect_coherent`).
    pub fn set_occluded(&mut self, item: u8, occluded: bool) {
        self.pending.set_occluded(item as usize, occluded);
    }
}

/// Every sample one surface vertex may use, drawn at the bounce's fixed
/// dimensions. They depend on the stream and the bounce only, so the surface
/// loop draws them before tracing the vertex's shadow rays: their hash chains
/// then run while Embree traverses instead of stalling the shading after it.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct BounceSamples {
    /// BSDF direction.
    u_bsdf: glam::Vec2,
    /// BSDF lobe choice.
    u_lobe: f32,
    /// Russian roulette.
    u_rr: f32,
    /// One 2D sample per distant light.
    u_distant: [glam::Vec2; crate::light::MAX_DISTANT],
    /// The local light's candidates (`ris.rs`).
    u_local: RisSamples,
    /// In a medium, the distant lights' shadow-ray roulette by
    /// transmittance (None: every shadow ray traced; always so without one).
    tr_roulette: Option<ShadowTrRoulette>,
}

impl BounceSamples {
    /// The samples of scattering event `bounces`. Each light set is drawn at
    /// its own fixed dimension and only when a light uses it: outdoors (sun
    /// and sky, no local lights) that is two draws, not four.
    /// `dim_base` offsets every dimension (`PathState::dim_base`).
    fn draw(stream: &mut SampleStream, bounces: u32, dim_base: u32, lights: &LightSet) -> Self {
        let dim = dim_base + CAMERA_DIMS + bounces * DIMS_PER_BOUNCE;
        stream.set_dimension(dim);
        let [u_bx, u_by, u_lobe, u_rr] = stream.next_4d();
        let mut u = BounceSamples {
            u_bsdf: glam::Vec2::new(u_bx, u_by),
            u_lobe,
            u_rr,
            ..Default::default()
        };
        let n_distant = lights.distant_count();
        for (k, pair) in u.u_distant.chunks_mut(2).enumerate() {
            if 2 * k < n_distant {
                stream.set_dimension(dim + DISTANT_SETS[k]);
                let [a0, a1, a2, a3] = stream.next_4d();
                pair.copy_from_slice(&[glam::Vec2::new(a0, a1), glam::Vec2::new(a2, a3)]);
            }
        }
        if !lights.is_empty() {
            stream.set_dimension(dim + LOCAL_SET);
            let first = stream.next_4d();
            let m = lights.local_candidates_at(bounces);
            u.u_local = RisSamples::draw(stream, (bounces, dim_base), first, m);
        }
        u
    }
}

/// What next-event estimation needs of a surface vertex: the interaction,
/// its BSDF and shading frame, `wo` in that frame, and the origin its
/// front-side rays share (every ray a reflecting vertex spawns leaves the
/// front side, so one offset serves its shadow rays and continuation).
#[derive(Clone, Copy)]
struct Vertex<'a> {
    si: &'a SurfaceInteraction,
    bsdf: &'a Bsdf,
    frame: &'a Frame,
    wo_local: Vec3,
    front: FrontOrigin,
}

/// The split vertex's next-event light to filter, when its shadow rays
/// were just resolved: the radiance now less `before`, less the sun's part
/// `sun` (sharp and nearly noise-free: it carries the relief's shading,
/// and at a glossy vertex the sun's highlight, a few pixels of the
/// brightest light in the frame that a filter would smear), zero without
/// a split vertex.
fn split_direct(st: &PathState, before: Vec3, sun: Vec3) -> Vec3 {
    if st.split.rho == Vec3::ZERO && st.split.rho_gloss == Vec3::ZERO {
        Vec3::ZERO
    } else {
        st.l - before - sun
    }
}

/// `d` with the direct-light part: `l_direct` and what it is filtered
/// against (`rho`, or at a glossy split vertex its albedo estimate); and
/// the light along glass's reflection (`l_refl`, `rho_refl`), for a path
/// that has ended.
fn direct_part(st: &PathState, l_direct: Vec3, d: DenoiseSample) -> DenoiseSample {
    let glossy = st.split.rho_gloss != Vec3::ZERO;
    DenoiseSample {
        l_direct,
        rho_direct: if glossy {
            st.split.rho_gloss
        } else {
            st.split.rho
        },
        glossy,
        split_behind_delta: st.split.behind_delta,
        l_refl: st.split.refl_from.map_or(d.l_refl, |l0| st.l - l0),
        rho_refl: st.split.rho_refl,
        rho_refl_hit: st.split.rho_refl_hit,
        ..d
    }
}

/// What a glass reflection's branch shows sharp
/// (`DenoiseSample::l_refl_sharp`), gathered as its path is traced.
struct SharpMirror {
    /// Whether the path is such a branch (else nothing is gathered).
    on_branch: bool,
    /// Whether the vertex whose shadow rays are pending was reached from
    /// the glass through delta scatters only.
    pending: bool,
    /// The light gathered so far.
    l: Vec3,
}

impl SharpMirror {
    fn new(on_branch: bool) -> Self {
        SharpMirror {
            on_branch,
            pending: false,
            l: Vec3::ZERO,
        }
    }

    /// Whether a path in state `st` came from the glass through delta
    /// scatters only.
    fn through_delta(&self, st: &PathState) -> bool {
        self.on_branch && !st.rough_bounce
    }

    /// Light `l` a path in state `st` met along its ray (the sky).
    fn add_seen(&mut self, st: &PathState, l: Vec3) {
        if self.through_delta(st) {
            self.l += l;
        }
    }

    /// Light the pending vertex added: its emission as it is shaded, its
    /// sun's next-event light as its shadow rays are resolved.
    fn add_pending(&mut self, l: Vec3) {
        if self.pending {
            self.l += l;
        }
    }
}

/// Reflection-only BSDFs see both faces of a surface the same way.
fn is_two_sided(bsdf: &Bsdf) -> bool {
    !matches!(bsdf, Bsdf::Dielectric { .. })
}

/// The receiver normal a vertex gives the light tree (`LightSet::select_at`):
/// a reflecting surface receives nothing from below its (front-facing)
/// geometric normal `n_geo`; glass receives from both sides (zero). Light
/// sampling and the BSDF-hit MIS weight must take the same one.
fn receiver_normal(bsdf: &Bsdf, n_geo: Vec3) -> Vec3 {
    if is_two_sided(bsdf) {
        n_geo
    } else {
        Vec3::ZERO
    }
}

/// The radiance of one camera ray and the parts of it the image-space
/// denoiser treats (`crate::denoise`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LiSample {
    /// Total radiance (W·sr⁻¹·m⁻², linear RGB).
    pub l: Vec3,
    /// Its parts split by the first event on the ray (fog light, light on
    /// the first surface) and what they are filtered against.
    pub denoise: DenoiseSample,
    /// The first visible surface's albedo and normal (`aov.rs`).
    pub aov: Aov,
}

impl LiSample {
    /// Adds the path of the glass reflection the camera ray split off
    /// (`PathContext::glass_lobes`): its light is the light along the
    /// glass's reflection, and the first surface it shows adds its albedo
    /// (each carries its lobe's throughput); the normal stays the
    /// refracted path's where that has one.
    fn add_reflection(&mut self, reflected: &LiSample) {
        self.l += reflected.l;
        self.denoise.l_refl += reflected.denoise.l_refl;
        self.denoise.l_refl_sharp += reflected.denoise.l_refl_sharp;
        self.aov.albedo += reflected.aov.albedo;
        if self.aov.normal == Vec3::ZERO {
            self.aov.normal = reflected.aov.normal;
        }
    }
}

/// Running sums of one pixel's samples, field by field.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PixelSum {
    /// Σ `LiSample::l`.
    pub l: Vec3,
    /// Σ `LiSample::denoise`.
    pub denoise: DenoiseSum,
    /// Σ `LiSample::aov`, field by field.
    pub aov: Aov,
}

impl PixelSum {
    /// Adds one sample.
    pub fn add(&mut self, li: &LiSample) {
        self.l += li.l;
        self.denoise.add(&li.denoise);
        self.aov.albedo += li.aov.albedo;
        self.aov.normal += li.aov.normal;
    }
}

impl<A: Accel> PathContext<'_, A> {
    /// Radiance arriving along `ray` (unit direction) of cone `cone` (a
    /// camera ray's: `RenderCamera::cone`); adds traced rays to `rays`.
    pub fn li(
        &self,
        ray: Ray,
        cone: RayCone,
        stream: &mut SampleStream,
        rays: &mut u64,
    ) -> LiSample {
        let hit = self.accel.intersect(&ray);
        self.li_from_hit(ray, hit, cone, stream, rays)
    }

    /// [`PathContext::li`] when the closest hit of `ray` is already known
    /// (e.g. from a packet of camera rays); `first_hit` counts as a traced ray.
    pub fn li_from_hit(
        &self,
        ray: Ray,
        first_hit: Option<Hit>,
        cone: RayCone,
        stream: &mut SampleStream,
        rays: &mut u64,
    ) -> LiSample {
        let start = self.start_path(ray, first_hit, cone, stream, rays);
        self.finish_path(start, stream, rays)
    }

    /// The first part of [`PathContext::li_from_hit`]: the first surface
    /// vertex, its shadow rays left pending. Scenes with a medium run the
    /// whole volumetric path here.
    pub fn start_path(
        &self,
        ray: Ray,
        first_hit: Option<Hit>,
        cone: RayCone,
        stream: &mut SampleStream,
        rays: &mut u64,
    ) -> PathStart {
        let mut st = PathState::new(ray.o);
        st.cone = cone;
        let mut pending = PendingShadows::new();
        if self.scene.medium.is_some() {
            return PathStart {
                volume: Some(self.li_volume(ray, first_hit, cone, stream, rays)),
                st,
                pending,
                next: None,
            };
        }
        *rays += 1;
        let Some(hit) = first_hit else {
            st.l += st.beta
                * self
                    .lights
                    .escaped_at(self.scene, ray.o, ray.d, st.prev_pdf, st.prev_delta);
            return PathStart {
                st,
                pending,
                next: None,
                volume: None,
            };
        };
        self.surfaces.prefetch(self.scene, &hit);
        let u = if st.bounces < self.max_depth {
            BounceSamples::draw(stream, st.bounces, st.dim_base, self.lights)
        } else {
            BounceSamples::default()
        };
        let next = self.surface_vertex_deferred(&ray, &hit, &mut st, &u, rays, &mut pending);
        PathStart {
            st,
            pending,
            next,
            volume: None,
        }
    }

    /// The rest of a path begun by [`PathContext::start_path`]: its radiance,
    /// with the reflection of the glass its camera ray met first traced
    /// after it ([`PathContext::glass_lobes`]).
    pub fn finish_path(
        &self,
        start: PathStart,
        stream: &mut SampleStream,
        rays: &mut u64,
    ) -> LiSample {
        let (mut sample, branch) = self.finish_refracted(start, stream, rays);
        if let Some(branch) = branch {
            let reflected = self.finish_path(
                PathStart {
                    st: PathState::of_glass_branch(&branch),
                    pending: PendingShadows::new(),
                    next: Some(branch.ray),
                    volume: None,
                },
                stream,
                rays,
            );
            sample.add_reflection(&reflected);
        }
        sample
    }

    /// [`PathContext::finish_path`] for the path alone, with the glass
    /// reflection it left to trace, if any.
    fn finish_refracted(
        &self,
        start: PathStart,
        stream: &mut SampleStream,
        rays: &mut u64,
    ) -> (LiSample, Option<GlassBranch>) {
        let PathStart {
            mut st,
            mut pending,
            next,
            volume,
        } = start;
        if let Some(sample) = volume {
            return (sample, None);
        }
        let Some(mut ray) = next else {
            let before = st.l;
            let sun = pending.resolve(self.accel, &mut st.l);
            let l_direct = split_direct(&st, before, sun);
            let sample = LiSample {
                l: st.l,
                denoise: direct_part(
                    &st,
                    l_direct,
                    DenoiseSample {
                        rho: st.split.rho,
                        openness: 1.0,
                        ..DenoiseSample::default()
                    },
                ),
                aov: st.aov.aov,
            };
            return (sample, st.glass_branch);
        };
        // The radiance once the first vertex's own light is in: what
        // follows is its indirect part (`DenoiseSample::l_surf`); and that
        // vertex's next-event estimates (`DenoiseSample::l_direct`).
        let mut l_first = None;
        let mut l_direct = Vec3::ZERO;
        // At a glossy split vertex: the radiance before its shadow rays,
        // and their sun's part.
        let mut gloss_before = None;
        // The split vertex's bounce: how freely its ray left (1 untraced).
        let mut openness = 1.0;
        // On a glass reflection's branch, what it shows sharp
        // (`DenoiseSample::l_refl_sharp`); and whether the vertex whose
        // shadow rays are pending was reached through delta scatters only.
        let mut sharp = SharpMirror::new(st.dim_base == GLASS_BRANCH_DIMS);
        loop {
            *rays += 1;
            let hit = self.accel.intersect(&ray);
            let mut u = BounceSamples::default();
            if let Some(hit) = &hit {
                self.surfaces.prefetch(self.scene, hit);
                if st.bounces < self.max_depth {
                    u = BounceSamples::draw(stream, st.bounces, st.dim_base, self.lights);
                }
            }
            // The previous vertex's shadow rays, while the record loads.
            let before = st.l;
            let sun = pending.resolve(self.accel, &mut st.l);
            sharp.add_pending(sun);
            if st.split.rho != Vec3::ZERO && l_first.is_none() {
                // This ray is the split vertex's bounce.
                openness = denoise_parts::openness(hit.as_ref().map(|h| h.t * ray.d.length()));
                l_first = Some(st.l);
                l_direct = split_direct(&st, before, sun);
            }
            if st.split.rho_gloss != Vec3::ZERO {
                gloss_before.get_or_insert((before, sun));
            }
            let Some(hit) = hit else {
                let before = st.l;
                st.l += st.beta
                    * self
                        .lights
                        .escaped_at(self.scene, ray.o, ray.d, st.prev_pdf, st.prev_delta);
                sharp.add_seen(&st, st.l - before);
                break;
            };
            let before = st.l;
            sharp.pending = sharp.through_delta(&st);
            let next = self.surface_vertex_deferred(&ray, &hit, &mut st, &u, rays, &mut pending);
            // Its emission (its next-event light is pending).
            sharp.add_pending(st.l - before);
            match next {
                Some(next) => ray = next,
                None => {
                    let before = st.l;
                    let sun = pending.resolve(self.accel, &mut st.l);
                    sharp.add_pending(sun);
                    if l_first.is_none() {
                        l_direct = split_direct(&st, before, sun);
                    }
                    if st.split.rho_gloss != Vec3::ZERO {
                        gloss_before.get_or_insert((before, sun));
                    }
                    break;
                }
            }
        }
        // No l_first with a split vertex: the path ended there, after its
        // own light, so its indirect estimate is zero.
        let l_surf = l_first.map_or(Vec3::ZERO, |l_first| st.l - l_first);
        // A glossy split vertex's light: all it reflects but the sun's
        // next-event estimate.
        if let Some((before, sun)) = gloss_before {
            l_direct = st.l - before - sun;
        }
        let (l_refl, l_refl_sharp) = if sharp.on_branch {
            (st.l - sharp.l, sharp.l)
        } else {
            (Vec3::ZERO, Vec3::ZERO)
        };
        let sample = LiSample {
            l: st.l,
            denoise: direct_part(
                &st,
                l_direct,
                DenoiseSample {
                    l_refl,
                    l_refl_sharp,
                    l_surf,
                    rho: st.split.rho,
                    split_behind_delta: st.split.behind_delta,
                    openness,
                    ..DenoiseSample::default()
                },
            ),
            aov: st.aov.aov,
        };
        (sample, st.glass_branch)
    }

    /// Both lobes of the smooth glass a camera ray meets first, where the
    /// image filters are on and there is no medium: (reflection,
    /// refraction), each with pdf 1, so f·|cos θi| is its whole share
    /// (the Fresnel reflectance, the tinted transmittance) instead of a
    /// share chosen by chance. The path goes on through the glass and the
    /// reflection is traced as a branch of its own (`finish_path`), so
    /// every sample sees both what the window mirrors and what is behind
    /// it. None elsewhere, and where only one lobe exists (total internal
    /// reflection).
    fn glass_lobes(
        &self,
        bounces: u32,
        vertex: &Vertex,
        u: glam::Vec2,
    ) -> Option<(BsdfSample, BsdfSample)> {
        // Bounce 0: the camera's own hit (a branch starts at bounce 1).
        if bounces > 0 || !self.scene.filter_indirect || self.scene.medium.is_some() {
            return None;
        }
        if !matches!(vertex.bsdf, Bsdf::Dielectric { .. }) || !vertex.bsdf.is_delta() {
            return None;
        }
        let wo = vertex.wo_local;
        // The smooth interface reflects below its reflection probability
        // and refracts above it (`dielectric::sample_smooth`).
        let reflected = vertex.bsdf.sample(wo, 0.0, u)?;
        let refracted = vertex.bsdf.sample(wo, ONE_MINUS_EPS, u)?;
        if reflected.wi.z * wo.z <= 0.0 || refracted.wi.z * wo.z >= 0.0 {
            return None;
        }
        let whole = |s: BsdfSample| BsdfSample { pdf: 1.0, ..s };
        Some((whole(reflected), whole(refracted)))
    }

    /// One surface vertex: emission (MIS-weighted), NEE, BSDF sampling and
    /// roulette, its distant lights' shadow rays under `tr_roulette` when
    /// given. Returns the continuation ray (None when the path ends),
    /// the suns' next-event part of the light it added, and the radiance
    /// before its next-event estimates (its emission in).
    pub(super) fn surface_vertex(
        &self,
        ray: &Ray,
        hit: &Hit,
        st: &mut PathState,
        stream: &mut SampleStream,
        rays: &mut u64,
        tr_roulette: Option<ShadowTrRoulette>,
    ) -> (Option<Ray>, Vec3, Vec3) {
        let mut pending = PendingShadows::new();
        let mut u = if st.bounces < self.max_depth {
            BounceSamples::draw(stream, st.bounces, st.dim_base, self.lights)
        } else {
            BounceSamples::default()
        };
        u.tr_roulette = tr_roulette;
        let next = self.surface_vertex_deferred(ray, hit, st, &u, rays, &mut pending);
        let before = st.l;
        let sun = pending.resolve(self.accel, &mut st.l);
        (next, sun, before)
    }

    /// [`PathContext::surface_vertex`] with the NEE shadow rays left in
    /// `pending` (empty on entry) instead of traced; their contributions are
    /// added when it is resolved, before anything the next vertex adds.
    /// `u` holds this bounce's samples (unused once `max_depth` is reached).
    fn surface_vertex_deferred(
        &self,
        ray: &Ray,
        hit: &Hit,
        st: &mut PathState,
        u: &BounceSamples,
        rays: &mut u64,
        pending: &mut PendingShadows,
    ) -> Option<Ray> {
        let scene = self.scene;
        let mut si = self.surfaces.interaction(scene, ray, hit);
        let wo = -ray.d;
        let mat = &scene.materials[si.material as usize];
        let cos_o = wo.dot(si.n_geo);
        let front = cos_o > 0.0;
        if mat.le != Vec3::ZERO && (front || mat.two_sided_emission) {
            let w = if st.prev_delta {
                1.0
            } else {
                let pdf_l = self.lights.pdf_triangle(
                    hit.geom_id,
                    hit.prim_id,
                    (st.prev_p, st.prev_n, st.bounces - 1),
                    si.p,
                    si.n_geo,
                );
                power_heuristic(1.0, st.prev_pdf, 1.0, pdf_l)
            };
            st.l += st.beta * mat.le * w;
        }
        if st.bounces == self.max_depth {
            return None;
        }
        // Seen through delta bounces: textured, filtered by the pixel's
        // footprint here (only a seen hit is textured); the cone goes on
        // through a delta bounce.
        let dist = hit.t;
        let footprint = if st.prev_delta {
            st.cone.footprint(dist, cos_o)
        } else {
            0.0
        };
        let mut bsdf = scene
            .material_view()
            .bsdf_filtered(&si, wo, st.prev_delta, footprint);
        if scene.regularize && st.rough_bounce {
            bsdf = bsdf.regularized(REGULARIZE_ALPHA);
        }
        if is_two_sided(&bsdf) && !front {
            si.n_geo = -si.n_geo;
            si.n_shading = -si.n_shading;
        }
        st.aov
            .at_vertex(st.prev_delta, st.beta, &bsdf, si.n_shading);
        if st.split.ahead && !bsdf.is_delta() {
            st.split.ahead = false;
            st.split_albedo = bsdf.diffuse_albedo();
            st.split_glossy = glossy_albedo(&bsdf).filter(|_| mat.le == Vec3::ZERO);
            if let (true, Some(albedo)) = (scene.filter_indirect, bsdf.diffuse_albedo()) {
                st.split.rho = st.beta * albedo;
                st.split.behind_delta = st.bounces > 0;
            } else if let (true, Some(albedo)) = (scene.filter_indirect, glossy_albedo(&bsdf)) {
                st.split.rho_gloss = st.beta * albedo;
                st.split.behind_delta = st.bounces > 0;
            }
        }
        // A relief's perturbed normal is a microsurface on the geometric
        // normal (Schüssler et al. 2017, `bsdf::normal_map`), not a frame.
        let frame = match bsdf {
            Bsdf::NormalMapped { .. } => Frame::from_z(si.n_geo),
            _ => Frame::from_z(si.n_shading),
        };
        let bsdf = bsdf.in_frame(&frame);
        let vertex = Vertex {
            wo_local: frame.to_local(wo),
            front: si.front_origin(),
            si: &si,
            bsdf: &bsdf,
            frame: &frame,
        };
        if !bsdf.is_delta() {
            let lights = self.lights;
            for (k, &u_light) in u.u_distant.iter().enumerate().take(lights.distant_count()) {
                // The radiance (sky, cloud deck) only for samples kept.
                let ls = lights.sample_distant_dir(scene, k, si.p, u_light);
                self.direct(&vertex, (k, u.tr_roulette), ls, st.beta, pending, rays);
            }
            if !lights.is_empty() {
                self.direct_local(&vertex, &u.u_local, st.beta, pending, rays);
            }
        }
        let glass = self.glass_lobes(st.bounces, &vertex, u.u_bsdf);
        let bs = match glass {
            Some((_, refracted)) => refracted,
            None => bsdf.sample(vertex.wo_local, u.u_lobe, u.u_bsdf)?,
        };
        if bs.pdf <= 0.0 {
            return None;
        }
        // The throughput's factor for this bounce, f·|cos θi|/pdf.
        let weight = bs.f * bs.wi.z.abs() / bs.pdf;
        if let Some((reflected, _)) = glass {
            let r = reflected.f * reflected.wi.z.abs();
            st.split.split_glass(r, st.beta);
            let ray = vertex.front.spawn_ray(&si, frame.from_local(reflected.wi));
            let cone = st.cone.through_delta(dist);
            st.glass_branch = Some(GlassBranch {
                ray,
                beta: st.beta * r,
                p: si.p,
                cone,
            });
        } else if st.split.ahead && (scene.filter_indirect || scene.filter_inscatter) {
            // In fog too: glass's reflection is filtered apart there as well.
            st.split
                .at_glass(&bsdf, vertex.wo_local, bs.wi, weight, st.beta, st.l);
        }
        // Glass's reflection is not followed to a split vertex: its light
        // would be filtered with that of the refracted samples behind it
        // (it is filtered apart: `SplitVertex::at_glass`).
        if st.split.ahead && !is_two_sided(&bsdf) && bs.wi.z * vertex.wo_local.z > 0.0 {
            st.split.ahead = false;
        }
        let wi = frame.from_local(bs.wi);
        // Reflection-only surfaces must not send light through the geometry.
        if is_two_sided(&bsdf) && wi.dot(si.n_geo) <= 0.0 {
            return None;
        }
        st.beta *= weight;
        if !st.beta.is_finite() || st.beta == Vec3::ZERO {
            return None;
        }
        st.prev_pdf = bs.pdf;
        st.prev_delta = bs.delta;
        st.rough_bounce |= !bs.delta;
        st.cone = st.cone.through_delta(dist);
        st.prev_p = si.p;
        st.prev_n = receiver_normal(&bsdf, si.n_geo);
        st.bounces += 1;
        if !st.survives_roulette(u.u_rr) {
            return None;
        }
        Some(vertex.front.spawn_ray(&si, wi))
    }
}

#[cfg(test)]
mod glass_tests;
#[cfg(test)]
mod regularize_tests;
#[cfg(test)]
mod tests;
