//! The first half step of up to eight bodies at once, one lane per body
//! (structure of arrays), for the bodies of the common case: started, free
//! on every axis, under a velocity-Verlet scheme, and either
//! - spherical tops (three equal principal moments: single spheres, regular
//!   tetrahedra, cubes of spheres), whose free rotation every such scheme
//!   takes as the exact exponential
//!   ([`crate::rotation::RotationScheme::drift`]), or
//! - asymmetric bodies (stones, any irregular clump) under the Richardson
//!   or the NO_SQUISH scheme ([`crate::rotation::richardson`],
//!   [`crate::rotation::no_squish`]), whose drift, a chain of rotations and
//!   exponentials, is most of such a body's first half (a block's lanes are
//!   all of one kind: [`LaneKind`]).
//!
//! A body's first half (`first_half::FirstHalf::apply`: half kick, drift,
//! rotation, ω, skin bound, sphere centres) is one long chain of dependent
//! operations, 43 ns a body on the settled tetra bed (10.8 ns a
//! sphere-step, measured as a pass of its own); the processor overlaps
//! little of one body's chain with the next's. Run as eight lanes of a loop
//! with no branch, the compiler turns the chain into vector instructions, so
//! eight bodies take about one body's latency. A block of one template whose
//! bodies all hold also has its sphere centres placed by the lanes, slot by
//! slot ([`BodyLanes::place`]). The loops are compiled for AVX-512 and AVX2
//! besides the baseline, and the widest the processor has runs
//! (`crate::par::simd`).
//!
//! Same bits: a lane runs the scalar path's own functions (the half kick,
//! [`crate::rotation::spherical_top_drift_small`],
//! [`crate::rotation::richardson::drift_small`] or
//! [`crate::rotation::no_squish::drift_small`], `DMat3::from_quat`, the
//! skin bound), the same IEEE operations in the same order, never contracted
//! into FMA. The branches of the scalar path become flags: a lane whose
//! rotation is too large for the series, or whose product is too far from
//! unit length for the Newton step, is discarded and its body takes the
//! scalar path; a body whose bound comes near half the skin takes the exact
//! per-sphere test.

use super::kick::HalfKick;
use super::kinematics::sphere_position;
use crate::neighbor::skin;
use crate::par::simd::{get3, set3, Simd};
use glam::{DMat3, DQuat, DVec3};

/// Bodies per block.
pub(crate) const LANES: usize = 8;

/// Most spheres per body whose centres the lanes place
/// ([`BodyLanes::place`]); bodies with more place their own.
pub(crate) const SLOTS: usize = 8;

/// Tests only: while set, every body takes the scalar path. The two paths
/// give the same bits, so this changes no result of a test that runs
/// meanwhile.
#[cfg(test)]
pub(crate) static SCALAR_ONLY: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

/// The bodies a block's lanes hold, and the drift they take.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum LaneKind {
    /// Spherical tops: the exact exponential of `L dt / I`.
    Top,
    /// Asymmetric bodies under the Richardson scheme.
    Richardson,
    /// Asymmetric bodies under the NO_SQUISH scheme.
    NoSquish,
}

type Row = [f64; LANES];
/// A 3-vector per lane (x, y and z rows), world frame.
type Rows3 = [Row; 3];
/// A quaternion per lane (x, y, z and w rows).
type Rows4 = [Row; 4];

