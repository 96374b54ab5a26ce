//! One node of the light tree as the walks read it: the importance of its
//! bounds with what does not depend on the point worked out once (the
//! arithmetic of `LightBounds::importance`, so the same bits), and where
//! its children or its light are, packed in one cache line. A walk is a
//! chain of dependent loads, one level after another; with a node's
//! links in a separate array each level waited for two cache misses (the
//! node, then its second child's importance), and at night the tree's
//! nodes do not fit the caches. The importance of several nodes is
//! computed lane by lane (`at_unculled_many`), the same bits as one alone.

use glam::Vec3;

use super::LightBounds;

/// Set in `Packed::link` for a leaf.
const LEAF: u32 = 1 << 31;
/// Set in `Packed::link` for bounds that emit on both sides of each normal.
const TWO_SIDED: u32 = 1 << 30;
/// The index part of `Packed::link`.
const INDEX: u32 = TWO_SIDED - 1;
/// Most nodes (and lights) a tree holds: indices live below the flags.
pub(super) const MAX_INDEX: usize = INDEX as usize;

/// A node's importance and links (64 bytes, one cache line).
#[derive(Clone, Copy, Debug, PartialEq)]
#[repr(C, align(64))]
pub(super) struct Packed {
    /// Centre of the positions' box.
    pc: Vec3,
    /// Half its extent.
    half: Vec3,
    w: Vec3,
    phi: f32,
    cos_theta_o: f32,
    sin_theta_o: f32,
    cos_theta_e: f32,
    /// Floor on the squared distance (half the box's diagonal).
    d2_min: f32,
    /// Squared radius of the box's bounding sphere.
    r2: f32,
    /// Leaf: the light's index, inner: the second child's node index (the
    /// first follows the node); with the `LEAF` and `TWO_SIDED` flags.
    link: u32,
}

/// A box against a receiver's plane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Side {
    Behind,
    Crossing,
    Front,
}

impl Packed {
    /// The node of bounds `b`: a leaf of light `index`, or an inner node
    /// whose second child is node `index`.
    pub(super) fn new(b: &LightBounds, index: u32, leaf: bool) -> Packed {
        assert!(index <= INDEX, "light tree index {index} past {INDEX}");
        let diag = b.p_max - b.p_min;
        Packed {
            pc: b.centroid(),
            half: 0.5 * diag,
            d2_min: 0.5 * diag.length(),
            r2: (0.25 * diag.length_squared()).max(0.0),
            w: b.w,
            phi: b.phi,
            cos_theta_o: b.cos_theta_o,
            sin_theta_o: safe_sqrt(1.0 - b.cos_theta_o * b.cos_theta_o),
            cos_theta_e: b.cos_theta_e,
            link: index | if leaf { LEAF } else { 0 } | if b.two_sided { TWO_SIDED } else { 0 },
        }
    }

    /// Whether the node is a leaf.
    #[inline]
    pub(super) fn is_leaf(&self) -> bool {
        self.link & LEAF != 0
    }

    /// A leaf's light, an inner node's second child.
    #[inline]
    pub(super) fn index(&self) -> u32 {
        self.link & INDEX
    }

    /// The importance at `p` for a receiver of normal `n` (zero: none).
    #[inline]
    pub(super) fn at(&self, p: Vec3, n: Vec3) -> f32 {
        // Nothing of a box wholly behind the receiver's plane reaches it.
        if n != Vec3::ZERO && self.side(p, n) == Side::Behind {
            return 0.0;
        }
        self.at_unculled(p, n)
    }

    /// Where the box lies against the plane through `p` of normal `n`
    /// (its corners farthest in front and behind).
    #[inline]
    pub(super) fn side(&self, p: Vec3, n: Vec3) -> Side {
        let (s, r) = (n.dot(self.pc - p), n.abs().dot(self.half));
        if s + r <= 0.0 {
            Side::Behind
        } else if s - r > 0.0 {
            Side::Front
        } else {
            Side::Crossing
        }
    }

