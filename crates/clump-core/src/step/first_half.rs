//! Velocity-Verlet integration of the bodies (docs/theory.md T-15, LIGGGHTS
//! `fix multisphere`): half kicks of the centre-of-mass velocity and of the
//! world angular momentum, with per-axis force/torque flags and the added-mass
//! factor; a full drift of the centre of mass; and a free-rotation drift of
//! the orientation by the chosen [`crate::rotation::RotationScheme`].

use super::body_props::BodyProps;
use super::first_half_lanes::{BodyLanes, LaneKind, LANES};
use super::kick::{Held, Kicks};
use super::kinematics::sphere_position;
use crate::neighbor::skin;
use crate::par::affinity::{body_chunk_cost, for_each_chunk_with, INITIAL_LOOP};
use crate::par::shared::{at, SharedMut};
use crate::par::simd::get3;
use crate::rotation::omega_world_rot;
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
    // SAFETY: the arrays stay put during the loop, and each body is moved
    // by one block only.
    let half = unsafe { FirstHalf::new(w, w.step, spheres) };
    let (force, torque) = (&w.bodies.force, &w.bodies.torque);
    let any_stale = AtomicBool::new(false);
    // the gather's chunks, so that a thread moves the bodies whose forces
    // it gathers (see crate::par::affinity); any size gives the same results
    let block = w.body_chunk();
    let cost = body_chunk_cost(&w.scratch.body_cost, n, block);
    for_each_chunk_with(
        n.div_ceil(block),
        cost,
        &mut w.scratch.balance[INITIAL_LOOP],
        BodyLanes::idle,
        |lanes, blk| {
            let mut stale = false;
            let end = ((blk + 1) * block).min(n);
            let mut held = [Held::default(); LANES];
            for k0 in (blk * block..end).step_by(LANES) {
                let k1 = (k0 + LANES).min(end);
                // SAFETY: each body index is handled by exactly one block;
                // every index is below n.
                unsafe {
                    for i in k0..k1 {
                        held[i - k0] = Held {
                            v: half.vel.read(i),
                            l: half.angm.read(i),
                            om: half.omega.read(i),
                            f: at(force, i),
                            m: at(torque, i),
                        };
                    }
                    stale |= half.apply_block(k0, &mut held[..k1 - k0], lanes);
                }
            }
            if stale {
                any_stale.store(true, Ordering::Relaxed);
            }
        },
    );
    any_stale.into_inner()
}

/// Tests only: whether every body takes the scalar path.
#[inline(always)]
fn lanes_off() -> bool {
    #[cfg(test)]
    return super::first_half_lanes::SCALAR_ONLY.load(std::sync::atomic::Ordering::SeqCst);
    #[cfg(not(test))]
    false
}

/// Fewest asymmetric bodies of a block for which [`BodyLanes`] run: a run
/// of the Richardson or NO_SQUISH lanes costs about three to four such
/// bodies' scalar first halves (eight lanes in two vectors of four on AVX2,
/// whose chains of dependent operations are as long as one body's), so
/// blocks of many-sphere stones, two to a chunk, are stepped one by one.
const GENERAL_MIN: usize = 4;

/// The first half step of one body at a time (see [`initial`]): the pass of
/// its own, or fused into the gather of the step before
/// ([`super::force::gather`]), which applies it to a few bodies at a time
/// right after their final kicks, while their state is still in the cache.
/// Holds pointers into the world's body, sphere and pair-body arrays.
pub(crate) struct FirstHalf {
    kicks: Kicks,
    /// The step this first half begins.
    step: u64,
    scheme: crate::rotation::RotationScheme,
    /// Whether the scheme lets [`BodyLanes`] take spherical tops (a
    /// velocity-Verlet drift by the exact exponential).
    lanes: bool,
    /// The lanes' kind for asymmetric bodies under the scheme, if they take
    /// them (Richardson and NO_SQUISH).
    general_lanes: Option<LaneKind>,
    /// The vector instructions [`BodyLanes`] run with.
    simd: crate::par::simd::Simd,
    pos: SharedMut<DVec3>,
    pub(crate) vel: SharedMut<DVec3>,
    quat: SharedMut<glam::DQuat>,
    pub(crate) angm: SharedMut<DVec3>,
    pub(crate) omega: SharedMut<DVec3>,
    /// The spheres' state, to move with their bodies (None: left alone).
    sst: Option<SharedMut<crate::sphere::SphereState>>,
    first: SharedMut<u32>,
    tfirst: SharedMut<u32>,
    toff: SharedMut<DVec3>,
    limit2: f64,
    /// Half the skin, m (`limit2` is its square).
    half_skin: f64,
    /// The bodies' poses at the last build (centre of mass, orientation;
    /// world frame, m), from which the skin check measures; one per body
    /// whenever the spheres are moved (`sst`).
    xref_pose: SharedMut<(DVec3, glam::DQuat)>,
    /// Per template: its farthest sphere centre from the centre of mass, m.
    treach: SharedMut<f64>,
    /// The pair stage's packed copy of the bodies' state, when built for
    /// these bodies (else the rebuild that follows fills it).
    pair_body: Option<SharedMut<crate::neighbor::PairBody>>,
    /// The bodies' centres, velocities and angular velocities are read from
    /// and stored in the packed copy only, not the body arrays (inside a
    /// fused stretch of steps; see [`World::catch_up_bodies`]).
    lag: bool,
}

