//! Validation and resolution of a parsed scenario: names become indices,
//! defaults are filled in, physical ranges are checked and every error points
//! at the offending key.
#![allow(
    clippy::result_large_err,
    clippy::neg_cmp_op_on_partial_ord,
    clippy::unnecessary_map_or
)]

use super::bounds;
use super::diag::{did_you_mean, list, num, Diagnostic};
use super::guard;
use super::model::*;
use super::placement;
use super::raw::*;
use super::source::{Seg, Source};
use super::Files;
use clump_core::boundary::Domain;
use clump_core::contact::time_scale::rayleigh_time;
use clump_core::contact::{Material, NormalLaw, PairProperties, RollingLaw};
use clump_core::health::{HealthLimits, DEFAULT_KINETIC_JUMP, DEFAULT_MAX_OVERLAP_RATIO};
use clump_core::insert::{
    Mix, MixEntry, Orientation, PackSpec, PackTarget, Region, SizeDistribution, StreamRate,
    StreamSpec, RSA_LIMIT,
};
use clump_core::multi_contact::MultiContact;
use clump_core::shape::{self, ClumpTemplate, ShapeError, Sphere};
use clump_core::wall::{TriMesh, Wall, WallMotion, WallShape};
use clump_core::world::{AddedMass, WorldConfig};
use glam::{DMat3, DQuat, DVec3};
use std::collections::HashMap;
use Seg::{I, K};

type R<T> = Result<T, Diagnostic>;

/// Largest `dt / t_Rayleigh` accepted.
pub const DT_ERROR_FRACTION: f64 = 0.5;
/// `dt / t_Rayleigh` above which a warning is given.
pub const DT_WARN_FRACTION: f64 = 0.3;
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
    /// Errors of the items of the current section (templates, walls,
    /// inserts), collected so that all of them are reported at once.
    errors: Vec<Diagnostic>,
}

