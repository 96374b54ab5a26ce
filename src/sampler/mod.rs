//! Deterministic randomness, the bottom layer: low-discrepancy pixel sample
//! streams (this file), the word hashes every other stream is keyed by
//! (`hash_words`, `mix64`) and a keyed scalar stream (`rng::Rng`, used by the
//! town generator and the weather draw).
//!
//! Pixel streams are keyed by (seed, frame, view, pixel, sample index,
//! dimension), as pbrt-v4's `StartPixelSample` does: a pixel's samples never
//! depend on which thread or tile rendered it, and every view gets an
//! independent stream so noise is not correlated between left and right
//! images.
//!
//! Each request draws a 4D point of Owen-scrambled Sobol (Burley 2020, via
//! `sobol_burley`) with its own scramble seed per request: the "padded"
//! construction of pbrt-v4's `PaddedSobolSampler`, in 4D sets. Sample indices
//! must stay below 2^16 (the sequence length of `sobol_burley`).
//!
//! `sobol_4d` is `sobol_burley::sample_4d`'s construction (Laine-Karras style
//! Owen scramble of the reversed index, Sobol dimensions 0..4, an independent
//! Owen scramble per dimension) with cheaper seeding: one splitmix64 output
//! per draw supplies both the index shuffle (low half) and the base of the
//! four per-dimension scrambles (high half, hashed per lane in SIMD), where
//! the library re-hashes a 32-bit seed serially first. The bit loop over the
//! shuffled index (about eight data-dependent branches) is replaced by two
//! 256-entry tables: Sobol points are XORs of one direction vector per set
//! index bit, so the 16-bit index splits into its two bytes.

pub mod rng;

use std::sync::LazyLock;

use glam::Vec2;
use sobol_burley::parts::{hash_int4, owen_scramble_int4_rev, owen_scramble_rev, sobol_rev, Int4};

/// Which stream a pixel sample belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct StreamKey {
    /// The user-visible seed of the whole configuration.
    pub seed: u64,
    /// Frame index within the sequence.
    pub frame: u32,
    /// View index: 0 = left, 1 + b = right camera of baseline b.
    pub view: u32,
}

/// Largest supported number of samples per pixel.
pub const MAX_SPP: u32 = 1 << 16;

/// A path's sample stream: sample index fixed, dimension advancing per request.
#[derive(Clone, Debug)]
pub struct SampleStream {
    pixel_key: u64,
    sample_index: u32,
    dimension: u32,
}

/// A 64-bit finaliser (splitmix64): decorrelates nearby keys.
pub fn mix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Hashes several words into one 64-bit key.
pub fn hash_words(words: &[u64]) -> u64 {
    hash_fold(HASH_INIT, words)
}

/// Initial state of [`hash_words`].
const HASH_INIT: u64 = 0x51_7cc1_b727_220a;

/// [`hash_words`] continued from state `h`.
fn hash_fold(h: u64, words: &[u64]) -> u64 {
    words.iter().fold(h, |h, &w| mix64(h ^ mix64(w)))
}

thread_local! {
    /// The last view key this thread opened streams for, with its hash state.
    static VIEW_STATE: std::cell::Cell<Option<(StreamKey, u64)>> = const { std::cell::Cell::new(None) };
}

impl SampleStream {
    /// The stream of `sample_index` for pixel `(i, j)` of the keyed view.
    pub fn new(key: StreamKey, i: u32, j: u32, sample_index: u32) -> Self {
        // = hash_words(&[seed, frame, view, (j << 32) | i]): the fold's state
        // after the view's three words is kept per thread, since a thread
        // asks for thousands of pixels of one view in a row.
        let view_state = VIEW_STATE.with(|cell| match cell.get() {
            Some((k, state)) if k == key => state,
            _ => {
                let state = hash_fold(HASH_INIT, &[key.seed, key.frame as u64, key.view as u64]);
                cell.set(Some((key, state)));
                state
            }
        });
        let pixel_key = hash_fold(view_state, &[((j as u64) << 32) | i as u64]);
        SampleStream {
            pixel_key,
            sample_index,
            dimension: 0,
        }
    }

    /// 64 random bits for the current draw (see [`sobol_4d`]).
    #[inline]
    fn scramble(&self) -> u64 {
        mix64(self.pixel_key ^ (self.dimension as u64).wrapping_mul(0x2545_f491_4f6c_dd1d))
    }

    /// The next four jointly stratified samples in [0, 1)⁴ (one SIMD evaluation).
    #[inline]
    pub fn next_4d(&mut self) -> [f32; 4] {
        let scramble = self.scramble();
        self.dimension += 1;
        sobol_4d(self.sample_index, scramble)
    }

    /// The next 1D sample in [0, 1).
    pub fn next_1d(&mut self) -> f32 {
        self.next_4d()[0]
    }

