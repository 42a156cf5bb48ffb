//! `clump check SCENARIO`: validates a scenario without running it and prints
//! derived quantities (mass properties, Rayleigh time, time step, stages,
//! expected counts, memory estimate). Packings are tried out in a scratch
//! world, so a region that cannot hold its bodies is reported here.

use crate::check_words;
use clap::Args;
use clump_core::insert::pack;
use clump_io::scenario::{self, InsertSpec, Scenario};
use std::path::PathBuf;
use std::process::ExitCode;

/// Arguments of `clump check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// Scenario file (TOML).
    pub scenario: PathBuf,
    /// Skip the trial packing of `kind = "pack"` insertions.
    #[arg(long)]
    pub no_pack: bool,
    /// Also check the scenario for this device: `gpu` names the adapter and
    /// refuses, at the key, what the GPU path does not run yet.
    #[arg(long, value_enum, default_value_t = crate::device::Device::Cpu)]
    pub device: crate::device::Device,
}

/// Rough memory per sphere (bytes): sphere arrays, wall-contact slots and
/// about six neighbour-list pairs with their history.
pub const BYTES_PER_SPHERE: f64 = 1100.0;
/// Rough memory per body (bytes).
pub const BYTES_PER_BODY: f64 = 320.0;

fn human_bytes(b: f64) -> String {
    if b < 1e6 {
        format!("{:.0} kB", b / 1e3)
    } else if b < 1e9 {
        format!("{:.1} MB", b / 1e6)
    } else {
        format!("{:.2} GB", b / 1e9)
    }
}

/// Runs `clump check`.
pub fn run(args: &CheckArgs) -> ExitCode {
    crate::cmd_run::progress::init_logging();
    let sc = match scenario::load(&args.scenario) {
        Ok(s) => s,
        Err(e) => {
            err!("{e}");
            return ExitCode::from(2);
        }
    };
    for w in &sc.warnings {
        err!("{w}");
    }
    report(&sc);
    if !crate::memory::fits(&sc) {
        return ExitCode::from(2);
    }
    if !args.no_pack {
        if let Err(e) = trial_pack(&sc) {
            err!("{e}");
            return ExitCode::from(2);
        }
    }
    if args.device == crate::device::Device::Gpu && !crate::device::check(&sc) {
        return ExitCode::from(2);
    }
    outln!("\nok: {} is valid", args.scenario.display());
    ExitCode::SUCCESS
}

