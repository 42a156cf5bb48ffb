//! Contact laws: the force and couple between two touching spheres of
//! different bodies, or between a sphere and a wall.
//!
//! The kernel is [`ContactModel::evaluate`]; a [`ContactModel`] is built once per
//! pair of materials from two [`Material`]s and the user's [`PairProperties`],
//! with every material-dependent constant precomputed.
//!
//! # Conventions
//! All vectors are in the **world frame**, SI units.
//! - `i` and `j` are the two sides of a contact; for a wall, `i` is the sphere
//!   and `j` the wall.
//! - [`ContactInput::normal`] is the unit vector from `j`'s centre to `i`'s
//!   centre (wall → sphere). A positive normal force component along `+normal`
//!   pushes `i` away from `j` (repulsion).
//! - [`ContactOutput::force`] is the force **on `i`**, applied at the contact
//!   point; `j` gets `−force`. The engine adds the moment of this force about
//!   each body's centre of mass. [`ContactOutput::torque`] is an extra pure
//!   couple on `i` (rolling resistance); `j` gets `−torque`.
//!
//! # Mixing rules (see [`material`])
//! - Effective Young's modulus `E* = [(1−ν₁²)/E₁ + (1−ν₂²)/E₂]⁻¹` (Pa).
//! - Effective shear modulus `G* = [2(2−ν₁)(1+ν₁)/E₁ + 2(2−ν₂)(1+ν₂)/E₂]⁻¹` (Pa),
//!   i.e. `[(2−ν₁)/G₁ + (2−ν₂)/G₂]⁻¹` with `G = E/(2(1+ν))` (Mindlin).
//! - Effective radius `R* = R₁R₂/(R₁+R₂)` (m); for a wall `R* = R` (sphere radius).
//! - Effective mass `m* = m₁m₂/(m₁+m₂)` of the two **bodies** (kg); for a wall
//!   `m* = m` (body mass). `R*` and `m*` are computed by the engine and passed in
//!   [`ContactInput`].
//! - A rigid wall is a material with `E = ∞`, whose compliance term
//!   `(1−ν²)/E` (and `2(2−ν)(1+ν)/E`) is zero.
//! - Restitution `e`, sliding friction `μ` and rolling friction `μ_r` are not
//!   mixed: they are given per material pair in [`PairProperties`].
//!
//! # Sub-models
//! - [`normal`]: Hertz (`F = (4/3)E*√R* δ^{3/2}`) or linear (`F = k_n δ`).
//! - [`damping`]: the normal/tangential dashpots; the default
//!   [`DampingLaw::Exact`] reproduces the input restitution exactly for both
//!   normal laws, with or without the tensile clamp; [`DampingLaw::Liggghts`]
//!   uses LIGGGHTS' formula (biased under the clamp).
//! - [`tangential`]: incremental history spring (Mindlin `k_t = 8G*√(R*δ)` or
//!   linear `k_t`), dashpot, Coulomb limit `|F_t| ≤ μF_n`; a sliding contact
//!   keeps the limit in its elastic spring.
//! - [`tangential::TangentialLaw::Liggghts`]: LIGGGHTS' rule (only the
//!   spring is limited, the dashpot dropped while sliding); such pairs run
//!   the scalar composition [`extended`].
//! - [`micro_slip`] ([`tangential::TangentialLaw::MindlinDeresiewicz`]):
//!   Mindlin–Deresiewicz micro-slip with loading/unloading/reloading
//!   history (Thornton & Yin 1991; Thornton, Cummins & Cleary 2011), on the
//!   scalar path [`extended`].
//! - [`mdr`] ([`tangential::TangentialLaw::Mdr`]): micro-slip exact for
//!   arbitrary load histories (method of dimensionality reduction), its
//!   profile kept per contact beside the history ([`mdr::SlipProfile`]),
//!   on the scalar path [`extended`].
//! - [`cohesion`]: SJKR and JKR; [`twisting`]: twisting resistance
//!   (both on the scalar path [`extended`]).
//! - [`rolling`]: rolling resistance, none, CDT or EPSD.
//! - [`time_scale`]: Rayleigh time and Hertz contact duration, for choosing a
//!   time step; [`stability`]: the damped contact's stability limit.
//!
//! # End of contact and tensile forces
//! The engine keeps a contact while `overlap > 0` and calls `evaluate` for it.
//! By default the total normal force is **clamped**,
//! `F_n = max(F_elastic − γ_n v_n, 0)`: a contact between non-cohesive
//! particles cannot pull, so near the end of a damped rebound, where the
//! dashpot would make it tensile, `F_n` is zero and the particles separate
//! with the speed they have then. The Coulomb and rolling limits use this
//! `F_n ≥ 0`. [`PairProperties::tensile`] `= true` keeps the unclamped law
//! (LIGGGHTS' default, `limitForce off`): `F_n` may be slightly negative near
//! separation and the limits use `|F_n|`. The exact-restitution damping is
//! calibrated for whichever rule the pair uses (see [`damping`]).

