//! Fixed-point sums of the coarse-grained fields (T-74 in
//! docs/theory.md): the same terms give the same bits in any order, so a
//! field summed by ranks in pieces is one process's field
//! ([`super::fields::Fields::from_fixed`] reads them).
//!
//! Each field `f` (density, momentum, …: [`super::fields::field`]) gets
//! one scale `2^k_f`, fixed by its largest term `|t|_max < 2^e` and its
//! number of terms `N` over the whole world: `k = 125 − e − ⌈log₂ N⌉`.
//! Every term is rounded once to the integer nearest `t 2^k` (at most
//! `2^(125 − ⌈log₂ N⌉)` in size) and summed in an `i128`, whose total
//! cannot overflow (`N 2^(125 − ⌈log₂ N⌉) ≤ 2^125`). A cell's value is the
//! total rounded once to f64 and scaled back by `2^−k`. Its error is at
//! most `n_c 2^(e + ⌈log₂ N⌉ − 126)` for `n_c` terms in the cell: with
//! 2³⁶ terms in all and 2¹³ in a cell, 2⁻⁷⁷ of the largest term, below
//! the f64 rounding of any cell value larger than 2⁻²⁴ of it. The scale
//! needs a first pass over the terms ([`Extent`]) and, on ranks, a
//! reduction of the extents before the sums.

/// Fields summed.
pub const FIELDS: usize = 10;
/// Components of each field, in the order of the field numbers of
/// [`super::fields::deposit`].
const COMPONENTS: [usize; FIELDS] = [1, 3, 9, 9, 1, 9, 1, 9, 1, 1];
/// Components of all fields, per cell.
const SLOTS: usize = 44;
/// The first slot of each field in a cell.
const FIRST: [usize; FIELDS] = [0, 1, 4, 13, 22, 23, 32, 33, 42, 43];

/// Per field: the largest term's magnitude and the number of terms.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Extent {
    max: [f64; FIELDS],
    count: [u64; FIELDS],
}

impl Extent {
    /// Counts the components `v` of a term of field `k`.
    pub fn see(&mut self, k: usize, v: &[f64]) {
        for x in v {
            self.max[k] = self.max[k].max(x.abs());
        }
        self.count[k] += v.len() as u64;
    }

    /// Takes in another part's extent (maxima and counts: exact in any
    /// order).
    pub fn merge(&mut self, o: &Extent) {
        for k in 0..FIELDS {
            self.max[k] = self.max[k].max(o.max[k]);
            self.count[k] += o.count[k];
        }
    }

    /// Bytes of the extent (little-endian).
    pub fn to_bytes(&self) -> Vec<u8> {
        let m = self.max.iter().flat_map(|x| x.to_le_bytes());
        m.chain(self.count.iter().flat_map(|c| c.to_le_bytes()))
            .collect()
    }

    /// The extent of [`Self::to_bytes`]' bytes.
    pub fn from_bytes(b: &[u8]) -> Option<Extent> {
        if b.len() != 16 * FIELDS {
            return None;
        }
        let word = |i: usize| b[8 * i..8 * i + 8].try_into().ok();
        let mut e = Extent::default();
        for k in 0..FIELDS {
            e.max[k] = f64::from_le_bytes(word(k)?);
            e.count[k] = u64::from_le_bytes(word(FIELDS + k)?);
        }
        Some(e)
    }

    /// The scale exponent `k` of each field (see the module docs).
    fn scales(&self) -> [i32; FIELDS] {
        std::array::from_fn(|f| {
            let (max, n) = (self.max[f], self.count[f]);
            if !(max > 0.0) || !max.is_finite() || n == 0 {
                return 0;
            }
            // max < 2^e
            let e = (((max.to_bits() >> 52) & 0x7ff) as i32 - 1022).max(-1021);
            let bits = 64 - (n - 1).leading_zeros() as i32;
            125 - e - bits
        })
    }
}

/// `x 2^k`, by steps that stay within the exponent range.
fn ldexp(mut x: f64, mut k: i32) -> f64 {
    while k > 1000 {
        x *= 2f64.powi(1000);
        k -= 1000;
    }
    while k < -1000 {
        x *= 2f64.powi(-1000);
        k += 1000;
    }
    x * 2f64.powi(k)
}

