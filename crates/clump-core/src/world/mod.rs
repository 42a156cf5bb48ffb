//! Everything one simulation owns, and how to set it up.

use crate::body::{Bodies, BodyInit};
use crate::boundary::Domain;
use crate::contact::{ContactTable, Material};
use crate::lost::LostBodies;
use crate::multi_contact::MultiContact;
use crate::neighbor::NeighborState;
use crate::rotation::RotationScheme;
use crate::shape::{ClumpTemplate, TemplateSet};
use crate::sphere::Spheres;
use crate::stats::ContactStats;
use crate::wall::{TriMesh, Wall, WallLoad, WallSet, WallShape};
use glam::DVec3;
use serde::{Deserialize, Serialize};
use thiserror::Error;

pub(crate) mod props;
mod scratch;
pub(crate) use scratch::{Scratch, StepPhase};

/// Added-mass model (docs/theory.md T-14): the body's inertia in the kicks is scaled by
/// `1 + coefficient · fluid_density / body_density`. Gravity still acts on the
/// true mass.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct AddedMass {
    /// Added-mass coefficient `CAdd` (0.5 for a sphere in potential flow).
    pub coefficient: f64,
    /// Fluid density, kg/m³.
    pub fluid_density: f64,
}

/// Global settings of a simulation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WorldConfig {
    /// The domain and its periodic axes.
    pub domain: Domain,
    /// Gravitational acceleration, world frame, m/s².
    pub gravity: DVec3,
    /// Time step, s.
    pub dt: f64,
    /// Rotation scheme for the free-rotation sub-step.
    pub rotation: RotationScheme,
    /// Added-mass model.
    pub added_mass: AddedMass,
    /// Verlet skin, m. `None`: adapted to the motion at every neighbour
    /// build; see [`World::skin`].
    pub skin: Option<f64>,
    /// Several-contact treatment between two bodies.
    pub multi_contact: MultiContact,
}

/// Errors while setting up a world.
#[derive(Debug, Error)]
pub enum WorldError {
    /// A reference to a missing template or material.
    #[error("{0}")]
    BadReference(String),
    /// A value given to a steering method is out of range.
    #[error("{0}")]
    BadValue(String),
}

/// The state of one simulation: the sets the step pipeline works on, each
/// owning its data (see ARCHITECTURE.md for which stage touches which).
pub struct World {
    /// Global settings.
    pub config: WorldConfig,
    /// Materials.
    pub materials: Vec<Material>,
    /// Contact models per material pair.
    pub contact_table: ContactTable,
    /// Clump templates (body frame) with their materials.
    pub templates: TemplateSet,
    /// The bodies: the one owner of body state, read through
    /// [`World::bodies`] and changed only through the world's methods
    /// ([`crate::steer`]), which keep what the step derives from it
    /// consistent.
    pub(crate) bodies: Bodies,
    /// The walls with their meshes and loads.
    pub walls: WallSet,
    /// Steps taken.
    pub step: u64,
    /// Simulated time, s.
    pub time: f64,
    /// Bodies that left the simulation, by cause.
    pub lost: LostBodies,
    /// Aggregates of the last force evaluation.
    pub stats: ContactStats,
    /// Number of neighbour-list builds so far.
    pub rebuilds: u64,
    /// Wall-clock time spent in each stage of the step pipeline so far (a
    /// profiling breakdown; not part of the simulated state).
    pub stage_times: crate::stats::StageTimes,
    /// Global id of the next body added.
    pub(crate) next_id: u64,
    /// The spheres, derived from the bodies and templates.
    pub(crate) spheres: Spheres,
    /// Neighbour lists and the contact store (springs, wall slots,
    /// history, the records of the last step asked to keep them).
    pub(crate) neighbors: NeighborState,
    /// Where the world is in its step (see [`StepPhase`]).
    pub(crate) phase: StepPhase,
    /// Working arrays of the step, reused so that steps do not allocate,
    /// and the learned thread balance; never part of the simulated state.
    pub(crate) scratch: Scratch,
    /// This rank's part when the world is split over ranks
    /// ([`World::partition`]); `None` in one process.
    pub(crate) part: Option<Box<crate::partition::Part>>,
    /// Heat transfer ([`World::enable_heat`]); `None`: the world has no
    /// temperatures and the step no heat stage.
    pub heat: Option<Box<crate::heat::Heat>>,
    /// The fluid the bodies are in, with its per-template data
    /// ([`World::set_fluid`]); `None`: no fluid force.
    pub(crate) fluid: Option<crate::fluid::FluidState>,
}

