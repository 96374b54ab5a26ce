//! Primitive tessellation in the object's local frame, f64: quad, box,
//! cylinder, ellipsoid. Triangles wind counter-clockwise seen from outside
//! (geometric normal (b − a) × (c − a) points out). Flat shapes carry no
//! normals; curved ones carry analytic per-vertex normals.
//!
//! Also the checks every loaded triangle list passes, OBJ file or inline
//! `kind = "mesh"`: finite coordinates within ±`MAX_COORD_M`, indices in
//! range, degenerate triangles dropped and an all-degenerate mesh refused.

use glam::DVec3;
use std::f64::consts::TAU;

use super::desc::ShapeDesc;

/// Largest accepted coordinate magnitude of a mesh vertex, metres.
pub const MAX_COORD_M: f64 = 1e7;

/// A tessellated shape in its local frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LocalMesh {
    /// Vertex positions, metres.
    pub positions: Vec<DVec3>,
    /// Unit per-vertex normals, or empty for flat shading.
    pub normals: Vec<DVec3>,
    /// Vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

impl LocalMesh {
    /// Appends the planar quad `v` (a loop) as two triangles wound to face
    /// `front`.
    pub fn push_quad_facing(&mut self, mut v: [DVec3; 4], front: DVec3) {
        if (v[1] - v[0]).cross(v[3] - v[0]).dot(front) < 0.0 {
            v.reverse();
        }
        let base = self.positions.len() as u32;
        self.positions.extend(v);
        self.triangles
            .extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
    }

    /// Keeps the triangles whose corners (positions) `keep` accepts, in
    /// order, and only the vertices they use: a removed face leaves no
    /// stray vertex (an OBJ export would list it). Vertices keep their
    /// order and normals.
    pub fn retain_triangles(&mut self, keep: impl Fn([DVec3; 3]) -> bool) {
        let positions = &self.positions;
        self.triangles
            .retain(|t| keep(t.map(|i| positions[i as usize])));
        // Each used vertex's new index, in the old order.
        let mut new_index: Vec<Option<u32>> = vec![None; self.positions.len()];
        for &i in self.triangles.iter().flatten() {
            new_index[i as usize] = Some(0);
        }
        for (next, slot) in new_index.iter_mut().flatten().enumerate() {
            *slot = next as u32;
        }
        let used = |v: &[DVec3]| -> Vec<DVec3> {
            v.iter()
                .zip(&new_index)
                .filter_map(|(&x, k)| k.map(|_| x))
                .collect()
        };
        self.positions = used(&self.positions);
        if !self.normals.is_empty() {
            self.normals = used(&self.normals);
        }
        for t in &mut self.triangles {
            *t = t.map(|i| new_index[i as usize].expect("a used vertex"));
        }
    }

    /// This mesh as an inline scene shape (`kind = "mesh"`).
    pub fn into_shape(self) -> ShapeDesc {
        ShapeDesc::Mesh {
            positions: self.positions.iter().map(|p| p.to_array()).collect(),
            normals: self.normals.iter().map(|n| n.to_array()).collect(),
            triangles: self.triangles,
        }
    }
}

/// Whether triangle abc has no usable area: with e1 = b − a, e2 = c − a and
/// s = max(|e1|², |e2|²), |e1 × e2|² ≤ 1e-24 · s² (a sine below 1e-12
/// relative to the longer edge: its normal would be noise) or s = 0.
pub fn is_degenerate(a: DVec3, b: DVec3, c: DVec3) -> bool {
    let (e1, e2) = (b - a, c - a);
    let s = e1.length_squared().max(e2.length_squared());
    e1.cross(e2).length_squared() <= 1e-24 * s * s || s == 0.0
}

