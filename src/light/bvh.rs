//! A light BVH for choosing one of many local lights from a shading point
//! (Conty Estevez & Kulla 2018, "Importance Sampling of Many Lights with
//! Adaptive Tree Splitting"; the layout and importance of pbrt-v4's
//! `BVHLightSampler`, §12.6.3). Each node bounds its lights' positions (box),
//! emission directions (a cone of half-angle θ_o around `w`, plus the spread
//! θ_e of emission about any of those normals) and intensity `phi`. Traversal
//! picks a child in proportion to an importance that bounds phi·cosθ'/d², so
//! the selection pmf of any light is recomputable exactly by replaying the
//! same arithmetic down its bit trail ([`LightBvh::pmf`]). A receiver that
//! reflects only (its normal given) also bounds its own cosine towards the
//! node, cos max(0, θ_i − θ_b) (pbrt-v4's `LightBounds::Importance` with a
//! normal): nodes wholly below its horizon get nothing, and lights that meet
//! it at grazing angles less.
//!
//! A walk may also start from a node of a [`Cut`], the tree's top weighed
//! once for a region of receivers (`cut.rs`); [`LightBvh::sample_facing`]
//! and [`LightBvh::pmf_facing`] are the walk from the root.
//!
//! Render space; `p` is the receiving point. The build is serial and uses
//! only deterministic selects, so the same lights give the same tree.

use glam::Vec3;

mod bounds;
mod build;
mod cut;
mod node;
pub(super) use bounds::acos_clamped;
#[cfg(test)]
use bounds::cone_union;
pub use bounds::LightBounds;
use build::{Subtree, PARALLEL_GRAIN};
pub use cut::{Cut, Region};
#[cfg(test)]
use node::{angle_sub_clamped, safe_sqrt};
use node::{Packed, Side, MAX_INDEX};

/// Child importances computed together in a walk's level
/// (`node::at_unculled_many`): two AVX registers of lanes.
const LANES: usize = 16;

/// One node as the build makes it: a leaf holds one light; an inner
/// node's first child follows it.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Node {
    bounds: LightBounds,
    /// Leaf: the light's index; inner: the second child's node index.
    child_or_light: u32,
    leaf: bool,
}

/// A light BVH over lights `0..n` given by their bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct LightBvh {
    /// Depth first, each inner node's first child after it (`node.rs`).
    nodes: Vec<Packed>,
    /// Per light: the branch taken at each depth (bit d = 1: second child).
    trails: Vec<u128>,
    /// Per light: its leaf's node index (`u32::MAX`: left out).
    leaves: Vec<u32>,
}

impl LightBvh {
    /// Builds the tree; lights with zero `phi` are left out (pmf 0).
    /// Subtrees of many lights are built in parallel (on the current rayon
    /// pool) into the very nodes a serial build gives.
    pub fn build(bounds: &[LightBounds]) -> LightBvh {
        Self::build_with_grain(bounds, PARALLEL_GRAIN)
    }

    /// [`LightBvh::build`], forking subtrees of at least `grain` lights.
    fn build_with_grain(bounds: &[LightBounds], grain: usize) -> LightBvh {
        let mut ids: Vec<u32> = (0..bounds.len() as u32)
            .filter(|&i| bounds[i as usize].phi > 0.0)
            .collect();
        let mut sub = Subtree::default();
        if !ids.is_empty() {
            sub.build(bounds, &mut ids, (0, 0), grain);
        }
        let mut trails = vec![0; bounds.len()];
        for (light, trail) in sub.trails {
            trails[light as usize] = trail;
        }
        assert!(
            sub.nodes.len() <= MAX_INDEX,
            "light tree of {} nodes",
            sub.nodes.len()
        );
        let mut leaves = vec![u32::MAX; bounds.len()];
        for (k, n) in sub.nodes.iter().enumerate() {
            if n.leaf {
                leaves[n.child_or_light as usize] = k as u32;
            }
        }
        LightBvh {
            nodes: sub
                .nodes
                .iter()
                .map(|n| Packed::new(&n.bounds, n.child_or_light, n.leaf))
                .collect(),
            trails,
            leaves,
        }
    }

    /// Whether the tree holds no light.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Weights of both children of inner node `k` (whose subtree ends
    /// before node `end`), first child first, with where each box lies
    /// against the receiver's plane; see [`LightBvh::reach`].
    fn child_weights(
        &self,
        k: usize,
        end: usize,
        p: Vec3,
        n: Vec3,
        walk: &mut Walk,
    ) -> [(f32, Side); 2] {
        let (children, reach) = self.children_reach(k, end, p, n, walk);
        [0, 1].map(|i| {
            let (weighed, side) = reach[i];
            let at = if weighed {
                self.nodes[children[i]].at_unculled(p, n)
            } else {
                0.0
            };
            (at, side)
        })
    }

