//! Velocity-Verlet integration of the bodies (seed 000, LIGGGHTS
//! `fix multisphere`): half kicks of the centre-of-mass velocity and of the
//! world angular momentum, with per-axis force/torque flags and the added-mass
//! factor; a full drift of the centre of mass; and a free-rotation drift of
//! the orientation by the chosen [`crate::rotation::RotationScheme`].

use super::affinity::{body_chunk_cost, for_each_chunk_with, INITIAL_LOOP};
use super::kinematics::sphere_position;
use super::shared::{at, SharedMut};
use crate::neighbor::skin;
use crate::rotation::{inverse_inertia, omega_world, omega_world_rot};
use crate::world::World;
use glam::{DMat3, DVec3};
use std::sync::atomic::{AtomicBool, Ordering};

/// First half of the step: v += F dt/(2 m'), x += v dt, L += M dt/(2 f_a),
/// q ← drift(q, L, dt), ω from L. A body before its start step moves
/// ballistically at its current velocity, ignoring forces.
///
/// With `spheres` (the sphere topology is current), the same pass also
/// updates the body's spheres (see [`super::kinematics`]) and checks them
/// against the Verlet skin; it then returns true when some sphere moved more
/// than half the skin since the last neighbour build. Without, the spheres
/// are left alone and it returns false.
pub fn initial(w: &mut World, spheres: bool) -> bool {
    let dt = w.config.dt;
    let scheme = w.config.rotation;
    let step = w.step;
    let n = w.bodies.len();
    let limit2 = skin::trigger_distance2(w.skin());
    let b = &mut w.bodies;
    let templates = &w.templates;
    let added = w.config.added_mass;
    let pos = SharedMut::new(&mut b.position);
    let vel = SharedMut::new(&mut b.velocity);
    let quat = SharedMut::new(&mut b.orientation);
    let angm = SharedMut::new(&mut b.angular_momentum);
    let omega = SharedMut::new(&mut b.angular_velocity);
    let (force, torque, mass, inertia) = (&b.force, &b.torque, &b.mass, &b.inertia);
    let (ff, tf, start, tmpl) = (&b.force_flag, &b.torque_flag, &b.start_step, &b.template);
    let sp = &mut w.spheres;
    let spheres = spheres && w.reference_position.len() == sp.len();
    let sst = SharedMut::new(&mut sp.state);
    let (first, tfirst, toff, xref) = (
        &sp.body_first,
        &w.template_first,
        &w.template_offset,
        &w.reference_position,
    );
    // the pair stage's packed copy of the bodies' state (when built for
    // these bodies; else the rebuild that follows fills it)
    let packed = w.pairs.body.len() == n;
    let pair_body = SharedMut::new(&mut w.pairs.body);
    let any_stale = AtomicBool::new(false);
    let cost = body_chunk_cost(&w.body_cost, n, BODY_BLOCK);
    for_each_chunk_with(
        n.div_ceil(BODY_BLOCK),
        cost,
        &mut w.balance[INITIAL_LOOP],
        || (),
        |_, blk| {
            let mut stale = false;
            for i in blk * BODY_BLOCK..((blk + 1) * BODY_BLOCK).min(n) {
                // SAFETY: each body index is handled by exactly one block.
                let (x, v, q, l, om) = unsafe {
                    (
                        pos.get(i),
                        vel.get(i),
                        quat.get(i),
                        angm.get(i),
                        omega.get(i),
                    )
                };
                // SAFETY (all `at` below): i < n, every body array has n
                // entries, template indices are valid, and with `spheres` the
                // sphere topology (body_first, reference positions) is current.
                let rot = if step < unsafe { at(start, i) } {
                    *x += *v * dt;
                    DMat3::from_quat(*q)
                } else {
                    let t = unsafe { at(tmpl, i) } as usize;
                    let fa = mass_factor(added, templates[t].density);
                    let kick = HalfKick::new(dt, unsafe { at(mass, i) }, fa);
                    let (fi, ti) = unsafe { (at(force, i), at(torque, i)) };
                    kick.apply(v, l, fi, ti, unsafe { at(ff, i) }, unsafe { at(tf, i) });
                    *x += *v * dt;
                    let inertia_i = unsafe { at(inertia, i) };
                    *q = scheme.drift(*q, *l, inertia_i, dt);
                    let rot = DMat3::from_quat(*q);
                    *om = omega_world_rot(&rot, *l, inverse_inertia(inertia_i));
                    rot
                };
                if packed {
                    // SAFETY: body i is handled by this block only; its
                    // column sum is not touched.
                    unsafe {
                        let pb = pair_body.ptr(i);
                        (*pb).position = *x;
                        (*pb).velocity = *v;
                        (*pb).angular_velocity = *om;
                    }
                }
                if spheres {
                    let o0 = unsafe { at(tfirst, at(tmpl, i) as usize) } as usize;
                    let (s0, s1) = unsafe { (at(first, i) as usize, at(first, i + 1) as usize) };
                    for (k, s) in (s0..s1).enumerate() {
                        let off = unsafe { at(toff, o0 + k) };
                        let px = sphere_position(*x, &rot, off);
                        // SAFETY: the spheres of body i are written by its block only.
                        unsafe { sst.get(s) }.position = px;
                        stale |= skin::moved_too_far(px, unsafe { at(xref, s) }, limit2);
                    }
                }
            }
            if stale {
                any_stale.store(true, Ordering::Relaxed);
            }
        },
    );
    any_stale.into_inner()
}