/// Checks that every vertex is finite and within ±`MAX_COORD_M`.
pub fn check_positions<P: Copy + Into<DVec3>>(positions: &[P]) -> Result<(), String> {
    for (i, &p) in positions.iter().enumerate() {
        let p: DVec3 = p.into();
        if !p.is_finite() {
            return Err(format!("vertex {i} is not finite: {p}"));
        }
        if p.abs().max_element() > MAX_COORD_M {
            return Err(format!("vertex {i} = {p} is beyond ±{MAX_COORD_M:e} m"));
        }
    }
    Ok(())
}

/// The triangles with an area (see `is_degenerate`), in order, and how many
/// were dropped; an index out of range is an error.
pub fn keep_nondegenerate<P: Copy + Into<DVec3>>(
    positions: &[P],
    triangles: &[[u32; 3]],
) -> Result<(Vec<[u32; 3]>, usize), String> {
    let mut kept = Vec::with_capacity(triangles.len());
    for &t in triangles {
        if let Some(&bad) = t.iter().find(|&&i| i as usize >= positions.len()) {
            return Err(format!(
                "vertex index {bad} out of range ({} vertices)",
                positions.len()
            ));
        }
        let [a, b, c] = t.map(|i| positions[i as usize].into());
        if !is_degenerate(a, b, c) {
            kept.push(t);
        }
    }
    let dropped = triangles.len() - kept.len();
    Ok((kept, dropped))
}

/// Checks an inline mesh as OBJ files are checked, and one shading normal
/// of usable length per vertex if any are given. An error names the field
/// at fault (`positions`, `normals`, `triangles`).
pub fn check_inline(
    positions: &[[f64; 3]],
    normals: &[[f64; 3]],
    triangles: &[[u32; 3]],
) -> Result<(), (&'static str, String)> {
    check_positions(positions).map_err(|m| ("positions", m))?;
    if !normals.is_empty() && normals.len() != positions.len() {
        let msg = format!(
            "{} normals for {} vertices (give one per vertex, or none)",
            normals.len(),
            positions.len()
        );
        return Err(("normals", msg));
    }
    // A length that is zero, subnormal, infinite or NaN has no direction.
    if let Some(i) = normals
        .iter()
        .position(|&n| !DVec3::from(n).length().is_normal())
    {
        let msg = format!("normal {i} = {:?} has no usable direction", normals[i]);
        return Err(("normals", msg));
    }
    let (kept, dropped) = keep_nondegenerate(positions, triangles).map_err(|m| ("triangles", m))?;
    if kept.is_empty() {
        let msg = format!(
            "no usable triangles ({} given, {dropped} degenerate)",
            triangles.len()
        );
        return Err(("triangles", msg));
    }
    Ok(())
}

/// Triangle count of each tessellated shape (the resource guard uses these).
pub fn cylinder_triangles(segments: u32, capped: bool) -> u64 {
    segments as u64 * if capped { 4 } else { 2 }
}

/// Triangle count of an ellipsoid: fans at both poles, quads in between.
pub fn ellipsoid_triangles(segments: u32, rings: u32) -> u64 {
    2 * segments as u64 * (rings as u64 - 1)
}

/// A `size[0]` × `size[1]` rectangle in the xy plane, normal +z.
pub fn quad(size: [f64; 2]) -> LocalMesh {
    let (hx, hy) = (size[0] / 2.0, size[1] / 2.0);
    LocalMesh {
        positions: vec![
            DVec3::new(-hx, -hy, 0.0),
            DVec3::new(hx, -hy, 0.0),
            DVec3::new(hx, hy, 0.0),
            DVec3::new(-hx, hy, 0.0),
        ],
        normals: Vec::new(),
        triangles: vec![[0, 1, 2], [0, 2, 3]],
    }
}

