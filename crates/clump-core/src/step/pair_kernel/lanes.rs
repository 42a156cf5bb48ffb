//! The lanes of a batch of touching pairs: one array per quantity, one
//! element per contact (structure of arrays), with each contact's geometry,
//! kinematics and torques, for the law loop of `crate::step::law_lanes`.

use super::BATCH;
use crate::contact::geometry::sphere_pair;
use crate::contact::{ContactHistory, ContactInput, ContactModel, SlidingLaw};
use crate::par::simd::{get3, set3};
use crate::step::law_lanes::LawLanes;
use glam::DVec3;

/// A 3-vector per lane (x, y and z rows), world frame.
pub(super) type Rows3 = [[f64; BATCH]; 3];

/// The inputs and outputs of a batch's contacts, lane `k` = contact `k`.
/// World frame, SI units.
#[repr(C)]
#[derive(Clone, Copy)]
pub(super) struct Lanes {
    // --- inputs
    /// `x_i − x_j`, m.
    pub separation: Rows3,
    /// Velocity of `i`'s body, m/s.
    pub velocity_i: Rows3,
    /// `ω` of `i`'s body, rad/s.
    pub omega_i: Rows3,
    /// `ω` of `j`'s body, rad/s.
    pub omega_j: Rows3,
    /// Tangential spring `ξ`, m: input, and output after the law.
    pub spring: Rows3,
    /// Radius of `i`, m.
    pub radius_i: [f64; BATCH],
    /// Radius of `j`, m.
    pub radius_j: [f64; BATCH],
    /// Mass of `i`'s body, kg.
    pub mass_i: [f64; BATCH],
    /// Mass of `j`'s body, kg.
    pub mass_j: [f64; BATCH],
    /// Multi-contact scale of the force.
    pub scale: [f64; BATCH],
    // --- outputs
    /// Force on `i`, scaled, N.
    pub force: Rows3,
    /// Torque on `i`'s body about its centre of mass, N m.
    pub torque_i: Rows3,
    /// Torque on `j`'s body about its centre of mass, N m.
    pub torque_j: Rows3,
    /// Unit normal, `j` → `i`.
    pub normal: Rows3,
    /// Overlap, m.
    pub overlap: [f64; BATCH],
    /// Elastic energy, unscaled, J.
    pub energy: [f64; BATCH],
    /// Signed normal force, unscaled, N.
    pub normal_force: [f64; BATCH],
    /// Normal stiffness, N/m.
    pub kn: [f64; BATCH],
    /// `R*`, m.
    pub r_star: [f64; BATCH],
    /// `m*`, kg.
    pub m_star: [f64; BATCH],
    // --- more inputs
    /// Lever arm `x_i − r_cm` of sphere `i` in its body, m.
    pub arm_i: Rows3,
    /// Lever arm `x_j − r_cm` of sphere `j` in its body, m.
    pub arm_j: Rows3,
    /// Velocity of `j`'s body, m/s.
    pub velocity_j: Rows3,
    /// Per-lane law, when the batch mixes models ([`Lanes::set_law`]).
    pub law: [[f64; BATCH]; SlidingLaw::LANE_ROWS],
    /// Output of the law loop: 1 where the contact slides, its outputs
    /// being those of a sticking contact until
    /// [`crate::step::law_lanes::finish_sliding`];
    /// else 0. A number, not a `bool`: a `bool` output kept the compiler
    /// from vectorising the loop.
    pub slide: [f64; BATCH],
}

/// One lane's contact geometry and kinematics (world frame, SI units).
struct LaneContact {
    /// Unit normal, `j` → `i`.
    normal: DVec3,
    /// Overlap, m.
    overlap: f64,
    /// Lever arms of the contact point from the two bodies' centres of
    /// mass, `x_c − r_cm`, m.
    lever_i: DVec3,
    lever_j: DVec3,
    /// Relative velocity of the contact points, m/s.
    vrel: DVec3,
    /// `R*`, m.
    radius: f64,
    /// `m*`, kg.
    mass: f64,
}

impl Lanes {
    /// All lanes zero.
    pub(super) fn zeroed() -> Self {
        let v = [0.0; BATCH];
        let v3 = [v; 3];
        Lanes {
            separation: v3,
            velocity_i: v3,
            omega_i: v3,
            omega_j: v3,
            spring: v3,
            radius_i: v,
            radius_j: v,
            mass_i: v,
            mass_j: v,
            scale: v,
            force: v3,
            torque_i: v3,
            torque_j: v3,
            normal: v3,
            overlap: v,
            energy: v,
            normal_force: v,
            kn: v,
            r_star: v,
            m_star: v,
            arm_i: v3,
            arm_j: v3,
            velocity_j: v3,
            law: [v; SlidingLaw::LANE_ROWS],
            slide: v,
        }
    }

