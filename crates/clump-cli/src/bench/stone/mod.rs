//! `clump bench --case stone-pile | stone-bed | stone-mix`: many-sphere asymmetric
//! stones, side by side with LIGGGHTS, both codes starting from the same
//! initial condition (the tetra-bed way).
//!
//! The stone is LIGGGHTS' own `stone1.multisphere` (50 spheres, radii 2.8 to
//! 10.4 mm, about 56 × 22 × 41 mm; GPL data of Debian's `liggghts-doc`, read
//! from the install and never shipped), or a procedurally made stone of the
//! same size and sphere count (`--stone procedural`), or any `x y z r` file
//! in mm. Material and contact are those of LIGGGHTS' tutorial
//! `multisphere_stone_restitution`: E = 10 MPa, ν = 0.45, ρ = 2500 kg/m³,
//! e = 0.3, μ = 0.5, Hertz–Mindlin with history, dt = 1e-5 s, LIGGGHTS'
//! damping law and no tensile clamp (`limitForce off`), Richardson rotation
//! (LIGGGHTS' `fix multisphere` scheme).
//!
//! The bench writes, in `--work`: the stone shifted to its centre of mass
//! (`stone.xyzr`, m; both codes read it, and LIGGGHTS gets Clump's exact mass
//! and inertia tensor so that both integrate the same body, instead of its
//! Monte-Carlo estimate), the initial condition (`ic.csv`: centre of mass,
//! quaternion mapping the file frame to the world, vz), the Clump scenario
//! (`scenario.toml`) and the LIGGGHTS input (`liggghts/in.stone`, with
//! `liggghts/ins.in` placing each stone at its pose).
//!
//! - **stone pile**: `--stones` (200) stones at random poses (seeded by
//!   `--pose-seed`, no two overlapping) in the tutorial's insertion region, the cylinder r = 0.25 m,
//!   0.1 < z < 0.4 m, moving down at 1 m/s, fall into a cylinder r = 0.26 m
//!   on the floor z = 0. Phase A: the fall; phase B: the pile, timed on its own.
//! - **stone bed**: `--stones` (2000) stones on a loose lattice (each stone
//!   along its principal axes, turned by a random half turn, jittered) in a
//!   box of about 0.6 × 0.6 m are settled by Clump alone (`--bed-settle`
//!   steps; the settled poses are kept in `--work` and reused), and both
//!   codes start from the settled poses at rest: phase A re-settles (the
//!   contact histories start from zero), phase B is the dense bed, timed on
//!   its own.
//! - **stone mix**: the pile with several templates and a size
//!   distribution ([`mix_stones`]): the `--stone` and a procedural stone,
//!   each at 0.75, 1 and 1.25 times its size (number fractions 0.3, 0.4,
//!   0.3 of each shape's half), six templates of 50 spheres.
//!
//! After the rounds the bench compares the physics of the two codes' final
//! states (the last round's): bed height, packing fraction and contacts,
//! computed the same way from the final sphere centres of both. One pile is
//! one sample of a random packing; `scripts/pile-ensemble.py` compares the
//! two codes over several pose seeds.

use super::measure::{median, report, run_liggghts_input, which, Figures};
use super::BenchArgs;
use anyhow::{bail, Context, Result};
use clump_core::shape::template::ClumpTemplate;
use clump_core::shape::Sphere;
use glam::{DQuat, DVec3};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

mod case_files;
mod physics;
mod poses;
mod stone;
pub use case_files::*;
pub use physics::*;
pub use poses::*;
pub use stone::*;

/// LIGGGHTS' stone of the tutorial `multisphere_stone_restitution` (Debian
/// `liggghts-doc`), 50 spheres in mm.
pub const LIGGGHTS_STONE: &str = "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public/multisphere_stone_restitution/data/stone1.multisphere";

/// The stone cases.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StoneCase {
    /// Stones falling into a cylinder.
    Pile,
    /// A dense bed of stones in a box.
    Bed,
    /// Stones of several shapes and sizes falling into a cylinder.
    Mix,
}

impl StoneCase {
    fn name(self) -> &'static str {
        match self {
            StoneCase::Pile => "stone-pile",
            StoneCase::Bed => "stone-bed",
            StoneCase::Mix => "stone-mix",
        }
    }
}

