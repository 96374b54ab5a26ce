//! The set of lights next-event estimation chooses from: explicit lights, the
//! sky, and every emissive triangle, selected in proportion to emitted power
//! (pbrt-v4's `PowerLightSampler`). Probabilities returned include the
//! selection pmf, so callers combine them directly in MIS weights.

use glam::{Vec2, Vec3};
use shaders_cpu::sampling::{luminance, sample_uniform_triangle};

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

/// All lights of a scene with their selection distribution.
#[derive(Clone, Debug)]
pub struct LightSet {
    entries: Vec<Entry>,
    cdf: Vec<f32>,
    pmf: Vec<f32>,
    sky_index: Option<usize>,
    sun: Option<(usize, Vec3, f32, Vec3)>,
    /// Per mesh, the entry index of each triangle (empty for non-emissive meshes).
    tri_entry: Vec<Vec<u32>>,
}

fn triangle_area(scene: &Scene, geom: u32, prim: u32) -> f32 {
    let m = &scene.meshes[geom as usize];
    let [a, b, c] = m.triangles[prim as usize].map(|i| m.p_f32[i as usize]);
    0.5 * (b - a).cross(c - a).length()
}

impl LightSet {
    /// Collects every light of `scene`.
    pub fn build(scene: &Scene) -> Self {
        let radius = scene_radius(scene);
        let mut entries = Vec::new();
        let mut weights = Vec::new();
        let mut sun = None;
        for light in &scene.lights {
            if let Light::Sun {
                dir_to_sun,
                angular_radius_rad,
                irradiance,
            } = *light
            {
                let le = sun_radiance(irradiance, angular_radius_rad);
                sun = Some((entries.len(), dir_to_sun, angular_radius_rad.cos(), le));
            }
            weights.push(power(light, radius));
            entries.push(Entry::Explicit(*light));
        }
        let sky_lum = sky_mean_luminance(scene);
        let sky_index = (sky_lum > 0.0).then(|| {
            let pi = std::f32::consts::PI;
            weights.push(pi * radius * radius * pi * sky_lum);
            entries.push(Entry::Sky);
            entries.len() - 1
        });
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
        LightSet {
            entries,
            cdf,
            pmf,
            sky_index,
            sun,
            tri_entry,
        }
    }

    /// Number of selectable lights.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether there is nothing to sample.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    fn select(&self, u: f32) -> usize {
        let i = self.cdf.partition_point(|&c| c <= u);
        i.min(self.entries.len() - 1)
    }

    /// Samples a light as seen from `p`.
    pub fn sample(&self, scene: &Scene, p: Vec3, u_select: f32, u: Vec2) -> Option<LightSample> {
        if self.entries.is_empty() {
            return None;
        }
        let idx = self.select(u_select);
        let pmf = self.pmf[idx];
        if pmf == 0.0 {
            return None;
        }
        match self.entries[idx] {
            Entry::Explicit(light) => {
                let (wi, li, pdf, dist, delta) = sample_explicit(&light, p, u)?;
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
                let n = cross / (2.0 * area);
                let d = q - p;
                let dist2 = d.length_squared();
                if dist2 == 0.0 || area == 0.0 {
                    return None;
                }
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

    /// Radiance of the sun disk in direction `dir` (zero outside it).
    pub fn sun_le(&self, dir: Vec3) -> Vec3 {
        match self.sun {
            Some((_, axis, cos_max, le)) if dir.dot(axis) >= cos_max => le,
            _ => Vec3::ZERO,
        }
    }

    /// Pdf (with pmf) that NEE would have produced escaping direction `dir`
    /// through the sky entry and the sun entry.
    pub fn pdf_infinite(&self, scene: &Scene, dir: Vec3) -> (f32, f32) {
        let sky = self
            .sky_index
            .map_or(0.0, |i| self.pmf[i] * scene.sky.pdf(dir));
        let sun = match self.sun {
            Some((i, axis, cos_max, _)) if dir.dot(axis) >= cos_max => {
                self.pmf[i] * shaders_cpu::sampling::uniform_cone_pdf(cos_max)
            }
            _ => 0.0,
        };
        (sky, sun)
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

/// Mean sky luminance over the sphere, by a fixed Fibonacci-lattice quadrature.
fn sky_mean_luminance(scene: &Scene) -> f32 {
    const N: usize = 256;
    let golden = std::f32::consts::PI * (3.0 - 5f32.sqrt());
    let sum: f32 = (0..N)
        .map(|k| {
            let z = 1.0 - (2 * k + 1) as f32 / N as f32;
            let r = (1.0 - z * z).max(0.0).sqrt();
            let phi = golden * k as f32;
            luminance(scene.sky.le(Vec3::new(r * phi.cos(), r * phi.sin(), z)))
        })
        .sum();
    sum / N as f32
}
