//! The scalar composition of the contact law for pairs that select a
//! sub-model the vectorised [`SlidingLaw`](super::SlidingLaw) does not have:
//! LIGGGHTS' tangential rule ([`super::tangential::liggghts_spring`]).
//!
//! The same sub-model formulas as [`SlidingLaw::evaluate`]: the stiffness
//! scale, elastic force and spring energy of [`super::normal`], the dashpots
//! and clamped normal force of [`super::damping`]; then the pair's
//! tangential rule and the rolling couple ([`ContactModel::rolling_couple`]).
//! The default Hertz–Mindlin pairs never come here: the pair kernel runs
//! them in vector lanes, and [`ContactModel::evaluate`] only dispatches here
//! for [`ContactModel::is_extended`] pairs.
//!
//! [`SlidingLaw::evaluate`]: super::SlidingLaw::evaluate

use super::tangential::{self, history_spring, liggghts_spring, TangentialLaw};
use super::{damping, normal};
use super::{ContactHistory, ContactInput, ContactModel, ContactOutput};

/// One contact of an extended pair (conventions of [`super`]): force and
/// couple on `i` (N, N m, world), stored elastic energy (J), signed normal
/// force (N); updates the springs in `h`. Requires `c.overlap > 0`.
pub fn evaluate(model: &ContactModel, c: &ContactInput, h: &mut ContactHistory) -> ContactOutput {
    let law = model.sliding_law();
    let n = c.normal;
    let d = c.overlap;
    let s = normal::stiffness_scale(law.hertz, c.radius, d);
    let kn = law.kn_coef * s;
    let kt = law.kt_coef * s;
    let gamma_n = damping::dashpot(law.gn_coef, s, c.mass);
    let gamma_t = damping::dashpot(law.gt_coef, s, c.mass);
    let vn = c.rel_velocity.dot(n);
    let vt = c.rel_velocity - vn * n;
    let f_el = normal::elastic_force(kn, d);
    let f_n = damping::normal_force(f_el, gamma_n, vn, law.fn_floor);
    let f_max = law.friction * f_n.abs();
    let xi = &mut h.tangential;
    let f_t = match model.properties().tangential {
        TangentialLaw::Clump => history_spring(xi, n, vt, c.dt, kt, gamma_t, f_max),
        TangentialLaw::Liggghts => liggghts_spring(xi, n, vt, c.dt, kt, gamma_t, f_max),
    };
    let energy =
        normal::spring_energy(law.energy_factor, f_el, d) + tangential::spring_energy(kt, *xi);
    let (torque, e_r) = model.rolling_couple(c, f_n, kn, &mut h.rolling);
    ContactOutput {
        force: f_n * n + f_t,
        torque,
        elastic_energy: e_r.map_or(energy, |e| energy + e),
        normal_force: f_n,
    }
}
