//! Static tiles: the flat meshes of objects that do not move within a
//! sequence (`LoadedScene::static_objects`), grouped by a fixed world grid
//! into prototypes whose local frame is anchored at the tile's centre, each
//! placed once per frame by a translation. Their geometry no longer depends
//! on the frame's render origin, so an accelerator cache (matched on the
//! meshes' bits) keeps their BVHs from frame to frame.
//!
//! A mesh goes whole to the tile of its bounding box's centre; a mesh wider
//! than a tile (ground, roads, ramps, hills) is cut at tile edges into one
//! piece per tile it crosses (`tile_clip`, with a 1 mm overlap so seams
//! between tiles have no cracks). Anchors are
//! multiples of `TILE_M / 2`, a power of two, so `p_world − anchor` is exact
//! in f64 and the local f32 positions are off by at most half an ulp of
//! |p − anchor| ≤ TILE_M/√2 + the mesh's half extent (≈ 4e-6 m for a 40 m
//! mesh). The f64 positions the ground-truth pass re-intersects are the
//! exact local ones carried through the instance's f64 translation, so
//! depth stays exact wherever the camera is in a town (no far corner is
//! worse than the centre). Emissive meshes stay flat (the light set
//! enumerates flat emitters), and so do spheres, moved into render space.

use std::collections::BTreeMap;

use glam::{DAffine3, DVec3};

use super::shapes::Leaves;
use super::tile_clip::{cell, split_by_tiles};
use super::{Instance, Mesh, Prototype};

/// Edge of a static tile, metres (a power of two).
pub const TILE_M: f64 = 64.0;

/// Name prefix of a static tile's prototype.
pub const TILE_PREFIX: &str = "static tile ";

/// The world-space leaves of the static objects sorted into tiles.
#[derive(Default)]
pub(super) struct StaticTiles {
    tiles: BTreeMap<(i64, i64), Tile>,
}

/// One tile's meshes (pieces included) and the whole meshes it stands for
/// (`Prototype::sources`: a cut mesh is listed once, at its first piece).
#[derive(Default)]
struct Tile {
    meshes: Vec<Mesh>,
    sources: Vec<(u8, u64)>,
}

impl StaticTiles {
    /// Takes the leaves of one static object, built around the world origin:
    /// emissive meshes and spheres go into `flat` in render space (around
    /// `origin_world`, the bits a direct build gives), the rest to tiles
    /// (whole, or cut into pieces when wider than a tile);
    /// `emits[i]` tells whether material `i` emits.
    pub fn add(&mut self, leaves: Leaves, emits: &[bool], origin_world: DVec3, flat: &mut Leaves) {
        for mut m in leaves.meshes {
            if m.tri_material.iter().any(|&t| emits[t as usize]) {
                for p in &mut m.p_render {
                    *p -= origin_world;
                }
                m.p_f32 = m.p_render.iter().map(|p| p.as_vec3()).collect();
                flat.meshes.push(m);
            } else if let Some(t) = tile_of(&m) {
                let tile = self.tiles.entry(t).or_default();
                tile.sources.push((m.semantic, m.triangles.len() as u64));
                tile.meshes.push(m);
            } else {
                // Wider than a tile: one piece per tile it crosses.
                let pieces = split_by_tiles(&m, TILE_M);
                let source = (m.semantic, m.triangles.len() as u64);
                for (k, (t, piece)) in pieces.into_iter().enumerate() {
                    let tile = self.tiles.entry(t).or_default();
                    if k == 0 {
                        tile.sources.push(source);
                    }
                    tile.meshes.push(piece);
                }
            }
        }
        for mut s in leaves.spheres {
            s.center -= origin_world;
            flat.spheres.push(s);
        }
    }

    /// One prototype per non-empty tile (in tile order) with its meshes in
    /// the tile's frame, and its placement around `origin_world`; instance
    /// `k` places prototype `first_prototype + k`.
    pub fn finish(
        self,
        first_prototype: u32,
        origin_world: DVec3,
    ) -> (Vec<Prototype>, Vec<Instance>) {
        let mut protos = Vec::with_capacity(self.tiles.len());
        let mut insts = Vec::with_capacity(self.tiles.len());
        for (k, (key, tile)) in self.tiles.into_iter().enumerate() {
            let Tile {
                mut meshes,
                sources,
            } = tile;
            let anchor = anchor(key);
            for m in &mut meshes {
                for p in &mut m.p_render {
                    *p -= anchor;
                }
                m.p_f32 = m.p_render.iter().map(|p| p.as_vec3()).collect();
            }
            protos.push(Prototype {
                prefab: format!("{TILE_PREFIX}{},{}", key.0, key.1),
                meshes,
                sources,
            });
            let render_from_local = DAffine3::from_translation(anchor - origin_world);
            insts.push(Instance::new(
                first_prototype + k as u32,
                render_from_local,
                None,
                None,
            ));
        }
        (protos, insts)
    }
}

