//! Description → immutable render-space `Scene`: prefabs, repeats and
//! transforms are flattened in f64 world coordinates, then `origin_world` is
//! subtracted (render space = world orientation, centred on the rig), and
//! only then are positions rounded to f32 for traversal.

use std::collections::HashMap;

use glam::{DAffine3, DVec3, Vec3, Vec4};
use shaders_cpu::bsdf::Bsdf;

use super::desc::{LightDesc, MaskFlag, MaterialDesc, MaterialKindDesc, ShapeDesc};
use super::load::{LoadedScene, SceneError, SceneErrorKind};
use super::mesh::{self, LocalMesh};
use super::validate::material_table;
use super::walk::walk;
use super::{mask_bits, Material, Mesh, Scene, Sphere};
use crate::light::Light;

/// Perceptual roughness below which a conductor counts as a mirror in the mask.
pub const MIRROR_ROUGHNESS: f64 = 0.1;

/// Builds the scene of one frame around `origin_world` (world metres): every
/// position becomes `p_world − origin_world`.
pub fn build_scene(scene: &LoadedScene, origin_world: DVec3) -> Result<Scene, SceneError> {
    let desc = &scene.desc;
    let table = material_table(desc, &scene.objs);
    let materials: Vec<Material> = table.iter().map(|m| build_material(m)).collect();
    let index: HashMap<&str, u32> = table
        .iter()
        .enumerate()
        .map(|(i, m)| (m.name.as_str(), i as u32))
        .collect();
    let mut meshes = Vec::new();
    let mut spheres = Vec::new();
    walk(desc, true, &mut |placed| {
        let resolve = |name: &str| {
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
        };
        let own = placed.object.material.as_deref().map(resolve).transpose()?;
        let at = Placement {
            world_from_local: placed.world_from_local,
            origin_world,
            semantic: placed.semantic,
            instance: placed.instance,
        };
        let to_mesh = |local: LocalMesh, tri_material: Vec<u32>| {
            render_mesh(
                &local.positions,
                &local.normals,
                local.triangles,
                tri_material,
                &at,
            )
        };
        let local = match &placed.object.shape {
            ShapeDesc::Sphere { radius } => {
                let m = placed.world_from_local;
                spheres.push(Sphere {
                    center: m.translation - origin_world,
                    radius: radius * m.matrix3.x_axis.length(),
                    material: own.unwrap_or(0),
                    semantic: placed.semantic,
                    instance: placed.instance,
                });
                return Ok(());
            }
            ShapeDesc::Obj { file } => {
                let asset = &scene.objs[file];
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
                meshes.push(to_mesh(merged, tri_material));
                return Ok(());
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
                meshes.push(render_mesh(positions, normals, kept, m, &at));
                return Ok(());
            }
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
            ShapeDesc::Instance { .. } => return Ok(()), // walk expands instances
        };
        let m = vec![own.unwrap_or(0); local.triangles.len()];
        meshes.push(to_mesh(local, m));
        Ok(())
    })?;
    let spheres_f32 = spheres
        .iter()
        .map(|s| s.center.as_vec3().extend(s.radius as f32))
        .collect::<Vec<Vec4>>();
    let (sky, sky_light) = crate::light::build_sky(desc.sky.as_ref(), origin_world);
    Ok(Scene {
        origin_world,
        meshes,
        spheres,
        spheres_f32,
        materials,
        lights: desc
            .lights
            .iter()
            .map(|l| build_light(l, origin_world))
            .chain(sky_light)
            .collect(),
        sky,
        medium: desc
            .medium
            .as_ref()
            .map(|m| super::desc::build_medium(m, origin_world)),
        filter_inscatter: desc
            .medium
            .as_ref()
            .is_some_and(|m| m.filter_inscatter && m.albedo.iter().any(|&a| a > 0.0)),
        filter_indirect: desc.render.filter_indirect && desc.medium.is_none(),
        rain: desc
            .rain
            .as_ref()
            .map(|r| super::desc::build_rain(r, origin_world)),
        wetness: desc
            .wetness
            .as_ref()
            .map(|w| crate::integrator::wet::Wetness::new(w, origin_world)),
    })
}

