//! What this machine's memory gives a loop that walks many arrays side by
//! side, as the step's per-body passes walk the structure-of-arrays fields:
//! `S` arrays of f64, each element read, incremented and written back, all
//! `S` arrays at index `i` before `i + 1`. It runs once on a working set far
//! beyond the caches (384 MiB) and once on one that fits the L3 (6 MiB,
//! repeated to the same bytes), and prints the bytes moved per second
//! (read + write) and their ratio, the memory penalty of a pass of `S`
//! streams.
//!
//! `cargo run --release -p clump-core --example memory_streams`

use std::hint::black_box;
use std::time::Instant;

/// Doubles between the starts of consecutive arrays within their pages (328
/// bytes), so that the i-th elements of the arrays spread over the page
/// offsets and L1 sets instead of all sharing one.
const SKEW: usize = 41;

/// Best of three passes over `s` arrays of `n` doubles, `reps` times each:
/// GB/s moved (read + write).
fn rate(s: usize, n: usize, reps: usize) -> f64 {
    let mut store: Vec<Vec<f64>> = (0..s)
        .map(|k| (0..n + SKEW * s).map(|i| (i + k) as f64).collect())
        .collect();
    let mut a: Vec<&mut [f64]> = store
        .iter_mut()
        .enumerate()
        .map(|(k, v)| &mut v[SKEW * k..SKEW * k + n])
        .collect();
    let mut best = f64::MAX;
    for _ in 0..3 {
        let t = Instant::now();
        for _ in 0..reps {
            for i in 0..n {
                for x in a.iter_mut() {
                    x[i] += 1.0;
                }
            }
        }
        best = best.min(t.elapsed().as_secs_f64());
        black_box(&mut a);
    }
    2.0 * 8.0 * (n * s * reps) as f64 / best / 1e9
}

fn main() {
    let (large, small) = (384usize << 20, 6usize << 20);
    println!("streams  beyond the caches GB/s  in the L3 GB/s  penalty");
    for s in [1, 2, 4, 8, 12, 16, 20, 24, 32] {
        let (nl, ns) = (large / 8 / s, small / 8 / s);
        let gl = rate(s, nl, 1);
        let gs = rate(s, ns, large / small);
        println!("{s:7}  {gl:26.1}  {gs:14.1}  {:7.2}", gs / gl);
    }
}
