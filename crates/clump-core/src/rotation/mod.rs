//! Rotational time integration of rigid bodies.
//!
//! State: orientation `q` (unit quaternion, body → world) and angular momentum
//! `L` in the **world** frame ([`RotState`]). Inertia is given by the principal
//! moments `(I1, I2, I3)` (body frame, kg m²).
//!
//! Production schemes ([`RotationScheme`]), each second order:
//! - [`RotationScheme::NoSquish`] (default): symplectic, time-reversible
//!   splitting of free rotation into exact rotations about the principal axes
//!   (Miller et al. 2002), see [`no_squish`].
//! - [`RotationScheme::Richardson`]: Richardson extrapolation of first-order
//!   orientation updates (the idea of LAMMPS/LIGGGHTS `MathExtra::richardson`),
//!   see [`richardson`].
//! - [`RotationScheme::ZhaoVanWachem`]: the predictor–corrector quaternion
//!   integrator of Zhao & van Wachem (2013), see [`zhao_van_wachem`]. In
//!   the DEM step it replaces both angular-momentum half kicks: the torque
//!   of the force evaluation at the start of the step, held constant in the
//!   world frame, is taken into the body frame with `q_0` and with the
//!   predicted `q_½` (see `crate::step::integrate`).
//! - [`RotationScheme::ZhaoVanWachemSplit`]: velocity-Verlet half kicks of
//!   `L` around a torque-free Zhao–van Wachem drift.
//! - [`RotationScheme::RichardsonLiggghts`]: LIGGGHTS' own linearised
//!   `MathExtra::richardson`, see [`richardson_liggghts`].
//!
//! [`mod@reference`] holds the two schemes of docs/theory.md T-5, kept to show their failure modes (Euler-angle rates and
//! direct integration of the transformation matrix), for tests only.

pub mod body_dynamics;
pub mod no_squish;
pub mod reference;
pub mod richardson;
pub mod richardson_liggghts;
pub mod zhao_van_wachem;

use crate::math::{quat_from_rotation_vector, renormalize};
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

pub use body_dynamics::{
    angular_acceleration_body, inverse_inertia, omega_body, omega_world, omega_world_inv,
    omega_world_rot, rotational_energy,
};

/// Choice of rotational integrator. Deserialises from the snake_case names
/// `"richardson"`, `"zhao_van_wachem"`, `"no_squish"`,
/// `"zhao_van_wachem_split"`, `"richardson_liggghts"`.
///
/// The default is [`RotationScheme::NoSquish`]: it is symplectic and
/// time-reversible, keeps `|L|` exact and shows no secular energy drift over
/// long runs (the other two schemes are second order too but not symplectic).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum RotationScheme {
    /// Richardson extrapolation of exact-exponential orientation sub-steps
    /// with `ω` recomputed from `L` (LAMMPS/LIGGGHTS `richardson` idea).
    Richardson,
    /// Zhao & van Wachem (2013) quaternion predictor–corrector; in the DEM
    /// step with the start-of-step torque held constant in the world frame.
    ZhaoVanWachem,
    /// Miller et al. (2002) NO_SQUISH symplectic principal-axis splitting.
    #[default]
    NoSquish,
    /// Half kicks of `L` around a torque-free Zhao & van Wachem drift.
    ZhaoVanWachemSplit,
    /// LIGGGHTS' `MathExtra::richardson` (linearised sub-steps, normalised).
    RichardsonLiggghts,
}

/// State of one rotating body: orientation (body → world) and angular
/// momentum in the WORLD frame (kg m²/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RotState {
    /// Orientation, unit quaternion mapping body → world.
    pub q: DQuat,
    /// Angular momentum about the centre of mass, world frame, kg m²/s.
    pub l_world: DVec3,
}

