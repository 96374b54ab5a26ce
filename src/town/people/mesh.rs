//! Smooth body parts as triangle meshes: tapered capsules (two spheres of
//! different radii joined by a cone-like band, optionally flattened front to
//! back), ellipsoids and closed frustums, gathered per material into inline
//! mesh objects with per-vertex normals.

use std::collections::BTreeMap;

use glam::DVec3;

use crate::scene::desc::{ObjectDesc, ShapeDesc, TransformDesc};

/// Sides around a limb.
const SIDES: usize = 8;
/// Latitudes per hemisphere cap, pole excluded (equator included).
const CAP_RINGS: usize = 2;
/// Rings of an umbrella canopy from the apex out to the rim.
const CANOPY_RINGS: usize = 4;

/// Triangles of one part, per material name.
#[derive(Default)]
pub struct Parts {
    meshes: BTreeMap<String, Builder>,
}

#[derive(Default)]
struct Builder {
    p: Vec<[f64; 3]>,
    n: Vec<[f64; 3]>,
    t: Vec<[u32; 3]>,
}

impl Builder {
    fn vertex(&mut self, p: DVec3, n: DVec3) -> u32 {
        self.p.push(p.to_array());
        self.n.push(n.normalize_or_zero().to_array());
        (self.p.len() - 1) as u32
    }

    /// Joins rings (each `sides` vertices from `first`) into bands, and the
    /// poles `south`/`north` (if any) to the first and last ring.
    fn stitch(&mut self, rings: &[u32], sides: usize, south: Option<u32>, north: Option<u32>) {
        let s = sides as u32;
        for w in rings.windows(2) {
            for k in 0..s {
                let (a, b) = (w[0] + k, w[0] + (k + 1) % s);
                let (c, d) = (w[1] + k, w[1] + (k + 1) % s);
                self.t.push([a, b, d]);
                self.t.push([a, d, c]);
            }
        }
        if let Some(sp) = south {
            let r = rings[0];
            for k in 0..s {
                self.t.push([sp, r + (k + 1) % s, r + k]);
            }
        }
        if let Some(np) = north {
            let r = *rings.last().expect("a ring");
            for k in 0..s {
                self.t.push([np, r + k, r + (k + 1) % s]);
            }
        }
    }
}

/// Two unit vectors across axis `u`: `side` is the one nearest `toward`
/// (the body's left, y), `front` completes the frame.
fn frame(u: DVec3, toward: DVec3) -> (DVec3, DVec3) {
    let mut side = toward - u * toward.dot(u);
    if side.length() < 1e-6 {
        side = DVec3::X - u * u.x;
    }
    let side = side.normalize();
    (side.cross(u).normalize(), side)
}

impl Parts {
    fn mesh(&mut self, mat: &str) -> &mut Builder {
        self.meshes.entry(mat.to_string()).or_default()
    }

    /// A tapered capsule from `a` (radius `ra`) to `b` (radius `rb`); its
    /// cross-section is squashed to `flat` times the radius front to back.
    pub fn capsule(&mut self, mat: &str, a: DVec3, b: DVec3, ra: f64, rb: f64, flat: f64) {
        let axis = b - a;
        let u = if axis.length() > 1e-9 {
            axis.normalize()
        } else {
            DVec3::Z
        };
        let (front, side) = frame(u, DVec3::Y);
        let m = self.mesh(mat);
        let mut rings = Vec::new();
        // Latitudes from the south pole of sphere a to the north pole of b.
        let lat: Vec<(f64, DVec3, f64)> = (1..=CAP_RINGS)
            .map(|i| (-(1.0 - i as f64 / CAP_RINGS as f64), a, ra))
            .chain((0..CAP_RINGS).map(|i| (i as f64 / CAP_RINGS as f64, b, rb)))
            .collect();
        for (f, c, r) in lat {
            let th = f * std::f64::consts::FRAC_PI_2;
            let first = m.p.len() as u32;
            for k in 0..SIDES {
                let ph = k as f64 * std::f64::consts::TAU / SIDES as f64;
                let (s, co) = ph.sin_cos();
                let radial = front * (co * th.cos()) + side * (s * th.cos()) + u * th.sin();
                let p = c + (front * (co * flat) + side * s) * (r * th.cos()) + u * (r * th.sin());
                let n = radial + front * (co * th.cos() * (1.0 / flat - 1.0));
                m.vertex(p, n);
            }
            rings.push(first);
        }
        let sp = m.vertex(a - u * ra, -u);
        let np = m.vertex(b + u * rb, u);
        m.stitch(&rings, SIDES, Some(sp), Some(np));
    }

    /// An ellipsoid centred at `c` with semi-axes `r` (x, y, z), `sides`
    /// around z and `bands` from pole to pole.
    pub fn ellipsoid(&mut self, mat: &str, c: DVec3, r: DVec3, sides: usize, bands: usize) {
        let m = self.mesh(mat);
        let mut rings = Vec::new();
        for i in 1..bands {
            let th = -std::f64::consts::FRAC_PI_2 + std::f64::consts::PI * i as f64 / bands as f64;
            let first = m.p.len() as u32;
            for k in 0..sides {
                let ph = k as f64 * std::f64::consts::TAU / sides as f64;
                let unit = DVec3::new(th.cos() * ph.cos(), th.cos() * ph.sin(), th.sin());
                m.vertex(c + unit * r, unit / r);
            }
            rings.push(first);
        }
        let sp = m.vertex(c - DVec3::Z * r.z, -DVec3::Z);
        let np = m.vertex(c + DVec3::Z * r.z, DVec3::Z);
        m.stitch(&rings, sides, Some(sp), Some(np));
    }