/// The state of a block's bodies, lane `k` = body `k` of the block; world
/// frame, SI units. The kinematic fields (centre, velocity, angular
/// momentum, orientation) are inputs, and the outputs after
/// [`BodyLanes::run`].
#[derive(Clone, Copy)]
pub(crate) struct BodyLanes {
    /// Centre of mass, m.
    pub x: Rows3,
    /// Velocity of the centre of mass, m/s.
    pub v: Rows3,
    /// Angular momentum, kg m²/s.
    pub l: Rows3,
    /// Orientation, body → world.
    pub q: Rows4,
    /// Force of the step before, N (input only).
    pub f: Rows3,
    /// Torque of the step before about the centre of mass, N m (input only).
    pub m: Rows3,
    /// The half kick's `dt/(2 m f_a)`, s/kg ([`HalfKick`]).
    pub dtfm: Row,
    /// The half kick's `dt/(2 f_a)`, s.
    pub dtt: Row,
    /// The principal moment (all three equal), kg m²; for spherical tops.
    pub inertia: Row,
    /// The principal moments (body frame), kg m²; for asymmetric bodies.
    pub moments: Rows3,
    /// Their inverses, 1/(kg m²).
    pub inv_inertia: Rows3,
    /// What the lanes hold.
    pub kind: LaneKind,
    /// Centre of mass at the last neighbour build, m: with `q_ref`, the
    /// skin check's reference pose.
    pub x_ref: Rows3,
    /// Orientation (body → world) at the last neighbour build.
    pub q_ref: Rows4,
    /// Farthest sphere centre from the centre of mass, m.
    pub reach: Row,
    /// Output: angular velocity, rad/s.
    pub om: Rows3,
    /// Output: rotation matrix (body → world), columns x, y, z.
    pub rot: [Rows3; 3],
    /// Output: whether the lane holds (else its body takes the scalar path).
    pub holds: [bool; LANES],
    /// Output: whether the body surely moved no sphere beyond half the skin
    /// ([`skin::surely_within`]; else its spheres take the exact test).
    pub within: [bool; LANES],
    /// Output of [`BodyLanes::place`]: sphere `s` of each body, m.
    pub spheres: [Rows3; SLOTS],
}

/// Lane `k` of a quaternion row set.
#[inline(always)]
fn get4(r: &Rows4, k: usize) -> DQuat {
    DQuat::from_xyzw(r[0][k], r[1][k], r[2][k], r[3][k])
}

/// Sets lane `k` of a quaternion row set.
#[inline(always)]
fn set4(r: &mut Rows4, k: usize, q: DQuat) {
    r[0][k] = q.x;
    r[1][k] = q.y;
    r[2][k] = q.z;
    r[3][k] = q.w;
}

impl BodyLanes {
    /// Every lane a body at rest at the origin with unit mass and moment
    /// ([`BodyLanes::set_idle`]).
    pub(crate) fn idle() -> Self {
        let zero = [0.0; LANES];
        let mut b = BodyLanes {
            x: [zero; 3],
            v: [zero; 3],
            l: [zero; 3],
            q: [zero; 4],
            f: [zero; 3],
            m: [zero; 3],
            dtfm: zero,
            dtt: zero,
            inertia: zero,
            moments: [zero; 3],
            inv_inertia: [zero; 3],
            kind: LaneKind::Top,
            x_ref: [zero; 3],
            q_ref: [zero; 4],
            reach: zero,
            om: [zero; 3],
            rot: [[zero; 3]; 3],
            holds: [false; LANES],
            within: [false; LANES],
            spheres: [[zero; 3]; SLOTS],
        };
        for k in 0..LANES {
            b.set_idle(k);
        }
        b
    }

    /// Makes lane `k` a body at rest at the origin with unit mass and
    /// moment, for a lane without a body: its results are not used, and
    /// such inputs keep them ordinary numbers.
    #[inline(always)]
    pub(crate) fn set_idle(&mut self, k: usize) {
        let (zero, rest) = (DVec3::ZERO, DQuat::IDENTITY);
        self.set(
            k,
            (zero, zero, zero, rest),
            (zero, zero),
            (HalfKick::new(1.0, 1.0, 1.0), 1.0),
            (zero, rest),
            0.0,
        );
        self.set_moments(k, DVec3::ONE, DVec3::ONE);
    }

