//! Exact sums of `f64` terms: the correctly rounded value of the real sum,
//! whatever the order of the terms and however they are split among
//! threads or MPI ranks (partial sums merge exactly).
//!
//! Every finite `f64` is an integer multiple of 2⁻¹⁰⁷⁴, below 2¹⁰²⁴: the
//! accumulator is one fixed-point integer in units of 2⁻¹⁰⁷⁴, held as
//! [`LIMBS`] signed 64-bit limbs of 32-bit digits (2 176 bits, room for
//! 2⁷⁸ terms of the largest magnitude). A term adds its 53-bit mantissa,
//! shifted, to three neighbouring limbs; the digits' carries are propagated
//! before a limb could overflow (every 2³⁰ terms) and when the value is
//! read. Infinities and NaNs are kept apart and give the IEEE result of the
//! sum (+∞ and −∞ together: NaN).
//!
//! Why not a crate: the `xsum` crate (Neal's superaccumulator, the only
//! one maintained) keeps its limbs in a `Vec` it does not expose, so two
//! partial sums can neither be merged nor sent to another rank, and it has
//! no thread-shared form. This module is that one accumulator, fixed-size,
//! with a merge, a byte form and [`AtomicExactSum`] (integer atomics, no
//! float atomics: the threads' order does not matter to an integer sum).

use std::sync::atomic::{AtomicI64, AtomicU8, Ordering};

/// Limbs of the accumulator (32-bit digits in `i64`).
pub const LIMBS: usize = 68;

/// Terms added between carry propagations: every term adds less than 2³²
/// to a limb, so a limb stays below 2⁶² in magnitude.
const CARRY_EVERY: u32 = 1 << 30;

/// The special values seen: +∞, −∞, NaN.
const POS_INF: u8 = 1;
const NEG_INF: u8 = 2;
const NAN: u8 = 4;

/// A term's three digits: the limb of its lowest bit and the (signed)
/// amounts for that limb and the next two; or its special-value flag.
#[inline(always)]
fn digits(x: f64) -> Result<(usize, [i64; 3]), u8> {
    let bits = x.to_bits();
    let e = ((bits >> 52) & 0x7ff) as usize;
    let f = bits & ((1u64 << 52) - 1);
    if e == 0x7ff {
        return Err(if f != 0 {
            NAN
        } else if bits >> 63 == 1 {
            NEG_INF
        } else {
            POS_INF
        });
    }
    // x = m · 2^(p − 1074)
    let (m, p) = if e == 0 {
        (f, 0)
    } else {
        (f | 1u64 << 52, e - 1)
    };
    let v = (m as u128) << (p % 32);
    let d = [
        (v & 0xffff_ffff) as i64,
        ((v >> 32) & 0xffff_ffff) as i64,
        (v >> 64) as i64,
    ];
    let d = if bits >> 63 == 1 { d.map(|x| -x) } else { d };
    Ok((p / 32, d))
}

/// Propagates the digits' carries: every limb but the last in `[0, 2³²)`,
/// the last signed.
fn carry(limb: &mut [i64; LIMBS]) {
    for i in 0..LIMBS - 1 {
        let c = limb[i] >> 32;
        limb[i] -= c << 32;
        limb[i + 1] += c;
    }
}

/// 2^e as an `f64`, for `e` in `-1074..=1023`.
fn pow2(e: i64) -> f64 {
    if e >= -1022 {
        f64::from_bits(((e + 1023) as u64) << 52)
    } else {
        f64::from_bits(1u64 << (e + 1074))
    }
}

