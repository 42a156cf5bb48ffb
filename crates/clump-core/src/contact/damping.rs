//! Normal and tangential dashpots, and their calibration from the coefficient
//! of restitution `e`.
//!
//! The dashpot force on `i` is `−γ v` (normal: `−γ_n v_n n`, tangential:
//! `−γ_t v_t`), with `γ ≥ 0`. Both normal laws write the dashpots with one
//! dimensionless damping ratio `β ≤ 0` (`ζ = −β` in the usual notation):
//! - **linear**: `γ_n = −2β√(m* k_n)`, `γ_t = −2β√(m* k_t)`;
//! - **Hertz** (the Tsuji-type form of LIGGGHTS' `hertz` model):
//!   `γ_n = −2√(5/6)·β·√(S_n m*)`, `S_n = 2E*√(R*δ)`, and
//!   `γ_t = −2√(5/6)·β·√(S_t m*)`, `S_t = 8G*√(R*δ)`, so the normal dashpot
//!   force grows as `δ^{1/4} v` and the restitution does not depend on the
//!   impact velocity.
//!
//! # The tensile clamp
//! By default ([`super::PairProperties::tensile`] `= false`) the total normal
//! force of a contact between non-cohesive particles cannot pull:
//! `F_n = max(F_el − γ_n v_n, 0)`. Near the end of a damped rebound the
//! dashpot term would otherwise make `F_n` tensile. Under the clamp the
//! particle leaves with the speed it has when `F_n` first reaches zero (from
//! then on the elastic force keeps shrinking and the dashpot force stays
//! tensile, so `F_n` stays clamped at zero until `δ = 0`). With `tensile =
//! true` the force is not clamped (LIGGGHTS' default, `limitForce off`) and
//! the contact ends at `δ = 0`.
//!
//! # One problem for both laws
//! Head-on Hertz impact at relative normal speed `v₀`:
//! `m* δ̈ = −K δ^{3/2} − γ_n δ̇`, `K = (4/3)E*√R*`. Since `S_n = (3/2)K δ^{1/2}`,
//! `γ_n = √5 (−β) √(K m*) δ^{1/4}`. With `δ = L x`, `t = T τ`,
//! `L = (m* v₀²/K)^{2/5}`, `T = L/v₀` this becomes the parameter-free problem
//!
//! `x'' = −x^{3/2} − c x^{1/4} x'`, `x(0) = 0`, `x'(0) = 1`, `c = −√5 β`,
//!
//! so `e` depends on `β` only (Antypov & Elliott 2011, "On an analytical
//! solution for the damped Hertzian spring", EPL 94:50004).
//!
//! **Phase-plane mapping.** Write `p = x'` and `w = (4/5)x^{5/4}` (so
//! `dw = x^{1/4}dx`). Along a trajectory
//! `dp/dw = (−x^{3/2} − c x^{1/4}p)/(x^{1/4}p) = −(5/4)w/p − c`, which is
//! exactly the phase-plane equation of the *linear* oscillator
//! `W'' + cW' + (5/4)W = 0` (with `p = W'`), whose damping ratio is
//! `ζ = c/√5 = −β`. Both start at `(w, p) = (0, 1)`. Contact ends at
//! `w = 0 ⇔ x = 0` (unclamped), and the Hertz force
//! `x^{1/4}((5/4)w + cp)` vanishes exactly where the linear force
//! `(5/4)W + cW'` does (clamped). So in **both** cases the exit speed of the
//! Hertz impact equals that of the linear spring–dashpot with the same `β`
//! — the `2√(5/6)` prefactor of the Tsuji/LIGGGHTS dashpot is precisely the
//! one that makes this hold. (The phase path is shared, not the time: the
//! Hertz contact lasts longer.) For the linear oscillator
//! `x'' + 2ζx' + x = 0`, `x(0) = 0`, `x'(0) = 1`:
//!
//! - **unclamped** (contact ends at `x = 0`, `ζ < 1`):
//!   `e = exp(−ζπ/√(1−ζ²))`, i.e. `β = ln e/√(ln²e + π²)` ([`log_beta`]); for
//!   `ζ ≥ 1` the overlap decays to zero only asymptotically (no rebound).
//! - **clamped** (contact force ends where `x'' = 0`): with `ζ = cos α` the
//!   solution `x = e^{−ζt} sin(ω_d t)/ω_d`, `ω_d = √(1−ζ²)`, has
//!   `x'' ∝ sin(ω_d t − 2α)`, so the force vanishes at `ω_d t* = 2α` with
//!   `x'(t*) = −e^{−ζt*}`:
//!   `e = exp(−2ζ·A(ζ))`, `A(ζ) = arccos ζ/√(1−ζ²)` (`ζ < 1`), `A(1) = 1`,
//!   `A(ζ) = arccosh ζ/√(ζ²−1)` (`ζ > 1`, the same calculation with real
//!   exponents) — [`clamped_restitution`]. The force pulse lasts
//!   `t* = 2A(ζ)/ω₀`. `e` falls monotonically from 1 (`ζ = 0`) through
//!   `e^{−2} ≈ 0.135` at critical damping (`ζ = 1`: under the clamp a
//!   critically damped contact **does rebound**) to 0 only as `ζ → ∞`
//!   (`e ≈ 1/(4ζ²)`). There is no finite `β` for `e = 0`.
//!
//! # [`DampingLaw::Exact`] (default)
//! The measured head-on restitution equals the input `e`, for both laws:
//! - clamped (default): `β = −ζ` with `exp(−2ζA(ζ)) = e`, solved by
//!   bisection on the closed form ([`clamped_beta`]; a few µs, to machine
//!   precision). `β ∈ (−∞, 0]`: `e = 0.5 → β = −0.2553`, `e = 0.2 → −0.7312`,
//!   `e = 0.1 → −1.243`, `e = 0.01 → −4.807` (over-damped). Small `e` needs
//!   strong dashpots, `γ_n dt/m*` grows as `1/√e`: resolve the dashpot as
//!   well as the spring when choosing `dt`.
//! - `e = 0` with the clamp: no finite dashpot stops the rebound, so the
//!   pair instead uses critical damping `β = −1` **without** the clamp, the
//!   only finite-damping law with no rebound (the overlap decays to zero
//!   asymptotically; the normal force is slightly tensile in the tail, at
//!   most `e^{−3}/2 ≈ 2.5 %` of its peak for the linear law). See
//!   [`damping_ratio`].
//! - tensile (`tensile = true`): `β = ln e/√(ln²e + π²)` for both laws
//!   (exact there by the mapping above); `e = 0 → β = −1` (no rebound).
//!
//! The closed forms are cross-checked against a direct numerical solution of
//! the non-dimensional problems ([`restitution_numeric`]: RK4, `Δτ = 10⁻³`, end
//! of contact or of the force located by interpolation) and a bracketed root
//! search on `β` ([`beta_numeric`]); they agree to ~10⁻⁷ in `e`.
//!
//! # [`DampingLaw::Liggghts`]
//! LIGGGHTS' formula `β = ln e/√(ln²e + π²)` for both laws, whatever the
//! clamp. Without the clamp (`tensile = true`, LIGGGHTS' default) it is
//! restitution-exact for both laws, so it coincides with `Exact`. **Under the
//! clamp it is biased**: less energy is dissipated and the measured `e` is
//! above the input (`e = 0.8 → 0.808`, `0.5 → 0.550`, `0.2 → 0.325`,
//! `0 → e^{−2} ≈ 0.135`, for both laws; Schwager & Pöschel 2008, Thornton, Cummins & Cleary 2013,
//! Powder Technol. 233:30) — the bias reported for LIGGGHTS with
//! `limitForce on`.

