//! Rays traced independently of the renderer, in f64, for the ground-truth
//! tests of generated objects (trees, vehicles, people): a level 96×54 rig
//! looking along +x, per-pixel candidate triangles, first hits with edge
//! ties (a ray within 10 µm of a triangle edge may go either way), and one
//! check of every view's depth and disparity against them.

use glam::DVec3;
use parallax::render::FrameOutput;

use crate::common::triangle::plane_hit;
use parallax::scene::desc::{ObjectDesc, ShapeDesc};

pub(super) const W: u32 = 96;
pub(super) const H: u32 = 54;
/// The triangles of a prefab's mesh objects, each corner placed by `place`
/// (a turn about z and a shift, written out by each test).
pub(super) fn placed_triangles(
    objects: &[ObjectDesc],
    place: impl Fn([f64; 3]) -> DVec3,
) -> Vec<[DVec3; 3]> {
    let mut out = Vec::new();
    for o in objects {
        let ShapeDesc::Mesh {
            positions,
            triangles,
            ..
        } = &o.shape
        else {
            panic!("prefabs of generated objects are meshes");
        };
        out.extend(
            triangles
                .iter()
                .map(|t| t.map(|k| place(positions[k as usize]))),
        );
    }
    out
}

/// Ray-to-edge distance below which a pixel is an edge tie, metres.
const TIE_M: f64 = 1e-5;

pub(super) fn f_px() -> f64 {
    (W as f64 / 2.0) / 30f64.to_radians().tan()
}

/// Ray direction with x component 1 (so t = depth Z) through pixel (i, j)
/// of a level camera looking along +x.
pub(super) fn dir(i: u32, j: u32) -> DVec3 {
    let f = f_px();
    DVec3::new(
        1.0,
        -((i as f64 + 0.5) - W as f64 / 2.0) / f,
        -((j as f64 + 0.5) - H as f64 / 2.0) / f,
    )
}

/// Nearest hit of the ray c + t·d (Möller–Trumbore in f64) and whether it
/// is a tie: some triangle's boundary passes within `TIE_M` of the ray
/// before the nearest clear hit.
pub(super) fn trace(c: DVec3, d: DVec3, tris: &[[DVec3; 3]], cand: &[u32]) -> (Option<f64>, bool) {
    let mut best: Option<f64> = None;
    let mut near_edges: Vec<f64> = Vec::new();
    for &k in cand {
        let [a, b, e] = tris[k as usize];
        let Some((t, u, v)) = plane_hit(c, d, [a, b, e]) else {
            continue;
        };
        if t <= 0.0 {
            continue;
        }
        let (e1, e2) = (b - a, e - a);
        // Distances of the plane hit point to the three edges, metres:
        // barycentric times the height over that edge.
        let area2 = e1.cross(e2).length();
        let bary = [1.0 - u - v, u, v];
        let edges = [e - b, e - a, b - a];
        let dist = |m: usize| bary[m] * area2 / edges[m].length();
        let inside = (0..3).map(dist).fold(f64::INFINITY, f64::min);
        if inside >= TIE_M {
            best = Some(best.map_or(t, |b: f64| b.min(t)));
        } else if inside > -TIE_M {
            near_edges.push(t);
        }
    }
    // The ground: the 400 m square z = 0 round the origin.
    if d.z < 0.0 {
        let t = -c.z / d.z;
        let p = c + d * t;
        if p.x.abs() < 200.0 && p.y.abs() < 200.0 {
            best = Some(best.map_or(t, |b: f64| b.min(t)));
        }
    }
    let tie = near_edges.iter().any(|&t| best.is_none_or(|b| t <= b));
    (best, tie)
}

/// Triangle indices whose projected bounding box covers each pixel of a
/// camera at `c` (every vertex is ahead of it).
pub(super) fn buckets(c: DVec3, tris: &[[DVec3; 3]]) -> Vec<Vec<u32>> {
    let f = f_px();
    let mut out = vec![Vec::new(); (W * H) as usize];
    for (k, t) in tris.iter().enumerate() {
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in t {
            let d = *p - c;
            assert!(d.x > 1.0, "vertex behind the camera");
            let uv = [
                W as f64 / 2.0 - f * d.y / d.x,
                H as f64 / 2.0 - f * d.z / d.x,
            ];
            for a in 0..2 {
                lo[a] = lo[a].min(uv[a]);
                hi[a] = hi[a].max(uv[a]);
            }
        }
        // Pixel centres i + 0.5 in [lo, hi], one pixel of margin.
        let i0 = (lo[0] - 1.5).ceil().max(0.0) as u32;
        let i1 = ((hi[0] + 0.5).floor()).min(W as f64 - 1.0);
        let j0 = (lo[1] - 1.5).ceil().max(0.0) as u32;
        let j1 = ((hi[1] + 0.5).floor()).min(H as f64 - 1.0);
        if i1 < 0.0 || j1 < 0.0 {
            continue;
        }
        for j in j0..=j1 as u32 {
            for i in i0..=i1 as u32 {
                out[(j * W + i) as usize].push(k as u32);
            }
        }
    }
    out
}

