//! Cohesion: the attractive part of the normal force, per material pair.
//!
//! # SJKR (LIGGGHTS' `cohesion sjkr`)
//! A cohesion energy density `k_c` (J/m³) times the area of the contact
//! circle, while the spheres overlap (`δ > 0`):
//!
//! `F_coh = −k_c A`, `A = π a²`,
//!
//! with `a` the radius of the circle in which the two undeformed spheres
//! intersect ([`lens_radius_sq`]): for radii `r_i`, `r_j` at distance
//! `d = r_i + r_j − δ`,
//! `a² = [(r_i + r_j)² − d²][d² − (r_i − r_j)²]/(4d²)`; for a sphere of
//! radius `r` on a wall, `a² = r² − (r − δ)² = 2rδ − δ²`. Written with
//! `R* = r_i r_j/(r_i + r_j)` and `S = r_i + r_j` (a wall: `S = ∞`, `R* = r`):
//! `a² = δ(2 − δ/S)(4R* − 2δ + δ²/S)/(4(1 − δ/S)²)`, which is both.
//! LIGGGHTS adds `F_coh` to the normal force after the normal model (and its
//! `limitForce` clamp), so the tangential and rolling limits see
//! `|F_n + F_coh|`; Clump does the same. Source: LIGGGHTS-PUBLIC 3.8
//! `cohesion_model_sjkr.h` and its documentation (`gran cohesion sjkr`).
//!
//! # JKR (Johnson, Kendall & Roberts 1971)
//! With the work of adhesion `Γ` (J/m², the energy per unit area to separate
//! the two surfaces; `2γ` for two like surfaces of surface energy `γ`), the
//! contact radius `a` and the overlap `δ` (negative: a neck under tension)
//! obey
//!
//! `δ = a²/R* − √(2πΓa/E*)`,  `F = 4E*a³/(3R*) − √(8πΓE*a³)`.
//!
//! A contact forms when the spheres touch (`δ = 0`, where
//! `a = (2πΓR*²/E*)^{1/3}` and `F = −(4/3)πΓR*`) and lasts while `δ ≥ −δ_c`;
//! the curve `δ(a)` has its minimum at `a_f = (πΓR*²/(8E*))^{1/3}`, where
//! `δ = −δ_c`, `δ_c = 3a_f²/R* = (3/4)(π²Γ²R*/E*²)^{1/3}`, and the force is
//! `−(5/6)πΓR*`; on the way there the force passes its minimum, the pull-off
//! force `F_c = −(3/2)πΓR*` (at `a_c = (9πΓR*²/(8E*))^{1/3}`). Zero force at
//! `a_0 = (9πΓR*²/(2E*))^{1/3}`. The loading and unloading curves are the
//! same `F(δ)` (the hysteresis is that the contact forms at `δ = 0` but
//! breaks only at `−δ_c`; the energy lost per cycle is the area between).
//! Given `δ ≥ −δ_c`, `a` is the larger root of `δ(a)` ([`jkr_contact_radius`]).
//! In the law, the Hertz part `4E*a³/(3R*)` plus the dashpot takes the
//! pair's clamp, and the adhesion `−√(8πΓE*a³)` is added; the dashpots and
//! the Mindlin tangential stiffness use `a` in place of `√(R*δ)`.
//! Sources: Johnson, Kendall & Roberts (1971), Proc. R. Soc. Lond. A 324,
//! 301; Johnson (1985) §5.5; the DEM form of Thornton & Ning (1998),
//! Powder Technol. 99, 154.

use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The cohesion model of a material pair.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "model")]
pub enum CohesionLaw {
    /// No cohesion (default).
    #[default]
    None,
    /// LIGGGHTS' SJKR: `F_coh = −k_c π a²` while `δ > 0`.
    Sjkr {
        /// Cohesion energy density `k_c`, J/m³ (LIGGGHTS'
        /// `cohesionEnergyDensity`).
        energy_density: f64,
    },
    /// JKR with the hysteresis of contact formation and breakage.
    Jkr {
        /// Work of adhesion `Γ`, J/m².
        surface_energy: f64,
    },
}

