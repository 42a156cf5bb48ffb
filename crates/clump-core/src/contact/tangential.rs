//! Tangential force: incremental history spring, dashpot and Coulomb limit.
//!
//! Per evaluation, with `n` the current unit normal and
//! `v_t = v_rel − (v_rel·n) n` the tangential relative velocity of the contact
//! points (m/s, world):
//! 1. **Rotate** the stored spring `ξ` (m, world) into the current tangent
//!    plane: remove its normal component and rescale it to its old length
//!    ([`rotate_into_plane`]); this follows the rotation of the contact without
//!    creating or destroying spring energy.
//! 2. **Increment**: `ξ ← ξ + v_t Δt`.
//! 3. **Trial force** on `i`: `F_t = −k_t ξ − γ_t v_t`, where `k_t` is
//!    `8G*√(R*δ)` (Hertz–Mindlin, evaluated at the current overlap) or the
//!    constant linear `k_t`, and `γ_t` is the tangential dashpot of
//!    [`super::damping`].
//! 4. **Coulomb limit** on the total tangential force: if `|F_t| > μF_n`,
//!    the contact slides: `F_t ← μF_n F_t/|F_t|` and the spring is stored so
//!    that its **elastic part alone** carries the limited force,
//!    `ξ = −F_t/k_t`. While sticking (`|F_t| ≤ μF_n`) the dashpot stays active.
//!
//! Why `ξ = −F_t/k_t` and not Luding's `ξ = −(F_t + γ_t v_t)/k_t` (Luding
//! 2008, "Cohesive, frictional powders: contact models for tension",
//! Granular Matter 10:235), which this crate used before: with strong
//! tangential damping, `γ_t|v_t| > μF_n`, Luding's stored spring points
//! *forward* (along the slip); with the Hertz–Mindlin `k_t ∝ √δ` growing
//! during loading, that spring then pulls the next trial force below the
//! limit, so a contact in gross sliding does not carry `μF_n` and the
//! tangential impulse of an oblique impact came out ~10 % low (Chung & Ooi
//! test 5, e = 0.5). With the elastic part at the limit, the next trial force
//! is `(k_t'/k_t)F_t − k_t' v_t Δt − γ_t v_t`: while the slip goes on, every
//! term opposes it and the dashpot adds to the demand instead of cancelling
//! the stored spring, so a grossly sliding contact carries `|F_t| = μF_n`
//! exactly at every step even while `k_t` grows (it sticks again only when
//! the slip slows, stops or reverses so that the demand falls below the
//! limit). This is close to LIGGGHTS (`tangential
//! history`), which compares the elastic part alone with the limit and drops
//! the dashpot while sliding; the two agree when `γ_t = 0`.
//!
//! `F_n` is the total (elastic + damping) normal force after the tensile
//! clamp (so `≥ 0`), or `|F_n|` for a pair with `tensile = true` (as
//! LIGGGHTS). With `k_t = 0` (a linear law with `kt = 0`) there is no
//! tangential force and the spring stays zero.
//!
//! # LIGGGHTS' rule ([`TangentialLaw::Liggghts`], [`liggghts_spring`])
//! LIGGGHTS 3.8 (`tangential history`, `tangential_model_history.h`) orders
//! the steps differently and limits only the spring:
//! 1. `ξ ← ξ + v_t Δt`, then the normal component is removed,
//!    `ξ ← ξ − (ξ·n) n` (projection without rescaling);
//! 2. if the spring force alone exceeds the limit, `k_t|ξ| > μ|F_n|`, the
//!    contact slides: `F_t = −μ|F_n| ξ/|ξ|` and `ξ = −F_t/k_t`; **the
//!    dashpot is dropped**;
//! 3. else it sticks: `F_t = −k_t ξ − γ_t v_t` (the total may then exceed
//!    `μ|F_n|` by up to `γ_t|v_t|`).

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Which rule limits the tangential force (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TangentialLaw {
    /// Spring plus dashpot limited to `μ|F_n|`; a sliding contact keeps the
    /// limit in its elastic spring ([`history_spring`]; default, the
    /// vectorised pair kernel).
    #[default]
    Clump,
    /// LIGGGHTS' `tangential history`: only the spring is checked against
    /// `μ|F_n|`, the dashpot is dropped while sliding ([`liggghts_spring`]).
    Liggghts,
    /// Micro-slip: Mindlin–Deresiewicz with loading, unloading and
    /// reloading history after Thornton & Yin (1991) / Thornton, Cummins &
    /// Cleary (2011) ([`super::micro_slip`]; Hertz law only, uses both
    /// history slots).
    MindlinDeresiewicz,
    /// Micro-slip exact for Hertz contact under arbitrary load histories:
    /// the method of dimensionality reduction with the profile kept per
    /// contact ([`super::mdr`]; Hertz law only, without cohesion).
    Mdr,
}

/// Rotates `v` (world) into the plane normal to the unit vector `n`: removes
/// its normal component and rescales the rest to the original length `|v|`.
/// If `v` is (almost) parallel to `n` (in-plane part below 10⁻⁶ of its length),
/// the result is zero. Same units as `v`.
#[inline(always)]
pub fn rotate_into_plane(v: DVec3, n: DVec3) -> DVec3 {
    let l0 = v.length_squared();
    let p = v - v.dot(n) * n;
    let lp = p.length_squared();
    let scale = if lp > 1e-12 * l0 {
        (l0 / lp).sqrt()
    } else {
        0.0
    };
    p * scale
}

/// Energy of the tangential spring `½ k_t |ξ|²`, J.
#[inline(always)]
pub fn spring_energy(kt: f64, xi: DVec3) -> f64 {
    0.5 * kt * xi.length_squared()
}

/// Tangential force on `i` (N, world) from the history spring, updating the
/// spring `xi` (m, world) in place as described in the module docs.
///
/// - `n`: unit normal (world); `v_t`: tangential relative velocity (m/s, world,
///   already in the tangent plane); `dt`: time step (s);
/// - `kt`: tangential stiffness (N/m, `≥ 0`);
/// - `gamma_t`: tangential dashpot coefficient (kg/s);
/// - `f_max`: Coulomb limit `μF_n` (N, `≥ 0`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn history_spring(
    xi: &mut DVec3,
    n: DVec3,
    v_t: DVec3,
    dt: f64,
    kt: f64,
    gamma_t: f64,
    f_max: f64,
) -> DVec3 {
    history_spring_as::<true>(xi, n, v_t, dt, kt, gamma_t, f_max).0
}

