//! Growing a plant skeleton: a recursive branching model (an L-system
//! without the string: each branch is a bent polyline that spawns child
//! branches along its length with phyllotactic or whorled azimuths), radii
//! by the pipe model (a node's cross-section is the sum of its children's,
//! r² = Σ rᵢ², so the trunk carries every twig), and leaves clustered at
//! the twig ends.

use glam::DVec3;

use super::mesh::{perpendicular, Blade, PlantMesh};
use crate::sampler::rng::Rng;

/// How child lengths vary with where they start along the trunk (t in
/// [0, 1] over the crown): the crown's silhouette.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Crown {
    /// Longest in the middle: a round or oval crown.
    Round,
    /// Longest low down, shortening slowly: a broad spreading crown.
    Spreading,
    /// Longest at the bottom, nothing at the top: a cone.
    Conical,
    /// Nearly even: a narrow column or an upright oval.
    Columnar,
}

impl Crown {
    fn length_factor(self, t: f64) -> f64 {
        match self {
            Crown::Round => 0.45 + 0.55 * (std::f64::consts::PI * (0.15 + 0.7 * t)).sin(),
            Crown::Spreading => 1.0 - 0.45 * t,
            Crown::Conical => 1.05 - 0.95 * t,
            Crown::Columnar => 0.9 - 0.3 * (2.0 * t - 1.0).abs(),
        }
    }
}

/// Branching per level below the trunk (level 1 = limbs off the trunk).
#[derive(Clone, Copy, Debug)]
pub struct Level {
    /// Children this level's parent spawns.
    pub count: u32,
    /// Angle between child and parent direction, degrees.
    pub angle_deg: f64,
    /// Child length as a fraction of the parent's.
    pub ratio: f64,
    /// Polyline segments per branch.
    pub segments: u32,
    /// Upward bend per unit length (negative: droop under its weight).
    pub lift: f64,
    /// Sides of the branch tube.
    pub sides: u32,
}

/// A species' growth form.
#[derive(Clone, Debug)]
pub struct Form {
    /// Trunk length, metres (to the leader's tip).
    pub trunk_m: f64,
    /// Fraction of the trunk below the first limb.
    pub clear_bole: f64,
    /// Trunk radius at the foot, metres (sets the twig radius by the pipe model).
    pub trunk_r: f64,
    /// Trunk polyline segments and tube sides.
    pub trunk_segments: u32,
    /// Sides of the trunk tube.
    pub trunk_sides: u32,
    /// Limbs leave the trunk in whorls of this many (1 = alternate, golden angle).
    pub whorl: u32,
    /// Silhouette.
    pub crown: Crown,
    /// Levels below the trunk; the last one is the twigs.
    pub levels: Vec<Level>,
    /// Random bend of every segment, radians.
    pub wobble: f64,
    /// Leaves per twig.
    pub leaves_per_twig: u32,
    /// Leaf blade.
    pub blade: Blade,
    /// Downward tilt of leaves from their twig, radians.
    pub leaf_droop: f64,
}

/// One node of the skeleton.
#[derive(Clone, Copy, Debug)]
struct Node {
    p: DVec3,
    parent: Option<usize>,
}

/// A grown plant: bark and leaf meshes, and the twig ends the leaves hang from.
#[derive(Clone, Debug)]
pub struct Grown {
    /// Trunk, limbs and twigs.
    pub bark: PlantMesh,
    /// Leaves (two triangles each).
    pub leaves: PlantMesh,
    /// Leaf count.
    pub leaf_count: usize,
    /// Base point of every leaf.
    pub leaf_bases: Vec<DVec3>,
    /// Every twig's tip and length, metres.
    pub twig_tips: Vec<(DVec3, f64)>,
}

struct Growth<'a> {
    form: &'a Form,
    rng: Rng,
    nodes: Vec<Node>,
    /// Node chains of every branch (first = the node it starts from) and its level.
    chains: Vec<(Vec<usize>, usize)>,
    /// Twig chains (indices into `chains`).
    twigs: Vec<usize>,
}

/// A turn of `dir` by `angle` away from itself, towards azimuth `az`
/// about it.
fn turn(dir: DVec3, angle: f64, az: f64) -> DVec3 {
    let u = perpendicular(dir);
    let v = dir.cross(u);
    let side = u * az.cos() + v * az.sin();
    (dir * angle.cos() + side * angle.sin()).normalize()
}

