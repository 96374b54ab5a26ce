//! Lays a level town onto the ground-elevation field of `grade`: flat
//! ground pieces (every quad, and the boxes of roads, markings, sidewalks,
//! shoulders and long low boxes such as hedges) become meshes whose
//! vertices follow h(x, y), tessellated into pieces ≤ `STEP_M` so the
//! surface stays within a few millimetres of the field (h'' ≤ A·k², the
//! chord error of a piece of length s is h''·s²/8); each building moves up
//! by the lowest h under its parts (its base never floats); everything else
//! (furniture, trees, props) moves up by h at its origin, repeat copies
//! each at their own point. Generated meshes (hills, ramps) get h added to
//! every vertex with their normals tilted to match.
//!
//! World frame z up, metres; a level town (no `Grade`) is never touched.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::scene::desc::{ObjectDesc, ShapeDesc, TransformDesc};
use crate::scene::mesh::LocalMesh;
use crate::scene::transform::repeat_offsets;

use super::buildings::BUILDING_ID_BASE;
use super::grade::Grade;
use super::FURNITURE_ID_BASE;

/// Longest side of one draped piece, metres.
pub const STEP_M: f64 = 5.0;
/// Longest side of a piece of a wide ground sheet (both sides > 100 m: the
/// ground under the town, 2 cm below everything), metres.
const SHEET_STEP_M: f64 = 10.0;

/// Classes whose boxes lie on the ground and are draped.
const GROUND_CLASSES: [&str; 4] = ["road", "road_line", "sidewalk", "terrain"];
/// Other boxes longer than this (and low on the ground) are draped, metres.
const LONG_BOX_M: f64 = 6.0;

/// A heading about z, or `None` when the transform also turns about x or
/// y or scales (such pieces are moved, never draped).
pub fn heading_only(t: &TransformDesc) -> Option<f64> {
    if t.scale.is_some() {
        return None;
    }
    match t.rotate_deg {
        None => Some(0.0),
        Some([0.0, 0.0, h]) => Some(h),
        Some(_) => None,
    }
}

/// Whether a building part: labelled with a building's instance id.
pub fn building_id(o: &ObjectDesc) -> Option<u16> {
    o.instance
        .filter(|&i| i >= BUILDING_ID_BASE && (i as u32) < FURNITURE_ID_BASE)
}

/// The piece to drape: (size x, size y, bottom z, top z) in its local
/// frame, or `None` when the object is not a flat ground piece (a building
/// part never is: the building moves as one).
fn ground_piece(o: &ObjectDesc) -> Option<([f64; 2], f64, f64)> {
    heading_only(&o.transform)?;
    let z = o.transform.translate.unwrap_or_default()[2];
    match &o.shape {
        ShapeDesc::Quad { size } if building_id(o).is_none() => Some((*size, z, z)),
        ShapeDesc::Box { size } if building_id(o).is_none() => {
            let (bottom, top) = (z - size[2] / 2.0, z + size[2] / 2.0);
            let ground = GROUND_CLASSES.contains(&o.semantic.as_deref().unwrap_or(""));
            let long_low = size[0].max(size[1]) > LONG_BOX_M && bottom.abs() < 0.1;
            (ground || long_low).then_some(([size[0], size[1]], bottom, top))
        }
        _ => None,
    }
}

/// A grid of (n_u + 1) × (n_v + 1) points over the piece, world (x, y).
struct Grid {
    n: [usize; 2],
    xy: Vec<[f64; 2]>,
}

/// Longest side of one piece of a flat piece of `size` metres cut into
/// pieces of at most `step` (wide ground sheets: twice that).
fn piece_step(size: [f64; 2], step: f64) -> f64 {
    if size[0].min(size[1]) > 100.0 {
        step * (SHEET_STEP_M / STEP_M)
    } else {
        step
    }
}

impl Grid {
    fn new(size: [f64; 2], at: [f64; 2], heading_deg: f64, step: f64) -> Grid {
        let step = piece_step(size, step);
        let n = size.map(|s| (s / step).ceil().max(1.0) as usize);
        let h = heading_deg.to_radians();
        let (c, s) = (h.cos(), h.sin());
        let mut xy = Vec::with_capacity((n[0] + 1) * (n[1] + 1));
        for j in 0..=n[1] {
            for i in 0..=n[0] {
                let u = size[0] * (i as f64 / n[0] as f64 - 0.5);
                let v = size[1] * (j as f64 / n[1] as f64 - 0.5);
                xy.push([at[0] + c * u - s * v, at[1] + s * u + c * v]);
            }
        }
        Grid { n, xy }
    }
    fn at(&self, i: usize, j: usize) -> usize {
        j * (self.n[0] + 1) + i
    }
    /// The boundary indices counter-clockwise (seen from above, local frame).
    fn ring(&self) -> Vec<usize> {
        let [nu, nv] = self.n;
        let mut r = Vec::new();
        r.extend((0..nu).map(|i| self.at(i, 0)));
        r.extend((0..nv).map(|j| self.at(nu, j)));
        r.extend((1..=nu).rev().map(|i| self.at(i, nv)));
        r.extend((1..=nv).rev().map(|j| self.at(0, j)));
        r
    }
}

