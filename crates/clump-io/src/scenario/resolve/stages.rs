//! `[[stage]]` (or the single stage of `[simulation]`): durations, gravity
//! and wall changes.

use super::model::*;
use super::raw::*;
use super::source::Seg;
use super::Seg::{I, K};
use super::{lookup, unique_name, Cx, R};
use crate::scenario::bounds;
use glam::DVec3;

/// The stages in order, with their first steps; `sim` is `[simulation]`.
pub(super) fn stages(
    cx: &mut Cx,
    raw: &RawScenario,
    sim: &RawSimulation,
    wall_names: &[String],
    dt: f64,
) -> R<Vec<StageDef>> {
    // ---------------- stages
    let mut stages: Vec<StageDef> = Vec::new();
    if raw.stage.is_empty() {
        let steps = steps_of(
            cx,
            dt,
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
            bodies: Vec::new(),
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
        for (i, st) in raw.stage.iter().enumerate() {
            match stage(cx, i, st, &names, wall_names, dt, first) {
                Ok(def) => {
                    // after a failed stage the later stages' first steps are
                    // not known; they are still checked for their own errors
                    match bounds::add_steps(cx.src, &[K("stage"), I(i)], first, def.steps) {
                        Ok(next) => first = next,
                        Err(d) => cx.errors.push(d),
                    }
                    names.push(def.name.clone());
                    stages.push(def);
                }
                Err(d) => cx.errors.push(d),
            }
        }
    }
    cx.barrier()?;
    Ok(stages)
}

/// The steps of a stage given by `duration` (s) or `steps`, not both.
fn steps_of(
    cx: &Cx,
    dt: f64,
    base: &[Seg],
    what: &str,
    duration: Option<f64>,
    steps: Option<u64>,
) -> R<u64> {
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
}

/// One `[[stage]]` entry, checked; `first` is its first step.
fn stage(
    cx: &Cx,
    i: usize,
    s: &RawStage,
    names: &[String],
    wall_names: &[String],
    dt: f64,
    first: u64,
) -> R<StageDef> {
    let t = [K("stage"), I(i)];
    let name = s.name.clone().unwrap_or_else(|| format!("stage{}", i + 1));
    unique_name(cx, &[K("stage"), I(i), K("name")], "stage", &name, &names)?;
    let steps = steps_of(cx, dt, &t, "[[stage]]", s.duration, s.steps)?;
    let gravity = match s.gravity {
        Some(g) => Some(cx.vec3(&[K("stage"), I(i), K("gravity")], g, "gravity")?),
        None => None,
    };
    let mut changes = Vec::new();
    for (j, c) in s.wall.iter().enumerate() {
        let cp = |k: &'static str| [K("stage"), I(i), K("wall"), I(j), K(k)];
        let ct = [K("stage"), I(i), K("wall"), I(j)];
        let wn = c
            .name
            .as_ref()
            .ok_or_else(|| cx.missing(&ct, "[[stage.wall]]", "name", "the name of a [[wall]]"))?;
        let wall = lookup(cx, &cp("name"), "wall", wn, wall_names)?;
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
    let mut bodies = Vec::new();
    for (j, c) in s.body.iter().enumerate() {
        let cp = |k: &'static str| [K("stage"), I(i), K("body"), I(j), K(k)];
        let ct = [K("stage"), I(i), K("body"), I(j)];
        let id = c.id.ok_or_else(|| {
            cx.missing(
                &ct,
                "[[stage.body]]",
                "id",
                "the global id of a body (1-based)",
            )
        })?;
        if id == 0 {
            return Err(cx.err(&cp("id"), "body ids start at 1"));
        }
        let opt = |cx: &Cx, k: &'static str, v: Option<[f64; 3]>| -> R<Option<DVec3>> {
            v.map(|a| cx.vec3(&cp(k), a, k)).transpose()
        };
        bodies.push(BodyChange {
            id,
            velocity: opt(cx, "velocity", c.velocity)?,
            angular_velocity: opt(cx, "angular_velocity", c.angular_velocity)?,
        });
    }
    Ok(StageDef {
        name,
        steps,
        first_step: first,
        gravity,
        walls: changes,
        bodies,
    })
}