    /// [`Packed::at`] for a box known not to lie wholly behind the
    /// receiver's plane. One node alone (a lone walk's level, a pmf's
    /// replay) returns as soon as its value is known: most such nodes at
    /// a later vertex are facing away or out of their spread, and their
    /// zero is the one `at_unculled_many` computes for them.
    #[inline]
    pub(super) fn at_unculled(&self, p: Vec3, n: Vec3) -> f32 {
        let v = p - self.pc;
        let d2_centre = v.length_squared();
        // Clamp the distance so points inside a large cluster do not blow up.
        let d2 = d2_centre.max(self.d2_min);
        let wi = v.normalize_or_zero();
        let mut cos_w = self.w.dot(wi);
        if self.link & TWO_SIDED != 0 {
            cos_w = cos_w.abs();
        }
        let sin_w = safe_sqrt(1.0 - cos_w * cos_w);
        // Half-angle θ_b of the cone from the centre that holds the whole
        // box as seen from p (the box's bounding sphere; −1 inside it).
        let inside = d2_centre < self.r2 || d2_centre == 0.0;
        let cos_b = if inside {
            -1.0
        } else {
            safe_sqrt(1.0 - self.r2 / d2_centre)
        };
        let sin_b = safe_sqrt(1.0 - cos_b * cos_b);
        // θ' = max(0, θ_w − θ_o − θ_b): the smallest angle between a normal
        // of the cone and a direction from the box towards p.
        let (cos_x, sin_x) = angle_sub_clamped(sin_w, cos_w, self.sin_theta_o, self.cos_theta_o);
        let (cos_p, _) = angle_sub_clamped(sin_x, cos_x, sin_b, cos_b);
        if cos_p <= self.cos_theta_e {
            return 0.0;
        }
        let importance = (self.phi * cos_p / d2).max(0.0);
        if n == Vec3::ZERO {
            return importance;
        }
        // θ_i' = max(0, θ_i − θ_b): the smallest angle between n and a
        // direction from p into the box (−wi points at its centre); sin θ_b
        // from r/d, as `at_unculled_many` says why.
        let sin_b = if inside {
            sin_b
        } else {
            safe_sqrt(self.r2 / d2_centre)
        };
        let cos_i = -n.dot(wi);
        let sin_i = safe_sqrt(1.0 - cos_i * cos_i);
        let (cos_pi, _) = angle_sub_clamped(sin_i, cos_i, sin_b, cos_b);
        if cos_pi <= 0.0 {
            return 0.0;
        }
        importance * cos_pi
    }
}

impl Packed {
    /// A bound of [`Packed::at_unculled`] (no receiver normal) over every
    /// point of the ball of centre `c` and radius `r`: zero only where no
    /// point of it can be lit. Its angles are those of the node's box grown
    /// by `r` seen from `c` (every direction from the box to a point of
    /// the ball lies within them); its distance is the centre's, floored at
    /// `r`, a weight rather than a bound.
    pub(super) fn at_ball(&self, c: Vec3, r: f32) -> f32 {
        let grown = Packed {
            r2: (self.r2.sqrt() + r) * (self.r2.sqrt() + r),
            d2_min: self.d2_min.max(r * r),
            ..*self
        };
        grown.at_unculled(c, Vec3::ZERO)
    }

    /// Whether the node's box lies behind the plane of every receiver in
    /// the ball (`c`, `r`) whose unit normal is within distance `spread`
    /// of unit `axis` (|n − axis| ≤ spread): then none of its lights
    /// reaches any of them.
    pub(super) fn behind_ball(&self, (c, r): (Vec3, f32), axis: Vec3, spread: f32) -> bool {
        // n·(q − p) ≤ axis·(q − p) + |n − axis|·|q − p| for q in the box,
        // p in the ball.
        let ahead = axis.dot(self.pc - c) + axis.abs().dot(self.half) + r;
        let reach = (self.pc - c).length() + self.r2.sqrt() + r;
        ahead + spread * reach <= 0.0
    }
}

