//! How long a cache line takes to go from one core to another and back, as
//! the bench measures it around each multi-threaded Clump round.
//!
//! On a shared virtual machine the guest cannot see where the host places
//! its vCPUs, and the placement changes: on the 2-vCPU Zen 3 host of
//! docs/performance.md §2 this round trip alternated between about 100 and
//! about 450 ns within minutes, and on a quiet stretch Clump's two-thread
//! tetra bed ran at 31.1–31.7 M sphere-steps/s in the first state and at
//! 28.2–28.3 M in the second (the bodies on the seam between the threads'
//! runs cross between the cores every step). A round's figure next to
//! this measure says which state the host was in.
//!
//! Two threads take turns on one atomic word: one writes an odd value and
//! spins until the other answers with the next even one. No `spin_loop`
//! hint: it would add the pause instruction's own latency to the figure.

use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// Round trips timed (after [`WARM_TRIPS`] untimed ones): about 20 ms at
/// 100 ns, 90 ms at 450 ns.
const TRIPS: u64 = 200_000;

/// Round trips before the clock starts (both threads running and the line
/// bouncing).
const WARM_TRIPS: u64 = 2_000;

/// Longest the probe spins before giving up: two threads that share one
/// core (another process busy on the other) would take a scheduler
/// quantum per trip.
const LIMIT: Duration = Duration::from_millis(500);

/// The word's value that tells the answering thread to stop.
const STOP: u64 = u64::MAX;

/// A word alone on its cache lines (two, for the adjacent-line prefetcher).
#[repr(align(128))]
struct Line(AtomicU64);

/// Mean round trip of a cache line between two threads of this process,
/// ns; `None` with fewer than two processors, or when the trips do not get
/// done within [`LIMIT`] (the two threads are then not running at once).
pub(crate) fn round_trip_ns() -> Option<f64> {
    if std::thread::available_parallelism().map_or(1, |n| n.get()) < 2 {
        return None;
    }
    let line = Line(AtomicU64::new(0));
    let word = &line.0;
    std::thread::scope(|s| {
        s.spawn(|| answer(word));
        let timed = ping(word);
        word.store(STOP, Ordering::Release);
        timed
    })
}

/// The answering side: each odd value gets the next even one, until
/// [`STOP`].
fn answer(word: &AtomicU64) {
    loop {
        let v = word.load(Ordering::Acquire);
        if v == STOP {
            return;
        }
        if v % 2 == 1 {
            // only if the word still holds `v`: a plain store could
            // overwrite a STOP written meanwhile (by an asker that gave up
            // while this thread was descheduled), and never return
            let _ = word.compare_exchange(v, v + 1, Ordering::AcqRel, Ordering::Acquire);
        }
    }
}

/// The asking side: [`WARM_TRIPS`] then [`TRIPS`] timed round trips; the
/// mean of the timed ones, ns, or `None` past [`LIMIT`].
fn ping(word: &AtomicU64) -> Option<f64> {
    let start = Instant::now();
    let mut timed_from = None;
    for trip in 0..WARM_TRIPS + TRIPS {
        if trip == WARM_TRIPS {
            timed_from = Some(Instant::now());
        }
        let ask = 2 * trip + 1;
        word.store(ask, Ordering::Release);
        let mut spins = 0u64;
        while word.load(Ordering::Acquire) != ask + 1 {
            spins += 1;
            // the clock read now and then only, not to slow the trip down
            if spins & 4095 == 0 && start.elapsed() > LIMIT {
                return None;
            }
        }
        if trip & 4095 == 0 && start.elapsed() > LIMIT {
            return None;
        }
    }
    let t = timed_from?.elapsed();
    Some(t.as_secs_f64() * 1e9 / TRIPS as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The answering side moves an odd value on to the next even one,
    /// leaves even values alone, and returns on STOP (which it never
    /// overwrites).
    #[test]
    fn the_answering_side_moves_odd_values_on_and_stops() {
        let w = AtomicU64::new(5);
        std::thread::scope(|s| {
            s.spawn(|| answer(&w));
            while w.load(Ordering::Acquire) != 6 {
                std::thread::yield_now();
            }
            w.store(STOP, Ordering::Release);
        });
        assert_eq!(w.load(Ordering::Acquire), STOP);
    }

    /// On a machine with two processors the probe answers with a round
    /// trip that a cache line can take (above the ~1 ns of one L1 hit and
    /// below the limit's share per trip); with one it declines.
    #[test]
    fn the_probe_measures_a_plausible_round_trip_or_declines() {
        let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
        // None: one processor, or the other thread not scheduled alongside
        // (a loaded test machine)
        if let Some(ns) = round_trip_ns() {
            assert!(cpus >= 2);
            let most = LIMIT.as_secs_f64() * 1e9 / TRIPS as f64;
            assert!(ns > 1.0 && ns <= most, "round trip {ns} ns");
        }
    }
}
