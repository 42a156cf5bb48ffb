//! `[output]`: output intervals and trajectories.

use super::model::*;
use super::raw::*;
use super::source::Seg;
use super::Seg::{I, K};
use super::{Cx, R};
use crate::scenario::bounds;

/// The output settings; intervals in seconds become steps of `dt`.
/// `two_d`: the scenario is planar (trajectories write the angle θ).
pub(super) fn output(
    cx: &mut Cx,
    raw: &RawScenario,
    stages: &[StageDef],
    dt: f64,
    two_d: bool,
    domain: &clump_core::boundary::Domain,
) -> R<OutputDef> {
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
    let contacts = match &o.contacts {
        Some(e) => to_steps(cx, [K("output"), K("contacts")], e.every, e.every_steps)?,
        None => None,
    };
    let fields = match &o.fields {
        Some(f) => Some(fields(cx, f, &to_steps, domain)?),
        None => None,
    };
    let flow = flow(cx, &o.flow, &to_steps)?;
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
                extras: crate::trajectory::Extras {
                    euler: t.euler.unwrap_or(false),
                    loads: t.loads.unwrap_or(false),
                    planar: two_d,
                    temperature: raw.heat.is_some(),
                },
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
        contacts,
        fields,
        flow,
    };
    Ok(output)
}

