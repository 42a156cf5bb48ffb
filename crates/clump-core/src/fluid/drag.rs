//! Drag laws: each gives the drag coefficient `β` (kg/s) of one particle,
//! so that its drag force is `F_d = β (u − v)` (N, world frame), `u` the
//! interstitial fluid velocity and `v` the particle velocity at its centre.
//! Inputs: `d` the (volume-equivalent) diameter (m), `eps` the local void
//! fraction (1 for a single particle), `w = |u − v|` (m/s), the fluid
//! density `rho` (kg/m³) and dynamic viscosity `mu` (Pa s). Each law is
//! written so that `w = 0` gives its finite Stokes limit (no division by
//! the Reynolds number). Equations: docs/theory.md T-60 to T-65.

use std::f64::consts::PI;

/// Fluid properties a law reads.
#[derive(Debug, Clone, Copy)]
pub struct FluidProps {
    /// Density, kg/m³.
    pub rho: f64,
    /// Dynamic viscosity, Pa s.
    pub mu: f64,
}

/// (T-60) Stokes drag, `F = 3π μ d (u − v)`, independent of `eps`.
pub fn stokes(f: FluidProps, d: f64, _eps: f64, _w: f64) -> f64 {
    3.0 * PI * f.mu * d
}

/// (T-61) Schiller & Naumann (1933): `C_d = 24/Re (1 + 0.15 Re^0.687)`
/// for `Re ≤ 1000`, 0.44 above, `Re = ρ w d/μ`; single particle
/// (`eps` unused). `β = (π/8) ρ d² C_d w`.
pub fn schiller_naumann(f: FluidProps, d: f64, _eps: f64, w: f64) -> f64 {
    let re = f.rho * w * d / f.mu;
    if re <= 1000.0 {
        3.0 * PI * f.mu * d * (1.0 + 0.15 * re.powf(0.687))
    } else {
        PI / 8.0 * f.rho * d * d * 0.44 * w
    }
}

/// (T-62) Di Felice (1994) with Dallavalle's `C_d = (0.63 + 4.8/√Re)²`:
/// `F = (π/8) ρ d² C_d (ε w)² ε^{−χ}`, `Re = ρ ε w d/μ` (superficial slip),
/// `χ = 3.7 − 0.65 exp(−(1.5 − log₁₀ Re)²/2)`.
pub fn di_felice(f: FluidProps, d: f64, eps: f64, w: f64) -> f64 {
    let re = f.rho * eps * w * d / f.mu;
    let chi = 3.7 - 0.65 * (-(1.5 - re.log10()).powi(2) / 2.0).exp();
    // C_d (ε w) = (0.63 √(ε w) + 4.8 √(μ/(ρ d)))², finite at w = 0
    let root = 0.63 * (eps * w).sqrt() + 4.8 * (f.mu / (f.rho * d)).sqrt();
    PI / 8.0 * f.rho * d * d * root * root * eps * eps.powf(-chi)
}

/// (T-63) Beetstra, van der Hoef & Kuipers (2007): `F = 3π μ d ε F(φ, Re) (u − v)`
/// with `φ = 1 − ε`, `Re = ρ ε w d/μ` and
/// `F = 10φ/ε² + ε²(1 + 1.5√φ) + 0.413 Re/(24 ε²) · (1/ε + 3εφ + 8.4 Re^−0.343)
/// / (1 + 10^{3φ} Re^{−(1+4φ)/2})`.
pub fn beetstra(f: FluidProps, d: f64, eps: f64, w: f64) -> f64 {
    let phi = 1.0 - eps;
    let re = f.rho * eps * w * d / f.mu;
    let e2 = eps * eps;
    let mut ff = 10.0 * phi / e2 + e2 * (1.0 + 1.5 * phi.sqrt());
    if re > 0.0 {
        let num = 1.0 / eps + 3.0 * eps * phi + 8.4 * re.powf(-0.343);
        let den = 1.0 + 10f64.powf(3.0 * phi) * re.powf(-(1.0 + 4.0 * phi) / 2.0);
        ff += 0.413 * re / (24.0 * e2) * num / den;
    }
    3.0 * PI * f.mu * d * eps * ff
}

/// (T-64) Gidaspow (1994): Ergun (1952) for `ε ≤ 0.8`, Wen & Yu (1966)
/// above, as the interphase coefficient `β_V` per unit volume, per
/// particle `β = β_V V_p/(1 − ε)`:
/// Ergun `β = V_p (150 (1−ε) μ/(ε d²) + 1.75 ρ w/d)`;
/// Wen–Yu `β = (3/4) C_d ρ ε w ε^−2.65 V_p/d`, `C_d = 24/Re_ε (1 + 0.15 Re_ε^0.687)`
/// for `Re_ε = ρ ε w d/μ ≤ 1000`, 0.44 above.
pub fn gidaspow(f: FluidProps, d: f64, eps: f64, w: f64) -> f64 {
    let vp = PI / 6.0 * d * d * d;
    if eps <= 0.8 {
        vp * (150.0 * (1.0 - eps) * f.mu / (eps * d * d) + 1.75 * f.rho * w / d)
    } else {
        let re = f.rho * eps * w * d / f.mu;
        let hinder = eps.powf(-2.65);
        if re <= 1000.0 {
            3.0 * PI * f.mu * d * (1.0 + 0.15 * re.powf(0.687)) * hinder
        } else {
            0.75 * 0.44 * f.rho * eps * w / d * vp * hinder
        }
    }
}

/// (T-65) Hölzer & Sommerfeld (2008), times `Re`:
/// `Re C_d = 8/√φ⊥ + 16/√φ + 3√Re/φ^{3/4} + 0.42·10^{0.4(−log₁₀ φ)^0.2} Re/φ⊥`,
/// `φ` the sphericity, `φ⊥` the crosswise sphericity.
pub fn holzer_sommerfeld_re_cd(re: f64, phi: f64, phi_perp: f64) -> f64 {
    let c = 0.42 * 10f64.powf(0.4 * (-phi.log10()).powf(0.2));
    8.0 / phi_perp.sqrt() + 16.0 / phi.sqrt() + 3.0 * re.sqrt() / phi.powf(0.75) + c * re / phi_perp
}

/// The shape correction of a non-spherical particle at particle Reynolds
/// number `re = ρ w d_v/μ`: Hölzer–Sommerfeld's `C_d` of the shape over
/// theirs of the sphere, which multiplies a law's `β` (so a sphere keeps
/// the law exactly).
pub fn shape_factor(re: f64, phi: f64, phi_perp: f64) -> f64 {
    holzer_sommerfeld_re_cd(re, phi, phi_perp) / holzer_sommerfeld_re_cd(re, 1.0, 1.0)
}