/// Bodies per block of the first half step: the gather's chunk, so that a
/// thread moves the bodies whose forces it gathers (see
/// [`super::affinity`]); any size gives the same results.
const BODY_BLOCK: usize = super::force::BODY_CHUNK;

/// The second half kick, `v += F dt/(2 m')`, `L += M dt/(2 f_a)`, ω from L
/// (world frame), of one body at a time: the force gather
/// ([`super::force::gather`]) applies it to each body as soon as that body's
/// force and torque are summed, in the same pass (one sweep over the bodies
/// and one parallel loop fewer per step). A body before its start step is
/// left alone.
pub(crate) struct FinalKick<'a> {
    dt: f64,
    step: u64,
    added: crate::world::AddedMass,
    templates: &'a [crate::shape::ClumpTemplate],
    b: &'a crate::body::Bodies,
}

impl<'a> FinalKick<'a> {
    /// The kick of the current step of `w`'s bodies `b`.
    pub(crate) fn new(
        dt: f64,
        step: u64,
        added: crate::world::AddedMass,
        templates: &'a [crate::shape::ClumpTemplate],
        b: &'a crate::body::Bodies,
    ) -> Self {
        FinalKick {
            dt,
            step,
            added,
            templates,
            b,
        }
    }

    /// Kicks body `i`: its velocity `v` (m/s), angular momentum `l`
    /// (kg m²/s) and angular velocity `om` (rad/s), all world frame, under
    /// the force `f` (N) and torque `m` (N m, about the centre of mass).
    ///
    /// # Safety
    /// `i` is a body index (`i < b.len()`); read unchecked in release builds.
    #[inline(always)]
    pub(crate) unsafe fn apply(
        &self,
        i: usize,
        v: &mut DVec3,
        l: &mut DVec3,
        om: &mut DVec3,
        f: DVec3,
        m: DVec3,
    ) {
        let b = self.b;
        if self.step < unsafe { at(&b.start_step, i) } {
            return;
        }
        let t = unsafe { at(&b.template, i) } as usize;
        let fa = mass_factor(self.added, self.templates[t].density);
        let (ff, tf) = unsafe { (at(&b.force_flag, i), at(&b.torque_flag, i)) };
        HalfKick::new(self.dt, unsafe { at(&b.mass, i) }, fa).apply(v, l, f, m, ff, tf);
        let (q, inertia) = unsafe { (at(&b.orientation, i), at(&b.inertia, i)) };
        *om = omega_world(q, *l, inertia);
    }
}

/// A half kick of one body over `dt/2`: `v += F dt/(2 m f_a)`,
/// `L += M dt/(2 f_a)` (world frame), per axis only where the flag allows.
struct HalfKick {
    /// `dt/(2 m f_a)`, s/kg.
    dtfm: f64,
    /// `dt/(2 f_a)`, s.
    dtt: f64,
}

impl HalfKick {
    #[inline(always)]
    fn new(dt: f64, mass: f64, fa: f64) -> Self {
        let half = 0.5 * dt;
        HalfKick {
            dtfm: half / (mass * fa),
            // without added mass (fa = 1) the quotient is `half` exactly
            dtt: if fa == 1.0 { half } else { half / fa },
        }
    }

    #[inline(always)]
    fn apply(
        &self,
        v: &mut glam::DVec3,
        l: &mut glam::DVec3,
        force: glam::DVec3,
        torque: glam::DVec3,
        ff: crate::body::AxisFlags,
        tf: crate::body::AxisFlags,
    ) {
        // a free body (every axis kicked, the common case): plain vector
        // additions, without building the masks (4 % of the gather)
        if ff == [true; 3] && tf == [true; 3] {
            *v += self.dtfm * force;
            *l += self.dtt * torque;
            return;
        }
        // whole-vector selects, not per-component stores: the integration
        // reads `v` and `l` back as vectors at once, and a vector load of
        // three separate scalar stores cannot be forwarded (a stall measured
        // at 9 % of the gather pass). Same bits: a locked axis keeps its value.
        let (fm, tm) = (glam::BVec3::from(ff), glam::BVec3::from(tf));
        *v = glam::DVec3::select(fm, *v + self.dtfm * force, *v);
        *l = glam::DVec3::select(tm, *l + self.dtt * torque, *l);
    }
}

/// Added-mass factor `1 + CAdd ρ_f / ρ_body`.
#[inline(always)]
fn mass_factor(a: crate::world::AddedMass, rho: f64) -> f64 {
    if a.coefficient == 0.0 || a.fluid_density == 0.0 {
        1.0
    } else {
        1.0 + a.coefficient * a.fluid_density / rho
    }
}