impl FirstHalf {
    /// The first half of step `step` of `w`'s bodies; with `spheres` (and
    /// a current sphere topology), their spheres move along and are checked
    /// against the skin.
    ///
    /// # Safety
    /// While the result is in use, `w`'s body, sphere, template and pair-body
    /// arrays are neither resized nor moved, and each body (with its spheres)
    /// is accessed by one thread at a time, through the result only.
    pub(crate) unsafe fn new(w: &mut World, step: u64, spheres: bool) -> Self {
        let n = w.bodies.len();
        let limit2 = skin::trigger_distance2(w.skin());
        let half_skin = 0.5 * w.skin();
        let poses = &mut w.neighbors.reference_pose;
        let spheres = spheres && poses.len() == n;
        let xref_pose = SharedMut::new(poses);
        let b = &mut w.bodies;
        FirstHalf {
            kicks: Kicks::new(
                w.config.dt,
                w.config.rotation,
                BodyProps::new(&mut w.scratch.props, b),
            ),
            step,
            scheme: w.config.rotation,
            lanes: w.config.rotation.kicks_torque()
                && w.config.rotation != crate::rotation::RotationScheme::RichardsonLiggghts
                && !lanes_off(),
            general_lanes: match w.config.rotation {
                crate::rotation::RotationScheme::Richardson => Some(LaneKind::Richardson),
                crate::rotation::RotationScheme::NoSquish => Some(LaneKind::NoSquish),
                _ => None,
            },
            simd: crate::par::simd::simd(),
            pos: SharedMut::new(&mut b.position),
            vel: SharedMut::new(&mut b.velocity),
            quat: SharedMut::new(&mut b.orientation),
            angm: SharedMut::new(&mut b.angular_momentum),
            omega: SharedMut::new(&mut b.angular_velocity),
            sst: spheres.then(|| SharedMut::new(&mut w.spheres.state)),
            first: SharedMut::new(&mut w.spheres.body_first),
            tfirst: SharedMut::new(&mut w.templates.first),
            toff: SharedMut::new(&mut w.templates.offset),
            limit2,
            half_skin,
            xref_pose,
            treach: SharedMut::new(&mut w.templates.centre_reach),
            pair_body: (w.neighbors.pairs.body.len() == n)
                .then(|| SharedMut::new(&mut w.neighbors.pairs.body)),
            lag: false,
        }
    }

    /// The same first half, keeping the bodies' centres, velocities and
    /// angular velocities in the packed copy only (see [`Self::lags`]),
    /// where that copy is built for these bodies.
    pub(crate) fn lagging(mut self) -> Self {
        self.lag = self.pair_body.is_some();
        self
    }

    /// Whether the body arrays' centres, velocities and angular velocities
    /// lag behind the packed copy once this first half is applied.
    pub(crate) fn lags(&self) -> bool {
        self.lag
    }

    /// Body `i`'s centre of mass (world frame, m) before its first half.
    ///
    /// # Safety
    /// As [`FirstHalf::apply`].
    #[inline(always)]
    unsafe fn centre(&self, i: usize) -> DVec3 {
        match &self.pair_body {
            Some(pb) if self.lag => (*pb.ptr(i)).position,
            _ => self.pos.read(i),
        }
    }

