//! The edge-avoiding à-trous kernel both denoiser components share
//! (Dammertz et al. 2010): dilated B3 passes, rows then columns, each tap
//! weighted by a caller's range weight on guide keys.

use std::ops::{Add, Div, Mul};

use rayon::prelude::*;

/// The B3-spline taps of one à-trous level at offsets −2..=2 (Dammertz et al.
/// 2010, "Edge-avoiding À-Trous wavelet transform"); its variance is one
/// pixel², so L levels (dilations 1, 2, …, 2^(L−1)) make a kernel of
/// σ² = (4^L − 1)/3.
const B3: [f32; 5] = [1.0 / 16.0, 0.25, 0.375, 0.25, 1.0 / 16.0];

/// The à-trous level count whose kernel's σ is nearest `sigma_px` by
/// ratio, in 1..=10.
pub(super) fn atrous_levels(sigma_px: f32) -> u32 {
    let ln_err = |l: u32| {
        let sigma_l = ((4f32.powi(l as i32) - 1.0) / 3.0).sqrt();
        (sigma_l / sigma_px.max(1e-3)).ln().abs()
    };
    (1..=10)
        .min_by(|&a, &b| ln_err(a).total_cmp(&ln_err(b)))
        .unwrap_or(1)
}

/// Which neighbours a pass visits.
#[derive(Clone, Copy, Debug)]
pub(super) enum Axis {
    Row,
    Column,
}

/// One edge-avoiding à-trous pass along `axis` with dilation `step`: each
/// pixel of `out` is the normalised sum of B3 tap × range weight × `data`
/// over its five neighbours (those inside the image).
pub(super) fn atrous_pass<T, K>(
    data: &[T],
    out: &mut [T],
    keys: &[K],
    (w, h): (usize, usize),
    step: usize,
    weight: &(impl Fn(K, K) -> f32 + Sync),
    axis: Axis,
) where
    T: Copy + Send + Sync + Default + Add<Output = T> + Mul<f32, Output = T> + Div<f32, Output = T>,
    K: Copy + Sync,
{
    out.par_chunks_mut(w).enumerate().for_each(|(j, row)| {
        for (i, o) in row.iter_mut().enumerate() {
            let c = j * w + i;
            let kc = keys[c];
            let (pos, len, stride) = match axis {
                Axis::Row => (i as isize, w as isize, 1isize),
                Axis::Column => (j as isize, h as isize, w as isize),
            };
            let mut s = T::default();
            let mut wsum = 0.0;
            for (t, &b3) in B3.iter().enumerate() {
                let d = (t as isize - 2) * step as isize;
                let q = pos + d;
                if q < 0 || q >= len {
                    continue;
                }
                let k = (c as isize + d * stride) as usize;
                let wt = b3 * weight(kc, keys[k]);
                s = s + data[k] * wt;
                wsum += wt;
            }
            // The centre tap always counts, so wsum ≥ 3/8.
            *o = s / wsum;
        }
    });
}

/// ln depth_z, so that a difference is the relative depth step; +inf for
/// sky (and any depth that is not a positive finite number).
pub(super) fn ln_depth(z: f32) -> f32 {
    if z.is_finite() && z > 0.0 {
        z.ln()
    } else {
        f32::INFINITY
    }
}

/// A rational stand-in for exp(−e/2) (equal to second order, a heavier
/// tail cut at 3σ): no transcendental call per tap.
#[inline]
pub(super) fn soft_gaussian(e: f32) -> f32 {
    if e > 9.0 {
        0.0
    } else {
        1.0 / (1.0 + e * (0.5 + e * 0.125))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atrous_levels_reach_the_asked_sigma() {
        // σ² = (4^L − 1)/3: 1, √5, √21, √85 for L = 1..4.
        assert_eq!(atrous_levels(0.5), 1);
        assert_eq!(atrous_levels(1.0), 1);
        assert_eq!(atrous_levels(2.0), 2);
        assert_eq!(atrous_levels(4.0), 3);
        assert_eq!(atrous_levels(9.0), 4);
        assert_eq!(atrous_levels(20.0), 5);
    }
}
