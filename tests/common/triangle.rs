//! An independent ray–triangle intersection (Möller–Trumbore in f64) for
//! tests that check the renderer's hits against their own.

use glam::DVec3;

/// Where the ray o + t·d meets the plane of triangle [a, b, c]: `(t, u, v)`
/// with the point a + u·(b − a) + v·(c − a); `None` when the ray is
/// parallel to the plane.
pub fn plane_hit(o: DVec3, d: DVec3, [a, b, c]: [DVec3; 3]) -> Option<(f64, f64, f64)> {
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(e2);
    let det = e1.dot(p);
    if det.abs() < 1e-300 {
        return None;
    }
    let s = o - a;
    let q = s.cross(e1);
    Some((e2.dot(q) / det, s.dot(p) / det, d.dot(q) / det))
}

/// The ray's parameter t > 0 where it hits the triangle (edges included).
pub fn hit(o: DVec3, d: DVec3, tri: [DVec3; 3]) -> Option<f64> {
    plane_hit(o, d, tri)
        .filter(|&(t, u, v)| u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0)
        .map(|(t, _, _)| t)
}
