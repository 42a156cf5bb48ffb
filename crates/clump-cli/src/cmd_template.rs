//! `clump template FILE [--density RHO] [--scale S] [--json]`: mass properties
//! of a multi-sphere template file (LIGGGHTS `x y z r` format), computed
//! exactly for the union of the spheres, with the naive sums (docs/theory.md T-9) for
//! comparison.
//!
//! `clump template --from-mesh MESH.stl [--spheres N | --tolerance T]
//! [--resolution DIV] [--overlap O] [--min-radius R] [--scale S] [--out PATH]
//! [--json]`: generates a template from a closed STL/OBJ mesh by the CLUMP
//! Euclidean-map method (Angelidakis et al. 2021, see
//! `clump_core::shape::from_mesh`), writes it as `x y z r` lines (m, mesh
//! frame) to `--out` or stdout, and reports its fidelity against the mesh's
//! exact polyhedral mass properties (to stdout with `--out`, else stderr).

use std::fmt;
use std::io::Write;
use std::path::PathBuf;

use clump_core::shape::from_mesh::{fidelity, generate, Fidelity, FromMeshOptions};
use clump_core::shape::{mass_properties, union_sphere_indices, MassProperties, Sphere};
use clump_io::mesh_file::{read_mesh_file, MeshTransform};
use clump_io::template_file::read_template_file;
use glam::DVec3;

