//! Resolution of a parsed scenario ([`super::raw`] → [`super::Scenario`]):
//! names become indices, defaults are filled in, physical ranges are checked
//! and every error points at the offending key.
#![allow(
    clippy::result_large_err,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::unnecessary_map_or
)]

mod contact;
mod convection;
mod dof;
mod domain;
mod fluid;
mod heat;
mod inserts;
mod materials;
mod output;
mod planar;
mod stability;
mod stages;
mod templates;
mod time_step;
mod walls;

use super::diag::{did_you_mean, list, num, Diagnostic};
use super::model::*;
use super::raw::*;
use super::source::{Seg, Source};
use super::Files;
use super::{bodies_file, diag, keys, model, raw, source};
use crate::scenario::guard;
use clump_core::health::HealthLimits;
use clump_core::multi_contact::MultiContact;
use clump_core::world::WorldConfig;
use glam::DVec3;

type R<T> = Result<T, Diagnostic>;

/// Largest `dt / t_Rayleigh` accepted.
pub const DT_ERROR_FRACTION: f64 = 0.5;
/// `dt / t_Rayleigh` above which a warning is given.
pub const DT_WARN_FRACTION: f64 = 0.3;
/// Largest `dt / dt_c` (the damped-contact stability limit of one contact,
/// docs/theory.md T-52) that `dt = "auto"` uses and an explicit `dt` passes
/// without a warning. A body in a bed carries several contacts whose
/// dashpots act on it together, so the step keeps a margin below the
/// one-contact limit: a bed of asymmetric clumps with e = 0.1 comes to rest
/// at 0.40 dt_c and does not at 0.52 dt_c (crates/clump-cli/tests/damped_bed.rs).
pub const DT_STABLE_FRACTION: f64 = 0.4;
/// Most spheres of a built-in rod (`n`): bounds memory and the mass
/// property computation of a mistyped `n`.
pub const MAX_ROD_SPHERES: u64 = 10_000;
/// Requested solid fraction of a pack region above which the scenario is refused.
pub const PACK_ERROR_FRACTION: f64 = 0.45;

fn sp(unit: &str) -> String {
    if unit.is_empty() {
        String::new()
    } else {
        format!(" {unit}")
    }
}

fn v3(a: [f64; 3]) -> DVec3 {
    DVec3::from_array(a)
}

struct Cx<'a> {
    src: &'a Source,
    files: &'a mut Files,
    warnings: Vec<Diagnostic>,
    /// Every error found so far, in file-section order, so that all of them
    /// are reported at once.
    errors: Vec<Diagnostic>,
    /// Where the current section's errors start in `errors`.
    section_start: usize,
}

