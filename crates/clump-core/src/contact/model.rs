//! [`ContactModel`]: the normal, damping, tangential and rolling sub-models
//! composed and precomputed for one pair of materials.
//!
//! Both normal laws share one code path. With the stiffness scale
//! `s = √(R*δ)` (Hertz) or `s = 1` (linear):
//! - elastic normal force `F_el = k̂_n s δ` (`k̂_n = (4/3)E*` or `k_n`),
//! - tangential stiffness `k_t = k̂_t s` (`k̂_t = 8G*` or `k_t`),
//! - dashpots `γ_n = ĝ_n √(s m*)`, `γ_t = ĝ_t √(s m*)`, where for Hertz
//!   `ĝ_n = −2√(5/6)β√(2E*)`, `ĝ_t = −2√(5/6)β√(8G*)` and for linear
//!   `ĝ_n = −2β√k_n`, `ĝ_t = −2β√k_t` (see [`super::damping`] for `β`),
//! - total normal force `F_n = max(F_el − γ_n v_n, 0)` (the tensile clamp,
//!   default) or `F_el − γ_n v_n` ([`PairProperties::tensile`]).
//!
//! [`SlidingLaw::evaluate`] is that composition, calling the sub-models'
//! own formulas: [`super::normal`] (stiffness scale, elastic force, spring
//! energy), [`super::damping`] (dashpots, the clamped normal force),
//! [`super::tangential`] (the history spring and its energy); the
//! constants come from the same files ([`normal::stiffness_coefficients`],
//! [`damping::dashpot_coefficients`]). The pair kernel and the wall path
//! run this one function.

use super::cohesion::{jkr_critical_separation, CohesionLaw};
use super::damping::{self, clamped_pulse_time, damping_ratio, DampingLaw};
use super::material::{effective_modulus, effective_shear_modulus, Material};
use super::normal::{self, NormalLaw};
use super::rolling::{cdt, epsd, rolling_omega, RollingLaw};
use super::tangential::{self, TangentialLaw};
use super::time_scale::hertz_contact_time;
use super::twisting::TwistingLaw;
use super::{ContactError, ContactInput};
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Contact properties the user gives per pair of materials. Missing fields
/// in a serialized form take their [`Default`] values.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct PairProperties {
    /// Normal coefficient of restitution `e ∈ [0, 1]`, dimensionless.
    pub restitution: f64,
    /// Sliding (Coulomb) friction coefficient `μ ≥ 0`, dimensionless.
    pub friction: f64,
    /// Rolling friction coefficient `μ_r ≥ 0`, dimensionless (the limiting
    /// rolling couple is `μ_r R* F_n`, `F_n` after the tensile clamp).
    pub rolling_friction: f64,
    /// Normal force law.
    pub normal: NormalLaw,
    /// How the dashpots are derived from `e`.
    pub damping: DampingLaw,
    /// Rolling-resistance law.
    pub rolling: RollingLaw,
    /// Whether the total normal force may be tensile (pull). `false`
    /// (default): a contact between non-cohesive particles cannot pull, the
    /// normal force is clamped, `F_n = max(F_el − γ_n v_n, 0)` (LIGGGHTS'
    /// `limitForce on`), and the Coulomb and rolling limits use this
    /// `F_n ≥ 0`. `true`: no clamp (LIGGGHTS' default, `limitForce off`): near
    /// the end of a damped rebound the dashpot makes `F_n` slightly tensile,
    /// and the limits use `|F_n|`, as LIGGGHTS does. [`DampingLaw::Exact`]
    /// is calibrated for either choice (see [`super::damping`]).
    pub tensile: bool,
    /// Tangential rule ([`TangentialLaw`]): Clump's (default) or LIGGGHTS'.
    pub tangential: TangentialLaw,
    /// Cohesion ([`CohesionLaw`]; default none).
    pub cohesion: CohesionLaw,
    /// Twisting resistance ([`TwistingLaw`]; default none).
    pub twisting: TwistingLaw,
}