    /// Sets lane `k`'s inputs (world frame): centre `x`, velocity `v`,
    /// angular momentum `l`, orientation `q`, force `f` and torque `m` of
    /// the step before, half kick and principal moment, the pose at the
    /// last build and the body's reach.
    #[inline(always)]
    pub(crate) fn set(
        &mut self,
        k: usize,
        (x, v, l, q): (DVec3, DVec3, DVec3, DQuat),
        (f, m): (DVec3, DVec3),
        (kick, inertia): (HalfKick, f64),
        (x_ref, q_ref): (DVec3, DQuat),
        reach: f64,
    ) {
        set3(&mut self.x, k, x);
        set3(&mut self.v, k, v);
        set3(&mut self.l, k, l);
        set4(&mut self.q, k, q);
        set3(&mut self.f, k, f);
        set3(&mut self.m, k, m);
        (self.dtfm[k], self.dtt[k]) = kick.quotients();
        self.inertia[k] = inertia;
        set3(&mut self.x_ref, k, x_ref);
        set4(&mut self.q_ref, k, q_ref);
        self.reach[k] = reach;
    }

    /// Lane `k`'s results: centre, velocity, angular momentum, orientation,
    /// angular velocity and rotation matrix (world frame).
    #[inline(always)]
    pub(crate) fn get(&self, k: usize) -> (DVec3, DVec3, DVec3, DQuat, DVec3, DMat3) {
        let rot = DMat3::from_cols(
            get3(&self.rot[0], k),
            get3(&self.rot[1], k),
            get3(&self.rot[2], k),
        );
        (
            get3(&self.x, k),
            get3(&self.v, k),
            get3(&self.l, k),
            get4(&self.q, k),
            get3(&self.om, k),
            rot,
        )
    }

    /// The first half step over `dt` (s) of every lane, `half_skin` (m)
    /// the skin check's limit, compiled for `simd` (detected on this
    /// processor by [`crate::par::simd::simd`]).
    #[inline(always)]
    pub(crate) fn run(&mut self, dt: f64, half_skin: f64, simd: Simd) {
        #[cfg(target_arch = "x86_64")]
        match simd {
            // SAFETY: `simd` was detected on this processor.
            Simd::Avx512 => return unsafe { run_avx512(self, dt, half_skin) },
            Simd::Avx2 => return unsafe { run_avx2(self, dt, half_skin) },
            Simd::Baseline => {}
        }
        let _ = simd;
        run_lanes(self, dt, half_skin);
    }

    /// Places the spheres of every lane's body, all of the same template
    /// with the body-frame offsets `offsets` (m, at most [`SLOTS`]), at the
    /// lanes' new poses ([`BodyLanes::run`]): sphere `s` of lane `k` at
    /// `spheres[s]`, lane `k`. The formula of every stage
    /// ([`sphere_position`]), vectorised over the lanes.
    #[inline(always)]
    pub(crate) fn place(&mut self, offsets: &[DVec3], simd: Simd) {
        debug_assert!(offsets.len() <= SLOTS);
        #[cfg(target_arch = "x86_64")]
        match simd {
            // SAFETY: `simd` was detected on this processor.
            Simd::Avx512 => return unsafe { place_avx512(self, offsets) },
            Simd::Avx2 => return unsafe { place_avx2(self, offsets) },
            Simd::Baseline => {}
        }
        let _ = simd;
        place_lanes(self, offsets);
    }

    /// Sets lane `k`'s principal moments `inertia` (body frame, kg m²) and
    /// their inverses `inv` (1/(kg m²)), for asymmetric bodies (after
    /// [`BodyLanes::set`]).
    #[inline(always)]
    pub(crate) fn set_moments(&mut self, k: usize, inertia: DVec3, inv: DVec3) {
        set3(&mut self.moments, k, inertia);
        set3(&mut self.inv_inertia, k, inv);
    }

