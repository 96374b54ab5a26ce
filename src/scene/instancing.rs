//! Which objects become two-level instances, and the scene's content counts.
//!
//! A top-level `kind = "instance"` object becomes one `Instance` per repeat
//! copy of a shared `Prototype` when its (prefab, material map) is placed at
//! least twice in the scene, or when it moves within a sequence (not one of
//! `LoadedScene::static_objects` of a scene that has them: its prototype's
//! accelerator is then kept from frame to frame); the prototype is the prefab's leaves (nested
//! instances and repeats included) built once in the prefab's frame. What
//! stays flat, built by `shapes` as before: every non-instance object, a
//! prefab placed once (a transform per hit would buy nothing), and a prefab
//! that holds an analytic sphere or an emissive material — so spheres stay
//! spheres and the light set finds every emitter among the flat meshes
//! (`light` enumerates emissive triangles of flat meshes only).
//!
//! Prototypes are keyed by (prefab, material map as written): instances
//! sharing one resolve to the same material indices, so hits read the
//! prototype's per-triangle materials directly (no remap in the hot path).

use std::collections::{BTreeMap, HashMap};

use glam::{DAffine3, DVec3};
use serde::Serialize;

use super::anchored::{is_tile, StaticTiles};
use super::desc::ShapeDesc;
use super::load::{LoadedScene, SceneError};
use super::semantic::class_id;
use super::shapes::Leaves;
use super::transform::{parent_from_local, repeat_count, repeat_offsets};
use super::walk::{walk_prefab, walk_top};
use super::{Instance, Mesh, Prototype, Scene, Sphere};
use crate::material::Material;

/// Whether `build_scene_with` makes prefab instances real instances.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Instancing {
    /// Prefabs placed at least twice or moving (and neither emissive nor
    /// holding a sphere) become prototypes with instances; static flat
    /// meshes are tiled (`anchored`).
    #[default]
    Prototypes,
    /// Everything flattened into render-space meshes.
    Flat,
}

/// The geometry of a built scene.
#[derive(Default)]
pub(super) struct Shapes {
    pub meshes: Vec<Mesh>,
    pub spheres: Vec<Sphere>,
    pub prototypes: Vec<Prototype>,
    pub instances: Vec<Instance>,
}

type Key<'a> = (&'a str, &'a BTreeMap<String, String>);

/// Builds every object of `scene` around `origin_world` (see the module
/// header for what is instanced); `materials` are the built table.
pub(super) fn build_shapes(
    scene: &LoadedScene,
    index: &HashMap<&str, u32>,
    materials: &[Material],
    origin_world: DVec3,
    mode: Instancing,
) -> Result<Shapes, SceneError> {
    let desc = &scene.desc;
    let mut placements: HashMap<Key, u64> = HashMap::new();
    for o in &desc.objects {
        if let ShapeDesc::Instance {
            prefab,
            material_map,
        } = &o.shape
        {
            *placements
                .entry((prefab.as_str(), material_map))
                .or_default() += repeat_count(&o.repeat);
        }
    }
    let mut flat = Leaves::default();
    let mut tiles = StaticTiles::default();
    let emits: Vec<bool> = materials.iter().map(|m| m.le != glam::Vec3::ZERO).collect();
    let mut out = Shapes::default();
    // Per key: the prototype's index, or None when the prefab stays flat.
    let mut protos: HashMap<Key, Option<u32>> = HashMap::new();
    for (i, o) in desc.objects.iter().enumerate() {
        let proto = match &o.shape {
            ShapeDesc::Instance {
                prefab,
                material_map,
            } if mode == Instancing::Prototypes
                && (placements[&(prefab.as_str(), material_map)] >= 2 || scene.moves(i)) =>
            {
                let key = (prefab.as_str(), material_map);
                match protos.get(&key) {
                    Some(&p) => p,
                    None => {
                        let built = prototype(scene, index, materials, i, prefab, material_map)?;
                        let p = built.map(|b| {
                            out.prototypes.push(b);
                            out.prototypes.len() as u32 - 1
                        });
                        protos.insert(key, p);
                        p
                    }
                }
            }
            _ => None,
        };
        let Some(p) = proto else {
            if mode == Instancing::Prototypes && scene.is_static(i) {
                // Built in world coordinates, then tiled (`anchored`).
                let mut world = Leaves::default();
                walk_top(desc, i, &mut |placed| {
                    world.add(scene, index, &placed, DVec3::ZERO)
                })?;
                tiles.add(world, &emits, origin_world, &mut flat);
            } else {
                walk_top(desc, i, &mut |placed| {
                    flat.add(scene, index, &placed, origin_world)
                })?;
            }
            continue;
        };
        let semantic = o.semantic.as_deref().map(|s| class_id(s).unwrap_or(0));
        let parent_from_local = parent_from_local(&o.transform);
        for offset in repeat_offsets(&o.repeat) {
            let world = DAffine3::from_translation(offset) * parent_from_local;
            let render = DAffine3 {
                matrix3: world.matrix3,
                translation: world.translation - origin_world,
            };
            out.instances
                .push(Instance::new(p, render, semantic, o.instance));
        }
    }
    let (protos, insts) = tiles.finish(out.prototypes.len() as u32, origin_world);
    out.prototypes.extend(protos);
    out.instances.extend(insts);
    out.meshes = flat.meshes;
    out.spheres = flat.spheres;
    Ok(out)
}

