//! Pure-Rust BVH backend (always built): binned-SAH binary BVH over the packed
//! triangles and spheres, ordered front-to-back traversal with a fixed stack.
//!
//! The ray/box test is conservative in the sense of Ize, "Robust BVH Ray
//! Traversal", JCGT 2(2), 2013: the far slab distance is inflated by
//! 1 + 2γ₃ so rounding never culls a box the ray touches, and a zero
//! direction component whose origin lies exactly on a slab plane (0·∞ = NaN)
//! keeps the box. Combined with the watertight triangle test this makes the
//! BVH return exactly what the brute-force scan returns. Instances: a
//! second, top-level BVH over their boxes, each prototype a BVH of its own
//! (`instances.rs`), traversed after the flat tree with its closest t.

use std::cmp::Ordering::{Equal, Less};

use glam::Vec3;

use super::bvh_build::{build_nodes, BuildRef, Node, MAX_DEPTH};
use super::instances::InstanceLayer;
use super::prim::WatertightRay;
use super::soup::{occludes, pack_primitives, ClosestSearch, PackedPrim};
use super::{Accel, AccelGeometry, Hit, Ray};

/// 1 + 2γ₃ with γₙ = nε/(1 − nε), ε = 2⁻²⁴ (Ize 2013, pbrt-v4 `Bounds3::IntersectP`).
const FAR_INFLATE: f32 = 1.0 + 2.0 * (3.0 * f32::EPSILON * 0.5) / (1.0 - 3.0 * f32::EPSILON * 0.5);

/// A binned-SAH BVH over triangles and spheres.
#[derive(Clone, Debug)]
pub struct BvhAccel {
    nodes: Vec<Node>,
    prims: Vec<PackedPrim>,
    /// Prototypes (each a BVH of its own) under a top-level BVH of placements.
    instances: InstanceLayer<BvhAccel>,
}

impl BvhAccel {
    /// Builds over `geo` (indices must be validated, see `build_accel`); large
    /// subtrees are built in parallel on the current rayon pool.
    pub fn build(geo: &AccelGeometry) -> Self {
        let prims_in = pack_primitives(geo);
        let mut refs: Vec<BuildRef> = prims_in
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let (min, max) = p.bounds();
                BuildRef {
                    min,
                    max,
                    index: i as u32,
                }
            })
            .collect();
        let nodes = build_nodes(&mut refs);
        let prims = refs.iter().map(|r| prims_in[r.index as usize]).collect();
        BvhAccel {
            nodes,
            prims,
            instances: InstanceLayer::build(geo, true, BvhAccel::build),
        }
    }

    /// Node count (for logs).
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }
}

/// Front-to-back traversal of `nodes` over `items` (leaf ranges index
/// `items`); `visit_leaf` gets each leaf's items and returns the current far
/// bound (shrinking as hits are found), or `None` to stop.
#[inline]
pub(crate) fn traverse<T>(
    nodes: &[Node],
    items: &[T],
    ray: &Ray,
    mut tmax: f32,
    mut visit_leaf: impl FnMut(&[T]) -> Option<f32>,
) {
    if nodes.is_empty() || !matches!(ray.tmin.partial_cmp(&tmax), Some(Less | Equal)) {
        return;
    }
    let inv_d = ray.d.recip();
    let mut stack = [0u32; MAX_DEPTH];
    let mut sp = 0usize;
    let mut index = 0usize;
    if slab_test(&nodes[0], ray.o, inv_d, ray.tmin, tmax).is_none() {
        return;
    }
    loop {
        let node = &nodes[index];
        if node.count > 0 {
            let start = node.offset as usize;
            match visit_leaf(&items[start..start + node.count as usize]) {
                Some(t) => tmax = t,
                None => return,
            }
        } else {
            let (left, right) = (index + 1, node.offset as usize);
            let t_left = slab_test(&nodes[left], ray.o, inv_d, ray.tmin, tmax);
            let t_right = slab_test(&nodes[right], ray.o, inv_d, ray.tmin, tmax);
            match (t_left, t_right) {
                (Some(tl), Some(tr)) => {
                    let (near, far) = if tl <= tr {
                        (left, right)
                    } else {
                        (right, left)
                    };
                    stack[sp] = far as u32;
                    sp += 1;
                    index = near;
                    continue;
                }
                (Some(_), None) => {
                    index = left;
                    continue;
                }
                (None, Some(_)) => {
                    index = right;
                    continue;
                }
                (None, None) => {}
            }
        }
        if sp == 0 {
            return;
        }
        sp -= 1;
        index = stack[sp] as usize;
    }
}