    /// The children of inner node `k` (whose subtree ends before node
    /// `end`) and whether each is weighed ([`LightBvh::reach`]); the next
    /// level's nodes start loading meanwhile.
    fn children_reach(
        &self,
        k: usize,
        end: usize,
        p: Vec3,
        n: Vec3,
        walk: &mut Walk,
    ) -> ([usize; 2], [(bool, Side); 2]) {
        let second = self.nodes[k].index() as usize;
        for child in [k + 1, second] {
            let c = &self.nodes[child];
            if !c.is_leaf() {
                node::prefetch(&self.nodes[child + 1]);
                node::prefetch(&self.nodes[c.index() as usize]);
            }
        }
        (
            [k + 1, second],
            [
                self.reach(k + 1..second, p, n, walk),
                self.reach(second..end, p, n, walk),
            ],
        )
    }

    /// Whether the subtree in `nodes` (its root first) is weighed by its
    /// root's importance, or weighs zero: it is unless one of its lights
    /// reaches the receiver's side of its plane. A node's box is the union
    /// of its children's, so it can cross the plane while both children
    /// lie wholly behind it: weighed by its box alone, a walk ended there
    /// with no light. Weighed so, a kept node always has a kept child. The
    /// answer depends on the node, `p` and `n` only; `walk` only spares
    /// repeating a search. The side is `Front` inside a walk already wholly
    /// in front (every box under it is).
    #[inline]
    fn reach(
        &self,
        nodes: std::ops::Range<usize>,
        p: Vec3,
        n: Vec3,
        walk: &mut Walk,
    ) -> (bool, Side) {
        if walk.in_front {
            return (true, Side::Front);
        }
        let k = nodes.start;
        let side = self.nodes[k].side(p, n);
        let reaches = match side {
            Side::Behind => false,
            Side::Front => true,
            Side::Crossing => {
                walk.witness.iter().any(|w| nodes.contains(w))
                    || self.node_in_front(k, p, n).is_some_and(|w| {
                        walk.witness = [w, walk.witness[0]];
                        true
                    })
            }
        };
        (reaches, side)
    }

    /// A leaf or node under node `k` whose box lies at least partly (a
    /// leaf) or wholly in front of the plane through `p` of normal `n`, if
    /// any: depth first, pruning boxes wholly behind it.
    fn node_in_front(&self, k: usize, p: Vec3, n: Vec3) -> Option<usize> {
        // At most one pending sibling per level of the tree.
        let mut stack = [0u32; 128];
        let mut top = 0;
        let mut k = k;
        loop {
            let node = &self.nodes[k];
            if node.is_leaf() {
                return Some(k);
            }
            stack[top] = node.index();
            top += 1;
            k += 1;
            loop {
                match self.nodes[k].side(p, n) {
                    Side::Front => return Some(k),
                    Side::Crossing => break,
                    Side::Behind if top == 0 => return None,
                    Side::Behind => {
                        top -= 1;
                        k = stack[top] as usize;
                    }
                }
            }
        }
    }

    /// Chooses a light for point `p` with `u` ∈ [0, 1): (light index, pmf),
    /// or None when no light can reach `p`.
    pub fn sample(&self, p: Vec3, u: f32) -> Option<(u32, f32)> {
        self.sample_facing(p, Vec3::ZERO, u)
    }

    /// [`LightBvh::sample`] for a receiver that reflects only, of unit
    /// normal `n` (zero: any receiver; [`LightBounds::importance_facing`]).
    pub fn sample_facing(&self, p: Vec3, n: Vec3, u: f32) -> Option<(u32, f32)> {
        self.sample_facing_many(p, n, [Some(u)])[0]
    }

    /// [`LightBvh::sample_facing`] for each number of `us` (None: no walk):
    /// what each gives alone, bit for bit. The walks step down the tree
    /// level by level together, so their cache misses overlap, and while
    /// they stand on the same node its children are weighed once.
    pub fn sample_facing_many<const M: usize>(
        &self,
        p: Vec3,
        n: Vec3,
        us: [Option<f32>; M],
    ) -> [Option<(u32, f32)>; M] {
        if self.nodes.is_empty() {
            return [None; M];
        }
        let root = Start {
            node: 0,
            end: self.nodes.len() as u32,
            pmf: 1.0,
        };
        self.walk_many(p, n, us.map(|u| u.map(|u| (root, u))))
    }

