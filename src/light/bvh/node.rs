//! One node of the light tree as the walks read it: the importance of its
//! bounds with what does not depend on the point worked out once (the
//! arithmetic of `LightBounds::importance`, so the same bits), and where
//! its children or its light are, packed in one cache line. A walk is a
//! chain of dependent loads, one level after another; with a node's
//! links in a separate array each level waited for two cache misses (the
//! node, then its second child's importance), and at night the tree's
//! nodes do not fit the caches.

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
    /// receiver's plane.
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
        let cos_b = if d2_centre < self.r2 || d2_centre == 0.0 {
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
        // direction from p into the box (−wi points at its centre).
        // sin θ_b from r/d: through cos θ_b it rounds to 0 for a box a few
        // thousand radii away, and a box that crosses the plane at a
        // grazing angle would weigh 0 (a walk's last kept node with no
        // kept child).
        let sin_b = if cos_b == -1.0 {
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

pub(super) fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}

/// cos and sin of max(0, a − b) for angles given by their sines and cosines.
pub(super) fn angle_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> (f32, f32) {
    if cos_a > cos_b {
        (1.0, 0.0)
    } else {
        (cos_a * cos_b + sin_a * sin_b, sin_a * cos_b - cos_a * sin_b)
    }
}
