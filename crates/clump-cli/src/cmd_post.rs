//! `clump post RUN_DIR`: post-processing of a finished (or running) run's
//! folder: PNG plots of thermo.csv and flow.csv, coarse-grained fields
//! from the saved contact frames (`--width …`, [`clump_io::post`]) with
//! plots of 1D profiles, and a force-chain picture of a slab. Output goes
//! to `RUN_DIR/post` unless `-o` says otherwise. Exit status 0 on success,
//! 1 when an input is missing or unreadable, 2 when the output cannot be
//! written.

use clap::Args;
use clump_io::post::bed::{density_in_bed, Occupancy};
use clump_io::post::frame::Frame;
use clump_io::post::kernel::Kernel;
use clump_io::post::read::{contact_frames, read_frame};
use clump_io::post::spec::{FieldSeries, FieldSpec};
use clump_validate::plot::{draw, Chart, Series, Style};
use clump_validate::plot_discs::{draw_discs, Disc};
use clump_validate::plot_segments::{draw_segments, Segment};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// Arguments of `clump post`.
#[derive(Debug, Args)]
pub struct PostArgs {
    /// The run's output folder.
    pub run_dir: PathBuf,
    /// Output folder (default RUN_DIR/post).
    #[arg(short = 'o', long = "out")]
    pub out: Option<PathBuf>,
    /// Coarse-grain the contact frames with this kernel width (standard
    /// deviation, m); without it no fields are computed.
    #[arg(long)]
    pub width: Option<f64>,
    /// Grid axes, comma-separated (x, y, z).
    #[arg(long, value_delimiter = ',', default_value = "z")]
    pub axes: Vec<String>,
    /// Cells per grid axis, comma-separated.
    #[arg(long, value_delimiter = ',', default_value = "50")]
    pub cells: Vec<usize>,
    /// Lower end per grid axis, m (default: the domain's).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub lo: Option<Vec<f64>>,
    /// Upper end per grid axis, m (default: the domain's).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    pub hi: Option<Vec<f64>>,
    /// Kernel: gaussian or lucy.
    #[arg(long, default_value = "gaussian")]
    pub kernel: String,
    /// Average the fields over the frames with time >= this (s); without
    /// it, over all frames.
    #[arg(long)]
    pub from: Option<f64>,
    /// Axis normal to the force-chain slab (x, y, z).
    #[arg(long, default_value = "y")]
    pub slab_axis: String,
    /// Slab thickness, m (default: four mean body diameters).
    #[arg(long)]
    pub slab: Option<f64>,
    /// Colour of the particle picture: speed, radius or body_id.
    #[arg(long = "color", default_value = "speed")]
    pub color: String,
}

fn axis(s: &str) -> Result<usize, String> {
    match s {
        "x" => Ok(0),
        "y" => Ok(1),
        "z" => Ok(2),
        _ => Err(format!("unknown axis '{s}': allowed are x, y, z")),
    }
}

/// The mean volume-equivalent diameter of a frame's bodies, m (0 without
/// bodies).
fn mean_diameter(frame: &Frame) -> f64 {
    frame
        .bodies
        .iter()
        .map(|b| b.equivalent_diameter())
        .sum::<f64>()
        / frame.bodies.len().max(1) as f64
}