/// Where a point of a level piece goes: world (x, y) and height above
/// the level ground → world position.
pub type Place<'a> = &'a dyn Fn([f64; 2], f64) -> DVec3;

/// Adds one layer of the grid at heights `dz` placed by `place`, facing up
/// or down (`Some(up)`), or only its vertices (`None`); returns the index
/// of its first vertex.
fn layer(m: &mut LocalMesh, g: &Grid, place: Place, dz: f64, up: Option<bool>) -> u32 {
    let base = m.positions.len() as u32;
    for p in &g.xy {
        m.positions.push(place(*p, dz));
    }
    let Some(up) = up else {
        return base;
    };
    for j in 0..g.n[1] {
        for i in 0..g.n[0] {
            let [a, b, c, d] = [
                g.at(i, j),
                g.at(i + 1, j),
                g.at(i + 1, j + 1),
                g.at(i, j + 1),
            ]
            .map(|k| base + k as u32);
            if up {
                m.triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                m.triangles.extend([[a, c, b], [a, d, c]]);
            }
        }
    }
    base
}

/// Appends a flat piece (a surface, or a box between two layers; size,
/// bottom and top z in its level frame at `at`, turned by `heading_deg`)
/// cut into pieces ≤ `step` metres, each grid point placed by `place`;
/// a box without `floor` has walls and top only.
pub fn piece_mesh(
    m: &mut LocalMesh,
    (size, bottom, top): ([f64; 2], f64, f64),
    (at, heading_deg): ([f64; 2], f64),
    (step, floor): (f64, bool),
    place: Place,
) {
    let g = Grid::new(size, at, heading_deg, step);
    let t = layer(m, &g, place, top, Some(true));
    if top == bottom {
        return;
    }
    let b = layer(m, &g, place, bottom, floor.then_some(false));
    // Walls: each boundary edge (counter-clockwise from above) with the
    // outside on its right.
    let ring = g.ring();
    for k in 0..ring.len() {
        let (p, q) = (ring[k] as u32, ring[(k + 1) % ring.len()] as u32);
        m.triangles
            .extend([[b + p, b + q, t + q], [b + p, t + q, t + p]]);
    }
}

/// Material, class and instance id of a merged draped mesh.
type MeshKey = (Option<String>, Option<String>, Option<u16>);