impl Default for PairProperties {
    /// `e = 0.5`, `μ = 0.5`, `μ_r = 0`, Hertz, exact damping, no rolling
    /// resistance, normal force clamped (not tensile), Clump's tangential
    /// rule.
    fn default() -> Self {
        PairProperties {
            restitution: 0.5,
            friction: 0.5,
            rolling_friction: 0.0,
            normal: NormalLaw::Hertz,
            damping: DampingLaw::Exact,
            rolling: RollingLaw::None,
            tensile: false,
            tangential: TangentialLaw::Clump,
            cohesion: CohesionLaw::None,
            twisting: TwistingLaw::None,
        }
    }
}

/// The normal and tangential part of a [`ContactModel`] (everything but
/// rolling resistance), with its material constants precomputed. Its
/// [`evaluate`](Self::evaluate) is branch-free straight-line arithmetic on
/// plain numbers, so that the engine can run it over arrays of contacts as
/// vector instructions (the pair kernel, `step::force`); the scalar
/// [`ContactModel::evaluate`] runs the same function, so there is one law.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlidingLaw {
    /// Hertz (`s = √(R*δ)`) or linear (`s = 1`) stiffness scale.
    pub hertz: bool,
    /// Lower bound of the total normal force, N: 0 (clamped) or −∞ (tensile).
    pub fn_floor: f64,
    /// `k̂_n`: `(4/3)E*` (Pa, Hertz) or `k_n` (N/m, linear).
    pub kn_coef: f64,
    /// `k̂_t`: `8G*` (Pa, Hertz) or `k_t` (N/m, linear).
    pub kt_coef: f64,
    /// `ĝ_n`, the normal dashpot `γ_n = ĝ_n √(s m*)`.
    pub gn_coef: f64,
    /// `ĝ_t`, the tangential dashpot `γ_t = ĝ_t √(s m*)`.
    pub gt_coef: f64,
    /// Normal spring energy `factor · F_el δ` (2/5 Hertz, 1/2 linear).
    pub energy_factor: f64,
    /// Sliding friction coefficient `μ`.
    pub friction: f64,
}

/// What [`SlidingLaw::evaluate`] returns, world frame, SI units.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SlidingOutput {
    /// Normal plus tangential force on `i`, N, at the contact point.
    pub force: DVec3,
    /// Signed normal force `F_n`, N (after the tensile clamp).
    pub normal_force: f64,
    /// Elastic energy of the normal and tangential springs, J.
    pub energy: f64,
    /// Normal stiffness `k_n = k̂_n s`, N/m (the EPSD rolling spring uses it).
    pub kn: f64,
}

impl SlidingLaw {
    /// Rows of a vector loop whose lanes carry their own law: the law's
    /// constants, one row each ([`Self::store_lane`], [`Self::load_lane`]).
    pub const LANE_ROWS: usize = 8;

    /// Stores the law as lane `k` of `rows`, one constant a row (numbers
    /// only: `hertz` as 1 or 0).
    #[inline(always)]
    pub fn store_lane<const N: usize>(&self, rows: &mut [[f64; N]; Self::LANE_ROWS], k: usize) {
        rows[0][k] = if self.hertz { 1.0 } else { 0.0 };
        rows[1][k] = self.fn_floor;
        rows[2][k] = self.kn_coef;
        rows[3][k] = self.kt_coef;
        rows[4][k] = self.gn_coef;
        rows[5][k] = self.gt_coef;
        rows[6][k] = self.energy_factor;
        rows[7][k] = self.friction;
    }

    /// The law stored as lane `k` of `rows` by [`Self::store_lane`].
    #[inline(always)]
    pub fn load_lane<const N: usize>(rows: &[[f64; N]; Self::LANE_ROWS], k: usize) -> Self {
        SlidingLaw {
            hertz: rows[0][k] != 0.0,
            fn_floor: rows[1][k],
            kn_coef: rows[2][k],
            kt_coef: rows[3][k],
            gn_coef: rows[4][k],
            gt_coef: rows[5][k],
            energy_factor: rows[6][k],
            friction: rows[7][k],
        }
    }

