//! Full validation of a `SceneDesc`: ranges, references (materials, prefabs,
//! semantic classes), prefab cycles, resource guards (pixels, frame memory,
//! triangle count, all before allocating), OBJ loading and inline mesh
//! checks (`mesh::check_inline`), and "no light".
//!
//! Every error names the scene file and the key path of the offending value.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use super::desc::{
    LightDesc, MaterialDesc, MaterialKindDesc, ObjectDesc, RigDesc, ScaleDesc, SceneDesc,
    ShapeDesc, SkyDesc,
};
use super::load::{SceneError, SceneErrorKind as K};
use super::mesh::MAX_COORD_M;
use super::obj::{count_triangles, load_obj, ObjAsset};
use super::desc::num;
use super::ranges::V;
use super::semantic::{class_id, CLASSES};

/// Largest accepted image, pixels (64 megapixels).
pub const MAX_PIXELS: u64 = 64_000_000;
/// Largest accepted triangle count of a built scene.
pub const MAX_TRIANGLES: u64 = 100_000_000;

/// Bytes of film and ground-truth buffers of one frame: per view (left and
/// one right per baseline) f64 RGB accumulation 24, f32 RGB 12, depth 4,
/// normal 12, semantic 1, instance 2, mask 1 (56 with padding); per baseline
/// a left and a right disparity (4) and occlusion (1) (8 each with padding).
pub fn frame_bytes(rig: &RigDesc) -> u64 {
    let baselines = rig.baselines_cm.len() as u64;
    let per_pixel = (1 + baselines) * 56 + 2 * baselines * 8;
    rig.width as u64 * rig.height as u64 * per_pixel
}

/// Validates a rig on its own (e.g. after command-line overrides), naming `file`.
pub fn check_rig(rig: &RigDesc, file: &Path) -> Result<(), SceneError> {
    V { file }.rig(rig)
}

