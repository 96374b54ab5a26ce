use std::collections::HashMap;

use glam::{DVec3, Vec2, Vec3};

use super::*;

const TILE: f64 = 64.0;

/// z of the tilted plane the test meshes lie in.
fn plane_z(x: f64, y: f64) -> f64 {
    0.03 * (x - 2e5) - 0.02 * (y + 1.5e5) + 4.0
}

/// A jittered grid of `n`×`n` quads, 23 m each, 2e5 m from the origin,
/// crossing several tile lines, with normals, uvs and two materials.
fn grid(n: usize) -> Mesh {
    let (x0, y0) = (2e5 - 37.3, -1.5e5 - 41.9);
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut jitter = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        ((s >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 6.0
    };
    let mut m = Mesh::default();
    for j in 0..=n {
        for i in 0..=n {
            let edge = i == 0 || j == 0 || i == n || j == n;
            let (dx, dy) = if edge {
                (0.0, 0.0)
            } else {
                (jitter(), jitter())
            };
            let (x, y) = (x0 + 23.0 * i as f64 + dx, y0 + 23.0 * j as f64 + dy);
            m.p_render.push(DVec3::new(x, y, plane_z(x, y)));
            m.normals.push(Vec3::new(-0.03, 0.02, 1.0).normalize());
            m.uvs.push(Vec2::new(i as f32, j as f32));
        }
    }
    let v = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
            let mat = ((i + j) % 2) as u32;
            if (i + j) % 3 == 0 {
                m.triangles.extend([[a, b, c], [a, c, d]]);
            } else {
                m.triangles.extend([[a, b, d], [b, c, d]]);
            }
            m.tri_material.extend([mat, mat]);
        }
    }
    m.semantic = 7;
    m.instance = 3;
    m
}