    /// Applies the first half step to body `i`, whose velocity `v`,
    /// angular momentum `l` and angular velocity `om` (world frame) are
    /// given as values and stored here, under the force `f` (N) and torque
    /// `m` (N m) of the step before (world frame). Returns true when one of
    /// its spheres moved more than half the skin since the last build.
    ///
    /// # Safety
    /// `i < n`, and body `i` is written by this thread only meanwhile.
    #[inline(always)]
    pub(crate) unsafe fn apply(
        &self,
        i: usize,
        v: &mut DVec3,
        l: &mut DVec3,
        om: &mut DVec3,
        f: DVec3,
        m: DVec3,
    ) -> bool {
        let dt = self.kicks.dt;
        let (mut x, mut q) = (self.centre(i), self.quat.read(i));
        // (all reads: i < n, every body array has n entries, template
        // indices are valid, and with spheres the sphere topology, first
        // spheres and reference positions, is current)
        let rot = if self.kicks.kick(self.step, i, v, l, f, m) {
            x += *v * dt;
            let inertia_i = self.kicks.props.inertia(i);
            if self.scheme == crate::rotation::RotationScheme::RichardsonLiggghts {
                // LIGGGHTS moves the spheres during the step with the ω of
                // the first half sub-step (see richardson_liggghts)
                let (qn, w_half) =
                    crate::rotation::richardson_liggghts::drift_omega(q, *l, inertia_i, dt);
                q = qn;
                *om = w_half;
                DMat3::from_quat(q)
            } else {
                if self.kicks.torque_kicks {
                    q = self.scheme.drift(q, *l, inertia_i, dt);
                } else {
                    q = self.kicks.zvw_full_step(i, q, l, m, inertia_i);
                }
                let rot = DMat3::from_quat(q);
                *om = omega_world_rot(&rot, *l, self.kicks.props.inverse_inertia(i));
                rot
            }
        } else {
            // before its start step: ballistic, forces ignored; a driven
            // body also turns at its prescribed world angular velocity
            x += *v * dt;
            if self.kicks.props.start(i) == crate::dof::DRIVEN {
                driven_turn(&mut q, l, *om, self.kicks.props.inertia(i), dt)
            } else {
                DMat3::from_quat(q)
            }
        };
        self.store(i, x, q, *v, *l, *om);
        match &self.sst {
            Some(sst) => self.move_spheres(i, x, q, &rot, sst),
            None => false,
        }
    }

    /// [`FirstHalf::apply`] to the bodies `b0..b0 + held.len()` (at most
    /// [`LANES`]), whose kicked state and load are `held`: the bodies of
    /// the common case (`super::first_half_lanes`) as lanes, the others one
    /// by one; `lanes` is scratch, kept between blocks. Returns true when
    /// one of their spheres moved more than half the skin since the last
    /// build.
    ///
    /// # Safety
    /// As [`FirstHalf::apply`], for each of these bodies.
    #[inline(always)]
    pub(crate) unsafe fn apply_block(
        &self,
        b0: usize,
        held: &mut [Held],
        lanes: &mut BodyLanes,
    ) -> bool {
        debug_assert!(held.len() <= LANES);
        let mut stale = false;
        let mut take = [false; LANES];
        if let (true, Some(_)) = (self.lanes, &self.sst) {
            // the lanes take the block's spherical tops or, under the
            // Richardson and NO_SQUISH schemes, its asymmetric bodies:
            // whichever are more, and asymmetric ones only from GENERAL_MIN
            // on (the lanes cost eight bodies' work however few they hold)
            let (mut top, mut asym) = ([false; LANES], [false; LANES]);
            // each body's principal moments and, for an asymmetric one,
            // their inverses, read once for the choice and the lanes
            let mut moments = [(DVec3::ZERO, DVec3::ZERO); LANES];
            for k in 0..held.len() {
                let i = b0 + k;
                if self.kicks.lanes_take(self.step, i) {
                    let inertia = self.kicks.props.inertia(i);
                    moments[k].0 = inertia;
                    top[k] = inertia.x == inertia.y && inertia.y == inertia.z && inertia.x > 0.0;
                    if !top[k] && self.general_lanes.is_some() {
                        // (ω's formula goes by the inverse moments, the
                        // drift's by the moments: a body is general by both;
                        // the lanes' NO_SQUISH has no branch for a zero
                        // moment)
                        let inv = self.kicks.props.inverse_inertia(i);
                        moments[k].1 = inv;
                        asym[k] =
                            !(inv.x == inv.y && inv.y == inv.z) && inertia.min_element() > 0.0;
                    }
                }
            }
            let count = |t: &[bool; LANES]| t.iter().filter(|&&t| t).count();
            let general = count(&asym) > count(&top) && count(&asym) >= GENERAL_MIN;
            lanes.kind = match self.general_lanes {
                Some(kind) if general => kind,
                _ => LaneKind::Top,
            };
            take = if general { asym } else { top };
            for (k, h) in held.iter().enumerate() {
                let i = b0 + k;
                if take[k] {
                    let (inertia, inv) = moments[k];
                    let kick = self.kicks.half_kick(i);
                    let reach = self.treach.read(self.kicks.props.template(i));
                    lanes.set(
                        k,
                        (self.centre(i), h.v, h.l, self.quat.read(i)),
                        (h.f, h.m),
                        (kick, inertia.x),
                        self.xref_pose.read(i),
                        reach,
                    );
                    if general {
                        lanes.set_moments(k, inertia, inv);
                    }
                }
            }
            if take.contains(&true) {
                // a lane without a body here computes a body at rest
                for k in (0..LANES).filter(|&k| !take[k]) {
                    lanes.set_idle(k);
                }
                lanes.run(self.kicks.dt, self.half_skin, self.simd);
            }
        }
        if let Some(sst) = &self.sst {
            if held.len() == LANES && self.place_block(b0, &take, lanes, sst) {
                return false;
            }
        }
        for (k, h) in held.iter_mut().enumerate() {
            let i = b0 + k;
            match &self.sst {
                Some(sst) if take[k] && lanes.holds[k] => {
                    let (x, v, l, q, om, rot) = lanes.get(k);
                    self.store(i, x, q, v, l, om);
                    stale |= self.place_spheres(i, x, &rot, sst, lanes.within[k]);
                }
                _ => stale |= self.apply(i, &mut h.v, &mut h.l, &mut h.om, h.f, h.m),
            }
        }
        stale
    }

