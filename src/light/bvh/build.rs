//! Building the light BVH: bucketed splits minimising Conty & Kulla's
//! cost (power × orientation × area, §4.4), halving by count past a depth
//! so every trail fits in 128 bits; large subtrees built in parallel into
//! the very nodes a serial build gives.

use glam::Vec3;

use super::{acos_clamped, LightBounds, Node};

/// Depth past which splits are by count, keeping every trail within 128 bits.
const MAX_SAH_DEPTH: u32 = 64;
/// Buckets per axis in the split search.
const BUCKETS: usize = 12;

/// Lights per subtree from which its two halves are built in parallel
/// (below it a fork costs more than the half it saves).
pub(super) const PARALLEL_GRAIN: usize = 4096;

/// Nodes of a subtree in depth-first order (inner nodes' child indices
/// relative to its first node) and the trails of its lights.
#[derive(Default)]
pub(super) struct Subtree {
    pub(super) nodes: Vec<Node>,
    pub(super) trails: Vec<(u32, u128)>,
}

impl Subtree {
    /// Appends the subtree over `ids` at `(trail, depth)`.
    pub(super) fn build(
        &mut self,
        all: &[LightBounds],
        ids: &mut [u32],
        at: (u128, u32),
        grain: usize,
    ) {
        let (trail, depth) = at;
        let node = self.nodes.len();
        if ids.len() == 1 {
            self.nodes.push(Node {
                bounds: all[ids[0] as usize],
                child_or_light: ids[0],
                leaf: true,
            });
            self.trails.push((ids[0], trail));
            return;
        }
        let total = ids[1..]
            .iter()
            .fold(all[ids[0] as usize], |b, &i| b.union(&all[i as usize]));
        self.nodes.push(Node {
            bounds: total,
            child_or_light: 0,
            leaf: false,
        });
        let mid = if depth < MAX_SAH_DEPTH {
            sah_split(all, ids, &total)
        } else {
            None
        }
        .unwrap_or_else(|| {
            // Fallback: halve by count along the widest centroid axis.
            let axis = centroid_box(all, ids).1.max_position();
            let mid = ids.len() / 2;
            ids.select_nth_unstable_by(mid, |&a, &b| {
                let (ca, cb) = (all[a as usize].centroid(), all[b as usize].centroid());
                ca[axis].total_cmp(&cb[axis]).then(a.cmp(&b))
            });
            mid
        });
        let (left, right) = ids.split_at_mut(mid);
        let right_at = (trail | (1u128 << depth), depth + 1);
        if ids_len_at_least(left, right, grain) {
            let (mut l, mut r) = (Subtree::default(), Subtree::default());
            rayon::join(
                || l.build(all, left, (trail, depth + 1), grain),
                || r.build(all, right, right_at, grain),
            );
            self.append(l);
            self.nodes[node].child_or_light = self.nodes.len() as u32;
            self.append(r);
        } else {
            self.build(all, left, (trail, depth + 1), grain);
            self.nodes[node].child_or_light = self.nodes.len() as u32;
            self.build(all, right, right_at, grain);
        }
    }

    /// Appends `sub`'s nodes (their child indices shifted to where they land).
    fn append(&mut self, sub: Subtree) {
        let offset = self.nodes.len() as u32;
        self.nodes.extend(sub.nodes.into_iter().map(|mut n| {
            if !n.leaf {
                n.child_or_light += offset;
            }
            n
        }));
        self.trails.extend(sub.trails);
    }
}

/// Whether both halves are big enough to be built in parallel.
fn ids_len_at_least(left: &[u32], right: &[u32], grain: usize) -> bool {
    left.len().min(right.len()) >= grain
}

/// Box of the centroids of `ids` and its extent.
fn centroid_box(all: &[LightBounds], ids: &[u32]) -> (Vec3, Vec3) {
    let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
    for &i in ids {
        let c = all[i as usize].centroid();
        lo = lo.min(c);
        hi = hi.max(c);
    }
    (lo, hi - lo)
}

/// Orientation measure M_Ω of a cone (pbrt-v4 eq. 12.x / Conty & Kulla eq. 1).
fn orientation_measure(b: &LightBounds) -> f32 {
    use std::f32::consts::PI;
    let theta_o = acos_clamped(b.cos_theta_o);
    let theta_e = acos_clamped(b.cos_theta_e);
    let theta_w = (theta_o + theta_e).min(PI);
    let sin_o = theta_o.sin();
    2.0 * PI * (1.0 - b.cos_theta_o)
        + PI / 2.0
            * (2.0 * theta_w * sin_o - (theta_o - 2.0 * theta_w).cos() - 2.0 * theta_o * sin_o
                + b.cos_theta_o)
}

/// Split cost of a cluster: power × orientation × surface area, stretched
/// along `axis` when the parent box is thin there (Conty & Kulla §4.4).
fn cost(b: &LightBounds, parent: &LightBounds, axis: usize) -> f32 {
    let d = parent.p_max - parent.p_min;
    let kr = if d[axis] > 0.0 {
        d.max_element() / d[axis]
    } else {
        1.0
    };
    let e = b.p_max - b.p_min;
    let area = 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    b.phi * orientation_measure(b) * kr * area.max(1e-8)
}

/// Bucketed split minimising [`cost`]; partitions `ids` and returns the split
/// index, or None when no bucket split separates the lights.
fn sah_split(all: &[LightBounds], ids: &mut [u32], parent: &LightBounds) -> Option<usize> {
    let (lo, ext) = centroid_box(all, ids);
    let bucket = |i: u32, axis: usize| {
        let t = (all[i as usize].centroid()[axis] - lo[axis]) / ext[axis];
        ((t * BUCKETS as f32) as usize).min(BUCKETS - 1)
    };
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in 0..3 {
        if ext[axis] <= 0.0 {
            continue;
        }
        let mut bins: [Option<LightBounds>; BUCKETS] = [None; BUCKETS];
        for &i in ids.iter() {
            let b = &mut bins[bucket(i, axis)];
            let l = &all[i as usize];
            *b = Some(b.map_or(*l, |x| x.union(l)));
        }
        // Unions of buckets below and above each split, swept once per side.
        let mut below = [None::<LightBounds>; BUCKETS];
        let mut above = [None::<LightBounds>; BUCKETS];
        let join = |a: Option<LightBounds>, b: &Option<LightBounds>| match (a, b) {
            (Some(a), Some(b)) => Some(a.union(b)),
            (a, b) => a.or(*b),
        };
        for k in 1..BUCKETS {
            below[k] = join(below[k - 1], &bins[k - 1]);
            let j = BUCKETS - 1 - k;
            above[j] = join(above[j + 1], &bins[j + 1]);
        }
        for split in 1..BUCKETS {
            // below[split] holds buckets 0..split; above[split − 1] holds split..
            let (Some(l), Some(r)) = (below[split], above[split - 1]) else {
                continue;
            };
            let c = cost(&l, parent, axis) + cost(&r, parent, axis);
            if best.is_none_or(|(bc, _, _)| c < bc) {
                best = Some((c, axis, split));
            }
        }
    }
    let (_, axis, split) = best?;
    let mut mid = 0;
    for k in 0..ids.len() {
        if bucket(ids[k], axis) < split {
            ids.swap(k, mid);
            mid += 1;
        }
    }
    (mid > 0 && mid < ids.len()).then_some(mid)
}