impl World {
    /// The bodies (storage order): position, velocity, orientation,
    /// angular momentum and velocity, force, torque, mass properties and
    /// flags, world frame, SI units. Read-only: change them through the
    /// steering methods ([`crate::steer`]).
    pub fn bodies(&self) -> &Bodies {
        &self.bodies
    }

    /// A new, empty world.
    pub fn new(config: WorldConfig, materials: Vec<Material>, contact_table: ContactTable) -> Self {
        World {
            config,
            materials,
            contact_table,
            templates: TemplateSet::default(),
            bodies: Bodies::default(),
            walls: WallSet::default(),
            step: 0,
            time: 0.0,
            lost: LostBodies::default(),
            stats: ContactStats::default(),
            rebuilds: 0,
            stage_times: Default::default(),
            next_id: 1,
            spheres: Spheres::default(),
            neighbors: NeighborState::default(),
            phase: StepPhase::default(),
            scratch: Scratch::default(),
            part: None,
            heat: None,
            fluid: None,
        }
    }

    /// Adds a template whose spheres are of material `material`; returns its index.
    pub fn add_template(
        &mut self,
        template: ClumpTemplate,
        material: u16,
    ) -> Result<u32, WorldError> {
        if material as usize >= self.materials.len() {
            return Err(WorldError::BadReference(format!(
                "template '{}' uses material {material}, which does not exist",
                template.name
            )));
        }
        if let Some(h) = self.heat.as_deref_mut() {
            // a template added after the heat was turned on (a scaled copy
            // of an insert's mix) takes its base's values by
            // [`World::inherit_template_heat`]
            h.model.template_temperature.push(f64::NAN);
            h.model.template_source.push(0.0);
        }
        if let Some(f) = &mut self.fluid {
            f.templates.push(crate::fluid::TemplateFluid::of(&template));
        }
        Ok(self.templates.push(template, material))
    }

    /// Gives template `t` the initial temperature and source density of
    /// template `base` (a scaled copy of it); nothing without heat.
    pub fn inherit_template_heat(&mut self, t: u32, base: u32) {
        if let Some(h) = self.heat.as_deref_mut() {
            let m = &mut h.model;
            let (t, base) = (t as usize, base as usize);
            if t < m.template_temperature.len() && base < m.template_temperature.len() {
                m.template_temperature[t] = m.template_temperature[base];
                m.template_source[t] = m.template_source[base];
            }
        }
    }

    /// Adds a wall; returns its index.
    pub fn add_wall(&mut self, wall: Wall) -> Result<usize, WorldError> {
        if wall.material as usize >= self.materials.len() {
            return Err(WorldError::BadReference(format!(
                "wall '{}' uses material {}, which does not exist",
                wall.name, wall.material
            )));
        }
        if let WallShape::Mesh { mesh, .. } = wall.shape {
            if mesh as usize >= self.walls.meshes.len() {
                return Err(WorldError::BadReference(format!(
                    "wall '{}' uses mesh {mesh}, which does not exist",
                    wall.name
                )));
            }
        }
        if self.walls.len() >= crate::wall::MAX_WALLS {
            return Err(WorldError::BadReference(format!(
                "too many walls (at most {})",
                crate::wall::MAX_WALLS
            )));
        }
        self.walls.list.push(wall);
        self.walls.loads.push(WallLoad::default());
        if let Some(h) = self.heat.as_deref_mut() {
            h.wall_flow.push(0.0);
            h.wall_heat.push(0.0);
        }
        self.phase.forces_changed();
        Ok(self.walls.len() - 1)
    }

    /// Adds a triangle mesh for [`WallShape::Mesh`] walls; returns its index.
    pub fn add_mesh(&mut self, mesh: TriMesh) -> u32 {
        self.walls.meshes.push(mesh);
        self.walls.meshes.len() as u32 - 1
    }

