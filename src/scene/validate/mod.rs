//! Full validation of a `SceneDesc`: ranges, references (materials, prefabs,
//! semantic classes), prefab cycles, resource guards (pixels, frame memory,
//! triangle count, all before allocating), OBJ loading and inline mesh
//! checks (`mesh::check_inline`), and "no light". The checks of each table
//! live in their own file (`rig`, `emitters`, `material`, `object`); this
//! one runs them in order and owns the whole-scene rules.
//!
//! Every error names the scene file and the key path of the offending value.

mod emitters;
mod material;
mod object;
mod rig;

pub use rig::{check_rig, frame_bytes, MAX_PIXELS};

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use super::desc::{
    LightDesc, MaterialDesc, MaterialKindDesc, ObjectDesc, SceneDesc, ShapeDesc, SkyDesc,
};
use super::load::{SceneError, SceneErrorKind as K};
use super::obj::{count_triangles, load_obj, ObjAsset};
use super::ranges::V;
use crate::sampler::MAX_SPP;

/// Largest accepted triangle count of a built scene.
pub const MAX_TRIANGLES: u64 = 100_000_000;

/// Every material of the built scene, in index order: the file's, then each
/// OBJ file's MTL materials (OBJ files in key order).
pub fn material_table<'a>(
    desc: &'a SceneDesc,
    objs: &'a BTreeMap<String, ObjAsset>,
) -> Vec<&'a MaterialDesc> {
    desc.materials
        .iter()
        .chain(objs.values().flat_map(|o| o.materials.iter()))
        .collect()
}

/// Every object with its key: top level, then each prefab's.
pub(crate) fn all_objects(desc: &SceneDesc) -> Vec<(String, &ObjectDesc)> {
    let top = desc
        .objects
        .iter()
        .enumerate()
        .map(|(i, o)| (format!("object[{i}]"), o));
    let inner = desc.prefabs.iter().enumerate().flat_map(|(p, pf)| {
        pf.objects
            .iter()
            .enumerate()
            .map(move |(j, o)| (format!("prefab[{p}].object[{j}]"), o))
    });
    top.chain(inner).collect()
}

/// Validates everything; returns the loaded OBJ files and the triangle count.
/// Checks run in a fixed order, so a file with several faults always
/// reports the same first one.
pub fn validate(
    desc: &SceneDesc,
    file: &Path,
) -> Result<(BTreeMap<String, ObjAsset>, u64), SceneError> {
    let v = V { file };
    v.rig(&desc.camera)?;
    v.render(desc)?;
    v.sky_and_lights(desc)?;
    v.materials(desc)?;
    v.prefab_names(desc)?;
    let objects = all_objects(desc);
    for (key, o) in &objects {
        v.object(key, o, desc)?;
    }
    super::prefab::check_cycles(desc, file)?;
    let (objs, exact) = load_objs(desc, file, &objects)?;
    let table = material_table(desc, &objs);
    let used = super::resolve::check_references(desc, &objs, &table, file)?;
    check_lit(desc, &table, &used, file)?;
    Ok((objs, exact))
}

