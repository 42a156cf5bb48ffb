//! The per-body arrays of a coupling, part of the body set
//! ([`crate::body::Bodies::coupling`]) so that they follow every
//! reordering of the bodies. Each array is empty while unused (the step
//! then reads nothing of it) or holds one entry per body, world frame.

use glam::DVec3;

/// Per-body coupling data, indexed by storage index like the bodies.
/// Checkpoints hold it beside the bodies (`WorldState::coupling`).
#[derive(Debug, Clone, Default, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct BodyCoupling {
    /// External force acting at every step until changed, N.
    pub force: Vec<DVec3>,
    /// External torque about the centre of mass, every step, N m.
    pub torque: Vec<DVec3>,
    /// External force for the next step's force evaluation only, N
    /// (cleared by that step).
    pub once_force: Vec<DVec3>,
    /// External torque for the next step only, N m.
    pub once_torque: Vec<DVec3>,
    /// Interstitial fluid velocity at the body, m/s (else the fluid's uniform one).
    pub fluid_velocity: Vec<DVec3>,
    /// Local void fraction at the body (else 1).
    pub void_fraction: Vec<f64>,
    /// The fluid force of the last force evaluation: drag, buoyancy and
    /// pressure gradient, N (written by the step while a fluid is set).
    pub fluid_force: Vec<DVec3>,
}

/// Calls `f` on each array with the value a new body gets.
macro_rules! each_array {
    ($c:expr, $f:ident) => {{
        $f(&mut $c.force, DVec3::ZERO);
        $f(&mut $c.torque, DVec3::ZERO);
        $f(&mut $c.once_force, DVec3::ZERO);
        $f(&mut $c.once_torque, DVec3::ZERO);
        $f(&mut $c.fluid_velocity, DVec3::ZERO);
        $f(&mut $c.void_fraction, 1.0);
        $f(&mut $c.fluid_force, DVec3::ZERO);
    }};
}

impl BodyCoupling {
    /// True when no array is in use.
    pub fn is_empty(&self) -> bool {
        self.force.is_empty()
            && self.torque.is_empty()
            && self.once_force.is_empty()
            && self.once_torque.is_empty()
            && self.fluid_velocity.is_empty()
            && self.void_fraction.is_empty()
            && self.fluid_force.is_empty()
    }

    /// True when every array is unused or holds `n` entries (one per body).
    pub fn fits(&self, n: usize) -> bool {
        fn ok<T>(v: &[T], n: usize) -> bool {
            v.is_empty() || v.len() == n
        }
        ok(&self.force, n)
            && ok(&self.torque, n)
            && ok(&self.once_force, n)
            && ok(&self.once_torque, n)
            && ok(&self.fluid_velocity, n)
            && ok(&self.void_fraction, n)
            && ok(&self.fluid_force, n)
    }

    /// A body was appended: the arrays in use grow by its default entry.
    pub(crate) fn push(&mut self) {
        fn grow<T: Copy>(v: &mut Vec<T>, x: T) {
            if !v.is_empty() {
                v.push(x);
            }
        }
        each_array!(self, grow);
    }

    /// The `n_other` bodies of `other` were appended to `n_self` bodies.
    pub(crate) fn append(&mut self, other: &BodyCoupling, n_self: usize, n_other: usize) {
        fn join<T: Copy>(a: &mut Vec<T>, b: &[T], n_self: usize, n_other: usize, x: T) {
            if a.is_empty() && b.is_empty() {
                return;
            }
            a.resize(n_self, x);
            if b.is_empty() {
                a.resize(n_self + n_other, x);
            } else {
                a.extend_from_slice(b);
            }
        }
        join(&mut self.force, &other.force, n_self, n_other, DVec3::ZERO);
        join(
            &mut self.torque,
            &other.torque,
            n_self,
            n_other,
            DVec3::ZERO,
        );
        join(
            &mut self.once_force,
            &other.once_force,
            n_self,
            n_other,
            DVec3::ZERO,
        );
        join(
            &mut self.once_torque,
            &other.once_torque,
            n_self,
            n_other,
            DVec3::ZERO,
        );
        join(
            &mut self.fluid_velocity,
            &other.fluid_velocity,
            n_self,
            n_other,
            DVec3::ZERO,
        );
        join(
            &mut self.void_fraction,
            &other.void_fraction,
            n_self,
            n_other,
            1.0,
        );
        join(
            &mut self.fluid_force,
            &other.fluid_force,
            n_self,
            n_other,
            DVec3::ZERO,
        );
    }

    /// Writes entries `perm[0], perm[1], …` into `out` (reusing its buffers).
    pub(crate) fn permute_into(&self, perm: &[u32], out: &mut BodyCoupling) {
        fn gather<T: Copy>(src: &[T], perm: &[u32], dst: &mut Vec<T>) {
            dst.clear();
            if !src.is_empty() {
                dst.extend(perm.iter().map(|&k| src[k as usize]));
            }
        }
        gather(&self.force, perm, &mut out.force);
        gather(&self.torque, perm, &mut out.torque);
        gather(&self.once_force, perm, &mut out.once_force);
        gather(&self.once_torque, perm, &mut out.once_torque);
        gather(&self.fluid_velocity, perm, &mut out.fluid_velocity);
        gather(&self.void_fraction, perm, &mut out.void_fraction);
        gather(&self.fluid_force, perm, &mut out.fluid_force);
    }
}

/// `v` as an array of `n` entries in use (filled with `x` when it was not).
pub(crate) fn in_use<T: Copy>(v: &mut Vec<T>, n: usize, x: T) -> &mut [T] {
    if v.len() != n {
        v.clear();
        v.resize(n, x);
    }
    v
}
