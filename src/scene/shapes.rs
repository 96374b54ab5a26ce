//! Objects → render-space meshes and spheres: each placed object (prefabs
//! and repeats flattened by `walk`) is tessellated or imported in local f64
//! coordinates, transformed to world, moved by −origin_world into render
//! space and only then rounded to f32. Material names resolve to indices of
//! the scene's material table here. `instancing` decides which objects
//! become leaves here and which prototypes.

use std::collections::HashMap;

use glam::{DAffine3, DVec3};

use super::desc::ShapeDesc;
use super::load::{LoadedScene, SceneError, SceneErrorKind};
use super::mesh::{self, LocalMesh};
use super::obj::ObjAsset;
use super::walk::Placed;
use super::{Mesh, Sphere};

/// Meshes and spheres collected from placed leaf objects.
#[derive(Default)]
pub(super) struct Leaves {
    pub meshes: Vec<Mesh>,
    pub spheres: Vec<Sphere>,
}

impl Leaves {
    /// Tessellates or imports one placed leaf object around `origin_world`
    /// (zero for a prototype's local frame); `index` maps material names
    /// to table indices.
    pub fn add(
        &mut self,
        scene: &LoadedScene,
        index: &HashMap<&str, u32>,
        placed: &Placed,
        origin_world: DVec3,
    ) -> Result<(), SceneError> {
        let resolve = |name: &str| resolve_material(scene, index, placed, name);
        let own = placed.object.material.as_deref().map(resolve).transpose()?;
        let at = Placement {
            world_from_local: placed.world_from_local,
            origin_world,
            semantic: placed.semantic,
            instance: placed.instance,
        };
        match &placed.object.shape {
            ShapeDesc::Sphere { radius } => {
                self.spheres.push(sphere(&at, *radius, own.unwrap_or(0)))
            }
            ShapeDesc::Obj { file } => {
                self.meshes
                    .push(obj_mesh(&scene.objs[file], own, resolve, &at)?)
            }
            ShapeDesc::Mesh {
                positions,
                normals,
                triangles,
            } => {
                // Validation checked the indices; this drops what it dropped.
                let (kept, _) = mesh::keep_nondegenerate(positions, triangles).map_err(|m| {
                    let key = format!("{}.triangles", placed.key);
                    SceneError::at(&scene.path, SceneErrorKind::Invalid, key, m)
                })?;
                let m = vec![own.unwrap_or(0); kept.len()];
                self.meshes
                    .push(render_mesh(positions, normals, kept, m, &at));
            }
            other => {
                // None: an instance, which walk has expanded.
                if let Some(local) = tessellate(other) {
                    let m = vec![own.unwrap_or(0); local.triangles.len()];
                    self.meshes.push(render_mesh(
                        &local.positions,
                        &local.normals,
                        local.triangles,
                        m,
                        &at,
                    ));
                }
            }
        }
        Ok(())
    }
}

/// The table index of material `name` as `placed` sees it (through its
/// prefabs' material maps); the error names the object's material key.
fn resolve_material(
    scene: &LoadedScene,
    index: &HashMap<&str, u32>,
    placed: &Placed,
    name: &str,
) -> Result<u32, SceneError> {
    let mapped = placed.map_material(name);
    index.get(mapped.as_str()).copied().ok_or_else(|| {
        let key = format!("{}.material{}", placed.key, placed.via);
        SceneError::at(
            &scene.path,
            SceneErrorKind::Invalid,
            key,
            format!("unknown material \"{mapped}\""),
        )
    })
}

/// Where a local mesh goes: its placement, the render origin, its labels.
struct Placement {
    world_from_local: DAffine3,
    origin_world: DVec3,
    semantic: u8,
    instance: u16,
}

/// An analytic sphere of local `radius` (uniform scale only, checked by
/// validation) at the placement's origin.
fn sphere(at: &Placement, radius: f64, material: u32) -> Sphere {
    let m = at.world_from_local;
    Sphere {
        center: m.translation - at.origin_world,
        radius: radius * m.matrix3.x_axis.length(),
        material,
        semantic: at.semantic,
        instance: at.instance,
    }
}

/// One mesh of all groups of an OBJ file; each group takes the object's own
/// material, else its `usemtl` material, else the default "" material.
fn obj_mesh(
    asset: &ObjAsset,
    own: Option<u32>,
    resolve: impl Fn(&str) -> Result<u32, SceneError>,
    at: &Placement,
) -> Result<Mesh, SceneError> {
    let mut merged = LocalMesh::default();
    let mut tri_material = Vec::new();
    for g in &asset.groups {
        let m = match (own, g.material) {
            (Some(m), _) => m,
            (None, Some(gm)) => resolve(&asset.materials[gm].name)?,
            (None, None) => resolve("")?,
        };
        let base = merged.positions.len() as u32;
        merged.positions.extend(&g.positions);
        merged
            .triangles
            .extend(g.triangles.iter().map(|t| t.map(|i| i + base)));
        tri_material.extend(std::iter::repeat_n(m, g.triangles.len()));
        merged.normals.extend(&g.normals);
    }
    // Shading normals only if every group has them.
    if merged.normals.len() != merged.positions.len() {
        merged.normals.clear();
    }
    Ok(render_mesh(
        &merged.positions,
        &merged.normals,
        merged.triangles,
        tri_material,
        at,
    ))
}

/// The local mesh of a tessellated primitive (quad, box, cylinder,
/// ellipsoid); None for the other shapes.
fn tessellate(shape: &ShapeDesc) -> Option<LocalMesh> {
    Some(match shape {
        ShapeDesc::Quad { size } => mesh::quad(*size),
        ShapeDesc::Box { size } => mesh::cuboid(*size),
        ShapeDesc::Cylinder {
            radius,
            height,
            segments,
            capped,
        } => mesh::cylinder(*radius, *height, *segments, *capped),
        ShapeDesc::Ellipsoid {
            radii,
            segments,
            rings,
        } => mesh::ellipsoid(*radii, *segments, *rings),
        ShapeDesc::Sphere { .. }
        | ShapeDesc::Obj { .. }
        | ShapeDesc::Mesh { .. }
        | ShapeDesc::Instance { .. } => return None,
    })
}

/// A local mesh (positions and optional normals as `DVec3` or `[f64; 3]`)
/// placed in render space.
fn render_mesh<P: Copy + Into<DVec3>>(
    positions: &[P],
    normals: &[P],
    triangles: Vec<[u32; 3]>,
    tri_material: Vec<u32>,
    at: &Placement,
) -> Mesh {
    let p_render: Vec<DVec3> = positions
        .iter()
        .map(|&p| at.world_from_local.transform_point3(p.into()) - at.origin_world)
        .collect();
    // Normals transform with the inverse transpose (non-uniform scale).
    let normal_from_local = at.world_from_local.matrix3.inverse().transpose();
    Mesh {
        p_f32: p_render.iter().map(|p| p.as_vec3()).collect(),
        p_render,
        normals: normals
            .iter()
            .map(|&n| (normal_from_local * n.into()).normalize().as_vec3())
            .collect(),
        uvs: Vec::new(),
        triangles,
        tri_material,
        semantic: at.semantic,
        instance: at.instance,
    }
}