/// The town's static objects laid on the field `grade` (order kept; draped
/// pieces merge into one mesh per material, class and instance, placed
/// where the first of them was).
pub fn drape_objects(objects: Vec<ObjectDesc>, grade: &Grade) -> Vec<ObjectDesc> {
    // Lowest ground under each building's parts.
    let mut base: BTreeMap<u16, f64> = BTreeMap::new();
    for o in &objects {
        if let Some(id) = building_id(o) {
            let h = footprint_points(o)
                .iter()
                .map(|p| grade.height_m(p[0], p[1]))
                .fold(f64::INFINITY, f64::min);
            base.entry(id).and_modify(|b| *b = b.min(h)).or_insert(h);
        }
    }
    let mut out: Vec<ObjectDesc> = Vec::with_capacity(objects.len());
    let mut meshes: BTreeMap<MeshKey, (usize, LocalMesh)> = BTreeMap::new();
    for o in objects {
        if let Some(piece) = ground_piece(&o) {
            let key = (o.material.clone(), o.semantic.clone(), o.instance);
            let slot = meshes.entry(key).or_insert_with(|| {
                out.push(o.clone());
                (out.len() - 1, LocalMesh::default())
            });
            let t = o.transform.translate.unwrap_or_default();
            let heading = heading_only(&o.transform).unwrap_or(0.0);
            for off in repeat_offsets(&o.repeat) {
                let at = [t[0] + off.x, t[1] + off.y];
                let (size, b, tp) = piece;
                let place =
                    |p: [f64; 2], dz: f64| DVec3::new(p[0], p[1], grade.height_m(p[0], p[1]) + dz);
                piece_mesh(
                    &mut slot.1,
                    (size, b + off.z, tp + off.z),
                    (at, heading),
                    (STEP_M, true),
                    &place,
                );
            }
            continue;
        }
        if let Some(id) = building_id(&o) {
            out.push(lifted(o, base[&id]));
            continue;
        }
        // A world-space mesh on the level ground (a piece bent by the
        // organic warp, cut ≤ STEP_M) follows h at every vertex.
        if matches!(o.shape, ShapeDesc::Mesh { .. })
            && o.transform.is_identity()
            && o.repeat.is_empty()
        {
            let mut one = [o];
            drape_meshes(&mut one, grade);
            let [o] = one;
            out.push(o);
            continue;
        }
        // Repeat copies spread over the ground each stand at their own point.
        let t = o.transform.translate.unwrap_or_default();
        let offsets = repeat_offsets(&o.repeat);
        let spread = offsets.iter().any(|d| d.x != 0.0 || d.y != 0.0);
        if !spread {
            let h = grade.height_m(t[0], t[1]);
            out.push(lifted(o, h));
            continue;
        }
        for d in offsets {
            let mut copy = o.clone();
            copy.repeat.clear();
            let p = [t[0] + d.x, t[1] + d.y, t[2] + d.z];
            copy.transform.translate = Some(p);
            let h = grade.height_m(p[0], p[1]);
            out.push(lifted(copy, h));
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

/// Points of an object's footprint, world (x, y): a box's four corners
/// (turned about z), any other shape's origin; every repeat copy.
fn footprint_points(o: &ObjectDesc) -> Vec<[f64; 2]> {
    let t = o.transform.translate.unwrap_or_default();
    let corners: Vec<[f64; 2]> = match (&o.shape, heading_only(&o.transform)) {
        (ShapeDesc::Box { size }, Some(h)) => {
            let (c, s) = (h.to_radians().cos(), h.to_radians().sin());
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .map(|(a, b)| {
                    let (u, v) = (a * size[0] / 2.0, b * size[1] / 2.0);
                    [t[0] + c * u - s * v, t[1] + s * u + c * v]
                })
                .to_vec()
        }
        _ => vec![[t[0], t[1]]],
    };
    repeat_offsets(&o.repeat)
        .iter()
        .flat_map(|d| corners.iter().map(move |p| [p[0] + d.x, p[1] + d.y]))
        .collect()
}

/// The object moved up by `dz` metres.
fn lifted(mut o: ObjectDesc, dz: f64) -> ObjectDesc {
    let mut t = o.transform.translate.unwrap_or_default();
    t[2] += dz;
    o.transform.translate = Some(t);
    o
}

/// Adds h to every vertex of the inline meshes among `objects` (world
/// positions, identity transform) and tilts their normals to match: a
/// normal n of a height field z = f has slopes (−n.x/n.z, −n.y/n.z), and
/// the new field f + h has the sum of both slopes.
pub fn drape_meshes(objects: &mut [ObjectDesc], grade: &Grade) {
    for o in objects {
        let ShapeDesc::Mesh {
            positions, normals, ..
        } = &mut o.shape
        else {
            continue;
        };
        for (k, p) in positions.iter_mut().enumerate() {
            let [gx, gy] = grade.gradient(p[0], p[1]);
            if let Some(n) = normals.get_mut(k) {
                let v = DVec3::new(n[0] / n[2] - gx, n[1] / n[2] - gy, 1.0).normalize();
                *n = v.to_array();
            }
            p[2] += grade.height_m(p[0], p[1]);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::town::parts::{class, ground_quad, repeated, slab};

    fn grade() -> Grade {
        let mut d = crate::town::parse_town_str(
            &std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/town04.toml"))
                .unwrap(),
            std::path::Path::new("town04.toml"),
        )
        .unwrap();
        d.road_grade_m = 8.0;
        Grade::new(&d, 1).unwrap()
    }

    #[test]
    fn draped_quads_and_boxes_follow_the_field_at_every_vertex() {
        let g = grade();
        let road = ground_quad([0.0, -7.0], [40.0, 7.0], 0.0, "asphalt", class("road"));
        let dash = repeated(
            slab(
                [1.0, -0.06],
                [4.0, 0.06],
                0.0,
                0.008,
                "paint",
                class("road_line"),
            ),
            &[(3, [6.0, 0.0, 0.0])],
        );
        let out = drape_objects(vec![road, dash], &g);
        assert_eq!(out.len(), 2);
        let ShapeDesc::Mesh {
            positions,
            triangles,
            ..
        } = &out[0].shape
        else {
            panic!("road not a mesh")
        };
        // 40 × 14 m in ≤ 5 m pieces: 8 × 3 cells.
        assert_eq!(triangles.len(), 2 * 8 * 3);
        for p in positions {
            assert!((p[2] - g.height_m(p[0], p[1])).abs() < 1e-12);
        }
        let ShapeDesc::Mesh { positions, .. } = &out[1].shape else {
            panic!("dash not a mesh")
        };
        // Three dashes, each a box of two 2 × 2 layers.
        assert_eq!(positions.len(), 3 * 2 * 4);
        let tops = positions
            .iter()
            .filter(|p| (p[2] - 0.008 - g.height_m(p[0], p[1])).abs() < 1e-12);
        assert_eq!(tops.count(), 12);
        let last = positions.iter().map(|p| p[0]).fold(f64::MIN, f64::max);
        assert!((last - 16.0).abs() < 1e-12);
    }
}
