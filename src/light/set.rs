//! The lights next-event estimation samples. Distant lights (suns and, where
//! it pays, the sky: `MAX_DISTANT` in all) are sampled at every vertex:
//! outdoors they are the only direct light, and one-sample selection would
//! give the sky a small share next to the sun. The sky joins them only where
//! it pays for its shadow ray. Under a sun and without a medium its NEE draws
//! nearly the cosine lobe BSDF sampling already draws: without it (escaped
//! rays then get full weight) the street's path time fell by 28–44 % for
//! 2–18 % more variance (60 % under broken cloud): 20–70 % more efficient
//! (1 / variance × time) in clear, sunset and night weather, within the noise
//! (±14 %) under broken cloud. Without a sun (overcast) the sky is the whole
//! light and keeps NEE; with a medium, medium vertices need it (a phase
//! function does not favour the sky) and its tables carry the fog's
//! transmittance. Local lights (point, spot, emissive triangles) are selected
//! one per vertex by a light BVH (`bvh.rs`, Conty Estevez & Kulla 2018) from
//! the shading point, each walk starting from the tree's cut for the cell
//! of space holding the point (`cuts.rs`, `bvh/cut.rs`); suns beyond `MAX_DISTANT` take a uniform share beside
//! the tree (pbrt-v4's `BVHLightSampler`). The older point-independent
//! selection (half by power, half uniform) and uniform selection stay
//! available as [`LightSelection`] kinds. Probabilities returned include the
//! selection pmf (1 for distant lights), so callers combine them directly in
//! MIS weights.

use glam::{Vec2, Vec3};
use shaders_cpu::sampling::power_heuristic;

use super::bvh::{LightBounds, LightBvh};
use super::emitter::Emitters;
pub use super::entry::LightSample;
use super::entry::{cloud_transmittance, sample_entry, Entry};
use super::fog_sky::FogSky;
use super::Light;
use crate::scene::Scene;

/// How one local light is chosen per vertex.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LightSelection {
    /// Light BVH, by a bound of each light's contribution at the point.
    #[default]
    Bvh,
    /// Independent of the point: half by emitted power, half uniform.
    Power,
    /// Independent of the point: uniform over local lights.
    Uniform,
}

/// Most distant lights sampled at every vertex; further suns join the
/// selected (local) group.
pub const MAX_DISTANT: usize = 4;

/// All lights of a scene with their selection distribution.
#[derive(Clone, Debug)]
pub struct LightSet {
    /// Sampled at every vertex (pmf 1).
    distant: Vec<Entry>,
    /// One of these is selected per vertex.
    entries: Vec<Entry>,
    selection: LightSelection,
    /// Point-independent selection (half power, half uniform; uniform for
    /// `LightSelection::Uniform`).
    cdf: Vec<f32>,
    pmf: Vec<f32>,
    /// The tree over local lights other than suns (index = entry index).
    bvh: LightBvh,
    /// Entry indices of the suns among the local lights (BVH selection).
    local_suns: Vec<u32>,
    /// Probability of picking one of `local_suns` rather than the tree.
    p_suns: f32,
    /// pmf of the sky (1 when NEE samples it, else 0).
    sky_pmf: f32,
    /// Sky tables weighted by the fog's transmittance (scenes with a medium).
    fog_sky: Option<FogSky>,
    /// Every sun, for rays that escape into one.
    suns: Vec<SunDisk>,
    /// Per mesh, the index in `emitters` of each triangle (`u32::MAX`:
    /// none; empty for non-emissive meshes).
    tri_index: Vec<Vec<u32>>,
    /// The emitters' triangles.
    emitters: Emitters,
    /// Whether a local light is a point or spot light (equiangular
    /// sampling's lights).
    delta_local: bool,
    /// Candidates per vertex and the probability that a vertex samples the
    /// local lights at all (the rest skip them; the pmfs include it, so the
    /// estimate keeps its mean).
    budget: LocalBudget,
    /// This set's number for the cache of its tree's cuts (`cuts.rs`).
    cut_set: u64,
}