impl Cx<'_> {
    /// Ends a section whose items collected their errors: the first error,
    /// if any (the others stay in `errors` and are reported with it); later
    /// sections depend on this one's names, so they are not checked.
    fn barrier(&mut self) -> R<()> {
        if self.errors.is_empty() {
            Ok(())
        } else {
            Err(self.errors.remove(0))
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
pub(super) fn build(
    src: &Source,
    raw: RawScenario,
    files: &mut Files,
) -> Result<Scenario, super::ScenarioError> {
    let mut cx = Cx {
        src,
        files,
        warnings: Vec::new(),
        errors: Vec::new(),
    };
    let sc = build_inner(&mut cx, raw).map_err(|first| {
        let mut diagnostics = vec![first];
        diagnostics.append(&mut cx.errors);
        super::ScenarioError { diagnostics }
    })?;
    Ok(Scenario {
        warnings: cx.warnings,
        ..sc
    })
}

fn build_inner(cx: &mut Cx, raw: RawScenario) -> R<Scenario> {
    // ---------------- materials
    let mut material_names: Vec<String> = Vec::new();
    let mut materials: Vec<Material> = Vec::new();
    if raw.material.is_empty() {
        return Err(Diagnostic::new(super::diag::Severity::Error, &cx.src.path, "no [[material]] defined")
            .note("help: add at least one, e.g.\n[[material]]\nname = \"glass\"\nyoungs_modulus = 5e6\npoisson_ratio = 0.3\ndensity = 2500"));
    }
    for (i, m) in raw.material.iter().enumerate() {
        let p = |k: &'static str| [K("material"), I(i), K(k)];
        let t = [K("material"), I(i)];
        let name = m
            .name
            .clone()
            .ok_or_else(|| cx.missing(&t, "[[material]]", "name", "name = \"glass\""))?;
        unique_name(cx, &p("name"), "material", &name, &material_names)?;
        let e = m.youngs_modulus.ok_or_else(|| {
            cx.missing(
                &t,
                "[[material]]",
                "youngs_modulus",
                "Young's modulus in Pa, e.g. youngs_modulus = 5e6",
            )
        })?;
        let nu = m.poisson_ratio.ok_or_else(|| {
            cx.missing(
                &t,
                "[[material]]",
                "poisson_ratio",
                "e.g. poisson_ratio = 0.3",
            )
        })?;
        let rho = m.density.ok_or_else(|| {
            cx.missing(
                &t,
                "[[material]]",
                "density",
                "density in kg/m^3, e.g. density = 2500",
            )
        })?;
        if !(e > 0.0) || e.is_nan() {
            return Err(cx
                .err(
                    &p("youngs_modulus"),
                    format!(
                        "youngs_modulus must be > 0 Pa (inf for a rigid wall material), found {e}"
                    ),
                )
                .label("must be positive"));
        }
        if !(nu < 0.5) {
            return Err(cx
                .err(&p("poisson_ratio"), format!("poisson_ratio must be < 0.5, found {nu}"))
                .label("must lie in (-1, 0.5)")
                .note("note: ν = 0.5 is an incompressible solid, for which the Hertz–Mindlin shear modulus terms break down"));
        }
        if !(nu > -1.0) {
            return Err(cx
                .err(
                    &p("poisson_ratio"),
                    format!("poisson_ratio must be > -1, found {nu}"),
                )
                .label("must lie in (-1, 0.5)"));
        }
        let rigid = e == f64::INFINITY;
        if !(rho.is_finite() && (rho > 0.0 || (rigid && rho >= 0.0))) {
            return Err(cx
                .err(
                    &p("density"),
                    format!("density must be > 0 kg/m^3, found {rho}"),
                )
                .label("must be positive"));
        }
        material_names.push(name);
        materials.push(Material {
            youngs_modulus: e,
            poisson_ratio: nu,
            density: rho,
        });
    }
    let nmat = materials.len();

    // ---------------- contact properties
    let default_props = contact_props(
        cx,
        &[K("contact")],
        "[contact]",
        &ContactFields::from_contact(&raw.contact),
        &PairProperties::default(),
    )?;
    let mut pair_table = vec![default_props; nmat * nmat];
    let mut pair_set: HashMap<(usize, usize), usize> = HashMap::new();
    for (i, pr) in raw.pair.iter().enumerate() {
        let t = [K("pair"), I(i)];
        let mp = [K("pair"), I(i), K("materials")];
        let ms = pr
            .materials
            .as_ref()
            .ok_or_else(|| cx.missing(&t, "[[pair]]", "materials", "materials = [\"a\", \"b\"]"))?;
        if ms.len() != 2 {
            return Err(cx.err(
                &mp,
                format!(
                    "'materials' must name exactly 2 materials, found {}",
                    ms.len()
                ),
            ));
        }
        let a = lookup(
            cx,
            &[K("pair"), I(i), K("materials"), I(0)],
            "material",
            &ms[0],
            &material_names,
        )?;
        let b = lookup(
            cx,
            &[K("pair"), I(i), K("materials"), I(1)],
            "material",
            &ms[1],
            &material_names,
        )?;
        let key = (a.min(b), a.max(b));
        if let Some(prev) = pair_set.insert(key, i) {
            return Err(cx
                .err(&mp, format!("pair {} – {} is defined twice", ms[0], ms[1]))
                .note(format!(
                    "note: first defined in [[pair]] number {}",
                    prev + 1
                )));
        }
        let props = contact_props(
            cx,
            &t,
            "[[pair]]",
            &ContactFields::from_pair(pr),
            &default_props,
        )?;
        pair_table[a * nmat + b] = props;
        pair_table[b * nmat + a] = props;
    }

    // ---------------- templates
    let mut template_names: Vec<String> = Vec::new();
    let mut templates: Vec<TemplateDef> = Vec::new();
    for (i, t) in raw.template.iter().enumerate() {
        match build_template(cx, i, t, &material_names, &materials, &template_names) {
            Ok(td) => {
                template_names.push(td.name.clone());
                templates.push(td);
            }
            Err(d) => cx.errors.push(d),
        }
    }
    cx.barrier()?;

    // ---------------- mixes
    let mut mix_names: Vec<String> = Vec::new();
    let mut mixes: Vec<MixDef> = Vec::new();
    for (i, m) in raw.mix.iter().enumerate() {
        let t = [K("mix"), I(i)];
        let name = m
            .name
            .clone()
            .ok_or_else(|| cx.missing(&t, "[[mix]]", "name", "name = \"rocks\""))?;
        unique_name(cx, &[K("mix"), I(i), K("name")], "mix", &name, &mix_names)?;
        if m.component.is_empty() {
            return Err(cx.err(&t, format!("mix '{name}' has no [[mix.component]]")).note(
                "help: add components, e.g.\n[[mix.component]]\ntemplate = \"stone_a\"\nfraction = 0.5",
            ));
        }
        let mut entries = Vec::new();
        for (j, c) in m.component.iter().enumerate() {
            let cp = |k: &'static str| [K("mix"), I(i), K("component"), I(j), K(k)];
            let ct = [K("mix"), I(i), K("component"), I(j)];
            let tn = c.template.as_ref().ok_or_else(|| {
                cx.missing(&ct, "[[mix.component]]", "template", "template = \"name\"")
            })?;
            let ti = lookup(cx, &cp("template"), "template", tn, &template_names)?;
            let fraction = c.fraction.unwrap_or(1.0);
            cx.positive(&cp("fraction"), fraction, "fraction", "")?;
            let size = match &c.size {
                None => SizeDistribution::default(),
                Some(s) => {
                    size_distribution(cx, &[K("mix"), I(i), K("component"), I(j), K("size")], s)?
                }
            };
            entries.push(MixEntry {
                template: ti as u32,
                fraction,
                size,
            });
        }
        mix_names.push(name.clone());
        mixes.push(MixDef {
            name,
            mix: Mix {
                basis: m.basis.unwrap_or_default(),
                entries,
            },
        });
    }

    // ---------------- simulation, domain, integrator
    let sim = raw.simulation.clone().unwrap_or_default();
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
    for a in &dom.periodic {
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
                        format!("max_overlap_ratio must lie in (0, 1], found {x}"),
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
                        format!("kinetic_energy_jump must be a finite number > 1, found {x}"),
                    )
                    .label("growth factor of the kinetic energy"));
            }
            x
        }
        None => DEFAULT_KINETIC_JUMP,
    };

    // ---------------- time step from the smallest sphere
    bounds::finite_particle_stiffness(cx.src, &templates, &materials, &material_names)?;
    let mut smallest: Option<(f64, f64, String)> = None; // (t_R, radius, template)
    for (ti, t) in templates.iter().enumerate() {
        let mut scale_min: f64 = 1.0;
        let mut used_scaled = false;
        for m in &mixes {
            for e in &m.mix.entries {
                if e.template as usize == ti {
                    let s = e.size.min_scale();
                    scale_min = if used_scaled { scale_min.min(s) } else { s };
                    used_scaled = true;
                }
            }
        }
        let scale_min = scale_min.min(1.0);
        let r = t.template.min_radius * scale_min;
        let tr = rayleigh_time(&materials[t.material as usize], r);
        if smallest.as_ref().map_or(true, |s| tr < s.0) {
            smallest = Some((tr, r, t.name.clone()));
        }
    }
    let dt_fraction = match sim.dt_fraction {
        Some(f) => {
            let p = [K("simulation"), K("dt_fraction")];
            if !(f > 0.0 && f <= DT_ERROR_FRACTION) {
                return Err(cx
                    .err(&p, format!("dt_fraction must lie in (0, {DT_ERROR_FRACTION}], found {f}"))
                    .note("note: DEM codes use 0.1–0.3 of the Rayleigh time; above 0.5 the explicit integration is unstable"));
            }
            f
        }
        None => 0.2,
    };
    let dt_path = [K("simulation"), K("dt")];
    let (dt, dt_auto) = match sim.dt.unwrap_or(DtSpec::Auto) {
        DtSpec::Auto => match &smallest {
            Some((tr, _, _)) => (dt_fraction * tr, true),
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
    };

    // ---------------- walls
    let mut wall_names: Vec<String> = Vec::new();
    let mut walls: Vec<Wall> = Vec::new();
    let mut meshes: Vec<TriMesh> = Vec::new();
    let mut torque_points: Vec<Option<DVec3>> = Vec::new();
    for (i, w) in raw.wall.iter().enumerate() {
        let built =
            build_wall(cx, i, w, &material_names, &wall_names, &mut meshes).and_then(|wall| {
                let tp = w
                    .torque_point
                    .map(|a| cx.vec3(&[K("wall"), I(i), K("torque_point")], a, "torque_point"))
                    .transpose()?;
                Ok((wall, tp))
            });
        let Ok((mut wall, tp)) = built.map_err(|d| cx.errors.push(d)) else {
            continue;
        };
        // [simulation] multi_contact is also the walls' default
        if let (None, Some(mc)) = (w.multi_contact, sim.multi_contact) {
            wall.multi_contact = mc;
        }
        torque_points.push(tp);
        wall_names.push(wall.name.clone());
        walls.push(wall);
    }
    cx.barrier()?;

    // ---------------- stages
    let mut stages: Vec<StageDef> = Vec::new();
    let steps_of =
        |cx: &Cx, base: &[Seg], what: &str, duration: Option<f64>, steps: Option<u64>| -> R<u64> {
            let mut pd = base.to_vec();
            pd.push(K("duration"));
            match (duration, steps) {
                (Some(_), Some(_)) => Err(cx.err(
                    &pd,
                    format!("give either 'duration' (s) or 'steps' in {what}, not both"),
                )),
                (Some(d), None) => {
                    let d = cx.positive(&pd, d, "duration", "s")?;
                    bounds::steps_of_duration(cx.src, &pd, d, dt)
                }
                (None, Some(n)) => {
                    let mut ps = base.to_vec();
                    ps.push(K("steps"));
                    bounds::steps_given(cx.src, &ps, n)
                }
                (None, None) => Err(cx.missing(
                    base,
                    what,
                    "duration",
                    "duration in s, e.g. duration = 0.5 (or steps = 10000)",
                )),
            }
        };
    if raw.stage.is_empty() {
        let steps = steps_of(
            cx,
            &[K("simulation")],
            "[simulation]",
            sim.duration,
            sim.steps,
        )?;
        stages.push(StageDef {
            name: "main".into(),
            steps,
            first_step: 0,
            gravity: None,
            walls: Vec::new(),
        });
    } else {
        if sim.duration.is_some() || sim.steps.is_some() {
            let k = if sim.duration.is_some() {
                "duration"
            } else {
                "steps"
            };
            return Err(cx
                .src
                .error_at_key(
                    &[K("simulation"), K(k)],
                    format!("'{k}' in [simulation] conflicts with the [[stage]] list"),
                )
                .note("help: with [[stage]] entries, give each stage its own duration"));
        }
        let mut first = 0u64;
        let mut names: Vec<String> = Vec::new();
        for (i, s) in raw.stage.iter().enumerate() {
            let t = [K("stage"), I(i)];
            let name = s.name.clone().unwrap_or_else(|| format!("stage{}", i + 1));
            unique_name(cx, &[K("stage"), I(i), K("name")], "stage", &name, &names)?;
            let steps = steps_of(cx, &t, "[[stage]]", s.duration, s.steps)?;
            let gravity = match s.gravity {
                Some(g) => Some(cx.vec3(&[K("stage"), I(i), K("gravity")], g, "gravity")?),
                None => None,
            };
            let mut changes = Vec::new();
            for (j, c) in s.wall.iter().enumerate() {
                let cp = |k: &'static str| [K("stage"), I(i), K("wall"), I(j), K(k)];
                let ct = [K("stage"), I(i), K("wall"), I(j)];
                let wn = c.name.as_ref().ok_or_else(|| {
                    cx.missing(&ct, "[[stage.wall]]", "name", "the name of a [[wall]]")
                })?;
                let wall = lookup(cx, &cp("name"), "wall", wn, &wall_names)?;
                let opt = |cx: &Cx, k: &'static str, v: Option<[f64; 3]>| -> R<Option<DVec3>> {
                    v.map(|a| cx.vec3(&cp(k), a, k)).transpose()
                };
                changes.push(WallChange {
                    wall,
                    active: c.active,
                    velocity: opt(cx, "velocity", c.velocity)?,
                    angular_velocity: opt(cx, "angular_velocity", c.angular_velocity)?,
                    center: opt(cx, "center", c.center)?,
                    surface_velocity: opt(cx, "surface_velocity", c.surface_velocity)?,
                });
            }
            names.push(name.clone());
            stages.push(StageDef {
                name,
                steps,
                first_step: first,
                gravity,
                walls: changes,
            });
            first = bounds::add_steps(cx.src, &t, first, steps)?;
        }
    }
    let stage_names: Vec<String> = stages.iter().map(|s| s.name.clone()).collect();

    // ---------------- inserts
    let mut inserts = Vec::new();
    for (i, ins) in raw.insert.iter().enumerate() {
        let def = build_insert(
            cx,
            i,
            ins,
            &stages,
            &stage_names,
            &templates,
            &template_names,
            &mixes,
            &mix_names,
            dt,
        )
        .and_then(|def| {
            placement::check_insert(cx.src, i, &def, &domain, &mut cx.warnings).map(|()| def)
        });
        match def {
            Ok(def) => inserts.push(def),
            Err(d) => cx.errors.push(d),
        }
    }
    cx.barrier()?;

    // ---------------- output
    let to_steps =
        |cx: &Cx, base: [Seg<'static>; 2], e: Option<f64>, s: Option<u64>| -> R<Option<u64>> {
            let [a, b] = base;
            match (e, s) {
                (Some(_), Some(_)) => Err(cx.err(
                    &[a, b, K("every")],
                    "give either 'every' (s) or 'every_steps', not both",
                )),
                (Some(x), None) => {
                    let x = cx.positive(&[a, b, K("every")], x, "every", "s")?;
                    Ok(Some(bounds::interval_steps(x, dt)))
                }
                (None, Some(0)) => Err(cx.err(
                    &[a, b, K("every_steps")],
                    "'every_steps' must be at least 1",
                )),
                (None, Some(n)) => Ok(Some(n.min(bounds::MAX_STEPS))),
                (None, None) => Ok(None),
            }
        };
    let o = &raw.output;
    let vtk = match &o.vtk {
        Some(e) => to_steps(cx, [K("output"), K("vtk")], e.every, e.every_steps)?,
        None => None,
    };
    let thermo = match &o.thermo {
        Some(e) => to_steps(cx, [K("output"), K("thermo")], e.every, e.every_steps)?,
        None => None,
    };
    let checkpoint = match &o.checkpoint {
        Some(e) => to_steps(cx, [K("output"), K("checkpoint")], e.every, e.every_steps)?,
        None => None,
    };
    let trajectory = match &o.trajectory {
        Some(t) => {
            let every =
                to_steps(cx, [K("output"), K("trajectory")], t.every, t.every_steps)?.unwrap_or(1);
            for (j, &b) in t.bodies.iter().enumerate() {
                if b == 0 {
                    return Err(cx.err(
                        &[K("output"), K("trajectory"), K("bodies"), I(j)],
                        "body ids start at 1 (the first inserted body)",
                    ));
                }
            }
            Some(TrajectoryDef {
                bodies: t.bodies.clone(),
                every,
            })
        }
        None => None,
    };
    let total_steps: u64 = stages.iter().map(|s| s.steps).sum();
    let output = OutputDef {
        directory: o.directory.clone(),
        vtk: vtk.or(Some((total_steps / 50).max(1))),
        thermo: thermo.or(Some((total_steps / 200).max(1))),
        checkpoint,
        trajectory,
        vtk_format: o.vtk_format.unwrap_or_default(),
    };

    let config = WorldConfig {
        domain,
        gravity,
        dt,
        rotation,
        added_mass,
        skin,
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
            Some(_) => max_overlap_ratio,
            None => guard::default_limit(overlap_estimate.as_ref()),
        },
        kinetic_jump,
        specific_energy_floor: floor,
    };
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
        warnings: Vec::new(),
    })
}