    /// Adds a body; returns its global id.
    pub fn add_body(&mut self, init: &BodyInit) -> Result<u64, WorldError> {
        self.templates.get(init.template as usize).ok_or_else(|| {
            WorldError::BadReference(format!(
                "body uses template {}, which does not exist",
                init.template
            ))
        })?;
        let id = self.next_id;
        self.next_id += 1;
        // a split world: every rank counts the id, the new body's owner keeps it
        if !self.keeps_new_body(init.position, id) {
            self.phase.topology_changed();
            return Ok(id);
        }
        let t = &self.templates[init.template as usize];
        self.bodies.push(id, init, t.mass, t.principal_inertia);
        if let Some(h) = self.heat.as_deref() {
            let (temperature, source) = heat_of_new_body(
                &h.model,
                &self.materials,
                &self.templates,
                init.template as usize,
            );
            self.bodies.temperature.push(temperature);
            self.bodies.heat_source.push(source);
        }
        self.phase.topology_changed();
        Ok(id)
    }

    /// The Verlet skin in use, m: the configured one; by default the one
    /// the last neighbour build chose for the motion
    /// ([`crate::neighbor::skin::adapted_skin`]), and before the first build
    /// [`crate::neighbor::skin::SKIN_DEFAULT`] times the smallest sphere
    /// radius of any template (never zero).
    ///
    /// With JKR cohesion the skin is at least twice the largest critical
    /// separation `δ_c` ([`ContactTable::max_reach`]), so that a contact
    /// stretched to `δ_c` stays in the pair and wall lists.
    pub fn skin(&self) -> f64 {
        let s = self.config.skin.unwrap_or_else(|| {
            if self.neighbors.adapted_skin > 0.0 {
                self.neighbors.adapted_skin
            } else {
                crate::neighbor::skin::SKIN_DEFAULT * self.min_radius()
            }
        });
        if self.contact_table.any_reach() {
            s.max(2.0 * self.contact_table.max_reach(self.max_radius()))
        } else {
            s
        }
    }

    /// Smallest sphere radius of any template, m (1 mm without templates).
    pub fn min_radius(&self) -> f64 {
        let r = self
            .templates
            .radius
            .iter()
            .cloned()
            .fold(f64::INFINITY, f64::min);
        if r.is_finite() {
            r
        } else {
            1e-3
        }
    }

    /// The thickest skin the adaptive skin may choose, m: [`SKIN_MAX`]
    /// times the largest radius, but thin enough that every periodic axis
    /// keeps three neighbour cells of `2 r_max + skin`, and never below the
    /// thinnest ([`crate::neighbor::skin::SKIN_MIN`] times the smallest
    /// radius).
    ///
    /// [`SKIN_MAX`]: crate::neighbor::skin::SKIN_MAX
    pub fn max_adapted_skin(&self) -> f64 {
        use crate::neighbor::skin::{SKIN_MAX, SKIN_MIN};
        let r_max = self.max_radius();
        let d = &self.config.domain;
        let size = d.size();
        let mut s = SKIN_MAX * r_max;
        for a in 0..3 {
            if d.periodic[a] {
                s = s.min(size[a] / 3.0 - 2.0 * r_max);
            }
        }
        s.max(SKIN_MIN * self.min_radius())
    }

    /// The skin (m) the adaptive skin chooses for the next lists when the
    /// spheres moved at most `d_max` (m) since the last build
    /// ([`crate::neighbor::skin::adapted_skin`], within
    /// [`World::max_adapted_skin`]).
    pub(crate) fn adapted_skin(&self, d_max: f64) -> f64 {
        crate::neighbor::skin::adapted_skin(
            self.min_radius(),
            self.max_adapted_skin(),
            d_max,
            self.step - self.neighbors.built_step,
            self.max_template_spheres(),
        )
    }

    /// Bodies per chunk of the per-step loops
    /// ([`crate::par::affinity::body_chunk`]), from the templates.
    pub(crate) fn body_chunk(&self) -> usize {
        crate::par::affinity::body_chunk(self.max_template_spheres())
    }

    /// Most spheres in any template (1 without templates): the skin's cost
    /// model reads it ([`crate::neighbor::skin::adapted_skin`]).
    pub fn max_template_spheres(&self) -> usize {
        self.templates.max_spheres()
    }

    /// Largest sphere radius of any template, m.
    pub fn max_radius(&self) -> f64 {
        self.templates.radius.iter().cloned().fold(0.0, f64::max)
    }

    /// The spheres (derived from the bodies at the current step).
    pub fn spheres(&self) -> &Spheres {
        &self.spheres
    }

