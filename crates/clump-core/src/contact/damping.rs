//! Normal and tangential dashpots, and their calibration from the coefficient
//! of restitution `e`.
//!
//! The dashpot force on `i` is `−γ v` (normal: `−γ_n v_n n`, tangential:
//! `−γ_t v_t`), with `γ ≥ 0`.
//!
//! # Linear spring (both damping laws)
//! `γ_n = −2β√(m* k_n)`, `γ_t = −2β√(m* k_t)` with
//! `β = ln e/√(ln²e + π²)` ([`log_beta`]). For a linear spring whose contact
//! ends when `δ ≤ 0` (no tensile clamp) this is exact: the rebound speed is `e`
//! times the impact speed. LIGGGHTS' `hooke` model uses the same formula, so
//! [`DampingLaw::Liggghts`] and [`DampingLaw::Exact`] coincide for
//! [`super::NormalLaw::Linear`].
//!
//! # Hertz spring
//! Both laws use the Tsuji-type form of LIGGGHTS' `hertz` model,
//! `γ_n = −2√(5/6)·β·√(S_n m*)`, `S_n = 2E*√(R*δ)`, and
//! `γ_t = −2√(5/6)·β·√(S_t m*)`, `S_t = 8G*√(R*δ)`, so the normal dashpot force
//! grows as `δ^{1/4} v` and the restitution does not depend on the impact
//! velocity.
//!
//! ## The restitution-exact coefficient
//! Head-on impact at relative normal speed `v₀`:
//! `m* δ̈ = −K δ^{3/2} − γ_n δ̇`, `K = (4/3)E*√R*`. Since `S_n = (3/2)K δ^{1/2}`,
//! `γ_n = 2√(5/6)(−β)√(3/2)√(K m*) δ^{1/4} = √5 (−β) √(K m*) δ^{1/4}`.
//! With `δ = L x`, `t = T τ`, `L = (m* v₀²/K)^{2/5}`, `T = L/v₀` this becomes the
//! parameter-free problem
//!
//! `x'' = −x^{3/2} − c x^{1/4} x'`, `x(0) = 0`, `x'(0) = 1`, `c = −√5 β`,
//!
//! and `e = −x'(τ_end)` at the first return to `x = 0` (contact ends when
//! `δ ≤ 0`; the force is **not** clamped, as in the engine). So `e` depends on
//! `β` only, as shown by Antypov & Elliott (2011), "On an analytical solution
//! for the damped Hertzian spring", EPL 94:50004.
//!
//! **Closed form.** Write `p = x'` and `w = (4/5)x^{5/4}` (so `dw = x^{1/4}dx`).
//! Along a trajectory `dp/dw = (−x^{3/2} − c x^{1/4}p)/(x^{1/4}p) = −(5/4)w/p − c`,
//! which is exactly the phase-plane equation `dp/dw = −(5/4)w/p − c` of the
//! *linear* oscillator `W'' + cW' + (5/4)W = 0` (with `p = W'`). Both start at
//! `(w, p) = (0, 1)` and contact ends at `w = 0 ⇔ x = 0`, so the exit speed is
//! the linear one: `e = exp(−ζπ/√(1−ζ²))` with `ζ = c/(2√(5/4)) = c/√5 = −β`,
//! i.e. `β = ln e/√(ln²e + π²)` **exactly** — the `2√(5/6)` prefactor of the
//! Tsuji/LIGGGHTS dashpot is precisely the one that makes this hold. (The
//! phase path is shared, not the time: the Hertz contact lasts longer.) Hence
//! `c_crit = √5` (`β = −1`): for `β ≤ −1` the overlap decays to zero only
//! asymptotically and there is no rebound.
//!
//! [`DampingLaw::Exact`] uses this closed form ([`exact_hertz_beta`]); it is
//! cross-checked against a direct numerical solution, [`hertz_restitution`]
//! (RK4 of the non-dimensional problem, `Δτ = 10⁻³`, end of contact located by
//! interpolation) and [`exact_hertz_beta_numeric`] (bracketed root search on
//! `β`), which agree to a few 10⁻⁶. Consequently, under this crate's no-clamp rule
//! [`DampingLaw::Liggghts`] and [`DampingLaw::Exact`] produce **identical**
//! coefficients for both normal laws; the variants are kept for configuration
//! compatibility. The often-reported bias of LIGGGHTS' formula for Hertz
//! (measured `e` above the input; Schwager & Pöschel 2008, Thornton, Cummins &
//! Cleary 2013, Powder Technol. 233:30) appears when the tensile part of the
//! normal force is clamped to zero (LIGGGHTS' `limitForce`), which this crate
//! does not do.
//!
//! `e = 0` gives `β = −1` (critical damping: no rebound, for both laws);
//! `e = 1` gives `β = 0` (no damping).

