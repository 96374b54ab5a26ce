//! The lights of a scene as `LightSet::build_with` gathers them: distant
//! lights, local entries with their power and light-BVH bounds, and the
//! suns as escaping rays see them.

use glam::Vec3;
use shaders_cpu::sampling::luminance;

use super::triangle_geometry;
use super::weights::explicit_bounds;
use crate::light::bvh::LightBounds;
use crate::light::entry::Entry;
use crate::light::{power, Light, SunCone, SunSampler};
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

    /// Every emissive triangle of a non-zero area as a local light; returns
    /// per mesh the entry index of each triangle (`u32::MAX`: none; empty
    /// for meshes without emission).
    pub(super) fn add_emissive_triangles(&mut self, scene: &Scene) -> Vec<Vec<u32>> {
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
                let (area, n, v) = triangle_geometry(scene, g as u32, t as u32);
                if area <= 0.0 || !n.is_finite() {
                    continue;
                }
                *slot = self.entries.len() as u32;
                self.weights
                    .push(std::f32::consts::PI * sides * area * luminance(mat.le));
                self.bounds.push(LightBounds {
                    p_min: v[0].min(v[1]).min(v[2]),
                    p_max: v[0].max(v[1]).max(v[2]),
                    w: n,
                    phi: area * luminance(mat.le),
                    cos_theta_o: 1.0,
                    cos_theta_e: 0.0,
                    two_sided: mat.two_sided_emission,
                });
                self.entries.push(Entry::Triangle {
                    v,
                    area,
                    le: mat.le,
                    two_sided: mat.two_sided_emission,
                });
            }
            tri_entry[g] = slots;
        }
        tri_entry
    }
}
