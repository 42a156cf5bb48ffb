//! `clump template FILE [--density RHO] [--scale S] [--json]`: mass properties
//! of a multi-sphere template file (LIGGGHTS `x y z r` format), computed
//! exactly for the union of the spheres, with the seed's naive sums for
//! comparison.

use std::fmt;
use std::io::Write;
use std::path::PathBuf;

use clump_core::shape::{mass_properties, union_sphere_indices, MassProperties, Sphere};
use clump_io::template_file::read_template_file;
use glam::DVec3;

/// Arguments of `clump template`.
#[derive(Debug, Clone, clap::Args)]
pub struct TemplateArgs {
    /// Template file: one sphere per line `x y z r` (m after scaling), `#` comments.
    pub file: PathBuf,
    /// Density, kg/m³.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub density: f64,
    /// Factor applied to all lengths of the file before anything else.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub scale: f64,
    /// Print one JSON object (keys: volume, mass, center_of_mass, inertia,
    /// principal_moments, principal_axes, naive_volume,
    /// naive_principal_moments, relative_error_bound).
    #[arg(long)]
    pub json: bool,
}

/// Bad user input (unreadable or malformed file, invalid density or scale,
/// degenerate template). The program should exit with status 2 on it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct InputError(pub String);

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for InputError {}

/// Runs `clump template`; on bad input prints `error: …` to stderr and exits
/// the process with status 2. Other failures (e.g. writing stdout) are
/// returned.
pub fn run(args: &TemplateArgs) -> anyhow::Result<()> {
    match execute(args) {
        Err(e) if e.downcast_ref::<InputError>().is_some() => {
            eprintln!("error: {e}");
            std::process::exit(2);
        }
        // A closed pipe (e.g. `clump template F | head`) is not an error.
        Err(e)
            if e.downcast_ref::<std::io::Error>()
                .is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe) =>
        {
            Ok(())
        }
        other => other,
    }
}

/// Like [`run`] but returns bad input as an [`InputError`] inside the
/// `anyhow::Error` (downcastable) instead of exiting.
pub fn execute(args: &TemplateArgs) -> anyhow::Result<()> {
    let (spheres, props) = compute(args)?;
    let mut out = std::io::stdout().lock();
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&to_json(&props))?)?;
    } else {
        write_table(&mut out, args, &spheres, &props)?;
    }
    Ok(())
}

/// Reads, scales and integrates the template: returns the scaled spheres (m,
/// input frame) and their mass properties (SI, input frame).
pub fn compute(args: &TemplateArgs) -> Result<(Vec<Sphere>, MassProperties), InputError> {
    if !args.scale.is_finite() || args.scale <= 0.0 {
        return Err(InputError(format!(
            "--scale must be finite and > 0, found {}",
            args.scale
        )));
    }
    if !args.density.is_finite() || args.density <= 0.0 {
        return Err(InputError(format!(
            "--density must be finite and > 0 (kg/m³), found {}",
            args.density
        )));
    }
    let spheres: Vec<Sphere> = read_template_file(&args.file)
        .map_err(|e| InputError(e.to_string()))?
        .into_iter()
        .map(|s| Sphere::new(s.center * args.scale, s.radius * args.scale))
        .collect();
    let props = mass_properties(&spheres, args.density)
        .map_err(|e| InputError(format!("{}: {e}", args.file.display())))?;
    Ok((spheres, props))
}

fn rows(m: &glam::DMat3) -> [[f64; 3]; 3] {
    [
        m.row(0).to_array(),
        m.row(1).to_array(),
        m.row(2).to_array(),
    ]
}

/// The JSON object printed by `--json` (exactly the documented keys; SI
/// units, input frame, matrices as arrays of rows).
pub fn to_json(p: &MassProperties) -> serde_json::Value {
    serde_json::json!({
        "volume": p.volume,
        "mass": p.mass,
        "center_of_mass": p.center_of_mass.to_array(),
        "inertia": rows(&p.inertia),
        "principal_moments": p.principal_moments.to_array(),
        "principal_axes": rows(&p.principal_axes),
        "naive_volume": p.naive_volume,
        "naive_principal_moments": p.naive_principal_moments.to_array(),
        "relative_error_bound": p.relative_error_bound,
    })
}

fn pct(naive: f64, exact: f64) -> String {
    format!("{:+.3} %", (naive - exact) / exact * 100.0)
}

fn vec3(v: DVec3) -> String {
    format!("({:+.9e}, {:+.9e}, {:+.9e})", v.x, v.y, v.z)
}

fn write_table(
    out: &mut impl Write,
    args: &TemplateArgs,
    spheres: &[Sphere],
    p: &MassProperties,
) -> std::io::Result<()> {
    let kept = union_sphere_indices(spheres).len();
    writeln!(out, "template           {}", args.file.display())?;
    writeln!(
        out,
        "spheres            {} ({} on the union boundary; others duplicate or lie inside another)",
        spheres.len(),
        kept
    )?;
    writeln!(out, "scale              {}", args.scale)?;
    writeln!(out, "density            {} kg/m^3", args.density)?;
    writeln!(out)?;
    writeln!(
        out,
        "{:<30}{:>18}{:>18}{:>12}",
        "", "exact (union)", "naive (sum)", "naive err"
    )?;
    let naive_mass = p.naive_volume * args.density;
    writeln!(
        out,
        "{:<30}{:>18.9e}{:>18.9e}{:>12}",
        "volume [m^3]",
        p.volume,
        p.naive_volume,
        pct(p.naive_volume, p.volume)
    )?;
    writeln!(
        out,
        "{:<30}{:>18.9e}{:>18.9e}{:>12}",
        "mass [kg]",
        p.mass,
        naive_mass,
        pct(naive_mass, p.mass)
    )?;
    for k in 0..3 {
        writeln!(
            out,
            "{:<30}{:>18.9e}{:>18.9e}{:>12}",
            format!("principal moment I{} [kg m^2]", k + 1),
            p.principal_moments[k],
            p.naive_principal_moments[k],
            pct(p.naive_principal_moments[k], p.principal_moments[k])
        )?;
    }
    writeln!(out)?;
    writeln!(
        out,
        "centre of mass [m] (input frame)      {}",
        vec3(p.center_of_mass)
    )?;
    writeln!(out, "inertia about the COM [kg m^2] (input frame):")?;
    for k in 0..3 {
        writeln!(out, "  {}", vec3(p.inertia.row(k)))?;
    }
    writeln!(out, "principal axes (unit, input frame, right-handed):")?;
    for k in 0..3 {
        writeln!(out, "  e{} = {}", k + 1, vec3(p.principal_axis(k)))?;
    }
    writeln!(out, "relative error bound  {:.2e}", p.relative_error_bound)?;
    Ok(())
}
