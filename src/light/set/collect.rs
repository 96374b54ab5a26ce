//! The lights of a scene as `LightSet::build_with` gathers them: distant
//! lights, local entries (explicit lights and emitters) with their power
//! and light-BVH bounds, and the suns as escaping rays see them.

use glam::Vec3;
use shaders_cpu::sampling::luminance;

use super::triangle_geometry;
use super::weights::explicit_bounds;
use crate::light::bvh::LightBounds;
use crate::light::emitter::{group, EmissiveTriangle, Emitters};
use crate::light::entry::Entry;
use crate::light::{power, Light, SunCone, SunSampler};
use crate::material::Material;
use crate::scene::Scene;

/// A sun as escaping rays see it.
#[derive(Clone, Copy, Debug)]
pub(super) struct SunDisk {
    pub(super) axis: Vec3,
    pub(super) cone: SunCone,
    pub(super) le: Vec3,
    /// Probability NEE picks it (1 in the distant group).
    pub(super) pmf: f32,
}

/// The lights of a scene as `LightSet::build_with` gathers them, before
/// the selection tables are made.
#[derive(Default)]
pub(super) struct Collected {
    /// Sampled at every vertex.
    pub(super) distant: Vec<Entry>,
    /// Selected one per vertex, with their selection weights (power) and
    /// light-BVH bounds.
    pub(super) entries: Vec<Entry>,
    pub(super) weights: Vec<f32>,
    pub(super) bounds: Vec<LightBounds>,
    /// Every sun, with its index among `entries` when it is not distant.
    pub(super) suns: Vec<(SunDisk, Option<usize>)>,
    /// The emitters' triangles.
    pub(super) emitters: Emitters,
}

impl Collected {
    /// The scene's explicit lights: the first `room_for_suns` suns as
    /// distant lights, every other light (further suns included) local.
    /// `radius` is the scene's (`scene_radius`), for the suns' power.
    pub(super) fn add_explicit(&mut self, scene: &Scene, room_for_suns: usize, radius: f32) {
        for light in &scene.lights {
            if let Light::Sun {
                dir_to_sun,
                angular_radius_rad,
                irradiance,
            } = *light
            {
                let in_distant = self.suns.len() < room_for_suns;
                self.suns.push((
                    SunDisk {
                        axis: dir_to_sun,
                        cone: SunCone::new(angular_radius_rad),
                        le: SunCone::new(angular_radius_rad).radiance(irradiance),
                        pmf: 1.0,
                    },
                    (!in_distant).then_some(self.entries.len()),
                ));
                if in_distant {
                    self.distant.push(Entry::Sun(SunSampler::new(
                        dir_to_sun,
                        angular_radius_rad,
                        irradiance,
                    )));
                    continue;
                }
            }
            self.weights.push(power(light, radius));
            self.bounds.push(explicit_bounds(light));
            self.entries.push(Entry::Explicit(*light));
        }
    }

    /// Every emissive triangle of a non-zero area as part of a local light,
    /// an emitter (`emitter::group`): per mesh and material, triangles close
    /// together as one. Returns per mesh the index in `emitters` of each
    /// triangle (`u32::MAX`: none; empty for meshes without emission).
    pub(super) fn add_emissive_triangles(&mut self, scene: &Scene) -> Vec<Vec<u32>> {
        let mut tri_index = vec![Vec::new(); scene.meshes.len()];
        for (g, mesh) in scene.meshes.iter().enumerate() {
            let emissive =
                |t: usize| scene.materials[mesh.tri_material[t] as usize].le != Vec3::ZERO;
            if !(0..mesh.triangles.len()).any(emissive) {
                continue;
            }
            // Per material, in the order each first appears.
            let mut by_material: Vec<(u32, Vec<EmissiveTriangle>)> = Vec::new();
            for t in 0..mesh.triangles.len() {
                if !emissive(t) {
                    continue;
                }
                let (area, n, v) = triangle_geometry(scene, g as u32, t as u32);
                if area <= 0.0 || !n.is_finite() {
                    continue;
                }
                let m = mesh.tri_material[t];
                let tri = EmissiveTriangle { v, prim: t as u32 };
                match by_material.iter_mut().find(|(k, _)| *k == m) {
                    Some((_, tris)) => tris.push(tri),
                    None => by_material.push((m, vec![tri])),
                }
            }
            let mut slots = vec![u32::MAX; mesh.triangles.len()];
            for (m, tris) in by_material {
                let mat = &scene.materials[m as usize];
                group(&tris, &mut |tris| self.add_emitter(mat, tris, &mut slots));
            }
            tri_index[g] = slots;
        }
        tri_index
    }

    /// One emitter of material `mat`: its entry, power and bounds (the
    /// union of its triangles'); records its triangles' indices in `slots`.
    fn add_emitter(&mut self, mat: &Material, tris: &[EmissiveTriangle], slots: &mut [u32]) {
        let entry = self.entries.len() as u32;
        let range = self.emitters.push(tris, entry);
        let sides = if mat.two_sided_emission { 2.0 } else { 1.0 };
        let mut weight = 0.0;
        let mut bounds: Option<LightBounds> = None;
        for (t, i) in tris.iter().zip(range.clone()) {
            slots[t.prim as usize] = i;
            let area = self.emitters.area(i);
            let [a, b, c] = t.v;
            weight += std::f32::consts::PI * sides * area * luminance(mat.le);
            let own = LightBounds {
                p_min: a.min(b).min(c),
                p_max: a.max(b).max(c),
                w: (b - a).cross(c - a).normalize(),
                phi: area * luminance(mat.le),
                cos_theta_o: 1.0,
                cos_theta_e: 0.0,
                two_sided: mat.two_sided_emission,
            };
            bounds = Some(bounds.map_or(own, |u| u.union(&own)));
        }
        self.weights.push(weight);
        self.bounds.push(bounds.expect("an emitter has a triangle"));
        self.entries.push(Entry::Emitter {
            first: range.start,
            end: range.end,
            le: mat.le,
            two_sided: mat.two_sided_emission,
        });
    }
}