fn report(sc: &Scenario) {
    outln!("scenario {}", sc.path.display());
    outln!("\nmaterials:");
    for (n, m) in sc.material_names.iter().zip(&sc.materials) {
        outln!(
            "  {n:<16} E = {:.3e} Pa  nu = {}  rho = {} kg/m^3",
            m.youngs_modulus,
            m.poisson_ratio,
            m.density
        );
    }
    outln!("\ntemplates (body frame = principal axes, origin at the centre of mass):");
    for t in &sc.templates {
        let tp = &t.template;
        let i = tp.principal_inertia;
        outln!(
            "  {:<16} {:>3} spheres  mass {:.6e} kg  volume {:.6e} m^3  I = ({:.4e}, {:.4e}, {:.4e}) kg m^2  r = [{:.3e}, {:.3e}] m  bounding radius {:.3e} m  material {}",
            t.name,
            tp.spheres.len(),
            tp.mass,
            tp.volume,
            i.x,
            i.y,
            i.z,
            tp.min_radius,
            tp.max_radius,
            tp.bounding_radius,
            sc.material_names[t.material as usize]
        );
        let c = tp.input_center_of_mass;
        println!(
            "  {:<16} centre of mass (input frame) ({:.6e}, {:.6e}, {:.6e}) m{}",
            "",
            c.x,
            c.y,
            c.z,
            if t.given_mass_properties {
                "  (mass, inertia and centre as given)"
            } else {
                ""
            }
        );
    }
    let ts = &sc.time_step;
    outln!("\ntime step:");
    match (ts.rayleigh_time, ts.smallest_radius, &ts.smallest_template) {
        (Some(tr), Some(r), Some(name)) => {
            outln!("  smallest sphere: r = {r:.4e} m (template '{name}'), Rayleigh time t_R = {tr:.4e} s");
            outln!(
                "  dt = {:.4e} s ({}) = {:.3} t_R (refused above {} t_R, warned about above {} t_R)",
                ts.dt,
                if ts.auto {
                    format!("auto, dt_fraction = {}", ts.fraction)
                } else {
                    "explicit".into()
                },
                ts.dt / tr,
                scenario::DT_ERROR_FRACTION,
                scenario::DT_WARN_FRACTION
            );
        }
        _ => outln!("  dt = {:.4e} s (explicit; no templates)", ts.dt),
    }
    if let Some(h) = &sc.heat {
        outln!(
            "  heat ({:?} conductance): thermal stability limit {:.4e} s (template '{}'), dt = {:.3e} of it (refused above 1)",
            h.model.conductance,
            h.stability_limit,
            h.limiting_template,
            ts.dt / h.stability_limit
        );
    }
    if let Some(st) = &ts.stability {
        let limited = ts.auto && ts.dt == scenario::DT_STABLE_FRACTION * st.dt;
        outln!(
            "  damped-contact stability limit dt_c = {:.4e} s (dt = {:.3} dt_c; {}), from {}",
            st.dt,
            ts.dt / st.dt,
            if limited {
                format!(
                    "dt = \"auto\" is limited to {} dt_c by it",
                    scenario::DT_STABLE_FRACTION
                )
            } else {
                format!("warned about above {} dt_c", scenario::DT_STABLE_FRACTION)
            },
            st.contact
        );
    }
    outln!("\nstages:");
    for s in &sc.stages {
        outln!(
            "  {:<16} steps {:>9} .. {:>9}  ({:.4} s .. {:.4} s)",
            s.name,
            s.first_step,
            s.first_step + s.steps,
            s.first_step as f64 * ts.dt,
            (s.first_step + s.steps) as f64 * ts.dt
        );
    }
    outln!(
        "  total: {} steps, {:.4} s simulated",
        sc.total_steps(),
        sc.duration()
    );
    outln!("\ninsertion:");
    for (k, ins) in sc.inserts.iter().enumerate() {
        let stage = &sc.stages[ins.stage].name;
        match &ins.kind {
            InsertSpec::File { bodies } => outln!("  #{} file: {} bodies at the start of stage '{stage}'", k + 1, bodies.len()),
            InsertSpec::Pack { expected_bodies, .. } => {
                outln!("  #{} pack: about {:.0} bodies at the start of stage '{stage}'", k + 1, expected_bodies)
            }
            InsertSpec::Stream { spec, expected_bodies, .. } => outln!(
                "  #{} stream: about {:.0} bodies between t = {:.4} s and {:.4} s (stage '{stage}')",
                k + 1,
                expected_bodies,
                spec.start,
                spec.end.unwrap_or(f64::INFINITY)
            ),
        }
    }
    let (nb, ns) = (sc.expected_bodies(), sc.expected_spheres());
    outln!("  expected in total: {nb:.0} bodies, {ns:.0} spheres");
    outln!("\nwalls:");
    for w in &sc.walls {
        outln!(
            "  {:<16} {}{}",
            w.name,
            check_words::wall(sc, w),
            if w.active { "" } else { " (inactive at start)" }
        );
    }
    if let Ok(world) = sc.build_world() {
        check_words::contacts(sc, &world);
    }
    let mem = ns * BYTES_PER_SPHERE + nb * BYTES_PER_BODY;
    outln!(
        "\nestimated memory: {} (about {:.1} kB per sphere and {:.1} kB per body)",
        human_bytes(mem),
        BYTES_PER_SPHERE / 1e3,
        BYTES_PER_BODY / 1e3
    );
    outln!("\noutput:\n{}", check_words::outputs(sc));
}

/// Tries every file and pack insertion in a scratch world, stage by stage.
fn trial_pack(sc: &Scenario) -> Result<(), scenario::ScenarioError> {
    let mut world = match sc.build_world() {
        Ok(w) => w,
        Err(e) => {
            return Err(scenario::ScenarioError::one(scenario::Diagnostic::new(
                scenario::Severity::Error,
                &sc.path,
                format!("cannot set up the simulation: {e}"),
            )))
        }
    };
    for (k, ins) in sc.inserts.iter().enumerate() {
        match &ins.kind {
            InsertSpec::File { bodies } => {
                for b in bodies {
                    world
                        .add_body(b)
                        .map_err(|e| sc.insert_error(k, e.to_string()))?;
                }
            }
            InsertSpec::Pack { spec, seed, .. } => {
                let t = std::time::Instant::now();
                let rep =
                    pack(&mut world, spec, *seed).map_err(|e| sc.insert_error(k, e.to_string()))?;
                outln!(
                    "trial packing #{}: {} bodies placed, solid fraction {:.3} ({:.2} s)",
                    k + 1,
                    rep.placed,
                    rep.volume_fraction,
                    t.elapsed().as_secs_f64()
                );
            }
            InsertSpec::Stream { .. } => {}
        }
    }
    Ok(())
}