/// Contact keys shared by `[contact]` and `[[pair]]`.
struct ContactFields {
    restitution: Option<f64>,
    friction: Option<f64>,
    rolling_friction: Option<f64>,
    law: Option<LawName>,
    kn: Option<f64>,
    kt: Option<f64>,
    damping: Option<clump_core::contact::DampingLaw>,
    rolling: Option<RollingLaw>,
    tensile: Option<bool>,
}

impl ContactFields {
    fn from_contact(c: &RawContact) -> Self {
        ContactFields {
            restitution: c.restitution,
            friction: c.friction,
            rolling_friction: c.rolling_friction,
            law: c.law,
            kn: c.kn,
            kt: c.kt,
            damping: c.damping,
            rolling: c.rolling,
            tensile: c.tensile,
        }
    }
    fn from_pair(c: &RawPair) -> Self {
        ContactFields {
            restitution: c.restitution,
            friction: c.friction,
            rolling_friction: c.rolling_friction,
            law: c.law,
            kn: c.kn,
            kt: c.kt,
            damping: c.damping,
            rolling: c.rolling,
            tensile: c.tensile,
        }
    }
}

fn contact_props(
    cx: &mut Cx,
    base: &[Seg],
    what: &str,
    f: &ContactFields,
    dflt: &PairProperties,
) -> R<PairProperties> {
    let p = |k: &'static str| {
        let mut v = base.to_vec();
        v.push(K(k));
        v
    };
    let mut out = *dflt;
    if let Some(e) = f.restitution {
        if !(0.0..=1.0).contains(&e) {
            return Err(cx
                .err(
                    &p("restitution"),
                    format!("restitution must lie in [0, 1], found {e}"),
                )
                .label("outside [0, 1]")
                .note("note: e = 1 is perfectly elastic, e = 0 perfectly plastic"));
        }
        out.restitution = e;
    }
    if let Some(mu) = f.friction {
        out.friction = cx.nonneg(&p("friction"), mu, "friction", "")?;
    }
    if let Some(mu) = f.rolling_friction {
        out.rolling_friction = cx.nonneg(&p("rolling_friction"), mu, "rolling_friction", "")?;
    }
    if let Some(d) = f.damping {
        out.damping = d;
    }
    if let Some(r) = f.rolling {
        out.rolling = r;
    }
    if let Some(t) = f.tensile {
        out.tensile = t;
    }
    let law = f.law.unwrap_or(match dflt.normal {
        NormalLaw::Hertz => LawName::Hertz,
        NormalLaw::Linear { .. } => LawName::Linear,
    });
    match law {
        LawName::Hertz => {
            for (k, v) in [("kn", f.kn), ("kt", f.kt)] {
                if v.is_some() {
                    return Err(cx
                        .src
                        .error_at_key(&p(k), format!("'{k}' is only used with law = \"linear\" (this {what} uses the Hertz law)"))
                        .note("help: add law = \"linear\", or remove the stiffness (Hertz stiffness follows from the materials)"));
                }
            }
            out.normal = NormalLaw::Hertz;
        }
        LawName::Linear => {
            let (dkn, dkt) = match dflt.normal {
                NormalLaw::Linear { kn, kt } => (Some(kn), Some(kt)),
                NormalLaw::Hertz => (None, None),
            };
            let kn = f.kn.or(dkn).ok_or_else(|| {
                cx.missing(
                    base,
                    what,
                    "kn",
                    "law = \"linear\" needs the normal stiffness in N/m, e.g. kn = 1e5",
                )
            })?;
            let kn = cx.positive(&p("kn"), kn, "kn", "N/m")?;
            let kt = match f.kt {
                Some(kt) => cx.nonneg(&p("kt"), kt, "kt", "N/m")?,
                None => dkt.filter(|_| f.kn.is_none()).unwrap_or(2.0 / 7.0 * kn),
            };
            out.normal = NormalLaw::Linear { kn, kt };
        }
    }
    if out.rolling != RollingLaw::None && out.rolling_friction == 0.0 && f.rolling.is_some() {
        let w = cx.src.warning_at(
            &p("rolling"),
            format!(
                "rolling = {:?} with rolling_friction = 0 has no effect",
                out.rolling
            )
            .to_lowercase(),
        );
        cx.warnings.push(w);
    }
    if out.rolling == RollingLaw::None && out.rolling_friction > 0.0 && f.rolling_friction.is_some()
    {
        let w = cx
            .src
            .warning_at(
                &p("rolling_friction"),
                format!(
                    "rolling_friction = {} has no effect without a rolling model",
                    out.rolling_friction
                ),
            )
            .label("ignored")
            .note("help: add rolling = \"epsd\" (or \"cdt\") to resist rolling");
        cx.warnings.push(w);
    }
    Ok(out)
}

