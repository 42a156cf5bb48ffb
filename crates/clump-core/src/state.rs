//! The complete dynamic state of a world, for checkpoints.
//!
//! A checkpoint holds everything that evolves: bodies (with the forces of
//! the last evaluation, which the next half kick uses), walls, contact
//! histories, the poses at the last neighbour build and the counters. Static
//! set-up (materials, templates, contact models) comes from the scenario.
//! Restoring rebuilds the neighbour list from the stored build poses, so the
//! resumed run repeats the uninterrupted one bit for bit.

use crate::body::Bodies;
use crate::contact::mdr::SlipProfile;
use crate::contact::ContactHistory;
use crate::neighbor::walls::WallList;
use crate::neighbor::walls::WALL_SLOTS;
use crate::stats::ContactStats;
use crate::step::{rebuild, StepError};
use crate::wall::{Wall, WallLoad};
use crate::world::{World, WorldConfig};
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// Serializable dynamic state of a [`World`].
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct WorldState {
    /// Global settings at the time of saving.
    pub config: WorldConfig,
    /// Steps taken.
    pub step: u64,
    /// Simulated time, s.
    pub time: f64,
    /// Bodies lost so far, by cause.
    pub lost: crate::lost::LostBodies,
    /// Neighbour builds so far.
    pub rebuilds: u64,
    /// Next global body id.
    pub next_id: u64,
    /// Bodies, in storage order.
    pub bodies: Bodies,
    /// Walls (pose and motion).
    pub walls: Vec<Wall>,
    /// Wall loads of the last evaluation.
    pub wall_loads: Vec<WallLoad>,
    /// Statistics of the last evaluation.
    pub stats: ContactStats,
    /// Body poses (centre of mass, world; orientation) at the last neighbour build.
    pub reference_pose: Vec<(DVec3, DQuat)>,
    /// Sphere-pair histories keyed by (lower, higher) global sphere id.
    pub pair_history: Vec<((u64, u64), ContactHistory)>,
    /// Sphere–wall contact slot keys, per sphere in storage order.
    pub wall_key: Vec<[u32; WALL_SLOTS]>,
    /// Sphere–wall contact histories, per sphere in storage order.
    pub wall_hist: Vec<[ContactHistory; WALL_SLOTS]>,
    /// The skin (m) the last neighbour build chose for the motion (0: none
    /// yet; absent from checkpoints of earlier versions).
    #[serde(default)]
    pub adapted_skin: f64,
    /// Step of the last neighbour build.
    #[serde(default)]
    pub built_step: u64,
    /// Per wall: the heat it has given the bodies since the start, J
    /// (empty without heat).
    #[serde(default)]
    pub wall_heat: Vec<f64>,
    /// MDR profiles of the sphere pairs (`tangential = "mdr"`), keyed as
    /// `pair_history`; empty when no law keeps them.
    #[serde(default)]
    pub pair_slip: Vec<((u64, u64), SlipProfile)>,
    /// MDR profiles of the sphere–wall slots, per sphere in storage order;
    /// empty when no law keeps them.
    #[serde(default)]
    pub wall_slip: Vec<[SlipProfile; WALL_SLOTS]>,
    // --- fluid coupling (issue 59): absent unless in use, so checkpoints
    // without a fluid or coupling keep their bytes
    /// The bodies' coupling arrays (external loads, fluid velocity, void
    /// fraction, fluid force; storage order), where any is in use.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub coupling: Option<crate::fluid::BodyCoupling>,
    /// The fluid's uniform velocity (m/s, world frame), which a driver may
    /// have changed, where a fluid is set.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fluid_velocity: Option<DVec3>,
    // --- end fluid coupling
}