    /// Lane `k`: the half kick, the drift of the centre and of the
    /// orientation, ω from L, the rotation matrix, and the skin bound, as
    /// `first_half::FirstHalf::apply` computes them for a free, started
    /// body of `kind`.
    #[inline(always)]
    fn lane(&mut self, k: usize, dt: f64, half_skin: f64, kind: LaneKind) {
        let (mut v, mut l) = (get3(&self.v, k), get3(&self.l, k));
        let kick = HalfKick::from_quotients(self.dtfm[k], self.dtt[k]);
        kick.apply_free(&mut v, &mut l, get3(&self.f, k), get3(&self.m, k));
        let x = get3(&self.x, k) + v * dt;
        let inertia = self.inertia[k];
        let inv = get3(&self.inv_inertia, k);
        let q0 = get4(&self.q, k);
        let (q, holds) = match kind {
            LaneKind::Top => crate::rotation::spherical_top_drift_small(q0, l, inertia, dt),
            LaneKind::Richardson => crate::rotation::richardson::drift_small(q0, l, inv, dt),
            LaneKind::NoSquish => {
                crate::rotation::no_squish::drift_small(q0, l, get3(&self.moments, k), dt)
            }
        };
        let rot = DMat3::from_quat(q);
        let om = if kind == LaneKind::Top {
            // ω = R I⁻¹ Rᵀ L = L / I for a spherical top (rotation::omega_world_rot)
            l * (1.0 / inertia)
        } else {
            crate::rotation::body_dynamics::omega_world_rot_general(&rot, l, inv)
        };
        let reach = self.reach[k];
        let bound =
            skin::body_displacement_bound(x, q, get3(&self.x_ref, k), get4(&self.q_ref, k), reach);
        self.within[k] = skin::surely_within(bound, half_skin, x.abs().max_element() + reach);
        self.holds[k] = holds;
        set3(&mut self.x, k, x);
        set3(&mut self.v, k, v);
        set3(&mut self.l, k, l);
        set4(&mut self.q, k, q);
        set3(&mut self.om, k, om);
        set3(&mut self.rot[0], k, rot.x_axis);
        set3(&mut self.rot[1], k, rot.y_axis);
        set3(&mut self.rot[2], k, rot.z_axis);
    }
}

/// The spheres of every lane of `b` ([`BodyLanes::place`]), each slot in
/// a loop the compiler vectorises.
#[inline(always)]
fn place_lanes(b: &mut BodyLanes, offsets: &[DVec3]) {
    for (s, &off) in offsets.iter().enumerate().take(SLOTS) {
        for k in 0..LANES {
            let rot = DMat3::from_cols(get3(&b.rot[0], k), get3(&b.rot[1], k), get3(&b.rot[2], k));
            let p = sphere_position(get3(&b.x, k), &rot, off);
            set3(&mut b.spheres[s], k, p);
        }
    }
}

/// [`place_lanes`] compiled for AVX-512.
///
/// # Safety
/// The processor supports AVX-512 F, VL and DQ.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl,avx512dq")]
unsafe fn place_avx512(b: &mut BodyLanes, offsets: &[DVec3]) {
    place_lanes(b, offsets)
}

/// [`place_lanes`] compiled for AVX2.
///
/// # Safety
/// The processor supports AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn place_avx2(b: &mut BodyLanes, offsets: &[DVec3]) {
    place_lanes(b, offsets)
}

/// Every lane of `b`, in a loop the compiler vectorises (one loop per
/// kind of body, with no branch inside).
#[inline(always)]
fn run_lanes(b: &mut BodyLanes, dt: f64, half_skin: f64) {
    match b.kind {
        LaneKind::Top => {
            for k in 0..LANES {
                b.lane(k, dt, half_skin, LaneKind::Top);
            }
        }
        LaneKind::Richardson => {
            for k in 0..LANES {
                b.lane(k, dt, half_skin, LaneKind::Richardson);
            }
        }
        LaneKind::NoSquish => {
            for k in 0..LANES {
                b.lane(k, dt, half_skin, LaneKind::NoSquish);
            }
        }
    }
}

/// [`run_lanes`] compiled for AVX-512 (8 doubles per vector).
///
/// # Safety
/// The processor supports AVX-512 F, VL and DQ.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512vl,avx512dq")]
unsafe fn run_avx512(b: &mut BodyLanes, dt: f64, half_skin: f64) {
    run_lanes(b, dt, half_skin)
}