/// `a²` (m²) of the circle in which two undeformed spheres overlapping by
/// `δ` (m) intersect, from `R*` (m) and the radius sum `S` (m; `∞` for a
/// sphere on a wall, where `R*` is the sphere's radius). Module docs.
#[inline]
pub fn lens_radius_sq(r_star: f64, radius_sum: f64, overlap: f64) -> f64 {
    let d = overlap;
    let u = d / radius_sum;
    d * (2.0 - u) * (4.0 * r_star - 2.0 * d + d * u) / (4.0 * (1.0 - u) * (1.0 - u))
}

/// SJKR cohesive normal force (N, negative: attraction) of energy density
/// `k_c` (J/m³) at overlap `δ > 0` (m).
#[inline]
pub fn sjkr_force(k_c: f64, r_star: f64, radius_sum: f64, overlap: f64) -> f64 {
    -k_c * PI * lens_radius_sq(r_star, radius_sum, overlap)
}

/// JKR critical separation `δ_c = (3/4)(π²Γ²R*/E*²)^{1/3}` (m, positive):
/// the contact breaks when `δ < −δ_c`.
pub fn jkr_critical_separation(gamma: f64, r_star: f64, e_star: f64) -> f64 {
    0.75 * (PI * PI * gamma * gamma * r_star / (e_star * e_star)).cbrt()
}

/// JKR pull-off force magnitude `(3/2)πΓR*` (N).
pub fn jkr_pull_off_force(gamma: f64, r_star: f64) -> f64 {
    1.5 * PI * gamma * r_star
}

/// JKR contact radius `a` (m) at overlap `δ ≥ −δ_c` (m): the larger root of
/// `δ = a²/R* − √(2πΓa/E*)`; `None` below `−δ_c` (no contact). Newton's
/// method on `x = √a`, `f(x) = x⁴/R* − cx − δ`, `c = √(2πΓ/E*)`: `f` is
/// convex, and from `x₀ = max((2R*δ⁺)^{1/4}, (2cR*)^{1/3})`, where
/// `f(x₀) ≥ 0`, the iterates fall monotonically to the larger root.
/// (`f(x₀) ≥ 0`: with `x₀ = (2cR*)^{1/3}`, `x₀⁴/R* = 2cx₀` and
/// `x₀⁴ ≥ 2R*δ⁺` give `cx₀ ≥ δ`; with `x₀ = (2R*δ)^{1/4}`, `x₀⁴/R* = 2δ`
/// and `x₀³ ≥ 2cR*` give `δ ≥ cx₀`; either way `x₀⁴/R* ≥ cx₀ + δ`.) The
/// start lies within a factor 2^{1/3} of the root, so Newton needs a few
/// steps; this solve runs for every JKR contact at every step.
pub fn jkr_contact_radius(gamma: f64, r_star: f64, e_star: f64, overlap: f64) -> Option<f64> {
    let c = (2.0 * PI * gamma / e_star).sqrt();
    let x_c = (2.0 * c * r_star).cbrt();
    // x at the minimum of f, where 4x³/R* = c: (cR*/4)^{1/3} = x_c/2
    let xf = 0.5 * x_c;
    let fmin = xf.powi(4) / r_star - c * xf - overlap;
    if fmin > 0.0 {
        return None;
    }
    let mut x = x_c.max((2.0 * r_star * overlap.max(0.0)).sqrt().sqrt());
    for _ in 0..100 {
        let f = x.powi(4) / r_star - c * x - overlap;
        let df = 4.0 * x.powi(3) / r_star - c;
        if df <= 0.0 {
            break;
        }
        let next = (x - f / df).max(xf);
        if next >= x {
            break;
        }
        x = next;
    }
    Some(x * x)
}

