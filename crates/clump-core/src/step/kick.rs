//! The half kicks of velocity Verlet (docs/theory.md T-15, LIGGGHTS
//! `fix multisphere`): `v += F dt/(2 m f_a)`, `L += M dt/(2 f_a)` per
//! world axis where the body's flags allow, `f_a` the added-mass factor.
//! [`HalfKick`] is the formula; [`FinalKick`] the step's second half kick,
//! which the gather applies to each body once its load is summed; the
//! first half's kick is in [`super::first_half`].

use super::body_props::BodyProps;
use crate::par::shared::SharedMut;
use crate::rotation::omega_world_inv;
use crate::world::props::PropsTable;
use glam::DVec3;

/// A body's kicked state and its load, held from its gather to its first
/// half; all world frame.
#[derive(Clone, Copy, Default)]
pub(crate) struct Held {
    /// Velocity of the centre of mass, m/s.
    pub v: DVec3,
    /// Angular momentum, kg m²/s.
    pub l: DVec3,
    /// Angular velocity, rad/s.
    pub om: DVec3,
    /// Force, N.
    pub f: DVec3,
    /// Torque about the centre of mass, N m.
    pub m: DVec3,
}

/// The second half kick, `v += F dt/(2 m')`, `L += M dt/(2 f_a)`, ω from L
/// (world frame), of one body at a time: the force gather
/// ([`super::force::gather`]) applies it to each body as soon as that body's
/// force and torque are summed, in the same pass (one sweep over the bodies
/// and one parallel loop fewer per step). A body before its start step is
/// left alone.
pub(crate) struct FinalKick {
    kicks: Kicks,
    step: u64,
    quat: SharedMut<glam::DQuat>,
}

impl FinalKick {
    /// The kick of step `step` of the bodies `b`.
    ///
    /// # Safety
    /// As [`BodyProps::new`]; the orientations are written by no other path
    /// while the result is in use.
    pub(crate) unsafe fn new(
        dt: f64,
        step: u64,
        rotation: crate::rotation::RotationScheme,
        props: &mut PropsTable,
        b: &mut crate::body::Bodies,
    ) -> Self {
        FinalKick {
            kicks: Kicks::new(dt, rotation, BodyProps::new(props, b)),
            step,
            quat: SharedMut::new(&mut b.orientation),
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
        if self.kicks.kick(self.step, i, v, l, f, m) {
            *om = omega_world_inv(self.quat.read(i), *l, self.kicks.props.inverse_inertia(i));
        }
    }
}

/// What a half kick of a body reads (pointers into the world's body and
/// template arrays, which it never writes).
pub(super) struct Kicks {
    pub(super) dt: f64,
    /// Velocity-Verlet half kicks of `L` (false: the rotation scheme
    /// advances `L` over the whole step, see [`Kicks::zvw_full_step`]).
    pub(super) torque_kicks: bool,
    /// The bodies' mass properties and degrees of freedom.
    pub(super) props: BodyProps,
}

impl Kicks {
    pub(super) fn new(
        dt: f64,
        rotation: crate::rotation::RotationScheme,
        props: BodyProps,
    ) -> Self {
        Kicks {
            dt,
            torque_kicks: rotation.kicks_torque(),
            props,
        }
    }

    /// Half kick of body `i` in step `step` (velocity `v`, angular momentum
    /// `l`, world frame, under force `f` and torque `m`); false, leaving
    /// them alone, for a body before its start step.
    ///
    /// # Safety
    /// `i` is a body index.
    #[inline(always)]
    pub(super) unsafe fn kick(
        &self,
        step: u64,
        i: usize,
        v: &mut DVec3,
        l: &mut DVec3,
        f: DVec3,
        m: DVec3,
    ) -> bool {
        let p = &self.props;
        if !p.started(step, i) {
            return false;
        }
        let mut kick = self.half_kick(i);
        if !self.torque_kicks {
            kick.dtt = 0.0;
        }
        let (ff, tf) = p.flags(i);
        kick.apply(v, l, f, m, ff, tf);
        true
    }