impl Growth<'_> {
    fn node(&mut self, p: DVec3, parent: Option<usize>) -> usize {
        self.nodes.push(Node { p, parent });
        self.nodes.len() - 1
    }

    /// A bent polyline of `segments` from node `from` along `dir`.
    fn chain(&mut self, from: usize, dir: DVec3, len: f64, segments: u32, lift: f64) -> Vec<usize> {
        let step = len / segments as f64;
        let (mut d, mut at, mut ids) = (dir, from, vec![from]);
        for _ in 0..segments {
            let w = self.form.wobble;
            let jitter = DVec3::new(
                self.rng.range(-w, w),
                self.rng.range(-w, w),
                self.rng.range(-w, w),
            );
            d = (d + DVec3::Z * (lift * step) + jitter).normalize();
            let p = self.nodes[at].p + d * step;
            at = self.node(p, Some(at));
            ids.push(at);
        }
        ids
    }

    /// Spawns the children of chain `ids` (level `level` of them), starting
    /// from fraction `t0` of its length.
    fn branch_out(&mut self, ids: &[usize], level: usize, len: f64, t0: f64, trunk: bool) {
        let Some(lv) = self.form.levels.get(level).copied() else {
            return;
        };
        let whorl = if trunk { self.form.whorl.max(1) } else { 1 };
        let groups = lv.count.div_ceil(whorl);
        let golden = 137.5f64.to_radians();
        let mut az = self.rng.range(0.0, std::f64::consts::TAU);
        let segs = ids.len() - 1;
        for g in 0..groups {
            let t = t0 + (1.0 - t0) * (g as f64 + self.rng.range(0.25, 0.75)) / groups as f64;
            let k = ((t * segs as f64).round() as usize).clamp(1, segs);
            let at = ids[k];
            let parent_dir = (self.nodes[at].p - self.nodes[ids[k - 1]].p).normalize();
            let shape = if trunk {
                self.form
                    .crown
                    .length_factor((t - t0) / (1.0 - t0).max(1e-9))
            } else {
                1.0 - 0.4 * t
            };
            for w in 0..whorl.min(lv.count - g * whorl) {
                let a = az + std::f64::consts::TAU * w as f64 / whorl as f64;
                let angle = (lv.angle_deg + self.rng.range(-8.0, 8.0)).to_radians();
                let dir = turn(parent_dir, angle, a);
                let child_len = len * lv.ratio * shape * self.rng.range(0.85, 1.15);
                let child = self.chain(at, dir, child_len, lv.segments, lv.lift);
                self.chains.push((child.clone(), level + 1));
                if level + 1 == self.form.levels.len() {
                    self.twigs.push(self.chains.len() - 1);
                } else {
                    self.branch_out(&child, level + 1, child_len, 0.25, false);
                }
            }
            az += if whorl > 1 {
                std::f64::consts::PI / whorl as f64 + self.rng.range(-0.3, 0.3)
            } else {
                golden
            };
        }
    }
}

/// Grows one plant of `form` from the stream `rng`.
pub fn grow(form: &Form, rng: Rng) -> Grown {
    let mut g = Growth {
        form,
        rng,
        nodes: Vec::new(),
        chains: Vec::new(),
        twigs: Vec::new(),
    };
    let root = g.node(DVec3::ZERO, None);
    let lean = turn(DVec3::Z, g.rng.range(0.0, 0.05), g.rng.range(0.0, 6.3));
    let trunk = g.chain(root, lean, form.trunk_m, form.trunk_segments, 0.02);
    g.chains.push((trunk.clone(), 0));
    g.branch_out(&trunk, 0, form.trunk_m, form.clear_bole, true);
    let radii = pipe_radii(&g.nodes, form.trunk_r);
    let mut bark = PlantMesh::default();
    for (ids, level) in &g.chains {
        let sides = if *level == 0 {
            form.trunk_sides
        } else {
            form.levels[level - 1].sides
        };
        // A child starts at its parent's node with its own radius.
        let mut path: Vec<(DVec3, f64)> = ids.iter().map(|&i| (g.nodes[i].p, radii[i])).collect();
        // The trunk flares at its foot; a branch starts at its parent's
        // node with its own radius.
        path[0].1 = if *level == 0 {
            1.3 * radii[ids[0]]
        } else {
            radii[ids[1]]
        };
        bark.tube(&path, sides);
    }
    let (leaves, leaf_bases, twig_tips) = hang_leaves(&mut g);
    Grown {
        bark,
        leaf_count: leaf_bases.len(),
        leaves,
        leaf_bases,
        twig_tips,
    }
}

