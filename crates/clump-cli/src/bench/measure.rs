//! What the bench's rounds measure and print: the figures of a run (times,
//! peak memory), the tetra-bed world and its end state and fingerprint,
//! LIGGGHTS' run of the same case.

use super::BenchArgs;
use anyhow::{bail, Context, Result};
use clump_core::world::World;
use clump_io::scenario::InsertSpec;
use std::path::{Path, PathBuf};

/// Figures of one timed run.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Figures {
    pub(crate) a_seconds: f64,
    pub(crate) b_seconds: f64,
    pub(crate) spheres: usize,
    pub(crate) peak_rss_mb: f64,
    /// A cache line's round trip between two cores just before and just
    /// after the run, ns (`core_latency`; multi-threaded Clump rounds only).
    pub(crate) cross_core_ns: [Option<f64>; 2],
}

/// The median of `key` over `v` (the upper one of an even count).
pub(crate) fn median(v: &[Figures], key: fn(&Figures) -> f64) -> f64 {
    let mut x: Vec<f64> = v.iter().map(key).collect();
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

pub(crate) fn report(code: &str, round: usize, na: u64, nb: u64, f: &Figures) {
    let ns = f.spheres as f64;
    // which state the host's cores were in (crate::core_latency)
    let cores = match f.cross_core_ns {
        [None, None] => String::new(),
        [before, after] => {
            let shown = |x: Option<f64>| x.map_or("-".into(), |x| format!("{x:.0}"));
            format!(
                "  cross-core round trip {} / {} ns (before / after)",
                shown(before),
                shown(after)
            )
        }
    };
    outln!(
        "round {round} {code}: A {:.2} s ({:.3} M sph-steps/s)  B {:.2} s ({:.3} M sph-steps/s)  peak RSS {:.1} MB{cores}",
        f.a_seconds,
        ns * na as f64 / f.a_seconds / 1e6,
        f.b_seconds,
        ns * nb as f64 / f.b_seconds / 1e6,
        f.peak_rss_mb
    );
}

pub(crate) fn which(name: &str) -> Option<PathBuf> {
    std::env::var_os("PATH").and_then(|p| {
        std::env::split_paths(&p)
            .map(|d| d.join(name))
            .find(|f| f.is_file())
    })
}

/// The benchmark scenario for `n` clumps: `benches/tetra_bed_<n>.toml`.
pub fn scenario_path(args: &BenchArgs) -> PathBuf {
    args.scenario
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("benches/tetra_bed_{}.toml", args.n)))
}

/// Builds the tetra-bed world from its scenario (which reads the shared
/// template and initial-condition files): the scenario's materials, walls
/// and settings, and the bodies of its file insertion. Returns the world and
/// the step counts of its two stages (phase A, phase B).
pub fn build_world(path: &Path, skin: Option<f64>) -> Result<(World, u64, u64)> {
    // the scenario's diagnostic starts with its own "error: ", which the
    // bench's caller prints once for every error
    let sc = clump_io::scenario::load(path).map_err(|e| {
        let text = e.to_string();
        anyhow::anyhow!(
            "{}",
            text.strip_prefix("error: ").unwrap_or(&text).trim_end()
        )
    })?;
    if sc.stages.len() != 2 {
        bail!(
            "{}: the benchmark needs two stages (fall, dense), found {}",
            path.display(),
            sc.stages.len()
        );
    }
    let mut w = sc
        .build_world()
        .map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))?;
    if skin.is_some() {
        w.config.skin = skin;
    }
    for ins in &sc.inserts {
        match &ins.kind {
            InsertSpec::File { bodies } if ins.stage == 0 => {
                for b in bodies {
                    w.add_body(b)?;
                }
            }
            _ => bail!(
                "{}: the benchmark takes its bodies from one file insertion in the first stage",
                path.display()
            ),
        }
    }
    Ok((w, sc.stages[0].steps, sc.stages[1].steps))
}

