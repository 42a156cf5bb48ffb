//! Run-time detection of the widest SIMD instruction set the contact-law
//! loop (`step::pair_kernel`) is compiled for.

/// The widest vector instruction set the law loop is compiled for that this
/// processor has. Every level gives the same bits: the law's arithmetic is
/// the same IEEE operations in the same order (no contraction into FMA),
/// only the number of contacts per instruction differs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Simd {
    /// The build's baseline (SSE2 on x86-64; any other architecture).
    Baseline,
    /// AVX2: 4 doubles per vector.
    Avx2,
    /// AVX-512 (F, VL, DQ): 8 doubles per vector, mask registers for the
    /// lane selects.
    Avx512,
}

/// The [`Simd`] level of this processor, detected once, then cached.
pub(crate) fn simd() -> Simd {
    #[cfg(target_arch = "x86_64")]
    {
        static LEVEL: std::sync::OnceLock<Simd> = std::sync::OnceLock::new();
        *LEVEL.get_or_init(|| {
            if std::arch::is_x86_feature_detected!("avx512f")
                && std::arch::is_x86_feature_detected!("avx512vl")
                && std::arch::is_x86_feature_detected!("avx512dq")
            {
                Simd::Avx512
            } else if std::arch::is_x86_feature_detected!("avx2") {
                Simd::Avx2
            } else {
                Simd::Baseline
            }
        })
    }
    #[cfg(not(target_arch = "x86_64"))]
    Simd::Baseline
}
