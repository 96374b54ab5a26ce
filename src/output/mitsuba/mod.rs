//! A built frame as a Mitsuba 3 scene (`parallax export --mitsuba`): an XML
//! file, one binary PLY per material under `meshes/`, and the sky baked to
//! `sky.exr` when it is not constant, so Mitsuba renders the frame the
//! reference mode (`render --reference`) renders. Coordinates are render
//! space (world − the scene's origin, written in the XML's header comment),
//! which keeps f32 precision in large towns.
//!
//! Mapping (docs/reference.md lists it with what has no twin):
//! - camera: `perspective`, horizontal fov, box pixel filter, the view's pose;
//! - path depth D → Mitsuba `max_depth` D + 1 (Mitsuba counts the camera
//!   segment); `path` integrator, `volpath` with a medium;
//! - diffuse → `diffuse`; conductor → `roughconductor` (GGX, α = roughness²;
//!   `conductor` when smooth); dielectric → `roughdielectric` /
//!   `dielectric` with the tint as specular transmittance; coated with a
//!   diffuse base → `roughplastic` / `plastic`, with a metal base → the base
//!   `roughconductor` (Mitsuba has no coated metal); opaque BSDFs are
//!   `twosided`, as parallax shades both faces; emissive → an `area`
//!   emitter (a flipped copy for two-sided ones);
//! - textures → the material's mean albedo (its `albedo`, base or tint);
//! - sun → `directional` with the sun's irradiance (a delta: no penumbra);
//!   point → `point`, spot → `spot` (W/sr both; Mitsuba's spot falls off
//!   linearly in angle between `beam_width` = inner and `cutoff_angle` =
//!   outer, parallax's smoothly in cosine: equal outside the transition);
//! - sky: constant → `constant`; any other sky → `envmap` baked from the
//!   sky's own radiance at pixel centres (the sun stays a light);
//! - homogeneous medium → a `homogeneous` medium (σ_t, albedo, HG g) filling a
//!   null-BSDF box over the medium's z range, the camera inside it.
//!
//! Height fog has no homogeneous twin and is refused; rain, wet surfaces and
//! the clouds' shadow on the sun are left out (listed in [`MitsubaExport::notes`]).

mod ply;
mod xml;

pub use ply::{decode as decode_ply, PlyMesh};

use std::io;
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};

use crate::camera::Camera;
use crate::scene::desc::{MaterialDesc, MaterialKindDesc};
use crate::scene::{LoadedScene, Scene};
use shaders_cpu::medium::Density;
use shaders_cpu::sky::Sky;

/// What to write besides the scene itself.
#[derive(Clone, Copy, Debug)]
pub struct MitsubaOptions<'a> {
    /// The view to render (the left camera or a right one).
    pub camera: &'a Camera,
    /// parallax's maximum path depth (scattering events).
    pub max_depth: u32,
    /// Samples per pixel (the XML's default; `spp` parameter).
    pub spp: u32,
    /// Width of the baked sky map, pixels (height is half).
    pub sky_width: u32,
}

/// What an export wrote.
#[derive(Clone, Debug, PartialEq)]
pub struct MitsubaExport {
    /// The scene file.
    pub xml: PathBuf,
    /// Mesh files (relative to the export directory) and their triangle
    /// counts (a prototype's once, however many instances place it).
    pub meshes: Vec<(String, u64)>,
    /// What the Mitsuba scene leaves out or approximates.
    pub notes: Vec<String>,
}

/// Why a scene cannot be exported (the message names the part).
#[derive(Debug)]
pub enum MitsubaError {
    /// The scene has something without a Mitsuba twin.
    Unsupported(String),
    /// Writing failed.
    Io(io::Error),
}

