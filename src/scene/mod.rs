//! Scenes: serde descriptions (`desc`), validation with file and key-path
//! errors (`load`, `validate`), and the immutable, render-space `Scene` built
//! from them (`build`): shapes (`shapes`, with OBJ import `obj`, primitive
//! tessellation `mesh`, prefab checks `prefab`, placement `transform`),
//! materials (built by `material`), emitters as data (`emitters`) and
//! semantic classes. Also what turns an accelerator hit on a scene into a
//! `SurfaceInteraction` (`surface`, and its cache `SurfaceTable`).
//!
//! The scene depends only on descriptions, geometry, the camera rig, the
//! accelerator's input and hit types, materials and the sampler; sampling
//! its lights is `light`'s job, shading it the integrators'.
//!
//! A `Scene` is built once per frame around a render origin (the frame's left
//! camera centre, world coordinates, f64): every position in it is
//! `p_world − origin_world`. f64 copies of positions are kept for the
//! ground-truth pass, which re-intersects the hit primitive in f64.
//!
//! Prefab instances placed more than once become two-level instances
//! (`instancing`): a `Prototype` holds the prefab's meshes once, in its own
//! frame, and each `Instance` places it by an f64 affine map; a hit on one
//! carries `Hit::inst_id`, and `surface`, `table` and the GT pass carry it
//! through the transform (`hit_mesh`).
//!
//! The flat meshes of a town's static objects are grouped into static tiles
//! (`anchored`): prototypes in a world-fixed frame, placed per frame by a
//! translation, so their accelerators survive from frame to frame.

mod anchored;
pub mod build;
pub mod desc;
pub mod emitters;
mod huge;
mod instancing;
pub mod load;
pub mod mesh;
mod mtl_check;
pub mod obj;
mod obj_scan;
mod polygon;
pub mod prefab;
mod ranges;
mod resolve;
pub use desc::semantic;
mod shapes;
mod surface;
mod table;
mod tile_clip;
pub mod transform;
pub mod validate;
mod walk;

pub use anchored::{is_tile, TILE_M};
pub use build::{build_scene, build_scene_with};
pub use desc::{serialize_scene, SceneDesc};
pub use emitters::Light;
pub use instancing::{Content, Instancing};
pub use load::{load_scene, parse_scene_str, LoadedScene, SceneError, SceneErrorKind};
pub use surface::surface_interaction;
pub use table::SurfaceTable;
// Materials are built below the scene; a scene stores them.
pub use crate::material::{mask_bits, Material};

use glam::{Affine3A, DAffine3, DVec3, Mat3A, Vec2, Vec3, Vec4};
use shaders_cpu::sky::Sky;

use crate::accel::{AccelGeometry, Hit, InstanceRef, TriMeshRef, NO_INSTANCE};
use crate::material::{MaterialView, Wetness};

/// A triangle mesh in render space.
#[derive(Clone, Debug, Default)]
pub struct Mesh {
    /// Positions, render space, f64 (exact GT re-intersection).
    pub p_render: Vec<DVec3>,
    /// The same positions rounded to f32 (traversal and shading).
    pub p_f32: Vec<Vec3>,
    /// Optional per-vertex shading normals (render space = world orientation).
    pub normals: Vec<Vec3>,
    /// Optional per-vertex texture coordinates.
    pub uvs: Vec<Vec2>,
    /// Vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// Material index per triangle (into `Scene::materials`).
    pub tri_material: Vec<u32>,
    /// Semantic class id of the object.
    pub semantic: u8,
    /// Instance id of the object (0 = none).
    pub instance: u16,
}

/// A prefab's meshes built once, in the prefab's own frame: `Mesh::p_render`
/// and `p_f32` hold local positions, `normals` local directions; materials
/// are resolved (a prototype is shared only by instances whose material
/// maps are the same), labels are the prefab's own (instances may override).
#[derive(Clone, Debug, Default)]
pub struct Prototype {
    /// Name of the prefab.
    pub prefab: String,
    /// Meshes in the local frame; `Hit::geom_id` = index.
    pub meshes: Vec<Mesh>,
    /// For a static tile (`anchored`): the semantic class and triangle
    /// count of each static mesh it stands for in content reports (a mesh
    /// cut into pieces is listed once, in the first tile it crosses).
    /// Empty for other prototypes.
    pub sources: Vec<(u8, u64)>,
}