use serde::{Deserialize, Serialize};

/// How the dashpot coefficients are derived from the restitution `e`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DampingLaw {
    /// Restitution-exact for the chosen normal law (default): the measured
    /// normal restitution of a head-on impact equals the input `e`.
    #[default]
    Exact,
    /// LIGGGHTS' formula `β = ln e/√(ln²e + π²)` for every normal law (exact
    /// for the linear law, biased for Hertz).
    Liggghts,
}

/// `2√(5/6)`, the prefactor of the Hertz (Tsuji/LIGGGHTS) dashpot
/// `γ = −2√(5/6)β√(S m*)`, dimensionless.
pub const HERTZ_DAMPING_PREFACTOR: f64 = 1.825_741_858_350_553_8;

/// The damping ratio of a linear spring–dashpot with restitution `e`,
/// `β = ln e/√(ln²e + π²)` (dimensionless, in `[−1, 0]`; `−1` for `e = 0`,
/// `0` for `e = 1`).
pub fn log_beta(e: f64) -> f64 {
    if e <= 0.0 {
        return -1.0;
    }
    if e >= 1.0 {
        return 0.0;
    }
    let l = e.ln();
    l / (l * l + std::f64::consts::PI * std::f64::consts::PI).sqrt()
}

/// Linear dashpot coefficient `γ = −2β√(m* k)`, kg/s, for stiffness `k` (N/m)
/// and effective mass `m*` (kg).
pub fn linear_gamma(beta: f64, stiffness: f64, mass: f64) -> f64 {
    -2.0 * beta * (stiffness * mass).sqrt()
}

/// Hertz dashpot coefficient `γ = −2√(5/6)β√(S m*)`, kg/s, for the stiffness
/// `S` (N/m; `S_n = 2E*√(R*δ)` or `S_t = 8G*√(R*δ)`) and effective mass `m*` (kg).
pub fn hertz_gamma(beta: f64, stiffness: f64, mass: f64) -> f64 {
    -HERTZ_DAMPING_PREFACTOR * beta * (stiffness * mass).sqrt()
}

/// RK4 step of the non-dimensional problem, `Δτ`.
const ODE_STEP: f64 = 1.0e-3;
/// Cap on the non-dimensional contact time; longer contacts count as `e = 0`.
const ODE_TAU_MAX: f64 = 60.0;
/// `√5`: `c = −√5 β`.
const SQRT5: f64 = 2.236_067_977_499_79;

/// Right-hand side `x'' = −x^{3/2} − c x^{1/4} x'` (no tensile clamp; `x` is
/// clamped at 0 only inside RK stages that overshoot the end of contact).
#[inline(always)]
fn rhs(x: f64, v: f64, c: f64) -> f64 {
    let xp = x.max(0.0);
    let r = xp.sqrt();
    -xp * r - c * r.sqrt() * v
}

/// Restitution of the non-dimensional damped Hertz impact
/// `x'' = −x^{3/2} − c x^{1/4} x'`, `x(0) = 0`, `x'(0) = 1`: returns
/// `−x'(τ_end)` at the first return to `x = 0` (0 if the sphere does not
/// separate by `τ = 60`).
pub fn hertz_restitution_nondim(c: f64) -> f64 {
    let h = ODE_STEP;
    // Start from the short-time series x ≈ τ − (16/45)cτ^{9/4},
    // x' ≈ 1 − (4/5)cτ^{5/4} (neglected terms O(τ^{5/2}), ~10⁻¹⁰ at τ₀ = 10⁻⁴),
    // which avoids stepping across the x^{1/4} singularity at τ = 0.
    let t0 = 1.0e-4_f64;
    let (mut x, mut v) = (
        t0 - 16.0 / 45.0 * c * t0.powf(2.25),
        1.0 - 0.8 * c * t0.powf(1.25),
    );
    let n_max = (ODE_TAU_MAX / h) as usize;
    for _ in 0..n_max {
        let k1x = v;
        let k1v = rhs(x, v, c);
        let k2x = v + 0.5 * h * k1v;
        let k2v = rhs(x + 0.5 * h * k1x, k2x, c);
        let k3x = v + 0.5 * h * k2v;
        let k3v = rhs(x + 0.5 * h * k2x, k3x, c);
        let k4x = v + h * k3v;
        let k4v = rhs(x + h * k3x, k4x, c);
        let xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        let vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if xn <= 0.0 {
            // End of contact inside this step: near x = 0 the force vanishes,
            // so interpolate linearly in x.
            let s = x / (x - xn);
            return (-(v + s * (vn - v))).max(0.0);
        }
        x = xn;
        v = vn;
    }
    0.0
}