/// The `f64` nearest to the non-negative integer of the normalised limbs
/// `l` (digits in `[0, 2³²)`) times 2⁻¹⁰⁷⁴, ties to even.
fn round(l: &[i64; LIMBS]) -> f64 {
    let Some(t) = (0..LIMBS).rev().find(|&i| l[i] != 0) else {
        return 0.0;
    };
    let at = |i: isize| if i < 0 { 0 } else { l[i as usize] as u128 };
    let t = t as isize;
    // the top three digits, w · 2^(32 (t − 2)); the rest only as sticky
    let w = at(t) << 64 | at(t - 1) << 32 | at(t - 2);
    let base = 32 * (t as i64 - 2);
    let sticky = t >= 3 && l[..(t - 2) as usize].iter().any(|&d| d != 0);
    let len = 128 - w.leading_zeros() as i64;
    if len + base <= 53 {
        // fewer than 54 bits: exact (t ≤ 1, so nothing is below w)
        let m = if base < 0 { w >> -base } else { w << base };
        return m as u64 as f64 * pow2(-1074);
    }
    let shift = (len - 53) as u32;
    let mut keep = (w >> shift) as u64;
    let rem = w & ((1u128 << shift) - 1);
    let half = 1u128 << (shift - 1);
    let mut exp = shift as i64 + base - 1074;
    if rem > half || (rem == half && (sticky || keep & 1 == 1)) {
        keep += 1;
        if keep == 1u64 << 53 {
            keep >>= 1;
            exp += 1;
        }
    }
    if exp > 1023 - 52 {
        return f64::INFINITY;
    }
    keep as f64 * pow2(exp)
}

/// An exact sum of `f64` terms (see the module's doc).
#[derive(Clone, Copy, PartialEq, Eq)]
pub struct ExactSum {
    limb: [i64; LIMBS],
    /// Terms added since the last carry propagation.
    adds: u32,
    special: u8,
}

impl Default for ExactSum {
    fn default() -> Self {
        ExactSum {
            limb: [0; LIMBS],
            adds: 0,
            special: 0,
        }
    }
}

impl std::fmt::Debug for ExactSum {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "ExactSum({:e})", self.value())
    }
}

impl ExactSum {
    /// The empty sum (zero).
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds the term `x` exactly.
    #[inline]
    pub fn add(&mut self, x: f64) {
        if self.adds == CARRY_EVERY {
            carry(&mut self.limb);
            self.adds = 0;
        }
        self.adds += 1;
        match digits(x) {
            Ok((k, d)) => {
                self.limb[k] += d[0];
                self.limb[k + 1] += d[1];
                self.limb[k + 2] += d[2];
            }
            Err(s) => self.special |= s,
        }
    }

    /// Adds every term of `xs`.
    pub fn add_all(&mut self, xs: impl IntoIterator<Item = f64>) {
        xs.into_iter().for_each(|x| self.add(x));
    }

    /// Adds another exact sum (its terms, exactly).
    pub fn merge(&mut self, o: &ExactSum) {
        let mut o = *o;
        carry(&mut o.limb);
        carry(&mut self.limb);
        for (a, b) in self.limb.iter_mut().zip(o.limb) {
            *a += b;
        }
        carry(&mut self.limb);
        self.adds = 0;
        self.special |= o.special;
    }

    /// The sum's value: the real sum of the terms rounded to the nearest
    /// `f64` (ties to even; ±∞ beyond the largest); an exact zero is +0.
    /// With an infinite term, that infinity (NaN for both signs, or with a
    /// NaN term).
    pub fn value(&self) -> f64 {
        if self.special != 0 {
            return if self.special & NAN != 0 || self.special == POS_INF | NEG_INF {
                f64::NAN
            } else if self.special == POS_INF {
                f64::INFINITY
            } else {
                f64::NEG_INFINITY
            };
        }
        let mut l = self.limb;
        carry(&mut l);
        if l[LIMBS - 1] < 0 {
            l.iter_mut().for_each(|d| *d = -*d);
            carry(&mut l);
            -round(&l)
        } else {
            round(&l)
        }
    }

