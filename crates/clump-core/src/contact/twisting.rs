//! Twisting resistance: a spring–dashpot–slider on the relative spin about
//! the contact normal (optional per material pair).
//!
//! With `ω_tw = (ω_i − ω_j)·n` (rad/s) and the stored twisting torque `M`
//! on `i` about `n` (N m), per step:
//!
//! ```text
//! M ← M − k_tw ω_tw Δt                      (spring)
//! trial  M_t = M − γ_tw ω_tw                 (plus dashpot)
//! if |M_t| > M_max:  M_t ← M_max sign(M_t),  M ← M_t   (slider: the spring holds the limit)
//! ```
//!
//! and the couple on `i` is `M_t n` (`j` gets `−M_t n`). The constants follow
//! the contact as in Marshall (2009), "Discrete-element modeling of
//! particulate aerosol flows", J. Comput. Phys. 228, 1541 (LAMMPS `pair
//! granular`, `twisting marshall`): with the contact radius `a` (`√(R*δ)`
//! for Hertz, `a` of JKR),
//!
//! `k_tw = ½ k_t a²`,  `γ_tw = ½ γ_t a²`,  `M_max = (2/3) a μ |F_n|`,
//!
//! `k_t`, `γ_t` the tangential stiffness and dashpot and `μ|F_n|` the
//! sliding limit of the pair (the torque of a uniform shear traction
//! `μ|F_n|/(πa²)` over the contact circle is `(2/3)aμ|F_n|`).
//!
//! The spring is stored in the normal component of the history's couple
//! spring ([`super::ContactHistory::rolling`], whose tangential part is the
//! EPSD rolling spring): a torque vector on `i`, so that swapping `i` and
//! `j` negates it as it does the rolling spring.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The twisting model of a material pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TwistingLaw {
    /// No twisting resistance (default).
    #[default]
    None,
    /// Marshall's spring–dashpot–slider (module docs).
    Marshall,
}

/// The twisting couple on `i` (N m, world, along `n`) and the spring's
/// energy (J), updating the twisting spring `m` (N m, the torque on `i`
/// about `n`). `w_tw`: relative spin about the normal (rad/s); `k`, `c`,
/// `m_max`: `k_tw` (N m/rad), `γ_tw` (N m s/rad), `M_max` (N m); `dt` (s).
#[inline]
pub fn sds(m: &mut f64, n: DVec3, w_tw: f64, dt: f64, k: f64, c: f64, m_max: f64) -> (DVec3, f64) {
    let spring = *m - k * w_tw * dt;
    let trial = spring - c * w_tw;
    let (couple, stored) = if trial.abs() > m_max {
        let l = m_max.copysign(trial);
        (l, l)
    } else {
        (trial, spring)
    };
    *m = stored;
    let energy = if k > 0.0 {
        0.5 * stored * stored / k
    } else {
        0.0
    };
    (couple * n, energy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spring_dashpot_slider_cases() {
        let n = DVec3::Z;
        // sticking: spring −k ω dt = −1e-6 (k = 1, ω = 1, dt = 1e-6), dashpot −0.1
        let mut m = 0.0;
        let (c, _) = sds(&mut m, n, 1.0, 1e-6, 1.0, 0.1, 1.0);
        assert!(
            (m + 1e-6).abs() < 1e-18 && (c.z + 0.100_001).abs() < 1e-15,
            "{m} {c}"
        );
        // sliding: the limit, stored in the spring
        let mut m = -0.95;
        let (c, _) = sds(&mut m, n, 1.0, 1e-6, 1.0, 0.1, 1.0);
        assert_eq!(c.z, -1.0);
        assert_eq!(m, -1.0);
    }
}
