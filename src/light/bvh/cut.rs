//! A cut of the light tree for a region of receivers (a small ball of
//! points, their normals near one axis or unknown): the few dozen nodes
//! that together hold every light able to reach the region, each weighed
//! by a bound of its importance over the region (the tree refined where
//! that weight is largest, as lightcuts refine a cut). A walk for a point
//! of the region picks a node of the cut by its weight, then goes down
//! from it as a walk from the root does, by the point's own importance:
//! the top of the tree, where most of a walk's levels and cache misses
//! are, is weighed once per region instead of once per walk.
//!
//! The selection stays exact: a light's probability is its cut node's
//! weight times the walk's below it, replayed down its trail
//! ([`LightBvh::pmf_in_cut`]). Nothing that can light a point of the
//! region is left out, because a node leaves the cut only where its
//! bound over the whole region is zero (`Packed::at_ball`,
//! `Packed::behind_ball`).

use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::BinaryHeap;

use glam::Vec3;

use super::{LightBvh, Start, ONE_MINUS_EPS};

/// The receivers a cut is made for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Region {
    /// Centre of the ball holding their points (render space, m).
    pub centre: Vec3,
    /// Its radius, m.
    pub radius: f32,
    /// A unit axis and a bound on |n − axis| of their unit normals, when
    /// they reflect only (the tree's receiver normal); None: any normal,
    /// or none.
    pub facing: Option<(Vec3, f32)>,
}

/// One node of a cut.
#[derive(Clone, Copy, Debug, PartialEq)]
struct CutNode {
    /// The node, with the probability of picking it.
    start: Start,
    /// Its depth in the tree (how many bits of a trail lead to it).
    depth: u32,
    /// The probability of picking it or a node before it.
    cdf: f32,
}

/// A cut of a [`LightBvh`] for a [`Region`]: nodes in tree order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Cut {
    nodes: Vec<CutNode>,
}

/// A node waiting in the refinement's queue, largest weight first (ties
/// by node index, so the cut does not depend on the queue's order).
#[derive(Clone, Copy, Debug)]
struct Queued {
    weight: f32,
    node: CutNode,
}

impl PartialEq for Queued {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}

impl Eq for Queued {}

impl PartialOrd for Queued {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Ord for Queued {
    fn cmp(&self, o: &Self) -> Ordering {
        self.weight
            .total_cmp(&o.weight)
            .then(o.node.start.node.cmp(&self.node.start.node))
    }
}

thread_local! {
    /// The refinement's queue, kept between cuts (its allocation).
    static QUEUE: RefCell<BinaryHeap<Queued>> = RefCell::default();
}

impl Cut {
    /// Whether the cut holds no node (no light reaches the region).
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// Number of nodes in the cut.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// The node `u` ∈ [0, 1) picks, with `u` rescaled to [0, 1) within it.
    fn pick(&self, u: f32) -> (Start, f32) {
        let j = self
            .nodes
            .partition_point(|c| c.cdf <= u)
            .min(self.nodes.len() - 1);
        let below = if j == 0 { 0.0 } else { self.nodes[j - 1].cdf };
        let start = self.nodes[j].start;
        let u = ((u - below) / start.pmf).clamp(0.0, ONE_MINUS_EPS);
        (start, u)
    }

    /// The cut node over leaf node `leaf`, if any.
    fn holding(&self, leaf: u32) -> Option<&CutNode> {
        let j = self.nodes.partition_point(|c| c.start.node <= leaf);
        let c = self.nodes.get(j.checked_sub(1)?)?;
        (leaf < c.start.end).then_some(c)
    }
}

impl LightBvh {
    /// The cut of at most `size` nodes (at least one) for `region`: the
    /// node of largest weight over the region is replaced by its children
    /// until the cut has `size` nodes or only leaves; nodes that weigh
    /// nothing over the region leave it.
    pub fn cut(&self, region: &Region, size: usize) -> Cut {
        let mut cut = Cut::default();
        self.cut_into(region, size, &mut cut);
        cut
    }

    /// [`LightBvh::cut`] into `cut`, whose nodes it replaces (a cache's
    /// slot keeps its allocation).
    pub fn cut_into(&self, region: &Region, size: usize, cut: &mut Cut) {
        QUEUE.with(|queue| self.refine(region, size, cut, &mut queue.borrow_mut()));
    }

    fn refine(&self, region: &Region, size: usize, cut: &mut Cut, queue: &mut BinaryHeap<Queued>) {
        let ball = (region.centre, region.radius);
        let weigh = |k: u32| {
            let node = &self.nodes[k as usize];
            match region.facing {
                Some((axis, spread)) if node.behind_ball(ball, axis, spread) => 0.0,
                _ => node.at_ball(region.centre, region.radius),
            }
        };
        // Leaves go straight to the cut (their weight in `pmf` until the
        // end), inner nodes to the queue.
        let done = &mut cut.nodes;
        done.clear();
        queue.clear();
        let offer = |node: CutNode, queue: &mut BinaryHeap<Queued>, done: &mut Vec<CutNode>| {
            let weight = weigh(node.start.node);
            if !(weight > 0.0 && weight.is_finite()) {
                return;
            }
            if self.nodes[node.start.node as usize].is_leaf() {
                let start = Start {
                    pmf: weight,
                    ..node.start
                };
                done.push(CutNode { start, ..node });
            } else {
                queue.push(Queued { weight, node });
            }
        };
        let at = |node: u32, end: u32, depth: u32| CutNode {
            start: Start {
                node,
                end,
                pmf: 1.0,
            },
            depth,
            cdf: 0.0,
        };
        if !self.nodes.is_empty() {
            offer(at(0, self.nodes.len() as u32, 0), queue, done);
        }
        while queue.len() + done.len() < size.max(1) {
            let Some(q) = queue.pop() else {
                break;
            };
            let (k, end, depth) = (q.node.start.node, q.node.start.end, q.node.depth);
            let second = self.nodes[k as usize].index();
            offer(at(k + 1, second, depth + 1), queue, done);
            offer(at(second, end, depth + 1), queue, done);
        }
        done.extend(queue.drain().map(|q| CutNode {
            start: Start {
                pmf: q.weight,
                ..q.node.start
            },
            ..q.node
        }));
        done.sort_unstable_by_key(|c| c.start.node);
        let total: f64 = done.iter().map(|c| c.start.pmf as f64).sum();
        let mut acc = 0.0f64;
        for c in done.iter_mut() {
            acc += c.start.pmf as f64;
            c.start.pmf = (c.start.pmf as f64 / total) as f32;
            c.cdf = (acc / total) as f32;
        }
    }

    /// [`LightBvh::sample_facing_many`] for a point `p` (normal `n`) of the
    /// region `cut` was made for: each walk from the cut node its number
    /// picks.
    pub fn sample_in_cut<const M: usize>(
        &self,
        cut: &Cut,
        (p, n): (Vec3, Vec3),
        us: [Option<f32>; M],
    ) -> [Option<(u32, f32)>; M] {
        if cut.is_empty() {
            return [None; M];
        }
        self.walk_many(p, n, us.map(|u| u.map(|u| cut.pick(u))))
    }

    /// The probability that [`LightBvh::sample_in_cut`] at `p` (normal `n`)
    /// returns `light` (bitwise the value it returns with it).
    pub fn pmf_in_cut(&self, cut: &Cut, (p, n): (Vec3, Vec3), light: u32) -> f32 {
        let leaf = self.leaves[light as usize];
        match cut.holding(leaf) {
            Some(c) if leaf != u32::MAX => self.replay(p, n, light, (c.start, c.depth)),
            _ => 0.0,
        }
    }
}