/// One placement of a prototype.
#[derive(Clone, Debug)]
pub struct Instance {
    /// Index into `Scene::prototypes`.
    pub prototype: u32,
    /// Local → render space, f64 (world placement minus the render origin).
    pub render_from_local: DAffine3,
    /// Its f64 inverse (the GT pass re-intersects in the local frame).
    pub local_from_render: DAffine3,
    /// f32 copy of `render_from_local` (shading).
    pub render_from_local_f32: Affine3A,
    /// Local → render map of winding normals (`InstanceRef::normal_to_render`).
    pub normal_to_render: Mat3A,
    /// Semantic class that replaces the prototype's (the instance object's).
    pub semantic: Option<u8>,
    /// Instance id that replaces the prototype's.
    pub instance: Option<u16>,
}

impl Instance {
    /// An instance of `prototype` at `render_from_local`.
    pub fn new(
        prototype: u32,
        render_from_local: DAffine3,
        semantic: Option<u8>,
        instance: Option<u16>,
    ) -> Instance {
        let local_from_render = render_from_local.inverse();
        let accel = InstanceRef {
            prototype,
            render_from_local: render_from_local.as_affine3a(),
            local_from_render: local_from_render.as_affine3a(),
        };
        Instance {
            prototype,
            render_from_local,
            local_from_render,
            render_from_local_f32: accel.render_from_local,
            normal_to_render: accel.normal_to_render(),
            semantic,
            instance,
        }
    }

    /// What the accelerator needs of this instance.
    pub fn accel_ref(&self) -> InstanceRef {
        InstanceRef {
            prototype: self.prototype,
            render_from_local: self.render_from_local_f32,
            local_from_render: self.local_from_render.as_affine3a(),
        }
    }
}

/// An analytic sphere in render space.
#[derive(Clone, Debug)]
pub struct Sphere {
    /// Centre, render space, f64.
    pub center: DVec3,
    /// Radius in metres.
    pub radius: f64,
    /// Material index.
    pub material: u32,
    /// Semantic class id.
    pub semantic: u8,
    /// Instance id (0 = none).
    pub instance: u16,
}

/// The immutable scene of one frame, shared by every view of that frame.
#[derive(Clone, Debug)]
pub struct Scene {
    /// World position of the render-space origin (metres).
    pub origin_world: DVec3,
    /// Flat triangle meshes (render space); geometry id = index.
    pub meshes: Vec<Mesh>,
    /// Prototypes of the instances (local frames).
    pub prototypes: Vec<Prototype>,
    /// Placed prototypes; `Hit::inst_id` = index.
    pub instances: Vec<Instance>,
    /// The instances as the accelerator wants them.
    pub instances_f32: Vec<InstanceRef>,
    /// Analytic spheres; geometry id = `meshes.len()`, prim id = index.
    pub spheres: Vec<Sphere>,
    /// Sphere data as the accelerator wants it (centre, radius), f32.
    pub spheres_f32: Vec<Vec4>,
    /// Materials, referenced by index.
    pub materials: Vec<Material>,
    /// Explicit lights (sun, point, spot); emissive triangles are found from materials.
    pub lights: Vec<Light>,
    /// Environment radiance for rays that leave the scene.
    pub sky: Sky,
    /// Participating medium in render space (None: clear air).
    pub medium: Option<shaders_cpu::medium::Medium>,
    /// Whether renders filter the camera rays' in-scattered radiance
    /// (`MediumDesc::filter_inscatter`; false without a scattering medium).
    pub filter_inscatter: bool,
    /// Whether renders filter the light Lambertian first surfaces reflect
    /// beyond their next-event estimates (`RenderDesc::filter_indirect`;
    /// false in scenes with a medium, whose paths take the volumetric loop).
    pub filter_indirect: bool,
    /// Whether paths widen glossy lobes met after a rough bounce
    /// (`Bsdf::regularized`): on with `RenderDesc::filter_indirect`, also
    /// in fog; off in plain path tracing.
    pub regularize: bool,
    /// The denoiser of the views' surfaces (`RenderDesc::denoiser`).
    pub denoiser: desc::Denoiser,
    /// Rain field centred on the rig; its `seed` is set per frame by the
    /// renderer (`Rain { seed, ..rain }`). None: no rain.
    pub rain: Option<shaders_cpu::medium::Rain>,
    /// Wet surfaces and puddles (None: dry).
    pub wetness: Option<Wetness>,
}