fn shape_error(cx: &Cx, i: usize, e: ShapeError, inline: bool) -> Diagnostic {
    let t = [K("template"), I(i)];
    match e {
        ShapeError::NonPositiveRadius { index, radius } if inline => cx
            .err(
                &[K("template"), I(i), K("spheres"), I(index)],
                format!("sphere {index} of template has radius {radius} m; radii must be > 0"),
            )
            .label("radius must be positive"),
        ShapeError::NonFiniteSphere { index, .. } if inline => cx.err(
            &[K("template"), I(i), K("spheres"), I(index)],
            format!("sphere {index} has a non-finite centre or radius"),
        ),
        ShapeError::InvalidMass { mass } => cx.err(
            &[K("template"), I(i), K("mass")],
            format!("mass must be > 0 kg, found {mass}"),
        ),
        ShapeError::InvalidInertia { reason } => cx.err(
            &[K("template"), I(i), K("inertia")],
            format!("invalid inertia tensor (kg m^2, about the centre of mass): {reason}"),
        ),
        other => cx.err(&t, format!("invalid template: {other}")),
    }
}

fn build_template(
    cx: &mut Cx,
    i: usize,
    t: &RawTemplate,
    material_names: &[String],
    materials: &[Material],
    seen: &[String],
) -> R<TemplateDef> {
    let tp = [K("template"), I(i)];
    let p = |k: &'static str| [K("template"), I(i), K(k)];
    let name = t
        .name
        .clone()
        .ok_or_else(|| cx.missing(&tp, "[[template]]", "name", "name = \"stone\""))?;
    unique_name(cx, &p("name"), "template", &name, seen)?;
    let mname = t.material.as_ref().ok_or_else(|| {
        cx.missing(
            &tp,
            "[[template]]",
            "material",
            "the name of a [[material]]",
        )
    })?;
    let mi = lookup(cx, &p("material"), "material", mname, material_names)?;
    let density = materials[mi].density;
    if !(density > 0.0 && density.is_finite()) {
        return Err(cx.err(&p("material"), format!("material '{mname}' has density {density}; a particle material needs a finite density > 0")));
    }
    let sources = [t.spheres.is_some(), t.file.is_some(), t.shape.is_some()];
    let nsrc = sources.iter().filter(|&&b| b).count();
    if nsrc != 1 {
        let d = if nsrc == 0 {
            cx.err(
                &tp,
                format!("template '{name}' needs its spheres: one of 'spheres', 'file' or 'shape'"),
            )
        } else {
            // point at the source key given last
            let k = ["spheres", "file", "shape"]
                .into_iter()
                .zip(sources)
                .filter(|(_, present)| *present)
                .map(|(k, _)| k)
                .max_by_key(|k| cx.src.key_span(&p(k)).map_or(0, |s| s.start))
                .unwrap_or("shape");
            cx.src.error_at_key(
                &p(k),
                format!("template '{name}' gives more than one of 'spheres', 'file', 'shape'"),
            )
        };
        return Err(d.note("help: spheres = [[x, y, z, r], ...] (m), file = \"stone.txt\" (LIGGGHTS x y z r), or shape = \"sphere\"|\"rod\"|\"tetrahedron\"|\"cube_octet\""));
    }
    // keys that belong to built-in shapes only
    if t.shape.is_none() {
        for (k, v) in [
            ("radius", t.radius.is_some()),
            ("n", t.n.is_some()),
            ("spacing", t.spacing.is_some()),
            ("edge", t.edge.is_some()),
        ] {
            if v {
                return Err(cx.src.error_at_key(
                    &p(k),
                    format!("'{k}' only applies to templates with a built-in 'shape'"),
                ));
            }
        }
    }
    let mut inline = false;
    let spheres: Vec<Sphere> = if let Some(sp) = &t.spheres {
        inline = true;
        if sp.is_empty() {
            return Err(cx.err(
                &p("spheres"),
                "'spheres' is empty; give at least one [x, y, z, r] (m)",
            ));
        }
        sp.iter()
            .map(|s| Sphere::new(DVec3::new(s[0], s[1], s[2]), s[3]))
            .collect()
    } else if let Some(f) = &t.file {
        let bytes = cx.read_file(&p("file"), "template", f)?;
        crate::template_file::parse_template_bytes(&bytes, std::path::Path::new(f))
            .map_err(|e| cx.err(&p("file"), format!("template file '{f}' is invalid: {e}")))?
    } else {
        let shape = t.shape.expect("one source");
        let radius = t.radius.ok_or_else(|| {
            cx.missing(
                &tp,
                "[[template]]",
                "radius",
                "sphere radius in m, e.g. radius = 0.001",
            )
        })?;
        let radius = cx.positive(&p("radius"), radius, "radius", "m")?;
        let need = |cx: &Cx, k: &'static str, v: Option<f64>, what: &str| -> R<f64> {
            let x = v.ok_or_else(|| cx.missing(&tp, "[[template]]", k, what))?;
            cx.positive(&p(k), x, k, "m")
        };
        let forbid = |cx: &Cx, k: &'static str, present: bool, s: &str| -> R<()> {
            if present {
                Err(cx
                    .src
                    .error_at_key(&p(k), format!("'{k}' does not apply to shape = \"{s}\"")))
            } else {
                Ok(())
            }
        };
        match shape {
            ShapeName::Sphere => {
                forbid(cx, "n", t.n.is_some(), "sphere")?;
                forbid(cx, "spacing", t.spacing.is_some(), "sphere")?;
                forbid(cx, "edge", t.edge.is_some(), "sphere")?;
                shape::single_sphere(radius)
            }
            ShapeName::Rod => {
                forbid(cx, "edge", t.edge.is_some(), "rod")?;
                let n = t.n.ok_or_else(|| {
                    cx.missing(&tp, "[[template]]", "n", "number of spheres, e.g. n = 4")
                })?;
                if n == 0 {
                    return Err(cx.err(&p("n"), "a rod needs n >= 1 spheres"));
                }
                if u64::from(n) > MAX_ROD_SPHERES {
                    return Err(cx
                        .err(&p("n"), format!("a rod may have at most {MAX_ROD_SPHERES} spheres, found {n}"))
                        .note("note: a clump's mass properties are computed over the union of its spheres; use a template file for unusual shapes"));
                }
                let spacing = need(
                    cx,
                    "spacing",
                    t.spacing,
                    "centre spacing in m, e.g. spacing = 0.001",
                )?;
                shape::rod(n as usize, radius, spacing)
            }
            ShapeName::Tetrahedron | ShapeName::CubeOctet => {
                let s = if shape == ShapeName::Tetrahedron {
                    "tetrahedron"
                } else {
                    "cube_octet"
                };
                forbid(cx, "n", t.n.is_some(), s)?;
                forbid(cx, "spacing", t.spacing.is_some(), s)?;
                let edge = need(cx, "edge", t.edge, "edge length in m, e.g. edge = 0.0012")?;
                if shape == ShapeName::Tetrahedron {
                    shape::tetrahedron(radius, edge)
                } else {
                    shape::cube_octet(radius, edge)
                }
            }
        }
    };
    let scale = t.scale.unwrap_or(1.0);
    let scale = cx.positive(&p("scale"), scale, "scale", "")?;
    let spheres: Vec<Sphere> = spheres
        .iter()
        .map(|s| Sphere::new(s.center * scale, s.radius * scale))
        .collect();
    let template =
        match (t.mass, t.inertia) {
            (None, None) => ClumpTemplate::from_spheres(&name, &spheres, density),
            (Some(m), Some(inertia)) => {
                cx.positive(&p("mass"), m, "mass", "kg")?;
                let mat = DMat3::from_cols_array_2d(&inertia).transpose();
                ClumpTemplate::with_override(&name, &spheres, density, m, mat)
            }
            (Some(_), None) => return Err(cx
                .src
                .error_at_key(
                    &p("mass"),
                    "'mass' needs 'inertia' too (3×3 tensor in kg m^2 about the centre of mass)",
                )
                .note("help: inertia = [[Ixx, Ixy, Ixz], [Ixy, Iyy, Iyz], [Ixz, Iyz, Izz]]")),
            (None, Some(_)) => {
                return Err(cx
                    .src
                    .error_at_key(&p("inertia"), "'inertia' needs 'mass' too (kg)"))
            }
        }
        .map_err(|e| {
            let mut d = shape_error(cx, i, e, inline);
            d.message = format!("template '{name}': {}", d.message);
            d
        })?;
    Ok(TemplateDef {
        name,
        material: mi as u16,
        template,
    })
}

