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
    };
    Ok(output)
}
