//! `[fluid]`: the fluid the particles are in (clump_core::fluid).

use super::{did_you_mean, list, Cx, Seg::K, R};
use crate::scenario::raw::{RawScenario, RawVelocity};
use clump_core::boundary::Domain;
use clump_core::fluid::{DragLaw, Fluid, VelocityGrid};
use glam::DVec3;
use std::sync::Arc;

/// The fluid of `[fluid]` and its velocity grid.
pub(super) type FluidSpec = (Option<Fluid>, Option<Arc<VelocityGrid>>);

/// The fluid of the scenario, if it has a `[fluid]` table, and the
/// velocity grid read from the file `velocity` names (checked to cover
/// `domain`, when the domain resolved).
pub(super) fn fluid(cx: &mut Cx, raw: &RawScenario, domain: Option<&Domain>) -> R<FluidSpec> {
    let Some(f) = &raw.fluid else {
        return Ok((None, None));
    };
    let p = |k: &'static str| [K("fluid"), K(k)];
    let density = f.density.ok_or_else(|| {
        cx.missing(
            &[K("fluid")],
            "[fluid]",
            "density",
            "fluid density in kg/m^3, e.g. density = 1000",
        )
    })?;
    let density = cx.positive(&p("density"), density, "density", "kg/m^3")?;
    let viscosity = f.viscosity.ok_or_else(|| {
        cx.missing(
            &[K("fluid")],
            "[fluid]",
            "viscosity",
            "dynamic viscosity in Pa s, e.g. viscosity = 1e-3",
        )
    })?;
    let viscosity = cx.positive(&p("viscosity"), viscosity, "viscosity", "Pa s")?;
    let (velocity, grid) = match &f.velocity {
        Some(RawVelocity::Uniform(v)) => match v[..] {
            [x, y, z] => (cx.vec3(&p("velocity"), [x, y, z], "velocity")?, None),
            _ => {
                return Err(cx
                    .err(
                        &p("velocity"),
                        format!("'velocity' needs 3 numbers [ux, uy, uz], found {}", v.len()),
                    )
                    .label("or a grid file name, velocity = \"flow.csv\""))
            }
        },
        Some(RawVelocity::File(name)) => {
            let g = grid_file(cx, name)?;
            if let Some(d) = domain {
                covers(cx, &g, name, d)?;
            }
            (DVec3::ZERO, Some(Arc::new(g)))
        }
        None => (DVec3::ZERO, None),
    };
    let pressure_gradient = match f.pressure_gradient {
        Some(v) => cx.vec3(&p("pressure_gradient"), v, "pressure_gradient")?,
        None => DVec3::ZERO,
    };
    let drag = match &f.drag {
        None => DragLaw::SchillerNaumann,
        Some(name) => DragLaw::from_name(name).ok_or_else(|| {
            let names: Vec<String> = DragLaw::NAMES.iter().map(|s| s.to_string()).collect();
            let d = cx.err(&p("drag"), format!("unknown drag law '{name}'"));
            let d = match did_you_mean(name, DragLaw::NAMES) {
                Some(s) => d.label(format!("did you mean '{s}'?")),
                None => d.label("no drag law of this name"),
            };
            d.note(format!("note: the drag laws are {}", list(&names)))
        })?,
    };
    let fluid = Fluid {
        density,
        viscosity,
        velocity,
        pressure_gradient,
        drag,
        buoyancy: f.buoyancy.unwrap_or(true),
    };
    Ok((Some(fluid), grid))
}

/// Reads the velocity grid file `name`: VTK image data (`.vti`, a
/// 3-component point-data array, [`crate::vti_grid`]) or CSV (the header
/// `x,y,z,ux,uy,uz`, then one node a line, m, m/s, world frame), on a
/// regular grid.
fn grid_file(cx: &mut Cx, name: &str) -> R<VelocityGrid> {
    let at = [K("fluid"), K("velocity")];
    let bytes = cx.read_file(&at, "velocity grid", name)?;
    let nodes = if name.to_ascii_lowercase().ends_with(".vti") {
        vti_nodes(cx, name, &bytes)?
    } else {
        csv_nodes(cx, name, &bytes)?
    };
    VelocityGrid::from_nodes(&nodes).map_err(|e| {
        cx.err(&at, format!("velocity grid file '{name}': {e}"))
            .note("help: the nodes must fill a regular grid: every combination of the x, y and z values, each axis equally spaced")
    })
}