impl Cx<'_> {
    /// Ends a section whose items collected their errors: the section's
    /// first error, if any (the others stay in `errors`).
    fn barrier(&mut self) -> R<()> {
        if self.errors.len() > self.section_start {
            Err(self.errors.remove(self.section_start))
        } else {
            Ok(())
        }
    }

    /// Takes the first error found (every section that failed left one).
    fn first_error(&mut self) -> Diagnostic {
        if self.errors.is_empty() {
            Diagnostic::new(
                super::diag::Severity::Error,
                &self.src.path,
                "the scenario could not be built (no diagnostic was recorded: please report this)",
            )
        } else {
            self.errors.remove(0)
        }
    }

    /// Builds one section; its errors join `errors` in order and the result
    /// is `None`. Sections that need it are then skipped, and the others
    /// are still checked, so one pass reports every independent error.
    fn section<T>(&mut self, f: impl FnOnce(&mut Self) -> R<T>) -> Option<T> {
        let start = self.errors.len();
        self.section_start = start;
        match f(self) {
            Ok(v) => Some(v),
            Err(d) => {
                self.errors.insert(start, d);
                None
            }
        }
    }

    fn err(&self, path: &[Seg], msg: impl Into<String>) -> Diagnostic {
        self.src.error_at(path, msg)
    }

    fn missing(&self, table: &[Seg], what: &str, key: &str, help: &str) -> Diagnostic {
        let mut d = self
            .src
            .error_at(table, format!("missing key '{key}' in {what}"));
        if !help.is_empty() {
            d = d.note(format!("help: {help}"));
        }
        d
    }

    fn positive(&self, path: &[Seg], x: f64, key: &str, unit: &str) -> R<f64> {
        if x.is_finite() && x > 0.0 {
            Ok(x)
        } else {
            Err(self
                .err(
                    path,
                    format!("'{key}' must be > 0{}, found {}", sp(unit), num(x)),
                )
                .label("must be positive"))
        }
    }

    fn nonneg(&self, path: &[Seg], x: f64, key: &str, unit: &str) -> R<f64> {
        if x.is_finite() && x >= 0.0 {
            Ok(x)
        } else {
            Err(self
                .err(
                    path,
                    format!("'{key}' must be >= 0{}, found {}", sp(unit), num(x)),
                )
                .label("must not be negative"))
        }
    }

    fn vec3(&self, path: &[Seg], a: [f64; 3], key: &str) -> R<DVec3> {
        let v = v3(a);
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(
                path,
                format!("'{key}' must have finite components, found {v}"),
            ))
        }
    }

    fn unit(&self, path: &[Seg], a: [f64; 3], key: &str) -> R<DVec3> {
        let v = self.vec3(path, a, key)?;
        let l = v.length();
        if l < 1e-12 {
            return Err(self.err(
                path,
                format!("'{key}' must be a non-zero direction vector, found {v}"),
            ));
        }
        if (l - 1.0).abs() > 1e-6 {
            self.warn_later(
                path,
                format!(
                    "'{key}' = {v} is not a unit vector; it is normalised to {}",
                    v / l
                ),
            );
        }
        Ok(v / l)
    }

    /// Reads a file the scenario refers to (`what`: "template", "mesh", …);
    /// the error points at `path` and says where relative paths start.
    fn read_file(&mut self, path: &[Seg], what: &str, f: &str) -> R<Vec<u8>> {
        match self.files.read(f) {
            Ok(b) => Ok(b),
            Err(e) => Err(self
                .err(path, format!("cannot read {what} file '{f}': {e}"))
                .label("file not readable")
                .note(format!(
                    "note: paths are relative to the scenario file's folder ({})",
                    self.files.base_display()
                ))),
        }
    }

    fn warn_later(&self, _path: &[Seg], _msg: String) {
        // normalisation is documented; no warning needed
    }
}

/// Name lookup with "which exist" in the error.
fn lookup(cx: &Cx, path: &[Seg], kind: &str, name: &str, names: &[String]) -> R<usize> {
    if let Some(i) = names.iter().position(|n| n == name) {
        return Ok(i);
    }
    let mut d = cx.err(path, format!("{kind} '{name}' does not exist"));
    d = match did_you_mean(name, names.iter().map(|s| s.as_str())) {
        Some(s) => d.label(format!("did you mean '{s}'?")),
        None => d.label(format!("no {kind} of this name")),
    };
    let plural = if kind.ends_with('x') {
        format!("{kind}es")
    } else {
        format!("{kind}s")
    };
    Err(d.note(format!("defined {plural}: {}", list(names))))
}

fn unique_name(cx: &Cx, path: &[Seg], kind: &str, name: &str, seen: &[String]) -> R<()> {
    if name.trim().is_empty() {
        return Err(cx.err(path, format!("{kind} name must not be empty")));
    }
    if seen.iter().any(|s| s == name) {
        return Err(cx
            .err(path, format!("duplicate {kind} name '{name}'"))
            .label("already defined above"));
    }
    Ok(())
}

