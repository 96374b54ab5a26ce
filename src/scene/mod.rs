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

pub mod build;
pub mod desc;
pub mod emitters;
mod huge;
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
pub mod transform;
pub mod validate;
mod walk;

pub use build::build_scene;
pub use desc::{serialize_scene, SceneDesc};
pub use emitters::Light;
pub use load::{load_scene, parse_scene_str, LoadedScene, SceneError, SceneErrorKind};
pub use surface::surface_interaction;
pub use table::SurfaceTable;
// Materials are built below the scene; a scene stores them.
pub use crate::material::{mask_bits, Material};

use glam::{DVec3, Vec2, Vec3, Vec4};
use shaders_cpu::sky::Sky;

use crate::accel::{AccelGeometry, TriMeshRef};
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
    /// Triangle meshes; geometry id = index.
    pub meshes: Vec<Mesh>,
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
        }
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

    /// Total triangle count.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum()
    }
}
