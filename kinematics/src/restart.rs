//! The seeded generator the iterative IK solvers draw their restart configurations from
//! ([`crate::qp_ik`], [`crate::chain_ik`]): the same seed, the same restarts, on any platform.

/// SplitMix64: a tiny, seeded, portable generator.
pub(crate) struct SplitMix64(pub(crate) u64);

impl SplitMix64 {
    /// A number in [0, 1).
    pub(crate) fn next_unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}
