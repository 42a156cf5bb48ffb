//! `[fluid]`: the fluid the particles are in (clump_core::fluid).

use super::{did_you_mean, list, Cx, Seg::K, R};
use crate::scenario::raw::RawScenario;
use clump_core::fluid::{DragLaw, Fluid};
use glam::DVec3;

/// The fluid of the scenario, if it has a `[fluid]` table.
pub(super) fn fluid(cx: &mut Cx, raw: &RawScenario) -> R<Option<Fluid>> {
    let Some(f) = &raw.fluid else {
        return Ok(None);
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
    let velocity = match f.velocity {
        Some(v) => cx.vec3(&p("velocity"), v, "velocity")?,
        None => DVec3::ZERO,
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
    Ok(Some(Fluid {
        density,
        viscosity,
        velocity,
        pressure_gradient,
        drag,
        buoyancy: f.buoyancy.unwrap_or(true),
    }))
}
