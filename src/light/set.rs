//! The lights next-event estimation samples. Distant lights (the sky and up to
//! `MAX_DISTANT − 1` suns) are sampled at every vertex: outdoors they are the
//! only light in every shadow, and one-sample selection would give the sky a
//! small share next to the sun. Local lights (point, spot, emissive triangles)
//! are selected one per vertex, half in proportion to emitted power
//! (pbrt-v4's `PowerLightSampler`), half uniformly. Probabilities returned
//! include the selection pmf (1 for distant lights), so callers combine them
//! directly in MIS weights.

use glam::{Vec2, Vec3};
use shaders_cpu::sampling::{
    luminance, power_heuristic, sample_uniform_triangle, uniform_cone_pdf,
};

use super::{power, sample_explicit, sun_radiance, Light};
use crate::scene::Scene;

/// One entry the sampler can pick.
#[derive(Clone, Copy, Debug)]
enum Entry {
    Explicit(Light),
    Sky,
    Triangle { geom: u32, prim: u32 },
}

/// A light sample as seen from a shading point.
#[derive(Clone, Copy, Debug)]
pub struct LightSample {
    /// Unit direction towards the light.
    pub wi: Vec3,
    /// Incident radiance (for delta lights: intensity / distance²).
    pub li: Vec3,
    /// Pdf per solid angle including the selection pmf (delta lights: the pmf).
    pub pdf: f32,
    /// Distance to the light sample (infinite for the sun and sky).
    pub dist: f32,
    /// Whether the light is a delta distribution (no MIS possible).
    pub delta: bool,
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
    cdf: Vec<f32>,
    pmf: Vec<f32>,
    /// pmf of the sky (1 when it emits, else 0).
    sky_pmf: f32,
    /// Every sun, for rays that escape into one.
    suns: Vec<SunDisk>,
    /// Per mesh, the entry index of each triangle (empty for non-emissive meshes).
    tri_entry: Vec<Vec<u32>>,
}

fn triangle_area(scene: &Scene, geom: u32, prim: u32) -> f32 {
    let m = &scene.meshes[geom as usize];
    let [a, b, c] = m.triangles[prim as usize].map(|i| m.p_f32[i as usize]);
    0.5 * (b - a).cross(c - a).length()
}

/// A sun as escaping rays see it.
#[derive(Clone, Copy, Debug)]
struct SunDisk {
    axis: Vec3,
    cos_max: f32,
    le: Vec3,
    /// Probability NEE picks it (1 in the distant group).
    pmf: f32,
}

impl LightSet {
    /// Collects every light of `scene`.
    pub fn build(scene: &Scene) -> Self {
        let radius = scene_radius(scene);
        let mut distant = Vec::new();
        let mut entries = Vec::new();
        let mut weights = Vec::new();
        let mut suns = Vec::new();
        let sky_emits = scene.sky.luminance_avg() > 0.0;
        let room_for_suns = MAX_DISTANT - sky_emits as usize;
        for light in &scene.lights {
            if let Light::Sun {
                dir_to_sun,
                angular_radius_rad,
                irradiance,
            } = *light
            {
                let in_distant = suns.len() < room_for_suns;
                suns.push((
                    SunDisk {
                        axis: dir_to_sun,
                        cos_max: angular_radius_rad.cos(),
                        le: sun_radiance(irradiance, angular_radius_rad),
                        pmf: 1.0,
                    },
                    (!in_distant).then_some(entries.len()),
                ));
                if in_distant {
                    distant.push(Entry::Explicit(*light));
                    continue;
                }
            }
            weights.push(power(light, radius));
            entries.push(Entry::Explicit(*light));
        }
        if sky_emits {
            distant.push(Entry::Sky);
        }
        let mut tri_entry = vec![Vec::new(); scene.meshes.len()];
        for (g, mesh) in scene.meshes.iter().enumerate() {
            let emissive =
                |t: usize| scene.materials[mesh.tri_material[t] as usize].le != Vec3::ZERO;
            if !(0..mesh.triangles.len()).any(emissive) {
                continue;
            }
            let mut slots = vec![u32::MAX; mesh.triangles.len()];
            for (t, slot) in slots.iter_mut().enumerate() {
                if !emissive(t) {
                    continue;
                }
                let mat = &scene.materials[mesh.tri_material[t] as usize];
                let sides = if mat.two_sided_emission { 2.0 } else { 1.0 };
                let area = triangle_area(scene, g as u32, t as u32);
                if area <= 0.0 {
                    continue;
                }
                *slot = entries.len() as u32;
                weights.push(std::f32::consts::PI * sides * area * luminance(mat.le));
                entries.push(Entry::Triangle {
                    geom: g as u32,
                    prim: t as u32,
                });
            }
            tri_entry[g] = slots;
        }
        let pmf = selection_pmf(&weights);
        let mut acc = 0.0f64;
        let cdf = pmf
            .iter()
            .map(|&p| {
                acc += p as f64;
                acc as f32
            })
            .collect();
        let suns = suns
            .into_iter()
            .map(|(disk, local)| SunDisk {
                pmf: local.map_or(1.0, |i| pmf[i]),
                ..disk
            })
            .collect();
        LightSet {
            distant,
            entries,
            cdf,
            pmf,
            sky_pmf: if sky_emits { 1.0 } else { 0.0 },
            suns,
            tri_entry,
        }
    }