pub mod cohesion;
pub mod damping;
mod evaluate;
pub mod extended;
pub mod geometry;
pub mod material;
pub mod mdr;
pub mod micro_slip;
pub mod model;
pub mod normal;
pub mod record;
pub mod rolling;
pub mod stability;
pub mod step_sums;
pub mod table;
pub mod tangential;
pub mod time_scale;
pub mod twisting;

pub use cohesion::CohesionLaw;
pub use damping::DampingLaw;
pub use material::Material;
pub use model::{ContactModel, PairProperties, SlidingLaw, SlidingOutput};
pub use normal::NormalLaw;
pub use rolling::RollingLaw;
pub use table::ContactTable;
pub use tangential::TangentialLaw;
pub use twisting::TwistingLaw;

use glam::DVec3;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Geometry and kinematics of one contact, all in the world frame, SI units.
/// `overlap` may be negative only for a JKR pair (a neck under tension).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactInput {
    /// Unit contact normal, world frame, from `j`'s centre to `i`'s centre
    /// (for a wall: from the wall to the sphere).
    pub normal: DVec3,
    /// Overlap `δ > 0`, m.
    pub overlap: f64,
    /// Velocity of `i`'s material point at the contact minus that of `j`,
    /// world frame, m/s (including the `ω × r` terms; computed by the engine).
    pub rel_velocity: DVec3,
    /// Relative angular velocity `ω_i − ω_j`, world frame, rad/s (for rolling
    /// resistance).
    pub rel_omega: DVec3,
    /// Effective radius `R* = R₁R₂/(R₁+R₂)`, m (wall: sphere radius).
    pub radius: f64,
    /// Radius sum `R₁ + R₂`, m (wall: `∞`); read by SJKR's contact area only.
    pub radius_sum: f64,
    /// Effective mass `m* = m₁m₂/(m₁+m₂)` of the two bodies, kg (wall: body mass).
    pub mass: f64,
    /// Time step, s (used for the history-spring increments).
    pub dt: f64,
}

/// Per-contact history, stored by the engine between steps. `Default` (all
/// zero) is the state of a new contact.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactHistory {
    /// Tangential spring displacement `ξ`, m, world frame. After an evaluation
    /// it lies in the current tangent plane (`ξ·n = 0`). The micro-slip
    /// model stores its force and a turning point here instead
    /// ([`micro_slip`], "Storage").
    pub tangential: DVec3,
    /// Couple spring on `i`, N m, world frame: in the tangent plane the
    /// EPSD rolling spring `M_r` (zero for other rolling laws), along the
    /// normal the twisting spring ([`twisting`]; zero without it). The
    /// micro-slip model stores a turning point here ([`micro_slip`]).
    pub rolling: DVec3,
}

/// Result of one contact evaluation, world frame, SI units.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct ContactOutput {
    /// Total contact force on `i` (normal + tangential), N, world frame,
    /// applied at the contact point; `j` gets `−force`. The engine adds the
    /// torque of this force about each body's centre of mass.
    pub force: DVec3,
    /// Extra couple on `i` (rolling resistance), N m, world frame; `j` gets
    /// `−torque`.
    pub torque: DVec3,
    /// Elastic energy stored in the contact, J: normal spring (Hertz
    /// `(2/5)F_el δ`, linear `½k_n δ²`) + tangential spring `½k_t|ξ|²`
    /// (+ EPSD rolling spring `½|M_r|²/k_r` when that law is used).
    pub elastic_energy: f64,
    /// Signed normal force component `F_n = force·normal`, N (elastic +
    /// damping, after the tensile clamp): `≥ 0` unless the pair is
    /// `tensile`, where it is negative when the contact is net tensile.
    pub normal_force: f64,
}

/// Invalid material or pair properties given to [`ContactModel::new`].
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ContactError {
    /// A material parameter is out of range.
    #[error("invalid material {which}: {what}")]
    Material {
        /// Which material (`"a"` or `"b"`).
        which: &'static str,
        /// What is wrong.
        what: String,
    },
    /// A pair property is out of range.
    #[error("invalid contact property: {0}")]
    Property(String),
}