    /// Walks down from each given node (with the probability of having
    /// come there, and a number in [0, 1)) to a leaf, all together:
    /// [`LightBvh::sample_facing_many`] from the root, a [`Cut`]'s
    /// walks from its nodes.
    fn walk_many<const M: usize>(
        &self,
        p: Vec3,
        n: Vec3,
        starts: [Option<(Start, f32)>; M],
    ) -> [Option<(u32, f32)>; M] {
        let mut out = [None; M];
        let mut walks = starts.map(|s| {
            s.map(|(s, u)| Walker {
                k: s.node as usize,
                pmf: s.pmf,
                end: s.end as usize,
                u,
                walk: Walk::new(n),
            })
        });
        // Per level: the walks that stand on an inner node get its
        // children's weights, the importances of the children weighed at
        // this level computed together (`node::at_unculled_many`).
        let mut weights = [[(0.0f32, Side::Behind); 2]; M];
        let mut active = walks.iter().flatten().count();
        while active > 0 {
            // A lone walk (a later vertex's one candidate, the last of a
            // first vertex's) goes on by itself: a level's bookkeeping
            // for M walks costs more than its two children's weights.
            if active == 1 {
                if let Some(i) = walks.iter().position(Option::is_some) {
                    out[i] = walks[i].take().and_then(|w| self.finish(p, n, w));
                }
                break;
            }
            // Children to weigh, (walk, which child, node) per lane.
            let mut lanes = [(0usize, 0usize, 0usize); LANES];
            let mut used = 0;
            // Per walk, the walk whose weights it takes (itself or one on
            // the same node before it).
            let mut from: [usize; M] = std::array::from_fn(|i| i);
            let mut last: Option<(usize, usize)> = None;
            for (i, (slot, out)) in walks.iter_mut().zip(out.iter_mut()).enumerate() {
                let Some(w) = slot else {
                    continue;
                };
                let node = &self.nodes[w.k];
                if node.is_leaf() {
                    // A lone root was never weighed against a sibling.
                    if w.k > 0 || node.at(p, n) > 0.0 {
                        *out = Some((node.index(), w.pmf));
                    }
                    *slot = None;
                    active -= 1;
                    continue;
                }
                // Walks on one node are adjacent when their numbers are
                // sorted: the first weighs its children for the rest.
                if let Some((k, j)) = last {
                    if k == w.k {
                        from[i] = j;
                        continue;
                    }
                }
                last = Some((w.k, i));
                let (children, reach) = self.children_reach(w.k, w.end, p, n, &mut w.walk);
                for c in 0..2 {
                    weights[i][c] = (0.0, reach[c].1);
                    if reach[c].0 {
                        if used == LANES {
                            self.weigh(&lanes, &mut weights, p, n);
                            used = 0;
                        }
                        lanes[used] = (i, c, children[c]);
                        used += 1;
                    }
                }
            }
            self.weigh(&lanes[..used], &mut weights, p, n);
            for (i, slot) in walks.iter_mut().enumerate() {
                let Some(w) = slot else {
                    continue;
                };
                let second = self.nodes[w.k].index() as usize;
                if !w.step(weights[from[i]], second) {
                    *slot = None;
                    active -= 1;
                }
            }
        }
        out
    }

    /// Walk `w` from its node down to a leaf alone: what
    /// [`LightBvh::sample_facing_many`] gives it, one level at a time.
    fn finish(&self, p: Vec3, n: Vec3, mut w: Walker) -> Option<(u32, f32)> {
        loop {
            let node = &self.nodes[w.k];
            if node.is_leaf() {
                // A lone root was never weighed against a sibling.
                return (w.k > 0 || node.at(p, n) > 0.0).then(|| (node.index(), w.pmf));
            }
            let weights = self.child_weights(w.k, w.end, p, n, &mut w.walk);
            if !w.step(weights, node.index() as usize) {
                return None;
            }
        }
    }

    /// Sets the weight of each child in `lanes` (walk, which child, node)
    /// to the node's importance, [`LANES`] nodes at a time.
    fn weigh(
        &self,
        lanes: &[(usize, usize, usize)],
        weights: &mut [[(f32, Side); 2]],
        p: Vec3,
        n: Vec3,
    ) {
        if lanes.is_empty() {
            return;
        }
        // The fewest lanes that hold them. One walk (a day frame's, a
        // later vertex's) weighs its two children one by one: alone, a
        // node stops at its first zero, and the lanes compute everything.
        match lanes.len() {
            ..=2 => {
                for &(i, c, k) in lanes {
                    weights[i][c].0 = self.nodes[k].at_unculled(p, n);
                }
            }
            3..=8 => self.weigh_lanes::<8>(lanes, weights, p, n),
            _ => self.weigh_lanes::<LANES>(lanes, weights, p, n),
        }
    }

    /// [`LightBvh::weigh`] for at most `L` children.
    fn weigh_lanes<const L: usize>(
        &self,
        lanes: &[(usize, usize, usize)],
        weights: &mut [[(f32, Side); 2]],
        p: Vec3,
        n: Vec3,
    ) {
        // Spare lanes repeat the first node (their values are dropped).
        let nodes = std::array::from_fn(|l| &self.nodes[lanes.get(l).unwrap_or(&lanes[0]).2]);
        let at = node::at_unculled_many::<L>(&nodes, p, n);
        for (&(i, c, _), at) in lanes.iter().zip(at) {
            weights[i][c].0 = at;
        }
    }

