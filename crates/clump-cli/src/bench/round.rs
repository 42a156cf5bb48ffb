//! One timed Clump round of `clump bench`, run in a process of its own.
//!
//! The bench runs every Clump round (tetra bed and stones) as a child
//! `clump bench --child-round …`, as it runs every LIGGGHTS round as a
//! process of its own. A round's peak memory is then that of a fresh
//! process, as a user's `clump run` sees it. Run one after another in the
//! long-lived bench process, the rounds inherited the heap and allocator
//! state of the rounds before them: on the tetra bed on two threads the
//! peak rose from 12.9 MB in the first round to 14.8 and 18.5 MB in the
//! next ones, although each round started with the peak reset to the
//! resident set of the moment.
//!
//! The child prints its figures as one line on stdout (`clump-round A B
//! SPHERES PEAK_MB`, numbers as Rust writes f64, which reads back exactly)
//! and its diagnostics (CPU times, stage shares, end state, fingerprint)
//! on stderr, which the bench passes through.

use super::measure::{build_world, cpu_seconds, peak_rss_mb, print_end_state, write_dump, Figures};
use super::BenchArgs;
use anyhow::{bail, Context, Result};
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

/// What one round runs.
pub(crate) struct Round<'a> {
    /// The Clump scenario; its first two stages' step counts are not used.
    pub scenario: &'a Path,
    /// Threads of the round's rayon pool.
    pub threads: usize,
    /// Verlet skin, m (None: the engine's).
    pub skin: Option<f64>,
    /// Steps of phase A, then of phase B (timed on its own).
    pub na: u64,
    pub nb: u64,
    /// Where the round writes its final sphere centres (LIGGGHTS dump
    /// format, full precision), if anywhere.
    pub dump: Option<&'a Path>,
}

/// The word that starts the child's figures line.
const TAG: &str = "clump-round";

/// Runs `round` in a child process of this executable; its figures.
pub(crate) fn run(round: &Round) -> Result<Figures> {
    // the host's state around a multi-threaded round (crate::core_latency)
    let probe = || {
        (round.threads >= 2)
            .then(crate::core_latency::round_trip_ns)
            .flatten()
    };
    let before = probe();
    let exe = std::env::current_exe().context("finding the clump executable for a bench round")?;
    let mut cmd = Command::new(&exe);
    cmd.args(["bench", "--child-round", "--scenario"])
        .arg(round.scenario)
        .arg("--threads")
        .arg(round.threads.to_string())
        .arg("--na")
        .arg(round.na.to_string())
        .arg("--nb")
        .arg(round.nb.to_string());
    if let Some(s) = round.skin {
        cmd.arg("--skin").arg(s.to_string());
    }
    if let Some(d) = round.dump {
        cmd.arg("--dump").arg(d);
    }
    let out = cmd
        .stdin(Stdio::null())
        .stderr(Stdio::inherit())
        .output()
        .with_context(|| format!("starting {} for a bench round", exe.display()))?;
    if !out.status.success() {
        bail!(
            "the Clump round (`{} bench --child-round`, scenario {}) failed ({}); its error is printed above",
            exe.display(),
            round.scenario.display(),
            out.status
        );
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let f = parse_figures(&text).with_context(|| {
        format!("the Clump round printed no `{TAG}` line of four numbers; it printed:\n{text}")
    })?;
    Ok(Figures {
        cross_core_ns: [before, probe()],
        ..f
    })
}

/// The figures of a child's `clump-round` line.
fn parse_figures(text: &str) -> Option<Figures> {
    let line = text.lines().rev().find(|l| l.starts_with(TAG))?;
    let v: Vec<f64> = line
        .split_whitespace()
        .skip(1)
        .map(|x| x.parse().ok())
        .collect::<Option<_>>()?;
    match v[..] {
        [a, b, spheres, peak] => Some(Figures {
            a_seconds: a,
            b_seconds: b,
            spheres: spheres as usize,
            peak_rss_mb: peak,
            cross_core_ns: [None; 2],
        }),
        _ => None,
    }
}

/// The child's side (`clump bench --child-round`): runs the round in this
/// process and prints its figures line.
pub(crate) fn child(args: &BenchArgs) -> Result<()> {
    let (Some(scenario), Some(na), Some(nb)) = (&args.scenario, args.na, args.nb) else {
        bail!("--child-round (one timed round, which the bench runs in a process of its own) needs --scenario, --na and --nb");
    };
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()?;
    let f = pool.install(|| -> Result<Figures> {
        let (mut w, _, _) = build_world(scenario, args.skin)?;
        w.prepare()?;
        let (t0, c0) = (Instant::now(), cpu_seconds());
        w.run(na)?;
        let (a, ca) = (t0.elapsed().as_secs_f64(), cpu_seconds() - c0);
        w.stage_times = Default::default();
        let (t1, c1, r1) = (Instant::now(), cpu_seconds(), w.rebuilds);
        w.run(nb)?;
        let (b, cb) = (t1.elapsed().as_secs_f64(), cpu_seconds() - c1);
        let ns = w.spheres().len() as f64;
        errln!(
            "clump: CPU time (all threads) phase A {ca:.2} s ({:.3} M sph-steps per CPU s), phase B {cb:.2} s ({:.3} M sph-steps per CPU s)",
            ns * na as f64 / ca / 1e6,
            ns * nb as f64 / cb / 1e6
        );
        let st = w.stage_times;
        let total = st.rows().iter().map(|r| r.1).sum::<f64>().max(1e-12);
        let shares: Vec<String> = st
            .rows()
            .iter()
            .map(|(name, t)| format!("{name} {:.1} %", 100.0 * t / total))
            .collect();
        errln!(
            "clump: phase B by stage: {} ({total:.2} s of {b:.2} s wall; {} rebuilds, skin {:.3} mm at the end, {:.1} ns per sphere-step)",
            shares.join(", "),
            w.rebuilds - r1,
            w.skin() * 1e3,
            1e9 * b / (ns * nb.max(1) as f64)
        );
        print_end_state(&w);
        if let Some(p) = &args.dump {
            write_dump(&w, p)?;
        }
        Ok(Figures {
            a_seconds: a,
            b_seconds: b,
            spheres: w.spheres().len(),
            peak_rss_mb: peak_rss_mb(),
            cross_core_ns: [None; 2],
        })
    })?;
    outln!(
        "{TAG} {} {} {} {}",
        f.a_seconds,
        f.b_seconds,
        f.spheres,
        f.peak_rss_mb
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_figures_line_reads_back_exactly() {
        let (a, b, peak) = (0.1 + 0.2, 1.0 / 3.0, 12.9375);
        let text = format!("noise\n{TAG} {a} {b} 8000 {peak}\n");
        let f = parse_figures(&text).unwrap();
        assert_eq!(
            (f.a_seconds, f.b_seconds, f.spheres, f.peak_rss_mb),
            (a, b, 8000, peak)
        );
        assert!(parse_figures("clump-round 1 2 3\n").is_none());
        assert!(parse_figures("clump-round 1 2 x 4\n").is_none());
        assert!(parse_figures("nothing\n").is_none());
    }
}