impl World {
    /// Captures the dynamic state. Call between steps.
    pub fn save_state(&mut self) -> Result<WorldState, StepError> {
        if !self.phase.forces_ready() {
            self.prepare()?;
        }
        let mut pair_history: Vec<_> = if self.neighbors.history_pending {
            self.neighbors
                .history_map
                .iter()
                .map(|(k, h)| (*k, *h))
                .collect()
        } else {
            let mut map = std::mem::take(&mut self.neighbors.history_map);
            self.neighbors.pairs.save_history(
                &self.spheres.gid,
                self.contact_table.any_reach(),
                &mut map,
            );
            let v = map.drain().collect();
            self.neighbors.history_map = map;
            v
        };
        pair_history.sort_by_key(|e| e.0);
        let mut pair_slip: Vec<_> = if self.neighbors.history_pending {
            self.neighbors
                .slip_map
                .iter()
                .map(|(k, p)| (*k, *p))
                .collect()
        } else {
            let mut map = std::mem::take(&mut self.neighbors.slip_map);
            self.neighbors.pairs.save_slip(&self.spheres.gid, &mut map);
            let v = map.drain().collect();
            self.neighbors.slip_map = map;
            v
        };
        pair_slip.sort_by_key(|e| e.0);
        let wall_slip = self
            .neighbors
            .wall_list
            .slip_per_sphere(self.spheres.len(), self.contact_table.keeps_slip_profile());
        let (wall_key, wall_hist) = self.neighbors.wall_list.per_sphere(self.spheres.len());
        Ok(WorldState {
            bodies: self.bodies.clone(),
            reference_pose: self.neighbors.reference_pose.clone(),
            pair_history,
            wall_key,
            wall_hist,
            pair_slip,
            wall_slip,
            coupling: (!self.bodies.coupling.is_empty()).then(|| self.bodies.coupling.clone()),
            ..self.global_state()
        })
    }

    /// The state's global part (settings, counters, walls, wall loads,
    /// statistics, skin), with no bodies: what every rank of a world split
    /// over ranks holds alike.
    pub(crate) fn global_state(&self) -> WorldState {
        WorldState {
            config: self.config,
            step: self.step,
            time: self.time,
            lost: self.lost,
            rebuilds: self.rebuilds,
            next_id: self.next_id,
            bodies: Bodies::default(),
            walls: self.walls.to_vec(),
            wall_loads: self.walls.loads.clone(),
            stats: self.stats,
            reference_pose: Vec::new(),
            pair_history: Vec::new(),
            wall_key: Vec::new(),
            wall_hist: Vec::new(),
            adapted_skin: self.neighbors.adapted_skin,
            built_step: self.neighbors.built_step,
            wall_heat: self
                .heat
                .as_ref()
                .map_or(Vec::new(), |h| h.wall_heat.clone()),
            pair_slip: Vec::new(),
            wall_slip: Vec::new(),
            coupling: None,
            fluid_velocity: self.fluid.as_ref().map(|f| f.fluid.velocity),
        }
    }

    /// Restores a state saved by [`World::save_state`] into a world built
    /// from the same scenario (same templates, materials and walls).
    pub fn restore_state(&mut self, s: WorldState) -> Result<(), String> {
        self.set_state(s)?;
        rebuild::rebuild(self, false).map_err(|e| e.to_string())?;
        self.rebuilds = self.rebuilds.saturating_sub(1);
        self.phase.forces_evaluated();
        Ok(())
    }