/// Prints (stderr) the bodies, contacts, lost bodies, kinetic energy and
/// rebuilds of `w` at the end of a timed run, and its state fingerprint.
pub(crate) fn print_end_state(w: &World) {
    let th = w.thermo();
    errln!(
        "clump: {} bodies, {} contacts, lost {}, KE {:.3e} J, rebuilds {}",
        th.bodies,
        th.pair_contacts + th.wall_contacts,
        th.lost_bodies,
        th.kinetic_translational + th.kinetic_rotational,
        w.rebuilds
    );
    errln!("clump: state fingerprint {:016x}", state_fingerprint(w));
}

/// FNV-1a hash of every body's position, velocity, angular momentum and
/// orientation bits (storage order): equal fingerprints mean the same state
/// bit for bit, to compare builds and thread counts.
pub fn state_fingerprint(w: &World) -> u64 {
    let mut h = 0xcbf29ce484222325u64;
    let b = &w.bodies();
    let mut mix = |x: f64| {
        h ^= x.to_bits();
        h = h.wrapping_mul(0x100000001b3);
    };
    for i in 0..b.len() {
        for v in [b.position[i], b.velocity[i], b.angular_momentum[i]] {
            v.to_array().into_iter().for_each(&mut mix);
        }
        b.orientation[i].to_array().into_iter().for_each(&mut mix);
    }
    h
}

/// Final sphere centres in the LIGGGHTS/LAMMPS dump format, ordered by body
/// id, every number as Rust writes f64 (it reads back exactly).
pub(crate) fn write_dump(w: &World, path: &Path) -> Result<()> {
    use std::fmt::Write;
    let sp = w.spheres();
    let mut order: Vec<usize> = (0..w.bodies().len()).collect();
    order.sort_by_key(|&b| w.bodies().id[b]);
    let mut s = String::new();
    writeln!(
        s,
        "ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{}",
        w.step,
        sp.len()
    )?;
    let d = w.config.domain;
    writeln!(
        s,
        "ITEM: BOX BOUNDS ff ff ff\n{} {}\n{} {}\n{} {}",
        d.lo.x, d.hi.x, d.lo.y, d.hi.y, d.lo.z, d.hi.z
    )?;
    writeln!(s, "ITEM: ATOMS id mol x y z radius")?;
    let mut id = 1;
    for b in order {
        for k in sp.of_body(b) {
            let x = sp.position(k);
            writeln!(
                s,
                "{id} {} {:e} {:e} {:e} {:e}",
                w.bodies().id[b],
                x.x,
                x.y,
                x.z,
                sp.radius[k]
            )?;
            id += 1;
        }
    }
    std::fs::write(path, s)?;
    Ok(())
}

/// CPU time (user + system, all threads) of this process so far, s (Linux
/// /proc/self/stat, 100 ticks per second): a load-independent companion of
/// the wall times on a shared machine.
pub(crate) fn cpu_seconds() -> f64 {
    std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // the command name may hold spaces: fields after the last ')'
            let rest = &s[s.rfind(')')? + 2..];
            let f: Vec<&str> = rest.split_whitespace().collect();
            Some((f.get(11)?.parse::<f64>().ok()? + f.get(12)?.parse::<f64>().ok()?) / 100.0)
        })
        .unwrap_or(f64::NAN)
}

/// Peak resident set size of this process so far, MB (Linux VmHWM).
pub(crate) fn peak_rss_mb() -> f64 {
    proc_status_mb("VmHWM:")
}

/// Resident memory of this process now, MB (Linux; NaN elsewhere).
pub(super) fn current_rss_mb() -> f64 {
    proc_status_mb("VmRSS:")
}

/// A memory figure of `/proc/self/status` (its line `key`), MB.
fn proc_status_mb(key: &str) -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with(key))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

