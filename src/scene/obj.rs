//! Wavefront OBJ/MTL import through tobj (the only file naming tobj), with
//! validation: finite, sane coordinates (|x| ≤ 1e7 m), valid indices (by
//! line, `obj_scan`), MTL values in range (by line, `mtl_check`), known
//! `usemtl` names, and degenerate triangles dropped (all-degenerate is an
//! error). Polygons are triangulated by `polygon` (ear clipping when
//! concave); `l` and `p` elements are not surfaces and are ignored.
//!
//! MTL → material: Ke > 0 emissive; d < 1, illum 4/6/7 or Ni with Tf
//! dielectric; Pm or illum 3 with strong Ks conductor (roughness from Ns);
//! otherwise Kd diffuse. Material names become "<file>/<mtl name>".

use std::cell::RefCell;
use std::path::Path;

use glam::DVec3;

use super::desc::{MaterialDesc, MaterialKindDesc};
use super::load::{SceneError, SceneErrorKind};
use super::mesh::{check_positions, keep_nondegenerate};
use super::{mtl_check, obj_scan, polygon};

pub use super::mesh::MAX_COORD_M;

/// One loaded OBJ file.
#[derive(Clone, Debug, Default)]
pub struct ObjAsset {
    /// Triangle groups, one per (OBJ object, material).
    pub groups: Vec<ObjGroup>,
    /// Its MTL materials, named "<file>/<mtl name>".
    pub materials: Vec<MaterialDesc>,
    /// Degenerate triangles dropped while loading.
    pub dropped_degenerate: usize,
}

impl ObjAsset {
    /// Triangles kept.
    pub fn triangle_count(&self) -> u64 {
        self.groups.iter().map(|g| g.triangles.len() as u64).sum()
    }
}

/// Triangles sharing one material, local (file) coordinates.
#[derive(Clone, Debug, Default)]
pub struct ObjGroup {
    /// Vertex positions, metres.
    pub positions: Vec<DVec3>,
    /// Per-vertex normals (empty when the file has none).
    pub normals: Vec<DVec3>,
    /// Vertex indices.
    pub triangles: Vec<[u32; 3]>,
    /// Index into `ObjAsset::materials`, `None` when no `usemtl` applies.
    pub material: Option<usize>,
}

/// Triangle count of OBJ text from its `f` lines (a face of n vertices is n − 2
/// triangles), without parsing coordinates: the resource guard runs on this.
pub fn count_triangles(text: &str) -> u64 {
    text.lines()
        .filter_map(|l| l.trim_start().strip_prefix("f "))
        .map(|rest| (rest.split_whitespace().count() as u64).saturating_sub(2))
        .sum()
}

/// Loads and validates the OBJ file `obj_path` (named `file` at key `key` of
/// the scene file `scene`).
pub fn load_obj(
    scene: &Path,
    key: &str,
    file: &str,
    obj_path: &Path,
) -> Result<ObjAsset, SceneError> {
    let err =
        |msg: String| SceneError::at(scene, SceneErrorKind::Obj, key, format!("{file}: {msg}"));
    let text = std::fs::read_to_string(obj_path).map_err(|e| {
        SceneError::at(
            scene,
            SceneErrorKind::Io,
            key,
            format!("cannot read OBJ {}: {e}", obj_path.display()),
        )
    })?;
    let scan = obj_scan::scan(&text).map_err(err)?;
    // Faces come back whole (face_arities) for `polygon` to triangulate.
    let options = tobj::LoadOptions {
        triangulate: false,
        single_index: true,
        ..Default::default()
    };
    let dir = obj_path.parent().unwrap_or(Path::new("."));
    // tobj's loader can only return its own error codes: keep ours aside.
    let mtl_error = RefCell::new(None);
    let load_mtl = |name: &Path| {
        let fail = |msg: String| {
            mtl_error.borrow_mut().get_or_insert(msg);
            Err(tobj::LoadError::MaterialParseError)
        };
        let text = match std::fs::read_to_string(dir.join(name)) {
            Ok(t) => t,
            Err(e) => return fail(format!("cannot read MTL {}: {e}", name.display())),
        };
        match mtl_check::check_mtl(&text) {
            Ok(()) => tobj::load_mtl_buf(&mut text.as_bytes()),
            Err(m) => fail(format!("{}: {m}", name.display())),
        }
    };
    let loaded = tobj::load_obj_buf(&mut scan.geometry(&text).as_bytes(), &options, load_mtl);
    if let Some(m) = mtl_error.take() {
        return Err(err(m));
    }
    let (models, mtl) = loaded.map_err(|e| err(format!("{e}")))?;
    let mtl = mtl.map_err(|e| err(format!("cannot load its MTL library: {e}")))?;
    // tobj silently ignores unknown `usemtl` names; we refuse them.
    for (i, line) in text.lines().enumerate() {
        if let Some(name) = line.trim_start().strip_prefix("usemtl ") {
            let name = name.trim();
            if !mtl.iter().any(|m| m.name == name) {
                return Err(err(format!(
                    "line {}: unknown MTL material \"{name}\"",
                    i + 1
                )));
            }
        }
    }
    let materials = mtl.iter().map(|m| material_from_mtl(file, m)).collect();
    let mut asset = ObjAsset {
        materials,
        ..Default::default()
    };
    let mut faces = scan.face_lines.iter().copied();
    for model in &models {
        let group = group_from_mesh(&model.mesh, &mut faces, &mut asset.dropped_degenerate)
            .map_err(|m| {
                // A face error names its line; others name the tobj object.
                if m.starts_with("line ") {
                    err(m)
                } else {
                    err(format!("object \"{}\": {m}", model.name))
                }
            })?;
        if !group.triangles.is_empty() {
            asset.groups.push(group);
        }
    }
    if asset.groups.is_empty() {
        return Err(err(format!(
            "no usable triangles ({} faces, {} degenerate dropped)",
            count_triangles(&text),
            asset.dropped_degenerate
        )));
    }
    Ok(asset)
}