    /// Stores lane `k`'s law.
    #[inline(always)]
    pub(super) fn set_law(&mut self, k: usize, law: &SlidingLaw) {
        law.store_lane(&mut self.law, k);
    }

    /// Contact `k` of a pair whose model runs the scalar composition
    /// ([`ContactModel::is_extended`]): the same geometry, kinematics and
    /// torques as [`LawLanes::contact_as`], the law and its rolling couple from
    /// [`ContactModel::evaluate`], starting from the history `h` (updated;
    /// the lane's spring is set to `h.tangential`).
    #[inline(never)]
    pub(super) fn contact_scalar(
        &mut self,
        k: usize,
        model: &ContactModel,
        h: &mut ContactHistory,
        slip: Option<&mut crate::contact::mdr::SlipProfile>,
        dt: f64,
    ) {
        let c = self.kinematics(k);
        let input = ContactInput {
            normal: c.normal,
            overlap: c.overlap,
            rel_velocity: c.vrel,
            rel_omega: get3(&self.omega_i, k) - get3(&self.omega_j, k),
            radius: c.radius,
            radius_sum: self.radius_i[k] + self.radius_j[k],
            mass: c.mass,
            dt,
        };
        let out = match slip {
            Some(s) => model.evaluate_slip(&input, h, s),
            None => model.evaluate(&input, h),
        };
        set3(&mut self.spring, k, h.tangential);
        // the lane's stiffness is read only by the kernel's rolling loop,
        // which skips these pairs (their couple is in `out.torque`)
        self.store(k, &c, out.force, out.elastic_energy, out.normal_force, 0.0);
        // the rolling couple, as the kernel adds it for vectorised pairs
        let couple = out.torque * self.scale[k];
        let (ti, tj) = (get3(&self.torque_i, k), get3(&self.torque_j, k));
        set3(&mut self.torque_i, k, ti + couple);
        set3(&mut self.torque_j, k, tj - couple);
    }

    /// Contact `k`'s geometry (`crate::contact::geometry`), the
    /// contact-point relative velocity from the bodies' velocities and
    /// angular velocities, `R*` and `m*`.
    #[inline(always)]
    fn kinematics(&self, k: usize) -> LaneContact {
        let (ri, rj) = (self.radius_i[k], self.radius_j[k]);
        let g = sphere_pair(get3(&self.separation, k), ri, rj);
        let (nrm, ai, aj) = (g.normal, g.arm_i, g.arm_j);
        let (wi, wj) = (get3(&self.omega_i, k), get3(&self.omega_j, k));
        let (ci, cj) = (get3(&self.arm_i, k), get3(&self.arm_j, k));
        // the contact point's lever arms, x_c − r_cm = c_i − a_i n on i's
        // body and c_j + a_j n on j's, and its velocities v + ω × (x_c − r_cm)
        let (lever_i, lever_j) = (ci - nrm * ai, cj + nrm * aj);
        let vrel = get3(&self.velocity_i, k) + wi.cross(lever_i)
            - (get3(&self.velocity_j, k) + wj.cross(lever_j));
        let (mi, mj) = (self.mass_i[k], self.mass_j[k]);
        LaneContact {
            normal: nrm,
            overlap: g.overlap,
            lever_i,
            lever_j,
            vrel,
            radius: ri * rj / (ri + rj),
            mass: mi * mj / (mi + mj),
        }
    }

    /// Stores contact `k`'s outputs: the force `force` on `i` (unscaled,
    /// N) scaled by the lane's multi-contact scale, its torques about the
    /// bodies' centres of mass, and the unscaled energy, normal force and
    /// stiffness.
    #[inline(always)]
    fn store(
        &mut self,
        k: usize,
        c: &LaneContact,
        force: DVec3,
        energy: f64,
        normal_force: f64,
        kn: f64,
    ) {
        let f = force * self.scale[k];
        set3(&mut self.force, k, f);
        set3(&mut self.torque_i, k, c.lever_i.cross(f));
        // −(lever_j × f), bit for bit
        set3(&mut self.torque_j, k, f.cross(c.lever_j));
        set3(&mut self.normal, k, c.normal);
        self.overlap[k] = c.overlap;
        self.energy[k] = energy;
        self.normal_force[k] = normal_force;
        self.kn[k] = kn;
        self.r_star[k] = c.radius;
        self.m_star[k] = c.mass;
    }