    /// Candidate and touching sphere pairs.
    pub fn pairs(&self) -> &crate::neighbor::PairList {
        &self.neighbors.pairs
    }

    /// Storage index of the body with global id `id`, if present (linear search).
    pub fn body_index(&self, id: u64) -> Option<usize> {
        self.bodies.id.iter().position(|&x| x == id)
    }
}

/// The initial temperature (K) and source power (W) of a new body of
/// template `t`: the template's, its source density times the body's
/// volume, `m / ρ`.
fn heat_of_new_body(
    model: &crate::heat::HeatModel,
    materials: &[Material],
    templates: &TemplateSet,
    t: usize,
) -> (f64, f64) {
    let rho = materials[templates.material(t) as usize].density;
    let q = model.template_source.get(t).copied().unwrap_or(0.0);
    let power = if q == 0.0 {
        0.0
    } else {
        q * templates[t].mass / rho
    };
    let temperature = model
        .template_temperature
        .get(t)
        .copied()
        .unwrap_or(f64::NAN);
    (temperature, power)
}

impl World {
    /// Turns heat transfer on (docs/theory.md T-53 … T-57): every body,
    /// present or added later, gets its template's temperature and source.
    /// Call after the templates and walls are added. Fails when a
    /// template's material has no thermal properties or a positive
    /// specific heat, a template has no temperature above 0 K, or a wall
    /// temperature is not above 0 K.
    pub fn enable_heat(&mut self, model: crate::heat::HeatModel) -> Result<(), WorldError> {
        if model.materials.len() != self.materials.len() {
            return Err(WorldError::BadValue(format!(
                "the heat model lists {} materials, the world has {}",
                model.materials.len(),
                self.materials.len()
            )));
        }
        for (m, t) in model.materials.iter().enumerate() {
            if let Some(t) = t {
                if !(t.conductivity >= 0.0 && t.conductivity.is_finite()) {
                    return Err(WorldError::BadValue(format!(
                        "material {m}: thermal conductivity must be >= 0 W/(m K), got {}",
                        t.conductivity
                    )));
                }
            }
        }
        for t in 0..self.templates.len() {
            let m = self.templates.material(t);
            let cp = model.materials[m as usize].map(|x| x.specific_heat);
            if !cp.is_some_and(|c| c > 0.0 && c.is_finite()) {
                return Err(WorldError::BadValue(format!(
                    "template '{}': its material {m} needs a specific heat > 0 J/(kg K)",
                    self.templates[t].name
                )));
            }
            let temp = model
                .template_temperature
                .get(t)
                .copied()
                .unwrap_or(f64::NAN);
            if !(temp > 0.0 && temp.is_finite()) {
                return Err(WorldError::BadValue(format!(
                    "template '{}': temperature must be > 0 K, got {temp}",
                    self.templates[t].name
                )));
            }
            let q = model.template_source.get(t).copied().unwrap_or(0.0);
            if !q.is_finite() {
                return Err(WorldError::BadValue(format!(
                    "template '{}': heat source must be finite, got {q}",
                    self.templates[t].name
                )));
            }
        }
        for (w, t) in model.wall_temperature.iter().enumerate() {
            if let Some(t) = t {
                if !(*t > 0.0 && t.is_finite()) {
                    return Err(WorldError::BadValue(format!(
                        "wall {w}: temperature must be > 0 K, got {t}"
                    )));
                }
            }
        }
        let n = self.bodies.len();
        self.bodies.temperature.clear();
        self.bodies.heat_source.clear();
        for b in 0..n {
            let (t, q) = heat_of_new_body(
                &model,
                &self.materials,
                &self.templates,
                self.bodies.template[b] as usize,
            );
            self.bodies.temperature.push(t);
            self.bodies.heat_source.push(q);
        }
        self.heat = Some(Box::new(crate::heat::Heat::new(model, self.walls.len())));
        Ok(())
    }

    /// The heat capacity `m c_p` of body `b`, J/K (0 without heat).
    pub fn heat_capacity(&self, b: usize) -> f64 {
        let Some(h) = self.heat.as_deref() else {
            return 0.0;
        };
        let m = self.templates.material(self.bodies.template[b] as usize);
        let cp = h.model.materials[m as usize].map_or(0.0, |t| t.specific_heat);
        self.bodies.mass[b] * cp
    }
}
