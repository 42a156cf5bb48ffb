//! NO_SQUISH free-rotor integrator (Miller, Eleftheriou, Pattnaik, Ndirango,
//! Newns & Martyna, J. Chem. Phys. 116, 8649 (2002)), written from the paper's
//! idea.
//!
//! The free-rotor Hamiltonian `T = Σ_k L_b,k² / (2 I_k)` is split into the
//! three terms `T_k`. The flow of `T_k` alone is exact and simple: a rotation
//! of the body about its principal axis `k` at the constant rate
//! `L_b,k / I_k` (the body-frame momentum rotates the opposite way so that the
//! world-frame `L` stays fixed). The symmetric composition
//! `T3(dt/2) T2(dt/2) T1(dt) T2(dt/2) T3(dt/2)` is symplectic,
//! time-reversible and second order: `L_world` is kept exactly, and the energy
//! error stays bounded (no secular drift).

use glam::{DQuat, DVec3};

use crate::math::{sin_cos, sin_cos_small};

/// How a rotation of the splitting takes its sine and cosine.
trait Trig {
    /// Whether a zero moment is looked for (no rotation about that axis).
    const GUARDED: bool;
    /// `(sin x, cos x)` and whether they hold.
    fn sin_cos(x: f64) -> (f64, f64, bool);
}

/// [`sin_cos`], with the zero-moment guard: [`drift`].
struct Exact;

impl Trig for Exact {
    const GUARDED: bool = true;
    #[inline(always)]
    fn sin_cos(x: f64) -> (f64, f64, bool) {
        let (s, c) = sin_cos(x);
        (s, c, true)
    }
}

/// [`sin_cos_small`], with no branch: [`drift_small`].
struct Series;

impl Trig for Series {
    const GUARDED: bool = false;
    #[inline(always)]
    fn sin_cos(x: f64) -> (f64, f64, bool) {
        sin_cos_small(x)
    }
}

/// Rotates the body by `phi = L_b,K / I_K · h` (rad) about its principal
/// axis `K`: the orientation gains the body-frame factor exp(φ/2 e_K) on
/// the right, and the body-frame angular momentum turns by −φ about `K`
/// (the world-frame angular momentum is unchanged). Returns whether the
/// sine and cosine held. `K` is a constant so that the indexing compiles
/// away.
#[inline(always)]
fn rotate_about_principal_axis<const K: usize, T: Trig>(
    q: &mut DQuat,
    l_body: &mut DVec3,
    inertia: DVec3,
    h: f64,
) -> bool {
    let i_k = inertia[K];
    if T::GUARDED && i_k <= 0.0 {
        return true;
    }
    let phi = l_body[K] / i_k * h;
    let (s2, c2, held) = T::sin_cos(0.5 * phi);
    let r = match K {
        0 => DQuat::from_xyzw(s2, 0.0, 0.0, c2),
        1 => DQuat::from_xyzw(0.0, s2, 0.0, c2),
        _ => DQuat::from_xyzw(0.0, 0.0, s2, c2),
    };
    *q = *q * r;
    let (s, c) = (2.0 * s2 * c2, c2 * c2 - s2 * s2);
    let (a, b) = ((K + 1) % 3, (K + 2) % 3);
    let (la, lb) = (l_body[a], l_body[b]);
    l_body[a] = c * la + s * lb;
    l_body[b] = -s * la + c * lb;
    held
}

/// NO_SQUISH free-rotation drift over `dt` (s): the symmetric splitting
/// 3(dt/2), 2(dt/2), 1(dt), 2(dt/2), 3(dt/2) of the free rotor into exact
/// rotations about the principal axes (Miller et al. 2002). `l_world` is the
/// angular momentum (world frame, kg m²/s), constant during the drift;
/// `inertia` the principal moments (body frame, kg m²). A zero moment means
/// no rotation about that axis.
pub fn drift(q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> DQuat {
    drift_by::<Exact>(q, l_world, inertia, dt).0
}

/// [`drift`] of a body whose three principal moments are positive, with
/// the sines and cosines by their series alone and no branch (for the
/// first half's lanes): the orientation, and whether every series holds
/// (half angles below 0.02). Where they do, this is [`drift`]'s result bit
/// for bit; elsewhere the orientation is to be discarded.
#[inline(always)]
pub fn drift_small(q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> (DQuat, bool) {
    drift_by::<Series>(q, l_world, inertia, dt)
}

/// The splitting of [`drift`], its sines and cosines by `T`: the
/// orientation, and whether they all held.
#[inline(always)]
fn drift_by<T: Trig>(q: DQuat, l_world: DVec3, inertia: DVec3, dt: f64) -> (DQuat, bool) {
    let half = 0.5 * dt;
    let mut q = q;
    let mut lb = q.conjugate() * l_world;
    let mut held = rotate_about_principal_axis::<2, T>(&mut q, &mut lb, inertia, half);
    held &= rotate_about_principal_axis::<1, T>(&mut q, &mut lb, inertia, half);
    held &= rotate_about_principal_axis::<0, T>(&mut q, &mut lb, inertia, dt);
    held &= rotate_about_principal_axis::<1, T>(&mut q, &mut lb, inertia, half);
    held &= rotate_about_principal_axis::<2, T>(&mut q, &mut lb, inertia, half);
    (q.normalize(), held)
}