/// The tile (x, y) holding the centre of `m`'s world bounding box; None for
/// a mesh wider than a tile (ground, hills, ramps), which is cut into
/// pieces instead.
fn tile_of(m: &Mesh) -> Option<(i64, i64)> {
    let (lo, hi) = m.p_render.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    if lo.x > hi.x || (hi - lo).truncate().max_element() > TILE_M {
        return None;
    }
    let c = (lo + hi) * 0.5;
    Some((cell(c.x, TILE_M), cell(c.y, TILE_M)))
}

/// World position of a tile's frame: its centre at z = 0.
fn anchor((x, y): (i64, i64)) -> DVec3 {
    let c = |i: i64| (i as f64 + 0.5) * TILE_M;
    DVec3::new(c(x), c(y), 0.0)
}

/// Whether prototype `p` is a static tile (its meshes count as flat ones in
/// content reports).
pub fn is_tile(p: &Prototype) -> bool {
    p.prefab.starts_with(TILE_PREFIX)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(points: &[[f64; 3]]) -> Mesh {
        let p_render: Vec<DVec3> = points.iter().map(|&p| DVec3::from(p)).collect();
        Mesh {
            p_f32: p_render.iter().map(|p| p.as_vec3()).collect(),
            p_render,
            triangles: vec![[0, 1, 2]],
            tri_material: vec![0],
            ..Mesh::default()
        }
    }

    #[test]
    fn meshes_go_to_the_tile_of_their_centre_in_exact_local_coordinates() {
        let mats = [false];
        let far = [1500.123456789, -733.987654321, 2.5];
        let mut tiles = StaticTiles::default();
        let mut flat = Leaves::default();
        let leaves = Leaves {
            meshes: vec![
                mesh(&[
                    far,
                    [far[0] + 3.0, far[1], 2.5],
                    [far[0], far[1] + 3.0, 2.5],
                ]),
                mesh(&[[1.0, 1.0, 0.0], [2.0, 1.0, 0.0], [1.0, 2.0, 0.0]]),
            ],
            spheres: Vec::new(),
        };
        tiles.add(leaves, &mats, DVec3::ZERO, &mut flat);
        assert!(flat.meshes.is_empty());
        let origin = DVec3::new(1490.7, -740.3, 1.6);
        let (protos, insts) = tiles.finish(7, origin);
        // Tile order: (0, 0) holds the mesh near the origin, (23, -12) the far one.
        assert_eq!(protos.len(), 2);
        assert_eq!(protos[1].prefab, "static tile 23,-12");
        assert!(protos.iter().all(is_tile));
        assert_eq!(insts[1].prototype, 8);
        let local = protos[1].meshes[0].p_render[0];
        // Anchor (23.5·64, −11.5·64, 0): the subtraction is exact.
        assert_eq!(local + DVec3::new(1504.0, -736.0, 0.0), DVec3::from(far));
        assert!(local.abs().max_element() < TILE_M);
        // Placed: the render-space point within f64 rounding of p − origin.
        let placed = insts[1].render_from_local.transform_point3(local);
        assert!((placed - (DVec3::from(far) - origin)).length() < 1e-12);
    }

    #[test]
    fn emissive_meshes_and_spheres_stay_flat_in_render_space() {
        let mats = [false, true];
        let mut lamp = mesh(&[[10.0, 0.0, 5.0], [11.0, 0.0, 5.0], [10.0, 1.0, 5.0]]);
        lamp.tri_material = vec![1];
        let ball = super::super::Sphere {
            center: DVec3::new(3.0, 4.0, 5.0),
            radius: 0.5,
            material: 0,
            semantic: 0,
            instance: 0,
        };
        let mut tiles = StaticTiles::default();
        let mut flat = Leaves::default();
        let leaves = Leaves {
            meshes: vec![lamp],
            spheres: vec![ball],
        };
        let origin = DVec3::new(1.0, 2.0, 3.0);
        tiles.add(leaves, &mats, origin, &mut flat);
        assert_eq!(flat.meshes[0].p_render[0], DVec3::new(9.0, -2.0, 2.0));
        assert_eq!(flat.meshes[0].p_f32[0], glam::Vec3::new(9.0, -2.0, 2.0));
        assert_eq!(flat.spheres[0].center, DVec3::new(2.0, 2.0, 2.0));
        assert!(tiles.finish(0, origin).0.is_empty());
    }
}
