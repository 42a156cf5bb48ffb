//! The scalar composition of the contact law for pairs that select a
//! sub-model the vectorised [`SlidingLaw`](super::SlidingLaw) does not have:
//! LIGGGHTS' tangential rule ([`super::tangential::liggghts_spring`]), the
//! micro-slip rules ([`super::micro_slip`], [`super::mdr`]),
//! cohesion ([`super::cohesion`]: SJKR, JKR) and twisting resistance
//! ([`super::twisting`]).
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

use super::cohesion::{
    jkr_contact_radius, jkr_force_parts, jkr_pull_off_force, sjkr_force, CohesionLaw,
};
use super::mdr::{mdr_tangential, SlipProfile};
use super::micro_slip::micro_slip;
use super::tangential::{self, history_spring, liggghts_spring, TangentialLaw};
use super::twisting::{self, TwistingLaw};
use super::{damping, normal};
use super::{ContactHistory, ContactInput, ContactModel, ContactOutput};
use glam::DVec3;

/// One contact of an extended pair (conventions of [`super`]): force and
/// couple on `i` (N, N m, world), stored elastic energy (J), signed normal
/// force (N); updates the springs in `h`. Requires `c.overlap > 0`, or for
/// a JKR pair `c.overlap ≥ −δ_c` ([`ContactModel::reach`]; below, the
/// contact carries no force).
///
/// Normal force: `F_n = max(F_el − γ_n v_n, floor) + F_coh`, the pair's
/// clamp on the elastic and dashpot part and the cohesion added after it
/// (LIGGGHTS' order). Without cohesion and for SJKR, `F_el` is the normal
/// law at `δ` with stiffness scale `s = √(R*δ)` (Hertz) or 1 (linear); for
/// JKR, `F_el = 4E*a³/(3R*)` and `F_coh = −√(8πΓE*a³)` at the JKR contact
/// radius `a`, and `s = a` (the Hertz `√(R*δ)` is the Hertz contact
/// radius). The Coulomb limit is `μ|F_n|` (LIGGGHTS, SJKR included); for
/// JKR `μ·max(F_n + 2F_c, 0)`, `F_c = (3/2)πΓR*` (Thornton & Yin 1991: the
/// friction of an adhesive contact vanishes at pull-off).
pub fn evaluate(
    model: &ContactModel,
    c: &ContactInput,
    h: &mut ContactHistory,
    slip: Option<&mut SlipProfile>,
) -> ContactOutput {
    let law = model.sliding_law();
    let n = c.normal;
    let d = c.overlap;
    let props = model.properties();
    let e_star = model.effective_modulus();
    let (s, f_el, f_coh, f_limit_shift) = match props.cohesion {
        CohesionLaw::Jkr { surface_energy: g } => {
            let Some(a) = jkr_contact_radius(g, c.radius, e_star, d) else {
                h.tangential = DVec3::ZERO;
                h.rolling = DVec3::ZERO;
                return ContactOutput::default();
            };
            let (f_h, f_a) = jkr_force_parts(g, c.radius, e_star, a);
            (a, f_h, f_a, 2.0 * jkr_pull_off_force(g, c.radius))
        }
        CohesionLaw::Sjkr { energy_density: k } => {
            let s = normal::stiffness_scale(law.hertz, c.radius, d);
            let f_coh = sjkr_force(k, c.radius, c.radius_sum, d);
            (
                s,
                normal::elastic_force(law.kn_coef * s, d),
                f_coh,
                f64::NAN,
            )
        }
        CohesionLaw::None => {
            let s = normal::stiffness_scale(law.hertz, c.radius, d);
            (s, normal::elastic_force(law.kn_coef * s, d), 0.0, f64::NAN)
        }
    };
    let kn = law.kn_coef * s;
    let kt = law.kt_coef * s;
    let gamma_n = damping::dashpot(law.gn_coef, s, c.mass);
    let gamma_t = damping::dashpot(law.gt_coef, s, c.mass);
    let vn = c.rel_velocity.dot(n);
    let vt = c.rel_velocity - vn * n;
    let f_n = damping::normal_force(f_el, gamma_n, vn, law.fn_floor) + f_coh;
    let f_max = if f_limit_shift.is_nan() {
        law.friction * f_n.abs()
    } else {
        law.friction * (f_n + f_limit_shift).max(0.0)
    };
    // the normal spring's energy at the Hertz overlap of the stiffness scale
    // (`δ` itself without JKR; `a²/R*` with it)
    let d_h = if law.hertz { s * s / c.radius } else { d };
    let e_n = normal::spring_energy(law.energy_factor, f_el, d_h);
    let xi = &mut h.tangential;
    let (f_t, energy) = match props.tangential {
        TangentialLaw::Clump => {
            let f = history_spring(xi, n, vt, c.dt, kt, gamma_t, f_max);
            (f, e_n + tangential::spring_energy(kt, *xi))
        }
        TangentialLaw::Liggghts => {
            let f = liggghts_spring(xi, n, vt, c.dt, kt, gamma_t, f_max);
            (f, e_n + tangential::spring_energy(kt, *xi))
        }
        TangentialLaw::MindlinDeresiewicz => {
            // Hertz without cohesion (ContactModel::new): the normal force
            // of the previous step at the previous overlap δ + v_n Δt
            let d_old = d + vn * c.dt;
            let f_n_old = if d_old > 0.0 {
                let s_old = normal::stiffness_scale(true, c.radius, d_old);
                let g_old = damping::dashpot(law.gn_coef, s_old, c.mass);
                let f_el_old = normal::elastic_force(law.kn_coef * s_old, d_old);
                damping::normal_force(f_el_old, g_old, vn, law.fn_floor).abs()
            } else {
                0.0
            };
            let (f, e_t) = micro_slip(h, n, vt, c.dt, kt, law.friction, f_n.abs(), f_n_old);
            (f, e_n + e_t)
        }
        TangentialLaw::Mdr => {
            // Hertz without cohesion (ContactModel::new): s = a, G̃ = k_t/(2a)
            let mut fresh = SlipProfile::default();
            let p = slip.unwrap_or(&mut fresh);
            let (f, e_t) = mdr_tangential(
                p,
                n,
                vt,
                c.dt,
                s * s,
                0.5 * law.kt_coef,
                law.friction,
                f_n.abs(),
            );
            // the spring slot holds the equivalent Mindlin spring
            // `ξ = −F_t/k_t` (records; a contact with a force is carried)
            *xi = if kt > 0.0 { -f / kt } else { DVec3::ZERO };
            (f, e_n + e_t)
        }
    };
    // the couple spring: the twisting spring along the normal, the EPSD
    // rolling spring in the tangent plane (which that law rotates)
    let twist = props.twisting != TwistingLaw::None;
    let m_tw = if twist { h.rolling.dot(n) } else { 0.0 };
    if twist {
        h.rolling -= m_tw * n;
    }
    let (mut torque, e_r) = model.rolling_couple(c, f_n, kn, &mut h.rolling);
    let mut energy = e_r.map_or(energy, |e| energy + e);
    if twist {
        // Marshall (2009): k_tw = k_t a²/2, γ_tw = γ_t a²/2, M_max = (2/3)aμ|F_n|
        let a = if law.hertz {
            s
        } else {
            (c.radius * d.max(0.0)).sqrt()
        };
        let mut m = m_tw;
        let (couple, e_tw) = twisting::sds(
            &mut m,
            n,
            c.rel_omega.dot(n),
            c.dt,
            0.5 * kt * a * a,
            0.5 * gamma_t * a * a,
            2.0 / 3.0 * a * law.friction * f_n.abs(),
        );
        h.rolling += m * n;
        torque += couple;
        energy += e_tw;
    }
    ContactOutput {
        force: f_n * n + f_t,
        torque,
        elastic_energy: energy,
        normal_force: f_n,
    }
}