    /// Every row with its field name and row index (to compare batches
    /// bit for bit).
    #[cfg(test)]
    fn rows(&self) -> Vec<(&'static str, usize, &[f64; BATCH])> {
        let mut out = Vec::new();
        let v3: [(&'static str, &Rows3); 12] = [
            ("separation", &self.separation),
            ("velocity_i", &self.velocity_i),
            ("omega_i", &self.omega_i),
            ("omega_j", &self.omega_j),
            ("spring", &self.spring),
            ("force", &self.force),
            ("torque_i", &self.torque_i),
            ("torque_j", &self.torque_j),
            ("normal", &self.normal),
            ("arm_i", &self.arm_i),
            ("arm_j", &self.arm_j),
            ("velocity_j", &self.velocity_j),
        ];
        for (name, r) in v3 {
            for (q, x) in r.iter().enumerate() {
                out.push((name, q, x));
            }
        }
        let v1: [(&'static str, &[f64; BATCH]); 12] = [
            ("radius_i", &self.radius_i),
            ("radius_j", &self.radius_j),
            ("mass_i", &self.mass_i),
            ("mass_j", &self.mass_j),
            ("scale", &self.scale),
            ("overlap", &self.overlap),
            ("energy", &self.energy),
            ("normal_force", &self.normal_force),
            ("kn", &self.kn),
            ("r_star", &self.r_star),
            ("m_star", &self.m_star),
            ("slide", &self.slide),
        ];
        out.extend(v1.into_iter().map(|(n, x)| (n, 0, x)));
        for (q, x) in self.law.iter().enumerate() {
            out.push(("law", q, x));
        }
        out
    }
}

impl LawLanes for Lanes {
    const LANES: usize = BATCH;

    #[inline(always)]
    fn lane_law(&self, k: usize) -> SlidingLaw {
        SlidingLaw::load_lane(&self.law, k)
    }

    /// Contact `k`: the geometry (`crate::contact::geometry`), the
    /// contact-point velocities from the bodies' velocities and angular
    /// velocities, `R*`, `m*`, the law, and the torques of its force about
    /// the two bodies' centres of mass: the contact point is
    /// `x_c = x_i − a_i n = x_j + a_j n`, so its lever arms from the centres
    /// of mass are `x_c − r_cm,i = c_i − a_i n` and `x_c − r_cm,j = c_j +
    /// a_j n` (with the spheres' lever arms `c = x_s − r_cm`), and the
    /// torques are `(x_c − r_cm,i) × f` on `i`'s body and
    /// `(x_c − r_cm,j) × (−f) = f × (x_c − r_cm,j)` on `j`'s (docs/theory.md
    /// T-11). The kinematics has both lever arms already: one cross product
    /// each, 12 multiplications a contact fewer (of about 110 in the law
    /// loop) than summing `c × f` and `a (n × f)`.
    #[inline(always)]
    fn contact_as<const LIMIT: bool>(&mut self, k: usize, law: &SlidingLaw, dt: f64) -> bool {
        let c = self.kinematics(k);
        let mut xi = get3(&self.spring, k);
        let (out, slide) =
            law.evaluate_as::<LIMIT>(c.normal, c.overlap, c.vrel, c.radius, c.mass, dt, &mut xi);
        set3(&mut self.spring, k, xi);
        self.store(k, &c, out.force, out.energy, out.normal_force, out.kn);
        slide
    }

    #[inline(always)]
    fn slide(&self, k: usize) -> f64 {
        self.slide[k]
    }

    #[inline(always)]
    fn set_slide(&mut self, k: usize, slide: f64) {
        self.slide[k] = slide;
    }

    #[inline(always)]
    fn set_spring(&mut self, k: usize, xi: DVec3) {
        set3(&mut self.spring, k, xi);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::model::sample_laws;
    use crate::par::simd::{get3, set3};
    use crate::par::simd::{levels, unit_numbers};
    use crate::step::law_lanes::{finish_sliding, law_lanes, run_law};

    /// Lanes of contacts with overlaps of 0 to 20 % of the radius, sliding
    /// and sticking springs, random velocities; `mixed`: every lane its own
    /// law (Hertz and linear, clamped and tensile).
    fn lanes(seed: u64, laws: &[SlidingLaw], mixed: bool) -> Lanes {
        let mut u = unit_numbers(seed);
        let mut l = Lanes::zeroed();
        for k in 0..BATCH {
            fn v3(u: &mut impl FnMut() -> f64, a: f64) -> DVec3 {
                DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * a
            }
            let (ri, rj) = (1e-3 * (0.5 + u()), 1e-3 * (0.5 + u()));
            let n = v3(&mut u, 2.0).normalize();
            let d = n * (ri + rj) * (1.0 - 0.1 * u());
            set3(&mut l.separation, k, d);
            set3(&mut l.velocity_i, k, v3(&mut u, 0.2));
            set3(&mut l.velocity_j, k, v3(&mut u, 0.2));
            set3(&mut l.omega_i, k, v3(&mut u, 50.0));
            set3(&mut l.omega_j, k, v3(&mut u, 50.0));
            set3(&mut l.arm_i, k, v3(&mut u, 1e-3));
            set3(&mut l.arm_j, k, v3(&mut u, 1e-3));
            // springs from far inside the Coulomb cone to far outside
            set3(&mut l.spring, k, {
                let a = 1e-4 * u() * u();
                v3(&mut u, a)
            });
            l.radius_i[k] = ri;
            l.radius_j[k] = rj;
            l.mass_i[k] = 1e-5 * (0.5 + u());
            l.mass_j[k] = 1e-5 * (0.5 + u());
            l.scale[k] = if k % 5 == 0 { 0.5 } else { 1.0 };
            if mixed {
                l.set_law(k, &laws[k % laws.len()]);
            }
        }
        l
    }

    /// Every row of `got` has the bits of `want`'s (`what` names the case).
    fn assert_same_bits(got: &Lanes, want: &Lanes, what: &str) {
        for ((name, q, g), (_, _, w)) in got.rows().into_iter().zip(want.rows()) {
            for k in 0..BATCH {
                assert_eq!(
                    g[k].to_bits(),
                    w[k].to_bits(),
                    "{what}: {name}[{q}] lane {k}"
                );
            }
        }
    }

    /// The law loop takes every contact as sticking and flags those that
    /// slide; evaluated again from their spring before the step, the lanes
    /// then hold, bit for bit, what the full law of each contact gives
    /// ([`Lanes::contact`], with the Coulomb limit), at every vector
    /// instruction set of this processor.
    #[test]
    fn sliding_contacts_evaluated_again_give_the_full_law() {
        let (laws, levels) = (sample_laws(), levels());
        for (case, law) in [None, Some(&laws[0]), Some(&laws[2])]
            .into_iter()
            .enumerate()
        {
            let base = lanes(case as u64 + 11, &laws, law.is_none());
            let mut want = base;
            for k in 0..BATCH {
                let lw = law.copied().unwrap_or_else(|| want.lane_law(k));
                want.contact_as::<true>(k, &lw, 1e-5);
            }
            for &level in &levels {
                let mut l = base;
                run_law(&mut l, BATCH, law, 1e-5, level);
                let sliding = (0..BATCH).filter(|&k| l.slide[k] != 0.0).count();
                // the springs span the cone: some lanes slide, most stick
                assert!(
                    sliding > 0 && 2 * sliding < BATCH,
                    "{level:?}, case {case}: {sliding} of {BATCH} lanes slide"
                );
                finish_sliding(&mut l, BATCH, law, 1e-5, |k| get3(&base.spring, k));
                assert_same_bits(&l, &want, &format!("{level:?}, case {case}"));
            }
        }
    }

    /// The law loop gives the same bits compiled for every vector
    /// instruction set this processor has (the engine picks the widest at
    /// run time; results must not depend on the machine's choice).
    #[test]
    fn law_lanes_same_bits_at_every_simd_level() {
        let (laws, levels) = (sample_laws(), levels());
        for (case, law) in [None, Some(&laws[0]), Some(&laws[3])]
            .into_iter()
            .enumerate()
        {
            for len in [BATCH, 13] {
                let base = lanes(case as u64 + 7, &laws, law.is_none());
                let mut want = base;
                law_lanes(&mut want, len, law, 1e-5);
                // the loop did something: a stiffness on every evaluated lane,
                // a force on most (a clamped lane separating fast has none)
                assert!((0..len).all(|k| want.kn[k] > 0.0));
                let pushed = (0..len).filter(|&k| want.force[0][k] != 0.0).count();
                assert!(2 * pushed > len, "{pushed} of {len} lanes with a force");
                for &level in &levels {
                    let mut l = base;
                    run_law(&mut l, len, law, 1e-5, level);
                    assert_same_bits(&l, &want, &format!("{level:?}, case {case}, len {len}"));
                }
            }
        }
    }
}
