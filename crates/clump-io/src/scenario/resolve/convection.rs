//! The heat keys of `[fluid]` (`temperature`, `thermal_conductivity`,
//! `specific_heat`): convection from the fluid (docs/theory.md T-90 …
//! T-93), checked key by key.

use super::heat::temperature;
use super::raw::RawScenario;
use super::Seg::K;
use super::{Cx, R};
use clump_core::heat::FluidHeat;

/// The fluid's thermal properties when `[fluid]` has a `temperature`
/// (convection on); `heat_on`: the scenario has `[heat]`, without which no
/// heat key of `[fluid]` may be given.
pub(super) fn fluid_heat(cx: &mut Cx, raw: &RawScenario, heat_on: bool) -> R<Option<FluidHeat>> {
    let Some(f) = &raw.fluid else {
        return Ok(None);
    };
    let p = |k: &'static str| [K("fluid"), K(k)];
    let given = [
        ("temperature", f.temperature),
        ("thermal_conductivity", f.thermal_conductivity),
        ("specific_heat", f.specific_heat),
    ];
    let first = given.iter().find(|(_, v)| v.is_some()).map(|(k, _)| *k);
    match (first, heat_on) {
        (None, _) => return Ok(None),
        (Some(k), false) => {
            return Err(cx
                .err(&p(k), "a heat key of [fluid] without [heat]: heat transfer is off")
                .label("has no effect")
                .note("help: add a [heat] table to turn heat transfer (and convection from the fluid) on, or remove the key"))
        }
        (Some(_), true) => {}
    }
    let Some(t) = f.temperature else {
        return Err(cx
            .err(&p(first.unwrap_or("thermal_conductivity")), "a fluid thermal property without the fluid's temperature: convection is off")
            .label("has no effect")
            .note("help: add temperature = ... (K) to [fluid] to turn convection from the fluid on, or remove the key"));
    };
    let temperature = temperature(cx, &p("temperature"), t)?;
    let property = |key: &'static str, v: Option<f64>, unit: &str, example: &str| match v {
        Some(x) => cx.positive(&p(key), x, key, unit),
        None => Err(cx.missing(&[K("fluid")], "[fluid] with a temperature", key, example)),
    };
    let conductivity = property(
        "thermal_conductivity",
        f.thermal_conductivity,
        "W/(m K)",
        "the fluid's thermal conductivity in W/(m K) for convection, e.g. thermal_conductivity = 0.6 (water)",
    )?;
    let specific_heat = property(
        "specific_heat",
        f.specific_heat,
        "J/(kg K)",
        "the fluid's specific heat in J/(kg K) for convection, e.g. specific_heat = 4180 (water)",
    )?;
    Ok(Some(FluidHeat {
        temperature,
        conductivity,
        specific_heat,
    }))
}
