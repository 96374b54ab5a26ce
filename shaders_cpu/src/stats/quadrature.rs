//! 2D composite and adaptive Simpson quadrature on axis-aligned rectangles,
//! used to turn a pdf into expected cell counts. Adaptive refinement (quad-tree
//! split, stop when the children agree with the parent within `tol`) copes with
//! the jump discontinuities of dielectric pdfs (TIR and back-facing cut-offs),
//! where the fixed rule converges only as O(h).

/// An axis-aligned rectangle [t0, t1] × [p0, p1].
#[derive(Clone, Copy, Debug)]
pub(super) struct Rect {
    /// First-axis bounds.
    pub t: [f64; 2],
    /// Second-axis bounds.
    pub p: [f64; 2],
}

impl Rect {
    /// The four quadrants.
    fn split(&self) -> [Rect; 4] {
        let tm = 0.5 * (self.t[0] + self.t[1]);
        let pm = 0.5 * (self.p[0] + self.p[1]);
        [
            Rect {
                t: [self.t[0], tm],
                p: [self.p[0], pm],
            },
            Rect {
                t: [tm, self.t[1]],
                p: [self.p[0], pm],
            },
            Rect {
                t: [self.t[0], tm],
                p: [pm, self.p[1]],
            },
            Rect {
                t: [tm, self.t[1]],
                p: [pm, self.p[1]],
            },
        ]
    }
}

/// Composite Simpson with `m` (even) intervals per axis.
pub(super) fn simpson_2d(f: &impl Fn(f64, f64) -> f64, r: &Rect, m: usize) -> f64 {
    let m = m.max(2) & !1;
    let ht = (r.t[1] - r.t[0]) / m as f64;
    let hp = (r.p[1] - r.p[0]) / m as f64;
    // Weights 1, 4, 2, …, 4, 1.
    let w = |k: usize| {
        if k == 0 || k == m {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        }
    };
    let mut sum = 0.0;
    for a in 0..=m {
        let t = r.t[0] + a as f64 * ht;
        for b in 0..=m {
            sum += w(a) * w(b) * f(t, r.p[0] + b as f64 * hp);
        }
    }
    sum * ht * hp / 9.0
}

/// Adaptive 2D Simpson: refines quadrants whose sum differs from `whole` (the
/// parent's estimate) by more than `tol`, at most `depth` levels deep.
pub(super) fn adaptive_simpson_2d(
    f: &impl Fn(f64, f64) -> f64,
    r: &Rect,
    whole: f64,
    tol: f64,
    m: usize,
    depth: u32,
) -> f64 {
    let quads = r.split();
    let parts = quads.map(|q| simpson_2d(f, &q, m));
    let sum: f64 = parts.iter().sum();
    if depth == 0 || (sum - whole).abs() <= tol {
        return sum;
    }
    quads
        .iter()
        .zip(parts)
        .map(|(q, part)| adaptive_simpson_2d(f, q, part, tol * 0.5, m, depth - 1))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simpson_is_exact_for_cubics_and_adapts_to_jumps() {
        let r = Rect {
            t: [0.0, 2.0],
            p: [-1.0, 1.0],
        };
        // ∫∫ t³ p² = (16/4)(2/3).
        let v = simpson_2d(&|t, p| t * t * t * p * p, &r, 2);
        assert!((v - 8.0 / 3.0).abs() < 1e-12);
        // Indicator of t + p < 1.3 over the square: area by geometry.
        let step = |t: f64, p: f64| if t + p < 1.3 { 1.0 } else { 0.0 };
        // Area of {t ∈ [0,2], p ∈ [-1,1], t + p < 1.3} = 4 − (1.7²)/2.
        let exact = 4.0 - 1.7 * 1.7 / 2.0;
        let whole = simpson_2d(&step, &r, 4);
        let adaptive = adaptive_simpson_2d(&step, &r, whole, 1e-4, 4, 10);
        assert!((adaptive - exact).abs() < 1e-3, "{adaptive} vs {exact}");
        assert!((adaptive - exact).abs() < (whole - exact).abs());
    }
}
