//! Chunk-to-thread affinity for the per-step loops.
//!
//! Each per-step loop (first half step, pair forces, gather) runs over fixed
//! chunks of bodies or spheres. Work stealing would hand the same bodies to
//! different threads from one stage to the next, and every stage would then
//! pull their data from the other core's cache. Here thread `t` of `T` always
//! takes the same contiguous run of chunks, `[n t/T, n (t+1)/T)`: the bodies
//! it moves in the first half step are the ones whose spheres' rows it
//! evaluates and whose forces it gathers (bodies and their spheres are stored
//! in the same Morton order, so the runs line up). Only the pairs across the
//! seam between two runs touch the other core's data.
//!
//! The results do not depend on the thread count: chunk boundaries are fixed
//! sizes, every chunk writes its own outputs, and every reduction over chunks
//! runs in chunk order afterwards.

/// Calls `f(c)` for every chunk `c` in `0..n`, each exactly once; thread `t`
/// of the current rayon pool's `T` takes chunks `[n t/T, n (t+1)/T)`, in
/// order. On one thread it is a plain loop.
pub(crate) fn for_each_chunk(n: usize, f: impl Fn(usize) + Sync) {
    let threads = rayon::current_num_threads();
    if threads <= 1 || n <= 1 {
        (0..n).for_each(f);
        return;
    }
    rayon::broadcast(|ctx| {
        let (t, nt) = (ctx.index(), ctx.num_threads());
        (n * t / nt..n * (t + 1) / nt).for_each(&f);
    });
}

/// Like [`for_each_chunk`], with one `&mut` scratch value per thread made by
/// `init` (once per call and thread).
pub(crate) fn for_each_chunk_with<S>(
    n: usize,
    init: impl Fn() -> S + Sync,
    f: impl Fn(&mut S, usize) + Sync,
) {
    let threads = rayon::current_num_threads();
    if threads <= 1 || n <= 1 {
        let mut s = init();
        (0..n).for_each(|c| f(&mut s, c));
        return;
    }
    rayon::broadcast(|ctx| {
        let (t, nt) = (ctx.index(), ctx.num_threads());
        let mut s = init();
        (n * t / nt..n * (t + 1) / nt).for_each(|c| f(&mut s, c));
    });
}