/// [`Packed::at_unculled`] of each of `nodes`, the same bits: the nodes'
/// fields are laid side by side and the arithmetic runs lane by lane
/// without branches, so the compiler computes several nodes per
/// instruction (a walk's square roots and divisions, the most of a night
/// frame's tree walks, then overlap instead of queueing one node after
/// another). Each lane's operations are those of [`Packed::at_unculled`]
/// (which only stops early where its value is known), and vector square
/// roots and divisions round as scalar ones, so a walk and
/// `LightBvh::pmf_facing`'s replay agree bitwise.
#[inline]
pub(super) fn at_unculled_many<const L: usize>(nodes: &[&Packed; L], p: Vec3, n: Vec3) -> [f32; L] {
    let mut lane = [[0.0f32; L]; 12];
    for (i, b) in nodes.iter().enumerate() {
        let fields = [
            b.pc.x,
            b.pc.y,
            b.pc.z,
            b.w.x,
            b.w.y,
            b.w.z,
            b.phi,
            b.cos_theta_o,
            b.sin_theta_o,
            b.cos_theta_e,
            b.d2_min,
            b.r2,
        ];
        for (l, f) in lane.iter_mut().zip(fields) {
            l[i] = f;
        }
    }
    let two_sided: [bool; L] = std::array::from_fn(|i| nodes[i].link & TWO_SIDED != 0);
    let [pcx, pcy, pcz, wx, wy, wz, phi, cos_o, sin_o, cos_e, d2_min, r2] = lane;
    let no_receiver = n == Vec3::ZERO;
    let mut out = [0.0f32; L];
    for i in 0..L {
        let (vx, vy, vz) = (p.x - pcx[i], p.y - pcy[i], p.z - pcz[i]);
        let d2_centre = vx * vx + vy * vy + vz * vz;
        // Clamp the distance so points inside a large cluster do not blow up.
        let d2 = d2_centre.max(d2_min[i]);
        // The unit direction from the centre to p (zero at the centre),
        // as `Vec3::normalize_or_zero` rounds it.
        let rcp = 1.0 / d2_centre.sqrt();
        let unit = rcp.is_finite() && rcp > 0.0;
        let (ux, uy, uz) = if unit {
            (vx * rcp, vy * rcp, vz * rcp)
        } else {
            (0.0, 0.0, 0.0)
        };
        let cos_w = wx[i] * ux + wy[i] * uy + wz[i] * uz;
        let cos_w = if two_sided[i] { cos_w.abs() } else { cos_w };
        let sin_w = safe_sqrt(1.0 - cos_w * cos_w);
        // Half-angle θ_b of the cone from the centre that holds the whole
        // box as seen from p (the box's bounding sphere; −1 inside it).
        let inside = d2_centre < r2[i] || d2_centre == 0.0;
        let s2 = r2[i] / d2_centre;
        let cos_b = if inside { -1.0 } else { safe_sqrt(1.0 - s2) };
        let sin_b = safe_sqrt(1.0 - cos_b * cos_b);
        // θ' = max(0, θ_w − θ_o − θ_b): the smallest angle between a normal
        // of the cone and a direction from the box towards p.
        let (cos_x, sin_x) = angle_sub_clamped(sin_w, cos_w, sin_o[i], cos_o[i]);
        let (cos_p, _) = angle_sub_clamped(sin_x, cos_x, sin_b, cos_b);
        let importance = (phi[i] * cos_p / d2).max(0.0);
        // θ_i' = max(0, θ_i − θ_b): the smallest angle between n and a
        // direction from p into the box (−wi points at its centre).
        // sin θ_b from r/d: through cos θ_b it rounds to 0 for a box a few
        // thousand radii away, and a box that crosses the plane at a
        // grazing angle would weigh 0 (a walk's last kept node with no
        // kept child).
        let sin_b = if inside { sin_b } else { safe_sqrt(s2) };
        let cos_i = -(n.x * ux + n.y * uy + n.z * uz);
        let sin_i = safe_sqrt(1.0 - cos_i * cos_i);
        let (cos_pi, _) = angle_sub_clamped(sin_i, cos_i, sin_b, cos_b);
        out[i] = if cos_p <= cos_e[i] {
            0.0
        } else if no_receiver {
            importance
        } else if cos_pi <= 0.0 {
            0.0
        } else {
            importance * cos_pi
        };
    }
    out
}

/// Asks the CPU to start loading `node` (one cache line); a hint only.
#[inline]
pub(super) fn prefetch(node: &Packed) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_mm_prefetch, _MM_HINT_T0};
        // SAFETY: prefetching is a hint that never faults; the address is
        // the node's.
        unsafe { _mm_prefetch::<_MM_HINT_T0>((node as *const Packed).cast::<i8>()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = node;
}

#[inline(always)]
pub(super) fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

/// cos and sin of max(0, a − b) for angles given by their sines and cosines.
#[inline(always)]
pub(super) fn angle_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> (f32, f32) {
    if cos_a > cos_b {
        (1.0, 0.0)
    } else {
        (cos_a * cos_b + sin_a * sin_b, sin_a * cos_b - cos_a * sin_b)
    }
}
