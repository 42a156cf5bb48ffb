//! Run-time detection of the widest SIMD instruction set the vectorised
//! loops (the contact law, `step::pair_kernel`; the first halves,
//! `step::first_half_lanes`) are compiled for, and the lane access those
//! loops share.

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

/// Lane `k` of a 3-vector stored as lanes (x, y and z rows of `N` lanes,
/// structure of arrays), as the vectorised loops keep their inputs and
/// outputs.
#[inline(always)]
pub(crate) fn get3<const N: usize>(r: &[[f64; N]; 3], k: usize) -> glam::DVec3 {
    glam::DVec3::new(r[0][k], r[1][k], r[2][k])
}

/// Sets lane `k` of a 3-vector stored as lanes (see [`get3`]).
#[inline(always)]
pub(crate) fn set3<const N: usize>(r: &mut [[f64; N]; 3], k: usize, x: glam::DVec3) {
    r[0][k] = x.x;
    r[1][k] = x.y;
    r[2][k] = x.z;
}

/// The vector instruction sets this processor has, for tests that compare
/// a loop compiled for each.
#[cfg(test)]
pub(crate) fn levels() -> Vec<Simd> {
    let mut levels = vec![Simd::Baseline];
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            levels.push(Simd::Avx2);
        }
        if simd() == Simd::Avx512 {
            levels.push(Simd::Avx512);
        }
    }
    eprintln!("levels on this processor: {levels:?}");
    levels
}

/// Uniform numbers in [0, 1) from a xorshift sequence seeded by `seed`
/// (non-zero), for tests that fill lanes with varied inputs.
#[cfg(test)]
pub(crate) fn unit_numbers(seed: u64) -> impl FnMut() -> f64 {
    let mut s = seed;
    move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}
