//! The time step: explicit or `"auto"`, checked against the Rayleigh time of
//! the smallest sphere.

use super::model::*;
use super::raw::*;
use super::Seg::K;
use super::{Cx, DT_ERROR_FRACTION, DT_STABLE_FRACTION, DT_WARN_FRACTION, R};
use crate::scenario::bounds;
use crate::scenario::diag::num;
use clump_core::contact::time_scale::rayleigh_time;
use clump_core::contact::{Material, PairProperties};

/// What the stability limit needs of the contacts: the pair properties
/// (`nmat × nmat`, row-major; empty when they failed) and the walls'
/// materials.
pub(super) struct Contacts<'a> {
    pub pairs: &'a [PairProperties],
    pub wall_materials: &'a [u16],
}

/// The time step from `[simulation]` (`sim`) and the smallest sphere of the
/// templates as the mixes scale them.
pub(super) fn time_step(
    cx: &mut Cx,
    sim: &RawSimulation,
    templates: &[TemplateDef],
    mixes: &[MixDef],
    materials: &[Material],
    material_names: &[String],
    contacts: &Contacts,
    domain: &clump_core::boundary::Domain,
    skin: Option<f64>,
) -> R<TimeStep> {
    // ---------------- time step from the smallest sphere
    bounds::finite_particle_stiffness(cx.src, templates, materials, material_names)?;
    let mut smallest: Option<(f64, f64, String)> = None; // (t_R, radius, template)
    let mut scales = Vec::with_capacity(templates.len());
    for (ti, t) in templates.iter().enumerate() {
        let mut scale_min: f64 = 1.0;
        let mut used_scaled = false;
        for m in mixes {
            for e in &m.mix.entries {
                if e.template as usize == ti {
                    let s = e.size.min_scale();
                    scale_min = if used_scaled { scale_min.min(s) } else { s };
                    used_scaled = true;
                }
            }
        }
        let scale_min = scale_min.min(1.0);
        scales.push(scale_min);
        let r = t.template.min_radius * scale_min;
        let tr = rayleigh_time(&materials[t.material as usize], r);
        if smallest.as_ref().map_or(true, |s| tr < s.0) {
            smallest = Some((tr, r, t.name.clone()));
        }
    }
    let stability = (contacts.pairs.len() == materials.len() * materials.len())
        .then(|| {
            super::stability::stability_limit(
                templates,
                &scales,
                materials,
                contacts.pairs,
                material_names,
                contacts.wall_materials,
            )
        })
        .flatten();
    let dt_fraction = match sim.dt_fraction {
        Some(f) => {
            let p = [K("simulation"), K("dt_fraction")];
            if !(f > 0.0 && f <= DT_ERROR_FRACTION) {
                return Err(cx
                    .err(&p, format!("dt_fraction must lie in (0, {DT_ERROR_FRACTION}], found {}", num(f)))
                    .note("note: DEM codes use 0.1–0.3 of the Rayleigh time; above 0.5 the explicit integration is unstable"));
            }
            f
        }
        None => 0.2,
    };
    let dt_path = [K("simulation"), K("dt")];
    let stable_dt = stability.as_ref().map(|s| DT_STABLE_FRACTION * s.dt);
    let (dt, dt_auto) = match sim.dt.unwrap_or(DtSpec::Auto) {
        DtSpec::Auto => match &smallest {
            Some((tr, _, _)) => (stable_dt.map_or(dt_fraction * tr, |s| s.min(dt_fraction * tr)), true),
            None => {
                return Err(cx
                    .err(&dt_path, "dt = \"auto\" needs at least one [[template]] (the time step follows the smallest sphere)")
                    .note("help: give an explicit time step, e.g. dt = 1e-5"))
            }
        },
        DtSpec::Fixed(dt) => {
            let dt = cx.positive(&dt_path, dt, "dt", "s")?;
            if let Some((tr, r, name)) = &smallest {
                let frac = dt / tr;
                if frac > DT_ERROR_FRACTION {
                    return Err(cx
                        .err(&dt_path, format!(
                            "dt = {dt:e} s is above the stability limit {:.3e} s ({DT_ERROR_FRACTION} × the Rayleigh time {tr:.3e} s of the smallest sphere, r = {r:e} m in template '{name}')",
                            DT_ERROR_FRACTION * tr
                        ))
                        .label(format!("{:.2} × t_Rayleigh", frac))
                        .note(format!("help: use dt <= {:.3e} s, or dt = \"auto\" (dt_fraction = 0.2 gives {:.3e} s)", 0.3 * tr, 0.2 * tr)));
                }
                if frac > DT_WARN_FRACTION {
                    cx.warnings.push(
                        cx.src
                            .warning_at(&dt_path, format!(
                                "dt = {dt:e} s is {frac:.2} × the Rayleigh time {tr:.3e} s of the smallest sphere (above {DT_WARN_FRACTION}); contacts may be poorly resolved"
                            ))
                            .label("large time step"),
                    );
                }
            }
            if let (Some(st), Some(limit)) = (&stability, stable_dt) {
                if dt > limit {
                    cx.warnings.push(
                        cx.src
                            .warning_at(&dt_path, format!(
                                "dt = {dt:e} s is {:.2} × the damped-contact stability limit dt_c = {:.3e} s of {} (above {DT_STABLE_FRACTION}): a bed may never come to rest, its contact forces flipping sign every step",
                                dt / st.dt, st.dt, st.contact
                            ))
                            .label("above the damped-contact limit")
                            .note(format!("help: use dt <= {limit:.3e} s or dt = \"auto\"; dt_c is small where a clump turns about a sphere far from its centre of mass (κ = {:.2}) and the damping is strong (low restitution): docs/scenario.md, Time step and stability", st.kappa)),
                    );
                }
            }
            (dt, false)
        }
    };
    bounds::periodic_cells(
        cx.src,
        &domain,
        &templates,
        &mixes,
        skin,
        smallest.as_ref().map(|s| s.1),
    )?;
    let time_step = TimeStep {
        dt,
        auto: dt_auto,
        fraction: dt_fraction,
        rayleigh_time: smallest.as_ref().map(|s| s.0),
        smallest_radius: smallest.as_ref().map(|s| s.1),
        smallest_template: smallest.as_ref().map(|s| s.2.clone()),
        stability,
    };
    Ok(time_step)
}