/// Arguments of `clump template`.
#[derive(Debug, Clone, clap::Args)]
pub struct TemplateArgs {
    /// Template file: one sphere per line `x y z r` (m after scaling), `#`
    /// comments. Not used with `--from-mesh`.
    #[arg(required_unless_present = "from_mesh", conflicts_with = "from_mesh")]
    pub file: Option<PathBuf>,
    /// Generate a template from this closed mesh (`.stl` ASCII/binary or
    /// `.obj`) instead of reading one.
    #[arg(long, value_name = "MESH")]
    pub from_mesh: Option<PathBuf>,
    /// With `--from-mesh`: largest number of spheres (default 50, or 1000
    /// when only --tolerance is given).
    #[arg(long, value_name = "N")]
    pub spheres: Option<usize>,
    /// With `--from-mesh`: stop when the spheres leave at most this fraction
    /// of the interior uncovered (estimated relative volume deficit).
    #[arg(long, value_name = "T")]
    pub tolerance: Option<f64>,
    /// With `--from-mesh`: voxels along the shortest bounding-box edge.
    #[arg(long, default_value_t = 50, value_name = "DIV")]
    pub resolution: usize,
    /// With `--from-mesh`: overlap fraction in [0, 1) between a new sphere
    /// and earlier ones (fraction of the earlier radius).
    #[arg(long, default_value_t = 0.6, value_name = "O")]
    pub overlap: f64,
    /// With `--from-mesh`: smallest sphere radius, m (after scaling).
    #[arg(long, default_value_t = 0.0, value_name = "R")]
    pub min_radius: f64,
    /// With `--from-mesh`: passes of the least-squares radius refinement
    /// against the surface (0: pure CLUMP placement, all spheres inscribed).
    #[arg(long, default_value_t = 20, value_name = "K")]
    pub refine: usize,
    /// With `--from-mesh`: write the template (`x y z r` lines) here instead of stdout.
    #[arg(long, value_name = "PATH")]
    pub out: Option<PathBuf>,
    /// Density, kg/m³.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub density: f64,
    /// Factor applied to all lengths of the file before anything else.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub scale: f64,
    /// Mass override, kg (needs --inertia), as a scenario template's `mass`.
    #[arg(long, value_name = "KG", allow_negative_numbers = true)]
    pub mass: Option<f64>,
    /// Inertia tensor override about the centre of mass, input frame, kg m²:
    /// `Ixx,Ixy,Ixz,Iyy,Iyz,Izz` (LIGGGHTS' `inertia_tensor` order; needs --mass).
    #[arg(
        long,
        value_name = "I6",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    pub inertia: Option<Vec<f64>>,
    /// Centre of mass override, input frame, m (after --scale): `x,y,z`;
    /// the inertia is taken about it (needs --mass and --inertia).
    #[arg(
        long,
        value_name = "XYZ",
        value_delimiter = ',',
        allow_negative_numbers = true
    )]
    pub center_of_mass: Option<Vec<f64>>,
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
    // progress of a slow integration (templates of 10⁴ spheres) on stderr
    crate::cmd_run::progress::init_logging();
    match execute(args) {
        Err(e) if e.downcast_ref::<InputError>().is_some() => {
            errln!("error: {e}");
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
    if let Some(mesh) = &args.from_mesh {
        return from_mesh(args, mesh);
    }
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
    let file = args
        .file
        .as_ref()
        .ok_or_else(|| InputError("a template FILE (or --from-mesh MESH) is required".into()))?;
    let spheres: Vec<Sphere> = read_template_file(file)
        .map_err(|e| InputError(e.to_string()))?
        .into_iter()
        .map(|s| Sphere::new(s.center * args.scale, s.radius * args.scale))
        .collect();
    let props = mass_properties(&spheres, args.density)
        .map_err(|e| InputError(format!("{}: {e}", file.display())))?;
    Ok((spheres, overrides(args, props)?))
}

/// Applies `--mass`, `--inertia` and `--center-of-mass` to `props`.
fn overrides(args: &TemplateArgs, props: MassProperties) -> Result<MassProperties, InputError> {
    for (name, v, n) in [
        ("--inertia", &args.inertia, 6),
        ("--center-of-mass", &args.center_of_mass, 3),
    ] {
        if let Some(v) = v.as_ref().filter(|v| v.len() != n) {
            return Err(InputError(format!(
                "{name} takes {n} comma-separated numbers, found {}",
                v.len()
            )));
        }
    }
    let mut props = match (args.mass, &args.inertia) {
        (None, None) => props,
        (Some(m), Some(i)) => {
            let t = glam::DMat3::from_cols_array_2d(&[
                [i[0], i[1], i[2]],
                [i[1], i[3], i[4]],
                [i[2], i[4], i[5]],
            ]);
            props
                .with_override(m, t)
                .map_err(|e| InputError(format!("--mass/--inertia: {e}")))?
        }
        _ => return Err(InputError("--mass and --inertia go together".into())),
    };
    if let Some(c) = &args.center_of_mass {
        if args.mass.is_none() {
            return Err(InputError(
                "--center-of-mass needs --mass and --inertia (the inertia is taken about it)"
                    .into(),
            ));
        }
        let c = DVec3::new(c[0], c[1], c[2]);
        if !c.is_finite() {
            return Err(InputError(format!(
                "--center-of-mass must be finite, found {c}"
            )));
        }
        props.center_of_mass = c;
    }
    Ok(props)
}

/// The JSON object printed by `--json` (exactly the documented keys; SI
/// units, input frame, matrices as arrays of rows).
pub fn to_json(p: &MassProperties) -> serde_json::Value {
    clump_io::template_json::mass_properties_json(p)
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
    let name = args
        .file
        .as_ref()
        .map_or(String::new(), |f| f.display().to_string());
    writeln!(out, "template           {name}")?;
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
    let given = |on: bool| if on { "  (given)" } else { "" };
    if args.mass.is_some() {
        writeln!(
            out,
            "given (override the exact column's mass and moments): mass {:.9e} kg",
            p.mass
        )?;
    }
    writeln!(
        out,
        "centre of mass [m] (input frame)      {}{}",
        vec3(p.center_of_mass),
        given(args.center_of_mass.is_some())
    )?;
    writeln!(
        out,
        "inertia about the COM [kg m^2] (input frame):{}",
        given(args.inertia.is_some())
    )?;
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

/// Bytes the sphere generation may need per voxel of the bounding box (an
/// interior voxel's centre, distance, ordering key and flags, with the
/// growth slack of their vectors).
const BYTES_PER_VOXEL: f64 = 64.0;

/// Refuses a `--resolution` whose voxel grid (the mesh's bounding box in
/// cubes of its smallest extent / `resolution`) needs more memory than is
/// available, saying how much it needs and which resolution fits, instead
/// of aborting on allocation.
fn voxel_memory_fits(mesh: &clump_core::wall::TriMesh, resolution: usize) -> anyhow::Result<()> {
    let (lo, hi) = mesh.bounds();
    let ext = hi - lo;
    let h = ext.min_element() / resolution as f64;
    if !(h > 0.0) {
        return Ok(()); // flat mesh: generate() reports it
    }
    let voxels = (ext.x / h).ceil() * (ext.y / h).ceil() * (ext.z / h).ceil();
    let need = voxels * BYTES_PER_VOXEL;
    if let Some(avail) = crate::memory::available_memory() {
        if need > avail {
            // memory grows as resolution³
            let fits = (resolution as f64 * (avail / need).cbrt()).floor();
            return Err(InputError(format!(
                "--resolution {resolution} needs about {:.1} GB for {voxels:.3e} voxels, but only {:.1} GB of memory is available; use --resolution {fits:.0} or less",
                need / 1e9,
                avail / 1e9
            ))
            .into());
        }
    }
    Ok(())
}

/// `--from-mesh`: generate, write the spheres, report the fidelity.
fn from_mesh(args: &TemplateArgs, path: &std::path::Path) -> anyhow::Result<()> {
    if !args.scale.is_finite() || args.scale <= 0.0 {
        return Err(InputError(format!(
            "--scale must be finite and > 0, found {}",
            args.scale
        ))
        .into());
    }
    let tr = MeshTransform {
        scale: args.scale,
        ..Default::default()
    };
    let mesh = read_mesh_file(path, &tr).map_err(|e| InputError(e.to_string()))?;
    let opt = FromMeshOptions {
        max_spheres: args
            .spheres
            .unwrap_or(if args.tolerance.is_some() { 1000 } else { 50 }),
        tolerance: args.tolerance,
        resolution: args.resolution,
        overlap: args.overlap,
        min_radius: args.min_radius,
        refine_iterations: args.refine,
    };
    let dropped = mesh.dropped_triangles();
    let bad_mesh = |e: &dyn std::fmt::Display| {
        let note = if dropped > 0 {
            format!(" ({dropped} zero-area triangles were dropped on reading)")
        } else {
            String::new()
        };
        InputError(format!("{}: {e}{note}", path.display()))
    };
    voxel_memory_fits(&mesh, args.resolution)?;
    let t0 = std::time::Instant::now();
    let spheres = generate(&mesh, &opt).map_err(|e| bad_mesh(&e))?;
    let elapsed = t0.elapsed().as_secs_f64();
    let fid = fidelity(&mesh, &spheres, 20_000).map_err(|e| bad_mesh(&e))?;
    let mut text = format!(
        "# clump template generated from {} (CLUMP Euclidean-map method, Angelidakis et al. 2021)\n\
         # spheres {}, resolution {}, overlap {}, refinement passes {}, scale {}; x y z r in m, mesh frame\n",
        path.display(),
        spheres.len(),
        opt.resolution,
        opt.overlap,
        opt.refine_iterations,
        args.scale
    );
    for s in &spheres {
        text.push_str(&format!(
            "{:.9e} {:.9e} {:.9e} {:.9e}\n",
            s.center.x, s.center.y, s.center.z, s.radius
        ));
    }
    let report = if args.json {
        serde_json::to_string_pretty(&fidelity_json(&fid, spheres.len(), elapsed))? + "\n"
    } else {
        fidelity_table(path, &fid, spheres.len(), elapsed)
    };
    match &args.out {
        Some(out) => {
            std::fs::write(out, text)
                .map_err(|e| anyhow::anyhow!("{}: cannot write template: {e}", out.display()))?;
            std::io::stdout().lock().write_all(report.as_bytes())?;
        }
        None => {
            std::io::stdout().lock().write_all(text.as_bytes())?;
            std::io::stderr().lock().write_all(report.as_bytes())?;
        }
    }
    Ok(())
}

/// The fidelity report as JSON (SI units, mesh frame, unit density).
pub fn fidelity_json(f: &Fidelity, n: usize, seconds: f64) -> serde_json::Value {
    clump_io::template_json::fidelity_json(f, n, seconds)
}

fn fidelity_table(path: &std::path::Path, f: &Fidelity, n: usize, seconds: f64) -> String {
    let mut s = String::new();
    let mut line = |l: String| {
        s.push_str(&l);
        s.push('\n');
    };
    line(format!("mesh               {}", path.display()));
    line(format!(
        "spheres            {n} (generated in {seconds:.2} s)"
    ));
    line(format!(
        "{:<34}{:>16}{:>16}{:>12}",
        "(unit density, mesh frame)", "mesh (exact)", "clump", "error"
    ));
    line(format!(
        "{:<34}{:>16.6e}{:>16.6e}{:>12}",
        "volume [m^3]",
        f.mesh.volume,
        f.clump.volume,
        pct(f.clump.volume, f.mesh.volume)
    ));
    for k in 0..3 {
        line(format!(
            "{:<34}{:>16.6e}{:>16.6e}{:>12}",
            format!("principal moment I{} [m^5]", k + 1),
            f.mesh.principal_moments[k],
            f.clump.principal_moments[k],
            pct(f.clump.principal_moments[k], f.mesh.principal_moments[k])
        ));
    }
    line(format!(
        "centroid offset / V^(1/3)         {:.3e}",
        f.centroid_error
    ));
    line(format!(
        "principal axis errors [deg]       {:.3} {:.3} {:.3}",
        f.axis_errors_deg.x, f.axis_errors_deg.y, f.axis_errors_deg.z
    ));
    line(format!(
        "surface deviation [m]             mean {:.4e}  max {:.4e}  ({} samples)",
        f.mean_surface_deviation, f.max_surface_deviation, f.samples
    ));
    s
}