impl V<'_> {
    /// `[render]`: samples per pixel and path depth.
    fn render(&self, desc: &SceneDesc) -> Result<(), SceneError> {
        if desc.render.spp == 0 || desc.render.spp > MAX_SPP {
            return Err(self.err(
                "render.spp",
                format!("must be in [1, {}], got {}", MAX_SPP, desc.render.spp),
            ));
        }
        if desc.render.max_depth == 0 {
            return Err(self.err("render.max_depth", "must be ≥ 1"));
        }
        Ok(())
    }

    /// The sky (a physical sky brings its own sun, so no sun light beside
    /// it), the weather tables, then every light.
    fn sky_and_lights(&self, desc: &SceneDesc) -> Result<(), SceneError> {
        if let Some(sky) = &desc.sky {
            self.sky(sky)?;
            let own_sun = matches!(sky, SkyDesc::Physical { .. });
            if let Some(i) = desc
                .lights
                .iter()
                .position(|l| own_sun && matches!(l, LightDesc::Sun { .. }))
            {
                return Err(self.err(
                    format!("light[{i}]"),
                    "a physical sky brings its own sun: remove the sun light and set sky.sun_elevation_deg / sky.sun_azimuth_deg",
                ));
            }
        }
        desc.check_weather()
            .map_err(|(key, msg)| self.err(key, msg))?;
        for (i, l) in desc.lights.iter().enumerate() {
            self.light(i, l)?;
        }
        Ok(())
    }

    /// Every material, and unique material names.
    fn materials(&self, desc: &SceneDesc) -> Result<(), SceneError> {
        let mut first: HashMap<&str, usize> = HashMap::new();
        for (i, m) in desc.materials.iter().enumerate() {
            self.material(i, m)?;
            if let Some(j) = first.insert(&m.name, i) {
                return Err(self.err(
                    format!("material[{i}].name"),
                    format!(
                        "duplicate material name \"{}\" (first at material[{j}])",
                        m.name
                    ),
                ));
            }
        }
        Ok(())
    }

    /// Unique prefab names.
    fn prefab_names(&self, desc: &SceneDesc) -> Result<(), SceneError> {
        let mut first: HashMap<&str, usize> = HashMap::new();
        for (p, pf) in desc.prefabs.iter().enumerate() {
            if let Some(q) = first.insert(&pf.name, p) {
                return Err(self.err(
                    format!("prefab[{p}].name"),
                    format!(
                        "duplicate prefab name \"{}\" (first at prefab[{q}])",
                        pf.name
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// Reads every OBJ file once, guards the triangle count on `f`-line counts
/// alone (before any OBJ parse or tessellation), then loads them; returns
/// the loaded files and the scene's exact triangle count.
fn load_objs(
    desc: &SceneDesc,
    file: &Path,
    objects: &[(String, &ObjectDesc)],
) -> Result<(BTreeMap<String, ObjAsset>, u64), SceneError> {
    let mut obj_texts = BTreeMap::new();
    for (key, o) in objects {
        if let ShapeDesc::Obj { file: f } = &o.shape {
            if !obj_texts.contains_key(f) {
                let path = obj_path(file, f);
                let text = std::fs::read_to_string(&path).map_err(|e| {
                    SceneError::at(
                        file,
                        K::Io,
                        format!("{key}.file"),
                        format!("cannot read OBJ {}: {e}", path.display()),
                    )
                })?;
                obj_texts.insert(f.clone(), (key.clone(), count_triangles(&text)));
            }
        }
    }
    let counts: BTreeMap<String, u64> = obj_texts
        .iter()
        .map(|(f, (_, n))| (f.clone(), *n))
        .collect();
    let estimate = super::prefab::estimate_triangles(desc, &desc.objects, &counts);
    if estimate > MAX_TRIANGLES {
        return Err(SceneError::at(file, K::Resource, "object", format!("the scene would have about {estimate} triangles, above the limit of {MAX_TRIANGLES}")));
    }
    let mut objs = BTreeMap::new();
    for (f, (key, _)) in &obj_texts {
        objs.insert(
            f.clone(),
            load_obj(file, &format!("{key}.file"), f, &obj_path(file, f))?,
        );
    }
    let exact = super::prefab::estimate_triangles(
        desc,
        &desc.objects,
        &objs
            .iter()
            .map(|(f, o)| (f.clone(), o.triangle_count()))
            .collect(),
    );
    Ok((objs, exact))
}

/// Something lights the scene: a light with power, an emissive material in
/// use (`used`, per entry of `table`), or a sky that is not black.
fn check_lit(
    desc: &SceneDesc,
    table: &[&MaterialDesc],
    used: &[bool],
    file: &Path,
) -> Result<(), SceneError> {
    let emitting = table.iter().zip(used).any(|(m, &u)| u && matches!(&m.kind, MaterialKindDesc::Emissive { radiance, .. } if radiance.iter().any(|&x| x > 0.0)));
    let lit = desc.lights.iter().any(|l| match l {
        LightDesc::Sun { irradiance: c, .. }
        | LightDesc::Point { intensity: c, .. }
        | LightDesc::Spot { intensity: c, .. } => c.iter().any(|&x| x > 0.0),
    });
    if !lit && !sky_lit(desc.sky.as_ref()) && !emitting {
        let msg = "no light: no sun, point or spot light with power, no emissive material in use, and the sky is black";
        return Err(SceneError::at(file, K::NoLight, "", msg));
    }
    Ok(())
}

/// Whether the sky gives any light.
fn sky_lit(sky: Option<&SkyDesc>) -> bool {
    match sky {
        Some(SkyDesc::Constant { le }) => le.iter().any(|&x| x > 0.0),
        Some(SkyDesc::Gradient {
            zenith,
            horizon,
            ground,
        }) => zenith.iter().chain(horizon).chain(ground).any(|&x| x > 0.0),
        // Airglow keeps the night sky above zero; the physical sky is dark
        // once the sun is past astronomical twilight.
        Some(SkyDesc::Physical {
            sun_elevation_deg, ..
        }) => *sun_elevation_deg > -20.0,
        Some(SkyDesc::Night { .. }) => true,
        Some(SkyDesc::Overcast { irradiance, .. }) => irradiance.iter().any(|&x| x > 0.0),
        None => false,
    }
}

/// An OBJ path from the scene file's directory.
pub fn obj_path(scene: &Path, file: &str) -> std::path::PathBuf {
    scene.parent().unwrap_or(Path::new(".")).join(file)
}