fn size_distribution(cx: &Cx, base: &[Seg], s: &RawSize) -> R<SizeDistribution> {
    let p = |k: &'static str| {
        let mut v = base.to_vec();
        v.push(K(k));
        v
    };
    let kind = s.distribution.ok_or_else(|| {
        cx.missing(
            base,
            "size",
            "distribution",
            "distribution = \"uniform\" (or \"normal\", \"fixed\")",
        )
    })?;
    let req = |k: &'static str, v: Option<f64>| -> R<f64> {
        let x = v.ok_or_else(|| {
            cx.missing(
                base,
                "size",
                k,
                &format!("the {k} scale factor (dimensionless)"),
            )
        })?;
        cx.positive(&p(k), x, k, "")
    };
    let forbid = |k: &'static str, present: bool, d: &str| -> R<()> {
        if present {
            Err(cx.src.error_at_key(
                &p(k),
                format!("'{k}' does not apply to distribution = \"{d}\""),
            ))
        } else {
            Ok(())
        }
    };
    let d = match kind {
        SizeKind::Fixed => {
            forbid("min", s.min.is_some(), "fixed")?;
            forbid("max", s.max.is_some(), "fixed")?;
            forbid("mean", s.mean.is_some(), "fixed")?;
            forbid("std", s.std.is_some(), "fixed")?;
            SizeDistribution::Fixed {
                scale: req("scale", s.scale)?,
            }
        }
        SizeKind::Uniform => {
            forbid("scale", s.scale.is_some(), "uniform")?;
            forbid("mean", s.mean.is_some(), "uniform")?;
            forbid("std", s.std.is_some(), "uniform")?;
            SizeDistribution::Uniform {
                min: req("min", s.min)?,
                max: req("max", s.max)?,
            }
        }
        SizeKind::Normal => {
            forbid("scale", s.scale.is_some(), "normal")?;
            let mean = req("mean", s.mean)?;
            let std = s.std.ok_or_else(|| {
                cx.missing(
                    base,
                    "size",
                    "std",
                    "standard deviation of the scale factor",
                )
            })?;
            let std = cx.nonneg(&p("std"), std, "std", "")?;
            let min = s
                .min
                .map(|m| cx.positive(&p("min"), m, "min", ""))
                .transpose()?
                .unwrap_or((mean - 3.0 * std).max(0.1 * mean));
            let max = s
                .max
                .map(|m| cx.positive(&p("max"), m, "max", ""))
                .transpose()?
                .unwrap_or(mean + 3.0 * std);
            SizeDistribution::Normal {
                mean,
                std,
                min,
                max,
            }
        }
    };
    match d {
        SizeDistribution::Uniform { min, max } | SizeDistribution::Normal { min, max, .. }
            if max < min =>
        {
            Err(cx.err(
                &p("max"),
                format!("size 'max' ({max}) is below 'min' ({min})"),
            ))
        }
        _ => Ok(d),
    }
}

