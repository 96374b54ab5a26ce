//! Flattening the object tree: top-level objects, prefab instances (with
//! composed material maps and semantic/instance overrides) and repeat grids,
//! in f64 world coordinates. Shared by validation and `build_scene`.
//!
//! world_from_local composes right to left: instance frames, then the
//! object's repeat offset, then its own transform.
//!
//! `walk_top` and `walk_prefab` walk one top-level object, or one prefab's
//! contents in the prefab's own frame: what `instancing` needs to build a
//! prototype once and to flatten what stays flat.

use std::collections::BTreeMap;

use glam::{DAffine3, DVec3};

use super::desc::{ObjectDesc, SceneDesc, ShapeDesc};
use super::semantic::class_id;
use super::transform::{parent_from_local, repeat_offsets};

/// One leaf object (not an instance) placed in the world.
pub struct Placed<'a> {
    /// Key path of the object in the file (`prefab[1].object[0]`).
    pub key: String,
    /// The instance chain that placed it (" (via object[3])"), or empty.
    pub via: String,
    /// The object as written.
    pub object: &'a ObjectDesc,
    /// Local → world (f64, metres).
    pub world_from_local: DAffine3,
    /// Material maps of the enclosing instances, outermost first.
    pub maps: Vec<&'a BTreeMap<String, String>>,
    /// Semantic class id after overrides.
    pub semantic: u8,
    /// Instance id after overrides.
    pub instance: u16,
}

impl Placed<'_> {
    /// A material name as the enclosing instances rename it (innermost first).
    pub fn map_material(&self, name: &str) -> String {
        self.maps
            .iter()
            .rev()
            .fold(name.to_string(), |n, map| map.get(&n).cloned().unwrap_or(n))
    }
}

struct Frame<'a> {
    world_from_parent: DAffine3,
    maps: Vec<&'a BTreeMap<String, String>>,
    semantic: Option<&'a str>,
    instance: Option<u16>,
    via: String,
}

impl Frame<'_> {
    /// The scene's own frame: world coordinates, no renames or overrides.
    fn top() -> Self {
        Frame {
            world_from_parent: DAffine3::IDENTITY,
            maps: Vec::new(),
            semantic: None,
            instance: None,
            via: String::new(),
        }
    }
}

/// Calls `visit` for every leaf object. With `expand_repeats` false each
/// object is visited once (its first copy), which is all validation needs.
/// Prefab references must already be checked (known names, no cycles).
pub fn walk<'a, E>(
    desc: &'a SceneDesc,
    expand_repeats: bool,
    visit: &mut dyn FnMut(Placed<'a>) -> Result<(), E>,
) -> Result<(), E> {
    let top = Frame::top();
    for (i, object) in desc.objects.iter().enumerate() {
        walk_object(
            desc,
            object,
            format!("object[{i}]"),
            &top,
            expand_repeats,
            visit,
        )?;
    }
    Ok(())
}

/// Calls `visit` for every leaf of top-level object `i` (repeats expanded).
pub fn walk_top<'a, E>(
    desc: &'a SceneDesc,
    i: usize,
    visit: &mut dyn FnMut(Placed<'a>) -> Result<(), E>,
) -> Result<(), E> {
    let top = Frame::top();
    walk_object(
        desc,
        &desc.objects[i],
        format!("object[{i}]"),
        &top,
        true,
        visit,
    )
}

/// Calls `visit` for every leaf of prefab `prefab` as top-level object `i`
/// instances it with `material_map`, in the prefab's frame (world_from_local
/// is prefab_from_local) and without the object's semantic/instance
/// overrides (the instance applies those).
pub fn walk_prefab<'a, E>(
    desc: &'a SceneDesc,
    i: usize,
    prefab: &str,
    material_map: &'a BTreeMap<String, String>,
    visit: &mut dyn FnMut(Placed<'a>) -> Result<(), E>,
) -> Result<(), E> {
    let inner = Frame {
        world_from_parent: DAffine3::IDENTITY,
        maps: vec![material_map],
        semantic: None,
        instance: None,
        via: format!("object[{i}] → "),
    };
    walk_prefab_objects(desc, prefab, &inner, true, visit)
}

/// Walks the objects of prefab `prefab` in `frame` (unknown names are
/// reported by validation before any walk).
fn walk_prefab_objects<'a, E>(
    desc: &'a SceneDesc,
    prefab: &str,
    frame: &Frame<'a>,
    expand_repeats: bool,
    visit: &mut dyn FnMut(Placed<'a>) -> Result<(), E>,
) -> Result<(), E> {
    let Some((p, prefab_desc)) = desc
        .prefabs
        .iter()
        .enumerate()
        .find(|(_, p)| p.name == prefab)
    else {
        return Ok(());
    };
    for (j, child) in prefab_desc.objects.iter().enumerate() {
        walk_object(
            desc,
            child,
            format!("prefab[{p}].object[{j}]"),
            frame,
            expand_repeats,
            visit,
        )?;
    }
    Ok(())
}

fn walk_object<'a, E>(
    desc: &'a SceneDesc,
    object: &'a ObjectDesc,
    key: String,
    frame: &Frame<'a>,
    expand_repeats: bool,
    visit: &mut dyn FnMut(Placed<'a>) -> Result<(), E>,
) -> Result<(), E> {
    let parent_from_local = parent_from_local(&object.transform);
    let offsets = if expand_repeats {
        repeat_offsets(&object.repeat)
    } else {
        vec![DVec3::ZERO]
    };
    // Outer overrides win over inner ones.
    let semantic = frame.semantic.or(object.semantic.as_deref());
    let instance = frame.instance.or(object.instance);
    for offset in offsets {
        let world_from_local =
            frame.world_from_parent * DAffine3::from_translation(offset) * parent_from_local;
        match &object.shape {
            ShapeDesc::Instance {
                prefab,
                material_map,
            } => {
                let mut maps = frame.maps.clone();
                maps.push(material_map);
                let inner = Frame {
                    world_from_parent: world_from_local,
                    maps,
                    semantic,
                    instance,
                    via: format!("{}{key} → ", frame.via),
                };
                walk_prefab_objects(desc, prefab, &inner, expand_repeats, visit)?;
            }
            _ => visit(Placed {
                key: key.clone(),
                via: if frame.via.is_empty() {
                    String::new()
                } else {
                    format!(" (via {})", frame.via.trim_end_matches(" → "))
                },
                object,
                world_from_local,
                maps: frame.maps.clone(),
                semantic: semantic.and_then(class_id).unwrap_or(0),
                instance: instance.unwrap_or(0),
            })?,
        }
    }
    Ok(())
}
