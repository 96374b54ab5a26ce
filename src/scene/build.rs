//! Description → immutable render-space `Scene`: materials (`material::build`),
//! shapes (`shapes`: prefabs, repeats and transforms flattened in f64 world
//! coordinates, then `origin_world` subtracted — render space = world
//! orientation, centred on the rig — and only then rounded to f32; shared
//! prefabs as prototypes with instances, `instancing`), emitters
//! (`emitters`) and the frame's air and weather (medium, rain, wetness).

use std::collections::HashMap;

use glam::{DVec3, Vec4};

use super::desc::{build_medium, build_rain, MaterialDesc, SceneDesc};
use super::emitters::build_emitters;
use super::instancing::{build_shapes, Instancing};
use super::load::{LoadedScene, SceneError};
use super::validate::material_table;
use super::{Scene, Sphere};
use crate::material::{build_material, Wetness};

/// Builds the scene of one frame around `origin_world` (world metres): every
/// position becomes `p_world − origin_world`.
pub fn build_scene(scene: &LoadedScene, origin_world: DVec3) -> Result<Scene, SceneError> {
    build_scene_with(scene, origin_world, Instancing::default())
}

/// As [`build_scene`], with shared prefabs instanced or everything flat.
pub fn build_scene_with(
    scene: &LoadedScene,
    origin_world: DVec3,
    mode: Instancing,
) -> Result<Scene, SceneError> {
    let desc = &scene.desc;
    let table = material_table(desc, &scene.objs);
    let materials: Vec<_> = table.iter().map(|m| build_material(m)).collect();
    let shapes = build_shapes(
        scene,
        &material_index(&table),
        &materials,
        origin_world,
        mode,
    )?;
    let (lights, sky) = build_emitters(desc, origin_world);
    Ok(Scene {
        origin_world,
        meshes: shapes.meshes,
        spheres_f32: spheres_f32(&shapes.spheres),
        spheres: shapes.spheres,
        instances_f32: shapes.instances.iter().map(|i| i.accel_ref()).collect(),
        prototypes: shapes.prototypes,
        instances: shapes.instances,
        materials,
        lights,
        sky,
        medium: desc.medium.as_ref().map(|m| build_medium(m, origin_world)),
        filter_inscatter: filters_inscatter(desc),
        filter_indirect: desc.render.filter_indirect && desc.medium.is_none(),
        regularize: desc.render.filter_indirect,
        denoiser: desc.render.denoiser,
        rain: desc.rain.as_ref().map(|r| build_rain(r, origin_world)),
        wetness: desc.wetness.as_ref().map(|w| Wetness::new(w, origin_world)),
    })
}

/// Material name → index into the scene's material table.
fn material_index<'a>(table: &[&'a MaterialDesc]) -> HashMap<&'a str, u32> {
    table
        .iter()
        .enumerate()
        .map(|(i, m)| (m.name.as_str(), i as u32))
        .collect()
}

/// Sphere data as the accelerator wants it: (centre, radius) in f32.
fn spheres_f32(spheres: &[Sphere]) -> Vec<Vec4> {
    spheres
        .iter()
        .map(|s| s.center.as_vec3().extend(s.radius as f32))
        .collect()
}

/// Whether renders filter the camera rays' in-scattered radiance: asked for
/// by the medium, and the medium scatters at all.
fn filters_inscatter(desc: &SceneDesc) -> bool {
    desc.medium
        .as_ref()
        .is_some_and(|m| m.filter_inscatter && m.albedo.iter().any(|&a| a > 0.0))
}