/// A pixel whose independently traced ray hits the objects or the ground.
pub(super) struct TracedPixel<'a> {
    /// 0 = left, b + 1 = the right view of baseline b.
    pub view: usize,
    /// The view's camera centre.
    pub c: DVec3,
    pub i: u32,
    pub j: u32,
    /// Traced depth.
    pub z: f64,
    /// The hit lies on the objects, in front of the ground z = 0.
    pub on_object: bool,
    /// Candidate triangles of the pixel (`buckets`).
    pub cand: &'a [u32],
}

/// Compares depth and disparity of every pixel of the left view and of each
/// right view (baselines along −y from `c_left`) with rays traced here
/// through `tris` over the ground z = 0 and the sky; on the left, `class`
/// labels exactly the object pixels. Calls `each` on every hit pixel and
/// returns (pixels checked, edge ties, object pixels on the left).
pub(super) fn check_views(
    out: &FrameOutput,
    c_left: DVec3,
    baselines_m: &[f64],
    tris: &[[DVec3; 3]],
    class: u8,
    mut each: impl FnMut(&TracedPixel),
) -> (usize, usize, usize) {
    let f = f_px();
    let cams: Vec<DVec3> = std::iter::once(c_left)
        .chain(
            baselines_m
                .iter()
                .map(|&b| c_left + DVec3::new(0.0, -b, 0.0)),
        )
        .collect();
    let (mut checked, mut ties, mut object_px) = (0usize, 0usize, 0usize);
    for (v, &c) in cams.iter().enumerate() {
        let cand = buckets(c, tris);
        for j in 0..H {
            for i in 0..W {
                let k = (j * W + i) as usize;
                let (z_true, tie) = trace(c, dir(i, j), tris, &cand[k]);
                if tie {
                    ties += 1;
                    continue;
                }
                let (z, d, bs) = if v == 0 {
                    let d = out.baselines.iter().map(|b| b.disparity_left[k]).collect();
                    (out.left.depth_z[k], d, baselines_m.to_vec())
                } else {
                    let b = &out.baselines[v - 1];
                    let d = vec![b.disparity_right[k]];
                    (b.depth_right[k] as f64, d, vec![baselines_m[v - 1]])
                };
                checked += 1;
                let Some(zt) = z_true else {
                    assert!(
                        z.is_infinite() && z > 0.0,
                        "view {v} ({i},{j}): {z}, not sky"
                    );
                    assert!(
                        d.iter().all(|&d| d == 0.0),
                        "view {v} ({i},{j}): sky disparity"
                    );
                    continue;
                };
                assert!(
                    (z - zt).abs() <= 1e-5 * zt,
                    "view {v} pixel ({i},{j}): Z {z} vs {zt}"
                );
                for (dv, bm) in d.iter().zip(bs) {
                    let (dt, dv) = (f * bm / zt, *dv as f64);
                    assert!(
                        (dv - dt).abs() <= 1e-5 * dt + 1e-6,
                        "view {v} pixel ({i},{j}) B={bm}: d {dv} vs {dt}"
                    );
                }
                let dz = dir(i, j).z;
                let ground = if dz < 0.0 { c.z / -dz } else { f64::INFINITY };
                // (beyond the ground square's edge the sky: no object either)
                let on_object = zt < ground * (1.0 - 1e-12);
                if v == 0 {
                    assert_eq!(
                        out.left.semantic[k] == class,
                        on_object,
                        "pixel ({i},{j}): semantic {} at Z {zt}",
                        out.left.semantic[k]
                    );
                    object_px += on_object as usize;
                }
                each(&TracedPixel {
                    view: v,
                    c,
                    i,
                    j,
                    z: zt,
                    on_object,
                    cand: &cand[k],
                });
            }
        }
    }
    (checked, ties, object_px)
}
