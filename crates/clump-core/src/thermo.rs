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
            heat: self.heat_thermo(),
            fluid_force: self
                .fluid()
                .map(|_| self.fluid_forces().iter().copied().sum()),
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

    /// The thermal part of [`World::thermo`]; sums in storage order.
    fn heat_thermo(&self) -> Option<HeatThermo> {
        let h = self.heat.as_deref()?;
        let t = &self.bodies.temperature;
        let n = t.len();
        let (mut sum, mut lo, mut hi, mut content) = (0.0, f64::INFINITY, f64::NEG_INFINITY, 0.0);
        for (b, &tb) in t.iter().enumerate() {
            sum += tb;
            lo = lo.min(tb);
            hi = hi.max(tb);
            content += self.heat_capacity(b) * tb;
        }
        let none = n == 0;
        Some(HeatThermo {
            mean_temperature: if none { f64::NAN } else { sum / n as f64 },
            min_temperature: if none { f64::NAN } else { lo },
            max_temperature: if none { f64::NAN } else { hi },
            heat_content: content,
            wall_flow: h.wall_flow.clone(),
            wall_heat: h.wall_heat.clone(),
            stability: h.stability,
        })
    }
}
