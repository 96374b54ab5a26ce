//! Description → immutable render-space `Scene` (placeholder).
use glam::{DVec3, Vec3};
use shaders_cpu::sky::Sky;

use super::{desc::SceneDesc, load::SceneError, Scene};

/// Builds the scene of one frame around `origin_world`.
pub fn build_scene(_desc: &SceneDesc, origin_world: DVec3) -> Result<Scene, SceneError> {
    Ok(Scene {
        origin_world,
        meshes: Vec::new(),
        spheres: Vec::new(),
        spheres_f32: Vec::new(),
        materials: Vec::new(),
        lights: Vec::new(),
        sky: Sky::Constant { le: Vec3::ONE },
    })
}