    /// The end of [`FirstHalf::apply_block`] for a whole block of bodies
    /// `b0..b0 + LANES` that the lanes took, that hold and that surely moved
    /// no sphere beyond half the skin, all of one template of at most
    /// [`super::first_half_lanes::SLOTS`] spheres: their state is stored and
    /// their spheres placed by the lanes. False, having done nothing, for
    /// any other block.
    ///
    /// # Safety
    /// As [`FirstHalf::apply_block`].
    #[inline(always)]
    unsafe fn place_block(
        &self,
        b0: usize,
        take: &[bool; LANES],
        lanes: &mut BodyLanes,
        sst: &SharedMut<crate::sphere::SphereState>,
    ) -> bool {
        let t = self.kicks.props.template(b0);
        let whole = (0..LANES).all(|k| {
            take[k] && lanes.holds[k] && lanes.within[k] && self.kicks.props.template(b0 + k) == t
        });
        let (s0, s1) = (
            self.first.read(b0) as usize,
            self.first.read(b0 + 1) as usize,
        );
        let n = s1 - s0;
        if !whole || n > super::first_half_lanes::SLOTS {
            return false;
        }
        let o0 = self.tfirst.read(t) as usize;
        debug_assert!(o0 + n <= self.toff.len() && s0 + LANES * n <= sst.len());
        let offsets = std::slice::from_raw_parts(self.toff.as_ptr().add(o0), n);
        lanes.place(offsets, self.simd);
        for k in 0..LANES {
            let i = b0 + k;
            let (x, v, l, q, om, _) = lanes.get(k);
            self.store(i, x, q, v, l, om);
            // the bodies' spheres follow each other in storage, n each
            debug_assert_eq!(self.first.read(i) as usize, s0 + k * n);
            let first = sst.ptr(s0 + k * n);
            for (s, slot) in lanes.spheres.iter().enumerate().take(n) {
                (*first.add(s)).position = get3(slot, k);
            }
        }
        true
    }

    /// Stores body `i`'s new centre `x`, orientation `q`, velocity `v`,
    /// angular momentum `l` and angular velocity `om` (world frame), also in
    /// the pair stage's copy (whose column sum is not touched); lagging,
    /// `x`, `v` and `om` in that copy only.
    ///
    /// # Safety
    /// As [`FirstHalf::apply`].
    #[inline(always)]
    unsafe fn store(&self, i: usize, x: DVec3, q: glam::DQuat, v: DVec3, l: DVec3, om: DVec3) {
        *self.quat.get(i) = q;
        *self.angm.get(i) = l;
        if !self.lag {
            *self.pos.get(i) = x;
            *self.vel.get(i) = v;
            *self.omega.get(i) = om;
        }
        if let Some(pb) = &self.pair_body {
            let pb = pb.ptr(i);
            (*pb).position = x;
            (*pb).velocity = v;
            (*pb).angular_velocity = om;
        }
    }