/// One tobj mesh as triangles; `face_lines` yields the OBJ line of each of
/// its faces in turn (tobj keeps file order).
fn group_from_mesh(
    mesh: &tobj::Mesh,
    face_lines: &mut impl Iterator<Item = usize>,
    dropped: &mut usize,
) -> Result<ObjGroup, String> {
    let positions: Vec<DVec3> = mesh
        .positions
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64))
        .collect();
    check_positions(&positions)?;
    let mut normals: Vec<DVec3> = mesh
        .normals
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64).normalize_or_zero())
        .collect();
    if normals.len() != positions.len()
        || normals.iter().any(|n| *n == DVec3::ZERO || !n.is_finite())
    {
        // Missing or unusable shading normals: fall back to geometric ones.
        normals.clear();
    }
    // No arities means every face is a triangle.
    let arities: Vec<usize> = if mesh.face_arities.is_empty() {
        vec![3; mesh.indices.len() / 3]
    } else {
        mesh.face_arities.iter().map(|&a| a as usize).collect()
    };
    let mut triangles = Vec::with_capacity(mesh.indices.len() / 3);
    let mut start = 0;
    for arity in arities {
        let face = &mesh.indices[start..start + arity];
        start += arity;
        let line = face_lines.next();
        if arity == 3 {
            triangles.push([face[0], face[1], face[2]]);
            continue;
        }
        let corners: Vec<DVec3> = face.iter().map(|&i| positions[i as usize]).collect();
        let tris = polygon::triangulate(&corners).map_err(|m| match line {
            Some(l) => format!("line {l}: {m}"),
            None => m,
        })?;
        triangles.extend(tris.iter().map(|t| t.map(|k| face[k])));
    }
    let (triangles, n) = keep_nondegenerate(&positions, &triangles)?;
    *dropped += n;
    Ok(ObjGroup {
        positions,
        normals,
        triangles,
        material: mesh.material_id,
    })
}

/// GGX roughness from a Phong exponent (Walter et al. 2007, αb = √(2/(αp + 2)));
/// no `Ns` means a smooth surface.
fn roughness_from_ns(ns: Option<f32>) -> f64 {
    let Some(ns) = ns else { return 0.0 };
    let ns = ns.max(0.0) as f64;
    let alpha = (2.0 / (ns + 2.0)).sqrt();
    alpha.sqrt().clamp(0.0, 1.0)
}

fn param(m: &tobj::Material, key: &str) -> Option<Vec<f64>> {
    let v: Option<Vec<f64>> = m
        .unknown_param
        .get(key)?
        .split_whitespace()
        .map(|s| s.parse().ok())
        .collect();
    v.filter(|v| !v.is_empty() && v.iter().all(|x| x.is_finite()))
}

fn rgb(v: Option<[f32; 3]>, default: f64) -> [f64; 3] {
    v.map_or([default; 3], |c| c.map(|x| (x as f64).clamp(0.0, 1.0)))
}

/// Maps one MTL material to a scene material named "<file>/<mtl name>".
pub fn material_from_mtl(file: &str, m: &tobj::Material) -> MaterialDesc {
    let illum = m.illumination_model.unwrap_or(2);
    let ke = m.emissive.unwrap_or([0.0; 3]).map(|x| (x as f64).max(0.0));
    let tf = param(m, "Tf").map(|v| {
        if v.len() >= 3 {
            [v[0], v[1], v[2]]
        } else {
            [v[0]; 3]
        }
    });
    let ks = rgb(m.specular, 0.0);
    let metallic = param(m, "Pm").is_some_and(|v| v[0] >= 0.5);
    let roughness =
        param(m, "Pr").map_or_else(|| roughness_from_ns(m.shininess), |v| v[0].clamp(0.0, 1.0));
    let kind = if ke.iter().any(|&x| x > 0.0) {
        MaterialKindDesc::Emissive {
            radiance: ke,
            two_sided: false,
        }
    } else if m.dissolve.is_some_and(|d| d < 1.0)
        || matches!(illum, 4 | 6 | 7)
        || (m.optical_density.is_some() && tf.is_some())
    {
        MaterialKindDesc::Dielectric {
            ior: m.optical_density.map_or(1.5, |n| n as f64),
            roughness,
            tint: tf.unwrap_or([1.0; 3]).map(|x| x.clamp(0.0, 1.0)),
        }
    } else if metallic || (illum == 3 && ks.iter().cloned().fold(0.0, f64::max) >= 0.5) {
        // Reflectance F0 from Kd (PBR base colour) or Ks; eta = 1 gives
        // F0 = k² / (4 + k²), inverted per channel.
        let f0 = if metallic { rgb(m.diffuse, 0.8) } else { ks };
        let k = f0.map(|f| 2.0 * (f.min(0.99) / (1.0 - f.min(0.99))).sqrt());
        MaterialKindDesc::Conductor {
            preset: None,
            eta: Some([1.0; 3]),
            k: Some(k),
            roughness,
        }
    } else {
        MaterialKindDesc::Diffuse {
            albedo: rgb(m.diffuse, 0.8),
        }
    };
    MaterialDesc {
        name: format!("{file}/{}", m.name),
        mask: None,
        texture: None,
        kind,
    }
}
