//! Bends a level town's static objects and generated meshes by the organic
//! warp W (`Warp`), the way `drape` lays them on a grade:
//!
//! - flat pieces longer than `LONG_M` (quads and boxes turned only about z:
//!   roads, markings, shoulders, sidewalks, lots, hedges, fences, rails)
//!   are cut into pieces ≤ `step` and every vertex goes to W(x, y) (z
//!   kept); they merge into one world-space mesh per material, class and
//!   instance, like draped pieces;
//! - a building (all parts with its instance id) moves as one rigid body:
//!   its first part's origin p₀ goes to W(p₀) and every part turns about
//!   it by the rotation of J at p₀ (`Warp::rotation_deg`), repeats too;
//! - everything else (furniture, trees, short pieces) moves to W at its
//!   origin and turns by the rotation there, each repeat copy spread over
//!   the ground at its own point;
//! - generated meshes (hills) move per vertex, normals by J⁻ᵀ.
//!
//! World frame z up, metres. A town that is not organic is never touched.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::scene::desc::{ObjectDesc, RepeatDesc, ShapeDesc, TransformDesc};
use crate::scene::mesh::LocalMesh;
use crate::scene::transform::repeat_offsets;

use super::Warp;
use crate::town::drape::{building_id, heading_only, piece_mesh};

/// Flat pieces longer than this are bent piecewise, metres.
pub const LONG_M: f64 = 6.0;
/// Longest side of a bent piece in a level town, metres: a road's chord
/// error is at most `Warp::max_bend` · s² / 8 ≈ 4 cm (graded towns cut at
/// `drape::STEP_M` for the grade).
pub const STEP_M: f64 = 10.0;

/// Ground cover (class `terrain`) is cut into pieces this many times `step`.
const TERRAIN_STEPS: f64 = 2.0;

/// The flat piece to bend: (size x, size y, bottom z, top z) in its level
/// frame, or `None` for a building part, a short piece or a piece that is
/// not a quad or box turned only about z.
fn bent_piece(o: &ObjectDesc) -> Option<([f64; 2], f64, f64)> {
    heading_only(&o.transform)?;
    if building_id(o).is_some() {
        return None;
    }
    let z = o.transform.translate.unwrap_or_default()[2];
    let (size, bottom, top) = match &o.shape {
        ShapeDesc::Quad { size } => (*size, z, z),
        ShapeDesc::Box { size } => ([size[0], size[1]], z - size[2] / 2.0, z + size[2] / 2.0),
        _ => return None,
    };
    (size[0].max(size[1]) > LONG_M).then_some((size, bottom, top))
}

/// Material, class and instance id of a merged bent mesh.
type MeshKey = (Option<String>, Option<String>, Option<u16>);

