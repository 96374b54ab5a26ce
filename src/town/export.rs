//! OBJ + MTL export of a built frame, so another renderer can render the
//! same geometry: world coordinates (render space + origin, f64 printed with
//! round-trip precision), one `o` per mesh named after its semantic class and
//! instance id, `usemtl` per material run. Analytic spheres are not exported.
//!
//! Beside the OBJ, `<stem>.cameras.json` gives the frame's cameras as a
//! render's camera file does (K, left pose, right poses) with the town,
//! town frame, configuration and seeds, so the export lines up with the
//! dataset frame it came from.
//!
//! MTL mapping (what `scene::obj` reads back): diffuse → Kd; conductor →
//! Pm 1 with Kd = normal-incidence reflectance and Pr roughness; dielectric →
//! d 0, Ni ior, Tf tint, Pr roughness; emissive → Ke radiance.

use std::fmt::Write as _;
use std::io;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::camera::StereoRig;
use crate::output::frame::{FrameSeeds, RigCameras, TownFrameRecord, CONVENTIONS};
use crate::scene::desc::{MaterialDesc, MaterialKindDesc};
use crate::scene::semantic::class_name;
use crate::scene::{LoadedScene, Scene};

/// What an export wrote.
#[derive(Clone, Debug, PartialEq)]
pub struct ExportStats {
    /// Triangles written.
    pub triangles: u64,
    /// Vertices written.
    pub vertices: u64,
    /// Materials written.
    pub materials: usize,
}

/// The cameras of an exported town frame, named and laid out as in a
/// render's camera file.
#[derive(Clone, Debug, Serialize)]
pub struct ExportCameras {
    /// Size, K, left and right poses, in the OBJ's world coordinates
    /// (flattened, as in a camera file).
    #[serde(flatten)]
    pub cameras: RigCameras,
    /// The seeds of the geometry (town and traffic; nothing is sampled).
    pub seeds: FrameSeeds,
    /// The town description, town frame and camera configuration.
    pub town: TownFrameRecord,
    /// Conventions, as in camera files.
    pub conventions: &'static str,
}

impl ExportCameras {
    /// The cameras of `rig` on the frame of `town` generated with `seed`.
    pub fn new(rig: &StereoRig, seed: u64, town: TownFrameRecord) -> Self {
        ExportCameras {
            cameras: RigCameras::of(rig),
            seeds: FrameSeeds::town(seed),
            town,
            conventions: CONVENTIONS,
        }
    }
}

/// The cameras file beside an OBJ: `<stem>.cameras.json`.
fn cameras_path(obj_path: &Path) -> PathBuf {
    obj_path.with_extension("cameras.json")
}

/// Writes `cameras` beside `obj_path` ([`cameras_path`]) and returns its path.
pub fn write_cameras(obj_path: &Path, cameras: &ExportCameras) -> io::Result<PathBuf> {
    let path = cameras_path(obj_path);
    crate::output::write_json(&path, cameras)?;
    Ok(path)
}

/// Writes `scene` (built from `loaded`) to `obj_path` and its materials to
/// the same path with extension `.mtl`.
pub fn write_obj(loaded: &LoadedScene, scene: &Scene, obj_path: &Path) -> io::Result<ExportStats> {
    let table = crate::scene::validate::material_table(&loaded.desc, &loaded.objs);
    let mtl_path = obj_path.with_extension("mtl");
    let mtl_name = mtl_path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene.mtl".into());
    let mut mtl = String::new();
    for m in &table {
        mtl_entry(&mut mtl, m);
    }
    let mut obj = format!("# parallax town export\nmtllib {mtl_name}\n");
    let (mut base, mut triangles) = (1u64, 0u64);
    // Instances flattened: an OBJ file has no instancing.
    for (g, m) in scene.flattened_meshes().enumerate() {
        let class = class_name(m.semantic).unwrap_or("unlabeled");
        let _ = writeln!(obj, "o {g}_{class}_{}", m.instance);
        for p in &m.p_render {
            let w = *p + scene.origin_world;
            let _ = writeln!(obj, "v {} {} {}", w.x, w.y, w.z);
        }
        let mut current = u32::MAX;
        for (t, &mi) in m.triangles.iter().zip(&m.tri_material) {
            if mi != current {
                current = mi;
                let _ = writeln!(obj, "usemtl {}", mtl_ident(&table[mi as usize].name));
            }
            let [a, b, c] = t.map(|i| i as u64 + base);
            let _ = writeln!(obj, "f {a} {b} {c}");
        }
        base += m.p_render.len() as u64;
        triangles += m.triangles.len() as u64;
    }
    // Atomic, and the directory is created: no half-written export.
    crate::output::write_atomic(&mtl_path, mtl.as_bytes())?;
    crate::output::write_atomic(obj_path, obj.as_bytes())?;
    Ok(ExportStats {
        triangles,
        vertices: base - 1,
        materials: table.len(),
    })
}

/// MTL names may not contain whitespace.
fn mtl_ident(name: &str) -> String {
    name.replace(char::is_whitespace, "_")
}

fn mtl_entry(out: &mut String, m: &MaterialDesc) {
    let _ = writeln!(out, "newmtl {}", mtl_ident(&m.name));
    let rgb = |c: [f64; 3]| format!("{} {} {}", c[0], c[1], c[2]);
    match &m.kind {
        MaterialKindDesc::Diffuse { albedo } => {
            let _ = writeln!(out, "Kd {}\nillum 1", rgb(*albedo));
        }
        MaterialKindDesc::Conductor {
            preset,
            eta,
            k,
            roughness,
        } => {
            let (eta, k) = crate::scene::desc::conductor_eta_k(preset, eta, k);
            // Normal-incidence Fresnel reflectance of a conductor.
            let f0: Vec<f64> = (0..3)
                .map(|i| {
                    let (n, kk) = (eta[i], k[i]);
                    ((n - 1.0).powi(2) + kk * kk) / ((n + 1.0).powi(2) + kk * kk)
                })
                .collect();
            let _ = writeln!(
                out,
                "Kd {}\nPm 1\nPr {roughness}\nillum 3",
                rgb([f0[0], f0[1], f0[2]])
            );
        }
        MaterialKindDesc::Dielectric {
            ior,
            roughness,
            tint,
        } => {
            let _ = writeln!(
                out,
                "Kd 0 0 0\nd 0\nNi {ior}\nTf {}\nPr {roughness}\nillum 7",
                rgb(*tint)
            );
        }
        MaterialKindDesc::Emissive { radiance, .. } => {
            let _ = writeln!(out, "Kd 0 0 0\nKe {}\nillum 1", rgb(*radiance));
        }
        MaterialKindDesc::Coated {
            albedo,
            coat_roughness,
            ..
        } => {
            // MTL's PBR extension: clear coat thickness and roughness.
            let kd = rgb(albedo.unwrap_or([0.5; 3]));
            let _ = writeln!(out, "Kd {kd}\nPc 1\nPcr {coat_roughness}\nillum 2");
        }
    }
    out.push('\n');
}