/// Where a local mesh goes: its placement, the render origin, its labels.
struct Placement {
    world_from_local: DAffine3,
    origin_world: DVec3,
    semantic: u8,
    instance: u16,
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

fn v3(c: [f64; 3]) -> Vec3 {
    DVec3::from(c).as_vec3()
}

/// Resolves one material description (mask bits per GROUND_TRUTH.md).
pub fn build_material(m: &MaterialDesc) -> Material {
    let (bsdf, le, two_sided_emission, mask) = match &m.kind {
        MaterialKindDesc::Diffuse { albedo } => (
            Bsdf::Lambert {
                albedo: v3(*albedo),
            },
            Vec3::ZERO,
            false,
            0,
        ),
        MaterialKindDesc::Conductor {
            preset,
            eta,
            k,
            roughness,
        } => {
            let (eta, k) = crate::scene::desc::conductor_eta_k(preset, eta, k);
            let alpha = (roughness * roughness) as f32;
            let mask = if *roughness < MIRROR_ROUGHNESS {
                mask_bits::MIRROR
            } else {
                0
            };
            (
                Bsdf::Conductor {
                    eta: v3(eta),
                    k: v3(k),
                    alpha,
                },
                Vec3::ZERO,
                false,
                mask,
            )
        }
        MaterialKindDesc::Dielectric {
            ior,
            roughness,
            tint,
        } => {
            let bsdf = Bsdf::Dielectric {
                eta: *ior as f32,
                alpha: (roughness * roughness) as f32,
                tint: v3(*tint),
            };
            (bsdf, Vec3::ZERO, false, mask_bits::TRANSPARENT)
        }
        MaterialKindDesc::Coated {
            albedo,
            preset,
            eta,
            k,
            base_roughness,
            coat_ior,
            coat_roughness,
        } => {
            let base = match albedo {
                Some(a) => shaders_cpu::bsdf::CoatBase::Lambert { albedo: v3(*a) },
                None => {
                    let (eta, k) = crate::scene::desc::conductor_eta_k(preset, eta, k);
                    shaders_cpu::bsdf::CoatBase::Conductor {
                        eta: v3(eta),
                        k: v3(k),
                        alpha: (base_roughness * base_roughness) as f32,
                    }
                }
            };
            let bsdf = Bsdf::Coated {
                base,
                eta: *coat_ior as f32,
                alpha: (coat_roughness * coat_roughness) as f32,
            };
            (bsdf, Vec3::ZERO, false, 0)
        }
        MaterialKindDesc::Emissive {
            radiance,
            two_sided,
        } => (
            Bsdf::Lambert { albedo: Vec3::ZERO },
            v3(*radiance),
            *two_sided,
            0,
        ),
    };
    let mask = match &m.mask {
        Some(flags) => flags.iter().fold(0, |bits, f| {
            bits | match f {
                MaskFlag::Transparent => mask_bits::TRANSPARENT,
                MaskFlag::Mirror => mask_bits::MIRROR,
            }
        }),
        None => mask,
    };
    Material {
        name: m.name.clone(),
        bsdf,
        le,
        two_sided_emission,
        mask,
        texture: m.texture.map(|t| t.build()),
    }
}

/// Unit vector towards a direction given by elevation above the horizon and
/// azimuth counter-clockwise from +x (world z up).
pub fn dir_from_elevation_azimuth(elevation_deg: f64, azimuth_deg: f64) -> DVec3 {
    let (e, a) = (elevation_deg.to_radians(), azimuth_deg.to_radians());
    DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
}

fn build_light(l: &LightDesc, origin_world: DVec3) -> Light {
    let p_render = |p: &[f64; 3]| (DVec3::from(*p) - origin_world).as_vec3();
    match l {
        LightDesc::Sun {
            elevation_deg,
            azimuth_deg,
            irradiance,
            angular_diameter_deg,
        } => Light::Sun {
            dir_to_sun: dir_from_elevation_azimuth(*elevation_deg, *azimuth_deg).as_vec3(),
            angular_radius_rad: (angular_diameter_deg / 2.0).to_radians() as f32,
            irradiance: v3(*irradiance),
        },
        LightDesc::Point {
            position,
            intensity,
        } => Light::Point {
            p: p_render(position),
            intensity: v3(*intensity),
        },
        LightDesc::Spot {
            position,
            direction,
            intensity,
            inner_deg,
            outer_deg,
        } => Light::Spot {
            p: p_render(position),
            dir: DVec3::from(*direction).normalize().as_vec3(),
            intensity: v3(*intensity),
            cos_inner: inner_deg.to_radians().cos() as f32,
            cos_outer: outer_deg.to_radians().cos() as f32,
        },
    }
}