impl RotationScheme {
    /// Free-rotation ("drift") over `dt` (s) with no torque: returns the new
    /// orientation (unit quaternion, body → world). The world-frame angular
    /// momentum `l_world` (kg m²/s) is constant in exact free rotation and is
    /// left unchanged by every scheme. `inertia` = principal moments (body
    /// frame, kg m²); a zero moment gives a zero angular-velocity component.
    ///
    /// A spherical top (three equal, positive principal moments `I`) turns
    /// at the constant world-frame `ω = L/I` (`ω × Iω = 0` in Euler's
    /// equations), so its free rotation is exactly `q ← exp(ω dt) q`. Every
    /// scheme but [`RotationScheme::RichardsonLiggghts`] (which reproduces
    /// LIGGGHTS' linearised sub-steps) takes that exact step for such a body: each of them
    /// reproduces a constant-`ω` rotation (Richardson's extrapolation of
    /// two exact half steps and one exact full step returns the full step;
    /// ZvW's corrector has zero angular acceleration; NO_SQUISH's exact
    /// principal-axis flows compose to it up to its `O(dt³)` splitting error,
    /// which the exact step removes), and it costs one exponential map
    /// instead of several. The regular tetrahedral clump of the shared
    /// benchmark is such a body.
    #[inline]
    pub fn drift(self, q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> DQuat {
        if inertia.x == inertia.y
            && inertia.y == inertia.z
            && inertia.x > 0.0
            && self != RotationScheme::RichardsonLiggghts
        {
            return match spherical_top_drift_small(q, l_world, inertia.x, dt) {
                (q1, true) => q1,
                _ => renormalize(quat_from_rotation_vector(l_world * (dt / inertia.x)) * q),
            };
        }
        self.drift_asymmetric(q, l_world, inertia, dt)
    }

    /// [`Self::drift`] of a body that is not a spherical top (out of line:
    /// the spherical-top step above is what the integration loop inlines).
    #[inline(never)]
    fn drift_asymmetric(self, q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> DQuat {
        match self {
            RotationScheme::Richardson => richardson::drift(q, l_world, inertia, dt),
            RotationScheme::ZhaoVanWachem | RotationScheme::ZhaoVanWachemSplit => {
                zhao_van_wachem::drift(q, l_world, inertia, dt)
            }
            RotationScheme::NoSquish => no_squish::drift(q, l_world, inertia, dt),
            RotationScheme::RichardsonLiggghts => {
                richardson_liggghts::drift(q, l_world, inertia, dt)
            }
        }
    }

    /// One full step of length `dt` (s) of a rigid body under a world-frame
    /// torque that depends on orientation (`torque(q)` returns N m, world
    /// frame). `inertia` = principal moments (body frame, kg m²).
    ///
    /// Richardson and NoSquish use the velocity-Verlet splitting: kick `L` by
    /// `T(q0) dt/2`, [`drift`](Self::drift), kick `L` by `T(q1) dt/2` (two
    /// torque evaluations). ZhaoVanWachem runs the paper's predictor–corrector
    /// (torque at `q0` and at the predicted `q_½`), see
    /// [`zhao_van_wachem::step`].
    pub fn step(
        self,
        state: &mut RotState,
        inertia: DVec3,
        torque: &mut dyn FnMut(DQuat) -> DVec3,
        dt: f64,
    ) {
        match self {
            RotationScheme::Richardson
            | RotationScheme::NoSquish
            | RotationScheme::ZhaoVanWachemSplit
            | RotationScheme::RichardsonLiggghts => {
                let half = 0.5 * dt;
                state.l_world += torque(state.q) * half;
                state.q = self.drift(state.q, state.l_world, inertia, dt);
                state.l_world += torque(state.q) * half;
            }
            RotationScheme::ZhaoVanWachem => zhao_van_wachem::step(state, inertia, torque, dt),
        }
    }

    /// All production schemes, for tests and benchmarks.
    pub const ALL: [RotationScheme; 5] = [
        RotationScheme::Richardson,
        RotationScheme::ZhaoVanWachem,
        RotationScheme::NoSquish,
        RotationScheme::ZhaoVanWachemSplit,
        RotationScheme::RichardsonLiggghts,
    ];

    /// Whether the DEM step kicks the angular momentum by half steps of the
    /// torque (velocity Verlet); false for [`RotationScheme::ZhaoVanWachem`],
    /// which advances `L` over the whole step itself.
    #[inline(always)]
    pub fn kicks_torque(self) -> bool {
        self != RotationScheme::ZhaoVanWachem
    }
}

/// The drift of a spherical top of principal moment `inertia` (kg m²) over
/// `dt` (s), `q ← exp(L dt/I) q` renormalised ([`RotationScheme::drift`];
/// `l_world` in kg m²/s, world frame), with no branch, so that a loop over
/// several bodies vectorises (`step::first_half_lanes`): the result, and
/// whether it holds, i.e. whether the rotation is small enough for the
/// exponential's series and the product near enough to unit length for
/// the Newton renormalisation. Where it holds, it is the drift's result
/// bit for bit; elsewhere it is to be discarded.
#[inline(always)]
pub(crate) fn spherical_top_drift_small(
    q: DQuat,
    l_world: DVec3,
    inertia: f64,
    dt: f64,
) -> (DQuat, bool) {
    let (turn, small) = crate::math::quat_from_small_rotation_vector(l_world * (dt / inertia));
    let (q1, unit) = crate::math::renormalize_near_unit(turn * q);
    (q1, small & unit)
}