/// An axis-aligned box centred at the origin.
pub fn cuboid(size: [f64; 3]) -> LocalMesh {
    let h = DVec3::from(size) / 2.0;
    // Vertex i has x sign from bit 0, y from bit 1, z from bit 2.
    let positions = (0..8)
        .map(|i| {
            let s = |bit: u32| if i >> bit & 1 == 1 { 1.0 } else { -1.0 };
            DVec3::new(s(0), s(1), s(2)) * h
        })
        .collect();
    let faces: [[u32; 4]; 6] = [
        [0, 2, 3, 1], // −z
        [4, 5, 7, 6], // +z
        [0, 1, 5, 4], // −y
        [2, 6, 7, 3], // +y
        [0, 4, 6, 2], // −x
        [1, 3, 7, 5], // +x
    ];
    let triangles = faces
        .iter()
        .flat_map(|f| [[f[0], f[1], f[2]], [f[0], f[2], f[3]]])
        .collect();
    LocalMesh {
        positions,
        normals: Vec::new(),
        triangles,
    }
}

/// A cylinder along +z from z = 0 to `height`, optionally capped.
pub fn cylinder(radius: f64, height: f64, segments: u32, capped: bool) -> LocalMesh {
    let mut m = LocalMesh::default();
    let n = segments;
    let dir = |i: u32| {
        let phi = TAU * i as f64 / n as f64;
        DVec3::new(phi.cos(), phi.sin(), 0.0)
    };
    // Side: vertex 2i at the base, 2i + 1 at the top, radial normals.
    for i in 0..n {
        let d = dir(i);
        m.positions.push(d * radius);
        m.positions.push(d * radius + DVec3::Z * height);
        m.normals.extend([d, d]);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        let (b0, t0, b1, t1) = (2 * i, 2 * i + 1, 2 * j, 2 * j + 1);
        m.triangles.push([b0, b1, t1]);
        m.triangles.push([b0, t1, t0]);
    }
    if capped {
        for (z, normal) in [(0.0, -DVec3::Z), (height, DVec3::Z)] {
            let centre = m.positions.len() as u32;
            m.positions.push(DVec3::Z * z);
            m.normals.push(normal);
            for i in 0..n {
                m.positions.push(dir(i) * radius + DVec3::Z * z);
                m.normals.push(normal);
            }
            for i in 0..n {
                let (a, b) = (centre + 1 + i, centre + 1 + (i + 1) % n);
                // Counter-clockwise seen from outside: reversed on the bottom.
                m.triangles.push(if z == 0.0 {
                    [centre, b, a]
                } else {
                    [centre, a, b]
                });
            }
        }
    }
    m
}

