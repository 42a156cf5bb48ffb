//! The exact accumulator (`clump_core::exact_sum`, T-73) against sums from
//! outside the code: Python's exact rationals on adversarial terms over the
//! whole `f64` range (the fixture, `scripts/exact_sum_cases.py`), and
//! Rust's correctly rounded `i128 as f64` on random terms whose exact sum
//! fits in an `i128`; and its independence of order, threads and splits.

use clump_core::exact_sum::{AtomicExactSum, ExactSum};
use proptest::prelude::*;

fn sum(xs: &[f64]) -> f64 {
    let mut s = ExactSum::new();
    s.add_all(xs.iter().copied());
    s.value()
}

#[test]
fn matches_exact_rational_sums_on_adversarial_terms() {
    let text = include_str!("fixtures/exact_sum_cases.txt");
    let mut n = 0;
    for (line, l) in text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.starts_with('#'))
    {
        let (terms, want) = l.split_once(';').expect("terms ; sum");
        let f = |h: &str| f64::from_bits(u64::from_str_radix(h, 16).expect("hex bits"));
        let xs: Vec<f64> = terms.split_whitespace().map(f).collect();
        let want = f(want.trim());
        let got = sum(&xs);
        assert_eq!(
            got.to_bits(),
            want.to_bits(),
            "case on line {}: {got:e} against {want:e}",
            line + 1
        );
        // the same terms backwards, and split in two merged halves
        let mut rev = xs.clone();
        rev.reverse();
        assert_eq!(sum(&rev).to_bits(), want.to_bits());
        let (a, b) = xs.split_at(xs.len() / 2);
        let (mut sa, mut sb) = (ExactSum::new(), ExactSum::new());
        sa.add_all(a.iter().copied());
        sb.add_all(b.iter().copied());
        sb.merge(&ExactSum::from_bytes(&sa.to_bytes()).unwrap());
        assert_eq!(sb.value().to_bits(), want.to_bits());
        n += 1;
    }
    assert!(n >= 200, "{n} cases");
}

proptest! {
    #[test]
    fn matches_i128_sums_rounded_by_the_standard_library(
        e0 in -960i32..900,
        terms in prop::collection::vec((-(1i64 << 53)..(1i64 << 53), 0i32..40), 1..64),
    ) {
        let xs: Vec<f64> = terms.iter().map(|&(m, e)| m as f64 * 2f64.powi(e0 + e)).collect();
        let exact: i128 = terms.iter().map(|&(m, e)| (m as i128) << e).sum();
        // i128 → f64 rounds to nearest, ties to even; the power of two is exact
        let want = exact as f64 * 2f64.powi(e0);
        prop_assert_eq!(sum(&xs).to_bits(), want.to_bits());
    }

    #[test]
    fn order_threads_and_splits_change_no_bit(
        xs in prop::collection::vec(prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO, 1..80),
        cut in 0usize..80,
        seed in 0u64..1000,
    ) {
        let want = sum(&xs);
        let mut shuffled = xs.clone();
        // a fixed permutation from the seed
        let n = shuffled.len();
        for i in (1..n).rev() {
            shuffled.swap(i, ((seed.wrapping_mul(6364136223846793005).wrapping_add(i as u64)) % (i as u64 + 1)) as usize);
        }
        prop_assert_eq!(sum(&shuffled).to_bits(), want.to_bits());
        let (a, b) = xs.split_at(cut.min(n));
        let at = AtomicExactSum::default();
        std::thread::scope(|s| {
            s.spawn(|| a.iter().for_each(|&x| at.add(x)));
            s.spawn(|| b.iter().for_each(|&x| at.add(x)));
        });
        prop_assert_eq!(at.load().value().to_bits(), want.to_bits());
    }
}