    /// Places body `i`'s spheres at its new pose (centre `x`, orientation
    /// `q`, its rotation matrix `rot`) and tells whether one moved more than
    /// half the skin since the last build.
    ///
    /// The body's bound ([`skin::body_displacement_bound`]) settles that for
    /// most bodies from their two poses; the spheres of a body near the
    /// limit take the exact test against their positions at the build
    /// (from the body's reference pose, not stored), so a rebuild comes at
    /// the same step as with the exact test alone.
    ///
    /// The spheres and offsets are taken as local slices first: written
    /// through `sst`'s pointer, a store could alias the pointers and the
    /// skin limit held in `self`, which the loop would then reload for every
    /// sphere.
    ///
    /// # Safety
    /// As [`FirstHalf::apply`]; the sphere topology is current.
    #[inline(always)]
    unsafe fn move_spheres(
        &self,
        i: usize,
        x: DVec3,
        q: glam::DQuat,
        rot: &DMat3,
        sst: &SharedMut<crate::sphere::SphereState>,
    ) -> bool {
        let (x0, q0) = self.xref_pose.read(i);
        let reach = self.treach.read(self.kicks.props.template(i));
        let bound = skin::body_displacement_bound(x, q, x0, q0, reach);
        let within = skin::surely_within(bound, self.half_skin, x.abs().max_element() + reach);
        self.place_spheres(i, x, rot, sst, within)
    }

    /// [`FirstHalf::move_spheres`] once the bound is settled: `within`,
    /// the body surely moved no sphere beyond half the skin
    /// ([`skin::surely_within`]); else its spheres take the exact test.
    ///
    /// # Safety
    /// As [`FirstHalf::move_spheres`].
    #[inline(always)]
    unsafe fn place_spheres(
        &self,
        i: usize,
        x: DVec3,
        rot: &DMat3,
        sst: &SharedMut<crate::sphere::SphereState>,
        within: bool,
    ) -> bool {
        let t = self.kicks.props.template(i);
        let o0 = self.tfirst.read(t) as usize;
        let (s0, s1) = (self.first.read(i) as usize, self.first.read(i + 1) as usize);
        let n = s1 - s0;
        debug_assert!(s1 <= sst.len() && i < self.xref_pose.len() && o0 + n <= self.toff.len());
        let state = std::slice::from_raw_parts_mut(sst.ptr(s0), n);
        let offset = std::slice::from_raw_parts(self.toff.as_ptr().add(o0), n);
        let limit2 = self.limit2;
        if within {
            for (st, &off) in state.iter_mut().zip(offset) {
                st.position = sphere_position(x, rot, off);
            }
            return false;
        }
        // near the limit: each sphere against its position at the build,
        // computed from the build's pose as the build computed it
        let (x0, q0) = self.xref_pose.read(i);
        let rot0 = DMat3::from_quat(q0);
        let mut stale = false;
        for (st, &off) in state.iter_mut().zip(offset) {
            let px = sphere_position(x, rot, off);
            st.position = px;
            stale |= skin::moved_too_far(px, sphere_position(x0, &rot0, off), limit2);
        }
        stale
    }
}

/// Turns a driven body (see [`crate::dof`]) over `dt` at its constant world
/// angular velocity `om` (rad/s): `q ← exp(ω dt) q`, and sets its world
/// angular momentum `l = R I Rᵀ ω` (kg m²/s) to match; `inertia` holds the
/// principal moments (kg m²). A body at rest (ω = 0) keeps its orientation
/// bit for bit. Returns the new rotation matrix (body → world).
#[inline(never)]
fn driven_turn(q: &mut glam::DQuat, l: &mut DVec3, om: DVec3, inertia: DVec3, dt: f64) -> DMat3 {
    if om != DVec3::ZERO {
        *q = crate::math::renormalize(crate::math::quat_from_rotation_vector(om * dt) * *q);
    }
    let rot = DMat3::from_quat(*q);
    *l = rot * (inertia * (rot.transpose() * om));
    rot
}