/// [`history_spring`], and whether the contact slides (its trial force
/// exceeds the limit). With `LIMIT` false the force and spring are those of
/// a contact that sticks, whether or not it does: the limit costs a square
/// root and two divisions, and a contact of a dense bed seldom slides
/// (0.2 % of the contacts of the settled tetra bed), so the batched pair
/// kernel takes the sticking result for all and evaluates again, with the
/// limit, only those that slide. For a contact that sticks both give the
/// same bits.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn history_spring_as<const LIMIT: bool>(
    xi: &mut DVec3,
    n: DVec3,
    v_t: DVec3,
    dt: f64,
    kt: f64,
    gamma_t: f64,
    f_max: f64,
) -> (DVec3, bool) {
    let s = rotate_into_plane(*xi, n) + v_t * dt;
    let f = -kt * s - gamma_t * v_t;
    let f2 = f.length_squared();
    // Branch-free (selects; the batched pair kernel runs this as vector
    // instructions). Sliding: the elastic spring alone carries the limited
    // force.
    let slide = f2 > f_max * f_max;
    let (xi_new, f_new) = if LIMIT {
        let fl = f * (f_max / f2.sqrt());
        if slide {
            (fl * (-1.0 / kt), fl)
        } else {
            (s, f)
        }
    } else {
        (s, f)
    };
    // no tangential stiffness: no tangential force, the spring stays zero
    let none = kt <= 0.0;
    *xi = if none { DVec3::ZERO } else { xi_new };
    let f_t = if none { DVec3::ZERO } else { f_new };
    (f_t, slide)
}

/// LIGGGHTS' history spring (module docs, "LIGGGHTS' rule"): tangential
/// force on `i` (N, world), updating `xi` (m, world). Arguments as
/// [`history_spring`]. With `k_t ≤ 0` there is no tangential force and the
/// spring stays zero, as in [`history_spring`].
#[inline]
pub fn liggghts_spring(
    xi: &mut DVec3,
    n: DVec3,
    v_t: DVec3,
    dt: f64,
    kt: f64,
    gamma_t: f64,
    f_max: f64,
) -> DVec3 {
    if kt <= 0.0 {
        *xi = DVec3::ZERO;
        return DVec3::ZERO;
    }
    let s = *xi + v_t * dt;
    let s = s - s.dot(n) * n;
    let mag = s.length();
    let f_spring = -kt * s;
    let f_shear = kt * mag;
    if f_shear > f_max {
        // sliding: the spring alone, rescaled to the limit; no dashpot
        let f = f_spring * (f_max / f_shear);
        *xi = f * (-1.0 / kt);
        f
    } else {
        *xi = s;
        f_spring - gamma_t * v_t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// LIGGGHTS' rule against hand-computed cases: sticking keeps the
    /// dashpot (and may exceed the limit by it), sliding drops it.
    #[test]
    fn liggghts_rule_cases() {
        let n = DVec3::Z;
        // sticking: spring 100 N/m × 1 mm = 0.1 N < 0.2 N; dashpot 0.5 × 0.3
        let mut xi = DVec3::new(0.9e-3, 0.0, 5e-4);
        let f = liggghts_spring(&mut xi, n, DVec3::new(0.1, 0.0, 0.0), 1e-3, 100.0, 0.5, 0.2);
        assert!((xi - DVec3::new(1e-3, 0.0, 0.0)).length() < 1e-15);
        assert!((f - DVec3::new(-0.1 - 0.05, 0.0, 0.0)).length() < 1e-15);
        // sticking although |F_t| = 0.25 > 0.2: only the spring is checked
        let mut xi = DVec3::new(0.9e-3, 0.0, 0.0);
        let f = liggghts_spring(&mut xi, n, DVec3::new(0.1, 0.0, 0.0), 1e-3, 100.0, 1.5, 0.2);
        assert!((f.x + 0.25).abs() < 1e-15, "{f}");
        // sliding: spring 0.3 N > 0.2 N: F_t = -0.2 N along ξ, no dashpot,
        // spring stored at the limit (2 mm)
        let mut xi = DVec3::new(2.9e-3, 0.0, 0.0);
        let f = liggghts_spring(&mut xi, n, DVec3::new(0.1, 0.0, 0.0), 1e-3, 100.0, 1.5, 0.2);
        assert!((f - DVec3::new(-0.2, 0.0, 0.0)).length() < 1e-15, "{f}");
        assert!((xi - DVec3::new(2e-3, 0.0, 0.0)).length() < 1e-15);
        // the default rule limits spring plus dashpot instead
        let mut xi = DVec3::new(0.9e-3, 0.0, 0.0);
        let f = history_spring(&mut xi, n, DVec3::new(0.1, 0.0, 0.0), 1e-3, 100.0, 1.5, 0.2);
        assert!((f.x + 0.2).abs() < 1e-15, "{f}");
    }
}
