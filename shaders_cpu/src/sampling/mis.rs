//! Multiple importance sampling weights (Veach 1997 ch. 9; pbrt-v4 §2.2.3).
//!
//! `nf`/`ng` are the sample counts of the two strategies, `f_pdf`/`g_pdf` their
//! pdfs (same measure) at the sample being weighted, drawn from strategy f.

/// Power heuristic (β = 2) weight of a sample drawn from strategy f.
///
/// Returns a value in [0, 1]; infinite `f_pdf` (a delta) gives 1.
#[inline]
pub fn power_heuristic(nf: f32, f_pdf: f32, ng: f32, g_pdf: f32) -> f32 {
    let f = nf * f_pdf;
    let g = ng * g_pdf;
    if f.is_infinite() {
        return 1.0;
    }
    let denom = f * f + g * g;
    if denom <= 0.0 {
        return 0.0;
    }
    f * f / denom
}

/// Balance heuristic weight of a sample drawn from strategy f, in [0, 1].
pub fn balance_heuristic(nf: f32, f_pdf: f32, ng: f32, g_pdf: f32) -> f32 {
    let f = nf * f_pdf;
    let g = ng * g_pdf;
    if f.is_infinite() {
        return 1.0;
    }
    if f + g <= 0.0 {
        return 0.0;
    }
    f / (f + g)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_heuristic_weights_sum_to_one() {
        for (a, b) in [(0.3f32, 2.0f32), (1.0, 1.0), (5.0, 0.01)] {
            let w = power_heuristic(1.0, a, 1.0, b) + power_heuristic(1.0, b, 1.0, a);
            assert!((w - 1.0).abs() < 1e-6);
            let w = balance_heuristic(1.0, a, 1.0, b) + balance_heuristic(1.0, b, 1.0, a);
            assert!((w - 1.0).abs() < 1e-6);
        }
        assert_eq!(power_heuristic(1.0, 2.0, 1.0, 2.0), 0.5);
        assert_eq!(power_heuristic(1.0, 0.0, 1.0, 0.0), 0.0);
        assert_eq!(power_heuristic(1.0, f32::INFINITY, 1.0, 3.0), 1.0);
    }
}
