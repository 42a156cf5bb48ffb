//! The sliding law ([`SlidingLaw`]) run over the lanes of a batch of
//! contacts, for any layout of lanes that implements [`LawLanes`]: the
//! sphere pairs of the pair kernel (`super::pair_kernel::lanes`) and the
//! sphere–wall touches of the wall pass (`super::wall_lanes`).
//!
//! The loop has no branches and no indirect access, so the compiler turns
//! it into vector instructions; it is compiled for AVX-512 and AVX2 besides
//! the baseline, and the widest the processor has runs
//! (`crate::par::simd`). Every level gives the same bits. The loop takes
//! every contact as sticking and flags those that slide; [`finish_sliding`]
//! evaluates them again with the Coulomb limit from their spring before the
//! step, after which every lane holds, bit for bit, what the full law gives.

use crate::contact::SlidingLaw;
use crate::par::simd::Simd;
use glam::DVec3;

/// A batch of contacts stored as lanes, one element per contact.
pub(super) trait LawLanes {
    /// Lanes a batch holds.
    const LANES: usize;

    /// Lane `k`'s own law (a batch that mixes models).
    fn lane_law(&self, k: usize) -> SlidingLaw;

    /// Contact `k` under `law`, its outputs stored in its lane; with
    /// `LIMIT` false the outputs of a contact that sticks, whether or not
    /// it does ([`SlidingLaw::evaluate_as`]). Returns whether it slides.
    fn contact_as<const LIMIT: bool>(&mut self, k: usize, law: &SlidingLaw, dt: f64) -> bool;

    /// Lane `k`'s flag: 1 where the law loop found the contact sliding.
    fn slide(&self, k: usize) -> f64;

    /// Sets lane `k`'s flag (a number, not a `bool`: a `bool` output kept
    /// the compiler from vectorising the loop).
    fn set_slide(&mut self, k: usize, slide: f64);

    /// Sets lane `k`'s tangential spring (m, world frame).
    fn set_spring(&mut self, k: usize, xi: DVec3);
}

/// Runs [`law_lanes`] over the first `len` lanes, compiled for the vector
/// instructions `simd` (detected on this processor).
#[inline(always)]
pub(super) fn run_law<L: LawLanes>(
    l: &mut L,
    len: usize,
    law: Option<&SlidingLaw>,
    dt: f64,
    simd: Simd,
) {
    #[cfg(target_arch = "x86_64")]
    match simd {
        // SAFETY: `simd` was detected on this processor.
        Simd::Avx512 => return unsafe { law_lanes_avx512(l, len, law, dt) },
        Simd::Avx2 => return unsafe { law_lanes_avx2(l, len, law, dt) },
        Simd::Baseline => {}
    }
    let _ = simd;
    law_lanes(l, len, law, dt);
}

/// [`law_lanes`] compiled for AVX-512 (8 doubles per vector).
///
/// # Safety
/// The processor supports AVX-512 F, VL and DQ.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl,avx512dq")]
unsafe fn law_lanes_avx512<L: LawLanes>(l: &mut L, len: usize, law: Option<&SlidingLaw>, dt: f64) {
    law_lanes(l, len, law, dt)
}

/// [`law_lanes`] compiled for AVX2 (4 doubles per vector).
///
/// # Safety
/// The processor supports AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn law_lanes_avx2<L: LawLanes>(l: &mut L, len: usize, law: Option<&SlidingLaw>, dt: f64) {
    law_lanes(l, len, law, dt)
}

/// The law over lanes `0..len`: `law` is the model of every lane, or
/// `None` when the lanes carry their own. Every lane takes the outputs of
/// a contact that sticks, and a lane that slides is flagged for
/// [`finish_sliding`].
#[inline(always)]
pub(super) fn law_lanes<L: LawLanes>(l: &mut L, len: usize, law: Option<&SlidingLaw>, dt: f64) {
    match law {
        Some(law) => {
            for k in 0..len.min(L::LANES) {
                let slide = l.contact_as::<false>(k, law, dt);
                l.set_slide(k, if slide { 1.0 } else { 0.0 });
            }
        }
        None => {
            for k in 0..len.min(L::LANES) {
                let law = l.lane_law(k);
                let slide = l.contact_as::<false>(k, &law, dt);
                l.set_slide(k, if slide { 1.0 } else { 0.0 });
            }
        }
    }
}

/// The contacts among lanes `0..len` that the law loop found sliding,
/// evaluated again with the Coulomb limit from their spring before the
/// step, `spring(k)` (the loop overwrote the lane's): afterwards every
/// lane holds what the full law gives, and no lane is flagged. `law` as
/// for [`run_law`].
#[inline(always)]
pub(super) fn finish_sliding<L: LawLanes>(
    l: &mut L,
    len: usize,
    law: Option<&SlidingLaw>,
    dt: f64,
    spring: impl Fn(usize) -> DVec3,
) {
    for k in 0..len.min(L::LANES) {
        if l.slide(k) != 0.0 {
            l.set_spring(k, spring(k));
            let law = law.copied().unwrap_or_else(|| l.lane_law(k));
            l.contact_as::<true>(k, &law, dt);
            l.set_slide(k, 0.0);
        }
    }
}