/// Resolves a parsed scenario.
pub(super) fn resolve(
    src: &Source,
    raw: RawScenario,
    files: &mut Files,
) -> Result<Scenario, super::ScenarioError> {
    let mut cx = Cx {
        src,
        files,
        warnings: Vec::new(),
        errors: Vec::new(),
        section_start: 0,
    };
    let sc = resolve_sections(&mut cx, raw).map_err(|first| {
        let mut diagnostics = vec![first];
        diagnostics.append(&mut cx.errors);
        super::ScenarioError { diagnostics }
    })?;
    Ok(Scenario {
        warnings: cx.warnings,
        ..sc
    })
}

/// The materials of the scenario's walls that name a known material, in
/// file order without repeats (the walls section reports the others).
fn wall_material_indices(raw: &RawScenario, material_names: &[String]) -> Vec<u16> {
    let mut out: Vec<u16> = Vec::new();
    for w in &raw.wall {
        let found = w
            .material
            .as_ref()
            .and_then(|m| material_names.iter().position(|n| n == m));
        if let Some(i) = found {
            if !out.contains(&(i as u16)) {
                out.push(i as u16);
            }
        }
    }
    out
}

fn resolve_sections(cx: &mut Cx, raw: RawScenario) -> R<Scenario> {
    let sim = raw.simulation.clone().unwrap_or_default();
    // sections in file order; each runs when what it needs was built
    let mats = cx.section(|cx| materials::materials(cx, &raw));
    // sections that only look materials up by name are still checked when
    // a material's values are wrong (their result is then discarded)
    let given_names: Vec<String> = match &mats {
        Some((names, _)) => names.clone(),
        None => raw.material.iter().filter_map(|m| m.name.clone()).collect(),
    };
    let pair_table =
        cx.section(|cx| contact::pair_table(cx, &raw, &given_names, given_names.len()));
    let mut tpls = mats
        .as_ref()
        .and_then(|(names, m)| cx.section(|cx| templates::templates(cx, &raw, names, m)));
    let two_d = cx.section(|cx| planar::two_d(cx, raw.domain.as_ref().and_then(|d| d.dimension)));
    if let (Some(true), Some((_, t))) = (two_d, tpls.as_mut()) {
        if cx.section(|cx| planar::templates(cx, t)).is_none() {
            tpls = None;
        }
    }
    let mixes = tpls
        .as_ref()
        .and_then(|(names, _)| cx.section(|cx| templates::mixes(cx, &raw, names)));
    let setting = cx.section(|cx| domain::setting(cx, &raw, &sim));
    let time_step = match (&mats, &tpls, &mixes, &setting) {
        (
            Some((material_names, materials)),
            Some((_, templates)),
            Some((_, mixes)),
            Some(setting),
        ) => cx.section(|cx| {
            let contacts = time_step::Contacts {
                pairs: pair_table.as_deref().unwrap_or(&[]),
                wall_materials: &wall_material_indices(&raw, material_names),
            };
            time_step::time_step(
                cx,
                &sim,
                templates,
                mixes,
                materials,
                material_names,
                &contacts,
                &setting.domain,
                setting.skin,
            )
        }),
        _ => None,
    };
    // the stages and outputs are still checked with a dt the user gave when
    // the time step could not be derived (e.g. a template failed)
    let dt = time_step.as_ref().map(|t| t.dt).or(match sim.dt {
        Some(DtSpec::Fixed(v)) if v.is_finite() && v > 0.0 => Some(v),
        _ => None,
    });
    let walls = cx.section(|cx| walls::walls(cx, &raw, &given_names));
    if let Some(setting) = &setting {
        cx.section(|cx| walls::periodic_planes(cx, &raw, &setting.domain));
    }
    let stages = match (&walls, dt) {
        (Some((wall_names, ..)), Some(dt)) => {
            cx.section(|cx| stages::stages(cx, &raw, &sim, wall_names, dt))
        }
        _ => None,
    };
    let mut inserts = match (&stages, &tpls, &mixes, dt, &setting) {
        (
            Some(stages),
            Some((template_names, templates)),
            Some((mix_names, mixes)),
            Some(dt),
            Some(setting),
        ) => cx.section(|cx| {
            inserts::inserts(
                cx,
                &raw,
                stages,
                templates,
                template_names,
                mixes,
                mix_names,
                dt,
                &setting.domain,
            )
        }),
        _ => None,
    };
    if let (Some(true), Some(ins), Some(setting), Some(stages)) =
        (two_d, inserts.as_mut(), &setting, &stages)
    {
        if cx
            .section(|cx| planar::inserts(cx, ins, setting.gravity, stages))
            .is_none()
        {
            inserts = None;
        }
    }
    let fluid = cx.section(|cx| fluid::fluid(cx, &raw, setting.as_ref().map(|s| &s.domain)));
    let output = match (&stages, dt, two_d, &setting) {
        (Some(stages), Some(dt), Some(two_d), Some(setting)) => {
            cx.section(|cx| output::output(cx, &raw, stages, dt, two_d, &setting.domain))
        }
        _ => None,
    };
    let (
        Some((material_names, materials)),
        Some(pair_table),
        Some((_, templates)),
        Some((_, mixes)),
        Some(setting),
        Some(time_step),
        Some((_, walls, meshes, torque_points)),
        Some(stages),
        Some(inserts),
        Some(output),
        Some(fluid),
    ) = (
        mats, pair_table, tpls, mixes, setting, time_step, walls, stages, inserts, output, fluid,
    )
    else {
        // a section that is `None` reported its error
        return Err(cx.first_error());
    };
    if !cx.errors.is_empty() {
        return Err(cx.first_error());
    }
    let dt = time_step.dt;
    output::unknown_trajectory_bodies(cx, &output, &inserts);

    let config = WorldConfig {
        domain: setting.domain,
        gravity: setting.gravity,
        dt,
        rotation: setting.rotation,
        added_mass: setting.added_mass,
        skin: setting.skin,
        multi_contact: sim.multi_contact.unwrap_or(MultiContact::Sum),
    };
    let motion = guard::MotionBounds::new(&config, &inserts, &walls, &stages);
    let floor = motion.energy_floor();
    let contacts = guard::Contacts {
        templates: &templates,
        mixes: &mixes,
        materials: &materials,
        material_names: &material_names,
        pair_table: &pair_table,
        walls: &walls,
    };
    let overlap_estimate = guard::expected_overlap(&contacts, motion.impact_speed());
    let stability = HealthLimits {
        max_overlap_ratio: match sim.max_overlap_ratio {
            Some(_) => setting.max_overlap_ratio,
            None => guard::default_limit(overlap_estimate.as_ref()),
        },
        kinetic_jump: setting.kinetic_jump,
        specific_energy_floor: floor,
    };
    let heat = heat::heat(
        cx,
        &raw,
        &heat::HeatInput {
            templates: &templates,
            mixes: &mixes,
            materials: &materials,
            material_names: &material_names,
            walls: &walls,
            max_overlap_ratio: stability.max_overlap_ratio,
            dt,
            dt_auto: time_step.auto,
        },
    )?;
    // convection: the heat keys of [fluid]
    let convection = convection::fluid_heat(cx, &raw, heat.is_some())?;
    let heat = heat.map(|h| HeatDef { convection, ..h });
    Ok(Scenario {
        path: cx.src.path.clone(),
        text: cx.src.text.clone(),
        files: cx.files.loaded.clone(),
        material_names,
        materials,
        pair_table,
        templates,
        mixes,
        inserts,
        walls,
        meshes,
        torque_points,
        config,
        time_step,
        stability,
        overlap_estimate,
        stages,
        output,
        fluid: fluid.0,
        fluid_grid: fluid.1,
        warnings: Vec::new(),
        heat,
    })
}
