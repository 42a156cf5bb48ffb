//! Rigid bodies (clumps), stored as a structure of arrays.
//!
//! Every body is an instance of a [`crate::shape::ClumpTemplate`]; its spheres
//! are derived from the body pose each step (see [`crate::sphere`]).

use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// Per-axis flags: `true` lets the world-frame force (or torque) component act.
/// This is LIGGGHTS' `fflag`/`tflag`: a `false` component is frozen (the
/// velocity or angular-momentum component is never kicked).
pub type AxisFlags = [bool; 3];

/// Everything needed to create one body.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BodyInit {
    /// Index of the template in the world's template list.
    pub template: u32,
    /// Centre of mass, world frame, m.
    pub position: DVec3,
    /// Orientation, body → world.
    pub orientation: DQuat,
    /// Centre-of-mass velocity, world frame, m/s.
    pub velocity: DVec3,
    /// Angular velocity, world frame, rad/s.
    pub angular_velocity: DVec3,
    /// Force flags per world axis (LIGGGHTS `fflag`).
    pub force_flag: AxisFlags,
    /// Torque flags per world axis (LIGGGHTS `tflag`).
    pub torque_flag: AxisFlags,
    /// Step from which the body is integrated under forces. Before it the body
    /// moves ballistically at `velocity` (LIGGGHTS' `has_stream … start_step`
    /// branch), ignoring forces.
    pub start_step: u64,
}

impl BodyInit {
    /// A body at rest at `position` with orientation `orientation`, all DOFs free.
    pub fn at_rest(template: u32, position: DVec3, orientation: DQuat) -> Self {
        Self {
            template,
            position,
            orientation,
            velocity: DVec3::ZERO,
            angular_velocity: DVec3::ZERO,
            force_flag: [true; 3],
            torque_flag: [true; 3],
            start_step: 0,
        }
    }
}

/// All bodies of a simulation, as a structure of arrays. Index `b` is the
/// body's *storage* index, which changes when bodies are spatially re-sorted;
/// `id[b]` is its permanent global id.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct Bodies {
    /// Permanent global id (unique for the whole run, also across ranks).
    pub id: Vec<u64>,
    /// Template index.
    pub template: Vec<u32>,
    /// Centre of mass, world frame, m.
    pub position: Vec<DVec3>,
    /// Centre-of-mass velocity, world frame, m/s.
    pub velocity: Vec<DVec3>,
    /// Orientation, body → world (unit quaternion).
    pub orientation: Vec<DQuat>,
    /// Angular momentum about the centre of mass, world frame, kg m²/s.
    pub angular_momentum: Vec<DVec3>,
    /// Angular velocity, world frame, rad/s (derived from the angular momentum).
    pub angular_velocity: Vec<DVec3>,
    /// Total force (contacts + gravity), world frame, N.
    pub force: Vec<DVec3>,
    /// Total torque about the centre of mass, world frame, N m.
    pub torque: Vec<DVec3>,
    /// Mass, kg (the true clump mass; the added-mass factor is applied separately).
    pub mass: Vec<f64>,
    /// Principal moments of inertia, body frame, kg m².
    pub inertia: Vec<DVec3>,
    /// Force flags per world axis.
    pub force_flag: Vec<AxisFlags>,
    /// Torque flags per world axis.
    pub torque_flag: Vec<AxisFlags>,
    /// Step from which forces act (ballistic before it).
    pub start_step: Vec<u64>,
    /// Temperature, K (one per body: lumped). Empty while the world has no
    /// heat (`World::heat`), else one per body.
    pub temperature: Vec<f64>,
    /// Heat source, W. Empty while the world has no heat, else one per body.
    pub heat_source: Vec<f64>,
    /// External forces and fluid data of a coupling (each array empty
    /// while unused); set through the world's methods, not checkpointed.
    #[serde(skip)]
    pub coupling: crate::fluid::BodyCoupling,
}

impl Bodies {
    /// Number of bodies.
    pub fn len(&self) -> usize {
        self.id.len()
    }

    /// True when there are no bodies.
    pub fn is_empty(&self) -> bool {
        self.id.is_empty()
    }