/// The nodes of a `.vti` file's image data.
fn vti_nodes(cx: &Cx, name: &str, bytes: &[u8]) -> R<Vec<(DVec3, DVec3)>> {
    let at = [K("fluid"), K("velocity")];
    let text = std::str::from_utf8(bytes).map_err(|_| {
        cx.err(
            &at,
            format!("velocity grid file '{name}': not UTF-8 text (a VTK XML file is)"),
        )
    })?;
    crate::vti_grid::read_vti(text).map_err(|e| {
        let line = e.line.map_or(String::new(), |l| format!(", line {l}"));
        cx.err(&at, format!("velocity grid file '{name}'{line}: {}", e.message))
            .note("help: a .vti is VTK XML image data (one piece, uncompressed ascii or binary) with a 3-component point-data array of the fluid velocity, m/s, world frame")
    })
}

/// The nodes of a CSV velocity grid file.
fn csv_nodes(cx: &Cx, name: &str, bytes: &[u8]) -> R<Vec<(DVec3, DVec3)>> {
    let at = [K("fluid"), K("velocity")];
    let bad = |cx: &Cx, line: usize, what: String| {
        cx.err(
            &at,
            format!("velocity grid file '{name}', line {line}: {what}"),
        )
        .note("help: the file is CSV with the header x,y,z,ux,uy,uz and one grid node a line (m, m/s, world frame)")
    };
    let text = String::from_utf8_lossy(bytes);
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let (at_line, header): (usize, Vec<&str>) = match lines.next() {
        Some((k, h)) => (k + 1, h.split(',').map(str::trim).collect()),
        None => (1, vec![]),
    };
    if header != ["x", "y", "z", "ux", "uy", "uz"] {
        return Err(bad(
            cx,
            at_line,
            format!(
                "the header must be x,y,z,ux,uy,uz, found '{}'",
                header.join(",")
            ),
        ));
    }
    let mut nodes = Vec::new();
    for (k, line) in lines {
        let vals: Vec<f64> = line
            .split(',')
            .map(|c| c.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|e| bad(cx, k + 1, format!("'{line}' is not 6 numbers: {e}")))?;
        let [x, y, z, ux, uy, uz] = vals[..] else {
            return Err(bad(
                cx,
                k + 1,
                format!("'{line}' has {} values, 6 are needed", vals.len()),
            ));
        };
        if !vals.iter().all(|v| v.is_finite()) {
            return Err(bad(
                cx,
                k + 1,
                format!("'{line}' has a value that is not finite"),
            ));
        }
        nodes.push((DVec3::new(x, y, z), DVec3::new(ux, uy, uz)));
    }
    Ok(nodes)
}

/// Refuses a grid whose bounding box does not contain the domain box,
/// naming the side that falls short.
fn covers(cx: &Cx, g: &VelocityGrid, name: &str, d: &Domain) -> R<()> {
    let (lo, hi) = g.bounds();
    for (a, axis) in ["x", "y", "z"].iter().enumerate() {
        let short = if lo[a] > d.lo[a] {
            Some(format!(
                "its lower {axis} is {} m, above the domain's {} m",
                lo[a], d.lo[a]
            ))
        } else if hi[a] < d.hi[a] {
            Some(format!(
                "its upper {axis} is {} m, below the domain's {} m",
                hi[a], d.hi[a]
            ))
        } else {
            None
        };
        if let Some(s) = short {
            return Err(cx
                .err(
                    &[K("fluid"), K("velocity")],
                    format!("velocity grid file '{name}': grid does not cover the domain: {s}"),
                )
                .label("the grid's box must contain [domain]'s box"));
        }
    }
    Ok(())
}