/// Barycentric coordinates of (x, y) in the xy projection of `t`.
fn bary(t: [DVec3; 3], x: f64, y: f64) -> [f64; 3] {
    let d = (t[1].x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (t[1].y - t[0].y);
    let b1 = ((x - t[0].x) * (t[2].y - t[0].y) - (t[2].x - t[0].x) * (y - t[0].y)) / d;
    let b2 = ((t[1].x - t[0].x) * (y - t[0].y) - (x - t[0].x) * (t[1].y - t[0].y)) / d;
    [1.0 - b1 - b2, b1, b2]
}

/// The triangle of `m` over (x, y) (with a tolerance for edges): its
/// material and the interpolated z.
fn over(m: &Mesh, x: f64, y: f64) -> Option<(u32, f64)> {
    m.triangles
        .iter()
        .zip(&m.tri_material)
        .find_map(|(t, &mat)| {
            let p = t.map(|i| m.p_render[i as usize]);
            let b = bary(p, x, y);
            b.iter()
                .all(|&w| w >= -1e-9)
                .then(|| (mat, b[0] * p[0].z + b[1] * p[1].z + b[2] * p[2].z))
        })
}

#[test]
fn pieces_cover_each_tile_with_the_mesh_it_holds_and_nothing_else() {
    let m = grid(8);
    let pieces = split_by_tiles(&m, TILE);
    // 184 m wide from x ≡ 26.7 and y ≡ 38.1 (mod 64): four columns and rows.
    assert_eq!(pieces.len(), 16);
    let e = SEAM_OVERLAP_M;
    for (&(tx, ty), p) in &pieces {
        let (x0, y0) = (tx as f64 * TILE, ty as f64 * TILE);
        assert_eq!((p.semantic, p.instance), (7, 3));
        assert_eq!(p.normals.len(), p.p_render.len());
        assert_eq!(p.uvs.len(), p.p_render.len());
        assert_eq!(p.tri_material.len(), p.triangles.len());
        for q in &p.p_render {
            assert!(q.x >= x0 - e && q.x <= x0 + TILE + e, "{q} in tile {tx}");
            assert!(q.y >= y0 - e && q.y <= y0 + TILE + e, "{q} in tile {ty}");
            // On the mesh's plane, within f64 rounding.
            assert!((q.z - plane_z(q.x, q.y)).abs() < 1e-9, "{q}");
        }
        // Each piece triangle lies in one triangle of the mesh, with its
        // material.
        for (t, &mat) in p.triangles.iter().zip(&p.tri_material) {
            let c = t.iter().map(|&i| p.p_render[i as usize]).sum::<DVec3>() / 3.0;
            assert_eq!(over(&m, c.x, c.y).map(|o| o.0), Some(mat), "{c}");
        }
    }
    // Every point of the mesh, seams included, is covered by its tile's
    // piece (and within the overlap by the neighbour's too), at the same
    // height and with the same material.
    let (lo, hi) = (m.p_render[0], m.p_render[m.p_render.len() - 1]);
    let mut checked = 0;
    for k in 0..400 {
        let x = lo.x + (hi.x - lo.x) * ((k * 37 % 400) as f64 + 0.5) / 400.0;
        let y = lo.y + (hi.y - lo.y) * ((k * 91 % 400) as f64 + 0.5) / 400.0;
        // The tile edge nearest to x, when it crosses the mesh.
        let seam_x = (x / TILE).round() * TILE;
        let mut points = vec![(x, y)];
        if seam_x > lo.x && seam_x < hi.x {
            points.extend([(seam_x, y), (seam_x + 0.9 * e, y), (seam_x - 0.9 * e, y)]);
        }
        for (x, y) in points {
            let (mat, z) = over(&m, x, y).expect("inside the mesh");
            let ty = cell(y, TILE);
            let tiles = if (x - seam_x).abs() < e {
                let k = cell(seam_x, TILE);
                vec![(k - 1, ty), (k, ty)]
            } else {
                vec![(cell(x, TILE), ty)]
            };
            for t in tiles {
                let (pm, pz) =
                    over(&pieces[&t], x, y).unwrap_or_else(|| panic!("{x},{y} in {t:?}"));
                assert_eq!(pm, mat);
                assert!((pz - z).abs() < 1e-9);
                checked += 1;
            }
        }
    }
    assert!(checked > 1200, "{checked}");
}

#[test]
fn edges_shared_in_the_mesh_stay_shared_in_each_piece() {
    let m = grid(8);
    let e = SEAM_OVERLAP_M;
    for (&(tx, ty), p) in &split_by_tiles(&m, TILE) {
        // The clip lines as `split_by_tiles` computes them.
        let (tx0, ty0) = (tx as f64 * TILE, ty as f64 * TILE);
        let (x0, y0) = (tx0 - e, ty0 - e);
        let (x1, y1) = (tx0 + TILE + e, ty0 + TILE + e);
        let (lo, hi) = (m.p_render[0], m.p_render[m.p_render.len() - 1]);
        let mut uses: HashMap<(u32, u32), u32> = HashMap::new();
        for t in &p.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *uses.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        for ((a, b), n) in uses {
            let (pa, pb) = (p.p_render[a as usize], p.p_render[b as usize]);
            // Edges along a clip line or the mesh's own border have one
            // triangle; every other edge has two (no crack, no T-junction).
            let along = |x: f64, y: f64| (pa.x == x && pb.x == x) || (pa.y == y && pb.y == y);
            let border = along(x0, y0) || along(x1, y1) || along(lo.x, lo.y) || along(hi.x, hi.y);
            assert_eq!(n, if border { 1 } else { 2 }, "edge {pa} {pb} in {tx},{ty}");
        }
    }
}

#[test]
fn cut_points_carry_interpolated_normals_and_uvs() {
    let mut m = grid(3);
    // Normals that vary along the grid (as the uvs do; affine, not
    // normalised, so the interpolant is exact), so a cut point's normal
    // shows whether it was interpolated between its edge's ends.
    let normal = |i: f64, j: f64| Vec3::new(0.1 * i as f32, 0.05 * j as f32, 1.0);
    for (k, n) in m.normals.iter_mut().enumerate() {
        *n = normal((k % 4) as f64, (k / 4) as f64);
    }
    for p in split_by_tiles(&m, TILE).values() {
        for ((q, uv), n) in p.p_render.iter().zip(&p.uvs).zip(&p.normals) {
            // uv follows the grid index: invert it on the undisturbed rows
            // and columns (the mesh's border), where it is affine in x, y.
            let (i, j) = ((q.x - (2e5 - 37.3)) / 23.0, (q.y - (-1.5e5 - 41.9)) / 23.0);
            let row = j.abs() < 1e-9 || (j - 3.0).abs() < 1e-9;
            let column = i.abs() < 1e-9 || (i - 3.0).abs() < 1e-9;
            if row {
                assert!((uv.x as f64 - i).abs() < 1e-4, "{q}: {uv}");
            }
            if column {
                assert!((uv.y as f64 - j).abs() < 1e-4, "{q}: {uv}");
            }
            if row || column {
                let want = normal(i, j).normalize();
                assert!((n.normalize() - want).length() < 1e-4, "{q}: {n} vs {want}");
            }
        }
    }
}

#[test]
fn a_mesh_inside_one_tile_is_one_unchanged_piece() {
    let mut m = grid(1);
    // One 23 m quad, moved to lie inside tile (3124, −2344).
    for p in &mut m.p_render {
        p.x += 10.0;
        p.y += 30.0;
    }
    let pieces = split_by_tiles(&m, TILE);
    assert_eq!(pieces.len(), 1);
    let p = &pieces[&(3124, -2344)];
    assert_eq!(p.triangles.len(), 2);
    let mut a: Vec<_> = p.p_render.iter().map(|q| q.to_array()).collect();
    let mut b: Vec<_> = m.p_render.iter().map(|q| q.to_array()).collect();
    a.sort_by(|x, y| x.partial_cmp(y).unwrap());
    b.sort_by(|x, y| x.partial_cmp(y).unwrap());
    assert_eq!(a, b);
}