impl V<'_> {
    fn rig(&self, rig: &RigDesc) -> Result<(), SceneError> {
        if rig.width == 0 || rig.height == 0 {
            let key = if rig.width == 0 {
                "camera.width"
            } else {
                "camera.height"
            };
            return Err(self.err(key, "image size must be at least 1 pixel"));
        }
        self.finite("camera.hfov_deg", &[rig.hfov_deg])?;
        if !(rig.hfov_deg > 0.0 && rig.hfov_deg < 180.0) {
            return Err(self.err(
                "camera.hfov_deg",
                format!("must be in (0, 180), got {}", num(rig.hfov_deg)),
            ));
        }
        if rig.baselines_cm.is_empty() {
            return Err(self.err("camera.baselines_cm", "at least one baseline is needed"));
        }
        self.positive("camera.baselines_cm", &rig.baselines_cm)?;
        // Centimetres: the right camera stays within the coordinate limit.
        self.range(
            "camera.baselines_cm",
            &rig.baselines_cm,
            0.0,
            MAX_COORD_M * 100.0,
        )?;
        crate::camera::check_baseline_dirs(&rig.baselines_cm)
            .map_err(|e| self.err(format!("camera.baselines_cm[{}]", e.index), e.to_string()))?;
        self.coord("camera.position", &rig.position)?;
        self.finite("camera.yaw_deg", &[rig.yaw_deg])?;
        self.range("camera.pitch_deg", &[rig.pitch_deg], -90.0, 90.0)?;
        self.range("camera.roll_deg", &[rig.roll_deg], -180.0, 180.0)?;
        let pixels = rig.width as u64 * rig.height as u64;
        if pixels > MAX_PIXELS {
            return Err(SceneError::at(
                self.file,
                K::Resource,
                "camera.width",
                format!(
                    "{}×{} = {pixels} pixels exceeds the limit of {MAX_PIXELS} pixels",
                    rig.width, rig.height
                ),
            ));
        }
        let need = frame_bytes(rig);
        if let Some(avail) = available_memory_bytes() {
            if need > avail {
                return Err(SceneError::at(
                    self.file,
                    K::Resource,
                    "camera.width",
                    format!(
                        "film and ground-truth buffers for {}×{} with {} baselines need {:.1} GiB, only {:.1} GiB of memory is available",
                        rig.width,
                        rig.height,
                        rig.baselines_cm.len(),
                        need as f64 / (1u64 << 30) as f64,
                        avail as f64 / (1u64 << 30) as f64
                    ),
                ));
            }
        }
        Ok(())
    }

    fn sky(&self, sky: &SkyDesc) -> Result<(), SceneError> {
        match sky {
            SkyDesc::Constant { le } => self.range("sky.le", le, 0.0, f64::MAX),
            SkyDesc::Gradient {
                zenith,
                horizon,
                ground,
            } => {
                self.range("sky.zenith", zenith, 0.0, f64::MAX)?;
                self.range("sky.horizon", horizon, 0.0, f64::MAX)?;
                self.range("sky.ground", ground, 0.0, f64::MAX)
            }
            SkyDesc::Physical {
                sun_elevation_deg,
                sun_azimuth_deg,
                turbidity,
                ground_albedo,
                cloud_cover,
                cloud_seed: _,
            } => {
                self.range("sky.sun_elevation_deg", &[*sun_elevation_deg], -90.0, 90.0)?;
                self.finite("sky.sun_azimuth_deg", &[*sun_azimuth_deg])?;
                self.range("sky.turbidity", &[*turbidity], 0.0, 20.0)?;
                self.range("sky.ground_albedo", &[*ground_albedo], 0.0, 1.0)?;
                self.range("sky.cloud_cover", &[*cloud_cover], 0.0, 1.0)
            }
            SkyDesc::Overcast {
                irradiance,
                ground_albedo,
            } => {
                self.range("sky.irradiance", irradiance, 0.0, f64::MAX)?;
                self.range("sky.ground_albedo", &[*ground_albedo], 0.0, 1.0)
            }
            SkyDesc::Night {
                moon_elevation_deg,
                moon_azimuth_deg,
                moon_phase_deg,
                sky_glow,
                turbidity,
                ..
            } => {
                self.range(
                    "sky.moon_elevation_deg",
                    &[*moon_elevation_deg],
                    -90.0,
                    90.0,
                )?;
                self.finite("sky.moon_azimuth_deg", &[*moon_azimuth_deg])?;
                self.range("sky.moon_phase_deg", &[*moon_phase_deg], 0.0, 180.0)?;
                self.range("sky.sky_glow", &[*sky_glow], 0.0, 1.0)?;
                self.range("sky.turbidity", &[*turbidity], 0.0, 20.0)
            }
        }
    }

    fn light(&self, i: usize, light: &LightDesc) -> Result<(), SceneError> {
        let k = |f: &str| format!("light[{i}].{f}");
        match light {
            LightDesc::Sun {
                elevation_deg,
                azimuth_deg,
                irradiance,
                angular_diameter_deg,
            } => {
                self.range(&k("elevation_deg"), &[*elevation_deg], -90.0, 90.0)?;
                self.finite(&k("azimuth_deg"), &[*azimuth_deg])?;
                self.range(&k("irradiance"), irradiance, 0.0, f64::MAX)?;
                self.positive(&k("angular_diameter_deg"), &[*angular_diameter_deg])?;
                self.range(
                    &k("angular_diameter_deg"),
                    &[*angular_diameter_deg],
                    0.0,
                    90.0,
                )
            }
            LightDesc::Point {
                position,
                intensity,
            } => {
                self.coord(&k("position"), position)?;
                self.range(&k("intensity"), intensity, 0.0, f64::MAX)
            }
            LightDesc::Spot {
                position,
                direction,
                intensity,
                inner_deg,
                outer_deg,
            } => {
                self.coord(&k("position"), position)?;
                self.finite(&k("direction"), direction)?;
                if direction.iter().all(|&x| x == 0.0) {
                    return Err(self.err(k("direction"), "must not be the zero vector"));
                }
                self.range(&k("intensity"), intensity, 0.0, f64::MAX)?;
                self.positive(&k("outer_deg"), &[*outer_deg])?;
                self.range(&k("outer_deg"), &[*outer_deg], 0.0, 179.999)?;
                self.range(&k("inner_deg"), &[*inner_deg], 0.0, *outer_deg)
            }
        }
    }

    fn material(&self, i: usize, m: &MaterialDesc) -> Result<(), SceneError> {
        let k = |f: &str| format!("material[{i}].{f}");
        if m.name.is_empty() || m.name.contains('/') {
            return Err(self.err(
                k("name"),
                format!(
                    "\"{}\": names must be non-empty without '/' (reserved for OBJ materials)",
                    m.name
                ),
            ));
        }
        if let Some(t) = &m.texture {
            if !matches!(m.kind, MaterialKindDesc::Diffuse { .. }) {
                return Err(self.err(k("texture"), "textures apply to diffuse materials only"));
            }
            self.range(&k("texture.scale"), &[t.scale], 1e-3, 1e3)?;
        }
        match &m.kind {
            MaterialKindDesc::Diffuse { albedo } => self.range(&k("albedo"), albedo, 0.0, 1.0),
            MaterialKindDesc::Conductor {
                preset,
                eta,
                k: kk,
                roughness,
            } => {
                self.range(&k("roughness"), &[*roughness], 0.0, 1.0)?;
                match (preset, eta, kk) {
                    (Some(_), None, None) => Ok(()),
                    (None, Some(eta), Some(kk)) => {
                        self.positive(&k("eta"), eta)?;
                        self.range(&k("k"), kk, 0.0, f64::MAX)
                    }
                    _ => Err(self.err(k("preset"), "give either `preset` or both `eta` and `k`")),
                }
            }
            MaterialKindDesc::Dielectric {
                ior,
                roughness,
                tint,
            } => {
                self.positive(&k("ior"), &[*ior])?;
                self.range(&k("roughness"), &[*roughness], 0.0, 1.0)?;
                self.range(&k("tint"), tint, 0.0, 1.0)
            }
            MaterialKindDesc::Emissive { radiance, .. } => {
                self.range(&k("radiance"), radiance, 0.0, f64::MAX)
            }
            MaterialKindDesc::Coated {
                albedo,
                preset,
                eta,
                k: kk,
                base_roughness,
                coat_ior,
                coat_roughness,
            } => {
                self.range(&k("coat_ior"), &[*coat_ior], 1.0 + 1e-6, 3.0)?;
                self.range(&k("coat_roughness"), &[*coat_roughness], 0.0, 1.0)?;
                self.range(&k("base_roughness"), &[*base_roughness], 0.0, 1.0)?;
                match (albedo, preset, eta, kk) {
                    (Some(a), None, None, None) => self.range(&k("albedo"), a, 0.0, 1.0),
                    (None, Some(_), None, None) => Ok(()),
                    (None, None, Some(eta), Some(kk)) => {
                        self.positive(&k("eta"), eta)?;
                        self.range(&k("k"), kk, 0.0, f64::MAX)
                    }
                    _ => Err(self.err(
                        k("albedo"),
                        "give exactly one base: `albedo`, `preset`, or both `eta` and `k`",
                    )),
                }
            }
        }
    }

    /// Checks one object's own fields (not references that depend on instancing).
    fn object(&self, key: &str, o: &ObjectDesc, desc: &SceneDesc) -> Result<(), SceneError> {
        let k = |f: &str| format!("{key}.{f}");
        if let Some(s) = &o.semantic {
            if class_id(s).is_none() {
                let known: Vec<&str> = CLASSES.iter().map(|c| c.0).collect();
                return Err(self.err(
                    k("semantic"),
                    format!(
                        "unknown semantic class \"{s}\" (known: {})",
                        known.join(", ")
                    ),
                ));
            }
        }
        let t = &o.transform;
        self.coord(&k("transform.translate"), &t.translate.unwrap_or_default())?;
        self.finite(
            &k("transform.rotate_deg"),
            &t.rotate_deg.unwrap_or_default(),
        )?;
        if let Some(s) = t.scale {
            self.positive(&k("transform.scale"), &s.axes())?;
            // A factor beyond the coordinate limit takes any shape beyond it.
            self.range(&k("transform.scale"), &s.axes(), 0.0, MAX_COORD_M)?;
        }
        for (r, level) in o.repeat.iter().enumerate() {
            if level.count == 0 {
                return Err(self.err(k(&format!("repeat[{r}].count")), "must be ≥ 1"));
            }
            self.coord(&k(&format!("repeat[{r}].offset")), &level.offset)?;
        }
        let needs_material = !matches!(o.shape, ShapeDesc::Obj { .. } | ShapeDesc::Instance { .. });
        if needs_material && o.material.is_none() {
            return Err(self.err(k("material"), "missing material"));
        }
        match &o.shape {
            ShapeDesc::Quad { size } => self.length(&k("size"), size),
            ShapeDesc::Box { size } => self.length(&k("size"), size),
            ShapeDesc::Sphere { radius } => {
                self.length(&k("radius"), &[*radius])?;
                if t.rotate_deg.is_some_and(|r| r != [0.0; 3]) {
                    return Err(self.err(
                        k("transform.rotate_deg"),
                        "a sphere may only be translated and scaled uniformly",
                    ));
                }
                if let Some(ScaleDesc::Axes([a, b, c])) = t.scale {
                    if a != b || b != c {
                        return Err(self.err(
                            k("transform.scale"),
                            "a sphere may only be scaled uniformly",
                        ));
                    }
                }
                Ok(())
            }
            ShapeDesc::Cylinder {
                radius,
                height,
                segments,
                ..
            } => {
                self.length(&k("radius"), &[*radius])?;
                self.length(&k("height"), &[*height])?;
                count_range(self, &k("segments"), *segments, 3)
            }
            ShapeDesc::Ellipsoid {
                radii,
                segments,
                rings,
            } => {
                self.length(&k("radii"), radii)?;
                count_range(self, &k("segments"), *segments, 3)?;
                count_range(self, &k("rings"), *rings, 2)
            }
            ShapeDesc::Obj { file } if file.is_empty() => {
                Err(self.err(k("file"), "empty file name"))
            }
            ShapeDesc::Obj { .. } => Ok(()),
            ShapeDesc::Mesh {
                positions,
                normals,
                triangles,
            } => {
                super::mesh::check_inline(positions, normals, triangles).map_err(|(field, msg)| {
                    match &o.name {
                        Some(name) => self.err(k(field), format!("mesh \"{name}\": {msg}")),
                        None => self.err(k(field), msg),
                    }
                })
            }
            ShapeDesc::Instance { prefab, .. } => {
                if o.material.is_some() {
                    return Err(self.err(
                        k("material"),
                        "not allowed on an instance (use material_map)",
                    ));
                }
                if !desc.prefabs.iter().any(|p| &p.name == prefab) {
                    return Err(self.err(k("prefab"), format!("unknown prefab \"{prefab}\"")));
                }
                Ok(())
            }
        }
    }
}