/// The prototype of `prefab` as object `i` maps its materials, or None when
/// it must stay flat (a sphere or an emissive material inside).
fn prototype(
    scene: &LoadedScene,
    index: &HashMap<&str, u32>,
    materials: &[Material],
    i: usize,
    prefab: &str,
    material_map: &BTreeMap<String, String>,
) -> Result<Option<Prototype>, SceneError> {
    let mut leaves = Leaves::default();
    walk_prefab(&scene.desc, i, prefab, material_map, &mut |placed| {
        leaves.add(scene, index, &placed, DVec3::ZERO)
    })?;
    let emissive = leaves
        .meshes
        .iter()
        .flat_map(|m| &m.tri_material)
        .any(|&t| materials[t as usize].le != glam::Vec3::ZERO);
    Ok((leaves.spheres.is_empty() && !emissive).then(|| Prototype {
        prefab: prefab.to_string(),
        meshes: leaves.meshes,
        sources: Vec::new(),
    }))
}

/// Prototype mesh `m` placed by `inst` in render space (f64 positions,
/// normals by the inverse transpose, labels resolved).
pub(super) fn place_mesh(m: &Mesh, inst: &Instance) -> Mesh {
    let x = inst.render_from_local;
    let p_render: Vec<DVec3> = m.p_render.iter().map(|&p| x.transform_point3(p)).collect();
    let n = x.matrix3.inverse().transpose();
    Mesh {
        p_f32: p_render.iter().map(|p| p.as_vec3()).collect(),
        p_render,
        normals: m
            .normals
            .iter()
            .map(|&v| (n * v.as_dvec3()).normalize().as_vec3())
            .collect(),
        uvs: m.uvs.clone(),
        triangles: m.triangles.clone(),
        tri_material: m.tri_material.clone(),
        semantic: inst.semantic.unwrap_or(m.semantic),
        instance: inst.instance.unwrap_or(m.instance),
    }
}

/// What a built scene holds (`Scene::content`); serialised as the content
/// report's `geometry` (without the per-class mesh counts). Static tiles
/// (`anchored`) are counted as the flat meshes they stand for (a mesh cut
/// into pieces as the one mesh it was: `Prototype::sources`), so the
/// figures do not depend on how the static world is grouped.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Content {
    /// Flat meshes.
    pub meshes: u64,
    /// Prototypes (shared prefab geometry).
    pub prototypes: u64,
    /// Instances of them.
    pub instances: u64,
    /// Triangles stored: flat meshes plus each prototype once.
    pub unique_triangles: u64,
    /// Triangles as if flattened: flat meshes plus every instance's.
    pub instanced_triangles: u64,
    /// Analytic spheres.
    pub spheres: u64,
    /// Triangles that cutting static meshes wider than a tile at tile
    /// edges adds (`tile_clip`): held in the accelerators and written by
    /// exports on top of the counts above.
    pub cut_triangles: u64,
    /// Objects per semantic class id: flat meshes, spheres and instances
    /// each count one (an instance with its own class counts there, else
    /// under its prototype's first mesh's class).
    #[serde(skip)]
    pub objects_per_class: BTreeMap<u8, u64>,
}

impl Scene {
    /// Counts of what this scene holds.
    pub fn content(&self) -> Content {
        let tris = |ms: &[Mesh]| ms.iter().map(|m| m.triangles.len() as u64).sum::<u64>();
        let tiles = || self.prototypes.iter().filter(|p| is_tile(p));
        let tile_meshes = || tiles().flat_map(|p| &p.sources);
        let flat = tris(&self.meshes) + tile_meshes().map(|s| s.1).sum::<u64>();
        let proto: Vec<u64> = self
            .prototypes
            .iter()
            .map(|p| if is_tile(p) { 0 } else { tris(&p.meshes) })
            .collect();
        let placed = || {
            self.instances
                .iter()
                .filter(|i| !is_tile(&self.prototypes[i.prototype as usize]))
        };
        let mut per_class = BTreeMap::new();
        let classes = self.meshes.iter().map(|m| m.semantic);
        let classes = classes.chain(tile_meshes().map(|s| s.0));
        let classes = classes.chain(self.spheres.iter().map(|s| s.semantic));
        let classes = classes.chain(placed().map(|i| {
            let first = self.prototypes[i.prototype as usize].meshes.first();
            i.semantic.or(first.map(|m| m.semantic)).unwrap_or(0)
        }));
        for c in classes {
            *per_class.entry(c).or_insert(0) += 1;
        }
        Content {
            meshes: (self.meshes.len() + tile_meshes().count()) as u64,
            prototypes: (self.prototypes.len() - tiles().count()) as u64,
            instances: placed().count() as u64,
            unique_triangles: flat + proto.iter().sum::<u64>(),
            instanced_triangles: flat + placed().map(|i| proto[i.prototype as usize]).sum::<u64>(),
            spheres: self.spheres.len() as u64,
            // Saturating: a cut that drops degenerate slivers may add none.
            cut_triangles: tiles()
                .map(|p| tris(&p.meshes))
                .sum::<u64>()
                .saturating_sub(tile_meshes().map(|s| s.1).sum::<u64>()),
            objects_per_class: per_class,
        }
    }
}
