//! Scenes: serde descriptions (`desc`), validation with file and key-path
//! errors (`load`), and the immutable, render-space `Scene` built from them
//! (`build`), with OBJ import (`obj`), primitive tessellation (`mesh`),
//! prefab checks (`prefab`), placement (`transform`) and semantic classes.
//!
//! A `Scene` is built once per frame around a render origin (the frame's left
//! camera centre, world coordinates, f64): every position in it is
//! `p_world − origin_world`. f64 copies of positions are kept for the
//! ground-truth pass, which re-intersects the hit primitive in f64.

pub mod build;
pub mod desc;
pub mod load;
pub mod mesh;
mod mtl_check;
pub mod obj;
mod obj_scan;
mod polygon;
pub mod prefab;
mod ranges;
mod resolve;
pub mod semantic;
pub mod transform;
pub mod validate;
mod walk;

pub use build::build_scene;
pub use desc::{serialize_scene, SceneDesc};
pub use load::{load_scene, parse_scene_str, LoadedScene, SceneError, SceneErrorKind};

use glam::{DVec3, Vec2, Vec3, Vec4};
use shaders_cpu::bsdf::Bsdf;
use shaders_cpu::sky::Sky;

use crate::accel::{AccelGeometry, TriMeshRef};
use crate::light::Light;

/// Mask bits of GROUND_TRUTH.md carried by a material.
pub mod mask_bits {
    /// Bit 0: sky (no surface hit).
    pub const SKY: u8 = 1;
    /// Bit 1: covered by rain particles.
    pub const RAIN: u8 = 2;
    /// Bit 2: transparent surface (glass, water).
    pub const TRANSPARENT: u8 = 4;
    /// Bit 3: mirror-like surface (puddle, chrome).
    pub const MIRROR: u8 = 8;
}

/// A resolved material: how a surface scatters and emits.
#[derive(Clone, Debug)]
pub struct Material {
    /// Name from the description (unique).
    pub name: String,
    /// Scattering model, evaluated in the local shading frame.
    pub bsdf: Bsdf,
    /// Emitted radiance (W·m⁻²·sr⁻¹ per RGB channel), zero if not emissive.
    pub le: Vec3,
    /// Whether emission leaves both faces (otherwise only the geometric front).
    pub two_sided_emission: bool,
    /// GT mask bits this surface sets (`mask_bits::TRANSPARENT`, `MIRROR`).
    pub mask: u8,
    /// Procedural albedo variation of a Lambertian `bsdf` (world position).
    pub texture: Option<shaders_cpu::texture::Texture>,
}

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
    pub wetness: Option<crate::integrator::wet::Wetness>,
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

    /// Total triangle count.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum()
    }
}