/// The fields of a grid as fixed-point sums.
#[derive(Debug, Clone, PartialEq)]
pub struct FixedGrid {
    k: [i32; FIELDS],
    sums: Vec<i128>,
}

impl FixedGrid {
    /// Zero sums for `cells` cells, with the scales of the whole world's
    /// `extent`.
    pub fn new(cells: usize, extent: &Extent) -> FixedGrid {
        FixedGrid {
            k: extent.scales(),
            sums: vec![0; cells * SLOTS],
        }
    }

    /// Adds the components `v` of a term of field `f` in `cell`.
    pub fn add(&mut self, f: usize, cell: usize, v: &[f64]) {
        let at = cell * SLOTS + FIRST[f];
        for (s, &x) in self.sums[at..at + v.len()].iter_mut().zip(v) {
            *s += ldexp(x, self.k[f]).round() as i128;
        }
    }

    /// Takes in another part's sums (integer sums: exact in any order);
    /// `None` when the two have other scales or sizes.
    pub fn merge(&mut self, o: &FixedGrid) -> Option<()> {
        if o.k != self.k || o.sums.len() != self.sums.len() {
            return None;
        }
        self.sums.iter_mut().zip(&o.sums).for_each(|(a, b)| *a += b);
        Some(())
    }

    /// Bytes of the sums (the scales, then the sums, little-endian).
    pub fn to_bytes(&self) -> Vec<u8> {
        let k = self.k.iter().flat_map(|k| k.to_le_bytes());
        k.chain(self.sums.iter().flat_map(|s| s.to_le_bytes()))
            .collect()
    }

    /// The sums of [`Self::to_bytes`]' bytes.
    pub fn from_bytes(b: &[u8]) -> Option<FixedGrid> {
        let head = 4 * FIELDS;
        if b.len() < head || (b.len() - head) % (16 * SLOTS) != 0 {
            return None;
        }
        let k =
            std::array::from_fn(|f| i32::from_le_bytes(b[4 * f..4 * f + 4].try_into().unwrap()));
        let sums = b[head..]
            .chunks_exact(16)
            .map(|c| i128::from_le_bytes(c.try_into().unwrap()))
            .collect();
        Some(FixedGrid { k, sums })
    }

    /// Cells of the grid.
    pub fn cells(&self) -> usize {
        self.sums.len() / SLOTS
    }

    /// Component `i` of field `f` in `cell`: its sum rounded once to f64
    /// and scaled back.
    pub fn value(&self, cell: usize, f: usize, i: usize) -> f64 {
        debug_assert!(i < COMPONENTS[f]);
        ldexp(self.sums[cell * SLOTS + FIRST[f] + i] as f64, -self.k[f])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Terms of every size in two orders and split in two merged parts
    /// give the same bits, and the value is the exact sum where that is
    /// representable (integers times a power of two, checked in i128).
    #[test]
    fn fixed_sums_are_order_free_and_exact_for_representable_totals() {
        let terms: Vec<f64> = (0..2000)
            .map(|i| ((i * 7919 % 1001) as f64 - 500.0) * 2f64.powi(-(i % 40)))
            .collect();
        let sum = |ts: &[f64]| {
            let mut e = Extent::default();
            terms.iter().for_each(|t| e.see(0, &[*t]));
            let mut g = FixedGrid::new(1, &e);
            ts.iter().for_each(|t| g.add(0, 0, &[*t]));
            g
        };
        let fwd = sum(&terms);
        let rev: Vec<f64> = terms.iter().rev().copied().collect();
        assert_eq!(fwd, sum(&rev));
        let (a, b) = terms.split_at(777);
        let mut m = sum(a);
        m.merge(&FixedGrid::from_bytes(&sum(b).to_bytes()).unwrap())
            .unwrap();
        assert_eq!(fwd, m);
        // the exact total: every term is an integer multiple of 2^-39
        let exact: i128 = terms.iter().map(|t| ldexp(*t, 39) as i128).sum();
        assert_eq!(fwd.value(0, 0, 0), ldexp(exact as f64, -39));
    }
}