    /// Number of distant lights sampled at every vertex (≤ `MAX_DISTANT`).
    pub fn distant_count(&self) -> usize {
        self.distant.len()
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
    pub fn sample_distant(&self, scene: &Scene, k: usize, p: Vec3, u: Vec2) -> Option<LightSample> {
        sample_entry(scene, &self.distant[k], 1.0, p, u)
    }

    /// Selects one local light and samples it as seen from `p`.
    pub fn sample(&self, scene: &Scene, p: Vec3, u_select: f32, u: Vec2) -> Option<LightSample> {
        if self.entries.is_empty() {
            return None;
        }
        let idx = self.select(u_select);
        let pmf = self.pmf[idx];
        if pmf == 0.0 {
            return None;
        }
        sample_entry(scene, &self.entries[idx], pmf, p, u)
    }

    /// Radiance of the sky and sun disks for a ray escaping along `dir` that
    /// was sampled with solid-angle pdf `prev_pdf` (or by a delta lobe / the
    /// camera), MIS-weighted against next-event estimation. Sun disks are not
    /// dimmed by the sky's cloud deck here; see [`LightSet::escaped_at`].
    pub fn escaped(&self, scene: &Scene, dir: Vec3, prev_pdf: f32, prev_delta: bool) -> Vec3 {
        self.escaped_from(scene, None, dir, prev_pdf, prev_delta)
    }

    /// [`LightSet::escaped`] for a ray leaving render-space point `p`: sun
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
        self.escaped_from(scene, Some(p), dir, prev_pdf, prev_delta)
    }

    fn escaped_from(
        &self,
        scene: &Scene,
        p: Option<Vec3>,
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
        if !prev_delta && l != Vec3::ZERO {
            l *= weight(self.sky_pmf * scene.sky.pdf(dir));
        }
        for sun in &self.suns {
            if dir.dot(sun.axis) >= sun.cos_max {
                let clouds = p.map_or(1.0, |p| cloud_transmittance(scene, p, dir));
                l += sun.le * clouds * weight(sun.pmf * uniform_cone_pdf(sun.cos_max));
            }
        }
        l
    }

