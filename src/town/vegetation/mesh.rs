//! Triangle meshes of grown plants: tapered generalised cylinders along
//! branch polylines (rings carried along the path by parallel transport, so
//! they never twist) and leaf blades (a folded four-point blade: two
//! triangles, or a needle spray of the same shape, long and narrow).

use glam::DVec3;

use crate::scene::desc::ShapeDesc;
use crate::scene::mesh::LocalMesh;

/// The outline of a leaf blade: length and width in metres, and where
/// along the blade (0 = stalk, 1 = tip) it is widest.
#[derive(Clone, Copy, Debug)]
pub struct Blade {
    /// Base-to-tip length, metres.
    pub len: f64,
    /// Greatest width, metres.
    pub width: f64,
    /// Fraction of the length where the blade is widest.
    pub widest: f64,
}

/// Positions and triangles of one plant part (bark or leaves).
#[derive(Clone, Debug, Default)]
pub struct PlantMesh {
    /// Vertex positions, metres, prefab frame (z up, origin at the foot).
    pub positions: Vec<DVec3>,
    /// Vertex indices, counter-clockwise seen from the outside or the
    /// leaf's upper face.
    pub triangles: Vec<[u32; 3]>,
}

/// A unit vector perpendicular to the unit vector `t`.
pub fn perpendicular(t: DVec3) -> DVec3 {
    let a = if t.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    t.cross(a).normalize()
}

impl PlantMesh {
    fn vertex(&mut self, p: DVec3) -> u32 {
        self.positions.push(p);
        (self.positions.len() - 1) as u32
    }

    /// A tube of `sides` sides along `path` (point, radius), open at the
    /// base (it starts inside its parent) and closed by a cone to the last
    /// point (the tip). Needs at least two points with distinct neighbours.
    pub fn tube(&mut self, path: &[(DVec3, f64)], sides: u32) {
        let n = path.len();
        if n < 2 || sides < 3 {
            return;
        }
        let tangent = |i: usize| {
            let a = path[i.saturating_sub(1)].0;
            let b = path[(i + 1).min(n - 1)].0;
            (b - a).normalize()
        };
        let mut normal = perpendicular(tangent(0));
        let mut prev_ring: Option<u32> = None;
        for (i, &(p, r)) in path[..n - 1].iter().enumerate() {
            let t = tangent(i);
            // Parallel transport: the previous normal made perpendicular
            // to the new tangent.
            let m = normal - t * normal.dot(t);
            normal = if m.length_squared() > 1e-12 {
                m.normalize()
            } else {
                perpendicular(t)
            };
            let binormal = t.cross(normal);
            let first = self.positions.len() as u32;
            for k in 0..sides {
                let a = std::f64::consts::TAU * k as f64 / sides as f64;
                self.vertex(p + (normal * a.cos() + binormal * a.sin()) * r);
            }
            if let Some(q) = prev_ring {
                for k in 0..sides {
                    let k1 = (k + 1) % sides;
                    let (a, b, c, d) = (q + k, q + k1, first + k1, first + k);
                    self.triangles.push([a, b, c]);
                    self.triangles.push([a, c, d]);
                }
            }
            prev_ring = Some(first);
        }
        let tip = self.vertex(path[n - 1].0);
        let q = prev_ring.expect("two or more points");
        for k in 0..sides {
            self.triangles.push([q + k, q + (k + 1) % sides, tip]);
        }
    }

    /// A blade from `base` along the unit `axis`, its upper face towards
    /// the unit `up` (perpendicular to `axis`), the two side points raised
    /// by `fold` metres along `up` (a midrib crease).
    pub fn leaf(&mut self, base: DVec3, axis: DVec3, up: DVec3, b: Blade, fold: f64) {
        let side = up.cross(axis) * (b.width / 2.0);
        let mid = base + axis * (b.len * b.widest) + up * fold;
        let i0 = self.vertex(base);
        let i1 = self.vertex(mid - side);
        let i2 = self.vertex(base + axis * b.len);
        let i3 = self.vertex(mid + side);
        self.triangles.push([i0, i1, i2]);
        self.triangles.push([i0, i2, i3]);
    }

    /// Appends `other`.
    pub fn extend(&mut self, other: &PlantMesh) {
        let off = self.positions.len() as u32;
        self.positions.extend_from_slice(&other.positions);
        self.triangles.extend(
            other
                .triangles
                .iter()
                .map(|t| [t[0] + off, t[1] + off, t[2] + off]),
        );
    }

    /// This mesh as an inline scene shape (flat shaded).
    pub fn to_shape(&self) -> ShapeDesc {
        LocalMesh {
            positions: self.positions.clone(),
            normals: Vec::new(),
            triangles: self.triangles.clone(),
        }
        .into_shape()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tube_closes_on_its_tip_and_keeps_its_radius() {
        let mut m = PlantMesh::default();
        let path = [
            (DVec3::ZERO, 0.2),
            (DVec3::new(0.0, 0.0, 1.0), 0.1),
            (DVec3::new(0.3, 0.0, 2.0), 0.05),
        ];
        m.tube(&path, 6);
        // Two rings of 6 and the tip; 6 quads and a fan of 6.
        assert_eq!(m.positions.len(), 13);
        assert_eq!(m.triangles.len(), 18);
        for (k, p) in m.positions[..6].iter().enumerate() {
            assert!((p.length() - 0.2).abs() < 1e-12, "ring 0 vertex {k}: {p}");
        }
        for p in &m.positions[6..12] {
            let d = *p - path[1].0;
            assert!((d.length() - 0.1).abs() < 1e-12);
        }
        assert_eq!(m.positions[12], path[2].0);
    }

    #[test]
    fn a_leaf_faces_up_and_spans_its_blade() {
        let mut m = PlantMesh::default();
        let b = Blade {
            len: 0.1,
            width: 0.04,
            widest: 0.4,
        };
        m.leaf(DVec3::ZERO, DVec3::X, DVec3::Z, b, 0.0);
        for t in &m.triangles {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            let n = (b - a).cross(c - a);
            assert!(n.z > 0.0, "triangle {t:?} faces {n}");
        }
        let area: f64 = m
            .triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                (b - a).cross(c - a).length() / 2.0
            })
            .sum();
        // A rhombus-like kite: half the length times the width.
        assert!((area - 0.1 * 0.04 / 2.0).abs() < 1e-12, "area {area}");
    }
}
