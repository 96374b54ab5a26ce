//! Deterministic random draws keyed by words: every value is a hash of
//! (seed, purpose tag, indices), so any part of a town or a weather can be
//! drawn on its own and frame K never depends on frames before it.

use super::{hash_words, mix64};

/// A small counter-based stream keyed by words (splitmix64 over `hash_words`).
#[derive(Clone, Debug)]
pub struct Rng {
    key: u64,
    counter: u64,
}

impl Rng {
    /// A stream keyed by `words` (seed first, then a tag and indices).
    pub fn new(words: &[u64]) -> Self {
        Rng {
            key: hash_words(words),
            counter: 0,
        }
    }

    /// The next 64 random bits.
    pub fn next_u64(&mut self) -> u64 {
        self.counter += 1;
        mix64(self.key ^ self.counter.wrapping_mul(0x9e37_79b9_7f4a_7c15))
    }

    /// Uniform in [0, 1).
    pub fn f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [0, 1) at f32's precision (never rounds up to 1).
    pub fn f32(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.f64()
    }

    /// Uniform integer in [lo, hi] (inclusive).
    pub fn int(&mut self, lo: u32, hi: u32) -> u32 {
        lo + (self.next_u64() % (hi - lo + 1) as u64) as u32
    }

    /// A uniformly chosen index below `n` (n ≥ 1).
    pub fn index(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// True with probability `p`.
    pub fn chance(&mut self, p: f64) -> bool {
        self.f64() < p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn same_key_same_stream_and_values_in_range() {
        let mut a = Rng::new(&[7, 1, 2]);
        let mut b = Rng::new(&[7, 1, 2]);
        let mut c = Rng::new(&[7, 1, 3]);
        let va: Vec<u64> = (0..8).map(|_| a.next_u64()).collect();
        let vb: Vec<u64> = (0..8).map(|_| b.next_u64()).collect();
        let vc: Vec<u64> = (0..8).map(|_| c.next_u64()).collect();
        assert_eq!(va, vb);
        assert_ne!(va, vc);
        for _ in 0..1000 {
            let x = a.range(2.0, 3.0);
            assert!((2.0..3.0).contains(&x));
            assert!((4..=6).contains(&a.int(4, 6)));
        }
    }
}
