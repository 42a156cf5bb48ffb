//! Whole-system quantities for the thermo output.

use crate::contact::step_sums::wall_loads;
use crate::exact_sum::ExactSum;
use crate::wall::WallLoad;
use crate::world::World;
use serde::{Deserialize, Serialize};

/// A snapshot of global quantities (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Thermo {
    /// Simulated time, s.
    pub time: f64,
    /// Step number.
    pub step: u64,
    /// Number of bodies.
    pub bodies: usize,
    /// Touching sphere–sphere contacts.
    pub pair_contacts: u64,
    /// Touching sphere–wall contacts.
    pub wall_contacts: u64,
    /// Translational kinetic energy Σ ½ m |v|², J.
    pub kinetic_translational: f64,
    /// Rotational kinetic energy Σ ½ ω·L (full clump inertia), J.
    pub kinetic_rotational: f64,
    /// Elastic energy stored in contacts, J.
    pub elastic: f64,
    /// Gravitational potential energy −Σ m g·x, J (zero at the origin).
    pub potential: f64,
    /// Largest overlap / smaller radius over all contacts.
    pub max_overlap_ratio: f64,
    /// Bodies lost so far, all causes (see [`crate::lost::LostBodies`]).
    pub lost_bodies: u64,
    /// Load on each wall (force and torque exerted by the particles), world frame.
    pub wall_loads: Vec<WallLoad>,
    /// The bodies' temperatures and heat, when the world has heat.
    pub heat: Option<HeatThermo>,
    /// Total fluid force on the bodies of the last force evaluation (drag,
    /// buoyancy, pressure gradient), N, world frame, when a fluid is set.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fluid_force: Option<glam::DVec3>,
}

/// Whole-system thermal quantities (SI units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HeatThermo {
    /// Mean body temperature, K (NaN without bodies).
    pub mean_temperature: f64,
    /// Lowest body temperature, K (NaN without bodies).
    pub min_temperature: f64,
    /// Highest body temperature, K (NaN without bodies).
    pub max_temperature: f64,
    /// Heat content Σ m c_p T of the bodies (from 0 K), J.
    pub heat_content: f64,
    /// Per wall: heat flow from the wall into the bodies in the last step, W.
    pub wall_flow: Vec<f64>,
    /// Per wall: heat given to the bodies since the start, J.
    pub wall_heat: Vec<f64>,
    /// The last step's largest `dt Σ H / (m c_p)` (stable at most 1).
    pub stability: f64,
}

/// The bodies' energies as exact sums ([`crate::exact_sum`]): translational
/// and rotational kinetic, gravitational potential.
pub(crate) type BodyEnergySums = [ExactSum; 3];

impl World {
    /// Global quantities at the current step. The energies are exact sums
    /// of the per-body and per-contact terms, correctly rounded (T-73):
    /// the same bits in any order, on any number of threads or ranks. The
    /// elastic energy and wall loads are exact when the step that ended
    /// here made the exact sums (every step before an event of a run,
    /// [`crate::contact::step_sums::StepSums::request`]); otherwise they
    /// are the step's statistics, summed by chunk in storage order.
    pub fn thermo(&self) -> Thermo {
        let [kt, kr, pe] = self.body_energy_sums(None);
        let sums = self.neighbors.records.sums.at_step(self.step);
        let extra = self.body_extra_sums(None);
        Thermo {
            time: self.time,
            step: self.step,
            bodies: self.bodies.len(),
            pair_contacts: self.stats.pair_contacts,
            wall_contacts: self.stats.wall_contacts,
            kinetic_translational: kt.value(),
            kinetic_rotational: kr.value(),
            elastic: sums
                .as_ref()
                .map_or(self.stats.elastic_energy, |s| s.0.value()),
            potential: pe.value(),
            max_overlap_ratio: self.stats.max_overlap_ratio,
            lost_bodies: self.lost.total(),
            wall_loads: sums.map_or_else(|| self.walls.loads.clone(), |s| wall_loads(&s.1)),
            heat: self.heat_thermo_of(&extra, self.bodies.len() as u64),
            fluid_force: self.fluid_force_of(&extra),
        }
    }

