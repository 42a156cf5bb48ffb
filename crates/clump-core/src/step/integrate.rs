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
    let n = w.bodies.len();
    let limit2 = skin::trigger_distance2(w.skin());
    let drift = Drift::new(
        &w.config,
        limit2,
        w.step,
        &w.templates,
        &mut w.bodies,
        &mut w.spheres,
        (&w.template_first, &w.template_offset, &w.reference_position),
        spheres,
    );
    let (force, torque) = (&w.bodies.force, &w.bodies.torque);
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
                // SAFETY: each body index is handled by exactly one block;
                // i < n.
                stale |= unsafe { drift.body(i, at(force, i), at(torque, i)) };
            }
            if stale {
                any_stale.store(true, Ordering::Relaxed);
            }
        },
    );
    any_stale.into_inner()
}

/// The first half of a step ([`initial`]) for one body at a time: the
/// separate pass runs it over all bodies, and the gather of the previous
/// step runs it on each body right after that body's final kick, when the
/// two steps follow each other with nothing in between (see
/// [`World::run`]). Same arithmetic either way, so the same bits.
pub(crate) struct Drift<'a> {
    dt: f64,
    /// The step whose first half this is.
    step: u64,
    scheme: crate::rotation::RotationScheme,
    /// Square of the skin trigger distance, m².
    limit2: f64,
    added: crate::world::AddedMass,
    templates: &'a [crate::shape::ClumpTemplate],
    pos: SharedMut<DVec3>,
    vel: SharedMut<DVec3>,
    quat: SharedMut<glam::DQuat>,
    angm: SharedMut<DVec3>,
    omega: SharedMut<DVec3>,
    mass: SharedMut<f64>,
    inertia: SharedMut<DVec3>,
    ff: SharedMut<crate::body::AxisFlags>,
    tf: SharedMut<crate::body::AxisFlags>,
    start: SharedMut<u64>,
    tmpl: SharedMut<u32>,
    /// Sphere state (written), when `spheres`.
    sst: SharedMut<crate::sphere::SphereState>,
    first: SharedMut<u32>,
    tfirst: &'a [u32],
    toff: &'a [DVec3],
    xref: &'a [DVec3],
    /// The spheres move with their bodies (the sphere topology is current).
    spheres: bool,
}

impl<'a> Drift<'a> {
    /// The first half of step `step` of the bodies `b` and their spheres
    /// `sp` (moved too when `spheres` and the sphere topology is current:
    /// `xref`, the reference positions of the last build, has one entry per
    /// sphere); `limit2` is the square of the skin trigger distance, m².
    /// Holds raw pointers into the body and sphere arrays: they must not be
    /// resized or moved while it is in use.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn new(
        config: &crate::world::WorldConfig,
        limit2: f64,
        step: u64,
        templates: &'a [crate::shape::ClumpTemplate],
        b: &mut crate::body::Bodies,
        sp: &mut crate::sphere::Spheres,
        (tfirst, toff, xref): (&'a [u32], &'a [DVec3], &'a [DVec3]),
        spheres: bool,
    ) -> Self {
        Drift {
            dt: config.dt,
            step,
            scheme: config.rotation,
            limit2,
            added: config.added_mass,
            templates,
            pos: SharedMut::new(&mut b.position),
            vel: SharedMut::new(&mut b.velocity),
            quat: SharedMut::new(&mut b.orientation),
            angm: SharedMut::new(&mut b.angular_momentum),
            omega: SharedMut::new(&mut b.angular_velocity),
            mass: SharedMut::new(&mut b.mass),
            inertia: SharedMut::new(&mut b.inertia),
            ff: SharedMut::new(&mut b.force_flag),
            tf: SharedMut::new(&mut b.torque_flag),
            start: SharedMut::new(&mut b.start_step),
            tmpl: SharedMut::new(&mut b.template),
            spheres: spheres && xref.len() == sp.len(),
            sst: SharedMut::new(&mut sp.state),
            first: SharedMut::new(&mut sp.body_first),
            tfirst,
            toff,
            xref,
        }
    }

    /// Body `i`'s first half step under the force `f` (N) and torque `m`
    /// (N m about its centre of mass), both world frame, and its spheres'
    /// update; true when one of them moved beyond the skin trigger.
    ///
    /// # Safety
    /// `i` is a body index, and no other thread touches body `i` or its
    /// spheres during the call. Unchecked in release builds.
    #[inline(always)]
    pub(crate) unsafe fn body(&self, i: usize, f: DVec3, m: DVec3) -> bool {
        let dt = self.dt;
        let (x, v, q, l, om) = (
            self.pos.get(i),
            self.vel.get(i),
            self.quat.get(i),
            self.angm.get(i),
            self.omega.get(i),
        );
        let t = self.tmpl.read(i) as usize;
        let rot = if self.step < self.start.read(i) {
            *x += *v * dt;
            DMat3::from_quat(*q)
        } else {
            let fa = mass_factor(self.added, self.templates[t].density);
            let kick = HalfKick::new(dt, self.mass.read(i), fa);
            kick.apply(v, l, f, m, self.ff.read(i), self.tf.read(i));
            *x += *v * dt;
            let inertia_i = self.inertia.read(i);
            *q = self.scheme.drift(*q, *l, inertia_i, dt);
            let rot = DMat3::from_quat(*q);
            *om = omega_world_rot(&rot, *l, inverse_inertia(inertia_i));
            rot
        };
        let mut stale = false;
        if self.spheres {
            // SAFETY: the sphere topology (body_first, template offsets,
            // reference positions) is current, so every index is in range.
            let o0 = at(self.tfirst, t) as usize;
            let (s0, s1) = (self.first.read(i) as usize, self.first.read(i + 1) as usize);
            for (k, s) in (s0..s1).enumerate() {
                let off = at(self.toff, o0 + k);
                let px = sphere_position(*x, &rot, off);
                self.sst.get(s).position = px;
                stale |= skin::moved_too_far(px, at(self.xref, s), self.limit2);
            }
        }
        stale
    }
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