    /// Pdf per solid angle (with pmf) that NEE would have chosen point `q` on
    /// emissive triangle (geom, prim), seen from `p` with light normal `n_light`.
    pub fn pdf_triangle(
        &self,
        scene: &Scene,
        geom: u32,
        prim: u32,
        p: Vec3,
        q: Vec3,
        n_light: Vec3,
    ) -> f32 {
        let Some(&idx) = self
            .tri_entry
            .get(geom as usize)
            .and_then(|v| v.get(prim as usize))
        else {
            return 0.0;
        };
        if idx == u32::MAX {
            return 0.0;
        }
        let d = q - p;
        let dist2 = d.length_squared();
        let cos_l = n_light.dot(d).abs() / dist2.sqrt();
        let area = triangle_area(scene, geom, prim);
        if cos_l == 0.0 || area == 0.0 {
            return 0.0;
        }
        self.pmf[idx as usize] * dist2 / (cos_l * area)
    }
}

/// Samples one entry with selection probability `pmf`.
fn sample_entry(scene: &Scene, entry: &Entry, pmf: f32, p: Vec3, u: Vec2) -> Option<LightSample> {
    match *entry {
        Entry::Explicit(light) => {
            let (wi, mut li, pdf, dist, delta) = sample_explicit(&light, p, u)?;
            if matches!(light, Light::Sun { .. }) {
                li *= cloud_transmittance(scene, p, wi);
            }
            Some(LightSample {
                wi,
                li,
                pdf: pdf * pmf,
                dist,
                delta,
            })
        }
        Entry::Sky => {
            let (wi, li, pdf) = scene.sky.sample(u);
            (pdf > 0.0).then_some(LightSample {
                wi,
                li,
                pdf: pdf * pmf,
                dist: f32::INFINITY,
                delta: false,
            })
        }
        Entry::Triangle { geom, prim } => {
            let m = &scene.meshes[geom as usize];
            let [a, b, c] = m.triangles[prim as usize].map(|i| m.p_f32[i as usize]);
            let bary = sample_uniform_triangle(u);
            let q = a * bary[0] + b * bary[1] + c * bary[2];
            let cross = (b - a).cross(c - a);
            let area = 0.5 * cross.length();
            let d = q - p;
            let dist2 = d.length_squared();
            if dist2 == 0.0 || area == 0.0 {
                return None;
            }
            let n = cross / (2.0 * area);
            let dist = dist2.sqrt();
            let wi = d / dist;
            let cos_l = -n.dot(wi);
            let mat = &scene.materials[m.tri_material[prim as usize] as usize];
            if cos_l <= 0.0 && !mat.two_sided_emission || cos_l == 0.0 {
                return None;
            }
            Some(LightSample {
                wi,
                li: mat.le,
                pdf: pmf * dist2 / (cos_l.abs() * area),
                dist,
                delta: false,
            })
        }
    }
}

/// Sun transmittance through the sky's cloud deck from render-space `p`
/// (a function of the world position only, so every view agrees).
fn cloud_transmittance(scene: &Scene, p: Vec3, wi: Vec3) -> f32 {
    scene
        .sky
        .cloud_transmittance(scene.origin_world + p.as_dvec3(), wi)
}

/// Selection probabilities: half by power, half uniform. Power alone starves
/// the sky next to the sun (≈ 9% of picks) although it is the only light in
/// every shadow; the uniform half keeps each light's share ≥ 1/(2N).
fn selection_pmf(weights: &[f32]) -> Vec<f32> {
    let n = weights.len().max(1) as f64;
    let total: f64 = weights.iter().map(|&w| w.max(0.0) as f64).sum();
    weights
        .iter()
        .map(|&w| {
            let by_power = if total > 0.0 {
                w.max(0.0) as f64 / total
            } else {
                1.0 / n
            };
            (0.5 * by_power + 0.5 / n) as f32
        })
        .collect()
}

/// Radius of the scene's bounding sphere around the render origin, clamped to a
/// range that keeps distant lights from swamping or vanishing in selection.
fn scene_radius(scene: &Scene) -> f32 {
    let r = scene
        .meshes
        .iter()
        .flat_map(|m| m.p_f32.iter())
        .map(|p| p.length())
        .chain(
            scene
                .spheres_f32
                .iter()
                .map(|s| s.truncate().length() + s.w),
        )
        .fold(0.0f32, f32::max);
    r.clamp(1.0, 100.0)
}
