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
            tracing::info!(
                "template of {} spheres: mass properties, first pass {done} of {total} slice intervals ({:.0} %, {:.0} s)",
                self.spheres,
                100.0 * done as f64 / total as f64,
                self.start.elapsed().as_secs_f64()
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
