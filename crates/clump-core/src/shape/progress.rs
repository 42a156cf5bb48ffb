//! Progress of a long mass-property integration, as `tracing` events
//! (target `clump_core::shape`), so that a template of 10⁴ spheres that takes
//! minutes says what it is doing. Nothing is reported for the first second,
//! then at most one message every two seconds; a program that installs no
//! tracing subscriber sees nothing.

use std::sync::atomic::{AtomicU64, AtomicUsize, Ordering};
use std::time::Instant;

/// First report after this long, s.
const QUIET: f64 = 1.0;
/// Then one report per this long at most, s.
const EVERY: f64 = 2.0;

/// Counts work done in one phase and reports it when slow. Thread-safe: the
/// first pass runs on rayon's threads. It only observes; the integration's
/// results never depend on it.
pub(crate) struct Progress {
    start: Instant,
    spheres: usize,
    done: AtomicUsize,
    /// Time of the last report, ms after `start` (0: none yet).
    last_ms: AtomicU64,
}

impl Progress {
    /// From this many spheres the first pass is announced with an estimate
    /// of its time before it starts.
    pub(crate) const ESTIMATED_FROM: usize = 2_000;
    /// Intervals timed for that estimate, spread evenly along the union.
    pub(crate) const SAMPLE: usize = 16;

    /// Announces the first pass: `intervals` intervals on `threads` threads,
    /// a sample of which took `mean` s each (a rough estimate: an interval's
    /// cost grows with the discs its cross-sections cut).
    pub(crate) fn estimate(&self, mean: f64, intervals: usize, threads: usize) {
        tracing::info!(
            "template of {} spheres: mass properties, first pass of {intervals} slice intervals: about {:.0} s on {threads} threads ({} intervals timed, {mean:.3} s each), then a refinement; give mass and inertia in the [[template]] to skip it",
            self.spheres,
            mean * intervals as f64 / threads.max(1) as f64,
            Self::SAMPLE
        );
    }

    pub(crate) fn new(spheres: usize) -> Self {
        Progress {
            start: Instant::now(),
            spheres,
            done: AtomicUsize::new(0),
            last_ms: AtomicU64::new(0),
        }
    }

    /// Whether a report is due now (and claims it).
    fn due(&self) -> bool {
        let now = self.start.elapsed().as_secs_f64();
        if now < QUIET {
            return false;
        }
        let now_ms = (now * 1000.0) as u64;
        let last = self.last_ms.load(Ordering::Relaxed);
        if last != 0 && (now_ms - last) as f64 / 1000.0 < EVERY {
            return false;
        }
        self.last_ms
            .compare_exchange(last, now_ms, Ordering::Relaxed, Ordering::Relaxed)
            .is_ok()
    }

    /// One more of `total` intervals of the first pass is integrated.
    pub(crate) fn interval_done(&self, total: usize) {
        let done = self.done.fetch_add(1, Ordering::Relaxed) + 1;
        if self.due() {
            let elapsed = self.start.elapsed().as_secs_f64();
            tracing::info!(
                "template of {} spheres: mass properties, first pass {done} of {total} slice intervals ({:.0} %, {elapsed:.0} s; about {:.0} s left in this pass, then a refinement; give mass and inertia in the [[template]] to skip it)",
                self.spheres,
                100.0 * done as f64 / total as f64,
                remaining_seconds(elapsed, done, total)
            );
        }
    }

    /// The adaptive refinement stands at `error` against `target` (relative).
    pub(crate) fn refining(&self, error: f64, target: f64) {
        if self.due() {
            tracing::info!(
                "template of {} spheres: mass properties, refining: error estimate {error:.2e}, target {target:.0e} ({:.0} s)",
                self.spheres,
                self.start.elapsed().as_secs_f64()
            );
        }
    }
}

/// Time left in a pass of `total` equal-cost intervals after `done` took
/// `elapsed` seconds, s: the rate so far carried to the end (the intervals
/// are slices of one sphere union, of similar cost on average).
fn remaining_seconds(elapsed: f64, done: usize, total: usize) -> f64 {
    if done == 0 {
        return f64::INFINITY;
    }
    elapsed * (total.saturating_sub(done)) as f64 / done as f64
}

#[cfg(test)]
mod tests {
    use super::remaining_seconds;

    #[test]
    fn remaining_time_carries_the_rate_so_far() {
        // a quarter done in 10 s: 30 s to go at the same rate
        assert_eq!(remaining_seconds(10.0, 25, 100), 30.0);
        assert_eq!(remaining_seconds(10.0, 100, 100), 0.0);
        assert!(remaining_seconds(1.0, 0, 100).is_infinite());
    }
}