fn build_wall(
    cx: &mut Cx,
    i: usize,
    w: &RawWall,
    material_names: &[String],
    seen: &[String],
    meshes: &mut Vec<TriMesh>,
) -> R<Wall> {
    let tp = [K("wall"), I(i)];
    let p = |k: &'static str| [K("wall"), I(i), K(k)];
    let name = w
        .name
        .clone()
        .ok_or_else(|| cx.missing(&tp, "[[wall]]", "name", "name = \"floor\""))?;
    unique_name(cx, &p("name"), "wall", &name, seen)?;
    let mname = w
        .material
        .as_ref()
        .ok_or_else(|| cx.missing(&tp, "[[wall]]", "material", "the name of a [[material]]"))?;
    let material = lookup(cx, &p("material"), "material", mname, material_names)? as u16;
    let kind = w.kind.ok_or_else(|| {
        cx.missing(
            &tp,
            "[[wall]]",
            "type",
            "type = \"plane\" (or \"cylinder\", \"box\", \"mesh\")",
        )
    })?;
    let allowed: &[&str] = match kind {
        WallKind::Plane => &["point", "normal"],
        WallKind::Cylinder => &["point", "axis", "radius", "inside"],
        WallKind::Box => &["lo", "hi", "inside"],
        WallKind::Mesh => &["file", "scale", "rotation", "offset", "merge_angle"],
    };
    let kname = match kind {
        WallKind::Plane => "plane",
        WallKind::Cylinder => "cylinder",
        WallKind::Box => "box",
        WallKind::Mesh => "mesh",
    };
    for (k, present) in [
        ("point", w.point.is_some()),
        ("normal", w.normal.is_some()),
        ("axis", w.axis.is_some()),
        ("radius", w.radius.is_some()),
        ("inside", w.inside.is_some()),
        ("lo", w.lo.is_some()),
        ("hi", w.hi.is_some()),
        ("file", w.file.is_some()),
        ("scale", w.scale.is_some()),
        ("rotation", w.rotation.is_some()),
        ("offset", w.offset.is_some()),
        ("merge_angle", w.merge_angle.is_some()),
    ] {
        if present && !allowed.contains(&k) {
            return Err(cx
                .src
                .error_at_key(
                    &p(k),
                    format!("'{k}' does not apply to a wall of type \"{kname}\""),
                )
                .label(format!("a {kname} uses {}", allowed.join(", "))));
        }
    }
    let req3 = |cx: &Cx, k: &'static str, v: Option<[f64; 3]>, help: &str| -> R<[f64; 3]> {
        v.ok_or_else(|| cx.missing(&tp, &format!("[[wall]] of type \"{kname}\""), k, help))
    };
    let shape = match kind {
        WallKind::Plane => {
            let point = cx.vec3(
                &p("point"),
                req3(
                    cx,
                    "point",
                    w.point,
                    "a point on the plane in m, point = [0, 0, 0]",
                )?,
                "point",
            )?;
            let normal = cx.unit(
                &p("normal"),
                req3(
                    cx,
                    "normal",
                    w.normal,
                    "unit normal towards the particles, normal = [0, 0, 1]",
                )?,
                "normal",
            )?;
            WallShape::Plane { point, normal }
        }
        WallKind::Cylinder => {
            let point = cx.vec3(
                &p("point"),
                req3(cx, "point", w.point, "a point on the axis in m")?,
                "point",
            )?;
            let axis = cx.unit(
                &p("axis"),
                req3(cx, "axis", w.axis, "axis direction, e.g. axis = [0, 1, 0]")?,
                "axis",
            )?;
            let radius = w.radius.ok_or_else(|| {
                cx.missing(
                    &tp,
                    "[[wall]] of type \"cylinder\"",
                    "radius",
                    "radius in m",
                )
            })?;
            let radius = cx.positive(&p("radius"), radius, "radius", "m")?;
            WallShape::Cylinder {
                point,
                axis,
                radius,
                inside: w.inside.unwrap_or(true),
            }
        }
        WallKind::Box => {
            let lo = cx.vec3(&p("lo"), req3(cx, "lo", w.lo, "lower corner in m")?, "lo")?;
            let hi = cx.vec3(&p("hi"), req3(cx, "hi", w.hi, "upper corner in m")?, "hi")?;
            if hi.cmple(lo).any() {
                return Err(cx.err(
                    &p("hi"),
                    format!("box 'hi' {hi} must be above 'lo' {lo} on every axis"),
                ));
            }
            WallShape::Box {
                lo,
                hi,
                inside: w.inside.unwrap_or(true),
            }
        }
        WallKind::Mesh => {
            let mesh = build_mesh(cx, i, w)?;
            meshes.push(mesh);
            WallShape::Mesh {
                mesh: meshes.len() as u32 - 1,
                position: DVec3::ZERO,
                orientation: DQuat::IDENTITY,
            }
        }
    };
    let default_center = match shape {
        WallShape::Plane { point, .. } | WallShape::Cylinder { point, .. } => point,
        WallShape::Box { lo, hi, .. } => 0.5 * (lo + hi),
        // the image of the file's origin
        WallShape::Mesh { .. } => w.offset.map(v3).unwrap_or_default(),
    };
    let o3 = |cx: &Cx, k: &'static str, v: Option<[f64; 3]>| -> R<DVec3> {
        v.map(|a| cx.vec3(&p(k), a, k))
            .transpose()
            .map(|x| x.unwrap_or_default())
    };
    let motion = WallMotion {
        velocity: o3(cx, "velocity", w.velocity)?,
        angular_velocity: o3(cx, "angular_velocity", w.angular_velocity)?,
        center: match w.center {
            Some(c) => cx.vec3(&p("center"), c, "center")?,
            None => default_center,
        },
        surface_velocity: o3(cx, "surface_velocity", w.surface_velocity)?,
    };
    Ok(Wall {
        name,
        shape,
        material,
        motion,
        multi_contact: w.multi_contact.unwrap_or_default(),
        active: w.active.unwrap_or(true),
    })
}

/// Reads and places the mesh of a `type = "mesh"` wall: file point `p`
/// becomes `offset + R(axis, angle) · (scale · p)` (world frame, m).
fn build_mesh(cx: &mut Cx, i: usize, w: &RawWall) -> R<TriMesh> {
    let tp = [K("wall"), I(i)];
    let p = |k: &'static str| [K("wall"), I(i), K(k)];
    let f = w.file.as_ref().ok_or_else(|| {
        cx.missing(
            &tp,
            "[[wall]] of type \"mesh\"",
            "file",
            "an STL or OBJ file relative to the scenario, file = \"data/hopper.stl\"",
        )
    })?;
    let scale = match w.scale {
        Some(s) => cx.positive(&p("scale"), s, "scale", "")?,
        None => 1.0,
    };
    let offset = match w.offset {
        Some(o) => cx.vec3(&p("offset"), o, "offset")?,
        None => DVec3::ZERO,
    };
    let rotation = match &w.rotation {
        None => DQuat::IDENTITY,
        Some(r) => {
            let rp = |k: &'static str| [K("wall"), I(i), K("rotation"), K(k)];
            let what = "'rotation' of a [[wall]] of type \"mesh\"";
            let axis = r.axis.ok_or_else(|| {
                cx.missing(
                    &p("rotation"),
                    what,
                    "axis",
                    "rotation = { axis = [1, 0, 0], angle = 90 }",
                )
            })?;
            let angle = r.angle.ok_or_else(|| {
                cx.missing(
                    &p("rotation"),
                    what,
                    "angle",
                    "the angle in degrees, e.g. angle = 90",
                )
            })?;
            let axis = cx.unit(&rp("axis"), axis, "axis")?;
            if !angle.is_finite() {
                return Err(cx.err(
                    &rp("angle"),
                    format!("'angle' must be finite (degrees), found {angle}"),
                ));
            }
            DQuat::from_axis_angle(axis, angle.to_radians())
        }
    };
    let merge_angle = match w.merge_angle {
        None => clump_core::wall::mesh::DEFAULT_MERGE_ANGLE,
        Some(a) if a.is_finite() && (0.0..90.0).contains(&a) => a.to_radians(),
        Some(a) => {
            return Err(cx
                .err(
                    &p("merge_angle"),
                    format!("'merge_angle' must be in [0, 90) degrees, found {a}"),
                )
                .label("out of range"))
        }
    };
    let bytes = cx.read_file(&p("file"), "mesh", f)?;
    let t = crate::mesh_file::MeshTransform {
        scale,
        rotation,
        offset,
    };
    let mut mesh = crate::mesh_file::read_mesh_bytes(&bytes, std::path::Path::new(f), &t)
        .map_err(|e| {
            cx.err(&p("file"), format!("mesh file '{f}' is invalid: {e}"))
                .note("help: a mesh wall needs an STL (ASCII or binary) or OBJ file with at least one triangle of non-zero area")
        })?;
    mesh.merge_angle = merge_angle;
    Ok(mesh)
}

