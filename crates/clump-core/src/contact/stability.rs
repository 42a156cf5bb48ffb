//! The stability limit of the explicit time step for a damped contact
//! (docs/theory.md T-51, T-52).
//!
//! Linearised about an overlap `δ`, a contact is a spring–dashpot of tangent
//! stiffness `k` (Hertz `2E*√(R*δ)`, linear `k_n`) and dashpot `γ_n`
//! between two bodies that respond at the contact like one point mass
//! `m_eff`, `1/m_eff = κ_a/m_a + κ_b/m_b` with the mobility factors `κ` of
//! [`crate::shape::mobility`] (a wall: `1/m = 0`). With `ω = √(k/m_eff)`
//! and `ζ = γ_n/(2√(k m_eff))` the central-difference (velocity-Verlet)
//! scheme is stable for `dt < dt_c = (2/ω)(√(1+ζ²) − ζ)` (Belytschko,
//! Liu & Moran, *Nonlinear Finite Elements*, 2000, §6.3). For the step's
//! form, whose dashpot uses the half-step velocity `(x_n − x_{n−1})/dt`,
//! the amplification polynomial is `λ² + (a + b − 2)λ + (1 − b)` with
//! `a = ω²dt²`, `b = 2ζω dt`; the Jury conditions give `b < 2` and
//! `a + 2b < 4`, and the second, `ω dt < 2(√(1+ζ²) − ζ)`, is the binding one. The dashpot is
//! calibrated with the bodies' masses, `γ_n = ĝ_n √(s m*)`, `m* = m_a m_b/
//! (m_a + m_b)`, so at a contact with `κ > 1` the damping ratio it actually
//! has is `ζ = ζ_calib √(m*/m_eff)` — larger, and the limit smaller, than
//! for spheres. Beyond `dt_c` the contact force flips sign every step with
//! a bounded amplitude (the normal force is clamped at zero), so the bed
//! never comes to rest.

use super::model::ContactModel;

/// `dt_c = (2/ω)(√(1+ζ²) − ζ)`, s, for angular frequency `omega` (rad/s) and
/// damping ratio `zeta ≥ 0`; written as `2/(ω(√(1+ζ²) + ζ))` to keep its
/// precision for large `ζ` (where it tends to `1/(ζω) = 2m/γ`).
pub fn critical_step(omega: f64, zeta: f64) -> f64 {
    2.0 / (omega * ((1.0 + zeta * zeta).sqrt() + zeta))
}

/// The stability limit (s) of one contact of `model` with effective radius
/// `r_star` (m) at overlap `overlap` (m), calibration mass `m_star` (kg, the
/// `m*` the dashpot is scaled with) and effective mass at the contact
/// `m_eff` (kg), from the normal spring and dashpot.
pub fn contact_step_limit(
    model: &ContactModel,
    r_star: f64,
    overlap: f64,
    m_star: f64,
    m_eff: f64,
) -> f64 {
    let law = model.sliding_law();
    let k = model.normal_stiffness(r_star, overlap);
    let s = super::normal::stiffness_scale(law.hertz, r_star, overlap);
    let gamma = super::damping::dashpot(law.gn_coef, s, m_star);
    let omega = (k / m_eff).sqrt();
    let zeta = gamma / (2.0 * (k * m_eff).sqrt());
    critical_step(omega, zeta)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The undamped limit is the textbook 2/ω; a pure dashpot (ζ → ∞) the
    /// forward-Euler limit 2m/γ = 1/(ζω).
    #[test]
    fn limits_of_the_closed_form() {
        assert_eq!(critical_step(1.0, 0.0), 2.0);
        let (w, z) = (3.0, 1e6);
        assert!((critical_step(w, z) * z * w - 1.0).abs() < 1e-9);
    }

    /// The closed form against the explicit scheme itself: a mass on a
    /// linear spring–dashpot integrated with the velocity-Verlet scheme
    /// whose dashpot uses the half-step velocity (as the step does) grows
    /// just above dt_c and decays just below.
    #[test]
    fn closed_form_matches_the_scheme() {
        for &zeta in &[0.0, 0.5, 1.243, 3.0] {
            let (k, m) = (1.0, 1.0);
            let gamma = 2.0 * zeta * (k * m as f64).sqrt();
            let dtc = critical_step((k / m as f64).sqrt(), zeta);
            // largest |x| over the last 100 of 600 steps against the first 100
            let growth = |dt: f64| {
                let (mut x, mut v) = (1.0f64, 0.0f64);
                let mut f = -k * x;
                let (mut early, mut late) = (0.0f64, 0.0f64);
                for step in 0..600 {
                    let vh = v + 0.5 * dt * f / m;
                    x += dt * vh;
                    f = -k * x - gamma * vh;
                    v = vh + 0.5 * dt * f / m;
                    if step < 100 {
                        early = early.max(x.abs());
                    } else if step >= 500 {
                        late = late.max(x.abs());
                    }
                }
                late / early
            };
            assert!(
                growth(dtc * 1.02) > 10.0,
                "ζ = {zeta}: not unstable above dt_c"
            );
            // undamped, the scheme is neutrally stable below dt_c (|λ| = 1: the
            // window maxima differ only by where the samples fall)
            let bound = if zeta == 0.0 { 1.05 } else { 1.0 };
            assert!(
                growth(dtc * 0.98) < bound,
                "ζ = {zeta}: not stable below dt_c"
            );
        }
    }
}
