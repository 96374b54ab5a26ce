//! Object descriptions: `[[object]]` (and `[[prefab.object]]`) with a shape
//! selected by `kind`, a transform and optional repeats.
//!
//! A local point p goes to its parent frame as T · Rz · Ry · Rx · S · p
//! (scale, then rotations about x, y, z, then translation). Repeats add
//! offsets in the parent frame. World z up, metres, degrees in files.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

/// One object: common placement fields plus a shape (`kind = ...`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectDesc {
    /// Optional name, for messages.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Material name. Required for every shape except `obj` (which may use its
    /// MTL materials) and `instance` (whose prefab objects carry theirs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Semantic class name (see `scene::semantic::CLASSES`); default "unlabeled" (id 0).
    /// On an instance, overrides the prefab objects' classes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub semantic: Option<String>,
    /// Instance id, 0 = none (default 0). On an instance, overrides the
    /// prefab objects' ids.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub instance: Option<u16>,
    /// Placement in the parent frame (default identity).
    #[serde(default, skip_serializing_if = "TransformDesc::is_identity")]
    pub transform: TransformDesc,
    /// Nested grid of copies: each entry multiplies the copies by `count`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub repeat: Vec<RepeatDesc>,
    /// The shape and its parameters.
    #[serde(flatten)]
    pub shape: ShapeDesc,
}

/// Local-to-parent placement: scale, then rotate about x, y, z, then translate.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransformDesc {
    /// Translation in metres (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub translate: Option<[f64; 3]>,
    /// Rotation angles in degrees about x, then y, then z (default 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rotate_deg: Option<[f64; 3]>,
    /// Scale factor(s), each > 0 (default 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scale: Option<ScaleDesc>,
}

impl TransformDesc {
    /// Whether no component is given.
    pub fn is_identity(&self) -> bool {
        self.translate.is_none() && self.rotate_deg.is_none() && self.scale.is_none()
    }
}

/// A uniform (`scale = s`) or per-axis (`scale = [sx, sy, sz]`) scale.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum ScaleDesc {
    /// The same factor on every axis.
    Uniform(f64),
    /// One factor per local axis.
    Axes([f64; 3]),
}

impl ScaleDesc {
    /// The per-axis factors.
    pub fn axes(self) -> [f64; 3] {
        match self {
            ScaleDesc::Uniform(s) => [s; 3],
            ScaleDesc::Axes(a) => a,
        }
    }
}

/// One level of a repeat grid.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RepeatDesc {
    /// Number of copies along this level, ≥ 1.
    pub count: u32,
    /// Offset between consecutive copies, parent frame, metres.
    pub offset: [f64; 3],
}

/// The shape of an object, selected by `kind`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum ShapeDesc {
    /// A rectangle in the local xy plane, normal +z, centred at the origin.
    Quad {
        /// Side lengths along local x and y, metres, > 0.
        size: [f64; 2],
    },
    /// An axis-aligned box centred at the origin.
    Box {
        /// Side lengths along local x, y, z, metres, > 0.
        size: [f64; 3],
    },
    /// An analytic sphere centred at the origin; its transform may only
    /// translate and scale uniformly.
    Sphere {
        /// Radius, metres, > 0.
        radius: f64,
    },
    /// A cylinder along local z with its base at z = 0.
    Cylinder {
        /// Radius, metres, > 0.
        radius: f64,
        /// Height, metres, > 0.
        height: f64,
        /// Number of sides, ≥ 3 (default 32).
        #[serde(default = "default_segments")]
        segments: u32,
        /// Whether the ends are closed by disks (default true).
        #[serde(default = "super::default_true")]
        capped: bool,
    },
    /// A tessellated ellipsoid centred at the origin.
    Ellipsoid {
        /// Semi-axes along local x, y, z, metres, > 0.
        radii: [f64; 3],
        /// Subdivisions around z, ≥ 3 (default 32).
        #[serde(default = "default_segments")]
        segments: u32,
        /// Subdivisions from pole to pole, ≥ 2 (default 16).
        #[serde(default = "default_rings")]
        rings: u32,
    },
    /// A Wavefront OBJ mesh; its MTL materials become scene materials named
    /// "<file>/<mtl name>" unless `material` overrides them all.
    Obj {
        /// Path relative to the scene file.
        file: String,
    },
    /// An inline triangle mesh in the local frame (generated geometry, or
    /// small hand-written meshes), checked as OBJ files are: finite vertices
    /// within ±1e7 m, indices in range, degenerate triangles dropped (a mesh
    /// with none left is an error). Needs `material`.
    Mesh {
        /// Vertex positions, metres.
        positions: Vec<[f64; 3]>,
        /// Per-vertex shading normals, one per position, or none (flat
        /// shading); each is normalised, so only its direction counts.
        #[serde(default, skip_serializing_if = "Vec::is_empty")]
        normals: Vec<[f64; 3]>,
        /// Vertex indices (0-based), counter-clockwise seen from the front.
        triangles: Vec<[u32; 3]>,
    },
    /// A copy of a `[[prefab]]`.
    Instance {
        /// Prefab name.
        prefab: String,
        /// Material renames applied to the prefab's objects (`from = "to"`).
        #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
        material_map: BTreeMap<String, String>,
    },
}

/// A reusable group of objects in its own frame.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PrefabDesc {
    /// Unique name, referenced by instance objects.
    pub name: String,
    /// The prefab's objects (they may instance other prefabs, without cycles).
    #[serde(rename = "object")]
    pub objects: Vec<ObjectDesc>,
}

fn default_segments() -> u32 {
    32
}
fn default_rings() -> u32 {
    16
}