/// Density of the stone, kg/m³ (the tutorial's).
const DENSITY: f64 = 2500.0;
/// Radius of the pile's container, m.
const PILE_WALL_RADIUS: f64 = 0.26;
/// The tutorial's insertion region: cylinder radius, bottom and top, m.
const PILE_REGION: (f64, f64, f64) = (0.25, 0.1, 0.4);
/// The pile's and the mix's default pose seed (`--pose-seed`).
pub const PILE_SEED: u64 = 32452843;
/// Initial velocity of the pile's stones, m/s (the tutorial's).
const PILE_VZ: f64 = -1.0;
/// Side of the bed's box footprint, m (about).
const BED_SIDE: f64 = 0.6;
/// Gap between lattice cells of the bed, m.
const BED_GAP: f64 = 0.002;
/// LIGGGHTS' neighbour skin, m (the tutorial's 4 mm is 1.4 smallest radii;
/// 1 mm keeps its lists as lean as Clump's).
const LIGGGHTS_SKIN: f64 = 0.001;

/// Settles the bed's lattice in Clump alone (`steps` steps) and returns
/// the settled poses at rest. Reuses `settled.csv` in `dir` when its key
/// line matches.
fn settled_bed(
    dir: &Path,
    stone: &Stone,
    n: usize,
    seed: u64,
    steps: u64,
    threads: usize,
) -> Result<(Vec<Pose>, BedBox)> {
    let (lattice, bbox) = bed_lattice(stone, n, seed);
    let key = format!(
        "# settled stone bed: stones {n}, seed {seed}, settle {steps}, stone {} ({} spheres, mass {:.9e})",
        stone.source,
        stone.spheres.len(),
        stone.template.mass
    );
    let cache = dir.join("settled.csv");
    let keyfile = dir.join("settled.key");
    if cache.is_file() && std::fs::read_to_string(&keyfile).ok().as_deref() == Some(key.as_str()) {
        errln!("stone bed: reusing the settled bed {}", cache.display());
        return Ok((read_ic(&cache)?, bbox));
    }
    let prep = dir.join("settle");
    let files = write_case(
        &prep,
        std::slice::from_ref(stone),
        &lattice,
        Geometry::Bed(bbox),
        steps.max(1),
        1,
        false,
    )?;
    errln!(
        "stone bed: settling {n} stones from the lattice in Clump alone, {steps} steps, {threads} threads (once; kept in {})",
        cache.display()
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let t0 = Instant::now();
    let poses = pool.install(|| -> Result<Vec<Pose>> {
        let (mut w, _, _) = super::measure::build_world(&files.scenario, None)?;
        w.prepare()?;
        w.run(steps)?;
        let th = w.thermo();
        errln!(
            "stone bed: settled in {:.0} s: KE {:.3e} J, {} contacts, lost {}",
            t0.elapsed().as_secs_f64(),
            th.kinetic_translational + th.kinetic_rotational,
            th.pair_contacts + th.wall_contacts,
            th.lost_bodies
        );
        if th.lost_bodies > 0 {
            bail!(
                "stone bed: {} stones were lost while settling",
                th.lost_bodies
            );
        }
        let to_body = stone.template.input_to_body;
        let mut order: Vec<usize> = (0..w.bodies().len()).collect();
        order.sort_by_key(|&b| w.bodies().id[b]);
        Ok(order
            .into_iter()
            .map(|b| Pose {
                kind: 0,
                x: w.bodies().position[b],
                // body → world times file → body
                q: (w.bodies().orientation[b] * to_body).normalize(),
                vz: 0.0,
            })
            .collect())
    })?;
    write_ic(&poses, &cache)?;
    std::fs::write(&keyfile, &key)?;
    Ok((poses, bbox))
}

/// What to prepare: stones and steps.
#[derive(Debug, Clone, Copy)]
pub struct Plan {
    /// Number of stones.
    pub n: usize,
    /// Steps of phase A.
    pub na: u64,
    /// Steps of phase B.
    pub nb: u64,
    /// Bed: steps of the Clump-only settling.
    pub settle: u64,
    /// Bed: threads of the settling.
    pub threads: usize,
    /// Clump uses LIGGGHTS' tangential rule.
    pub liggghts_tangential: bool,
    /// Pile and mix: seed of the stones' random poses.
    pub pose_seed: u64,
}

/// Writes the case's files (initial condition, Clump scenario, LIGGGHTS
/// input) into `dir`; for the bed, settles it first (or reuses the settled
/// bed). `stones` are the case's stones with their number fractions (one
/// for the pile and the bed, whose first stone is used). Returns the files,
/// the poses and the floor area under the bed, m².
pub fn prepare(
    case: StoneCase,
    dir: &Path,
    stones: &[(Stone, f64)],
    plan: &Plan,
) -> Result<(CaseFiles, Vec<Pose>, f64)> {
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let Plan {
        n,
        na,
        nb,
        settle,
        threads,
        liggghts_tangential: lt,
        pose_seed,
    } = *plan;
    let (list, fractions): (Vec<Stone>, Vec<f64>) = stones.iter().cloned().unzip();
    match case {
        StoneCase::Pile | StoneCase::Mix => {
            let kinds = kinds_by_fraction(n, &fractions);
            let poses = pile_poses(&list, &kinds, pose_seed)?;
            let files = write_case(dir, &list, &poses, Geometry::Pile, na, nb, lt)?;
            let area = std::f64::consts::PI * PILE_WALL_RADIUS.powi(2);
            Ok((files, poses, area))
        }
        StoneCase::Bed => {
            let stone = &list[..1];
            let (poses, bbox) = settled_bed(dir, &stone[0], n, 2024, settle, threads)?;
            let files = write_case(dir, stone, &poses, Geometry::Bed(bbox), na, nb, lt)?;
            Ok((files, poses, 4.0 * bbox.hx * bbox.hy))
        }
    }
}

/// `clump bench --case stone-pile | stone-bed`.
pub fn run(args: &BenchArgs, case: StoneCase) -> Result<()> {
    let stone = load_stone(&args.stone)?;
    let stones = match case {
        StoneCase::Mix => mix_stones(&stone)?,
        _ => vec![(stone, 1.0)],
    };
    let n = args.stones.unwrap_or(match case {
        StoneCase::Pile | StoneCase::Mix => 200,
        StoneCase::Bed => 2000,
    });
    if n == 0 {
        bail!("--stones: the bench needs at least one stone");
    }
    let (na, nb) = match case {
        StoneCase::Pile | StoneCase::Mix => (args.na.unwrap_or(30000), args.nb.unwrap_or(10000)),
        StoneCase::Bed => (args.na.unwrap_or(2000), args.nb.unwrap_or(10000)),
    };
    let dir = args
        .work
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("out/bench-{}", case.name())));
    let lig = if args.liggghts_rounds > 0 {
        let l = which("liggghts");
        if l.is_none() {
            errln!("liggghts is not installed (apt-get install liggghts): running Clump only");
        }
        l
    } else {
        None
    };
    let (files, poses, footprint) = prepare(
        case,
        &dir,
        &stones,
        &Plan {
            n,
            na,
            nb,
            settle: args.bed_settle,
            threads: args.threads,
            liggghts_tangential: args.liggghts_tangential,
            pose_seed: args.pose_seed,
        },
    )?;
    // spheres of each body in initial-condition order, and in all
    let per_body: Vec<usize> = poses
        .iter()
        .map(|p| stones[p.kind].0.spheres.len())
        .collect();
    let nsph_total: usize = per_body.iter().sum();
    for (k, (s, _)) in stones.iter().enumerate() {
        let count = poses.iter().filter(|p| p.kind == k).count();
        outln!(
            "{}: stone {k}: {count} of {n}, {} spheres ({}; mass {:.4e} kg, bounding radius {:.1} mm)",
            case.name(),
            s.spheres.len(),
            s.source,
            s.template.mass,
            s.template.bounding_radius * 1e3,
        );
    }
    outln!(
        "{}: {n} stones, {nsph_total} spheres, phase A {na} steps, phase B {nb} steps, clump threads {}; files in {}",
        case.name(),
        args.threads,
        dir.display()
    );
    let rounds = args.liggghts_rounds.max(1);
    let (mut clump, mut peer) = (Vec::new(), Vec::new());
    // each round overwrites both codes' final dumps; the last round's are
    // compared after the loop
    let final_dump = dir.join("clump_final.dump");
    for round in 0..rounds {
        let f = super::round::run(&super::round::Round {
            scenario: &files.scenario,
            threads: args.threads,
            skin: args.skin,
            na,
            nb,
            dump: Some(&final_dump),
        })?;
        report("clump", round, na, nb, &f);
        clump.push(f);
        if let Some(bin) = &lig {
            let vars = [("NA", na.to_string()), ("NB", nb.to_string())];
            let f =
                run_liggghts_input(bin, &files.liggghts, "in.stone", &vars, na, nb, nsph_total)?;
            report("liggghts", round, na, nb, &f);
            peer.push(f);
        }
    }
    let cfin = final_from_dump(&final_dump, &per_body)?;
    let lfin = if peer.is_empty() {
        None
    } else {
        Some(final_from_dump(
            &files.liggghts.join("final.dump"),
            &per_body,
        )?)
    };
    let tput = |s: f64, steps: u64| nsph_total as f64 * steps as f64 / s;
    let (ca, cb) = (
        tput(median(&clump, |f| f.a_seconds), na),
        tput(median(&clump, |f| f.b_seconds), nb),
    );
    outln!(
        "clump    (threads {}): phase A {:.3} M sphere-steps/s, phase B {:.3} M sphere-steps/s (medians), peak RSS {:.0} MB",
        args.threads,
        ca / 1e6,
        cb / 1e6,
        median(&clump, |f| f.peak_rss_mb)
    );
    if !peer.is_empty() {
        let (la, lb) = (
            tput(median(&peer, |f| f.a_seconds), na),
            tput(median(&peer, |f| f.b_seconds), nb),
        );
        outln!(
            "liggghts (serial):    phase A {:.3} M sphere-steps/s, phase B {:.3} M sphere-steps/s (medians), peak RSS {:.0} MB",
            la / 1e6,
            lb / 1e6,
            median(&peer, |f| f.peak_rss_mb)
        );
        for (phase, key) in [
            ("A", (|f: &Figures| f.a_seconds) as fn(&Figures) -> f64),
            ("B", |f: &Figures| f.b_seconds),
        ] {
            let mut r: Vec<f64> = clump
                .iter()
                .zip(&peer)
                .map(|(c, l)| key(l) / key(c))
                .collect();
            let list: Vec<String> = r.iter().map(|x| format!("{x:.2}x")).collect();
            r.sort_by(f64::total_cmp);
            outln!(
                "phase {phase} ratio clump/liggghts per round: {}; median {:.2}x",
                list.join(", "),
                r[r.len() / 2]
            );
        }
    }
    // the mean volume of the initial condition's bodies
    let vol = poses
        .iter()
        .map(|p| stones[p.kind].0.template.volume)
        .sum::<f64>()
        / n as f64;
    let pc = physics(&cfin, vol, footprint);
    print_physics("clump", &pc, case);
    if let Some(l) = &lfin {
        let pl = physics(l, vol, footprint);
        print_physics("liggghts", &pl, case);
        let rel = |a: f64, b: f64| 100.0 * (a - b) / b;
        outln!(
            "physics clump vs liggghts: mean sphere height {:+.2} %, surface {:+.2} %, packing fraction {:+.2} %, sphere contacts {:+.2} %, body contacts {:+.2} %",
            rel(pc.mean_z, pl.mean_z),
            rel(pc.surface, pl.surface),
            rel(pc.phi, pl.phi),
            rel(pc.sphere_contacts as f64, pl.sphere_contacts as f64),
            rel(pc.body_contacts as f64, pl.body_contacts as f64)
        );
    }
    Ok(())
}

