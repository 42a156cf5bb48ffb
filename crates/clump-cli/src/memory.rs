//! How much memory a run needs, said before anything is allocated.
//!
//! A run holds about [`BYTES_PER_SPHERE`] per sphere (sphere and body state,
//! neighbour and contact lists), measured with `clump bench --scaling`
//! (docs/performance.md §3: 345–553 bytes per sphere of tetrahedron clumps,
//! 10⁴–10⁶ spheres, over the builds measured), rounded up.

use clump_io::scenario::Scenario;

/// Resident bytes per sphere of a running simulation.
pub const BYTES_PER_SPHERE: f64 = 600.0;

/// Memory the system can still give, bytes (Linux `MemAvailable`; `None`
/// elsewhere).
pub fn available_memory() -> Option<f64> {
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let kb: f64 = info
        .lines()
        .find_map(|l| l.strip_prefix("MemAvailable:"))?
        .trim()
        .trim_end_matches("kB")
        .trim()
        .parse()
        .ok()?;
    Some(kb * 1024.0)
}

/// What the scenario's bodies need against what the machine has.
pub enum Verdict {
    /// Fits (or the machine does not say how much it has).
    Fits,
    /// Streams may bring more than fits, if their bodies accumulate.
    StreamsMayExhaust(String),
    /// The packs and body files alone do not fit.
    DoesNotFit(String),
}

/// Compares the spheres the scenario places (packs and body files, all held
/// at once) and brings in total (with streams) with the available memory.
pub fn verdict(sc: &Scenario) -> Verdict {
    let Some(avail) = available_memory() else {
        return Verdict::Fits;
    };
    let gb = |b: f64| {
        let g = b / 1e9;
        if g < 1e4 {
            format!("{g:.1}")
        } else {
            format!("{g:.2e}")
        }
    };
    let placed = sc.placed_spheres();
    let total = sc.expected_spheres();
    if placed * BYTES_PER_SPHERE > avail {
        return Verdict::DoesNotFit(format!(
            "the packs and body files place {placed:.3e} spheres, which need about {} GB ({BYTES_PER_SPHERE:.0} bytes per sphere), but only {} GB of memory is available; fewer or larger bodies, or a smaller region, fit",
            gb(placed * BYTES_PER_SPHERE),
            gb(avail)
        ));
    }
    if total * BYTES_PER_SPHERE > avail {
        return Verdict::StreamsMayExhaust(format!(
            "the inserts bring {total:.3e} spheres in total, about {} GB if they all stay in the domain ({BYTES_PER_SPHERE:.0} bytes per sphere); {} GB of memory is available, so the run fails if that many accumulate",
            gb(total * BYTES_PER_SPHERE),
            gb(avail)
        ));
    }
    Verdict::Fits
}

/// Prints the verdict on stderr (an error or a warning naming the scenario
/// file); false when the run cannot fit.
pub fn fits(sc: &Scenario) -> bool {
    match verdict(sc) {
        Verdict::Fits => true,
        Verdict::StreamsMayExhaust(m) => {
            errln!("warning: {}: {m}", sc.path.display());
            true
        }
        Verdict::DoesNotFit(m) => {
            errln!("error: {}: {m}", sc.path.display());
            false
        }
    }
}