/// An ellipsoid with semi-axes `radii`, `segments` around z and `rings`
/// from pole to pole; normals ∝ (x/a², y/b², z/c²).
pub fn ellipsoid(radii: [f64; 3], segments: u32, rings: u32) -> LocalMesh {
    let r = DVec3::from(radii);
    let mut m = LocalMesh::default();
    let mut push = |unit: DVec3| {
        let p = unit * r;
        m.positions.push(p);
        m.normals.push((p / (r * r)).normalize());
    };
    push(DVec3::Z);
    for ring in 1..rings {
        let theta = std::f64::consts::PI * ring as f64 / rings as f64;
        for s in 0..segments {
            let phi = TAU * s as f64 / segments as f64;
            push(DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ));
        }
    }
    push(-DVec3::Z);
    let south = m.positions.len() as u32 - 1;
    let at = |ring: u32, s: u32| 1 + (ring - 1) * segments + s % segments;
    for s in 0..segments {
        m.triangles.push([0, at(1, s), at(1, s + 1)]);
        m.triangles
            .push([south, at(rings - 1, s + 1), at(rings - 1, s)]);
    }
    for ring in 1..rings - 1 {
        for s in 0..segments {
            let (a, b, c, d) = (
                at(ring, s),
                at(ring + 1, s),
                at(ring + 1, s + 1),
                at(ring, s + 1),
            );
            m.triangles.push([a, b, c]);
            m.triangles.push([a, c, d]);
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A capped cylinder without its top cap: the same triangles (as
    /// corner positions, with the same normals) as before, minus the cap's,
    /// and no vertex that no triangle uses.
    #[test]
    fn retaining_triangles_drops_the_vertices_only_removed_faces_used() {
        let full = cylinder(0.5, 2.0, 8, true);
        let top = |c: [DVec3; 3]| c.iter().all(|p| p.z == 2.0);
        let corners = |m: &LocalMesh| -> Vec<Vec<(DVec3, Option<DVec3>)>> {
            let at = |i: u32| (m.positions[i as usize], m.normals.get(i as usize).copied());
            m.triangles.iter().map(|t| t.map(at).to_vec()).collect()
        };
        let want: Vec<_> = corners(&full)
            .into_iter()
            .filter(|c| !top([c[0].0, c[1].0, c[2].0]))
            .collect();
        let mut cut = full.clone();
        cut.retain_triangles(|c| !top(c));
        assert_eq!(cut.triangles.len(), 8 * 3);
        assert_eq!(corners(&cut), want);
        assert_eq!(cut.normals.len(), cut.positions.len());
        let mut used = vec![false; cut.positions.len()];
        for &i in cut.triangles.iter().flatten() {
            used[i as usize] = true;
        }
        assert!(used.iter().all(|&u| u), "a vertex no triangle uses");
        // The vertices kept are exactly those the kept triangles used, in
        // their old order.
        let kept: std::collections::BTreeSet<u32> = (full.triangles.iter())
            .filter(|t| !top(t.map(|i| full.positions[i as usize])))
            .flatten()
            .copied()
            .collect();
        let kept_positions: Vec<DVec3> = kept.iter().map(|&i| full.positions[i as usize]).collect();
        assert!(kept.len() < full.positions.len());
        assert_eq!(cut.positions, kept_positions);
    }

    /// Every triangle's geometric normal points away from the centroid.
    fn assert_outward(m: &LocalMesh, centre: DVec3) {
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            let n = (b - a).cross(c - a);
            assert!(n.length() > 0.0, "degenerate triangle {t:?}");
            assert!(
                n.dot((a + b + c) / 3.0 - centre) > 0.0,
                "inward triangle {t:?}"
            );
        }
    }

    #[test]
    fn degeneracy_is_relative_to_edge_length_and_indices_are_checked() {
        let (a, b) = (DVec3::ZERO, DVec3::X);
        for s in [1e-6, 1.0, 1e6] {
            // A sine of 1e-9 is a thin but real triangle at any scale, 1e-13 is not.
            assert!(!is_degenerate(a * s, b * s, DVec3::new(0.5, 1e-9, 0.0) * s));
            assert!(is_degenerate(a * s, b * s, DVec3::new(0.5, 1e-13, 0.0) * s));
        }
        assert!(is_degenerate(b, b, b));
        let p = [a, b, DVec3::Y, DVec3::X * 2.0];
        let (kept, dropped) = keep_nondegenerate(&p, &[[0, 1, 2], [0, 1, 3], [2, 1, 0]]).unwrap();
        assert_eq!((kept, dropped), (vec![[0, 1, 2], [2, 1, 0]], 1));
        let e = keep_nondegenerate(&p, &[[0, 1, 4]]).unwrap_err();
        assert!(e.contains("index 4") && e.contains("4 vertices"), "{e}");
    }

    #[test]
    fn shapes_wind_outward_with_predicted_counts() {
        let b = cuboid([1.0, 2.0, 3.0]);
        assert_eq!(b.triangles.len(), 12);
        assert_outward(&b, DVec3::ZERO);
        let c = cylinder(1.0, 2.0, 12, true);
        assert_eq!(c.triangles.len() as u64, cylinder_triangles(12, true));
        assert_outward(&c, DVec3::Z);
        let e = ellipsoid([1.0, 2.0, 0.5], 10, 6);
        assert_eq!(e.triangles.len() as u64, ellipsoid_triangles(10, 6));
        assert_outward(&e, DVec3::ZERO);
        let q = quad([2.0, 4.0]);
        let [a, b, c] = q.triangles[0].map(|i| q.positions[i as usize]);
        assert!((b - a).cross(c - a).z > 0.0);
    }
}