    /// The probability that [`LightBvh::sample`] at `p` returns `light`
    /// (bitwise the value it returns with that light).
    pub fn pmf(&self, p: Vec3, light: u32) -> f32 {
        self.pmf_facing(p, Vec3::ZERO, light)
    }

    /// The probability that [`LightBvh::sample_facing`] at `p` for normal
    /// `n` returns `light` (bitwise the value it returns with that light).
    pub fn pmf_facing(&self, p: Vec3, n: Vec3, light: u32) -> f32 {
        if self.nodes.is_empty() {
            return 0.0;
        }
        let root = Start {
            node: 0,
            end: self.nodes.len() as u32,
            pmf: 1.0,
        };
        self.replay(p, n, light, (root, 0))
    }

    /// The probability that a walk from `start` (at depth `depth`) ends at
    /// `light`, whose leaf lies under it: the walk's arithmetic replayed
    /// down the light's trail.
    fn replay(&self, p: Vec3, n: Vec3, light: u32, (start, depth): (Start, u32)) -> f32 {
        let mut trail = self.trails[light as usize] >> depth;
        let mut k = start.node as usize;
        let mut pmf = start.pmf;
        let mut end = start.end as usize;
        let mut walk = Walk::new(n);
        loop {
            let node = &self.nodes[k];
            if node.is_leaf() {
                if node.index() != light {
                    return 0.0; // left out of the tree
                }
                return if k > 0 || node.at(p, n) > 0.0 {
                    pmf
                } else {
                    0.0
                };
            }
            let second = node.index() as usize;
            let w = self.child_weights(k, end, p, n, &mut walk);
            let sum = w[0].0 + w[1].0;
            if sum == 0.0 || !sum.is_finite() {
                return 0.0;
            }
            let taken = (trail & 1) as usize;
            pmf *= w[taken].0 / sum;
            trail >>= 1;
            if taken == 0 {
                end = second;
                k += 1;
            } else {
                k = second;
            }
            walk.descend(w[taken].1);
        }
    }
}

/// Where a walk starts: a node, the end of its subtree, and the
/// probability of having come there.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Start {
    node: u32,
    end: u32,
    pmf: f32,
}

/// One walk of [`LightBvh::sample_facing_many`] under way.
#[derive(Clone, Copy)]
struct Walker {
    /// The node it stands on, and the end of that node's subtree.
    k: usize,
    end: usize,
    /// The probability of the branches taken so far.
    pmf: f32,
    /// Its number, rescaled at each branch to [0, 1).
    u: f32,
    walk: Walk,
}

impl Walker {
    /// Takes a branch of inner node `k` (second child `second`) by the
    /// children's `weights`; false when neither can be taken.
    #[inline]
    fn step(&mut self, weights: [(f32, Side); 2], second: usize) -> bool {
        let [(w0, side0), (w1, side1)] = weights;
        let sum = w0 + w1;
        if sum == 0.0 || !sum.is_finite() {
            return false;
        }
        let p0 = w0 / sum;
        // Reuse u: rescale the chosen sub-interval back to [0, 1).
        if self.u < p0 {
            self.pmf *= p0;
            self.u = (self.u / p0).min(ONE_MINUS_EPS);
            self.walk.descend(side0);
            self.end = second;
            self.k += 1;
        } else {
            let p1 = w1 / sum;
            self.pmf *= p1;
            self.u = ((self.u - p0) / p1).clamp(0.0, ONE_MINUS_EPS);
            self.walk.descend(side1);
            self.k = second;
        }
        true
    }
}

/// What a walk down the tree knows of the receiver's plane (no bearing on
/// the weights, only on the work of finding them).
#[derive(Clone, Copy)]
struct Walk {
    /// Every light of the current node lies in front (or no normal).
    in_front: bool,
    /// The last two nodes found to reach the front, under the current
    /// node or not (`usize::MAX`: none).
    witness: [usize; 2],
}

impl Walk {
    fn new(n: Vec3) -> Walk {
        Walk {
            in_front: n == Vec3::ZERO,
            witness: [usize::MAX; 2],
        }
    }

    /// Steps to a child whose box lies `side` of the receiver's plane (as
    /// `LightBvh::weight` found it).
    #[inline]
    fn descend(&mut self, side: Side) {
        self.in_front = side == Side::Front;
    }
}

const ONE_MINUS_EPS: f32 = 1.0 - f32::EPSILON / 2.0;

#[cfg(test)]
#[path = "bvh_tests.rs"]
mod tests;