impl Scene {
    /// The view of this scene an accelerator is built over.
    pub fn accel_geometry(&self) -> AccelGeometry<'_> {
        AccelGeometry {
            meshes: self
                .meshes
                .iter()
                .map(|m| TriMeshRef {
                    positions: &m.p_f32,
                    triangles: &m.triangles,
                })
                .collect(),
            spheres: &self.spheres_f32,
            prototypes: self
                .prototypes
                .iter()
                .map(|p| {
                    p.meshes
                        .iter()
                        .map(|m| TriMeshRef {
                            positions: &m.p_f32,
                            triangles: &m.triangles,
                        })
                        .collect()
                })
                .collect(),
            instances: &self.instances_f32,
        }
    }

    /// The mesh a triangle hit lies on, and the instance placing it (None
    /// for flat meshes); None for spheres.
    #[inline]
    pub fn hit_mesh(&self, hit: &Hit) -> Option<(&Mesh, Option<&Instance>)> {
        if hit.inst_id == NO_INSTANCE {
            return self.meshes.get(hit.geom_id as usize).map(|m| (m, None));
        }
        let inst = &self.instances[hit.inst_id as usize];
        let mesh = &self.prototypes[inst.prototype as usize].meshes[hit.geom_id as usize];
        Some((mesh, Some(inst)))
    }

    /// Render-space f64 vertices of the triangle `hit` hit (None for spheres).
    pub fn hit_triangle(&self, hit: &Hit) -> Option<[DVec3; 3]> {
        let (m, inst) = self.hit_mesh(hit)?;
        let tri = m.triangles[hit.prim_id as usize].map(|i| m.p_render[i as usize]);
        Some(match inst {
            None => tri,
            Some(i) => tri.map(|p| i.render_from_local.transform_point3(p)),
        })
    }

    /// Semantic class and instance id of what `hit` hit.
    pub fn hit_labels(&self, hit: &Hit) -> (u8, u16) {
        match self.hit_mesh(hit) {
            Some((m, None)) => (m.semantic, m.instance),
            Some((m, Some(i))) => (
                i.semantic.unwrap_or(m.semantic),
                i.instance.unwrap_or(m.instance),
            ),
            None => {
                let s = &self.spheres[hit.prim_id as usize];
                (s.semantic, s.instance)
            }
        }
    }

    /// Every triangle mesh in render space as if nothing were instanced:
    /// the flat meshes, then each instance's prototype meshes transformed
    /// in f64 (labels resolved). For export and hashing, not rendering.
    pub fn flattened_meshes(&self) -> impl Iterator<Item = std::borrow::Cow<'_, Mesh>> {
        use std::borrow::Cow;
        let flat = self.meshes.iter().map(Cow::Borrowed);
        let placed = self.instances.iter().flat_map(move |inst| {
            self.prototypes[inst.prototype as usize]
                .meshes
                .iter()
                .map(move |m| Cow::Owned(instancing::place_mesh(m, inst)))
        });
        flat.chain(placed)
    }

    /// What shading reads of this scene: materials, wetness, render origin.
    #[inline]
    pub fn material_view(&self) -> MaterialView<'_> {
        MaterialView {
            materials: &self.materials,
            wetness: self.wetness.as_ref(),
            origin_world: self.origin_world,
        }
    }

    /// Triangle count as if flattened (every instance counts its
    /// prototype's triangles); see [`Scene::content`] for stored counts.
    pub fn triangle_count(&self) -> usize {
        self.content().instanced_triangles as usize
    }
}
