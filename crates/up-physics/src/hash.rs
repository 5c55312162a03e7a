//! FNV-1a, 64-bit: the state hash and the warm-start lookup key hash.
//! Chosen because it is tiny, fixed and identical on every platform.

pub(crate) const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

/// Streaming FNV-1a over 32-bit words.
#[derive(Clone, Copy)]
pub(crate) struct Fnv1a(pub u64);

impl Fnv1a {
    pub fn new() -> Self {
        Self(FNV_OFFSET)
    }

    #[inline]
    pub fn write_u32(&mut self, x: u32) {
        for byte in x.to_le_bytes() {
            self.0 ^= byte as u64;
            self.0 = self.0.wrapping_mul(FNV_PRIME);
        }
    }

    #[inline]
    pub fn write_f32(&mut self, x: f32) {
        self.write_u32(x.to_bits());
    }

    pub fn write_bytes(&mut self, bytes: &[u8]) {
        for &byte in bytes {
            self.0 ^= byte as u64;
            self.0 = self.0.wrapping_mul(FNV_PRIME);
        }
    }

    pub fn finish(self) -> u64 {
        self.0
    }
}

/// FNV-1a of a few floats, as the state hash writes them (their bits, in
/// order): one field of a body's state (`crate::divergence`).
pub(crate) fn hash_f32s(xs: impl IntoIterator<Item = f32>) -> u64 {
    let mut h = Fnv1a::new();
    for x in xs {
        h.write_f32(x);
    }
    h.finish()
}

/// A 64-bit hash folded to 32 bits, for hashes printed many to a line.
pub(crate) fn fold32(h: u64) -> u32 {
    (h ^ (h >> 32)) as u32
}

/// A quick, deterministic mix of a 64-bit key, for open-addressing tables.
#[inline]
pub(crate) fn mix64(mut x: u64) -> u64 {
    x ^= x >> 33;
    x = x.wrapping_mul(0xff51_afd7_ed55_8ccd);
    x ^= x >> 33;
    x = x.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    x ^ (x >> 33)
}

/// Numbers in [0, 1) from `seed`, the same on every platform: for tests
/// (the project's one generator, `up_geom::SplitMix64`).
#[cfg(test)]
pub(crate) fn uniform(seed: u64) -> impl FnMut() -> f32 {
    let mut rng = up_geom::SplitMix64::new(seed);
    move || rng.unit()
}