/// (low, high) of a slab's two distances. NaN (0·∞: origin on a slab plane,
/// direction parallel to it) lands in `low` if it is `a` and in `high` if it is
/// `b` — both places where the min/max that follow ignore it, so the box is kept.
#[inline(always)]
fn ordered(a: f32, b: f32) -> (f32, f32) {
    if a > b {
        (b, a)
    } else {
        (a, b)
    }
}

/// Entry distance of the ray into the node's box within `[tmin, tmax]`, if any.
#[inline(always)]
fn slab_test(node: &Node, o: Vec3, inv_d: Vec3, tmin: f32, tmax: f32) -> Option<f32> {
    let t0 = (node.min - o) * inv_d;
    let t1 = (node.max - o) * inv_d;
    let (lx, hx) = ordered(t0.x, t1.x);
    let (ly, hy) = ordered(t0.y, t1.y);
    let (lz, hz) = ordered(t0.z, t1.z);
    // `f32::max`/`f32::min` return the other operand when one is NaN.
    let t_near = tmin.max(lx).max(ly).max(lz);
    let t_far = (hx.min(hy).min(hz) * FAR_INFLATE).min(tmax);
    (t_near <= t_far).then_some(t_near)
}

impl Accel for BvhAccel {
    fn intersect(&self, ray: &Ray) -> Option<Hit> {
        let mut search = ClosestSearch::new(ray);
        traverse(&self.nodes, &self.prims, ray, ray.tmax, |prims| {
            for prim in prims {
                search.test(prim);
            }
            Some(search.tmax())
        });
        let mut best = search.finish();
        self.instances.intersect(ray, &mut best);
        best
    }

    fn occluded(&self, ray: &Ray) -> bool {
        let wray = WatertightRay::new(ray);
        let mut hit = false;
        traverse(&self.nodes, &self.prims, ray, ray.tmax, |prims| {
            hit = prims.iter().any(|p| occludes(ray, &wray, p));
            (!hit).then_some(ray.tmax)
        });
        hit || self.instances.occluded(ray)
    }

    fn backend_name(&self) -> &'static str {
        "bvh"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_node() -> Node {
        Node {
            min: Vec3::ZERO,
            max: Vec3::ONE,
            offset: 0,
            count: 1,
        }
    }

    #[test]
    fn slab_test_keeps_box_for_parallel_ray_on_its_face() {
        let node = unit_node();
        for o in [
            Vec3::new(0.0, 0.5, -1.0),
            Vec3::new(1.0, 0.5, -1.0),
            Vec3::new(0.0, 1.0, -1.0),
        ] {
            let d = Vec3::Z;
            assert_eq!(
                slab_test(&node, o, d.recip(), 0.0, f32::INFINITY),
                Some(1.0),
                "o = {o}"
            );
        }
        // Just outside the face: culled.
        let o = Vec3::new(-1e-6, 0.5, -1.0);
        assert_eq!(
            slab_test(&node, o, Vec3::Z.recip(), 0.0, f32::INFINITY),
            None
        );
    }

    #[test]
    fn slab_test_honours_segment_bounds() {
        let node = unit_node();
        let o = Vec3::new(0.5, 0.5, -2.0);
        let inv_d = Vec3::Z.recip();
        assert_eq!(slab_test(&node, o, inv_d, 0.0, 1.9), None);
        assert_eq!(slab_test(&node, o, inv_d, 3.1, 9.0), None);
        assert_eq!(slab_test(&node, o, inv_d, 2.5, 9.0), Some(2.5));
    }
}