fn count_range(v: &V, key: &str, n: u32, min: u32) -> Result<(), SceneError> {
    if n < min || n > 1 << 16 {
        return Err(v.err(key, format!("must be in [{min}, 65536], got {n}")));
    }
    Ok(())
}

/// `MemAvailable` from /proc/meminfo, if readable.
fn available_memory_bytes() -> Option<u64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

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
pub fn validate(
    desc: &SceneDesc,
    file: &Path,
) -> Result<(BTreeMap<String, ObjAsset>, u64), SceneError> {
    let v = V { file };
    v.rig(&desc.camera)?;
    if desc.render.spp == 0 || desc.render.spp > crate::sampler::MAX_SPP {
        return Err(v.err(
            "render.spp",
            format!(
                "must be in [1, {}], got {}",
                crate::sampler::MAX_SPP,
                desc.render.spp
            ),
        ));
    }
    if desc.render.max_depth == 0 {
        return Err(v.err("render.max_depth", "must be ≥ 1"));
    }
    if let Some(sky) = &desc.sky {
        v.sky(sky)?;
        let own_sun = matches!(sky, SkyDesc::Physical { .. });
        if let Some(i) = desc
            .lights
            .iter()
            .position(|l| own_sun && matches!(l, LightDesc::Sun { .. }))
        {
            return Err(v.err(
                format!("light[{i}]"),
                "a physical sky brings its own sun: remove the sun light and set sky.sun_elevation_deg / sky.sun_azimuth_deg",
            ));
        }
    }
    desc.check_weather().map_err(|(key, msg)| v.err(key, msg))?;
    for (i, l) in desc.lights.iter().enumerate() {
        v.light(i, l)?;
    }
    let mut first: HashMap<&str, usize> = HashMap::new();
    for (i, m) in desc.materials.iter().enumerate() {
        v.material(i, m)?;
        if let Some(j) = first.insert(&m.name, i) {
            return Err(v.err(
                format!("material[{i}].name"),
                format!(
                    "duplicate material name \"{}\" (first at material[{j}])",
                    m.name
                ),
            ));
        }
    }
    let mut prefab_first: HashMap<&str, usize> = HashMap::new();
    for (p, pf) in desc.prefabs.iter().enumerate() {
        if let Some(q) = prefab_first.insert(&pf.name, p) {
            return Err(v.err(
                format!("prefab[{p}].name"),
                format!(
                    "duplicate prefab name \"{}\" (first at prefab[{q}])",
                    pf.name
                ),
            ));
        }
    }
    let objects = all_objects(desc);
    for (key, o) in &objects {
        v.object(key, o, desc)?;
    }
    super::prefab::check_cycles(desc, file)?;

    // Resource guard on counts alone, before any OBJ parse or tessellation.
    let mut obj_texts = BTreeMap::new();
    for (key, o) in &objects {
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

    let table = material_table(desc, &objs);
    let used = super::resolve::check_references(desc, &objs, &table, file)?;

    let sky_lit = match &desc.sky {
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
    };
    let emitting = table.iter().zip(&used).any(|(m, &u)| u && matches!(&m.kind, MaterialKindDesc::Emissive { radiance, .. } if radiance.iter().any(|&x| x > 0.0)));
    let lit = desc.lights.iter().any(|l| match l {
        LightDesc::Sun { irradiance: c, .. }
        | LightDesc::Point { intensity: c, .. }
        | LightDesc::Spot { intensity: c, .. } => c.iter().any(|&x| x > 0.0),
    });
    if !lit && !sky_lit && !emitting {
        let msg = "no light: no sun, point or spot light with power, no emissive material in use, and the sky is black";
        return Err(SceneError::at(file, K::NoLight, "", msg));
    }
    Ok((objs, exact))
}

/// An OBJ path from the scene file's directory.
pub fn obj_path(scene: &Path, file: &str) -> std::path::PathBuf {
    scene.parent().unwrap_or(Path::new(".")).join(file)
}
