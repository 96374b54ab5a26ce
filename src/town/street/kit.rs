//! A prefab builder: parts (boxes, rods, prisms, rings, lettering) added in
//! the prefab's local frame and merged into one inline mesh per (material,
//! class, shading), so a detailed prefab is a handful of scene objects.
//!
//! Local frame: z up, origin on the ground at the foot of the item. Faces
//! of signs and signal heads look along local −x (`face_frame`): face
//! coordinates u (right, as a viewer on −x sees it), v (up) and w (out of
//! the face, towards −x). Every transform is a rotation plus a translation,
//! so winding and normals stay valid.

use glam::{DAffine3, DMat3, DQuat, DVec3};

use crate::scene::desc::{ObjectDesc, TransformDesc};
use crate::scene::mesh::{cuboid, cylinder, LocalMesh};
use crate::town::lettering::text_mesh;

/// One merged mesh of the kit.
struct Part {
    material: String,
    class: &'static str,
    /// Whether the mesh carries per-vertex normals (round parts).
    smooth: bool,
    mesh: LocalMesh,
}

/// Parts of one prefab, merged per (material, class, shading).
#[derive(Default)]
pub struct Kit {
    parts: Vec<Part>,
    /// Objects added as they are (lens slots placed by their own transform).
    extra: Vec<ObjectDesc>,
}

/// The frame of a sign face whose back plane is at local x = `x0`, centred
/// at (y, z) = (`y`, `z`): face (u, v, w) → local (x0 − w, y − u, z + v).
pub fn face_frame(x0: f64, y: f64, z: f64) -> DAffine3 {
    DAffine3 {
        matrix3: DMat3::from_cols(DVec3::NEG_Y, DVec3::Z, DVec3::NEG_X),
        translation: DVec3::new(x0, y, z),
    }
}

/// `frame` followed by a turn of `heading_deg` about z at the origin (a
/// face turned to look along another direction).
pub fn turned(frame: DAffine3, heading_deg: f64) -> DAffine3 {
    DAffine3::from_rotation_z(heading_deg.to_radians()) * frame
}

