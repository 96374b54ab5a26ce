//! Deterministic low-discrepancy sample streams keyed by
//! (seed, frame, view, pixel, sample index, dimension), as pbrt-v4's
//! `StartPixelSample` does: a pixel's samples never depend on which thread or
//! tile rendered it, and every view gets an independent stream so noise is not
//! correlated between left and right images.
//!
//! Each request draws a 4D point of Owen-scrambled Sobol (Burley 2020, via
//! `sobol_burley`) with its own scramble seed per request: the "padded"
//! construction of pbrt-v4's `PaddedSobolSampler`, in 4D sets. Sample indices
//! must stay below 2^16 (the sequence length of `sobol_burley`).
//!
//! `sobol_4d` computes exactly `sobol_burley::sample_4d(index, 0, seed)` but
//! replaces the library's bit loop over the shuffled index (about eight
//! data-dependent branches per draw) by two 256-entry tables: Sobol points are
//! XORs of one direction vector per set index bit, so the 16-bit index splits
//! into its two bytes.

use std::sync::LazyLock;

use glam::Vec2;
use sobol_burley::parts::{
    hash, hash_int4, owen_scramble_int4_rev, owen_scramble_rev, sobol_rev, Int4,
};

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

    fn scramble_seed(&self) -> u32 {
        mix64(self.pixel_key ^ (self.dimension as u64).wrapping_mul(0x2545_f491_4f6c_dd1d)) as u32
    }

    /// The next four jointly stratified samples in [0, 1)⁴ (one SIMD evaluation).
    pub fn next_4d(&mut self) -> [f32; 4] {
        let seed = self.scramble_seed();
        self.dimension += 1;
        sobol_4d(self.sample_index, seed)
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

/// `sobol_burley::sample_4d(sample_index, 0, seed)`, bit for bit, by table.
pub fn sobol_4d(sample_index: u32, seed: u32) -> [f32; 4] {
    debug_assert!(sample_index < MAX_SPP);
    let rev = owen_scramble_rev(sample_index.reverse_bits(), hash(seed ^ 0x79c6_8e4a));
    let t = &SOBOL_TABLES.0;
    let sobol =
        Int4::from(t[0][(rev >> 24) as usize]) ^ Int4::from(t[1][((rev >> 16) & 0xff) as usize]);
    // The library's scramble for dimension set 0.
    let seed4: Int4 = [seed.wrapping_mul(0x9c8f_2d3b); 4].into();
    let scramble = seed4 ^ [0x912f_69ba, 0x174f_18ab, 0x691e_72ca, 0xb40c_c1b8].into();
    owen_scramble_int4_rev(sobol, hash_int4(scramble))
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

    #[test]
    fn table_sobol_equals_the_library_bit_for_bit() {
        let mut seed = 0x1234_5678u32;
        for index in (0..MAX_SPP).step_by(7).chain([0, 1, MAX_SPP - 1]) {
            seed = sobol_burley::parts::hash(seed ^ index);
            let ours = sobol_4d(index, seed).map(f32::to_bits);
            let lib = sobol_burley::sample_4d(index, 0, seed).map(f32::to_bits);
            assert_eq!(ours, lib, "index {index} seed {seed:#x}");
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