/// Pipe-model radii: every tip carries the same cross-section, a node the
/// sum over the tips above it; scaled so the foot has `trunk_r`.
fn pipe_radii(nodes: &[Node], trunk_r: f64) -> Vec<f64> {
    // Parents come before their children, so one reverse pass sums them.
    let mut area = vec![0.0f64; nodes.len()];
    for i in (0..nodes.len()).rev() {
        if area[i] == 0.0 {
            area[i] = 1.0;
        }
        if let Some(p) = nodes[i].parent {
            area[p] += area[i];
        }
    }
    let scale = trunk_r / area[0].sqrt();
    area.iter().map(|a| a.sqrt() * scale).collect()
}

/// Leaves along the outer half of every twig, alternating sides, and a
/// cluster at the tip.
fn hang_leaves(g: &mut Growth) -> (PlantMesh, Vec<DVec3>, Vec<(DVec3, f64)>) {
    let form = g.form;
    let mut mesh = PlantMesh::default();
    let mut bases = Vec::new();
    let mut tips = Vec::new();
    let twigs = std::mem::take(&mut g.twigs);
    for &c in &twigs {
        let ids = g.chains[c].0.clone();
        let pts: Vec<DVec3> = ids.iter().map(|&i| g.nodes[i].p).collect();
        let len: f64 = pts.windows(2).map(|w| (w[1] - w[0]).length()).sum();
        tips.push((*pts.last().expect("twig"), len));
        for k in 0..form.leaves_per_twig {
            let s = 0.4 + 0.6 * (k as f64 + 0.5) / form.leaves_per_twig as f64;
            let x = s * (pts.len() - 1) as f64;
            let i = (x.floor() as usize).min(pts.len() - 2);
            let f = x - i as f64;
            let base = pts[i].lerp(pts[i + 1], f);
            let along = (pts[i + 1] - pts[i]).normalize();
            let side = if k % 2 == 0 { 1.0 } else { -1.0 };
            let az = side * g.rng.range(0.9, 1.6) + g.rng.range(-0.3, 0.3);
            let tip_cluster = k + 3 >= form.leaves_per_twig;
            let spread = if tip_cluster { 0.5 } else { 1.0 };
            let mut axis = turn(along, spread * g.rng.range(0.6, 1.1), az);
            axis = (axis - DVec3::Z * form.leaf_droop * g.rng.range(0.5, 1.5)).normalize();
            // Upper face towards the sky, tilted at random.
            let sky = (DVec3::Z + DVec3::new(g.rng.range(-0.5, 0.5), g.rng.range(-0.5, 0.5), 0.0))
                .normalize();
            let mut up = sky - axis * sky.dot(axis);
            if up.length_squared() < 1e-6 {
                up = perpendicular(axis);
            }
            let scale = g.rng.range(0.75, 1.2);
            let blade = Blade {
                len: form.blade.len * scale,
                width: form.blade.width * scale,
                widest: form.blade.widest,
            };
            let fold = blade.width * g.rng.range(0.05, 0.25);
            mesh.leaf(base, axis, up.normalize(), blade, fold);
            bases.push(base);
        }
    }
    g.twigs = twigs;
    (mesh, bases, tips)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nodes(parents: &[Option<usize>]) -> Vec<Node> {
        parents
            .iter()
            .map(|&parent| Node {
                p: DVec3::ZERO,
                parent,
            })
            .collect()
    }

    #[test]
    fn pipe_model_sums_cross_sections() {
        // 0 → 1 → {2, 3 → 4}: tips 2 and 4, so 0, 1 carry two, 3 one.
        let n = nodes(&[None, Some(0), Some(1), Some(1), Some(3)]);
        let r = pipe_radii(&n, 0.2);
        assert!((r[0] - 0.2).abs() < 1e-15);
        assert!((r[1] - 0.2).abs() < 1e-15);
        let tip = 0.2 / 2f64.sqrt();
        for i in [2, 3, 4] {
            assert!((r[i] - tip).abs() < 1e-15, "node {i}: {}", r[i]);
        }
        // r₀² = r₂² + r₃² (the pipe model's rule).
        assert!((r[0] * r[0] - r[2] * r[2] - r[3] * r[3]).abs() < 1e-15);
    }

    #[test]
    fn crowns_have_their_silhouettes() {
        let f = |c: Crown, t: f64| c.length_factor(t);
        assert!(f(Crown::Conical, 0.0) > 2.0 * f(Crown::Conical, 0.9));
        assert!(f(Crown::Round, 0.5) > f(Crown::Round, 0.0));
        assert!(f(Crown::Round, 0.5) > f(Crown::Round, 1.0));
        assert!(f(Crown::Spreading, 0.0) > f(Crown::Spreading, 1.0));
    }
}
