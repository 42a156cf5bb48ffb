//! Limits that keep a scenario's numbers within what a run can do: step
//! counts that cannot overflow the counters or run for ever, periodic axes
//! long enough for the neighbour grid, and particle materials with a finite
//! stiffness (so that a time step exists).
#![allow(clippy::result_large_err)]

use super::diag::Diagnostic;
use super::model::{MixDef, TemplateDef};
use super::source::{Seg, Source};
use clump_core::boundary::Domain;
use clump_core::contact::Material;
use clump_core::neighbor::skin::SKIN_MAX;

/// Most steps a run may have (all stages together): 10¹² steps take days
/// even for a handful of bodies, so anything above is a unit mistake.
pub const MAX_STEPS: u64 = 1_000_000_000_000;

type R<T> = Result<T, Diagnostic>;

fn too_many(src: &Source, path: &[Seg], what: String) -> Diagnostic {
    src.error_at(
        path,
        format!("{what}; at most {MAX_STEPS:.0e} steps are allowed"),
    )
    .label("too many steps")
    .note("help: check the units: 'duration' and 'dt' are in s")
}

/// Steps of a stage of `duration` (s, already checked > 0) at time step `dt`
/// (s); an error at `path` when they exceed [`MAX_STEPS`].
pub fn steps_of_duration(src: &Source, path: &[Seg], duration: f64, dt: f64) -> R<u64> {
    let n = ((duration / dt) - 1e-9).ceil().max(1.0);
    if n <= MAX_STEPS as f64 {
        Ok(n as u64)
    } else {
        Err(too_many(
            src,
            path,
            if n.is_finite() {
                format!("duration = {duration:e} s is {n:.3e} steps of dt = {dt:e} s")
            } else {
                format!(
                    "duration = {duration:e} s is more steps of dt = {dt:e} s than can be counted"
                )
            },
        ))
    }
}

/// A `steps = n` count at `path`: at least 1 and at most [`MAX_STEPS`].
pub fn steps_given(src: &Source, path: &[Seg], n: u64) -> R<u64> {
    if n == 0 {
        return Err(src
            .error_at(path, "'steps' must be at least 1, found 0")
            .label("must be positive"));
    }
    if n > MAX_STEPS {
        return Err(too_many(src, path, format!("steps = {n}")));
    }
    Ok(n)
}

/// Adds a stage's `steps` to the running `total`; an error at `path` when
/// the sum exceeds [`MAX_STEPS`].
pub fn add_steps(src: &Source, path: &[Seg], total: u64, steps: u64) -> R<u64> {
    let t = total.saturating_add(steps);
    if t > MAX_STEPS {
        return Err(too_many(
            src,
            path,
            format!("the stages up to this one have {t} steps"),
        ));
    }
    Ok(t)
}

/// An output interval of `x` seconds in steps of `dt` (s): at least 1, and
/// no more than [`MAX_STEPS`] (a longer interval writes the same output:
/// the first and the last step only).
pub fn interval_steps(x: f64, dt: f64) -> u64 {
    ((x / dt).round().min(MAX_STEPS as f64) as u64).max(1)
}

/// Every template's material must have a finite Young's modulus: `inf` is
/// for rigid walls, and a rigid particle has no contact time, so no time
/// step would resolve its contacts.
pub fn finite_particle_stiffness(
    src: &Source,
    templates: &[TemplateDef],
    materials: &[Material],
    material_names: &[String],
) -> R<()> {
    for (i, t) in templates.iter().enumerate() {
        let m = &materials[t.material as usize];
        if !m.youngs_modulus.is_finite() {
            return Err(src
                .error_at(
                    &[Seg::K("template"), Seg::I(i), Seg::K("material")],
                    format!(
                        "template '{}' uses material '{}' with youngs_modulus = inf: particles need a finite Young's modulus (no time step resolves a rigid particle's contacts)",
                        t.name, material_names[t.material as usize]
                    ),
                )
                .label("rigid material")
                .note("help: inf is for wall materials; give the particles' material a finite youngs_modulus (e.g. 1e8 Pa; dt follows from it)")
                );
        }
    }
    Ok(())
}

/// Each periodic axis must hold at least 3 neighbour cells. A cell is at
/// least the largest sphere diameter (templates scaled by the largest size
/// factor of any mix) plus the thickest Verlet skin the run may choose
/// (`skin`, else [`SKIN_MAX`] × the smallest radius `r_min`, m; an adapted
/// skin thicker than that is limited at run time to keep three cells,
/// `clump_core::world::World::max_adapted_skin`).
pub fn periodic_cells(
    src: &Source,
    domain: &Domain,
    templates: &[TemplateDef],
    mixes: &[MixDef],
    skin: Option<f64>,
    r_min: Option<f64>,
) -> R<()> {
    if !domain.periodic.iter().any(|&p| p) {
        return Ok(());
    }
    let mut r_max: f64 = 0.0;
    for (ti, t) in templates.iter().enumerate() {
        let mut scale: f64 = 1.0;
        for m in mixes {
            for e in m.mix.entries.iter().filter(|e| e.template as usize == ti) {
                scale = scale.max(e.size.max_scale());
            }
        }
        r_max = r_max.max(t.template.max_radius * scale);
    }
    let skin = skin.unwrap_or(SKIN_MAX * r_min.unwrap_or(0.0));
    let cell = 2.0 * r_max + skin;
    if !(cell > 0.0) {
        return Ok(());
    }
    for a in 0..3 {
        let l = domain.hi[a] - domain.lo[a];
        if domain.periodic[a] && l < 3.0 * cell {
            let axis = ["x", "y", "z"][a];
            return Err(src
                .error_at(
                    &[Seg::K("domain"), Seg::K("periodic")],
                    format!(
                        "periodic axis {axis} is {l:.4e} m long, shorter than 3 neighbour cells of {cell:.4e} m (largest sphere diameter {:.4e} m + skin {skin:.4e} m)",
                        2.0 * r_max
                    ),
                )
                .label(format!("{axis} too short"))
                .note(format!(
                    "help: make the domain at least {:.4e} m long along {axis}, or not periodic along it",
                    3.0 * cell
                )));
        }
    }
    Ok(())
}