use serde::{Deserialize, Serialize};

/// How the dashpot coefficients are derived from the restitution `e`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DampingLaw {
    /// Restitution-exact for the chosen normal law and clamp (default): the
    /// measured normal restitution of a head-on impact equals the input `e`.
    #[default]
    Exact,
    /// LIGGGHTS' formula `β = ln e/√(ln²e + π²)` for every normal law (exact
    /// without the tensile clamp, biased upwards with it).
    Liggghts,
}

/// `2√(5/6)`, the prefactor of the Hertz (Tsuji/LIGGGHTS) dashpot
/// `γ = −2√(5/6)β√(S m*)`, dimensionless.
pub const HERTZ_DAMPING_PREFACTOR: f64 = 1.825_741_858_350_553_8;

/// The damping ratio of an unclamped linear spring–dashpot with restitution
/// `e`, `β = ln e/√(ln²e + π²)` (dimensionless, in `[−1, 0]`; `−1` for
/// `e = 0`, `0` for `e = 1`).
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

/// `A(ζ)` of the module docs, dimensionless: `arccos ζ/√(1−ζ²)` for
/// `0 ≤ ζ < 1`, `1` at `ζ = 1`, `arccosh ζ/√(ζ²−1)` for `ζ > 1` (written
/// with `atan2` and `ln_1p` so that it stays accurate near `ζ = 1`).
fn clamp_a(zeta: f64) -> f64 {
    if zeta < 1.0 {
        let s = ((1.0 - zeta) * (1.0 + zeta)).sqrt();
        if s > 0.0 {
            s.atan2(zeta) / s
        } else {
            1.0
        }
    } else {
        let s = ((zeta - 1.0) * (zeta + 1.0)).sqrt();
        if s > 0.0 {
            (zeta - 1.0 + s).ln_1p() / s
        } else {
            1.0
        }
    }
}