    /// Normal force with its dashpot and the tensile clamp, then the
    /// tangential history spring with its dashpot and Coulomb limit (see the
    /// [module docs](self)), updating the spring `xi` (m, world). `n` is the
    /// unit normal (world), `overlap` `δ > 0` (m), `v_rel` the relative
    /// velocity of the contact points (m/s, world), `radius` `R*` (m), `mass`
    /// `m*` (kg), `dt` (s).
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate(
        &self,
        n: DVec3,
        overlap: f64,
        v_rel: DVec3,
        radius: f64,
        mass: f64,
        dt: f64,
        xi: &mut DVec3,
    ) -> SlidingOutput {
        self.evaluate_as::<true>(n, overlap, v_rel, radius, mass, dt, xi)
            .0
    }

    /// [`Self::evaluate`], and whether the contact slides; with `LIMIT`
    /// false, the result of a contact that sticks, whether or not it does
    /// ([`tangential::history_spring_as`]): for a contact that sticks the
    /// same bits as [`Self::evaluate`].
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub fn evaluate_as<const LIMIT: bool>(
        &self,
        n: DVec3,
        overlap: f64,
        v_rel: DVec3,
        radius: f64,
        mass: f64,
        dt: f64,
        xi: &mut DVec3,
    ) -> (SlidingOutput, bool) {
        let d = overlap;
        let s = normal::stiffness_scale(self.hertz, radius, overlap);
        let kn = self.kn_coef * s;
        let kt = self.kt_coef * s;
        let gamma_n = damping::dashpot(self.gn_coef, s, mass);
        let gamma_t = damping::dashpot(self.gt_coef, s, mass);
        let vn = v_rel.dot(n);
        let vt = v_rel - vn * n;
        let f_el = normal::elastic_force(kn, d);
        // The Coulomb and rolling limits use |F_n|, which is F_n itself
        // when clamped.
        let f_n = damping::normal_force(f_el, gamma_n, vn, self.fn_floor);
        let (f_t, slide) = tangential::history_spring_as::<LIMIT>(
            xi,
            n,
            vt,
            dt,
            kt,
            gamma_t,
            self.friction * f_n.abs(),
        );
        let out = SlidingOutput {
            force: f_n * n + f_t,
            normal_force: f_n,
            energy: normal::spring_energy(self.energy_factor, f_el, d)
                + tangential::spring_energy(kt, *xi),
            kn,
        };
        (out, slide)
    }
}

/// Precomputed contact model for one pair of materials. Cheap to evaluate;
/// `Copy`, `Send + Sync`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactModel {
    props: PairProperties,
    e_star: f64,
    g_star: f64,
    /// Damping ratio actually used, ≤ 0 (see [`super::damping::damping_ratio`]).
    beta: f64,
    law: SlidingLaw,
    rolling_friction: f64,
    rolling: RollingLaw,
    rolling_damping: f64,
    /// The pair selects a sub-model the vectorised [`SlidingLaw`] does not
    /// have (LIGGGHTS' tangential rule, cohesion, twisting): it runs the scalar composition
    /// [`super::extended::evaluate`], in the pair kernel and on walls.
    extended: bool,
}

