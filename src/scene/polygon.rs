//! Triangulation of one OBJ polygon (three or more corners, possibly concave
//! or slightly non-planar) in its best-fit plane (Newell normal).
//!
//! A convex polygon keeps the fan from its first corner, the triangles tobj
//! made before, so files of convex faces render the same bytes; a concave
//! one is ear-clipped by `earcut`, so no triangle leaves it and their areas
//! sum to its area. A self-intersecting polygon has no such triangulation
//! and is refused.

use earcut::utils3d::project3d_to_2d;
use earcut::Earcut;
use glam::DVec3;

use super::mesh::is_degenerate;

/// Relative mismatch between the triangles' area and the polygon's above
/// which the polygon is taken to cross itself (rounding stays far below).
const AREA_TOLERANCE: f64 = 1e-7;

/// Triangles of the polygon `corners` as corner indices, wound like the
/// polygon; an error says why it cannot be triangulated.
pub fn triangulate(corners: &[DVec3]) -> Result<Vec<[usize; 3]>, String> {
    let n = corners.len();
    let fan: Vec<[usize; 3]> = (1..n.saturating_sub(1)).map(|i| [0, i, i + 1]).collect();
    if n <= 3 {
        return Ok(fan);
    }
    let p3: Vec<[f64; 3]> = corners.iter().map(|c| c.to_array()).collect();
    let mut p2 = Vec::with_capacity(n);
    if !project3d_to_2d(&p3, n, &mut p2) {
        // No Newell normal: collinear corners (every triangle is degenerate
        // and dropped later), or lobes of opposite turn cancelling out.
        let flat = fan
            .iter()
            .all(|t| is_degenerate(corners[t[0]], corners[t[1]], corners[t[2]]));
        return if flat {
            Ok(fan)
        } else {
            Err(format!(
                "the {n}-corner polygon crosses itself (its area cancels out)"
            ))
        };
    }
    let area = signed_area(&p2);
    if is_convex(&p2, area) {
        return Ok(fan);
    }
    let mut flat = Vec::new();
    Earcut::new().earcut(p2.iter().copied(), &[] as &[usize], &mut flat);
    let mut tris: Vec<[usize; 3]> = flat.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    let mut covered = 0.0;
    for t in &mut tris {
        let a = signed_area(&[p2[t[0]], p2[t[1]], p2[t[2]]]);
        covered += a.abs();
        // earcut fixes its own winding: restore the polygon's.
        if a * area < 0.0 {
            t.swap(1, 2);
        }
    }
    if (covered - area.abs()).abs() > AREA_TOLERANCE * area.abs() {
        return Err(format!(
            "the {n}-corner polygon crosses itself (ear clipping covers {covered:.6e} of its {:.6e} m² in its plane)",
            area.abs()
        ));
    }
    Ok(tris)
}

/// Shoelace area, positive for counter-clockwise corners.
fn signed_area(p: &[[f64; 2]]) -> f64 {
    let n = p.len();
    (0..n)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % n]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum::<f64>()
        / 2.0
}

/// Whether every corner turns the same way as the polygon (straight corners
/// allowed) and the boundary goes round once: a convex, simple polygon.
fn is_convex(p: &[[f64; 2]], area: f64) -> bool {
    let n = p.len();
    let mut turning = 0.0;
    for i in 0..n {
        let (a, b, c) = (p[(i + n - 1) % n], p[i], p[(i + 1) % n]);
        let (u, v) = ([b[0] - a[0], b[1] - a[1]], [c[0] - b[0], c[1] - b[1]]);
        let cross = u[0] * v[1] - u[1] * v[0];
        if cross * area < 0.0 {
            return false;
        }
        turning += cross.atan2(u[0] * v[0] + u[1] * v[1]);
    }
    // A star turns the same way at every corner but goes round twice.
    turning.abs() < 3.0 * std::f64::consts::PI
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(xy: &[[f64; 2]]) -> Vec<DVec3> {
        xy.iter().map(|p| DVec3::new(p[0], p[1], 0.0)).collect()
    }

    /// Sum of the triangles' areas and whether every one keeps the +z winding.
    fn area_and_winding(c: &[DVec3], tris: &[[usize; 3]]) -> (f64, bool) {
        let mut sum = 0.0;
        let mut ccw = true;
        for t in tris {
            let n = (c[t[1]] - c[t[0]]).cross(c[t[2]] - c[t[0]]);
            sum += n.length() / 2.0;
            ccw &= n.z >= 0.0;
        }
        (sum, ccw)
    }

    #[test]
    fn convex_polygon_keeps_the_fan() {
        let c = poly(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
        assert_eq!(triangulate(&c).unwrap(), vec![[0, 1, 2], [0, 2, 3]]);
    }

    #[test]
    fn concave_polygon_is_ear_clipped_within_its_area() {
        // An arrow whose notch is at corner 0: the fan from 0 would fill it.
        let c = poly(&[[1.0, 0.5], [0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]]);
        let tris = triangulate(&c).unwrap();
        assert_eq!(tris.len(), 3);
        let (area, ccw) = area_and_winding(&c, &tris);
        assert!((area - 1.5).abs() < 1e-12, "area {area}");
        assert!(ccw);
    }

    #[test]
    fn self_intersecting_polygons_are_refused() {
        let bowtie = poly(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0], [0.0, 1.0]]);
        assert!(triangulate(&bowtie).unwrap_err().contains("crosses itself"));
        let uneven = poly(&[[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 1.0]]);
        assert!(triangulate(&uneven).unwrap_err().contains("crosses itself"));
        let star: Vec<[f64; 2]> = (0..5)
            .map(|k| {
                let a = (2 * k) as f64 * std::f64::consts::TAU / 5.0;
                [a.cos(), a.sin()]
            })
            .collect();
        assert!(triangulate(&poly(&star)).is_err());
    }

    #[test]
    fn collinear_corners_give_degenerate_triangles_only() {
        let c = poly(&[[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]]);
        assert_eq!(triangulate(&c).unwrap().len(), 2);
    }
}