    /// Bytes that [`ExactSum::from_bytes`] reads back as this sum (to send
    /// it to another rank): the normalised limbs, little-endian, and the
    /// special flags.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut l = self.limb;
        carry(&mut l);
        let mut out = Vec::with_capacity(LIMBS * 8 + 1);
        l.iter()
            .for_each(|d| out.extend_from_slice(&d.to_le_bytes()));
        out.push(self.special);
        out
    }

    /// The sum written by [`ExactSum::to_bytes`]; `None` for bytes of
    /// another length or digits out of range.
    pub fn from_bytes(b: &[u8]) -> Option<ExactSum> {
        if b.len() != LIMBS * 8 + 1 {
            return None;
        }
        let mut s = ExactSum::default();
        for (d, c) in s.limb.iter_mut().zip(b.chunks_exact(8)) {
            *d = i64::from_le_bytes(c.try_into().ok()?);
        }
        if s.limb[..LIMBS - 1]
            .iter()
            .any(|&d| !(0..1 << 32).contains(&d))
        {
            return None;
        }
        s.special = b[LIMBS * 8] & (POS_INF | NEG_INF | NAN);
        Some(s)
    }

    /// The sum in a short form for messages: the digits between the lowest
    /// non-zero one and the highest that is not the sign's fill (a few for
    /// sums of terms of like magnitude), the top limb and the special
    /// flags. [`ExactSum::from_compact`] reads it back exactly.
    pub fn to_compact(&self) -> Vec<u8> {
        let mut l = self.limb;
        carry(&mut l);
        let top = l[LIMBS - 1];
        let fill = if top < 0 { (1i64 << 32) - 1 } else { 0 };
        let hi = (0..LIMBS - 1)
            .rev()
            .find(|&i| l[i] != fill)
            .map_or(0, |i| i + 1);
        let lo = (0..hi).find(|&i| l[i] != 0).unwrap_or(hi);
        let mut out = Vec::with_capacity(11 + 4 * (hi - lo));
        out.push(self.special);
        out.extend_from_slice(&top.to_le_bytes());
        out.push(lo as u8);
        out.push((hi - lo) as u8);
        l[lo..hi]
            .iter()
            .for_each(|&d| out.extend_from_slice(&(d as u32).to_le_bytes()));
        out
    }

    /// The sum of [`ExactSum::to_compact`]'s bytes at the start of `b`, and
    /// the number of bytes it took; `None` for bytes of another form.
    pub fn from_compact(b: &[u8]) -> Option<(ExactSum, usize)> {
        let special = *b.first()?;
        let top = i64::from_le_bytes(b.get(1..9)?.try_into().ok()?);
        let (lo, n) = (*b.get(9)? as usize, *b.get(10)? as usize);
        if lo + n > LIMBS - 1 {
            return None;
        }
        let fill = if top < 0 { (1i64 << 32) - 1 } else { 0 };
        let mut s = ExactSum::default();
        s.limb[lo + n..LIMBS - 1].fill(fill);
        s.limb[LIMBS - 1] = top;
        let digits = b.get(11..11 + 4 * n)?;
        for (d, c) in s.limb[lo..lo + n].iter_mut().zip(digits.chunks_exact(4)) {
            *d = u32::from_le_bytes(c.try_into().ok()?) as i64;
        }
        s.special = special & (POS_INF | NEG_INF | NAN);
        Some((s, 11 + 4 * n))
    }
}

/// An exact sum that several threads add to at once (integer atomics;
/// each term is three relaxed additions). At most 2³¹ terms between two
/// [`AtomicExactSum::clear`]s (no carry is propagated in between).
pub struct AtomicExactSum {
    limb: [AtomicI64; LIMBS],
    special: AtomicU8,
}

impl Default for AtomicExactSum {
    fn default() -> Self {
        AtomicExactSum {
            limb: std::array::from_fn(|_| AtomicI64::new(0)),
            special: AtomicU8::new(0),
        }
    }
}

impl std::fmt::Debug for AtomicExactSum {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.load().fmt(f)
    }
}