    /// The next 2D sample in [0, 1)².
    pub fn next_2d(&mut self) -> Vec2 {
        let u = self.next_4d();
        Vec2::new(u[0], u[1])
    }

    /// Jumps to a fixed dimension (e.g. the start of a bounce), so that the
    /// number of draws in one bounce cannot shift the next bounce's samples.
    pub fn set_dimension(&mut self, dimension: u32) {
        self.dimension = dimension;
    }
}

/// Reversed-bit Sobol points of dimensions 0..4 for the high (`[0]`) and low
/// (`[1]`) byte of a reversed 16-bit sample index.
#[repr(align(16))]
struct SobolTables([[[u32; 4]; 256]; 2]);

static SOBOL_TABLES: LazyLock<SobolTables> = LazyLock::new(|| {
    let mut t = SobolTables([[[0; 4]; 256]; 2]);
    for b in 0..256u32 {
        for d in 0..4u32 {
            t.0[0][b as usize][d as usize] = sobol_rev(b << 24, d);
            t.0[1][b as usize][d as usize] = sobol_rev(b << 16, d);
        }
    }
    t
});

/// Keys XORed into the high half of a draw's scramble to seed each
/// dimension's Owen scramble (sobol_burley's dimension-set-0 constants).
const LANE_KEYS: [u32; 4] = [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8];