impl ContactModel {
    /// Builds the model for materials `a` and `b` (symmetric in `a`, `b`) with
    /// pair properties `p`. Validates: `E > 0` (∞ for a rigid wall, but not both
    /// rigid), `ν ∈ (−1, 0.5)`, `ρ > 0`, `0 ≤ e ≤ 1`, `μ ≥ 0`, `μ_r ≥ 0`, and for
    /// the linear law `k_n > 0`, `k_t ≥ 0`, all finite. Cheap: closed-form
    /// coefficients, and for the clamped exact damping a bisection on a
    /// closed form (a few µs; see [`super::damping`]).
    pub fn new(a: &Material, b: &Material, p: &PairProperties) -> Result<Self, ContactError> {
        a.validate("a")?;
        b.validate("b")?;
        let perr = |s: String| Err(ContactError::Property(s));
        let e = p.restitution;
        if !(0.0..=1.0).contains(&e) {
            return perr(format!("restitution must lie in [0, 1], got {e}"));
        }
        if !(p.friction >= 0.0 && p.friction.is_finite()) {
            return perr(format!(
                "friction coefficient must be finite and >= 0, got {}",
                p.friction
            ));
        }
        if !(p.rolling_friction >= 0.0 && p.rolling_friction.is_finite()) {
            return perr(format!(
                "rolling friction coefficient must be finite and >= 0, got {}",
                p.rolling_friction
            ));
        }
        let e_star = effective_modulus(a, b);
        let g_star = effective_shear_modulus(a, b);
        // The same β serves both normal laws (phase-plane mapping, see
        // `damping`), clamped or not.
        let (beta, clamped) = damping_ratio(p.damping, e, p.tensile);
        match p.normal {
            NormalLaw::Hertz => {
                if !e_star.is_finite() {
                    return perr(
                        "Hertz contact between two rigid materials (E* is infinite)".into(),
                    );
                }
            }
            NormalLaw::Linear { kn, kt } => {
                if !(kn > 0.0 && kn.is_finite()) {
                    return perr(format!(
                        "linear normal stiffness kn must be finite and > 0 N/m, got {kn}"
                    ));
                }
                if !(kt >= 0.0 && kt.is_finite()) {
                    return perr(format!(
                        "linear tangential stiffness kt must be finite and >= 0 N/m, got {kt}"
                    ));
                }
            }
        }
        match p.cohesion {
            CohesionLaw::None => {}
            CohesionLaw::Sjkr { energy_density: k } => {
                if !(k >= 0.0 && k.is_finite()) {
                    return perr(format!(
                        "cohesion energy density must be finite and >= 0 J/m^3, got {k}"
                    ));
                }
            }
            CohesionLaw::Jkr { surface_energy: g } => {
                if !(g >= 0.0 && g.is_finite()) {
                    return perr(format!(
                        "surface energy must be finite and >= 0 J/m^2, got {g}"
                    ));
                }
                if p.normal != NormalLaw::Hertz {
                    return perr("JKR cohesion needs the Hertz normal law".into());
                }
            }
        }
        if p.tangential == TangentialLaw::Mdr {
            if p.normal != NormalLaw::Hertz {
                return perr("tangential = mdr needs the Hertz normal law".into());
            }
            if p.cohesion != CohesionLaw::None {
                return perr("tangential = mdr cannot be combined with cohesion".into());
            }
        }
        if p.tangential == TangentialLaw::MindlinDeresiewicz {
            if p.normal != NormalLaw::Hertz {
                return perr("tangential = mindlin_deresiewicz needs the Hertz normal law".into());
            }
            if p.cohesion != CohesionLaw::None {
                return perr(
                    "tangential = mindlin_deresiewicz cannot be combined with cohesion".into(),
                );
            }
            // the model uses both history slots (contact::micro_slip)
            if p.rolling == RollingLaw::Epsd || p.twisting != TwistingLaw::None {
                return perr("tangential = mindlin_deresiewicz cannot be combined with EPSD rolling resistance or twisting resistance (it stores its turning points in their history slot)".into());
            }
        }
        let (hertz, kn_coef, kt_coef, energy_factor) =
            normal::stiffness_coefficients(p.normal, e_star, g_star);
        let (gn_coef, gt_coef) = damping::dashpot_coefficients(p.normal, beta, e_star, g_star);
        Ok(ContactModel {
            props: *p,
            e_star,
            g_star,
            beta,
            law: SlidingLaw {
                hertz,
                fn_floor: if clamped { 0.0 } else { f64::NEG_INFINITY },
                kn_coef,
                kt_coef,
                gn_coef,
                gt_coef,
                energy_factor,
                friction: p.friction,
            },
            rolling_friction: p.rolling_friction,
            rolling: p.rolling,
            rolling_damping: 0.0,
            extended: p.tangential != TangentialLaw::Clump
                || p.cohesion != CohesionLaw::None
                || p.twisting != TwistingLaw::None,
        })
    }