fn print_physics(code: &str, p: &Physics, case: StoneCase) {
    outln!(
        "physics {code:8}: {} bodies, mean sphere height {:.6} m, surface {:.6} m, {} {:.5}, sphere contacts {}, body contacts {}",
        p.bodies,
        p.mean_z,
        p.surface,
        match case {
            StoneCase::Pile | StoneCase::Mix => {
                "packing fraction (of the container floor, a loose pile)"
            }
            StoneCase::Bed => "packing fraction",
        },
        p.phi,
        p.sphere_contacts,
        p.body_contacts
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("clump-bench-stone-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    /// Writes `case` for `stones` in a temporary folder, and checks that the
    /// LIGGGHTS input and the Clump scenario describe the same bodies: the
    /// spheres Clump builds from scenario.toml sit where LIGGGHTS'
    /// insertions put them (the pose of ins.in applied to the stone file of
    /// the insertion's distribution), and LIGGGHTS gets Clump's mass of
    /// each stone. Returns the folder, the files and the poses.
    fn same_bodies(
        case: StoneCase,
        stones: &[(Stone, f64)],
        n: usize,
        name: &str,
    ) -> (PathBuf, CaseFiles, Vec<Pose>) {
        let d = tmp(name);
        let (files, poses, _) = prepare(
            case,
            &d,
            stones,
            &Plan {
                n,
                na: 10,
                nb: 10,
                settle: 0,
                threads: 1,
                liggghts_tangential: false,
                pose_seed: PILE_SEED,
            },
        )
        .unwrap();
        let ns = stones.len();
        // LIGGGHTS' side: the insertions and the template files it reads
        let ins = std::fs::read_to_string(files.liggghts.join("ins.in")).unwrap();
        let tpl: Vec<Vec<Sphere>> = (0..ns)
            .map(|k| {
                let f = files.liggghts.join(format!("{}.xyzr", stone_name(k, ns)));
                clump_io::template_file::read_template_file(&f).unwrap()
            })
            .collect();
        let mut lig = Vec::new();
        let lines: Vec<&str> = ins.lines().collect();
        for w in lines.windows(2) {
            if !w[0].starts_with("region r") {
                continue;
            }
            let r: Vec<f64> = w[0]
                .split_whitespace()
                .skip(3)
                .take(6)
                .map(|x| x.parse().unwrap())
                .collect();
            let x = DVec3::new(
                0.5 * (r[0] + r[1]),
                0.5 * (r[2] + r[3]),
                0.5 * (r[4] + r[5]),
            );
            let t: Vec<&str> = w[1].split_whitespace().collect();
            let at = |k: &str| t.iter().position(|s| *s == k).unwrap();
            let o = at("constant");
            let o = o + 1 + t[o + 1..].iter().position(|s| *s == "constant").unwrap();
            let q: Vec<f64> = t[o + 1..o + 5].iter().map(|x| x.parse().unwrap()).collect();
            let q = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
            let vz: f64 = t[at("vel") + 4].parse().unwrap();
            assert_eq!(vz, PILE_VZ);
            let pdd = t[at("distributiontemplate") + 1];
            let k: usize = pdd.strip_prefix("pdd").unwrap().parse::<usize>().unwrap() - 1;
            for s in &tpl[k] {
                lig.push(x + q * s.center);
            }
        }
        let total: usize = poses.iter().map(|p| stones[p.kind].0.spheres.len()).sum();
        assert_eq!(lig.len(), total);
        // Clump's side
        let (mut w, na, nb) = super::super::measure::build_world(&files.scenario, None).unwrap();
        assert_eq!((na, nb), (10, 10));
        w.prepare().unwrap();
        assert_eq!(w.templates.len(), ns);
        // as the bench reads Clump's final state back: through its dump
        let dump = d.join("clump_final.dump");
        super::super::measure::write_dump(&w, &dump).unwrap();
        let per_body: Vec<usize> = poses
            .iter()
            .map(|p| stones[p.kind].0.spheres.len())
            .collect();
        let f = final_from_dump(&dump, &per_body).unwrap();
        assert_eq!(f.pos.len(), lig.len());
        for (a, b) in f.pos.iter().zip(&lig) {
            assert!((*a - *b).length() < 1e-9, "{a} vs {b}");
        }
        for b in 0..w.bodies().len() {
            assert!((w.bodies().velocity[b] - DVec3::new(0.0, 0.0, PILE_VZ)).length() < 1e-12);
        }
        let input = std::fs::read_to_string(files.liggghts.join("in.stone")).unwrap();
        for (s, _) in stones {
            assert!(input.contains(&format!("mass {:.9e}", s.template.mass)));
        }
        assert!(input.contains("zcylinder 0.26"));
        (d, files, poses)
    }

    #[test]
    fn liggghts_input_and_clump_scenario_describe_the_same_bodies() {
        let stone = load_stone("procedural").unwrap();
        assert_eq!(stone.spheres.len(), 50);
        let (d, files, _) = same_bodies(StoneCase::Pile, &[(stone.clone(), 1.0)], 20, "same");
        // Clump's own tangential rule unless asked for LIGGGHTS'
        let sc = std::fs::read_to_string(&files.scenario).unwrap();
        assert!(!sc.contains("tangential"));
        let poses = read_ic(&d.join("ic.csv")).unwrap();
        let f = write_case(
            &d.join("lt"),
            std::slice::from_ref(&stone),
            &poses,
            Geometry::Pile,
            1,
            1,
            true,
        )
        .unwrap();
        let sc = std::fs::read_to_string(&f.scenario).unwrap();
        assert!(sc.contains("tangential = \"liggghts\""));
        super::super::measure::build_world(&f.scenario, None).unwrap();
        let _ = std::fs::remove_dir_all(&d);
    }

    /// The mix: six templates (two shapes in three sizes), each body built
    /// by both codes from its own template; the size classes hold the
    /// numbers their fractions give, and each is the stone scaled (mass as
    /// the cube of the scale, from the exact mass properties).
    #[test]
    fn the_mix_gives_each_body_its_own_template_in_both_codes() {
        let stone = load_stone("procedural").unwrap();
        let mix = mix_stones(&stone).unwrap();
        assert_eq!(mix.len(), 6);
        for (k, (s, _)) in mix.iter().enumerate() {
            let (scale, _) = MIX_SIZES[k % 3];
            let base = &mix[3 * (k / 3) + 1].0;
            let r = s.template.mass / base.template.mass;
            assert!(
                (r - scale.powi(3)).abs() < 1e-9 * r,
                "stone {k}: mass ratio {r}"
            );
        }
        let (d, _, poses) = same_bodies(StoneCase::Mix, &mix, 40, "mix");
        let count = |k: usize| poses.iter().filter(|p| p.kind == k).count();
        // 40 stones, half of each shape: 6, 8, 6 of each (0.3, 0.4, 0.3)
        for k in 0..6 {
            assert_eq!(count(k), [6, 8, 6][k % 3], "stone {k}");
        }
        // LIGGGHTS numbers spheres body by body: unequal counts map back
        let dump = d.join("final.dump");
        std::fs::write(
            &dump,
            "ITEM: ATOMS id x y z radius\n1 0 0 0 1\n2 0 0 0 1\n3 0 0 0 1\n4 0 0 0 1\n5 0 0 0 1\n",
        )
        .unwrap();
        let f = final_from_dump(&dump, &[2, 1, 2]).unwrap();
        assert_eq!(f.body, vec![0, 0, 1, 2, 2]);
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_missing_stone_template_is_refused_clearly() {
        let e = load_stone("/nonexistent/stone1.multisphere")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("no stone template file at /nonexistent/stone1.multisphere"),
            "{e}"
        );
        if !Path::new(LIGGGHTS_STONE).is_file() {
            let e = load_stone("liggghts").unwrap_err().to_string();
            assert!(
                e.contains("liggghts-doc") && e.contains("--stone procedural"),
                "{e}"
            );
        }
    }

    /// `--pose-seed`: another seed pours another pile (every stone placed
    /// anew, still inside the region and clear of the others), the same
    /// seed the same pile.
    #[test]
    fn another_pose_seed_pours_another_pile() {
        let stone = load_stone("procedural").unwrap();
        let stones = [stone.clone()];
        let kinds = vec![0; 30];
        let a = pile_poses(&stones, &kinds, PILE_SEED).unwrap();
        let b = pile_poses(&stones, &kinds, 1).unwrap();
        let again = pile_poses(&stones, &kinds, 1).unwrap();
        assert!(b.iter().zip(&again).all(|(p, q)| p.x == q.x && p.q == q.q));
        assert!(a.iter().zip(&b).all(|(p, q)| (p.x - q.x).length() > 1e-3));
        let (rr, z0, z1) = PILE_REGION;
        let spheres: Vec<Vec<Sphere>> = b.iter().map(|p| placed(&stone, p).collect()).collect();
        for (k, sp) in spheres.iter().enumerate() {
            for s in sp {
                assert!(s.center.truncate().length() + s.radius <= rr + 1e-12);
                assert!(s.center.z - s.radius >= z0 - 1e-12 && s.center.z + s.radius <= z1 + 1e-12);
            }
            for other in &spheres[..k] {
                assert!(!overlapping(sp, other));
            }
        }
    }

    /// The bed's lattice holds no overlapping stones and stays in its box.
    #[test]
    fn bed_lattice_is_loose_and_inside() {
        let stone = load_stone("procedural").unwrap();
        let (poses, b) = bed_lattice(&stone, 300, 5);
        assert!(poses.iter().all(|p| p.kind == 0));
        assert_eq!(poses.len(), 300);
        let placed: Vec<Vec<Sphere>> = poses.iter().map(|p| placed(&stone, p).collect()).collect();
        for (i, a) in placed.iter().enumerate() {
            for s in a {
                assert!(s.center.x.abs() + s.radius <= b.hx + 1e-9);
                assert!(s.center.y.abs() + s.radius <= b.hy + 1e-9);
                assert!(s.center.z - s.radius >= 0.0 && s.center.z + s.radius <= b.top);
            }
            for c in &placed[i + 1..] {
                assert!(!overlapping(a, c));
            }
        }
    }
}