/// [`run_lanes`] compiled for AVX2 (4 doubles per vector).
///
/// # Safety
/// The processor supports AVX2.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn run_avx2(b: &mut BodyLanes, dt: f64, half_skin: f64) {
    run_lanes(b, dt, half_skin)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rotation::{omega_world, RotationScheme};
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn bits3(v: DVec3) -> [u64; 3] {
        v.to_array().map(f64::to_bits)
    }

    /// Every lane of every vector level the processor has is the scalar
    /// first half of a free spherical top bit for bit: the velocity-Verlet
    /// half kick, the drift of the centre, the rotation scheme's drift (its
    /// public entry, with its branches), ω from L, the rotation matrix, the
    /// skin bound and the sphere centres of 1 to 8 slots. A lane whose
    /// rotation is beyond the series (half angle ≥ 0.01) does not hold;
    /// every other lane does.
    #[test]
    fn lanes_are_the_scalar_first_half_bit_for_bit() {
        lanes_against_the_scalar_path(LaneKind::Top);
    }

    /// The same for asymmetric bodies (three different principal moments)
    /// under the Richardson scheme.
    #[test]
    fn richardson_lanes_are_the_scalar_first_half_bit_for_bit() {
        lanes_against_the_scalar_path(LaneKind::Richardson);
    }

    /// The same for asymmetric bodies under the NO_SQUISH scheme.
    #[test]
    fn no_squish_lanes_are_the_scalar_first_half_bit_for_bit() {
        lanes_against_the_scalar_path(LaneKind::NoSquish);
    }

    /// The squared half angle a lane's series is judged by: the series
    /// holds below a half angle of 0.01 (h² < 1e-4): a spherical top turns
    /// by ω dt at once, a body under Richardson by ω dt/2 twice, ω changing
    /// a little between the two; NO_SQUISH turns about its principal axes
    /// y and z by ω_k dt/2 and about x by ω_x dt, and its series holds
    /// below a half angle of 0.02 (the angles scaled here to compare with
    /// 1e-4 alike).
    fn series_h2(kind: LaneKind, q: DQuat, l1: DVec3, i3: DVec3, dt: f64) -> f64 {
        match kind {
            LaneKind::Top => 0.25 * (l1 * (dt / i3.x)).length_squared(),
            LaneKind::Richardson => 0.25 * (omega_world(q, l1, i3) * (0.5 * dt)).length_squared(),
            LaneKind::NoSquish => {
                let w = crate::rotation::omega_body(q, l1, i3).abs();
                let half = [0.5 * w.x * dt, 0.25 * w.y * dt, 0.25 * w.z * dt]
                    .into_iter()
                    .fold(0.0, f64::max);
                (half / 0.02).powi(2) * 1e-4
            }
        }
    }

    /// The lanes of `kind` against the scalar path, for the tests above.
    fn lanes_against_the_scalar_path(kind: LaneKind) {
        let general = kind != LaneKind::Top;
        let scheme = match kind {
            LaneKind::NoSquish => RotationScheme::NoSquish,
            _ => RotationScheme::Richardson,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let dt = 1e-5;
        let half_skin = 2e-5;
        let mut levels = vec![Simd::Baseline];
        let detected = crate::par::simd::simd();
        if detected != Simd::Baseline {
            levels.push(Simd::Avx2);
        }
        if detected == Simd::Avx512 {
            levels.push(Simd::Avx512);
        }
        let rnd3 = |rng: &mut ChaCha8Rng, s: f64| {
            DVec3::new(
                rng.gen_range(-s..s),
                rng.gen_range(-s..s),
                rng.gen_range(-s..s),
            )
        };
        let (mut held, mut fast, mut near) = (0, 0, 0);
        for round in 0..400 {
            let mut b = BodyLanes::idle();
            b.kind = kind;
            let mut inputs = Vec::new();
            for k in 0..LANES {
                let x = rnd3(&mut rng, 0.1);
                let q = DQuat::from_scaled_axis(rnd3(&mut rng, 3.0)).normalize();
                let inertia = rng.gen_range(1e-12..1e-6);
                let i3 = if general {
                    // the moments of a stone, up to 2.5 times apart
                    DVec3::new(
                        inertia,
                        inertia * rng.gen_range(1.05..1.6),
                        inertia * rng.gen_range(1.7..2.5),
                    )
                } else {
                    DVec3::splat(inertia)
                };
                // ω up to 100 rad/s, a few lanes far beyond the series
                let spin = if (round + k) % 13 == 0 { 3e4 } else { 100.0 };
                let l = rnd3(&mut rng, spin) * i3;
                let v = rnd3(&mut rng, 1.0);
                let mass = rng.gen_range(1e-6..1e-2);
                let f = rnd3(&mut rng, 1.0) * mass * 10.0;
                let m = rnd3(&mut rng, 1e-3) * inertia * 1e3;
                let added = if k % 3 == 0 {
                    1.0
                } else {
                    rng.gen_range(1.0..1.5)
                };
                // the reference pose a little away, some near half the skin
                let x_ref = x - rnd3(&mut rng, if k % 2 == 0 { 1e-5 } else { 1e-6 });
                let q_ref = (DQuat::from_scaled_axis(rnd3(&mut rng, 1e-3)) * q).normalize();
                let reach = rng.gen_range(0.0..2e-3);
                b.set(
                    k,
                    (x, v, l, q),
                    (f, m),
                    (HalfKick::new(dt, mass, added), inertia),
                    (x_ref, q_ref),
                    reach,
                );
                if general {
                    b.set_moments(k, i3, crate::rotation::inverse_inertia(i3));
                }
                inputs.push((x, v, l, q, f, m, mass, added, i3, x_ref, q_ref, reach));
            }
            let offsets: Vec<DVec3> = (0..1 + round % SLOTS)
                .map(|_| rnd3(&mut rng, 2e-3))
                .collect();
            let mut outs = Vec::new();
            for &simd in &levels {
                let mut lanes = b;
                lanes.run(dt, half_skin, simd);
                lanes.place(&offsets, simd);
                outs.push(lanes);
            }
            for (k, &(x, v, l, q, f, m, mass, added, i3, x_ref, q_ref, reach)) in
                inputs.iter().enumerate()
            {
                // the scalar path, as first_half::FirstHalf::apply takes it
                let (mut v1, mut l1) = (v, l);
                HalfKick::new(dt, mass, added).apply_free(&mut v1, &mut l1, f, m);
                let x1 = x + v1 * dt;
                let q1 = scheme.drift(q, l1, i3, dt);
                let om1 = omega_world(q1, l1, i3);
                let rot1 = DMat3::from_quat(q1);
                let bound = skin::body_displacement_bound(x1, q1, x_ref, q_ref, reach);
                let within = skin::surely_within(bound, half_skin, x1.abs().max_element() + reach);
                let h2 = series_h2(kind, q, l1, i3, dt);
                let clear = !general || !(0.8e-4..1.25e-4).contains(&h2);
                for lanes in &outs {
                    if clear {
                        assert_eq!(lanes.holds[k], h2 < 1e-4, "series, lane {k}, h² = {h2}");
                    }
                    if !lanes.holds[k] {
                        fast += 1;
                        continue;
                    }
                    held += 1;
                    let (x2, v2, l2, q2, om2, rot2) = lanes.get(k);
                    assert_eq!(bits3(x2), bits3(x1), "centre, lane {k}");
                    assert_eq!(bits3(v2), bits3(v1), "velocity, lane {k}");
                    assert_eq!(bits3(l2), bits3(l1), "angular momentum, lane {k}");
                    assert_eq!(
                        q2.to_array().map(f64::to_bits),
                        q1.to_array().map(f64::to_bits),
                        "orientation, lane {k}"
                    );
                    assert_eq!(bits3(om2), bits3(om1), "angular velocity, lane {k}");
                    assert_eq!(
                        rot2.to_cols_array().map(f64::to_bits),
                        rot1.to_cols_array().map(f64::to_bits),
                        "rotation, lane {k}"
                    );
                    assert_eq!(lanes.within[k], within, "skin bound, lane {k}");
                    for (s, &off) in offsets.iter().enumerate() {
                        let slot = &lanes.spheres[s];
                        let p = get3(slot, k);
                        let want = crate::step::kinematics::sphere_position(x1, &rot1, off);
                        assert_eq!(bits3(p), bits3(want), "sphere {s}, lane {k}");
                    }
                    near += usize::from(!within);
                }
            }
        }
        // the counts run over every level the processor has (3 with
        // AVX-512, 2 with AVX2 only); per level, 3 200 lanes
        let n = levels.len();
        assert!(
            fast > 16 * n && held > 2600 * n && near > 33 * n && held - near > 33 * n,
            "lanes held {held} ({near} near the skin), beyond the series {fast}, over {n} levels"
        );
    }

    /// Runs the bed `bed` with its bodies `odd` (storage indices) made
    /// bodies the lanes do not take: a locked force axis, a locked torque
    /// axis, a start at step 700 (it moves ballistically until then), and
    /// a spin beyond the exponential's series; 1 500 steps with the lanes
    /// and on the scalar path alone give every body's state the same bits,
    /// with rebuilds on the way.
    fn same_bits_with_and_without_lanes(bed: impl Fn() -> crate::world::World, odd: [usize; 4]) {
        use std::sync::atomic::Ordering;
        let run = |scalar: bool| {
            let mut w = bed();
            let [force, torque, late, spun] = odd;
            w.bodies.force_flag[force] = [true, true, false];
            w.bodies.torque_flag[torque] = [false, true, true];
            w.bodies.start_step[late] = 700;
            w.bodies.velocity[late] = DVec3::new(0.0, 0.0, -0.05);
            let spin = w.bodies.inertia[spun].x * 4e3;
            w.bodies.angular_momentum[spun] = DVec3::new(0.0, spin, spin);
            SCALAR_ONLY.store(scalar, Ordering::SeqCst);
            w.run(1500).unwrap();
            SCALAR_ONLY.store(false, Ordering::SeqCst);
            (crate::testbed::state_bits(&w), w.rebuilds)
        };
        let (lanes, rebuilds) = run(false);
        let (scalar, _) = run(true);
        assert!(rebuilds > 3, "only {rebuilds} rebuilds");
        assert!(lanes == scalar, "the lanes changed the bits");
    }

    /// A settling tetra bed (spherical tops) with the bodies the lanes do
    /// not take mixed in ([`same_bits_with_and_without_lanes`]).
    #[test]
    fn a_bed_steps_the_same_bits_with_and_without_lanes() {
        same_bits_with_and_without_lanes(
            || crate::testbed::tetra_lattice_bed(6, 6, 3, None),
            [3, 10, 20, 30],
        );
    }

    /// An asymmetric clump of three unequal spheres (three different
    /// principal moments).
    fn stone() -> crate::shape::ClumpTemplate {
        let s = [
            (DVec3::ZERO, 1e-3),
            (DVec3::new(1.1e-3, 0.0, 0.0), 0.8e-3),
            (DVec3::new(0.0, 0.9e-3, 0.3e-3), 0.7e-3),
        ]
        .map(|(center, radius)| crate::shape::Sphere { center, radius });
        let density = crate::testbed::tetra_material().density;
        crate::shape::ClumpTemplate::from_spheres("stone", &s, density).unwrap()
    }

    /// A settling bed of asymmetric stones and tetrahedra (two stones to a
    /// tetrahedron, so that blocks hold both kinds) under the Richardson
    /// and the NO_SQUISH schemes, with the bodies the lanes do not take
    /// among the stones ([`same_bits_with_and_without_lanes`]).
    #[test]
    fn a_stone_bed_steps_the_same_bits_with_and_without_lanes() {
        let stone = stone();
        let i = stone.principal_inertia;
        assert!(i.x < i.y && i.y < i.z, "not asymmetric: {i}");
        let templates = [stone.clone(), stone, crate::testbed::tetra_template()];
        for scheme in [RotationScheme::Richardson, RotationScheme::NoSquish] {
            let bed = || {
                let mut w = crate::testbed::lattice_bed(&templates, 6, 6, 3, None);
                w.config.rotation = scheme;
                w
            };
            same_bits_with_and_without_lanes(bed, [3, 10, 19, 31]);
        }
    }
}
