//! Sine and cosine of an angle given in turns (1 turn = 2π rad), inline and
//! without libm: every warp's azimuth is φ = 2π·u, so the argument reduction
//! is exact in turns. t − round(4t)/4 ∈ [−1/8, 1/8] is computed without
//! rounding (Sterbenz), leaving |x| ≤ π/4 rad for Cephes' `sinf`/`cosf`
//! minimax polynomials (Moshier 1989), then a quarter-turn rotation.
//! Error ≤ 2e-7 absolute, about what libm's f32 `sin_cos` of 2π·u has after
//! rounding 2π·u; the hot warps call this instead of an out-of-line
//! `sincosf`.

/// (sin 2πt, cos 2πt) for any finite `t` (turns); |error| ≤ 2e-7.
#[inline(always)]
pub fn sin_cos_turns(t: f32) -> (f32, f32) {
    let q = (4.0 * t).round();
    // Exact: both terms are multiples of t's ulp and |r| ≤ 1/8.
    let r = t - 0.25 * q;
    let x = r * std::f32::consts::TAU;
    let z = x * x;
    let s = ((-1.951_529_6e-4 * z + 8.332_161e-3) * z - 1.666_665_5e-1) * z * x + x;
    let c = ((2.443_315_7e-5 * z - 1.388_731_6e-3) * z + 4.166_664_6e-2) * z * z - 0.5 * z + 1.0;
    // Rotate by q quarter turns: (s, c) → (c, −s) → (−s, −c) → (−c, s),
    // branch-free (q is as random as the sample): swap on odd q, then flip
    // the sine's sign for q ≡ 2, 3 and the cosine's for q ≡ 1, 2 (mod 4).
    let q = q as i32;
    let swap = ((q & 1) as u32).wrapping_neg();
    let (s, c) = (s.to_bits(), c.to_bits());
    let (a, b) = ((s & !swap) | (c & swap), (c & !swap) | (s & swap));
    (
        f32::from_bits(a ^ (((q & 2) as u32) << 30)),
        f32::from_bits(b ^ ((((q + 1) & 2) as u32) << 30)),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sin_cos_turns_matches_f64_within_2e7() {
        let n = 200_000;
        let mut worst = 0.0f64;
        for k in 0..=n {
            // t over [−1, 2]: negative and multi-turn arguments too.
            let t = -1.0 + 3.0 * k as f32 / n as f32;
            let (s, c) = sin_cos_turns(t);
            let a = std::f64::consts::TAU * t as f64;
            worst = worst.max((s as f64 - a.sin()).abs());
            worst = worst.max((c as f64 - a.cos()).abs());
        }
        assert!(worst < 2e-7, "worst error {worst:e}");
    }

    #[test]
    fn quarter_turns_are_exact() {
        assert_eq!(sin_cos_turns(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_turns(0.25), (1.0, -0.0));
        assert_eq!(sin_cos_turns(0.5), (-0.0, -1.0));
        assert_eq!(sin_cos_turns(0.75), (-1.0, 0.0));
        assert_eq!(sin_cos_turns(-0.25), (-1.0, 0.0));
    }
}