fn build_region(cx: &Cx, base: &[Seg], r: &RawRegion) -> R<Region> {
    let p = |k: &'static str| {
        let mut v = base.to_vec();
        v.push(K(k));
        v
    };
    let kind = r.kind.ok_or_else(|| {
        cx.missing(
            base,
            "region",
            "type",
            "type = \"box\" (lo, hi) or \"cylinder\" (base, axis, radius, height)",
        )
    })?;
    let (allowed, kname): (&[&str], &str) = match kind {
        RegionKind::Box => (&["lo", "hi"], "box"),
        RegionKind::Cylinder => (&["base", "axis", "radius", "height"], "cylinder"),
    };
    for (k, present) in [
        ("lo", r.lo.is_some()),
        ("hi", r.hi.is_some()),
        ("base", r.base.is_some()),
        ("axis", r.axis.is_some()),
        ("radius", r.radius.is_some()),
        ("height", r.height.is_some()),
    ] {
        if present && !allowed.contains(&k) {
            return Err(cx.src.error_at_key(
                &p(k),
                format!(
                    "'{k}' does not apply to a region of type \"{kname}\" (it uses {})",
                    allowed.join(", ")
                ),
            ));
        }
    }
    match kind {
        RegionKind::Box => {
            let lo =
                r.lo.ok_or_else(|| cx.missing(base, "region", "lo", "lower corner in m"))?;
            let hi =
                r.hi.ok_or_else(|| cx.missing(base, "region", "hi", "upper corner in m"))?;
            let (lo, hi) = (cx.vec3(&p("lo"), lo, "lo")?, cx.vec3(&p("hi"), hi, "hi")?);
            if hi.cmple(lo).any() {
                return Err(cx.err(
                    &p("hi"),
                    format!("region 'hi' {hi} must be above 'lo' {lo} on every axis"),
                ));
            }
            Ok(Region::Box { lo, hi })
        }
        RegionKind::Cylinder => {
            let b = r.base.ok_or_else(|| {
                cx.missing(base, "region", "base", "centre of the bottom disc in m")
            })?;
            let b = cx.vec3(&p("base"), b, "base")?;
            let axis = cx.unit(&p("axis"), r.axis.unwrap_or([0.0, 0.0, 1.0]), "axis")?;
            let radius = r
                .radius
                .ok_or_else(|| cx.missing(base, "region", "radius", "radius in m"))?;
            let height = r
                .height
                .ok_or_else(|| cx.missing(base, "region", "height", "height in m"))?;
            let radius = cx.positive(&p("radius"), radius, "radius", "m")?;
            let height = cx.positive(&p("height"), height, "height", "m")?;
            Ok(Region::Cylinder {
                base: b,
                axis,
                radius,
                height,
            })
        }
    }
}