    /// Checks `s` against this world's scenario and takes it, without
    /// building the lists ([`World::restore_state`] builds them whole, a
    /// rank's share builds them for its part).
    pub(crate) fn set_state(&mut self, s: WorldState) -> Result<(), String> {
        if s.walls.len() != self.walls.len() {
            return Err(format!(
                "checkpoint has {} walls, the scenario {}",
                s.walls.len(),
                self.walls.len()
            ));
        }
        if let Some(&t) = s
            .bodies
            .template
            .iter()
            .find(|&&t| t as usize >= self.templates.len())
        {
            return Err(format!(
                "checkpoint refers to template {t}, the scenario has {}",
                self.templates.len()
            ));
        }
        let nb = s.bodies.len();
        let b = &s.bodies;
        let lens = [
            b.template.len(),
            b.position.len(),
            b.velocity.len(),
            b.orientation.len(),
            b.angular_momentum.len(),
            b.angular_velocity.len(),
            b.force.len(),
            b.torque.len(),
            b.mass.len(),
            b.inertia.len(),
            b.force_flag.len(),
            b.torque_flag.len(),
            b.start_step.len(),
        ];
        if lens.iter().any(|&l| l != nb) {
            return Err(format!(
                "checkpoint body arrays have inconsistent lengths ({nb} ids, {lens:?})"
            ));
        }
        let heat_len = if self.heat.is_some() { nb } else { 0 };
        if b.temperature.len() != heat_len || b.heat_source.len() != heat_len {
            return Err(format!(
                "checkpoint has {} body temperatures for {nb} bodies; the scenario {}",
                b.temperature.len(),
                if self.heat.is_some() {
                    "has heat transfer"
                } else {
                    "has none"
                }
            ));
        }
        if let Some(h) = self.heat.as_deref() {
            if s.wall_heat.len() != h.wall_heat.len() {
                return Err("checkpoint wall heat does not match its walls".into());
            }
        }
        if s.wall_loads.len() != s.walls.len() {
            return Err("checkpoint wall loads do not match its walls".into());
        }
        if s.coupling.as_ref().is_some_and(|c| !c.fits(nb)) {
            return Err(format!(
                "checkpoint coupling arrays do not fit its {nb} bodies"
            ));
        }
        for (a, b) in s.walls.iter().zip(&self.walls) {
            let same_kind = match (&a.shape, &b.shape) {
                (
                    crate::wall::WallShape::Mesh { mesh: ma, .. },
                    crate::wall::WallShape::Mesh { mesh: mb, .. },
                ) => ma == mb,
                (x, y) => std::mem::discriminant(x) == std::mem::discriminant(y),
            };
            if a.name != b.name || a.material != b.material || !same_kind {
                return Err(format!(
                    "checkpoint wall '{}' does not match the scenario's wall '{}'",
                    a.name, b.name
                ));
            }
        }
        if s.config.domain != self.config.domain
            || s.config.dt.to_bits() != self.config.dt.to_bits()
        {
            return Err("checkpoint domain or time step differs from the scenario's".into());
        }
        let ns: usize = s
            .bodies
            .template
            .iter()
            .map(|&t| self.templates[t as usize].spheres.len())
            .sum();
        if s.reference_pose.len() != nb || s.wall_key.len() != ns || s.wall_hist.len() != ns {
            return Err("checkpoint arrays have inconsistent lengths".into());
        }
        if !(s.adapted_skin >= 0.0 && s.adapted_skin.is_finite()) || s.built_step > s.step {
            return Err(format!(
                "checkpoint skin {} m (must be finite and >= 0) or last build step {} (at most the step {}) is invalid",
                s.adapted_skin, s.built_step, s.step
            ));
        }
        if let Some(h) = self.heat.as_deref_mut() {
            h.wall_heat = s.wall_heat;
        }
        self.config = s.config;
        self.neighbors.adapted_skin = s.adapted_skin;
        self.neighbors.built_step = s.built_step;
        self.step = s.step;
        self.time = s.time;
        self.lost = s.lost;
        self.rebuilds = s.rebuilds;
        self.next_id = s.next_id;
        self.bodies = s.bodies;
        self.restore_coupling(s.coupling, s.fluid_velocity)?;
        self.walls.list = s.walls;
        self.walls.loads = s.wall_loads;
        self.stats = s.stats;
        self.neighbors.reference_pose = s.reference_pose;
        self.neighbors.history_map = s.pair_history.into_iter().collect();
        self.neighbors.slip_map = s.pair_slip.into_iter().collect();
        self.neighbors.wall_list = WallList::from_per_sphere(&s.wall_key, &s.wall_hist);
        self.neighbors.wall_list.set_slip_per_sphere(&s.wall_slip);
        Ok(())
    }
}