/// Restitution of a head-on impact under the tensile clamp with damping ratio
/// `β ≤ 0` (dimensionless), the same for the linear and the Hertz law:
/// `e = exp(−2ζA(ζ))`, `ζ = −β` (module docs). `β = 0 → 1`,
/// `β = −1 → e^{−2}`, `→ 0` only as `β → −∞`.
pub fn clamped_restitution(beta: f64) -> f64 {
    let zeta = (-beta).max(0.0);
    if zeta.is_infinite() {
        return 0.0;
    }
    (-2.0 * zeta * clamp_a(zeta)).exp()
}

/// Duration of the force pulse of a clamped head-on linear impact in units of
/// `1/ω₀` (`ω₀ = √(k_n/m*)`), dimensionless: `ω₀t* = 2A(ζ)`, `ζ = −β`
/// (`π` undamped, 2 at critical damping, `→ 0` as `β → −∞`).
pub fn clamped_pulse_time(beta: f64) -> f64 {
    2.0 * clamp_a((-beta).max(0.0))
}

/// The damping ratio `β` (dimensionless, `≤ 0`) for which a clamped contact
/// (either normal law) rebounds with restitution `e`: the root of
/// [`clamped_restitution`]`(β) = e`, by bisection on `ζ = −β` (the exponent
/// `2ζA(ζ)` increases monotonically). Accurate to a few ulp; a few µs.
/// `e ≥ 1 → 0`; `e ≤ 0` (or NaN) → `−∞` (no finite damping stops the rebound).
pub fn clamped_beta(e: f64) -> f64 {
    if e >= 1.0 {
        return 0.0;
    }
    if e.is_nan() || e <= 0.0 {
        return f64::NEG_INFINITY;
    }
    let target = -e.ln();
    let g = |z: f64| 2.0 * z * clamp_a(z);
    let mut hi = 1.0_f64;
    while g(hi) < target {
        hi *= 2.0; // ζ ≈ e^{target/2}/2 for large target: bounded for e > 0
    }
    let mut lo = 0.0_f64;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if g(mid) < target {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    -0.5 * (lo + hi)
}

/// The damping ratio `β` (dimensionless) and whether the normal force is
/// clamped at zero, for damping law `law`, restitution `e ∈ [0, 1]` and the
/// pair's `tensile` option (see the module docs):
///
/// | law | `tensile` | `β` | clamped |
/// |---|---|---|---|
/// | `Exact` | false, `e > 0` | [`clamped_beta`]`(e)` | yes |
/// | `Exact` | false, `e = 0` | `−1` | no (no finite clamped dashpot stops the rebound) |
/// | `Exact` | true | [`log_beta`]`(e)` | no |
/// | `Liggghts` | false | [`log_beta`]`(e)` | yes (biased) |
/// | `Liggghts` | true | [`log_beta`]`(e)` | no |
pub fn damping_ratio(law: DampingLaw, e: f64, tensile: bool) -> (f64, bool) {
    match (law, tensile) {
        (_, true) => (log_beta(e), false),
        (DampingLaw::Liggghts, false) => (log_beta(e), true),
        (DampingLaw::Exact, false) if e > 0.0 => (clamped_beta(e), true),
        (DampingLaw::Exact, false) => (-1.0, false),
    }
}

/// The law's dashpot constants `(ĝ_n, ĝ_t)` for damping ratio `β ≤ 0`, such
/// that `γ = ĝ √(s m*)` ([`dashpot`]): Hertz `ĝ_n = −2√(5/6)β√(2E*)`,
/// `ĝ_t = −2√(5/6)β√(8G*)` (from [`hertz_gamma`] with `S_n = 2E* s`,
/// `S_t = 8G* s`); linear `ĝ_n = −2β√k_n`, `ĝ_t = −2β√k_t` ([`linear_gamma`]).
pub fn dashpot_coefficients(
    law: super::NormalLaw,
    beta: f64,
    e_star: f64,
    g_star: f64,
) -> (f64, f64) {
    match law {
        super::NormalLaw::Hertz => {
            let pre = -HERTZ_DAMPING_PREFACTOR * beta;
            (pre * (2.0 * e_star).sqrt(), pre * (8.0 * g_star).sqrt())
        }
        super::NormalLaw::Linear { kn, kt } => (-2.0 * beta * kn.sqrt(), -2.0 * beta * kt.sqrt()),
    }
}

/// Dashpot coefficient `γ = ĝ √(s m*)`, kg/s, from the law's constant `ĝ`
/// ([`dashpot_coefficients`]), the stiffness scale `s`
/// ([`super::normal::stiffness_scale`]) and the effective mass `m*` (kg).
#[inline(always)]
pub fn dashpot(coef: f64, scale: f64, mass: f64) -> f64 {
    coef * (scale * mass).sqrt()
}

/// Total normal force `F_n = F_el − γ_n v_n` (N) with the tensile clamp:
/// at least `floor` (0 clamped, −∞ tensile). `v_n` (m/s) is negative while
/// approaching. A comparison rather than `f64::max`: one instruction in
/// the vectorised loop, and NaN propagates.
#[inline(always)]
pub fn normal_force(f_el: f64, gamma_n: f64, v_n: f64, floor: f64) -> f64 {
    let f_raw = f_el - gamma_n * v_n;
    if f_raw < floor {
        floor
    } else {
        f_raw
    }
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

/// RK4 step of the non-dimensional problems, `Δτ`.
const ODE_STEP: f64 = 1.0e-3;
/// Cap on the non-dimensional contact time; longer contacts count as `e = 0`.
const ODE_TAU_MAX: f64 = 60.0;
/// `√5`: `c = −√5 β` for Hertz.
const SQRT5: f64 = 2.236_067_977_499_79;

/// Total (unclamped) non-dimensional normal force: Hertz
/// `x^{3/2} + c x^{1/4} x'`, linear `x + c x'` (`x` taken as 0 where an RK
/// stage overshoots the end of contact).
#[inline(always)]
fn nondim_force(hertz: bool, x: f64, v: f64, c: f64) -> f64 {
    let xp = x.max(0.0);
    if hertz {
        let r = xp.sqrt();
        xp * r + c * r.sqrt() * v
    } else {
        xp + c * v
    }
}

/// Restitution of the non-dimensional head-on impact `x'' = −F`, `x(0) = 0`,
/// `x'(0) = 1`, with `F = x^{3/2} + c x^{1/4}x'` (`hertz`, `c = −√5β`) or
/// `F = x + c x'` (linear, `c = −2β`), integrated by RK4 with `Δτ = 10⁻³`:
/// unclamped, `−x'` at the first return to `x = 0`; clamped, `−x'` where `F`
/// first reaches zero on the way out (the force stays zero afterwards, module
/// docs), both located by linear interpolation inside the step. 0 if neither
/// happens by `τ = 60`.
fn nondim_restitution(hertz: bool, c: f64, clamped: bool) -> f64 {
    let h = ODE_STEP;
    let (mut x, mut v) = if hertz {
        // Start from the short-time series x ≈ τ − (16/45)cτ^{9/4},
        // x' ≈ 1 − (4/5)cτ^{5/4} (neglected terms O(τ^{5/2}), ~10⁻¹⁰ at
        // τ₀ = 10⁻⁴), which avoids stepping across the x^{1/4} singularity.
        let t0 = 1.0e-4_f64;
        (
            t0 - 16.0 / 45.0 * c * t0.powf(2.25),
            1.0 - 0.8 * c * t0.powf(1.25),
        )
    } else {
        (0.0, 1.0)
    };
    let f = |x: f64, v: f64| -nondim_force(hertz, x, v, c);
    let n_max = (ODE_TAU_MAX / h) as usize;
    for _ in 0..n_max {
        let k1x = v;
        let k1v = f(x, v);
        let k2x = v + 0.5 * h * k1v;
        let k2v = f(x + 0.5 * h * k1x, k2x);
        let k3x = v + 0.5 * h * k2v;
        let k3v = f(x + 0.5 * h * k2x, k3x);
        let k4x = v + h * k3v;
        let k4v = f(x + h * k3x, k4x);
        let xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        let vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if xn <= 0.0 {
            // End of contact inside this step: near x = 0 the force is
            // small, so interpolate linearly in x.
            let s = x / (x - xn);
            return (-(v + s * (vn - v))).max(0.0);
        }
        if clamped && vn < 0.0 {
            let (f0, f1) = (nondim_force(hertz, x, v, c), nondim_force(hertz, xn, vn, c));
            if f1 <= 0.0 {
                // The force reaches zero inside this step; there x'' = 0, so
                // x' is nearly constant and linear interpolation is accurate.
                let s = if f0 > 0.0 { f0 / (f0 - f1) } else { 0.0 };
                return (-(v + s * (vn - v))).max(0.0);
            }
        }
        x = xn;
        v = vn;
    }
    0.0
}

/// Restitution of the non-dimensional damped Hertz impact without the clamp,
/// `x'' = −x^{3/2} − c x^{1/4} x'`, `x(0) = 0`, `x'(0) = 1`: `−x'(τ_end)` at
/// the first return to `x = 0` (0 if the sphere does not separate by
/// `τ = 60`). RK4, see [`restitution_numeric`].
pub fn hertz_restitution_nondim(c: f64) -> f64 {
    nondim_restitution(true, c, false)
}

/// Measured restitution of a head-on Hertz impact with the dashpot
/// `γ_n = −2√(5/6)β√(S_n m*)`, without the clamp (contact ends at `δ = 0`),
/// by RK4; independent of velocity, stiffness and mass. `β ∈ [−1, 0]`.
pub fn hertz_restitution(beta: f64) -> f64 {
    restitution_numeric(true, beta, false)
}

/// Measured restitution of a head-on impact with damping ratio `β ≤ 0`
/// (dimensionless), found by integrating the non-dimensional problem of the
/// module docs with RK4 (`Δτ = 10⁻³`): Hertz (`hertz`, dashpot
/// `−2√(5/6)β√(S_n m*)`) or linear (`−2β√(k_n m*)`), with or without the
/// tensile clamp. An independent check of [`clamped_restitution`] and
/// [`log_beta`]; about a millisecond per call. 0 if the contact does not end
/// by `τ = 60`.
pub fn restitution_numeric(hertz: bool, beta: f64, clamped: bool) -> f64 {
    let zeta = -beta;
    let c = if hertz { SQRT5 * zeta } else { 2.0 * zeta };
    nondim_restitution(hertz, c, clamped)
}

/// `β ≤ 0` with [`restitution_numeric`]`(hertz, β, clamped) = e`, found
/// numerically: regula falsi with the Illinois modification, safeguarded by
/// bisection, on `ζ = −β` in `[0, 1]` (unclamped) or in a bracket doubled
/// until it holds the root (clamped); each evaluation is an RK4 integration.
/// An independent check of [`damping_ratio`]'s closed forms; a few ms, not
/// used by [`super::ContactModel`]. Accurate to ~10⁻⁶ in `e` for `e ≳ 10⁻³`.
/// `e ≥ 1 → 0`; `e ≤ 0 → −1` (unclamped) or `−∞` (clamped).
pub fn beta_numeric(hertz: bool, e: f64, clamped: bool) -> f64 {
    if e >= 1.0 {
        return 0.0;
    }
    if e.is_nan() || e <= 0.0 {
        return if clamped { f64::NEG_INFINITY } else { -1.0 };
    }
    let g = |z: f64| restitution_numeric(hertz, -z, clamped) - e;
    // g(ζ) = e(ζ) − e_target is decreasing, g(0) = 1 − e > 0.
    let (mut a, mut b) = (0.0_f64, 1.0_f64);
    let (mut ga, mut gb) = (1.0 - e, g(1.0));
    while gb > 0.0 && b < 1e6 {
        a = b;
        ga = gb;
        b *= 2.0;
        gb = g(b);
    }
    let mut side = 0i32;
    let mut z = 0.5 * (a + b);
    for it in 0..100 {
        // Illinois regula falsi; every 4th iteration a plain bisection step
        // guarantees the bracket shrinks.
        z = if it % 4 == 3 {
            0.5 * (a + b)
        } else {
            (a * gb - b * ga) / (gb - ga)
        };
        if !(z > a && z < b) {
            z = 0.5 * (a + b);
        }
        let gz = g(z);
        if gz.abs() < 1e-10 || (b - a) < 1e-12 * b {
            break;
        }
        if gz > 0.0 {
            a = z;
            ga = gz;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        } else {
            b = z;
            gb = gz;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        }
    }
    -z
}

/// The damping ratio `β` (dimensionless, in `[−1, 0]`) for which the Hertz
/// dashpot `γ_n = −2√(5/6)β√(S_n m*)` gives exactly the restitution `e` in a
/// head-on impact **without** the tensile clamp: by the phase-plane argument
/// of the module docs this is `ln e/√(ln²e + π²)` ([`log_beta`]). `e = 1 → 0`,
/// `e = 0 → −1` (no rebound).
pub fn exact_hertz_beta(e: f64) -> f64 {
    log_beta(e)
}

/// [`beta_numeric`] for the unclamped Hertz impact: the numerical check of
/// [`exact_hertz_beta`].
pub fn exact_hertz_beta_numeric(e: f64) -> f64 {
    beta_numeric(true, e, false)
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
        for hertz in [true, false] {
            for clamped in [true, false] {
                // (the linear interpolation at x = 0 costs ~10⁻⁷ for the
                // linear law, whose force is not small there relative to h)
                let e = restitution_numeric(hertz, 0.0, clamped);
                assert!((e - 1.0).abs() < 1e-6, "{hertz} {clamped}: {e}");
            }
        }
        assert_eq!(clamped_restitution(0.0), 1.0);
        assert_eq!(clamped_beta(1.0), 0.0);
    }

    /// The unclamped closed form agrees with the direct numerical solution.
    #[test]
    fn closed_form_matches_ode() {
        let mut worst = 0.0_f64;
        for k in 1..=19 {
            let e = 0.05 * k as f64;
            let b = exact_hertz_beta(e);
            worst = worst.max((hertz_restitution(b) - e).abs());
            worst = worst.max((restitution_numeric(false, b, false) - e).abs());
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
            "beta = -1 (critical) must not rebound without the clamp"
        );
    }

    /// `A(ζ)` is continuous through ζ = 1 and has the right limits.
    #[test]
    fn clamp_a_is_smooth() {
        assert_eq!(clamp_a(1.0), 1.0);
        for d in [1e-12, 1e-9, 1e-6, 1e-3] {
            // A(1 ± d) ≈ 1 ∓ d/3
            let tol = 0.2 * d * d + 1e-14;
            assert!((clamp_a(1.0 - d) - (1.0 + d / 3.0)).abs() < tol, "{d}");
            assert!((clamp_a(1.0 + d) - (1.0 - d / 3.0)).abs() < tol, "{d}");
        }
        assert!((clamp_a(0.0) - std::f64::consts::FRAC_PI_2).abs() < 1e-15);
        // Large ζ: e ≈ 1/(4ζ²).
        let z = 1e4;
        assert!((clamped_restitution(-z) * 4.0 * z * z - 1.0).abs() < 1e-3);
        assert_eq!(clamped_restitution(f64::NEG_INFINITY), 0.0);
        assert!((clamped_restitution(-1.0) - (-2.0f64).exp()).abs() < 1e-15);
    }

    /// The clamped closed form and its inverse agree with the RK4 solution of
    /// both non-dimensional problems (an independent check), over
    /// e ∈ [0.01, 1], to ≤ 10⁻⁵ in e; the inverse round-trips to 10⁻¹².
    #[test]
    fn clamped_closed_form_matches_ode() {
        let mut worst = [0.0_f64; 2];
        let es: Vec<f64> = [
            0.01, 0.02, 0.05, 0.1, 0.135, 0.136, 0.2, 0.3, 0.5, 0.7, 0.9, 0.98,
        ]
        .into_iter()
        .chain((1..=19).map(|k| 0.05 * k as f64))
        .collect();
        for &e in &es {
            let b = clamped_beta(e);
            assert!(b <= 0.0 && b.is_finite());
            assert!(
                (clamped_restitution(b) - e).abs() < 1e-12 * e.max(0.1),
                "e {e}"
            );
            for (k, hertz) in [(0, true), (1, false)] {
                let e_ode = restitution_numeric(hertz, b, true);
                worst[k] = worst[k].max((e_ode - e).abs());
            }
        }
        eprintln!(
            "clamped: worst |e_ode − e| Hertz {:.2e}, linear {:.2e}",
            worst[0], worst[1]
        );
        assert!(
            worst[0] < 1e-5 && worst[1] < 1e-5,
            "worst |e_ode − e|: Hertz {:.2e}, linear {:.2e}",
            worst[0],
            worst[1]
        );
        // The root search on the ODE (no closed form involved) finds the same β.
        for e in [0.05, 0.3, 0.5, 0.9] {
            for hertz in [true, false] {
                let bn = beta_numeric(hertz, e, true);
                let b = clamped_beta(e);
                assert!(
                    (bn - b).abs() < 1e-5 * b.abs().max(1.0),
                    "e {e} {hertz}: {bn} vs {b}"
                );
            }
        }
        // Reference values (independent: the closed form evaluated by hand).
        assert!((clamped_beta(0.5) + 0.255_275_637_648_651_7).abs() < 1e-12);
        assert!((clamped_beta((-2.0f64).exp()) + 1.0).abs() < 1e-12);
        assert_eq!(clamped_beta(0.0), f64::NEG_INFINITY);
        assert_eq!(clamped_beta(f64::NAN), f64::NEG_INFINITY);
    }

    /// Critical damping rebounds under the clamp (e = e⁻²), and the
    /// LIGGGHTS formula is biased upwards there.
    #[test]
    fn clamp_bias_of_log_beta() {
        for hertz in [true, false] {
            let e = restitution_numeric(hertz, -1.0, true);
            assert!((e - (-2.0f64).exp()).abs() < 1e-5, "{hertz}: {e}");
            for e_in in [0.2, 0.5, 0.8] {
                let e_out = restitution_numeric(hertz, log_beta(e_in), true);
                assert!(e_out > e_in + 0.005, "{hertz} {e_in}: {e_out}");
                assert!((e_out - clamped_restitution(log_beta(e_in))).abs() < 1e-5);
            }
        }
    }

    #[test]
    fn damping_ratio_table() {
        use DampingLaw::*;
        assert_eq!(damping_ratio(Exact, 0.5, false), (clamped_beta(0.5), true));
        assert_eq!(damping_ratio(Exact, 0.0, false), (-1.0, false));
        assert_eq!(damping_ratio(Exact, 0.5, true), (log_beta(0.5), false));
        assert_eq!(damping_ratio(Exact, 0.0, true), (-1.0, false));
        assert_eq!(damping_ratio(Liggghts, 0.5, false), (log_beta(0.5), true));
        assert_eq!(damping_ratio(Liggghts, 0.0, false), (-1.0, true));
        assert_eq!(damping_ratio(Liggghts, 0.5, true), (log_beta(0.5), false));
        assert_eq!(damping_ratio(Exact, 1.0, false), (0.0, true));
    }

    /// Solving for β is cheap enough for `ContactModel::new`.
    #[test]
    fn clamped_beta_is_fast() {
        let t = std::time::Instant::now();
        let mut s = 0.0;
        for k in 0..1000 {
            s += clamped_beta(1e-3 + 0.998 * k as f64 / 1000.0);
        }
        let per = t.elapsed().as_secs_f64() / 1000.0;
        assert!(s.is_finite());
        assert!(per < 1e-3, "{per} s per solve");
    }
}