    /// Body `i`'s half kick over `dt/2`: its template row's quotients,
    /// else computed from its own mass.
    ///
    /// # Safety
    /// `i` is a body index.
    #[inline(always)]
    pub(super) unsafe fn half_kick(&self, i: usize) -> HalfKick {
        let p = &self.props;
        match p.row_kick(i) {
            Some((dtfm, dtt)) => HalfKick::from_quotients(dtfm, dtt),
            None => HalfKick::new(self.dt, p.own_mass(i), p.factor(i)),
        }
    }

    /// Whether body `i` takes its first half of step `step` in
    /// [`BodyLanes`]: started, and free on every axis.
    ///
    /// # Safety
    /// `i` is a body index.
    #[inline(always)]
    pub(super) unsafe fn lanes_take(&self, step: u64, i: usize) -> bool {
        let p = &self.props;
        p.started(step, i) && p.flags(i) == ([true; 3], [true; 3])
    }

    /// The rotation of body `i` over the whole step by Zhao & van Wachem
    /// (2013) as Zhao & van Wachem (2013) give it (docs/theory.md T-20) (see
    /// [`crate::rotation::zhao_van_wachem`]): the torque `m` (N m, world
    /// frame) of the force evaluation at the start of the step, divided by
    /// the added-mass factor, is held constant in the world frame over the
    /// step and taken into the body frame with `q` (= q_0) and with the
    /// predicted `q_½`. Returns `q_1`; sets the world angular momentum `l`
    /// to `q_1 I ω_b,1`, keeping the components whose torque flag is off.
    ///
    /// # Safety
    /// `i` is a body index.
    #[inline(never)]
    pub(super) unsafe fn zvw_full_step(
        &self,
        i: usize,
        q: glam::DQuat,
        l: &mut DVec3,
        m: DVec3,
        inertia: DVec3,
    ) -> glam::DQuat {
        let fa = self.props.factor(i);
        let tm = glam::BVec3::from(self.props.flags(i).1);
        let torque = DVec3::select(tm, m / fa, DVec3::ZERO);
        let mut st = crate::rotation::RotState { q, l_world: *l };
        crate::rotation::zhao_van_wachem::step(&mut st, inertia, &mut |_| torque, self.dt);
        *l = DVec3::select(tm, st.l_world, *l);
        st.q
    }
}

/// A half kick of one body over `dt/2`: `v += F dt/(2 m f_a)`,
/// `L += M dt/(2 f_a)` (world frame), per axis only where the flag allows.
#[derive(Debug, Clone, Copy)]
pub(crate) struct HalfKick {
    /// `dt/(2 m f_a)`, s/kg.
    dtfm: f64,
    /// `dt/(2 f_a)`, s.
    dtt: f64,
}

impl HalfKick {
    #[inline(always)]
    pub(crate) fn new(dt: f64, mass: f64, fa: f64) -> Self {
        let half = 0.5 * dt;
        HalfKick {
            dtfm: half / (mass * fa),
            // without added mass (fa = 1) the quotient is `half` exactly
            dtt: if fa == 1.0 { half } else { half / fa },
        }
    }

    /// The kick of the quotients `dt/(2 m f_a)` and `dt/(2 f_a)`
    /// ([`Self::quotients`]).
    #[inline(always)]
    pub(crate) fn from_quotients(dtfm: f64, dtt: f64) -> Self {
        HalfKick { dtfm, dtt }
    }

    /// `dt/(2 m f_a)` (s/kg) and `dt/(2 f_a)` (s).
    #[inline(always)]
    pub(crate) fn quotients(&self) -> (f64, f64) {
        (self.dtfm, self.dtt)
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
            self.apply_free(v, l, force, torque);
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

    /// [`HalfKick::apply`] to a body free on every axis.
    #[inline(always)]
    pub(crate) fn apply_free(
        &self,
        v: &mut glam::DVec3,
        l: &mut glam::DVec3,
        force: glam::DVec3,
        torque: glam::DVec3,
    ) {
        *v += self.dtfm * force;
        *l += self.dtt * torque;
    }
}
