//! Emissive triangles grouped into emitters: the triangles of one mesh and
//! material that lie close together (a lamp's bulb, a car's head-light, a
//! window) form one light of the set, and a triangle inside it is drawn in
//! proportion to its area projected towards the shading point,
//! max(0, A·n·(p − v₀)) (|·| when both faces emit): for a lamp small
//! against its distance that is nearly its solid angle, so the draw is
//! close to uniform over what the point sees, and faces turned away get
//! nothing. The light tree then has one leaf per emitter instead of per
//! triangle (a night town's 255 k triangles are some 3 k lamps and
//! windows), so its walks are shorter and its nodes stay in cache.
//!
//! The draw's pmf is recomputed exactly ([`Emitters::pmf`]): the same
//! weights summed in the same order. Render space; `n` is the geometric
//! normal (b − a) × (c − a), the emitting face's when one-sided.

use glam::{Vec2, Vec3};

/// Most triangles in one emitter: a draw weighs each of them.
const MAX_TRIANGLES: usize = 256;
/// Largest diagonal of an emitter's box, metres: beyond it the tree tells
/// its parts apart better than a draw by projected area.
const MAX_DIAGONAL_M: f32 = 1.0;

/// Triangles whose weights are computed together, lane by lane.
const LANES: usize = 8;

/// The weights' planes of `LANES` consecutive triangles, side by side.
#[derive(Clone, Copy, Debug, Default)]
struct Planes {
    /// A·n̂ = ½ (b − a) × (c − a) by component, and A·n̂·a: the weight seen
    /// from p is A·n̂·p − A·n̂·a (positive in front).
    x: [f32; LANES],
    y: [f32; LANES],
    z: [f32; LANES],
    d: [f32; LANES],
}

/// The triangles of every emitter, each emitter's contiguous; an emitter
/// of several starts and ends on a multiple of `LANES` (the gaps are
/// triangles of zero weight and area that belong to none).
#[derive(Clone, Debug, Default)]
pub(super) struct Emitters {
    /// Vertices, render space.
    v: Vec<[Vec3; 3]>,
    /// Area, m².
    area: Vec<f32>,
    /// Triangle t's plane is lane t % `LANES` of `planes[t / LANES]`.
    planes: Vec<Planes>,
    /// The set's entry of the emitter each triangle belongs to.
    entry: Vec<u32>,
}

/// One triangle as the grouping reads it.
#[derive(Clone, Copy, Debug)]
pub(super) struct EmissiveTriangle {
    /// Vertices, render space.
    pub v: [Vec3; 3],
    /// Its index in its mesh.
    pub prim: u32,
}

/// A triangle drawn from an emitter.
#[derive(Clone, Copy, Debug)]
pub(super) struct Drawn {
    /// Its vertices and area.
    pub v: [Vec3; 3],
    pub area: f32,
    /// The probability of drawing it among the emitter's triangles.
    pub pmf: f32,
    /// The number that drew it, rescaled to [0, 1) within its share.
    pub u: f32,
}

/// An emitter's weights seen from a point, `LANES` at a time, and their sum.
struct Weights {
    w: [[f32; LANES]; MAX_TRIANGLES / LANES],
    chunks: usize,
    sum: f32,
}

impl Emitters {
    /// Appends one emitter's triangles (at most `MAX_TRIANGLES`) for set
    /// entry `entry`; returns the range of their indices.
    pub(super) fn push(&mut self, tris: &[EmissiveTriangle], entry: u32) -> std::ops::Range<u32> {
        assert!(tris.len() <= MAX_TRIANGLES, "{} triangles", tris.len());
        let several = tris.len() > 1;
        if several {
            self.pad();
        }
        let first = self.v.len() as u32;
        for t in tris {
            let [a, b, c] = t.v;
            let an = 0.5 * (b - a).cross(c - a);
            self.push_one(t.v, an.length(), [an.x, an.y, an.z, an.dot(a)], entry);
        }
        let end = self.v.len() as u32;
        if several {
            self.pad();
        }
        first..end
    }

