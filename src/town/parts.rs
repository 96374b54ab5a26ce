//! Small constructors for scene objects the generators emit: boxes, quads,
//! cylinders, ellipsoids and prefab instances with a material, a semantic
//! class and an instance id, placed by translation and a heading about z.

use std::collections::BTreeMap;

use crate::scene::desc::{ObjectDesc, RepeatDesc, ScaleDesc, ShapeDesc, TransformDesc};
use crate::scene::mesh::LocalMesh;

/// Label of an object: semantic class name and instance id (0 = none).
#[derive(Clone, Copy, Debug)]
pub struct Label {
    /// Semantic class (see `scene::semantic::CLASSES`).
    pub class: &'static str,
    /// Instance id.
    pub instance: u16,
}

/// A label without an instance id.
pub fn class(name: &'static str) -> Label {
    Label {
        class: name,
        instance: 0,
    }
}

fn transform(at: [f64; 3], heading_deg: f64) -> TransformDesc {
    TransformDesc {
        translate: Some(at),
        rotate_deg: (heading_deg != 0.0).then_some([0.0, 0.0, heading_deg]),
        scale: None,
    }
}

/// An object of `shape` with a material, `label`'s class and instance,
/// placed by `t`.
pub fn object(
    shape: ShapeDesc,
    material: Option<&str>,
    label: Label,
    t: TransformDesc,
) -> ObjectDesc {
    ObjectDesc {
        name: None,
        material: material.map(str::to_string),
        semantic: Some(label.class.to_string()),
        instance: (label.instance != 0).then_some(label.instance),
        transform: t,
        repeat: Vec::new(),
        shape,
    }
}

/// A box of `size` centred at `at`, turned by `heading_deg` about z.
pub fn cuboid(size: [f64; 3], at: [f64; 3], heading_deg: f64, mat: &str, l: Label) -> ObjectDesc {
    object(
        ShapeDesc::Box { size },
        Some(mat),
        l,
        transform(at, heading_deg),
    )
}

/// A box on the ground: `min`/`max` corners of its footprint, top at `top_z`,
/// bottom at `bottom_z`.
pub fn slab(
    min: [f64; 2],
    max: [f64; 2],
    bottom_z: f64,
    top_z: f64,
    mat: &str,
    l: Label,
) -> ObjectDesc {
    let size = [max[0] - min[0], max[1] - min[1], top_z - bottom_z];
    let at = [
        (min[0] + max[0]) / 2.0,
        (min[1] + max[1]) / 2.0,
        (bottom_z + top_z) / 2.0,
    ];
    cuboid(size, at, 0.0, mat, l)
}

/// A horizontal rectangle facing up at height `z`.
pub fn ground_quad(min: [f64; 2], max: [f64; 2], z: f64, mat: &str, l: Label) -> ObjectDesc {
    let size = [max[0] - min[0], max[1] - min[1]];
    let at = [(min[0] + max[0]) / 2.0, (min[1] + max[1]) / 2.0, z];
    object(ShapeDesc::Quad { size }, Some(mat), l, transform(at, 0.0))
}

/// A mesh already in world coordinates (identity transform), which the
/// organic warp bends vertex by vertex.
pub fn world_mesh(mesh: LocalMesh, mat: &str, l: Label) -> ObjectDesc {
    object(mesh.into_shape(), Some(mat), l, TransformDesc::default())
}

/// A vertical cylinder with its base at `at`.
pub fn cylinder(
    radius: f64,
    height: f64,
    segments: u32,
    at: [f64; 3],
    mat: &str,
    l: Label,
) -> ObjectDesc {
    object(
        ShapeDesc::Cylinder {
            radius,
            height,
            segments,
            capped: true,
        },
        Some(mat),
        l,
        transform(at, 0.0),
    )
}

/// A cylinder lying along local y (an axle) centred at `at` in the parent frame.
pub fn wheel(radius: f64, width: f64, at: [f64; 3], mat: &str, l: Label) -> ObjectDesc {
    let t = TransformDesc {
        translate: Some([at[0], at[1] + width / 2.0, at[2]]),
        rotate_deg: Some([90.0, 0.0, 0.0]),
        scale: None,
    };
    object(
        ShapeDesc::Cylinder {
            radius,
            height: width,
            segments: 16,
            capped: true,
        },
        Some(mat),
        l,
        t,
    )
}

/// A coarse ellipsoid centred at `at`.
pub fn blob(radii: [f64; 3], at: [f64; 3], mat: &str, l: Label) -> ObjectDesc {
    object(
        ShapeDesc::Ellipsoid {
            radii,
            segments: 14,
            rings: 8,
        },
        Some(mat),
        l,
        transform(at, 0.0),
    )
}

/// An instance of prefab `name` at `at`, heading `heading_deg`, with
/// material renames and a label overriding the prefab's.
pub fn instance(
    name: &str,
    at: [f64; 3],
    heading_deg: f64,
    map: &[(&str, &str)],
    l: Label,
) -> ObjectDesc {
    let material_map: BTreeMap<String, String> = map
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    object(
        ShapeDesc::Instance {
            prefab: name.to_string(),
            material_map,
        },
        None,
        l,
        transform(at, heading_deg),
    )
}

/// The same object with a repeat grid (count, offset) per level.
pub fn repeated(mut o: ObjectDesc, levels: &[(u32, [f64; 3])]) -> ObjectDesc {
    o.repeat = levels
        .iter()
        .filter(|(c, _)| *c > 1)
        .map(|&(count, offset)| RepeatDesc { count, offset })
        .collect();
    o
}

/// The same object scaled per axis (applied before rotation).
pub fn scaled(mut o: ObjectDesc, s: [f64; 3]) -> ObjectDesc {
    o.transform.scale = Some(ScaleDesc::Axes(s));
    o
}

/// A horizontal rectangle facing up, centred at `at`, turned by
/// `heading_deg` about z (a turn about z keeps its height exact).
pub fn turned_quad(
    size: [f64; 2],
    at: [f64; 3],
    heading_deg: f64,
    mat: &str,
    l: Label,
) -> ObjectDesc {
    object(
        ShapeDesc::Quad { size },
        Some(mat),
        l,
        transform(at, heading_deg),
    )
}