#[allow(clippy::too_many_arguments)]
fn build_insert(
    cx: &mut Cx,
    i: usize,
    ins: &RawInsert,
    stages: &[StageDef],
    stage_names: &[String],
    templates: &[TemplateDef],
    template_names: &[String],
    mixes: &[MixDef],
    mix_names: &[String],
    dt: f64,
) -> R<InsertDef> {
    let tp = [K("insert"), I(i)];
    let p = |k: &'static str| [K("insert"), I(i), K(k)];
    let kind = ins.kind.ok_or_else(|| {
        cx.missing(
            &tp,
            "[[insert]]",
            "kind",
            "kind = \"pack\" (or \"stream\", \"file\")",
        )
    })?;
    let kname = match kind {
        InsertKind::File => "file",
        InsertKind::Pack => "pack",
        InsertKind::Stream => "stream",
    };
    let stage = match &ins.stage {
        Some(s) => lookup(cx, &p("stage"), "stage", s, stage_names)?,
        None => 0,
    };
    let allowed: &[&str] = match kind {
        InsertKind::File => &["file", "template", "format", "orientation_frame"],
        InsertKind::Pack => &[
            "mix",
            "template",
            "count",
            "volume_fraction",
            "region",
            "seed",
            "velocity",
            "orientation",
            "max_attempts",
        ],
        InsertKind::Stream => &[
            "mix",
            "template",
            "count",
            "region",
            "seed",
            "velocity",
            "orientation",
            "bodies_per_second",
            "kg_per_second",
            "start",
            "end",
            "max_attempts",
        ],
    };
    for (k, present) in [
        ("file", ins.file.is_some()),
        ("format", ins.format.is_some()),
        ("orientation_frame", ins.orientation_frame.is_some()),
        ("mix", ins.mix.is_some()),
        ("template", ins.template.is_some()),
        ("count", ins.count.is_some()),
        ("volume_fraction", ins.volume_fraction.is_some()),
        ("region", ins.region.is_some()),
        ("seed", ins.seed.is_some()),
        ("velocity", ins.velocity.is_some()),
        ("orientation", ins.orientation.is_some()),
        ("bodies_per_second", ins.bodies_per_second.is_some()),
        ("kg_per_second", ins.kg_per_second.is_some()),
        ("start", ins.start.is_some()),
        ("end", ins.end.is_some()),
        ("max_attempts", ins.max_attempts.is_some()),
    ] {
        if present && !allowed.contains(&k) {
            return Err(cx
                .src
                .error_at_key(&p(k), format!("'{k}' does not apply to kind = \"{kname}\""))
                .note(format!(
                    "note: kind = \"{kname}\" uses: stage, {}",
                    allowed.join(", ")
                )));
        }
    }
    if kind == InsertKind::File {
        let f = ins.file.as_ref().ok_or_else(|| {
            cx.missing(
                &tp,
                "[[insert]] of kind \"file\"",
                "file",
                "a CSV file of bodies, relative to the scenario",
            )
        })?;
        let bytes = cx.read_file(&p("file"), "body", f)?;
        let default_template = match &ins.template {
            Some(t) => Some(lookup(cx, &p("template"), "template", t, template_names)? as u32),
            None => None,
        };
        let format = ins.format.unwrap_or_default();
        let mut bodies =
            super::bodies_file::parse(&bytes, format, template_names, default_template).map_err(
                |(line, msg)| {
                    cx.err(&p("file"), format!("{f}:{line}: {msg}"))
                        .label("in this file")
                },
            )?;
        if ins.orientation_frame == Some(super::raw::OrientationFrame::Input) {
            // q_input maps (x_input − com) to world; x_input − com =
            // input_to_body⁻¹ x_body, so body → world is q_input · input_to_body⁻¹.
            for b in &mut bodies {
                let t = &templates[b.template as usize].template;
                b.orientation = (b.orientation * t.input_to_body.conjugate()).normalize();
            }
        }
        return Ok(InsertDef {
            stage,
            kind: InsertSpec::File { bodies },
        });
    }
    // mix or template
    let mix = match (&ins.mix, &ins.template) {
        (Some(_), Some(_)) => {
            return Err(cx
                .src
                .error_at_key(&p("template"), "give either 'mix' or 'template', not both"))
        }
        (Some(m), None) => mixes[lookup(cx, &p("mix"), "mix", m, mix_names)?]
            .mix
            .clone(),
        (None, Some(t)) => {
            Mix::single(lookup(cx, &p("template"), "template", t, template_names)? as u32)
        }
        (None, None) => {
            return Err(cx.missing(
                &tp,
                &format!("[[insert]] of kind \"{kname}\""),
                "mix",
                "mix = \"name\" or template = \"name\"",
            ))
        }
    };
    let region_raw = ins.region.as_ref().ok_or_else(|| {
        cx.missing(
            &tp,
            &format!("[[insert]] of kind \"{kname}\""),
            "region",
            "region = { type = \"box\", lo = [..], hi = [..] }",
        )
    })?;
    let region = build_region(cx, &p("region"), region_raw)?;
    let velocity = match ins.velocity {
        Some(v) => cx.vec3(&p("velocity"), v, "velocity")?,
        None => DVec3::ZERO,
    };
    let orientation = match ins.orientation {
        None => Orientation::Random,
        Some(q) => {
            let q = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
            if !q.is_finite() || q.length() < 1e-12 {
                return Err(cx.err(
                    &p("orientation"),
                    "orientation must be a non-zero quaternion [w, x, y, z]",
                ));
            }
            Orientation::Fixed {
                quaternion: q.normalize(),
            }
        }
    };
    let seed = ins.seed.unwrap_or(1 + i as u64);
    // expected body volume
    let (mean_volume, mean_mass) = {
        let mut wsum = 0.0;
        let mut v = 0.0;
        let mut m = 0.0;
        for e in &mix.entries {
            let t = &templates[e.template as usize].template;
            let c = e.size.mean_cube();
            let w = match mix.basis {
                clump_core::insert::FractionBasis::Number => e.fraction,
                clump_core::insert::FractionBasis::Mass => e.fraction / (t.mass * c),
            };
            wsum += w;
            v += w * t.volume * c;
            m += w * t.mass * c;
        }
        (v / wsum, m / wsum)
    };
    let region_volume = region.volume();
    match kind {
        InsertKind::Pack => {
            let target = match (ins.count, ins.volume_fraction) {
                (Some(_), Some(_)) => {
                    return Err(cx.src.error_at_key(
                        &p("volume_fraction"),
                        "give either 'count' or 'volume_fraction', not both",
                    ))
                }
                (Some(n), None) => {
                    let phi = n as f64 * mean_volume / region_volume;
                    if phi > PACK_ERROR_FRACTION {
                        let cap = (RSA_LIMIT * region_volume / mean_volume).floor();
                        return Err(cx
                            .err(&p("count"), format!(
                                "the region cannot hold {n} bodies: they need a solid volume fraction of {phi:.2} of the region ({region_volume:.3e} m^3), but random packing reaches about {RSA_LIMIT}"
                            ))
                            .label(format!("at most about {cap} bodies fit"))
                            .note("help: enlarge the region, lower the count, or insert in several stages or with a stream"));
                    }
                    if phi > 0.3 {
                        let w = cx.src.warning_at(&p("count"), format!("packing {n} bodies fills {phi:.2} of the region; random packing may fail above about {RSA_LIMIT}"));
                        cx.warnings.push(w);
                    }
                    PackTarget::Count(n as usize)
                }
                (None, Some(f)) => {
                    let f = cx.positive(&p("volume_fraction"), f, "volume_fraction", "")?;
                    if f > PACK_ERROR_FRACTION {
                        return Err(cx
                            .err(&p("volume_fraction"), format!("volume_fraction {f} cannot be reached by random packing (about {RSA_LIMIT} at most)"))
                            .label("too dense"));
                    }
                    PackTarget::VolumeFraction(f)
                }
                (None, None) => {
                    return Err(cx.missing(
                        &tp,
                        "[[insert]] of kind \"pack\"",
                        "count",
                        "count = 500 (or volume_fraction = 0.3)",
                    ))
                }
            };
            let expected = match target {
                PackTarget::Count(n) => n as f64,
                PackTarget::VolumeFraction(f) => f * region_volume / mean_volume,
            };
            let spec = PackSpec {
                region,
                target,
                mix,
                velocity,
                orientation,
                max_attempts_per_body: ins.max_attempts.unwrap_or(1000),
            };
            Ok(InsertDef {
                stage,
                kind: InsertSpec::Pack {
                    spec,
                    seed,
                    expected_bodies: expected,
                },
            })
        }
        InsertKind::Stream => {
            let rate = match (ins.bodies_per_second, ins.kg_per_second) {
                (Some(_), Some(_)) => {
                    return Err(cx.src.error_at_key(
                        &p("kg_per_second"),
                        "give either 'bodies_per_second' or 'kg_per_second', not both",
                    ))
                }
                (Some(r), None) => StreamRate::BodiesPerSecond(cx.positive(
                    &p("bodies_per_second"),
                    r,
                    "bodies_per_second",
                    "1/s",
                )?),
                (None, Some(r)) => StreamRate::MassPerSecond(cx.positive(
                    &p("kg_per_second"),
                    r,
                    "kg_per_second",
                    "kg/s",
                )?),
                (None, None) => {
                    return Err(cx.missing(
                        &tp,
                        "[[insert]] of kind \"stream\"",
                        "bodies_per_second",
                        "bodies_per_second = 1000 (or kg_per_second = 0.5)",
                    ))
                }
            };
            let body_rate = match rate {
                StreamRate::BodiesPerSecond(r) => r,
                StreamRate::MassPerSecond(m) => m / mean_mass,
            };
            let st = &stages[stage];
            let t0 = st.first_step as f64 * dt;
            let t_stage_end = (st.first_step + st.steps) as f64 * dt;
            let start = cx.nonneg(&p("start"), ins.start.unwrap_or(0.0), "start", "s")?;
            let mut end = match ins.end {
                Some(e) => {
                    let e = cx.nonneg(&p("end"), e, "end", "s")?;
                    if e < start {
                        return Err(cx.err(
                            &p("end"),
                            format!("stream 'end' ({e} s) is before its 'start' ({start} s)"),
                        ));
                    }
                    t0 + e
                }
                None => t_stage_end,
            };
            if let Some(n) = ins.count {
                end = end.min(t0 + start + n as f64 / body_rate);
            }
            let vol_rate = body_rate * mean_volume;
            // the region must be able to take the stream: bodies leave at |v|
            let exit_normal = if velocity.length() > 0.0 {
                Some(velocity.normalize())
            } else {
                None
            };
            let flux_cap = match (exit_normal, region) {
                (Some(n), Region::Box { lo, hi }) => {
                    let d = hi - lo;
                    let area =
                        (d.y * d.z * n.x.abs() + d.x * d.z * n.y.abs() + d.x * d.y * n.z.abs())
                            .max(1e-300);
                    Some(RSA_LIMIT * area * velocity.length())
                }
                (
                    Some(n),
                    Region::Cylinder {
                        axis,
                        radius,
                        height,
                        ..
                    },
                ) => {
                    let c = n.dot(axis).abs();
                    let area = std::f64::consts::PI * radius * radius * c
                        + 2.0 * radius * height * (1.0 - c * c).sqrt();
                    Some(RSA_LIMIT * area * velocity.length())
                }
                (None, _) => None,
            };
            if let Some(cap) = flux_cap {
                if vol_rate > cap {
                    return Err(cx
                        .err(&p(if ins.bodies_per_second.is_some() { "bodies_per_second" } else { "kg_per_second" }), format!(
                            "the stream region cannot pass this rate: {vol_rate:.3e} m^3/s of solid through a region that lets through at most about {cap:.3e} m^3/s at {:.3} m/s",
                            velocity.length()
                        ))
                        .note("help: enlarge the region across the flow, raise the velocity, or lower the rate"));
                }
            }
            let spec = StreamSpec {
                region,
                mix,
                rate,
                velocity,
                start: t0 + start,
                end: Some(end),
                exit_normal,
                orientation,
                max_attempts_per_body: ins.max_attempts.unwrap_or(20),
            };
            let expected = (body_rate * (end - t0 - start)).max(0.0).floor();
            Ok(InsertDef {
                stage,
                kind: InsertSpec::Stream {
                    spec,
                    seed,
                    expected_bodies: expected,
                },
            })
        }
        InsertKind::File => unreachable!(),
    }
}
