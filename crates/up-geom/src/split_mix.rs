//! SplitMix64 (Steele, Lea, Flood 2014; the seeder of xoshiro): the one
//! random generator of the project. One u64 of state, passes BigCrush, and
//! gives the same numbers on every platform, native and wasm, so a seed fixes
//! a spawn layout, a fit's sample points or a test's inputs everywhere.
//!
//! Its streams feed state hashes (spawn layouts) and fitted sphere trees:
//! any change to the arithmetic below changes results.

/// A SplitMix64 stream.
#[derive(Clone, Debug)]
pub struct SplitMix64 {
    state: u64,
}

impl SplitMix64 {
    pub fn new(seed: u64) -> Self {
        Self { state: seed }
    }

    pub fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.state;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1), from the top 24 bits: every value is an exact f32.
    pub fn unit(&mut self) -> f32 {
        (self.next_u64() >> 40) as f32 * (1.0 / (1u64 << 24) as f32)
    }

    /// Uniform in [0, 1), from the top 53 bits: every value is an exact f64.
    pub fn unit_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.unit()
    }

    /// Uniform in 0..n (n > 0), without modulo bias worth noticing for n ≪ 2⁶⁴.
    pub fn below(&mut self, n: usize) -> usize {
        ((u128::from(self.next_u64()) * n as u128) >> 64) as usize
    }

    /// Fisher–Yates shuffle.
    pub fn shuffle<T>(&mut self, items: &mut [T]) {
        for i in (1..items.len()).rev() {
            let j = self.below(i + 1);
            items.swap(i, j);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sequence_is_the_reference_splitmix64() {
        // First outputs for seed 1234567 from the reference C implementation.
        let mut rng = SplitMix64::new(1234567);
        assert_eq!(rng.next_u64(), 6457827717110365317);
        assert_eq!(rng.next_u64(), 3203168211198807973);
    }

    #[test]
    fn floats_are_the_top_bits_of_the_stream() {
        let mut words = SplitMix64::new(99);
        let mut floats = SplitMix64::new(99);
        for _ in 0..1000 {
            let w = words.next_u64();
            assert_eq!(
                floats.clone().unit().to_bits(),
                ((w >> 40) as f32 / 16_777_216.0).to_bits()
            );
            assert_eq!(
                floats.unit_f64(),
                (w >> 11) as f64 / 9_007_199_254_740_992.0
            );
        }
    }

    #[test]
    fn floats_stay_in_range_and_shuffle_is_a_permutation() {
        let mut rng = SplitMix64::new(7);
        for _ in 0..10_000 {
            let u = rng.unit();
            assert!((0.0..1.0).contains(&u));
            let d = rng.unit_f64();
            assert!((0.0..1.0).contains(&d));
            let r = rng.range(-2.0, 3.0);
            assert!((-2.0..3.0).contains(&r));
            assert!(rng.below(5) < 5);
        }
        let mut v: Vec<u32> = (0..100).collect();
        rng.shuffle(&mut v);
        let mut sorted = v.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..100).collect::<Vec<_>>());
        assert_ne!(v, sorted);
    }
}
