//! Binned-SAH construction of the pure-Rust BVH (Wald, "On fast Construction
//! of SAH-based Bounding Volume Hierarchies", 2007): centroids binned on all
//! three axes, the cheapest plane by the surface area heuristic, a leaf when
//! splitting does not pay. Large subtrees are built in parallel with
//! `rayon::join` and spliced; the node array is depth-first (left child right
//! after its parent).

use glam::Vec3;

/// Bins per axis.
const BIN_COUNT: usize = 16;
/// Largest leaf the SAH may choose; bigger sets are always split.
pub(crate) const MAX_LEAF: usize = 8;
/// SAH cost of one box test relative to one primitive test.
const TRAVERSAL_COST: f32 = 0.3;
/// Subtrees at least this big are built on another rayon task.
const PARALLEL_MIN: usize = 32 * 1024;
/// Beyond this depth the builder splits at the object median, bounding depth by
/// this plus log2(n) (traversal stacks are sized for it).
const SAH_MAX_DEPTH: u32 = 48;
/// Node boxes are padded by this fraction of their largest |coordinate| (≈ 16 ulps).
const BOX_PAD_REL: f32 = 1.0 / (1 << 19) as f32;
/// Traversal stack size that the depth bound above guarantees suffices.
pub(crate) const MAX_DEPTH: usize = 96;

/// A BVH node, 32 bytes. Interior (`count == 0`): left child at index + 1,
/// right child at `offset`. Leaf: primitives `offset .. offset + count`.
#[derive(Clone, Copy, Debug)]
#[repr(C)]
pub(crate) struct Node {
    /// Box minimum corner.
    pub min: Vec3,
    /// Box maximum corner.
    pub max: Vec3,
    /// Right child (interior) or first primitive (leaf).
    pub offset: u32,
    /// Primitive count; 0 for interior nodes.
    pub count: u32,
}

/// A primitive as the builder sees it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BuildRef {
    /// Box minimum corner.
    pub min: Vec3,
    /// Box maximum corner.
    pub max: Vec3,
    /// Index into the caller's primitive list.
    pub index: u32,
}

impl BuildRef {
    fn centroid(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }
}

#[derive(Clone, Copy)]
struct Aabb {
    min: Vec3,
    max: Vec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        min: Vec3::splat(f32::INFINITY),
        max: Vec3::splat(f32::NEG_INFINITY),
    };

    fn grow(&mut self, min: Vec3, max: Vec3) {
        self.min = self.min.min(min);
        self.max = self.max.max(max);
    }

    fn half_area(&self) -> f32 {
        let e = (self.max - self.min).max(Vec3::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }
}

/// Builds the node array over `refs` (reordered in place into leaf order).
/// Returns no nodes for no primitives.
pub(crate) fn build_nodes(refs: &mut [BuildRef]) -> Vec<Node> {
    if refs.is_empty() {
        return Vec::new();
    }
    let mut nodes = Vec::with_capacity(2 * refs.len() / 3 + 1);
    build_into(&mut nodes, refs, 0, 0);
    nodes
}

/// Appends the subtree over `refs` (whose first primitive sits at `prim_base`
/// in the final order) to `nodes`.
fn build_into(nodes: &mut Vec<Node>, refs: &mut [BuildRef], prim_base: u32, depth: u32) {
    let mut bounds = Aabb::EMPTY;
    let mut centroids = Aabb::EMPTY;
    for r in refs.iter() {
        bounds.grow(r.min, r.max);
        let c = r.centroid();
        centroids.grow(c, c);
    }
    // Pad the box by a few ulps of its coordinates: the triangle test's own
    // rounding (shear of p − o) can place a hit a few ulps outside the exact
    // box, which matters for rays starting on a surface (t ≈ 0).
    let pad = bounds.min.abs().max(bounds.max.abs()).max_element() * BOX_PAD_REL;
    let node_index = nodes.len();
    nodes.push(Node {
        min: bounds.min - Vec3::splat(pad),
        max: bounds.max + Vec3::splat(pad),
        offset: prim_base,
        count: refs.len() as u32,
    });
    if refs.len() == 1 {
        return;
    }
    let mid = match choose_split(refs, &bounds, &centroids, depth) {
        Some(mid) => mid,
        None => return,
    };
    let (left, right) = refs.split_at_mut(mid);
    let right_base = prim_base + mid as u32;
    if refs_len_is_parallel(left.len(), right.len()) {
        let (mut left_nodes, mut right_nodes) = rayon::join(
            || subtree(left, prim_base, depth + 1),
            || subtree(right, right_base, depth + 1),
        );
        // Splice: the subtrees were built with node indices relative to their
        // own root; shift right-child links to the final positions.
        let left_start = nodes.len() as u32;
        for n in left_nodes.iter_mut().filter(|n| n.count == 0) {
            n.offset += left_start;
        }
        let right_start = left_start + left_nodes.len() as u32;
        for n in right_nodes.iter_mut().filter(|n| n.count == 0) {
            n.offset += right_start;
        }
        nodes.append(&mut left_nodes);
        nodes[node_index].offset = right_start;
        nodes.append(&mut right_nodes);
    } else {
        build_into(nodes, left, prim_base, depth + 1);
        nodes[node_index].offset = nodes.len() as u32;
        build_into(nodes, right, right_base, depth + 1);
    }
    nodes[node_index].count = 0;
}