/// Area and unit normal of a triangle.
fn triangle_geometry(scene: &Scene, geom: u32, prim: u32) -> (f32, Vec3, [Vec3; 3]) {
    let m = &scene.meshes[geom as usize];
    let v = m.triangles[prim as usize].map(|i| m.p_f32[i as usize]);
    let cross = (v[1] - v[0]).cross(v[2] - v[0]);
    let len = cross.length();
    (0.5 * len, cross / len, v)
}

/// Where a BVH selection's number goes ([`LightSet::route`]).
enum Route {
    /// This vertex skips the local lights.
    Skip,
    /// A local sun: (entry, pmf).
    Sun((usize, f32)),
    /// The light tree, with this number.
    Tree(f32),
}

impl LightSet {
    /// Collects every light of `scene`, local lights chosen by a light BVH.
    pub fn build(scene: &Scene) -> Self {
        Self::build_with(scene, LightSelection::Bvh)
    }

    /// Collects every light of `scene` with local lights chosen by `selection`.
    pub fn build_with(scene: &Scene, selection: LightSelection) -> Self {
        let sky_emits = scene.sky.luminance_avg() > 0.0;
        let has_sun = scene.lights.iter().any(|l| matches!(l, Light::Sun { .. }));
        // Where NEE of the sky pays for its shadow ray (module docs).
        let sky_sampled = sky_emits && (scene.medium.is_some() || !has_sun);
        let radius = scene_radius(scene);
        let mut c = Collected::default();
        c.add_explicit(scene, MAX_DISTANT - sky_sampled as usize, radius);
        if sky_sampled {
            c.distant.push(Entry::Sky);
        }
        let tri_index = c.add_emissive_triangles(scene);
        let Collected {
            distant,
            entries,
            weights,
            bounds,
            suns,
            emitters,
        } = c;
        let pmf = if selection == LightSelection::Uniform {
            vec![1.0 / weights.len().max(1) as f32; weights.len()]
        } else {
            selection_pmf(&weights)
        };
        let bvh = LightBvh::build(&bounds);
        let local_suns: Vec<u32> = (0..entries.len() as u32)
            .filter(|&i| matches!(entries[i as usize], Entry::Explicit(Light::Sun { .. })))
            .collect();
        let n_suns = local_suns.len() as f32;
        let p_suns = n_suns / (n_suns + if bvh.is_empty() { 0.0 } else { 1.0 }).max(1.0);
        let mut acc = 0.0f64;
        let cdf = pmf
            .iter()
            .map(|&p| {
                acc += p as f64;
                acc as f32
            })
            .collect();
        let delta_local = entries
            .iter()
            .any(|e| matches!(e, Entry::Explicit(Light::Point { .. } | Light::Spot { .. })));
        let local_power: f32 = weights.iter().map(|w| w.max(0.0)).sum();
        let distant_power = distant_power(scene, radius);
        let share = local_power / (local_power + distant_power).max(f32::MIN_POSITIVE);
        let budget = LocalBudget::new(
            share,
            selection == LightSelection::Bvh,
            !local_suns.is_empty(),
        );
        let suns = suns
            .into_iter()
            .map(|(disk, local)| SunDisk {
                pmf: match (local, selection) {
                    (None, _) => 1.0,
                    (Some(_), LightSelection::Bvh) => p_suns / n_suns * budget.p_first,
                    (Some(i), _) => pmf[i],
                },
                ..disk
            })
            .collect();
        LightSet {
            delta_local,
            budget,
            distant,
            entries,
            selection,
            cdf,
            pmf,
            bvh,
            local_suns,
            p_suns,
            sky_pmf: if sky_sampled { 1.0 } else { 0.0 },
            fog_sky: scene
                .medium
                .filter(|_| sky_sampled)
                .map(|m| FogSky::new(m, |d| scene.sky.le(d))),
            suns,
            tri_index,
            emitters,
            cut_set: cuts::next_set(),
        }
    }

