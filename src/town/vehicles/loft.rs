//! Generated surfaces for vehicles: a parametric grid swept over (u, v)
//! (a lofted body, a patch of it lifted off as a skin), a lathe (tyres,
//! rims, steering wheels) and smooth per-vertex normals averaged from the
//! faces. Every builder winds triangles counter-clockwise seen from the
//! side its normals point to.

use glam::DVec3;

use crate::scene::mesh::LocalMesh;

/// A surface point for parameters (u, v).
pub type Surface<'a> = &'a dyn Fn(f64, f64) -> [f64; 3];

/// `n + 1` samples from `a` to `b`.
fn steps(a: f64, b: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..=n).map(move |k| a + (b - a) * k as f64 / n as f64)
}

/// The grid of `f` over u ∈ [u0, u1] (nu cells) × v ∈ [v0, v1] (nv cells),
/// each point moved `lift` metres along the surface normal; faces wind
/// (u, v) counter-clockwise, so the normal is ∂u × ∂v (`flip` reverses).
#[allow(clippy::too_many_arguments)]
pub fn grid(
    f: Surface,
    (u0, u1, nu): (f64, f64, usize),
    (v0, v1, nv): (f64, f64, usize),
    lift: f64,
    flip: bool,
) -> LocalMesh {
    let mut m = LocalMesh::default();
    for u in steps(u0, u1, nu) {
        for v in steps(v0, v1, nv) {
            m.positions.push(DVec3::from(f(u, v)));
        }
    }
    let row = nv as u32 + 1;
    for i in 0..nu as u32 {
        for j in 0..nv as u32 {
            let (a, b, c, d) = (
                i * row + j,
                (i + 1) * row + j,
                (i + 1) * row + j + 1,
                i * row + j + 1,
            );
            if flip {
                m.triangles.push([a, c, b]);
                m.triangles.push([a, d, c]);
            } else {
                m.triangles.push([a, b, c]);
                m.triangles.push([a, c, d]);
            }
        }
    }
    smooth(&mut m);
    if lift != 0.0 {
        for (p, n) in m.positions.iter_mut().zip(&m.normals) {
            *p += *n * lift;
        }
    }
    m
}

/// Per-vertex normals: the area-weighted mean of the adjacent faces'
/// normals (a vertex with none keeps +z).
pub fn smooth(m: &mut LocalMesh) {
    let mut acc = vec![DVec3::ZERO; m.positions.len()];
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| m.positions[i as usize]);
        let n = (b - a).cross(c - a);
        for &i in t {
            acc[i as usize] += n;
        }
    }
    m.normals = acc
        .into_iter()
        .map(|n| n.try_normalize().unwrap_or(DVec3::Z))
        .collect();
}

/// A closed profile of (radius, y) points revolved about the y axis in
/// `segments` steps, faces turned to point out of the solid it bounds.
pub fn lathe(profile: &[[f64; 2]], segments: usize) -> LocalMesh {
    let np = profile.len();
    let f = |u: f64, v: f64| {
        let [r, y] = profile[(v.round() as usize) % np];
        [r * u.cos(), y, r * u.sin()]
    };
    let mut m = grid(
        &f,
        (0.0, std::f64::consts::TAU, segments),
        (0.0, np as f64, np),
        0.0,
        false,
    );
    if volume(&m) < 0.0 {
        m.triangles.iter_mut().for_each(|t| t.swap(1, 2));
        smooth(&mut m);
    }
    m
}

/// Signed volume of a closed mesh (divergence theorem), > 0 when faces
/// point out.
pub fn volume(m: &LocalMesh) -> f64 {
    m.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| m.positions[i as usize]);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lathed_square_is_an_outward_ring_of_the_right_volume() {
        // Square section r ∈ [1, 2], y ∈ [0, 1] revolved: π(2² − 1²)·1 = 3π
        // for the smooth ring, less for 256 flat sides (cos-factor ~1e-4).
        let prof = [[1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]];
        let m = lathe(&prof, 256);
        let v = volume(&m).abs();
        assert!((v - 3.0 * std::f64::consts::PI).abs() < 3e-3, "{v}");
        assert!(volume(&m) > 0.0);
        // Either orientation of the profile gives the same outward solid.
        let rev: Vec<[f64; 2]> = prof.iter().rev().copied().collect();
        assert!((volume(&lathe(&rev, 256)) - volume(&m)).abs() < 1e-9);
    }

    #[test]
    fn grid_lift_moves_points_along_the_normal() {
        let plane = |u: f64, v: f64| [u, v, 0.0];
        let m = grid(&plane, (0.0, 1.0, 2), (0.0, 1.0, 2), 0.01, false);
        assert!(m.positions.iter().all(|p| (p.z - 0.01).abs() < 1e-12));
        let m = grid(&plane, (0.0, 1.0, 2), (0.0, 1.0, 2), 0.01, true);
        assert!(m.positions.iter().all(|p| (p.z + 0.01).abs() < 1e-12));
    }
}
