//! `[simulation]` (gravity, skin, stability limits), `[domain]` and
//! `[integrator]`.

use super::diag::Diagnostic;
use super::raw::*;
use super::Seg::{I, K};
use super::{Cx, R};
use crate::scenario::diag::num;
use clump_core::boundary::Domain;
use clump_core::health::{DEFAULT_KINETIC_JUMP, DEFAULT_MAX_OVERLAP_RATIO};
use clump_core::rotation::RotationScheme;
use clump_core::world::AddedMass;
use glam::DVec3;

/// The settings of `[simulation]`, `[domain]` and `[integrator]` that do not
/// depend on the time step.
pub(super) struct Setting {
    pub gravity: DVec3,
    pub domain: Domain,
    pub rotation: RotationScheme,
    pub added_mass: AddedMass,
    pub skin: Option<f64>,
    pub max_overlap_ratio: f64,
    pub kinetic_jump: f64,
}

/// Reads the settings; `sim` is `[simulation]` (default when absent).
pub(super) fn setting(cx: &mut Cx, raw: &RawScenario, sim: &RawSimulation) -> R<Setting> {
    // ---------------- simulation, domain, integrator
    let gravity = match sim.gravity {
        Some(g) => cx.vec3(&[K("simulation"), K("gravity")], g, "gravity")?,
        None => DVec3::new(0.0, 0.0, -9.81),
    };
    let dom = raw.domain.clone().ok_or_else(|| {
        Diagnostic::new(super::diag::Severity::Error, &cx.src.path, "missing table [domain]").note(
            "help: every scenario needs a simulation box, e.g.\n[domain]\nlo = [-0.1, -0.1, 0.0]   # m\nhi = [0.1, 0.1, 0.3]\nperiodic = []           # e.g. [\"x\", \"y\"]",
        )
    })?;
    let lo = dom.lo.ok_or_else(|| {
        cx.missing(
            &[K("domain")],
            "[domain]",
            "lo",
            "lower corner in m, lo = [x, y, z]",
        )
    })?;
    let hi = dom.hi.ok_or_else(|| {
        cx.missing(
            &[K("domain")],
            "[domain]",
            "hi",
            "upper corner in m, hi = [x, y, z]",
        )
    })?;
    let lo = cx.vec3(&[K("domain"), K("lo")], lo, "lo")?;
    let hi = cx.vec3(&[K("domain"), K("hi")], hi, "hi")?;
    if hi.cmple(lo).any() {
        return Err(cx.err(
            &[K("domain"), K("hi")],
            format!("domain 'hi' {hi} must be above 'lo' {lo} on every axis"),
        ));
    }
    let mut periodic = [false; 3];
    for (i, a) in dom.periodic.iter().enumerate() {
        if periodic[*a as usize] {
            return Err(cx
                .err(
                    &[K("domain"), K("periodic"), I(i)],
                    format!(
                        "axis \"{}\" is listed twice in periodic",
                        ["x", "y", "z"][*a as usize]
                    ),
                )
                .note("help: list each periodic axis once, e.g. periodic = [\"x\", \"y\"]"));
        }
        periodic[*a as usize] = true;
    }
    let domain = Domain { lo, hi, periodic };
    let rotation = raw.integrator.rotation.unwrap_or_default();
    let added_mass = match &raw.integrator.added_mass {
        None => AddedMass::default(),
        Some(a) => {
            let p = |k: &'static str| [K("integrator"), K("added_mass"), K(k)];
            let c = cx.nonneg(
                &p("coefficient"),
                a.coefficient.unwrap_or(0.5),
                "coefficient",
                "",
            )?;
            let rho = a.fluid_density.ok_or_else(|| {
                cx.missing(
                    &[K("integrator"), K("added_mass")],
                    "[integrator.added_mass]",
                    "fluid_density",
                    "fluid density in kg/m^3, e.g. fluid_density = 1000",
                )
            })?;
            let rho = cx.nonneg(&p("fluid_density"), rho, "fluid_density", "kg/m^3")?;
            AddedMass {
                coefficient: c,
                fluid_density: rho,
            }
        }
    };
    let skin = match sim.skin {
        Some(s) => Some(cx.positive(&[K("simulation"), K("skin")], s, "skin", "m")?),
        None => None,
    };

    let max_overlap_ratio = match sim.max_overlap_ratio {
        Some(x) => {
            if !(x > 0.0 && x <= 1.0) {
                return Err(cx
                    .err(
                        &[K("simulation"), K("max_overlap_ratio")],
                        format!("max_overlap_ratio must lie in (0, 1], found {}", num(x)),
                    )
                    .label("overlap / smaller sphere radius")
                    .note(
                        "note: real contacts overlap by 1–5 % of the radius; the default is 0.15",
                    ));
            }
            x
        }
        None => DEFAULT_MAX_OVERLAP_RATIO,
    };
    let kinetic_jump = match sim.kinetic_energy_jump {
        Some(x) => {
            if !(x > 1.0 && x.is_finite()) {
                return Err(cx
                    .err(
                        &[K("simulation"), K("kinetic_energy_jump")],
                        format!(
                            "kinetic_energy_jump must be a finite number > 1, found {}",
                            num(x)
                        ),
                    )
                    .label("growth factor of the kinetic energy"));
            }
            x
        }
        None => DEFAULT_KINETIC_JUMP,
    };
    Ok(Setting {
        gravity,
        domain,
        rotation,
        added_mass,
        skin,
        max_overlap_ratio,
        kinetic_jump,
    })
}