/// Reads a CSV with a header into (columns, rows).
fn read_csv(path: &Path) -> Result<(Vec<String>, Vec<Vec<f64>>), String> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap_or("")
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| {
            l.split(',')
                .map(|x| x.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    Ok((header, rows))
}

/// One chart of the columns whose names `pick` selects against column 0.
fn chart_of(
    header: &[String],
    rows: &[Vec<f64>],
    pick: impl Fn(&str) -> bool,
    title: &str,
    y_label: &str,
    cumulative: bool,
) -> Option<Chart> {
    let series: Vec<Series> = header
        .iter()
        .enumerate()
        .filter(|(_, h)| pick(h))
        .map(|(k, h)| {
            let mut acc = 0.0;
            let pts = rows
                .iter()
                .map(|r| {
                    acc = if cumulative { acc + r[k] } else { r[k] };
                    (r[0], acc)
                })
                .collect();
            Series::new(h.clone(), pts, Style::Line)
        })
        .collect();
    (!series.is_empty() && !rows.is_empty()).then(|| Chart {
        title: title.into(),
        x_label: header[0].clone(),
        y_label: y_label.into(),
        series,
    })
}

fn save(
    out: &Path,
    name: &str,
    chart: Option<Chart>,
    made: &mut Vec<PathBuf>,
) -> Result<(), String> {
    if let Some(c) = chart {
        let p = out.join(name);
        draw(&p, &c).map_err(|e| format!("{}: {e}", p.display()))?;
        made.push(p);
    }
    Ok(())
}

/// The thermo.csv and flow.csv plots.
fn series_plots(run: &Path, out: &Path, made: &mut Vec<PathBuf>) -> Result<(), String> {
    let thermo = run.join("thermo.csv");
    if thermo.exists() {
        let (h, r) = read_csv(&thermo)?;
        save(
            out,
            "thermo_energy.png",
            chart_of(&h, &r, |c| c.ends_with("[J]"), "Energies", "J", false),
            made,
        )?;
        save(
            out,
            "thermo_walls.png",
            chart_of(
                &h,
                &r,
                |c| c.ends_with("_fz[N]") || c.ends_with("_fx[N]") || c.ends_with("_fy[N]"),
                "Loads of the particles on the walls",
                "N",
                false,
            ),
            made,
        )?;
        save(
            out,
            "thermo_contacts.png",
            chart_of(
                &h,
                &r,
                |c| c.ends_with("contacts") || c == "bodies",
                "Contacts and bodies",
                "count",
                false,
            ),
            made,
        )?;
        save(
            out,
            "thermo_overlap.png",
            chart_of(
                &h,
                &r,
                |c| c == "max_overlap_ratio",
                "Largest overlap / radius",
                "ratio",
                false,
            ),
            made,
        )?;
    }
    let flow = run.join("flow.csv");
    if flow.exists() {
        let (h, r) = read_csv(&flow)?;
        save(
            out,
            "flow_planes.png",
            chart_of(
                &h,
                &r,
                |c| c.ends_with("_net_mass_total[kg]"),
                "Net mass through each plane",
                "kg",
                false,
            ),
            made,
        )?;
        save(
            out,
            "flow_regions.png",
            chart_of(
                &h,
                &r,
                |c| c.ends_with("_mass[kg]") && !c.contains("_mass_"),
                "Mass in each region",
                "kg",
                false,
            ),
            made,
        )?;
    }
    Ok(())
}

/// The fields of every contact frame (and their average) and, for a 1D
/// grid, profile plots of the average.
fn fields(
    a: &PostArgs,
    frames: &[Frame],
    out: &Path,
    made: &mut Vec<PathBuf>,
) -> Result<(), String> {
    let Some(width) = a.width else { return Ok(()) };
    let axes = a
        .axes
        .iter()
        .map(|s| axis(s))
        .collect::<Result<Vec<_>, _>>()?;
    let kernel = match a.kernel.as_str() {
        "gaussian" => Kernel::Gaussian,
        "lucy" => Kernel::Lucy,
        k => return Err(format!("--kernel {k}: allowed are gaussian, lucy")),
    };
    if !(width > 0.0 && width.is_finite()) || a.cells.len() != axes.len() || a.cells.contains(&0) {
        return Err("--width must be > 0 (m) and --cells give one count >= 1 per axis".into());
    }
    let spec = FieldSpec {
        axes,
        cells: a.cells.clone(),
        lo: a.lo.clone(),
        hi: a.hi.clone(),
        kernel,
        width,
        average: true,
    };
    let first = frames.first().ok_or("no contact frames to coarse-grain")?;
    spec.check(&first.domain)?;
    let mut series = FieldSeries::new(out, spec.clone());
    let window: Vec<&Frame> = frames
        .iter()
        .filter(|f| a.from.is_none_or(|t| f.time >= t))
        .collect();
    for f in &window {
        series.add(f).map_err(|e| e.to_string())?;
    }
    let mean = series
        .finish()
        .map_err(|e| e.to_string())?
        .ok_or("no frames in the averaging window")?;
    if let (Some(f0), Some(f1)) = (window.first(), window.last()) {
        outln!(
            "fields averaged over {} frames, t = {:.4} to {:.4} s{}",
            window.len(),
            f0.time,
            f1.time,
            if a.from.is_none() {
                " (all frames; --from T averages the settled ones only)"
            } else {
                ""
            }
        );
    }
    let d = window.last().map_or(0.0, |f| mean_diameter(f));
    if width < 0.5 * d {
        outln!(
            "note: --width {width:e} m is under half the mean body diameter ({d:.3e} m): the fields resolve the layers of body centres (densities can exceed the solid's); a width of d/2 or more gives bulk values"
        );
    }
    if spec.axes.len() == 1 {
        let g = spec.grid(&first.domain);
        let in_bed = bed_profile(&g, &window, &mean.density, out, made)?;
        let name = ["x", "y", "z"][spec.axes[0]];
        let z: Vec<f64> = (0..g.len()).map(|i| g.centre(0, i)).collect();
        let prof = |title: &str, unit: &str, curves: Vec<(&str, Vec<f64>)>| Chart {
            title: title.into(),
            x_label: format!("{name} [m]"),
            y_label: unit.into(),
            series: curves
                .into_iter()
                .map(|(l, v)| Series::new(l, z.iter().copied().zip(v).collect(), Style::Line))
                .collect(),
        };
        let s = mean.stress();
        let vel = mean.velocity();
        let charts = [
            (
                "profile_density.png",
                Chart {
                    title: "Density (time average)".into(),
                    x_label: format!("{name} [m]"),
                    y_label: "kg/m³".into(),
                    series: vec![
                        Series::new(
                            "over the whole cross-section",
                            z.iter().copied().zip(mean.density.clone()).collect(),
                            Style::Line,
                        ),
                        Series::new("in the bed (profile_bed.csv)", in_bed, Style::Line),
                    ],
                },
            ),
            (
                "profile_stress.png",
                prof(
                    "Stress (time average, compressive positive)",
                    "Pa",
                    vec![
                        ("σ_xx", s.iter().map(|m| m.x_axis.x).collect()),
                        ("σ_yy", s.iter().map(|m| m.y_axis.y).collect()),
                        ("σ_zz", s.iter().map(|m| m.z_axis.z).collect()),
                        ("σ_xz", s.iter().map(|m| m.z_axis.x).collect()),
                    ],
                ),
            ),
            (
                "profile_velocity.png",
                prof(
                    "Velocity (time average)",
                    "m/s",
                    vec![
                        ("v_x", vel.iter().map(|v| v.x).collect()),
                        ("v_y", vel.iter().map(|v| v.y).collect()),
                        ("v_z", vel.iter().map(|v| v.z).collect()),
                    ],
                ),
            ),
            (
                "profile_structure.png",
                prof(
                    "Coordination number and order",
                    "",
                    vec![
                        ("coordination", mean.coordination()),
                        (
                            "order Q_zz",
                            mean.order().iter().map(|q| q.z_axis.z).collect(),
                        ),
                        (
                            "fabric F_zz",
                            mean.fabric().iter().map(|q| q.z_axis.z).collect(),
                        ),
                    ],
                ),
            ),
        ];
        for (file, c) in charts {
            save(out, file, Some(c), made)?;
        }
    }
    Ok(())
}

/// `profile_bed.csv`: the share of the cross-section the bed occupies at
/// each cell of the 1D grid `g` (averaged over `window`) and the density
/// in the bed, [`clump_io::post::bed`]; returns the density's points
/// where it is defined, for the density plot.
fn bed_profile(
    g: &clump_io::post::grid::Grid,
    window: &[&Frame],
    density: &[f64],
    out: &Path,
    made: &mut Vec<PathBuf>,
) -> Result<Vec<(f64, f64)>, String> {
    let mut occ = Occupancy::default();
    for f in window {
        occ.add(f, g);
    }
    let fraction = occ.mean();
    let in_bed = density_in_bed(density, &fraction);
    let name = ["x", "y", "z"][g.axes[0]];
    let mut csv = format!("{name}[m],occupied_fraction,density_in_bed[kg/m^3]\n");
    let mut points = Vec::new();
    for (k, (f, b)) in fraction.iter().zip(&in_bed).enumerate() {
        let x = g.centre(0, k);
        match b {
            Some(b) => {
                csv += &format!("{x:e},{f:e},{b:e}\n");
                points.push((x, *b));
            }
            None => csv += &format!("{x:e},{f:e},nan\n"),
        }
    }
    let p = out.join("profile_bed.csv");
    std::fs::write(&p, csv).map_err(|e| format!("cannot write {}: {e}", p.display()))?;
    made.push(p);
    if let Some(peak) = points.iter().map(|p| p.1).reduce(f64::max) {
        outln!("density in the bed: up to {peak:.4e} kg/m³ (the share of the cross-section the bed occupies is in profile_bed.csv)");
    }
    Ok(points)
}

/// The force chains of the last frame in a slab, projected on the plane
/// normal to the slab axis, line width ∝ |F|.
fn force_chains(
    a: &PostArgs,
    frame: &Frame,
    out: &Path,
    made: &mut Vec<PathBuf>,
) -> Result<(), String> {
    let n = axis(&a.slab_axis)?;
    let (u, v) = match n {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    let cs = frame.contacts.as_deref().unwrap_or(&[]);
    let thick = a.slab.unwrap_or(4.0 * mean_diameter(frame));
    let mid = 0.5 * (frame.domain.lo[n] + frame.domain.hi[n]);
    let inside: Vec<_> = cs
        .iter()
        .filter(|c| (c.point[n] - mid).abs() <= 0.5 * thick)
        .collect();
    let fmax = inside.iter().map(|c| c.force.length()).fold(0.0, f64::max);
    if inside.is_empty() || fmax <= 0.0 {
        return Ok(());
    }
    let segs: Vec<Segment> = inside
        .iter()
        .map(|c| Segment {
            a: (c.centre_i[u], c.centre_i[v]),
            b: (c.end_j[u], c.end_j[v]),
            width: 1.0 + 9.0 * c.force.length() / fmax,
        })
        .collect();
    let names = ["x", "y", "z"];
    let p = out.join("force_chains.png");
    draw_segments(
        &p,
        &format!("Force chains at t = {:.4} s ({} contacts, {} = {:.4} ± {:.4} m, width ∝ |F|, max {:.3} N)", frame.time, segs.len(), names[n], mid, 0.5 * thick, fmax),
        &format!("{} [m]", names[u]),
        &format!("{} [m]", names[v]),
        &segs,
    )
    .map_err(|e| format!("{}: {e}", p.display()))?;
    made.push(p);
    Ok(())
}

/// The file of the last frame of `RUN/spheres.pvd`, if any.
fn last_spheres_frame(run: &Path) -> Option<PathBuf> {
    let text = std::fs::read_to_string(run.join("spheres.pvd")).ok()?;
    let line = text.lines().rev().find(|l| l.contains("file=\""))?;
    let i = line.find("file=\"")? + 6;
    let j = line[i..].find('"')?;
    Some(run.join(&line[i..i + j]))
}

/// `particles.png`: the spheres of the last frame as discs seen along the
/// slab axis (`--slab-axis`, default y: a side view), coloured by `--color`.
fn particles(a: &PostArgs, out: &Path, made: &mut Vec<PathBuf>) -> Result<(), String> {
    let Some(f) = last_spheres_frame(&a.run_dir) else {
        return Ok(()); // no VTK output: nothing to draw
    };
    if f.extension()
        .is_some_and(|e| !["vtp", "pvtp", "vtu", "pvtu"].iter().any(|x| e == *x))
    {
        outln!(
            "note: particles.png is drawn from .vtp and .vtu frames only (this run wrote {})",
            f.display()
        );
        return Ok(());
    }
    let arr = clump_io::post::read::read_vtp(&f)?;
    let get = |k: &str| {
        arr.get(k)
            .ok_or_else(|| format!("{}: no array '{k}'", f.display()))
    };
    let (pts, radius) = (get("Points")?, get("radius")?);
    let n = axis(&a.slab_axis)?;
    let (u, v) = match n {
        0 => (1, 2),
        1 => (0, 2),
        _ => (0, 1),
    };
    let (value, label): (Box<dyn Fn(usize) -> f64>, &str) = match a.color.as_str() {
        "speed" => {
            let vel = get("velocity")?;
            (
                Box::new(move |i| {
                    (vel[3 * i] * vel[3 * i]
                        + vel[3 * i + 1] * vel[3 * i + 1]
                        + vel[3 * i + 2] * vel[3 * i + 2])
                        .sqrt()
                }),
                "|v| [m/s]",
            )
        }
        "radius" => (Box::new(|i| radius[i]), "radius [m]"),
        "body_id" => {
            let id = get("body_id")?;
            (Box::new(move |i| id[i]), "body id")
        }
        c => return Err(format!("--color {c}: allowed are speed, radius, body_id")),
    };
    // seen from the negative side of the axis for y (a right-handed side
    // view with x to the right and z up), from the positive side otherwise
    let toward = if n == 1 { -1.0 } else { 1.0 };
    let discs: Vec<Disc> = (0..radius.len())
        .map(|i| Disc {
            centre: (pts[3 * i + u], pts[3 * i + v]),
            depth: toward * pts[3 * i + n],
            radius: radius[i],
            value: value(i),
        })
        .collect();
    if discs.is_empty() {
        return Ok(());
    }
    let lo = discs.iter().map(|d| d.value).fold(f64::INFINITY, f64::min);
    let hi = discs
        .iter()
        .map(|d| d.value)
        .fold(f64::NEG_INFINITY, f64::max);
    let names = ["x", "y", "z"];
    let p = out.join("particles.png");
    let name = f
        .file_name()
        .map(|x| x.to_string_lossy().into_owned())
        .unwrap_or_default();
    draw_discs(
        &p,
        &format!("{} spheres of {name}, seen along {}", discs.len(), names[n]),
        (&format!("{} [m]", names[u]), &format!("{} [m]", names[v])),
        label,
        (lo, hi),
        &discs,
    )
    .map_err(|e| format!("{}: {e}", p.display()))?;
    made.push(p);
    Ok(())
}

/// `paraview_view.py` beside the pictures: opens the run's spheres with the
/// README's recipe (Glyph → Sphere scaled by `radius` × 2, All Points,
/// coloured by velocity, at the last time): `paraview --script=FILE` or
/// `pvpython FILE`.
fn paraview_script(a: &PostArgs, out: &Path, made: &mut Vec<PathBuf>) -> Result<(), String> {
    if !a.run_dir.join("spheres.pvd").is_file() {
        return Ok(());
    }
    let run =
        std::fs::canonicalize(&a.run_dir).map_err(|e| format!("{}: {e}", a.run_dir.display()))?;
    let here = std::fs::canonicalize(out).map_err(|e| format!("{}: {e}", out.display()))?;
    // relative to the script when it sits inside the run folder (the
    // default RUN/post), so the folder can be moved
    let pvd = match here.strip_prefix(&run) {
        Ok(rel) => {
            let ups = rel.components().count();
            let mut s = "os.path.join(HERE".to_string();
            for _ in 0..ups {
                s.push_str(", \"..\"");
            }
            s + ", \"spheres.pvd\")"
        }
        Err(_) => format!("{:?}", run.join("spheres.pvd").display().to_string()),
    };
    let text = format!(
        r#"# Written by `clump post`: the run's spheres with the README's recipe.
# paraview --script=paraview_view.py   (or: pvpython paraview_view.py)
import os
from paraview.simple import *
HERE = os.path.dirname(os.path.abspath(__file__))
r = PVDReader(FileName={pvd})
t = r.TimestepValues[-1] if r.TimestepValues else 0.0
g = Glyph(Input=r, GlyphType="Sphere")
g.ScaleArray = ["POINTS", "radius"]
g.ScaleFactor = 2.0            # a unit glyph sphere has diameter 1
g.GlyphMode = "All Points"     # the default draws at most about 5000
view = GetActiveViewOrCreate("RenderView")
view.ViewTime = t
d = Show(g, view)
ColorBy(d, ("POINTS", "velocity", "Magnitude"))
d.SetScalarBarVisibility(view, True)
ResetCamera(view)
Render(view)
"#
    );
    let p = out.join("paraview_view.py");
    std::fs::write(&p, text).map_err(|e| format!("cannot write {}: {e}", p.display()))?;
    made.push(p);
    Ok(())
}

/// Runs `clump post`.
pub fn run(a: &PostArgs) -> ExitCode {
    let out = a.out.clone().unwrap_or_else(|| a.run_dir.join("post"));
    if let Err(e) = std::fs::create_dir_all(&out) {
        errln!("error: cannot create {}: {e}", out.display());
        return ExitCode::from(2);
    }
    let mut made = Vec::new();
    let result = (|| -> Result<(), String> {
        if !a.run_dir.is_dir() {
            return Err(format!("{}: not a folder", a.run_dir.display()));
        }
        series_plots(&a.run_dir, &out, &mut made)?;
        let list = match contact_frames(&a.run_dir) {
            Ok(l) => l,
            Err(e) if a.width.is_some() => return Err(e),
            Err(_) => Vec::new(),
        };
        let frames = list
            .iter()
            .map(|&(s, t)| read_frame(&a.run_dir, s, t))
            .collect::<Result<Vec<_>, _>>()?;
        fields(a, &frames, &out, &mut made)?;
        if let (None, Some(last)) = (a.width, frames.last()) {
            let d = mean_diameter(last);
            outln!(
                "note: {} contact frames, but no coarse-grained fields without --width (the kernel width in m; about one body diameter, {d:.3e} m here, e.g. --width {d:.1e} --axes z --cells 50); docs/post.md",
                frames.len()
            );
        }
        if let Some(last) = frames.last() {
            force_chains(a, last, &out, &mut made)?;
        }
        particles(a, &out, &mut made)?;
        paraview_script(a, &out, &mut made)?;
        Ok(())
    })();
    for p in &made {
        outln!("wrote {}", p.display());
    }
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            errln!("error: {e}");
            ExitCode::from(1)
        }
    }
}