impl AtomicExactSum {
    /// Adds the term `x` exactly.
    #[inline]
    pub fn add(&self, x: f64) {
        match digits(x) {
            Ok((k, d)) => {
                self.limb[k].fetch_add(d[0], Ordering::Relaxed);
                self.limb[k + 1].fetch_add(d[1], Ordering::Relaxed);
                self.limb[k + 2].fetch_add(d[2], Ordering::Relaxed);
            }
            Err(s) => {
                self.special.fetch_or(s, Ordering::Relaxed);
            }
        }
    }

    /// Back to zero.
    pub fn clear(&mut self) {
        self.limb.iter_mut().for_each(|d| *d.get_mut() = 0);
        *self.special.get_mut() = 0;
    }

    /// The sum so far (read when no thread adds).
    pub fn load(&self) -> ExactSum {
        let mut s = ExactSum {
            limb: std::array::from_fn(|i| self.limb[i].load(Ordering::Relaxed)),
            adds: 0,
            special: self.special.load(Ordering::Relaxed),
        };
        carry(&mut s.limb);
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_sums_are_exact_and_cancellation_is_exact() {
        let mut s = ExactSum::new();
        s.add_all([1e308, 1.0, -1e308, 1e-300, 2.0f64.powi(-1074)]);
        assert_eq!(s.value(), 1.0, "1 + 1e-300 + tiny rounds to 1");
        let mut s = ExactSum::new();
        s.add_all([1e308, 1e308, -1e308]);
        assert_eq!(s.value(), 1e308, "no overflow in between");
        let mut s = ExactSum::new();
        s.add_all([0.1, 0.2, 0.3]);
        // the three doubles' real sum is nearer 0.6 than its neighbours
        // (Python's math.fsum gives 0.6; left to right it is 0.6000000000000001)
        assert_eq!(s.value(), 0.6);
    }

    #[test]
    fn specials_give_the_ieee_result() {
        let mut s = ExactSum::new();
        s.add_all([1.0, f64::INFINITY]);
        assert_eq!(s.value(), f64::INFINITY);
        s.add(f64::NEG_INFINITY);
        assert!(s.value().is_nan());
        let mut s = ExactSum::new();
        s.add_all([f64::MAX, f64::MAX]);
        assert_eq!(s.value(), f64::INFINITY, "a finite sum past the range");
    }

    #[test]
    fn bytes_and_atomics_keep_the_sum() {
        let xs = [3.5, -1e-310, 7e200, -7e200, 0.1];
        let mut s = ExactSum::new();
        s.add_all(xs);
        let back = ExactSum::from_bytes(&s.to_bytes()).unwrap();
        assert_eq!(back.value().to_bits(), s.value().to_bits());
        let a = AtomicExactSum::default();
        xs.iter().for_each(|&x| a.add(x));
        assert_eq!(a.load().value().to_bits(), s.value().to_bits());
        assert!(ExactSum::from_bytes(&[0; 3]).is_none());
    }

    #[test]
    fn the_compact_form_keeps_every_limb() {
        let cases: [&[f64]; 6] = [
            &[],
            &[3.5, -1e-310, 7e200, -7e200, 0.1],
            &[-0.1, -1e-300, 2.5],
            &[-1e-300],
            &[f64::MAX, -5e-324],
            &[1.0, f64::NAN],
        ];
        for xs in cases {
            let mut s = ExactSum::new();
            s.add_all(xs.iter().copied());
            let c = s.to_compact();
            let (back, n) = ExactSum::from_compact(&c).unwrap();
            assert_eq!(n, c.len());
            assert_eq!(back.to_bytes(), s.to_bytes(), "{xs:?}");
        }
        let mut s = ExactSum::new();
        s.add_all([0.25, 1.0, 3.0]);
        assert!(s.to_compact().len() <= 11 + 4 * 3, "a short sum is short");
        assert!(ExactSum::from_compact(&[0; 5]).is_none());
    }
}