/// Measured restitution of a head-on Hertz impact with the dashpot
/// `γ_n = −2√(5/6)β√(S_n m*)` (contact ends at `δ = 0`, no clamp); independent
/// of velocity, stiffness and mass. `β ∈ [−1, 0]`.
pub fn hertz_restitution(beta: f64) -> f64 {
    hertz_restitution_nondim(-SQRT5 * beta)
}

/// The damping ratio `β` (dimensionless, in `[−1, 0]`) for which the Hertz
/// dashpot `γ_n = −2√(5/6)β√(S_n m*)` gives exactly the restitution `e` in a
/// head-on impact without tensile clamping: by the phase-plane argument of the
/// module docs this is `ln e/√(ln²e + π²)` ([`log_beta`]). `e = 1 → 0`,
/// `e = 0 → −1` (no rebound).
pub fn exact_hertz_beta(e: f64) -> f64 {
    log_beta(e)
}

/// `β` with `hertz_restitution(β) = e`, found numerically (regula falsi with
/// the Illinois modification, safeguarded by bisection, on `c = −√5β ∈ [0, √5]`,
/// each evaluation an RK4 integration). An independent check of
/// [`exact_hertz_beta`]; it costs about a millisecond and is not used by
/// [`super::ContactModel`]. Accurate to a few 10⁻⁶ in `e` for `e ≳ 10⁻³` (longer
/// contacts are cut at `τ = 60`).
pub fn exact_hertz_beta_numeric(e: f64) -> f64 {
    if e >= 1.0 {
        return 0.0;
    }
    if e <= 0.0 {
        return -1.0;
    }
    // g(c) = e(c) − e_target is decreasing, g(0) = 1 − e > 0, g(√5) = −e < 0.
    let (mut a, mut b) = (0.0_f64, SQRT5);
    let (mut ga, mut gb) = (1.0 - e, -e);
    let mut side = 0i32;
    let mut c = 0.5 * (a + b);
    for it in 0..100 {
        // Illinois regula falsi; every 4th iteration a plain bisection step
        // guarantees the bracket shrinks.
        c = if it % 4 == 3 {
            0.5 * (a + b)
        } else {
            (a * gb - b * ga) / (gb - ga)
        };
        if !(c > a && c < b) {
            c = 0.5 * (a + b);
        }
        let g = hertz_restitution_nondim(c) - e;
        if g.abs() < 1e-10 || (b - a) < 1e-12 {
            break;
        }
        if g > 0.0 {
            a = c;
            ga = g;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        } else {
            b = c;
            gb = g;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        }
    }
    -c / SQRT5
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_beta_limits() {
        assert_eq!(log_beta(1.0), 0.0);
        assert_eq!(log_beta(0.0), -1.0);
        assert!(
            (log_beta(0.5) - (0.5f64.ln() / (0.5f64.ln().powi(2) + 9.869604401089358).sqrt()))
                .abs()
                < 1e-15
        );
    }

    #[test]
    fn prefactor() {
        assert!((HERTZ_DAMPING_PREFACTOR - 2.0 * (5.0f64 / 6.0).sqrt()).abs() < 1e-15);
        assert!((SQRT5 - 5.0f64.sqrt()).abs() < 1e-14);
    }

    #[test]
    fn undamped_is_elastic() {
        assert!((hertz_restitution_nondim(0.0) - 1.0).abs() < 1e-9);
    }

    /// The closed form agrees with the direct numerical solution.
    #[test]
    fn closed_form_matches_ode() {
        let mut worst = 0.0_f64;
        for k in 1..=19 {
            let e = 0.05 * k as f64;
            let b = exact_hertz_beta(e);
            worst = worst.max((hertz_restitution(b) - e).abs());
            let bn = exact_hertz_beta_numeric(e);
            assert!((bn - b).abs() < 1e-5, "e {e}: numeric {bn} closed {b}");
            assert!(b < 0.0 && b > -1.0);
        }
        assert!(worst < 1e-5, "worst |e_ode − e| = {worst}");
        for e in [0.01, 0.002] {
            assert!((hertz_restitution(exact_hertz_beta(e)) - e).abs() < 1e-5);
        }
        assert!(
            hertz_restitution(-1.0) < 1e-3,
            "beta = -1 (critical) must not rebound"
        );
    }
}