impl std::fmt::Display for MitsubaError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            MitsubaError::Unsupported(m) => write!(f, "{m}"),
            MitsubaError::Io(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for MitsubaError {}

/// Checks that `scene` has a Mitsuba twin (before anything is written).
pub fn check(scene: &Scene) -> Result<(), MitsubaError> {
    if let Some(m) = &scene.medium {
        if let Density::HeightExp { .. } = m.density {
            return Err(MitsubaError::Unsupported(
                "[medium] kind = \"height_fog\" has no Mitsuba twin (only homogeneous media export)"
                    .into(),
            ));
        }
    }
    Ok(())
}

/// Writes `scene` (built from `loaded`) seen from `opts.camera` into `dir`
/// (created if needed): `scene.xml`, `meshes/*.ply` and maybe `sky.exr`.
pub fn write_mitsuba(
    loaded: &LoadedScene,
    scene: &Scene,
    opts: &MitsubaOptions,
    dir: &Path,
) -> Result<MitsubaExport, MitsubaError> {
    check(scene)?;
    let table = crate::scene::validate::material_table(&loaded.desc, &loaded.objs);
    let mut notes = Vec::new();
    let groups = gather_meshes(scene, &table);
    let mut x = xml::Xml::new(scene.origin_world, opts);
    for (i, m) in table.iter().enumerate() {
        x.bsdf(i, m);
    }
    material_notes(&table, &mut notes);
    let mut meshes = Vec::new();
    let mut open_group = None;
    for g in &groups {
        if g.prototype != open_group {
            if open_group.is_some() {
                x.end_group();
            }
            if let Some(k) = g.prototype {
                x.begin_group(k);
            }
            open_group = g.prototype;
        }
        let name = format!("meshes/{}.ply", g.file_stem);
        write(dir, &name, &g.mesh.encode())?;
        x.shape(&name, g.material, g.emission);
        meshes.push((name, g.mesh.triangles.len() as u64));
    }
    if open_group.is_some() {
        x.end_group();
    }
    for inst in &scene.instances {
        x.instance(inst.prototype as usize, &inst.render_from_local);
    }
    for s in &scene.spheres {
        x.sphere(
            s.center.as_vec3(),
            s.radius,
            s.material,
            emission(table[s.material as usize]),
        );
    }
    for l in &scene.lights {
        x.light(l);
    }
    match &scene.sky {
        Sky::Constant { le } => x.constant_sky(*le),
        sky => {
            let (w, h, pixels) = bake_sky(sky, opts.sky_width);
            let path = dir.join("sky.exr");
            crate::output::write_exr_rgb_f32(&path, w, h, &pixels).map_err(MitsubaError::Io)?;
            x.envmap("sky.exr");
            if matches!(sky, Sky::Physical(_)) {
                notes.push("the clouds' shadow on the sun is not exported".into());
            }
        }
    }
    if let Some(m) = &scene.medium {
        x.medium(m, opts.camera.center_world - scene.origin_world);
    }
    if scene.rain.is_some() {
        notes.push("rain is not exported".into());
    }
    if scene.wetness.is_some() {
        notes.push("wet surfaces and puddles are not exported (dry materials)".into());
    }
    let xml_path = dir.join("scene.xml");
    write(dir, "scene.xml", x.finish().as_bytes())?;
    Ok(MitsubaExport {
        xml: xml_path,
        meshes,
        notes,
    })
}

fn write(dir: &Path, name: &str, bytes: &[u8]) -> Result<(), MitsubaError> {
    crate::output::write_atomic(&dir.join(name), bytes).map_err(MitsubaError::Io)
}

/// One note per kind of approximation, naming its materials.
fn material_notes(table: &[&MaterialDesc], notes: &mut Vec<String>) {
    let names = |f: &dyn Fn(&MaterialDesc) -> bool| -> Vec<&str> {
        table
            .iter()
            .filter(|m| f(m))
            .map(|m| m.name.as_str())
            .collect()
    };
    let kinds: [(&str, Vec<&str>); 3] = [
        (
            "procedural textures as their mean albedo",
            names(&|m| m.texture.is_some()),
        ),
        (
            "coated paint as Mitsuba's plastic (its own coat model)",
            names(&|m| {
                matches!(
                    m.kind,
                    MaterialKindDesc::Coated {
                        albedo: Some(_),
                        ..
                    }
                )
            }),
        ),
        (
            "coated metal as its bare base (Mitsuba has no coated conductor)",
            names(&|m| matches!(m.kind, MaterialKindDesc::Coated { albedo: None, .. })),
        ),
    ];
    for (what, list) in kinds {
        if !list.is_empty() {
            notes.push(format!(
                "{} materials: {what} ({})",
                list.len(),
                list.join(", ")
            ));
        }
    }
}

/// The emitted radiance of a material, if it emits: (radiance, two-sided).
fn emission(m: &MaterialDesc) -> Option<([f64; 3], bool)> {
    match m.kind {
        MaterialKindDesc::Emissive {
            radiance,
            two_sided,
        } => Some((radiance, two_sided)),
        _ => None,
    }
}

/// One PLY file: the triangles of one material (one face of an emitter)
/// of the flat meshes or of one prototype.
struct Group {
    file_stem: String,
    /// The prototype it belongs to (None: flat, render space).
    prototype: Option<usize>,
    material: usize,
    /// Emitted radiance (an `area` emitter on the shape).
    emission: Option<[f64; 3]>,
    mesh: PlyMesh,
}

/// (material, with normals, back face) → the triangles gathered.
type Gathered = std::collections::BTreeMap<(usize, bool, bool), PlyMesh>;

/// Adds `m`'s triangles to `by_key`, per material (and per normals present
/// or not, as a PLY file has normals for all vertices or none), with the
/// back face of two-sided emitters as its own flipped group.
fn gather(by_key: &mut Gathered, m: &crate::scene::Mesh, table: &[&MaterialDesc]) {
    let with_normals = !m.normals.is_empty();
    let mut per_material: std::collections::BTreeMap<usize, Vec<[u32; 3]>> = Default::default();
    for (t, &mi) in m.triangles.iter().zip(&m.tri_material) {
        per_material.entry(mi as usize).or_default().push(*t);
    }
    let positions: Vec<Vec3> = m.p_render.iter().map(|p| p.as_vec3()).collect();
    for (mi, tris) in per_material {
        let faces: &[bool] = match emission(table[mi]) {
            Some((_, true)) => &[false, true],
            _ => &[false],
        };
        for &back in faces {
            by_key
                .entry((mi, with_normals, back))
                .or_default()
                .append(&positions, &m.normals, &tris, back);
        }
    }
}

/// The flat meshes' groups, then each prototype's (in its local frame;
/// emitters are never instanced, `scene::instancing` flattens them).
fn gather_meshes(scene: &Scene, table: &[&MaterialDesc]) -> Vec<Group> {
    let mut flat = Gathered::new();
    for m in &scene.meshes {
        gather(&mut flat, m, table);
    }
    let mut sets = vec![(None, flat)];
    for (k, proto) in scene.prototypes.iter().enumerate() {
        let mut g = Gathered::new();
        for m in &proto.meshes {
            gather(&mut g, m, table);
        }
        sets.push((Some(k), g));
    }
    let mut groups = Vec::new();
    for (prototype, set) in sets {
        for ((mi, normals, back), mesh) in set {
            let prefix = prototype.map_or(String::new(), |k| format!("p{k:05}_"));
            groups.push(Group {
                file_stem: format!(
                    "{prefix}m{mi:04}{}{}",
                    if normals { "_n" } else { "" },
                    if back { "_back" } else { "" }
                ),
                prototype,
                material: mi,
                emission: emission(table[mi]).map(|(le, _)| le),
                mesh,
            });
        }
    }
    groups
}

/// The sky's radiance on Mitsuba's latitude-longitude map, `width` × `width`/2
/// pixels sampled at their centres. Mitsuba's envmap maps local direction
/// (sin φ sin θ, cos θ, −cos φ sin θ) to (u, v) = (φ/2π, θ/π) with y up; the
/// XML's to_world ([`xml::ENVMAP_TO_WORLD`]) turns local y to world z.
fn bake_sky(sky: &Sky, width: u32) -> (usize, usize, Vec<Vec3>) {
    let (w, h) = (width.max(8) as usize, (width.max(8) / 2) as usize);
    let mut px = Vec::with_capacity(w * h);
    for j in 0..h {
        let theta = std::f64::consts::PI * (j as f64 + 0.5) / h as f64;
        for i in 0..w {
            let phi = 2.0 * std::f64::consts::PI * (i as f64 + 0.5) / w as f64;
            let local = DVec3::new(
                phi.sin() * theta.sin(),
                theta.cos(),
                -phi.cos() * theta.sin(),
            );
            px.push(sky.le(xml::envmap_to_world(local).as_vec3()));
        }
    }
    (w, h, px)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The baked map's pixel whose centre points straight up (world z) holds
    /// the zenith radiance, the one pointing down the ground's.
    #[test]
    fn baked_gradient_sky_has_zenith_up_and_ground_down() {
        let sky = Sky::Gradient {
            zenith: Vec3::new(1.0, 0.0, 0.0),
            horizon: Vec3::new(0.0, 1.0, 0.0),
            ground: Vec3::new(0.0, 0.0, 1.0),
        };
        let (w, h, px) = bake_sky(&sky, 64);
        assert_eq!((w, h), (64, 32));
        let top = px[0];
        assert!(top.x > 0.9 && top.z == 0.0, "top row is the zenith: {top}");
        assert_eq!(
            px[(h - 1) * w],
            Vec3::new(0.0, 0.0, 1.0),
            "bottom row: ground"
        );
    }
}