/// The town's static objects bent by `w` (order kept; bent pieces merge
/// into one mesh per material, class and instance, placed where the first
/// of them was), pieces cut ≤ `step` metres.
pub fn bend_objects(objects: Vec<ObjectDesc>, w: &Warp, step: f64) -> Vec<ObjectDesc> {
    // Each building's anchor: its first part's origin.
    let mut anchor: BTreeMap<u16, [f64; 2]> = BTreeMap::new();
    for o in &objects {
        if let Some(id) = building_id(o) {
            let t = o.transform.translate.unwrap_or_default();
            anchor.entry(id).or_insert([t[0], t[1]]);
        }
    }
    let place = |p: [f64; 2], dz: f64| {
        let q = w.map(p);
        DVec3::new(q[0], q[1], dz)
    };
    let mut out: Vec<ObjectDesc> = Vec::with_capacity(objects.len());
    let mut meshes: BTreeMap<MeshKey, (usize, LocalMesh)> = BTreeMap::new();
    for o in objects {
        let t = o.transform.translate.unwrap_or_default();
        if let Some((size, bottom, top)) = bent_piece(&o) {
            let key = (o.material.clone(), o.semantic.clone(), o.instance);
            let slot = meshes.entry(key).or_insert_with(|| {
                out.push(o.clone());
                (out.len() - 1, LocalMesh::default())
            });
            let heading = heading_only(&o.transform).unwrap_or(0.0);
            // Ground cover (lots, fields, crop ridges, gravel) lies beside
            // the roads: twice the step keeps its edges within ~15 cm.
            let step = match o.semantic.as_deref() {
                Some("terrain") => TERRAIN_STEPS * step,
                _ => step,
            };
            for off in repeat_offsets(&o.repeat) {
                let at = [t[0] + off.x, t[1] + off.y];
                let piece = (size, bottom + off.z, top + off.z);
                // A box standing on (or sunk into) the ground needs no floor.
                let floor = bottom + off.z > 0.0;
                piece_mesh(&mut slot.1, piece, (at, heading), (step, floor), &place);
            }
            continue;
        }
        if let Some(id) = building_id(&o) {
            let a = anchor[&id];
            out.push(rigid(o, a, w.map(a), w.rotation_deg(a)));
            continue;
        }
        if matches!(o.shape, ShapeDesc::Mesh { .. }) && o.transform.is_identity() {
            let mut one = [o];
            bend_meshes(&mut one, w);
            let [o] = one;
            out.push(o);
            continue;
        }
        let offsets = repeat_offsets(&o.repeat);
        if offsets.iter().all(|d| d.x == 0.0 && d.y == 0.0) {
            let a = [t[0], t[1]];
            out.push(rigid(o, a, w.map(a), w.rotation_deg(a)));
            continue;
        }
        for d in offsets {
            let mut copy = o.clone();
            copy.repeat.clear();
            copy.transform.translate = Some([t[0] + d.x, t[1] + d.y, t[2] + d.z]);
            let a = [t[0] + d.x, t[1] + d.y];
            out.push(rigid(copy, a, w.map(a), w.rotation_deg(a)));
        }
    }
    for (_, (slot, mesh)) in meshes {
        let o = &mut out[slot];
        o.transform = TransformDesc::default();
        o.repeat.clear();
        o.shape = mesh.into_shape();
    }
    out
}

/// `(x, y)` turned by the angle with cosine `c` and sine `s`.
fn turn(c: f64, s: f64, x: f64, y: f64) -> [f64; 2] {
    [c * x - s * y, s * x + c * y]
}

/// The object moved rigidly: the point `from` goes to `to` and the object
/// turns about it by `deg` degrees (about world z; its repeat offsets too).
fn rigid(mut o: ObjectDesc, from: [f64; 2], to: [f64; 2], deg: f64) -> ObjectDesc {
    let (s, c) = deg.to_radians().sin_cos();
    let t = o.transform.translate.unwrap_or_default();
    let d = turn(c, s, t[0] - from[0], t[1] - from[1]);
    o.transform.translate = Some([to[0] + d[0], to[1] + d[1], t[2]]);
    // Rz(θ)·Rz(γ)·Ry·Rx = Rz(θ + γ)·Ry·Rx in the scene's order.
    let r = o.transform.rotate_deg.unwrap_or_default();
    o.transform.rotate_deg = Some([r[0], r[1], r[2] + deg]);
    for RepeatDesc { offset, .. } in &mut o.repeat {
        let [x, y] = turn(c, s, offset[0], offset[1]);
        (offset[0], offset[1]) = (x, y);
    }
    o
}

/// Moves every vertex of the inline meshes among `objects` (world
/// positions, identity transform) to W(x, y), z kept; normals go by J⁻ᵀ
/// (= [[1, −a′], [−b′, 1 + a′b′]] since det J = 1), z kept, renormalised.
pub fn bend_meshes(objects: &mut [ObjectDesc], w: &Warp) {
    for o in objects {
        let ShapeDesc::Mesh {
            positions, normals, ..
        } = &mut o.shape
        else {
            continue;
        };
        for (k, p) in positions.iter_mut().enumerate() {
            let [[j00, j01], [j10, j11]] = w.jacobian([p[0], p[1]]);
            if let Some(n) = normals.get_mut(k) {
                let v = DVec3::new(j11 * n[0] - j10 * n[1], -j01 * n[0] + j00 * n[1], n[2]);
                *n = v.normalize().to_array();
            }
            [p[0], p[1]] = w.map([p[0], p[1]]);
        }
    }
}