    /// One triangle: vertices, area, plane and entry.
    fn push_one(&mut self, v: [Vec3; 3], area: f32, plane: [f32; 4], entry: u32) {
        let t = self.v.len();
        if t.is_multiple_of(LANES) {
            self.planes.push(Planes::default());
        }
        let (c, l) = (&mut self.planes[t / LANES], t % LANES);
        [c.x[l], c.y[l], c.z[l], c.d[l]] = plane;
        self.v.push(v);
        self.area.push(area);
        self.entry.push(entry);
    }

    /// Fills up the last lanes with triangles of no weight.
    fn pad(&mut self) {
        while !self.v.len().is_multiple_of(LANES) {
            self.push_one([Vec3::ZERO; 3], 0.0, [0.0; 4], u32::MAX);
        }
    }

    /// The set entry of the emitter holding triangle `t`.
    pub(super) fn entry_of(&self, t: u32) -> u32 {
        self.entry[t as usize]
    }

    /// Area of triangle `t`, m².
    pub(super) fn area(&self, t: u32) -> f32 {
        self.area[t as usize]
    }

    /// The weights of the emitter `tris` (of several triangles) seen from
    /// `p`: lane by lane, summed per lane and the lanes in a fixed tree,
    /// so a draw and a pmf's replay get the same bits.
    #[inline]
    fn weights(&self, tris: std::ops::Range<u32>, two_sided: bool, p: Vec3) -> Weights {
        let planes = &self.planes[tris.start as usize / LANES..(tris.end as usize).div_ceil(LANES)];
        let mut out = Weights {
            w: [[0.0; LANES]; MAX_TRIANGLES / LANES],
            chunks: planes.len(),
            sum: 0.0,
        };
        let mut lanes = [0.0f32; LANES];
        for (c, w) in planes.iter().zip(out.w.iter_mut()) {
            *w = std::array::from_fn(|i| {
                let s = c.x[i] * p.x + c.y[i] * p.y + c.z[i] * p.z - c.d[i];
                if two_sided {
                    s.abs()
                } else {
                    s.max(0.0)
                }
            });
            for (l, w) in lanes.iter_mut().zip(w.iter()) {
                *l += w;
            }
        }
        let [a, b, c, d, e, f, g, h] = lanes;
        out.sum = ((a + b) + (c + d)) + ((e + f) + (g + h));
        out
    }

    /// Draws a triangle of the emitter `tris` seen from `p` with `u` ∈
    /// [0, 1); None when no triangle faces `p`. A lone triangle is drawn
    /// with pmf 1 whatever its facing (its sample then finds it).
    #[inline]
    pub(super) fn draw(
        &self,
        tris: std::ops::Range<u32>,
        two_sided: bool,
        p: Vec3,
        u: f32,
    ) -> Option<Drawn> {
        let first = tris.start as usize;
        let drawn = |t: usize, pmf: f32, u: f32| Drawn {
            v: self.v[t],
            area: self.area[t],
            pmf,
            u,
        };
        if tris.len() == 1 {
            return Some(drawn(first, 1.0, u));
        }
        let ws = self.weights(tris, two_sided, p);
        let sum = ws.sum;
        if sum.is_nan() || sum <= 0.0 || sum.is_infinite() {
            return None;
        }
        // The first triangle whose running sum passes u·sum, whole chunks
        // skipped by their sums; rounding can leave u·sum at or past the
        // running sum's end, which the last weighed triangle takes.
        let target = u * sum;
        let mut acc = 0.0f32;
        let mut last = None;
        for (c, w) in ws.w[..ws.chunks].iter().enumerate() {
            let chunk: f32 = w.iter().sum();
            if chunk <= 0.0 {
                continue;
            }
            if target >= acc + chunk {
                let k = (0..LANES).rev().find(|&k| w[k] > 0.0).expect("a weight");
                let below = acc + w[..k].iter().sum::<f32>();
                last = Some((c * LANES + k, below, w[k]));
                acc += chunk;
                continue;
            }
            for (k, &wk) in w.iter().enumerate() {
                if wk > 0.0 {
                    if target < acc + wk {
                        let t = c * LANES + k;
                        return Some(drawn(first + t, wk / sum, rescale(target - acc, wk)));
                    }
                    last = Some((c * LANES + k, acc, wk));
                }
                acc += wk;
            }
        }
        let (t, below, w) = last?;
        Some(drawn(first + t, w / sum, rescale(target - below, w)))
    }

