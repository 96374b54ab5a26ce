//! Cutting a static mesh wider than a tile (ground, roads, ramps, hills)
//! into one piece per static tile (`anchored`), so that it joins the tiles'
//! prototypes instead of being rebuilt in render space every frame.
//!
//! Each triangle is clipped (Sutherland–Hodgman, f64 world coordinates) to
//! every tile square it meets, each square widened by [`SEAM_OVERLAP_M`]:
//! neighbouring pieces overlap in a 2 mm strip along tile edges, so a ray
//! crossing a seam always meets one piece well inside its edge, whatever
//! rounding the two instances' f32 transforms bring (no cracks between
//! tiles). Within a piece the mesh stays watertight: the point where an
//! edge crosses a clip line is computed from the edge's two end vertices in
//! a fixed order, so the two triangles sharing that edge get the same bits.
//! Pieces of one triangle lie in its plane up to f64 rounding (1e-16
//! relative), which is what the ground-truth pass re-intersects.

use std::collections::{BTreeMap, HashMap};

use glam::{DVec3, Vec2, Vec3};

use super::mesh::is_degenerate;
use super::Mesh;

/// How far each piece reaches past its tile's edge, metres.
pub const SEAM_OVERLAP_M: f64 = 1e-3;

/// One polygon vertex with the attributes the mesh carries.
#[derive(Clone, Copy, Debug)]
struct Vert {
    p: DVec3,
    n: Vec3,
    uv: Vec2,
}

impl Vert {
    fn key(&self) -> [u64; 6] {
        [
            self.p.x.to_bits(),
            self.p.y.to_bits(),
            self.p.z.to_bits(),
            u64::from(self.n.x.to_bits()) | u64::from(self.n.y.to_bits()) << 32,
            u64::from(self.n.z.to_bits()),
            u64::from(self.uv.x.to_bits()) | u64::from(self.uv.y.to_bits()) << 32,
        ]
    }
}

/// Where segment `a`–`b` crosses the line `p[axis] = c`: computed from the
/// end points ordered by their bits, so either direction gives one result.
fn crossing(a: Vert, b: Vert, axis: usize, c: f64) -> Vert {
    // An end point on the line is the crossing itself.
    for v in [a, b] {
        if v.p[axis] == c {
            return v;
        }
    }
    let ka = a.p.to_array().map(f64::to_bits);
    let kb = b.p.to_array().map(f64::to_bits);
    let (a, b) = if ka <= kb { (a, b) } else { (b, a) };
    let t = (c - a.p[axis]) / (b.p[axis] - a.p[axis]);
    let mut p = a.p + (b.p - a.p) * t;
    p[axis] = c;
    let tf = t as f32;
    Vert {
        p,
        n: a.n + (b.n - a.n) * tf,
        uv: a.uv + (b.uv - a.uv) * tf,
    }
}

/// Keeps the part of `poly` on the side `sign · (p[axis] − c) ≥ 0`.
fn clip(poly: &[Vert], axis: usize, c: f64, sign: f64) -> Vec<Vert> {
    let inside = |v: &Vert| sign * (v.p[axis] - c) >= 0.0;
    let mut out: Vec<Vert> = Vec::with_capacity(poly.len() + 1);
    // A vertex on the line would come twice (as itself and as a crossing).
    let mut push = |v: Vert| {
        if out.last().is_none_or(|l| l.p != v.p) {
            out.push(v);
        }
    };
    for (i, &cur) in poly.iter().enumerate() {
        let prev = poly[(i + poly.len() - 1) % poly.len()];
        match (inside(&prev), inside(&cur)) {
            (true, true) => push(cur),
            (true, false) => push(crossing(prev, cur, axis, c)),
            (false, true) => {
                push(crossing(prev, cur, axis, c));
                push(cur);
            }
            (false, false) => {}
        }
    }
    if out.len() > 1 && out[0].p == out[out.len() - 1].p {
        out.pop();
    }
    out
}