/// `[output.fields]`: interval (steps) and what to coarse-grain.
fn fields(
    cx: &Cx,
    f: &RawFields,
    to_steps: &dyn Fn(&Cx, [Seg<'static>; 2], Option<f64>, Option<u64>) -> R<Option<u64>>,
    domain: &clump_core::boundary::Domain,
) -> R<(u64, crate::post::spec::FieldSpec)> {
    let at = |k: &'static str| [K("output"), K("fields"), K(k)];
    let every =
        to_steps(cx, [K("output"), K("fields")], f.every, f.every_steps)?.ok_or_else(|| {
            cx.err(
                &[K("output"), K("fields")],
                "give 'every' (s) or 'every_steps'",
            )
        })?;
    if f.axes.is_empty() || f.axes.len() > 3 {
        return Err(cx.err(
            &at("axes"),
            "'axes' lists 1 to 3 of \"x\", \"y\", \"z\", e.g. axes = [\"z\"]",
        ));
    }
    let mut axes = Vec::new();
    for (j, a) in f.axes.iter().enumerate() {
        let k = match a.as_str() {
            "x" => 0,
            "y" => 1,
            "z" => 2,
            _ => {
                return Err(cx.err(
                    &[K("output"), K("fields"), K("axes"), I(j)],
                    format!("unknown axis '{a}': allowed are \"x\", \"y\", \"z\""),
                ))
            }
        };
        if axes.contains(&k) {
            return Err(cx.err(
                &[K("output"), K("fields"), K("axes"), I(j)],
                format!("axis '{a}' is listed twice"),
            ));
        }
        axes.push(k);
    }
    if f.cells.len() != axes.len() {
        return Err(cx.err(
            &at("cells"),
            format!("'cells' needs one count per axis ({} axes)", axes.len()),
        ));
    }
    let mut cells = Vec::new();
    for (j, &c) in f.cells.iter().enumerate() {
        if !(1..=100_000).contains(&c) {
            return Err(cx.err(
                &[K("output"), K("fields"), K("cells"), I(j)],
                "cell counts are whole numbers from 1 to 100000",
            ));
        }
        cells.push(c as usize);
    }
    for (key, v) in [("lo", &f.lo), ("hi", &f.hi)] {
        if let Some(v) = v {
            if v.len() != axes.len() || v.iter().any(|x| !x.is_finite()) {
                return Err(cx.err(
                    &at(key),
                    format!(
                        "'{key}' needs one finite coordinate (m) per axis ({} axes)",
                        axes.len()
                    ),
                ));
            }
        }
    }
    let width = match f.width {
        Some(w) => cx.positive(&at("width"), w, "width", "m")?,
        None => {
            return Err(cx.err(
                &[K("output"), K("fields")],
                "missing key 'width' (the kernel's standard deviation, m)",
            ))
        }
    };
    let spec = crate::post::spec::FieldSpec {
        axes,
        cells,
        lo: f.lo.clone(),
        hi: f.hi.clone(),
        kernel: f.kernel.unwrap_or(crate::post::kernel::Kernel::Gaussian),
        width,
        average: f.average.unwrap_or(false),
    };
    let g = spec.grid(domain);
    if let Some(k) = (0..g.axes.len()).find(|&k| g.lo[k] >= g.hi[k]) {
        return Err(cx.err(
            &at("hi"),
            format!("'hi' must be above 'lo' along axis {}", f.axes[k]),
        ));
    }
    spec.check(domain).map_err(|e| cx.err(&at("width"), e))?;
    Ok((every, spec))
}

/// `[[output.flow]]`: the sampling interval (steps) and the probes.
fn flow(
    cx: &Cx,
    raw: &[RawFlow],
    to_steps: &dyn Fn(&Cx, [Seg<'static>; 2], Option<f64>, Option<u64>) -> R<Option<u64>>,
) -> R<Option<(u64, Vec<crate::post::flow::FlowProbe>)>> {
    use crate::post::flow::{FlowProbe, Probe};
    let mut every: Option<u64> = None;
    let mut probes = Vec::new();
    for (j, f) in raw.iter().enumerate() {
        let at = |k: &'static str| [K("output"), K("flow"), I(j), K(k)];
        let table = [K("output"), K("flow"), I(j)];
        let name = f
            .name
            .clone()
            .ok_or_else(|| cx.missing(&table, "[[output.flow]]", "name", "name = \"outlet\""))?;
        if name.is_empty() || name.contains(|c: char| c == ',' || c == '"' || c.is_whitespace()) {
            return Err(cx.err(
                &at("name"),
                "a probe name is a non-empty word without commas, quotes or spaces",
            ));
        }
        if probes.iter().any(|p: &FlowProbe| p.name == name) {
            return Err(cx.err(
                &at("name"),
                format!("a second probe named '{name}': names are unique"),
            ));
        }
        if let Some(e) = to_steps(cx, [K("output"), K("flow")], f.every, f.every_steps)? {
            if every.is_some_and(|x| x != e) {
                return Err(cx.err(&at(if f.every.is_some() { "every" } else { "every_steps" }), "every [[output.flow]] probe is sampled at one interval: give the same interval or leave it out after the first"));
            }
            every = Some(e);
        }
        let kind = f.kind.as_deref().ok_or_else(|| {
            cx.missing(
                &table,
                "[[output.flow]]",
                "type",
                "type = \"plane\" or \"region\"",
            )
        })?;
        let probe = match kind {
            "plane" => {
                let point = f
                    .point
                    .ok_or_else(|| cx.missing(&table, "a plane probe", "point", ""))?;
                let normal = f
                    .normal
                    .ok_or_else(|| cx.missing(&table, "a plane probe", "normal", ""))?;
                let (p, n) = (glam::DVec3::from(point), glam::DVec3::from(normal));
                if !p.is_finite() || !n.is_finite() || n.length() == 0.0 {
                    return Err(cx.err(
                        &at("normal"),
                        "'point' is finite and 'normal' a finite, non-zero vector",
                    ));
                }
                let stray = [
                    ("lo", f.lo.is_some()),
                    ("hi", f.hi.is_some()),
                    ("bins", f.bins.is_some()),
                ];
                if let Some((k, _)) = stray.iter().find(|x| x.1) {
                    return Err(cx.err(&at(k), "'lo', 'hi' and 'bins' belong to a region probe; a plane takes 'point' and 'normal'"));
                }
                Probe::Plane {
                    point: p,
                    normal: n.normalize(),
                }
            }
            "region" => {
                let lo =
                    f.lo.ok_or_else(|| cx.missing(&table, "a region probe", "lo", ""))?;
                let hi =
                    f.hi.ok_or_else(|| cx.missing(&table, "a region probe", "hi", ""))?;
                let (lo, hi) = (glam::DVec3::from(lo), glam::DVec3::from(hi));
                if !lo.is_finite() || !hi.is_finite() || (0..3).any(|a| lo[a] >= hi[a]) {
                    return Err(cx.err(&at("hi"), "'hi' must be above 'lo' along every axis (m)"));
                }
                let stray = [("point", f.point.is_some()), ("normal", f.normal.is_some())];
                if let Some((k, _)) = stray.iter().find(|x| x.1) {
                    return Err(cx.err(&at(k), "'point' and 'normal' belong to a plane probe; a region takes 'lo', 'hi' and 'bins'"));
                }
                let bins = f.bins.clone().unwrap_or_default();
                if bins.len() == 1
                    || bins.iter().any(|x| !x.is_finite() || *x < 0.0)
                    || bins.windows(2).any(|w| w[0] >= w[1])
                {
                    return Err(cx.err(
                        &at("bins"),
                        "'bins' lists at least two ascending diameters >= 0 (m), the bin edges",
                    ));
                }
                Probe::Region { lo, hi, bins }
            }
            other => {
                return Err(cx.err(
                    &at("type"),
                    format!("unknown probe type '{other}': allowed are \"plane\" and \"region\""),
                ))
            }
        };
        probes.push(FlowProbe { name, probe });
    }
    if probes.is_empty() {
        return Ok(None);
    }
    let every = every.ok_or_else(|| {
        cx.err(
            &[K("output"), K("flow"), I(0)],
            "give the sampling interval 'every' (s) or 'every_steps'",
        )
    })?;
    Ok(Some((every, probes)))
}

/// Warns about trajectory body ids above the number of bodies the inserts
/// are expected to place (ids are 1, 2, … in insertion order), which would
/// give an empty trajectory file (a driver that adds bodies itself, as from
/// Python, may still create them: hence a warning).
pub(super) fn unknown_trajectory_bodies(cx: &mut Cx, output: &OutputDef, inserts: &[InsertDef]) {
    let Some(t) = &output.trajectory else { return };
    let total: f64 = inserts
        .iter()
        .map(|i| match &i.kind {
            InsertSpec::File { bodies } => bodies.len() as f64,
            InsertSpec::Pack {
                expected_bodies, ..
            }
            | InsertSpec::Stream {
                expected_bodies, ..
            } => *expected_bodies,
        })
        .sum();
    let total = total.ceil();
    for (j, &b) in t.bodies.iter().enumerate() {
        if b as f64 > total {
            let w = cx
                .src
                .warning_at(
                    &[K("output"), K("trajectory"), K("bodies"), I(j)],
                    format!("body {b} may never exist: the inserts place about {total} bodies, numbered 1 to {total} in insertion order"),
                )
                .label("no such body expected");
            cx.warnings.push(w);
        }
    }
}