    /// Appends one body with the given global id, mass (kg) and principal
    /// inertia (body frame, kg m²).
    pub fn push(&mut self, id: u64, init: &BodyInit, mass: f64, inertia: DVec3) {
        let q = init.orientation.normalize();
        // L_world = R I Rᵀ ω_world
        let w_body = q.inverse() * init.angular_velocity;
        let l_world = q * (inertia * w_body);
        self.id.push(id);
        self.template.push(init.template);
        self.position.push(init.position);
        self.velocity.push(init.velocity);
        self.orientation.push(q);
        self.angular_momentum.push(l_world);
        self.angular_velocity.push(init.angular_velocity);
        self.force.push(DVec3::ZERO);
        self.torque.push(DVec3::ZERO);
        self.mass.push(mass);
        self.inertia.push(inertia);
        self.force_flag.push(init.force_flag);
        self.torque_flag.push(init.torque_flag);
        self.start_step.push(init.start_step);
        self.coupling.push();
    }

    /// Appends every body of `other`, in its order.
    pub fn append(&mut self, other: &Bodies) {
        self.coupling
            .append(&other.coupling, self.len(), other.len());
        self.id.extend_from_slice(&other.id);
        self.template.extend_from_slice(&other.template);
        self.position.extend_from_slice(&other.position);
        self.velocity.extend_from_slice(&other.velocity);
        self.orientation.extend_from_slice(&other.orientation);
        self.angular_momentum
            .extend_from_slice(&other.angular_momentum);
        self.angular_velocity
            .extend_from_slice(&other.angular_velocity);
        self.force.extend_from_slice(&other.force);
        self.torque.extend_from_slice(&other.torque);
        self.mass.extend_from_slice(&other.mass);
        self.inertia.extend_from_slice(&other.inertia);
        self.force_flag.extend_from_slice(&other.force_flag);
        self.torque_flag.extend_from_slice(&other.torque_flag);
        self.start_step.extend_from_slice(&other.start_step);
        self.temperature.extend_from_slice(&other.temperature);
        self.heat_source.extend_from_slice(&other.heat_source);
    }

    /// Reorders all arrays so that new index `k` holds old index `perm[k]`.
    /// `perm` may be shorter than `len()`: bodies not listed are dropped.
    pub fn permute(&mut self, perm: &[u32]) {
        let mut out = Bodies::default();
        self.permute_into(perm, &mut out);
        *self = out;
    }

    /// Writes the bodies `perm[0], perm[1], …` of `self` into `out`, reusing
    /// `out`'s buffers (no allocation once they are large enough): the
    /// double-buffered form of [`Bodies::permute`] used at every rebuild.
    pub fn permute_into(&self, perm: &[u32], out: &mut Bodies) {
        fn gather<T: Copy>(src: &[T], perm: &[u32], dst: &mut Vec<T>) {
            dst.clear();
            dst.extend(perm.iter().map(|&k| src[k as usize]));
        }
        // the heat arrays are empty without heat, and stay so
        fn gather_opt(src: &[f64], perm: &[u32], dst: &mut Vec<f64>) {
            dst.clear();
            if !src.is_empty() {
                gather(src, perm, dst);
            }
        }
        gather(&self.id, perm, &mut out.id);
        gather(&self.template, perm, &mut out.template);
        gather(&self.position, perm, &mut out.position);
        gather(&self.velocity, perm, &mut out.velocity);
        gather(&self.orientation, perm, &mut out.orientation);
        gather(&self.angular_momentum, perm, &mut out.angular_momentum);
        gather(&self.angular_velocity, perm, &mut out.angular_velocity);
        gather(&self.force, perm, &mut out.force);
        gather(&self.torque, perm, &mut out.torque);
        gather(&self.mass, perm, &mut out.mass);
        gather(&self.inertia, perm, &mut out.inertia);
        gather(&self.force_flag, perm, &mut out.force_flag);
        gather(&self.torque_flag, perm, &mut out.torque_flag);
        gather(&self.start_step, perm, &mut out.start_step);
        gather_opt(&self.temperature, perm, &mut out.temperature);
        gather_opt(&self.heat_source, perm, &mut out.heat_source);
        self.coupling.permute_into(perm, &mut out.coupling);
    }
}