/// The Hertz part `4E*a³/(3R*)` and the adhesion part `−√(8πΓE*a³)` of
/// the JKR force (N) at contact radius `a` (m).
#[inline]
pub fn jkr_force_parts(gamma: f64, r_star: f64, e_star: f64, a: f64) -> (f64, f64) {
    let a3 = a * a * a;
    (
        4.0 * e_star * a3 / (3.0 * r_star),
        -(8.0 * PI * gamma * e_star * a3).sqrt(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lens area formula against direct geometry: two spheres'
    /// intersection circle, and the sphere–wall limit.
    #[test]
    fn lens_radius_matches_geometry() {
        let (ri, rj) = (1.0e-3, 0.4e-3);
        for delta in [1e-9, 1e-6, 1e-4, 3e-4] {
            let d: f64 = ri + rj - delta;
            // the circle lies at x from i's centre: x = (d² + ri² − rj²)/(2d)
            let x = (d * d + ri * ri - rj * rj) / (2.0 * d);
            let want = ri * ri - x * x;
            let got = lens_radius_sq(ri * rj / (ri + rj), ri + rj, delta);
            assert!((got - want).abs() <= 1e-9 * want, "{delta}: {got} {want}");
            let wall = lens_radius_sq(ri, f64::INFINITY, delta);
            // the sphere's chord circle at depth δ: r² − (r − δ)², factored
            // as δ(2r − δ) (the unfactored difference cancels: at δ = 1e-9 r
            // it keeps only about six digits of its own)
            let want = delta * (2.0 * ri - delta);
            assert!(
                (wall - want).abs() <= 1e-12 * want,
                "{delta}: {wall} {want}"
            );
        }
    }

    /// The JKR root satisfies the JKR relation, is the larger root, and
    /// the special points have their closed-form forces.
    #[test]
    fn jkr_points() {
        let (g, r, e) = (0.05, 1e-3, 1e7);
        let dc = jkr_critical_separation(g, r, e);
        let c = (2.0 * PI * g / e).sqrt();
        for d in [-dc * 0.999_999, -0.5 * dc, 0.0, 1e-7, 1e-5] {
            let a = jkr_contact_radius(g, r, e, d).unwrap();
            let back = a * a / r - (c * c * a).sqrt();
            assert!((back - d).abs() < 1e-12 * dc.max(d.abs()), "{d}: {back}");
            assert!(a >= (PI * g * r * r / (8.0 * e)).cbrt() * (1.0 - 1e-9));
        }
        assert!(jkr_contact_radius(g, r, e, -dc * 1.000_001).is_none());
        // a sweep over the range of the start's two branches (δ from −δ_c
        // to 10⁴ δ_c, where the Hertz term dominates) and over Γ/E*: the
        // root satisfies the relation and lies right of the minimum
        for (g, e) in [(0.05, 1e7), (0.17, 5.5e5), (1e-3, 1e10)] {
            let dc = jkr_critical_separation(g, r, e);
            let c = (2.0 * PI * g / e).sqrt();
            let af = (PI * g * r * r / (8.0 * e)).cbrt();
            for k in 0..=200 {
                let d = dc * ((1e4f64).powf(k as f64 / 200.0) - 1.999_999);
                let a = jkr_contact_radius(g, r, e, d).unwrap();
                let back = a * a / r - (c * c * a).sqrt();
                assert!(
                    (back - d).abs() < 1e-12 * dc.max(d.abs()),
                    "{g} {e} {d}: {back}"
                );
                assert!(a >= af * (1.0 - 1e-9), "{g} {e} {d}");
            }
        }
        // at δ = 0: F = −(4/3)πΓR*
        let a = jkr_contact_radius(g, r, e, 0.0).unwrap();
        let (h, ad) = jkr_force_parts(g, r, e, a);
        assert!((h + ad + 4.0 / 3.0 * PI * g * r).abs() < 1e-12 * PI * g * r);
    }
}