pub(super) fn run_liggghts(args: &BenchArgs, bin: &Path, na: u64, nb: u64) -> Result<Figures> {
    let work = std::env::temp_dir().join(format!("clump-bench-liggghts-{}", std::process::id()));
    // the shared layout: the case files in the folder, the LIGGGHTS input
    // in liggghts/ (gen_liggghts.py reads ../ic_N.txt)
    let run_dir = work.join("liggghts");
    std::fs::create_dir_all(&run_dir)?;
    let src = args.dir.join("liggghts");
    for f in ["in.bench", "tetra.multisphere", "gen_liggghts.py"] {
        std::fs::copy(src.join(f), run_dir.join(f))
            .with_context(|| format!("copying {}", src.join(f).display()))?;
    }
    for f in std::fs::read_dir(&args.dir)? {
        let p = f?.path();
        if let (true, Some(name)) = (p.is_file(), p.file_name()) {
            std::fs::copy(&p, work.join(name))?;
        }
    }
    let work_root = work;
    let work = run_dir;
    let ztop = if args.n <= 2000 { "0.2" } else { "0.31" };
    let ok = std::process::Command::new("python3")
        .arg("gen_liggghts.py")
        .arg(args.n.to_string())
        .current_dir(&work)
        .status()?;
    if !ok.success() {
        bail!("gen_liggghts.py failed");
    }
    let vars = [
        ("N", args.n.to_string()),
        ("ZTOP", ztop.to_string()),
        ("NA", na.to_string()),
        ("NB", nb.to_string()),
    ];
    // the insertion include runs many 1-step loops first; phase A and B are
    // the last loops of NA and NB steps
    let figures = run_liggghts_input(bin, &work, "in.bench", &vars, na, nb, 4 * args.n)?;
    if let Some(p) = &args.dump {
        let f = work.join(format!("final_{}.dump", args.n));
        let _ = std::fs::copy(f, p.with_extension("liggghts.dump"));
    }
    let _ = std::fs::remove_dir_all(&work_root);
    Ok(figures)
}

/// Runs LIGGGHTS on `input` in `dir` with `vars` (`-var NAME VALUE`),
/// under `/usr/bin/time` for its peak memory; phase A and B are the last
/// loops of `na` and `nb` steps.
pub(crate) fn run_liggghts_input(
    bin: &Path,
    dir: &Path,
    input: &str,
    vars: &[(&str, String)],
    na: u64,
    nb: u64,
    spheres: usize,
) -> Result<Figures> {
    let mut cmd = std::process::Command::new("/usr/bin/time");
    cmd.args(["-f", "MAXRSS_KB %M"])
        .arg(bin)
        .args(["-in", input]);
    for (k, v) in vars {
        cmd.args(["-var", k, v]);
    }
    let out = cmd
        .current_dir(dir)
        .output()
        .with_context(|| format!("running {} under /usr/bin/time", bin.display()))?;
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    // "Loop time of T on P procs for N steps with M atoms": phase B is the
    // last loop of `nb` steps, phase A the last loop of `na` steps before it
    // (also when na = nb)
    let loops: Vec<(u64, f64)> = text
        .lines()
        .filter(|l| l.starts_with("Loop time of"))
        .filter_map(|l| {
            let w: Vec<&str> = l.split_whitespace().collect();
            Some((w.get(8)?.parse().ok()?, w.get(3)?.parse().ok()?))
        })
        .collect();
    let ib = loops.iter().rposition(|l| l.0 == nb);
    let ia = ib.and_then(|ib| loops[..ib].iter().rposition(|l| l.0 == na));
    let rss = text
        .lines()
        .find(|l| l.starts_with("MAXRSS_KB"))
        .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        .unwrap_or(f64::NAN)
        / 1024.0;
    match (ia, ib) {
        (Some(a), Some(b)) if out.status.success() => Ok(Figures {
            a_seconds: loops[a].1,
            b_seconds: loops[b].1,
            spheres,
            peak_rss_mb: rss,
            cross_core_ns: [None; 2],
        }),
        _ => bail!(
            "LIGGGHTS failed or its loop times could not be read (input {}); its output ends with:\n{}",
            dir.join(input).display(),
            text.lines()
                .rev()
                .take(20)
                .collect::<Vec<_>>()
                .into_iter()
                .rev()
                .collect::<Vec<_>>()
                .join("\n")
        ),
    }
}