/// A piece of a mesh being gathered: its vertices deduplicated by bits.
struct Piece {
    mesh: Mesh,
    index: HashMap<[u64; 6], u32>,
}

impl Piece {
    fn vertex(&mut self, v: Vert, normals: bool, uvs: bool) -> u32 {
        let m = &mut self.mesh;
        *self.index.entry(v.key()).or_insert_with(|| {
            m.p_render.push(v.p);
            if normals {
                m.normals.push(v.n);
            }
            if uvs {
                m.uvs.push(v.uv);
            }
            m.p_render.len() as u32 - 1
        })
    }
}

/// The tile cell of coordinate `v`.
pub(super) fn cell(v: f64, tile: f64) -> i64 {
    (v / tile).floor() as i64
}

/// `m` (world-space `p_render`) cut into pieces per tile `(x, y)` of edge
/// `tile`: every tile whose square, widened by [`SEAM_OVERLAP_M`], meets a
/// triangle gets the part of it inside. Pieces keep `m`'s labels, per
/// triangle materials, normals and texture coordinates (interpolated along
/// cut edges); their `p_f32` is left empty (the caller moves them first).
pub fn split_by_tiles(m: &Mesh, tile: f64) -> BTreeMap<(i64, i64), Mesh> {
    let (normals, uvs) = (!m.normals.is_empty(), !m.uvs.is_empty());
    let vert = |i: u32| Vert {
        p: m.p_render[i as usize],
        n: if normals {
            m.normals[i as usize]
        } else {
            Vec3::ZERO
        },
        uv: if uvs { m.uvs[i as usize] } else { Vec2::ZERO },
    };
    let mut pieces: BTreeMap<(i64, i64), Piece> = BTreeMap::new();
    let e = SEAM_OVERLAP_M;
    for (t, tri) in m.triangles.iter().enumerate() {
        let v = tri.map(vert);
        let lo = v[0].p.min(v[1].p).min(v[2].p);
        let hi = v[0].p.max(v[1].p).max(v[2].p);
        for x in cell(lo.x - e, tile)..=cell(hi.x + e, tile) {
            for y in cell(lo.y - e, tile)..=cell(hi.y + e, tile) {
                let (x0, y0) = (x as f64 * tile, y as f64 * tile);
                let whole = lo.x >= x0 - e
                    && hi.x <= x0 + tile + e
                    && lo.y >= y0 - e
                    && hi.y <= y0 + tile + e;
                let poly = if whole {
                    v.to_vec()
                } else {
                    let poly = clip(&v, 0, x0 - e, 1.0);
                    let poly = clip(&poly, 0, x0 + tile + e, -1.0);
                    let poly = clip(&poly, 1, y0 - e, 1.0);
                    clip(&poly, 1, y0 + tile + e, -1.0)
                };
                if poly.len() < 3 {
                    continue;
                }
                let piece = pieces.entry((x, y)).or_insert_with(|| Piece {
                    mesh: Mesh {
                        semantic: m.semantic,
                        instance: m.instance,
                        ..Mesh::default()
                    },
                    index: HashMap::new(),
                });
                // A fan over the convex polygon.
                for k in 1..poly.len() - 1 {
                    let f = [poly[0], poly[k], poly[k + 1]];
                    if is_degenerate(f[0].p, f[1].p, f[2].p) {
                        continue;
                    }
                    let ids = f.map(|w| piece.vertex(w, normals, uvs));
                    piece.mesh.triangles.push(ids);
                    piece.mesh.tri_material.push(m.tri_material[t]);
                }
            }
        }
    }
    pieces
        .into_iter()
        .filter(|(_, p)| !p.mesh.triangles.is_empty())
        .map(|(k, p)| (k, p.mesh))
        .collect()
}

#[cfg(test)]
#[path = "tile_clip_tests.rs"]
mod tests;