fn refs_len_is_parallel(left: usize, right: usize) -> bool {
    left.min(right) >= PARALLEL_MIN
}

fn subtree(refs: &mut [BuildRef], prim_base: u32, depth: u32) -> Vec<Node> {
    let mut nodes = Vec::with_capacity(2 * refs.len() / 3 + 1);
    build_into(&mut nodes, refs, prim_base, depth);
    nodes
}

/// Partitions `refs` and returns the split index, or `None` to make a leaf.
fn choose_split(
    refs: &mut [BuildRef],
    bounds: &Aabb,
    centroids: &Aabb,
    depth: u32,
) -> Option<usize> {
    let n = refs.len();
    let extent = centroids.max - centroids.min;
    if depth >= SAH_MAX_DEPTH || extent.max_element() <= 0.0 {
        // Degenerate centroids (or a pathological depth): object median.
        if n <= MAX_LEAF && extent.max_element() <= 0.0 {
            return None;
        }
        let axis = extent.max_position();
        let mid = n / 2;
        refs.select_nth_unstable_by(mid, |a, b| {
            a.centroid()[axis].total_cmp(&b.centroid()[axis])
        });
        return Some(mid);
    }
    // Evaluate every plane between bins on every axis.
    let mut best = (f32::INFINITY, 0usize, 0usize);
    for axis in 0..3 {
        if extent[axis] <= 0.0 {
            continue;
        }
        let scale = BIN_COUNT as f32 / extent[axis];
        let mut bins = [(Aabb::EMPTY, 0usize); BIN_COUNT];
        for r in refs.iter() {
            let b = bin_of(r.centroid()[axis], centroids.min[axis], scale);
            bins[b].0.grow(r.min, r.max);
            bins[b].1 += 1;
        }
        // Sweep from the right to get suffix areas and counts.
        let mut right_cost = [0.0f32; BIN_COUNT];
        let mut acc = Aabb::EMPTY;
        let mut count = 0;
        for i in (1..BIN_COUNT).rev() {
            acc.grow(bins[i].0.min, bins[i].0.max);
            count += bins[i].1;
            right_cost[i] = acc.half_area() * count as f32;
        }
        let mut acc = Aabb::EMPTY;
        let mut count = 0;
        for i in 0..BIN_COUNT - 1 {
            acc.grow(bins[i].0.min, bins[i].0.max);
            count += bins[i].1;
            if count == 0 || count == n {
                continue;
            }
            let cost = acc.half_area() * count as f32 + right_cost[i + 1];
            if cost < best.0 {
                best = (cost, axis, i + 1);
            }
        }
    }
    // SAH with intersection cost 1 per primitive.
    let leaf_cost = n as f32;
    let split_cost = TRAVERSAL_COST + best.0 / bounds.half_area().max(f32::MIN_POSITIVE);
    if best.0.is_infinite() || (n <= MAX_LEAF && leaf_cost <= split_cost) {
        if n <= MAX_LEAF {
            return None;
        }
        let axis = extent.max_position();
        let mid = n / 2;
        refs.select_nth_unstable_by(mid, |a, b| {
            a.centroid()[axis].total_cmp(&b.centroid()[axis])
        });
        return Some(mid);
    }
    let (_, axis, split_bin) = best;
    let scale = BIN_COUNT as f32 / extent[axis];
    let (mut i, mut j) = (0, n);
    // In-place partition: refs in bins below `split_bin` go left.
    while i < j {
        if bin_of(refs[i].centroid()[axis], centroids.min[axis], scale) < split_bin {
            i += 1;
        } else {
            j -= 1;
            refs.swap(i, j);
        }
    }
    Some(i)
}

#[inline]
fn bin_of(c: f32, min: f32, scale: f32) -> usize {
    (((c - min) * scale) as usize).min(BIN_COUNT - 1)
}