    /// The probability that [`Emitters::draw`] from `p` gives triangle `t`
    /// of the emitter `tris` (bitwise the pmf it returns with it).
    pub(super) fn pmf(&self, tris: std::ops::Range<u32>, two_sided: bool, p: Vec3, t: u32) -> f32 {
        if tris.len() == 1 {
            return 1.0;
        }
        let k = (t - tris.start) as usize;
        let ws = self.weights(tris, two_sided, p);
        let sum = ws.sum;
        if sum.is_nan() || sum <= 0.0 || sum.is_infinite() {
            return 0.0;
        }
        ws.w[k / LANES][k % LANES] / sum
    }
}

/// `x` ∈ [0, w) as a number in [0, 1).
#[inline]
fn rescale(x: f32, w: f32) -> f32 {
    (x / w).clamp(0.0, 1.0 - f32::EPSILON / 2.0)
}

/// Splits one mesh's triangles of one material into emitters: halves at
/// the middle of the centroids' box along its widest axis (so lamps apart
/// are parted whole) until each holds at most `MAX_TRIANGLES` within a box
/// of diagonal `MAX_DIAGONAL_M`, or its triangles' centroids coincide.
/// Deterministic; each emitter's triangles keep their order in `tris`.
/// Calls `emit` per emitter, in order.
pub(super) fn group(tris: &[EmissiveTriangle], emit: &mut impl FnMut(&[EmissiveTriangle])) {
    let centroid = |t: &EmissiveTriangle| (t.v[0] + t.v[1] + t.v[2]) / 3.0;
    // Parts still to split, the next one last (a stack: a long run of
    // lopsided splits cannot overflow the thread's stack).
    let mut parts = vec![tris.to_vec()];
    while let Some(tris) = parts.pop() {
        if tris.is_empty() {
            continue;
        }
        let (lo, hi) = bounds(tris.iter().flat_map(|t| t.v));
        let (c_lo, c_hi) = bounds(tris.iter().map(centroid));
        let small = tris.len() <= MAX_TRIANGLES && (hi - lo).length() <= MAX_DIAGONAL_M;
        let extent = c_hi - c_lo;
        if small || tris.len() == 1 || extent.max_element().is_nan() || extent.max_element() <= 0.0
        {
            emit(&tris);
            continue;
        }
        let axis = extent.max_position();
        let mid = c_lo[axis] + 0.5 * extent[axis];
        let (mut left, mut right): (Vec<_>, Vec<_>) =
            tris.iter().partition(|t| centroid(t)[axis] < mid);
        if left.is_empty() || right.is_empty() {
            // Centroids too close for the middle to part them: by count.
            let mut sorted = tris.clone();
            sorted.sort_by(|a, b| centroid(a)[axis].total_cmp(&centroid(b)[axis]));
            right = sorted.split_off(sorted.len() / 2);
            left = sorted;
            left.sort_by_key(|t| t.prim);
            right.sort_by_key(|t| t.prim);
        }
        parts.push(right);
        parts.push(left);
    }
}

/// The corners of the box holding `points`.
fn bounds(points: impl Iterator<Item = Vec3>) -> (Vec3, Vec3) {
    points.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// A point uniform on the drawn triangle, with `u.x` replaced by the
/// draw's rescaled number.
#[inline]
pub(super) fn point_on(d: &Drawn, u: Vec2) -> Vec3 {
    let bary = shaders_cpu::sampling::sample_uniform_triangle(Vec2::new(d.u, u.y));
    let [a, b, c] = d.v;
    a * bary[0] + b * bary[1] + c * bary[2]
}

#[cfg(test)]
#[path = "emitter_tests.rs"]
mod tests;