    /// Number of distant lights sampled at every vertex (≤ `MAX_DISTANT`).
    pub fn distant_count(&self) -> usize {
        self.distant.len()
    }

    /// Whether distant light `k` is directional (a sun: every shadow ray
    /// towards it from nearby points is nearly parallel).
    pub fn distant_is_directional(&self, k: usize) -> bool {
        matches!(self.distant[k], Entry::Sun(_))
    }

    /// Whether a local light is a point or spot light.
    pub fn has_delta_local(&self) -> bool {
        self.delta_local
    }

    /// Candidates NEE resamples the local light from at a path's first
    /// vertex (≤ [`LOCAL_CANDIDATES`]): all of them where the local lights
    /// bring at least `LOCAL_SHARE_FOR_RIS` of the emitted power, else one.
    pub fn local_candidates(&self) -> usize {
        self.budget.candidates
    }

    /// Candidates at a vertex after `bounce` scattering events: the first
    /// vertex's [`LightSet::local_candidates`], fewer at later ones
    /// (`share::LOCAL_CANDIDATES_DEEP`).
    pub fn local_candidates_at(&self, bounce: u32) -> usize {
        if bounce == 0 {
            self.budget.candidates
        } else {
            self.budget.candidates_deep
        }
    }

    /// Number of local lights one is selected from.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether there are no local lights.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    fn select(&self, u: f32) -> usize {
        let i = self.cdf.partition_point(|&c| c <= u);
        i.min(self.entries.len() - 1)
    }

    /// Samples distant light `k` (< `distant_count()`) as seen from `p`.
    /// Under fog the sky is drawn ∝ its luminance times the fog's
    /// transmittance from `p` (see `fog_sky.rs`).
    pub fn sample_distant(&self, scene: &Scene, k: usize, p: Vec3, u: Vec2) -> Option<LightSample> {
        match (&self.distant[k], &self.fog_sky) {
            (Entry::Sky, Some(fs)) => {
                let (wi, pdf) = fs.table_at(p).sample(u);
                (pdf > 0.0).then(|| LightSample {
                    wi,
                    li: scene.sky.le(wi),
                    pdf,
                    dist: f32::INFINITY,
                    delta: false,
                })
            }
            (entry, _) => sample_entry(scene, &self.emitters, entry, 1.0, p, u),
        }
    }

    /// [`LightSet::sample_distant`] with the radiance left out (`li` is
    /// zero): [`LightSet::distant_li`] gives it for the drawn direction, the
    /// same bits, so a caller can skip it (sky tables, the cloud deck) for
    /// samples it rejects first.
    pub fn sample_distant_dir(
        &self,
        scene: &Scene,
        k: usize,
        p: Vec3,
        u: Vec2,
    ) -> Option<LightSample> {
        self.sample_distant_dir_if(scene, k, p, u, |_, _| true)
    }

    /// [`LightSet::sample_distant_dir`], None where the fog-weighted sky
    /// table's drawn row is declined by `row_kept` (its z range; other
    /// distant lights ignore it): `SkyDistribution::sample_if_row`.
    pub fn sample_distant_dir_if(
        &self,
        scene: &Scene,
        k: usize,
        p: Vec3,
        u: Vec2,
        row_kept: impl FnOnce(f32, f32) -> bool,
    ) -> Option<LightSample> {
        let (wi, pdf) = match (&self.distant[k], &self.fog_sky) {
            (Entry::Sky, Some(fs)) => fs.table_at(p).sample_if_row(u, row_kept)?,
            (Entry::Sky, None) => scene.sky.sample_dir(u),
            (Entry::Sun(sun), _) => {
                let (wi, _, pdf) = sun.sample(u);
                (wi, pdf)
            }
            _ => unreachable!("distant lights are suns and the sky"),
        };
        (pdf > 0.0).then_some(LightSample {
            wi,
            li: Vec3::ZERO,
            pdf,
            dist: f32::INFINITY,
            delta: false,
        })
    }

    /// Radiance of distant light `k` arriving at `p` from `wi` (drawn by
    /// [`LightSet::sample_distant_dir`]): the sky's, or the sun's dimmed by
    /// the cloud deck at `p`.
    pub fn distant_li(&self, scene: &Scene, k: usize, p: Vec3, wi: Vec3) -> Vec3 {
        match &self.distant[k] {
            Entry::Sky => scene.sky.le(wi),
            Entry::Sun(sun) => sun.le() * cloud_transmittance(scene, p, wi),
            _ => unreachable!("distant lights are suns and the sky"),
        }
    }

    /// Pdf per solid angle (with pmf) that NEE from `p` draws sky direction `dir`.
    pub fn sky_pdf(&self, scene: &Scene, p: Vec3, dir: Vec3) -> f32 {
        match &self.fog_sky {
            Some(fs) => self.sky_pmf * fs.table_at(p).pdf(dir),
            None => self.sky_pmf * scene.sky.pdf(dir),
        }
    }

    /// Which selection the set uses for [`LightSet::sample`].
    pub fn selection(&self) -> LightSelection {
        self.selection
    }

    /// Chooses a local light for point `p` with `u_select` ∈ [0, 1):
    /// (entry index, selection pmf), or None when no light can reach `p`.
    /// `n`: the unit normal of a receiver that reflects only, on the side
    /// it reflects (the tree then weighs lights by their cosine to it;
    /// [`crate::light::bvh::LightBounds::importance_facing`]), or zero.
    /// `bounce`: the scattering events of the path before this vertex
    /// ([`LightSet::p_local_at`]).
    pub fn select_at(&self, p: Vec3, n: Vec3, u_select: f32, bounce: u32) -> Option<(usize, f32)> {
        if self.entries.is_empty() {
            return None;
        }
        if self.selection != LightSelection::Bvh {
            let idx = self.select(u_select);
            return (self.pmf[idx] > 0.0).then_some((idx, self.pmf[idx]));
        }
        match self.route(u_select, bounce) {
            Route::Skip => None,
            Route::Sun(pick) => Some(pick),
            Route::Tree(u) => {
                let [walked] = self.walk_tree((p, n), [Some(u)], bounce);
                walked.map(|w| self.tree_pick(w, bounce))
            }
        }
    }

    /// Where `u_select` sends a BVH selection at a vertex after `bounce`
    /// events: vertices past `p_local` skip the local lights; the rest
    /// reuse the number rescaled, for a local sun or for the tree.
    fn route(&self, u_select: f32, bounce: u32) -> Route {
        let p_local = self.p_local_at(bounce);
        if u_select >= p_local {
            return Route::Skip;
        }
        let u_select = u_select / p_local;
        if u_select < self.p_suns {
            let n = self.local_suns.len();
            let k = ((u_select / self.p_suns * n as f32) as usize).min(n - 1);
            return Route::Sun((
                self.local_suns[k] as usize,
                self.p_suns / n as f32 * p_local,
            ));
        }
        Route::Tree(((u_select - self.p_suns) / (1.0 - self.p_suns)).clamp(0.0, 1.0 - f32::EPSILON))
    }

    /// The tree's choice for each number of `us` at receiver `p`, normal
    /// `n`: walks from the cut of the cell holding `p` (`cuts.rs`).
    fn walk_tree<const M: usize>(
        &self,
        (p, n): (Vec3, Vec3),
        us: [Option<f32>; M],
        bounce: u32,
    ) -> [Option<(u32, f32)>; M] {
        if us.iter().all(Option::is_none) || self.bvh.is_empty() {
            return [None; M];
        }
        cuts::with_cut((self.cut_set, &self.bvh), (p, n), bounce, |cut| {
            self.bvh.sample_in_cut(cut, (p, n), us)
        })
    }

    /// The probability that [`LightSet::walk_tree`] returns `light`.
    fn tree_pmf(&self, (p, n): (Vec3, Vec3), light: u32, bounce: u32) -> f32 {
        if self.bvh.is_empty() {
            return 0.0;
        }
        cuts::with_cut((self.cut_set, &self.bvh), (p, n), bounce, |cut| {
            self.bvh.pmf_in_cut(cut, (p, n), light)
        })
    }

    /// A tree walk's (entry, pmf) as a selection: the pmf times the
    /// probability of walking the tree at all.
    fn tree_pick(&self, (idx, pmf): (u32, f32), bounce: u32) -> (usize, f32) {
        (
            idx as usize,
            pmf * (1.0 - self.p_suns) * self.p_local_at(bounce),
        )
    }

    /// [`LightSet::select_at`] for each number of `us` (None: no choice):
    /// what each gives alone, bit for bit, the light tree walked for all
    /// of them at once ([`LightBvh::sample_facing_many`]).
    pub fn select_many<const M: usize>(
        &self,
        (p, n): (Vec3, Vec3),
        us: [Option<f32>; M],
        bounce: u32,
    ) -> [Option<(usize, f32)>; M] {
        if self.selection != LightSelection::Bvh || self.entries.is_empty() {
            return us.map(|u| u.and_then(|u| self.select_at(p, n, u, bounce)));
        }
        let mut picks = [None; M];
        let mut tree = [None; M];
        for ((u, pick), t) in us.iter().zip(picks.iter_mut()).zip(tree.iter_mut()) {
            match u.map(|u| self.route(u, bounce)) {
                None | Some(Route::Skip) => {}
                Some(Route::Sun(sun)) => *pick = Some(sun),
                Some(Route::Tree(u)) => *t = Some(u),
            }
        }
        let walked = self.walk_tree((p, n), tree, bounce);
        for (pick, w) in picks.iter_mut().zip(walked) {
            if let Some(w) = w {
                *pick = Some(self.tree_pick(w, bounce));
            }
        }
        picks
    }

    /// Samples local light `idx` chosen with probability `pmf` (by
    /// [`LightSet::select_many`]) as seen from `p`.
    pub fn sample_picked(
        &self,
        scene: &Scene,
        (idx, pmf): (usize, f32),
        p: Vec3,
        u: Vec2,
    ) -> Option<LightSample> {
        sample_entry(scene, &self.emitters, &self.entries[idx], pmf, p, u)
    }

    /// Probability that a vertex after `bounce` scattering events samples
    /// the local lights at all (BVH selection; 1 for the others).
    pub fn p_local_at(&self, bounce: u32) -> f32 {
        self.budget.p_local(bounce)
    }

    /// Probability that [`LightSet::select_at`] at `p` for receiver normal
    /// `n` after `bounce` scattering events returns local light `idx` (the
    /// same value it returns with it).
    pub fn pmf_at(&self, p: Vec3, n: Vec3, idx: usize, bounce: u32) -> f32 {
        let p_local = self.p_local_at(bounce);
        match self.selection {
            _ if idx >= self.entries.len() => 0.0,
            LightSelection::Bvh => match self.entries[idx] {
                Entry::Explicit(Light::Sun { .. }) => {
                    self.p_suns / self.local_suns.len() as f32 * p_local
                }
                _ => self.tree_pmf((p, n), idx as u32, bounce) * (1.0 - self.p_suns) * p_local,
            },
            _ => self.pmf[idx],
        }
    }

    /// Selects one local light for `p` after `bounce` scattering events (by
    /// the set's [`LightSelection`]) and samples it as seen from `p`.
    pub fn sample(
        &self,
        scene: &Scene,
        p: Vec3,
        u_select: f32,
        u: Vec2,
        bounce: u32,
    ) -> Option<LightSample> {
        self.sample_facing(scene, (p, Vec3::ZERO), u_select, u, bounce)
    }

    /// [`LightSet::sample`] for a receiver at `p` of normal `n` (see
    /// [`LightSet::select_at`]).
    pub fn sample_facing(
        &self,
        scene: &Scene,
        (p, n): (Vec3, Vec3),
        u_select: f32,
        u: Vec2,
        bounce: u32,
    ) -> Option<LightSample> {
        let (idx, pmf) = self.select_at(p, n, u_select, bounce)?;
        sample_entry(scene, &self.emitters, &self.entries[idx], pmf, p, u)
    }

    /// Radiance of the sky and sun disks for a ray leaving render-space point
    /// `p` along `dir`, sampled with solid-angle pdf `prev_pdf` (or by a delta
    /// lobe / the camera), MIS-weighted against next-event estimation. Sun
    /// disks are dimmed by the cloud deck's transmittance at `p`, exactly as
    /// next-event estimation dims them, so MIS stays unbiased under clouds.
    pub fn escaped_at(
        &self,
        scene: &Scene,
        p: Vec3,
        dir: Vec3,
        prev_pdf: f32,
        prev_delta: bool,
    ) -> Vec3 {
        let weight = |pdf_light: f32| {
            if prev_delta {
                1.0
            } else {
                power_heuristic(1.0, prev_pdf, 1.0, pdf_light)
            }
        };
        let mut l = scene.sky.le(dir);
        // MIS only where NEE samples the sky too (else full weight).
        if !prev_delta && self.sky_pmf > 0.0 && l != Vec3::ZERO {
            l *= weight(self.sky_pdf(scene, p, dir));
        }
        for sun in &self.suns {
            if sun.cone.contains(sun.axis, dir) {
                let clouds = cloud_transmittance(scene, p, dir);
                l += sun.le * clouds * weight(sun.pmf * sun.cone.pdf());
            }
        }
        l
    }

    /// Pdf per solid angle (with pmf) that NEE would have chosen point `q` on
    /// emissive triangle (geom, prim) of a flat mesh, seen from `p` (receiver
    /// normal `n`, as [`LightSet::select_at`] takes it, after `bounce`
    /// scattering events) with light normal `n_light`. Emitters are never instanced (`scene::instancing`
    /// flattens prefabs with emissive materials), so a hit on an emitter
    /// always names a flat mesh.
    pub fn pdf_triangle(
        &self,
        geom: u32,
        prim: u32,
        (p, n, bounce): (Vec3, Vec3, u32),
        q: Vec3,
        n_light: Vec3,
    ) -> f32 {
        let Some(&t) = self
            .tri_index
            .get(geom as usize)
            .and_then(|v| v.get(prim as usize))
        else {
            return 0.0;
        };
        if t == u32::MAX {
            return 0.0;
        }
        let idx = self.emitters.entry_of(t) as usize;
        let Entry::Emitter {
            first,
            end,
            two_sided,
            ..
        } = self.entries[idx]
        else {
            return 0.0;
        };
        let area = self.emitters.area(t);
        let d = q - p;
        let dist2 = d.length_squared();
        let cos_l = n_light.dot(d).abs() / dist2.sqrt();
        if cos_l == 0.0 || area == 0.0 {
            return 0.0;
        }
        let pmf = self.pmf_at(p, n, idx, bounce) * self.emitters.pmf(first..end, two_sided, p, t);
        pmf * dist2 / (cos_l * area)
    }
}

mod collect;
mod cuts;
use collect::{Collected, SunDisk};
mod global;
mod share;
use share::LocalBudget;
pub use share::LOCAL_CANDIDATES;
mod weights;
use weights::{distant_power, scene_radius, selection_pmf};

#[cfg(test)]
mod tests;