/// Point `sample_index` (< 2^16) of 4D Owen-scrambled Sobol, scrambled by the
/// 64 random bits `scramble`: its low half shuffles the index (nested
/// uniform scramble of the reversed index), its high half, hashed with one
/// key per dimension, seeds the four dimensions' Owen scrambles.
#[inline]
pub fn sobol_4d(sample_index: u32, scramble: u64) -> [f32; 4] {
    debug_assert!(sample_index < MAX_SPP);
    let rev = owen_scramble_rev(sample_index.reverse_bits(), scramble as u32);
    let t = &SOBOL_TABLES.0;
    let sobol =
        Int4::from(t[0][(rev >> 24) as usize]) ^ Int4::from(t[1][((rev >> 16) & 0xff) as usize]);
    // Off the index chain's critical path: runs while the tables load.
    let lanes = hash_int4(Int4::from([(scramble >> 32) as u32; 4]) ^ LANE_KEYS.into());
    owen_scramble_int4_rev(sobol, lanes)
        .reverse_bits()
        .to_f32_norm()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(view: u32) -> StreamKey {
        StreamKey {
            seed: 7,
            frame: 3,
            view,
        }
    }

    #[test]
    fn streams_are_reproducible_and_distinct_per_view_and_pixel() {
        let a: Vec<f32> = (0..8)
            .map(|s| SampleStream::new(key(0), 5, 9, s).next_1d())
            .collect();
        let b: Vec<f32> = (0..8)
            .map(|s| SampleStream::new(key(0), 5, 9, s).next_1d())
            .collect();
        let c: Vec<f32> = (0..8)
            .map(|s| SampleStream::new(key(1), 5, 9, s).next_1d())
            .collect();
        let d: Vec<f32> = (0..8)
            .map(|s| SampleStream::new(key(0), 6, 9, s).next_1d())
            .collect();
        assert_eq!(a, b);
        assert_ne!(a, c);
        assert_ne!(a, d);
    }

    #[test]
    fn pixel_key_equals_hash_of_all_four_words_across_views() {
        // Alternating views must not reuse the other view's cached state.
        for view in [0, 1, 0, 2, 2, 0] {
            let k = key(view);
            let st = SampleStream::new(k, 17, 4, 0);
            let expect = hash_words(&[7, 3, view as u64, (4u64 << 32) | 17]);
            assert_eq!(st.pixel_key, expect);
        }
    }

    /// [`sobol_4d`] written plainly: the library's per-bit Sobol loop and
    /// scalar hashes, one dimension at a time.
    fn sobol_4d_reference(sample_index: u32, scramble: u64) -> [f32; 4] {
        use sobol_burley::parts::{hash, u32_to_f32_norm};
        let rev = owen_scramble_rev(sample_index.reverse_bits(), scramble as u32);
        std::array::from_fn(|d| {
            let seed = hash((scramble >> 32) as u32 ^ LANE_KEYS[d]);
            u32_to_f32_norm(owen_scramble_rev(sobol_rev(rev, d as u32), seed).reverse_bits())
        })
    }

    #[test]
    fn table_sobol_equals_the_per_bit_reference() {
        let mut scramble = 0x1234_5678_9abc_def0u64;
        for index in (0..MAX_SPP).step_by(7).chain([0, 1, MAX_SPP - 1]) {
            scramble = mix64(scramble ^ index as u64);
            let ours = sobol_4d(index, scramble).map(f32::to_bits);
            let reference = sobol_4d_reference(index, scramble).map(f32::to_bits);
            assert_eq!(ours, reference, "index {index} scramble {scramble:#x}");
        }
    }

    /// The first 64 samples of one draw of pixel (i, j).
    fn draws(i: u32, j: u32, dimension: u32) -> Vec<[f32; 4]> {
        (0..64)
            .map(|s| {
                let mut st = SampleStream::new(key(0), i, j, s);
                st.set_dimension(dimension);
                st.next_4d()
            })
            .collect()
    }

    #[test]
    fn first_pair_is_a_02_net_and_every_dimension_is_stratified() {
        for (i, j, dim) in [(0, 0, 0), (3, 7, 1), (640, 2, 9), (5, 5, 33)] {
            let u = draws(i, j, dim);
            // Every elementary interval of area 1/64 of dims (0, 1), for each
            // of the 7 shapes 2^a × 2^(6−a), holds exactly one point.
            for a in 0..=6 {
                let (nx, ny) = (1usize << a, 1usize << (6 - a));
                let mut seen = [false; 64];
                for p in &u {
                    let cell = (p[0] * nx as f32) as usize + nx * (p[1] * ny as f32) as usize;
                    assert!(!seen[cell], "shape {nx}x{ny}: two points in one interval");
                    seen[cell] = true;
                }
            }
            // Each dimension alone: one point per 1/64 interval.
            for d in 0..4 {
                let mut seen = [false; 64];
                for p in &u {
                    let cell = (p[d] * 64.0) as usize;
                    assert!(!seen[cell], "dimension {d}: two points in one interval");
                    seen[cell] = true;
                }
            }
        }
    }

    fn correlation(a: &[f32], b: &[f32]) -> f64 {
        let n = a.len() as f64;
        let (ma, mb) = (
            a.iter().map(|&x| x as f64).sum::<f64>() / n,
            b.iter().map(|&x| x as f64).sum::<f64>() / n,
        );
        let cov: f64 = a
            .iter()
            .zip(b)
            .map(|(&x, &y)| (x as f64 - ma) * (y as f64 - mb))
            .sum();
        let va: f64 = a.iter().map(|&x| (x as f64 - ma).powi(2)).sum();
        let vb: f64 = b.iter().map(|&y| (y as f64 - mb).powi(2)).sum();
        cov / (va * vb).sqrt()
    }

    #[test]
    fn draws_are_uncorrelated_across_dimensions_pixels_and_views() {
        // 64 pixels × 64 samples: independent uniforms would give |ρ| ≈ 0.016.
        let lane = |view: u32, di: u32, dim: u32, d: usize| -> Vec<f32> {
            (0..64u32)
                .flat_map(|px| {
                    (0..64u32).map(move |s| {
                        let mut st = SampleStream::new(key(view), px + di, 11, s);
                        st.set_dimension(dim);
                        st.next_4d()[d]
                    })
                })
                .collect()
        };
        let base = lane(0, 0, 5, 0);
        let others = [
            ("next draw, same lane", lane(0, 0, 6, 0)),
            ("next draw, other lane", lane(0, 0, 6, 1)),
            ("same draw, other lane", lane(0, 0, 5, 2)),
            ("next pixel", lane(0, 1, 5, 0)),
            ("other view", lane(1, 0, 5, 0)),
        ];
        for (what, other) in &others {
            let rho = correlation(&base, other);
            assert!(rho.abs() < 0.06, "{what}: correlation {rho:.4}");
        }
    }

    #[test]
    fn every_dimension_has_a_uniform_mean() {
        // 64 stratified samples per pixel: each pixel's mean is within 1/64 of
        // ½; over 256 pixels the mean is much closer.
        for dim in [0, 1, 7] {
            let mut total = [0.0f64; 4];
            for px in 0..256 {
                let u = draws(px, 3, dim);
                for d in 0..4 {
                    let mean = u.iter().map(|p| p[d] as f64).sum::<f64>() / 64.0;
                    assert!(
                        (mean - 0.5).abs() < 1.0 / 64.0,
                        "pixel {px} dim {d}: {mean}"
                    );
                    total[d] += mean / 256.0;
                }
            }
            for m in total {
                assert!((m - 0.5).abs() < 2e-3, "dimension set {dim}: mean {m}");
            }
        }
    }

    #[test]
    fn pixel_stream_is_stratified() {
        // 64 samples of a 2D dimension: one per 8×8 stratum (a (0,2)-net property
        // of Sobol in base 2 that Owen scrambling preserves).
        let mut seen = [false; 64];
        for s in 0..64 {
            let mut st = SampleStream::new(key(2), 100, 50, s);
            st.set_dimension(4);
            let u = st.next_2d();
            let cell = (u.x * 8.0) as usize + 8 * (u.y * 8.0) as usize;
            assert!(!seen[cell], "two samples in one stratum");
            seen[cell] = true;
        }
    }
}