    /// Sets the EPSD rolling viscous ratio `η_r ≥ 0` (dimensionless; default 0):
    /// `C_r = η_r·2√(I_r k_r)`, `I_r = (7/5)m*R*²`, active only while the rolling
    /// spring is not fully mobilised. No effect for other rolling laws.
    pub fn with_rolling_damping(mut self, eta_r: f64) -> Result<Self, ContactError> {
        if !(eta_r >= 0.0 && eta_r.is_finite()) {
            return Err(ContactError::Property(format!(
                "rolling damping ratio must be finite and >= 0, got {eta_r}"
            )));
        }
        self.rolling_damping = eta_r;
        Ok(self)
    }

    /// Whether the pair keeps an MDR profile (`tangential = "mdr"`).
    pub fn keeps_slip_profile(&self) -> bool {
        self.props.tangential == TangentialLaw::Mdr
    }

    /// The normal and tangential part of the law.
    pub fn sliding_law(&self) -> &SlidingLaw {
        &self.law
    }

    /// Whether the pair selects a sub-model that only the scalar
    /// composition has ([`super::extended`]); the pair kernel then runs
    /// [`Self::evaluate`] for it instead of the vectorised [`SlidingLaw`].
    pub fn is_extended(&self) -> bool {
        self.extended
    }

    /// How far apart (m, ≥ 0) the surfaces of a contact between spheres of
    /// effective radius `r_star` (m) may move before it breaks: JKR's
    /// critical separation `δ_c`, 0 for every other law (a contact ends at
    /// `δ = 0`). See [`super::cohesion`].
    pub fn reach(&self, r_star: f64) -> f64 {
        match self.props.cohesion {
            CohesionLaw::Jkr { surface_energy } => {
                jkr_critical_separation(surface_energy, r_star, self.e_star)
            }
            _ => 0.0,
        }
    }

    /// JKR pull-off force magnitude `(3/2)πΓR*` (N) for effective radius
    /// `r_star` (m); 0 without JKR cohesion.
    pub fn pull_off_force(&self, r_star: f64) -> f64 {
        match self.props.cohesion {
            CohesionLaw::Jkr { surface_energy } => {
                super::cohesion::jkr_pull_off_force(surface_energy, r_star)
            }
            _ => 0.0,
        }
    }

    /// The EPSD rolling viscous ratio `η_r` ([`Self::with_rolling_damping`]).
    pub fn rolling_damping(&self) -> f64 {
        self.rolling_damping
    }

    /// Whether the law has a rolling couple (a rolling law other than none).
    pub fn has_rolling(&self) -> bool {
        self.rolling != RollingLaw::None
    }

    /// Rolling couple on `i` (N m, world) of the contact `c` whose normal
    /// force is `f_n` (N) and normal stiffness `kn` (N/m, from
    /// [`SlidingLaw::evaluate`]), updating the EPSD spring `m_r` (N m,
    /// world); with the EPSD spring's elastic energy (J) for that law. Reads
    /// `c.normal`, `c.rel_omega`, `c.radius`, `c.mass` and `c.dt` only.
    #[inline(always)]
    pub fn rolling_couple(
        &self,
        c: &ContactInput,
        f_n: f64,
        kn: f64,
        m_r: &mut DVec3,
    ) -> (DVec3, Option<f64>) {
        let abs_fn = f_n.abs();
        let n = c.normal;
        match self.rolling {
            RollingLaw::None => (DVec3::ZERO, None),
            RollingLaw::Cdt => (
                cdt(
                    rolling_omega(c.rel_omega, n),
                    self.rolling_friction * c.radius * abs_fn,
                ),
                None,
            ),
            RollingLaw::Epsd => {
                let mr = self.rolling_friction * c.radius;
                let kr = 2.25 * kn * mr * mr;
                let cr =
                    self.rolling_damping * 2.0 * (1.4 * c.mass * c.radius * c.radius * kr).sqrt();
                let (t, e_r) = epsd(
                    m_r,
                    n,
                    rolling_omega(c.rel_omega, n),
                    c.dt,
                    kr,
                    cr,
                    mr * abs_fn,
                );
                (t, Some(e_r))
            }
        }
    }