    /// A closed frustum along z from `c` (radius `r0`, at the top) down to
    /// `c - h·z` (radius `r1`), squashed to `flat` front to back: a skirt.
    pub fn frustum(&mut self, mat: &str, c: DVec3, h: f64, r0: f64, r1: f64, flat: f64) {
        let m = self.mesh(mat);
        let slope = (r1 - r0) / h;
        let mut rings = Vec::new();
        for (z, r) in [(0.0, r1), (h, r0)] {
            let first = m.p.len() as u32;
            for k in 0..SIDES + 4 {
                let ph = k as f64 * std::f64::consts::TAU / (SIDES + 4) as f64;
                let (s, co) = ph.sin_cos();
                let p = c + DVec3::new(co * r * flat, s * r, z - h);
                m.vertex(p, DVec3::new(co / flat, s, slope));
            }
            rings.push(first);
        }
        let sp = m.vertex(c - DVec3::Z * h, -DVec3::Z);
        let np = m.vertex(c, DVec3::Z);
        m.stitch(&rings, SIDES + 4, Some(sp), Some(np));
    }

    /// An open umbrella canopy hanging from `apex`: `ribs` ribs of length
    /// `radius` drooping `depth` at their tips (a dome z ∝ −ρ²), the cloth
    /// between two ribs drawn in a little at the rim; open underneath (both
    /// faces are seen: reflection-only materials are two-sided).
    pub fn canopy(&mut self, mat: &str, apex: DVec3, radius: f64, depth: f64, ribs: usize) {
        let m = self.mesh(mat);
        let around = 2 * ribs;
        let mut rings = Vec::new();
        for i in 1..=CANOPY_RINGS {
            let f = i as f64 / CANOPY_RINGS as f64;
            let first = m.p.len() as u32;
            for k in 0..around {
                let ph = k as f64 * std::f64::consts::TAU / around as f64;
                // Between ribs the cloth sags inward, most at the rim.
                let rho = radius * f * if k % 2 == 1 { 1.0 - 0.07 * f } else { 1.0 };
                let dir = DVec3::new(ph.cos(), ph.sin(), 0.0);
                let p = apex + dir * rho - DVec3::Z * (depth * (rho / radius).powi(2));
                // Gradient of z + depth·ρ²/R² = const.
                let n = DVec3::Z + dir * (2.0 * depth * rho / (radius * radius));
                m.vertex(p, n);
            }
            rings.push(first);
        }
        let top = m.vertex(apex, DVec3::Z);
        let s = around as u32;
        // Counter-clockwise seen from above: the face normal is the cloth's.
        for k in 0..s {
            m.t.push([top, rings[0] + k, rings[0] + (k + 1) % s]);
        }
        for w in rings.windows(2) {
            for k in 0..s {
                let (a, b) = (w[0] + k, w[0] + (k + 1) % s);
                let (c, d) = (w[1] + k, w[1] + (k + 1) % s);
                m.t.push([a, c, d]);
                m.t.push([a, d, b]);
            }
        }
    }

    /// Triangles in all parts.
    pub fn triangle_count(&self) -> usize {
        self.meshes.values().map(|b| b.t.len()).sum()
    }

    /// One inline mesh object per material, labelled `class`.
    pub fn into_objects(self, class: &str) -> Vec<ObjectDesc> {
        self.meshes
            .into_iter()
            .map(|(mat, b)| ObjectDesc {
                name: None,
                material: Some(mat),
                semantic: Some(class.to_string()),
                instance: None,
                transform: TransformDesc::default(),
                repeat: Vec::new(),
                shape: ShapeDesc::Mesh {
                    positions: b.p,
                    normals: b.n,
                    triangles: b.t,
                },
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle faces outward: its normal points away from the
    /// part's centre (a closed convex part, counter-clockwise outside).
    fn outward(parts: Parts, centre: DVec3) {
        for b in parts.meshes.values() {
            for t in &b.t {
                let [a, bb, c] = t.map(|k| DVec3::from_array(b.p[k as usize]));
                let n = (bb - a).cross(c - a);
                let mid = (a + bb + c) / 3.0;
                assert!(n.dot(mid - centre) > 0.0, "inward triangle {t:?}");
            }
        }
    }

    #[test]
    fn capsule_surface_is_at_its_radii_and_faces_out() {
        let (a, b) = (DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.3, 0.1, 0.5));
        let mut p = Parts::default();
        p.capsule("m", a, b, 0.05, 0.03, 1.0);
        assert_eq!(p.triangle_count(), 2 * SIDES * (2 * CAP_RINGS));
        // Every vertex lies on sphere a or sphere b (round cross-section).
        for v in &p.meshes["m"].p {
            let v = DVec3::from_array(*v);
            let da = ((v - a).length() - 0.05).abs();
            let db = ((v - b).length() - 0.03).abs();
            assert!(da.min(db) < 1e-12, "{v} off both spheres");
        }
        outward(p, (a + b) / 2.0);
    }

    #[test]
    fn ellipsoid_and_frustum_face_out() {
        let c = DVec3::new(1.0, 2.0, 3.0);
        let mut p = Parts::default();
        p.ellipsoid("m", c, DVec3::new(0.1, 0.08, 0.12), 10, 6);
        outward(p, c);
        let mut f = Parts::default();
        f.frustum("m", c, 0.4, 0.15, 0.25, 0.7);
        outward(f, c - DVec3::Z * 0.2);
    }
}