/// A convex polygon of `n` corners on a circle of radius `r` in the (u, v)
/// plane, the first corner at angle `start_rad` from +u, counter-clockwise.
pub fn regular(n: usize, r: f64, start_rad: f64) -> Vec<[f64; 2]> {
    (0..n)
        .map(|k| {
            let a = start_rad + std::f64::consts::TAU * k as f64 / n as f64;
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

/// A prism: the convex, counter-clockwise polygon `poly` of the (u, v)
/// plane extruded over w ∈ [w0, w1] (flat shaded, closed).
pub fn prism(poly: &[[f64; 2]], w0: f64, w1: f64) -> LocalMesh {
    ring_prism(poly, None, w0, w1)
}

/// The band between the convex polygon `outer` and `inner` (same corner
/// count, inner inside outer) extruded over w ∈ [w0, w1]; with no inner,
/// the filled polygon. Closed, counter-clockwise seen from outside.
pub fn ring_prism(outer: &[[f64; 2]], inner: Option<&[[f64; 2]]>, w0: f64, w1: f64) -> LocalMesh {
    let n = outer.len() as u32;
    let mut m = LocalMesh::default();
    let at = |p: [f64; 2], w: f64| DVec3::new(p[0], p[1], w);
    // Vertices: outer at w0 (0..n), outer at w1 (n..2n), then the inner
    // ring likewise (2n..4n) or the two centres (2n, 2n + 1).
    m.positions.extend(outer.iter().map(|&p| at(p, w0)));
    m.positions.extend(outer.iter().map(|&p| at(p, w1)));
    match inner {
        Some(inner) => {
            m.positions.extend(inner.iter().map(|&p| at(p, w0)));
            m.positions.extend(inner.iter().map(|&p| at(p, w1)));
        }
        None => {
            let c = outer
                .iter()
                .fold([0.0, 0.0], |a, p| [a[0] + p[0], a[1] + p[1]]);
            let c = [c[0] / n as f64, c[1] / n as f64];
            m.positions.extend([at(c, w0), at(c, w1)]);
        }
    }
    for k in 0..n {
        let j = (k + 1) % n;
        // Outer wall, facing away from the centre.
        m.triangles.push([k, j, n + j]);
        m.triangles.push([k, n + j, n + k]);
        match inner {
            Some(_) => {
                let (i0, i1) = (2 * n, 3 * n);
                // Front (w1, +w) and back (w0, −w) bands, inner wall inward.
                m.triangles.push([n + k, n + j, i1 + j]);
                m.triangles.push([n + k, i1 + j, i1 + k]);
                m.triangles.push([k, i0 + j, j]);
                m.triangles.push([k, i0 + k, i0 + j]);
                m.triangles.push([i0 + k, i1 + j, i0 + j]);
                m.triangles.push([i0 + k, i1 + k, i1 + j]);
            }
            None => {
                m.triangles.push([n + k, n + j, 2 * n + 1]);
                m.triangles.push([k, 2 * n, j]);
            }
        }
    }
    m
}

/// `m` moved by `t` (rotation + translation).
fn moved(mut m: LocalMesh, t: DAffine3) -> LocalMesh {
    for p in &mut m.positions {
        *p = t.transform_point3(*p);
    }
    for n in &mut m.normals {
        *n = t.matrix3 * *n;
    }
    m
}

impl Kit {
    fn part(&mut self, material: &str, class: &'static str, smooth: bool) -> &mut LocalMesh {
        let k = self
            .parts
            .iter()
            .position(|p| p.material == material && p.class == class && p.smooth == smooth)
            .unwrap_or_else(|| {
                self.parts.push(Part {
                    material: material.to_string(),
                    class,
                    smooth,
                    mesh: LocalMesh::default(),
                });
                self.parts.len() - 1
            });
        &mut self.parts[k].mesh
    }

    /// Adds mesh `m` placed by `t` (its normals decide the shading).
    pub fn add(&mut self, material: &str, class: &'static str, m: LocalMesh, t: DAffine3) {
        let m = moved(m, t);
        let part = self.part(material, class, !m.normals.is_empty());
        let base = part.positions.len() as u32;
        part.positions.extend(m.positions);
        part.normals.extend(m.normals);
        part.triangles
            .extend(m.triangles.iter().map(|t| t.map(|i| i + base)));
    }

    /// An axis-aligned box of `size` centred at `centre`.
    pub fn block(&mut self, material: &str, class: &'static str, size: [f64; 3], centre: [f64; 3]) {
        let t = DAffine3::from_translation(DVec3::from(centre));
        self.add(material, class, cuboid(size), t);
    }

    /// A box of `size` centred at `centre`, turned by `rot`.
    pub fn block_turned(
        &mut self,
        material: &str,
        class: &'static str,
        size: [f64; 3],
        centre: DVec3,
        rot: DQuat,
    ) {
        let t = DAffine3::from_rotation_translation(rot, centre);
        self.add(material, class, cuboid(size), t);
    }

    /// A round rod of radius `r` from `a` to `b` (capped, `segments` sides).
    pub fn rod(
        &mut self,
        material: &str,
        class: &'static str,
        a: DVec3,
        b: DVec3,
        r: f64,
        segments: u32,
    ) {
        let d = b - a;
        let rot = DQuat::from_rotation_arc(DVec3::Z, d.normalize());
        let t = DAffine3::from_rotation_translation(rot, a);
        self.add(material, class, cylinder(r, d.length(), segments, true), t);
    }

    /// `text` as raised letters of cap height `cap`, `depth` deep, centred
    /// at (u, v) = `centre` of `frame`'s face, rising from w = `w0`.
    #[allow(clippy::too_many_arguments)]
    pub fn text(
        &mut self,
        material: &str,
        class: &'static str,
        text: &str,
        cap: f64,
        depth: f64,
        frame: DAffine3,
        centre: [f64; 2],
        w0: f64,
    ) {
        let width = crate::town::lettering::layout(text, cap).width;
        let shift = DVec3::new(centre[0] - width / 2.0, centre[1] - cap / 2.0, w0);
        let t = frame * DAffine3::from_translation(shift);
        self.add(material, class, text_mesh(text, cap, depth), t);
    }

    /// An object added as it is.
    pub fn object(&mut self, o: ObjectDesc) {
        self.extra.push(o);
    }

    /// The merged parts as inline mesh objects (in order of first use),
    /// then the objects added as they are.
    pub fn objects(self) -> Vec<ObjectDesc> {
        let mut out: Vec<ObjectDesc> = self
            .parts
            .into_iter()
            .filter(|p| !p.mesh.triangles.is_empty())
            .map(|p| ObjectDesc {
                name: None,
                material: Some(p.material),
                semantic: Some(p.class.to_string()),
                instance: None,
                transform: TransformDesc::default(),
                repeat: Vec::new(),
                shape: p.mesh.into_shape(),
            })
            .collect();
        out.extend(self.extra);
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Signed volume of a closed mesh (divergence theorem): positive when
    /// every triangle winds counter-clockwise seen from outside.
    fn volume(m: &LocalMesh) -> f64 {
        m.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.positions[i as usize]);
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }

    #[test]
    fn prisms_and_rings_are_closed_outward_solids_of_the_right_volume() {
        // A unit square 0.1 thick: 0.1 m³; a square band 2×2 minus 1×1: 0.3.
        let sq = regular(
            4,
            std::f64::consts::FRAC_1_SQRT_2,
            std::f64::consts::FRAC_PI_4,
        );
        assert!((volume(&prism(&sq, 0.0, 0.1)) - 0.1).abs() < 1e-12);
        let big: Vec<[f64; 2]> = sq.iter().map(|p| [2.0 * p[0], 2.0 * p[1]]).collect();
        let band = ring_prism(&big, Some(&sq), 0.2, 0.3);
        assert!((volume(&band) - 0.3).abs() < 1e-12, "{}", volume(&band));
    }

    #[test]
    fn face_frame_is_a_rotation_that_faces_minus_x() {
        let f = face_frame(1.0, 2.0, 3.0);
        assert!((f.matrix3.determinant() - 1.0).abs() < 1e-15);
        // Out of the face (w) is −x; u (the viewer's right) is −y; v is up.
        assert_eq!(
            f.transform_point3(DVec3::new(0.0, 0.0, 0.5)),
            DVec3::new(0.5, 2.0, 3.0)
        );
        assert_eq!(
            f.transform_point3(DVec3::new(1.0, 1.0, 0.0)),
            DVec3::new(1.0, 1.0, 4.0)
        );
        // A turned rod keeps its length; a kit merges parts per material.
        let mut kit = Kit::default();
        kit.rod("m", "pole", DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0), 0.1, 6);
        kit.rod("m", "pole", DVec3::ZERO, DVec3::Z, 0.1, 6);
        kit.block("n", "pole", [1.0; 3], [0.0; 3]);
        let objects = kit.objects();
        assert_eq!(objects.len(), 2);
    }
}