    /// Effective Young's modulus `E*`, Pa.
    pub fn effective_modulus(&self) -> f64 {
        self.e_star
    }

    /// Effective shear modulus `G*`, Pa.
    pub fn effective_shear_modulus(&self) -> f64 {
        self.g_star
    }

    /// The damping ratio `β` used, dimensionless, `≤ 0` (see
    /// [`super::damping::damping_ratio`]: below −1 for the clamped exact damping with
    /// `e < e^{−2}`).
    pub fn damping_ratio(&self) -> f64 {
        self.beta
    }

    /// Whether the total normal force is clamped at zero (not tensile): the
    /// pair's `!tensile`, except for exact damping with `e = 0`, which uses
    /// critical damping without the clamp (see [`super::damping::damping_ratio`]).
    pub fn clamps_normal_force(&self) -> bool {
        self.law.fn_floor == 0.0
    }

    /// The pair properties this model was built from.
    pub fn properties(&self) -> &PairProperties {
        &self.props
    }

    /// Normal stiffness for time-step estimates, N/m: the Hertz tangent
    /// stiffness `2E*√(R*δ)` at overlap `δ` (m), or the linear `k_n`.
    pub fn normal_stiffness(&self, r_star: f64, overlap: f64) -> f64 {
        if self.law.hertz {
            1.5 * self.law.kn_coef * (r_star * overlap).sqrt()
        } else {
            self.law.kn_coef
        }
    }

    /// Contact duration of a head-on impact, s, at relative normal speed
    /// `v_normal` (m/s), effective radius `r_star` (m) and mass `m_star` (kg):
    /// Hertz: the undamped `2.9432 δ_max/v`; linear: the exact damped
    /// duration of the force pulse, `ω₀ = √(k_n/m*)`: unclamped
    /// `π/(ω₀√(1−β²))` (infinite for `β ≤ −1`), clamped `2A(−β)/ω₀` (until
    /// the force reaches zero; `A` in [`super::damping`]).
    pub fn contact_time(&self, r_star: f64, m_star: f64, v_normal: f64) -> f64 {
        if self.law.hertz {
            hertz_contact_time(self.e_star, r_star, m_star, v_normal)
        } else {
            let w0 = (self.law.kn_coef / m_star).sqrt();
            if self.clamps_normal_force() {
                return clamped_pulse_time(self.beta) / w0;
            }
            let r = 1.0 - self.beta * self.beta;
            if r > 0.0 {
                std::f64::consts::PI / (w0 * r.sqrt())
            } else {
                f64::INFINITY
            }
        }
    }
}

/// Hertz and linear laws, clamped and tensile, for tests of the loops that
/// run [`SlidingLaw`] as vector lanes.
#[cfg(test)]
pub(crate) fn sample_laws() -> Vec<SlidingLaw> {
    use super::{Material, NormalLaw};
    let mat = Material {
        youngs_modulus: 5e6,
        poisson_ratio: 0.3,
        density: 2500.0,
    };
    let mut laws = vec![];
    for normal in [NormalLaw::Hertz, NormalLaw::Linear { kn: 2e3, kt: 1e3 }] {
        for tensile in [false, true] {
            let p = PairProperties {
                normal,
                tensile,
                ..PairProperties::default()
            };
            laws.push(*ContactModel::new(&mat, &mat, &p).unwrap().sliding_law());
        }
    }
    laws
}