    /// Asks the step that ends at world step `at` (`None`: none) to make
    /// the exact contact sums that [`World::thermo`] reports (a driver
    /// asks it of the step before each event; it costs three integer
    /// additions per contact term in that step only).
    pub fn request_exact_sums(&mut self, at: Option<u64>) {
        self.neighbors.records.sums.request(at);
    }

    /// The bodies' energy sums (of the bodies of `mask` only, when given).
    pub(crate) fn body_energy_sums(&self, mask: Option<&[bool]>) -> BodyEnergySums {
        let b = &self.bodies;
        let g = self.config.gravity;
        let mut s = BodyEnergySums::default();
        for i in (0..b.len()).filter(|&i| mask.map_or(true, |m| m[i])) {
            s[0].add(0.5 * b.mass[i] * b.velocity[i].length_squared());
            s[1].add(0.5 * b.angular_velocity[i].dot(b.angular_momentum[i]));
            s[2].add(-(b.mass[i] * g.dot(b.position[i])));
        }
        s
    }

    /// The temperature and heat sums and the fluid force sums of the
    /// bodies (of `mask` only, when given), when the world has heat or a
    /// fluid (T-73: the same bits in any order).
    pub(crate) fn body_extra_sums(&self, mask: Option<&[bool]>) -> BodyExtraSums {
        let mut x = BodyExtraSums::default();
        let keep = |i: usize| mask.map_or(true, |m| m[i]);
        if self.heat.is_some() {
            for (b, &tb) in self.bodies.temperature.iter().enumerate() {
                if keep(b) {
                    x.sums[0].add(tb);
                    x.sums[1].add(self.heat_capacity(b) * tb);
                    x.lo = x.lo.min(tb);
                    x.hi = x.hi.max(tb);
                }
            }
        }
        if self.fluid().is_some() {
            for (b, f) in self.fluid_forces().iter().enumerate() {
                if keep(b) {
                    (0..3).for_each(|k| x.sums[2 + k].add(f[k]));
                }
            }
        }
        x
    }

    /// The thermal part of [`World::thermo`] from the sums `x` of `n`
    /// bodies (the walls' heat flows are every rank's, T-94).
    pub(crate) fn heat_thermo_of(&self, x: &BodyExtraSums, n: u64) -> Option<HeatThermo> {
        let h = self.heat.as_deref()?;
        let none = n == 0;
        Some(HeatThermo {
            mean_temperature: if none {
                f64::NAN
            } else {
                x.sums[0].value() / n as f64
            },
            min_temperature: if none { f64::NAN } else { x.lo },
            max_temperature: if none { f64::NAN } else { x.hi },
            heat_content: x.sums[1].value(),
            wall_flow: h.wall_flow.clone(),
            wall_heat: h.wall_heat.clone(),
            stability: h.stability,
        })
    }

    /// The total fluid force of [`World::thermo`] from the sums `x`.
    pub(crate) fn fluid_force_of(&self, x: &BodyExtraSums) -> Option<glam::DVec3> {
        self.fluid()
            .map(|_| glam::DVec3::from_array(std::array::from_fn(|k| x.sums[2 + k].value())))
    }
}

/// The bodies' sums of [`World::body_extra_sums`]: temperature, heat
/// content, fluid force (x, y, z), and the lowest and highest temperature.
#[derive(Debug, Clone)]
pub(crate) struct BodyExtraSums {
    /// Σ T, Σ m c T, Σ f_x, Σ f_y, Σ f_z.
    pub sums: [ExactSum; 5],
    /// Lowest temperature (+∞ without bodies).
    pub lo: f64,
    /// Highest temperature (−∞ without bodies).
    pub hi: f64,
}

impl Default for BodyExtraSums {
    fn default() -> Self {
        BodyExtraSums {
            sums: Default::default(),
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
        }
    }
}
