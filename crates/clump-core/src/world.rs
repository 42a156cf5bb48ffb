//! Everything one simulation owns, and how to set it up.

use crate::body::{Bodies, BodyInit};
use crate::boundary::Domain;
use crate::contact::{ContactModel, Material, PairProperties};
use crate::multi_contact::MultiContact;
use crate::neighbor::{CellGrid, PairList};
use crate::rotation::RotationScheme;
use crate::shape::ClumpTemplate;
use crate::sphere::Spheres;
use crate::wall::{TriMesh, Wall, WallLoad, WallShape};
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Added-mass model (seed 000): the body's inertia in the kicks is scaled by
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

/// Contact models for every pair of materials (symmetric table).
#[derive(Debug, Clone, Default)]
pub struct ContactTable {
    n: usize,
    models: Vec<ContactModel>,
    /// Some model has a rolling couple.
    rolling: bool,
}

impl ContactTable {
    /// Builds the table; `props(a, b)` gives the pair properties of materials `a`, `b`.
    pub fn new(
        materials: &[Material],
        mut props: impl FnMut(usize, usize) -> PairProperties,
    ) -> Result<Self, WorldError> {
        let n = materials.len();
        let mut models = Vec::with_capacity(n * n);
        for a in 0..n {
            for b in 0..n {
                let (lo, hi) = (a.min(b), a.max(b));
                let (mut ma, mut mb) = (materials[lo], materials[hi]);
                if ma.youngs_modulus.is_infinite() && mb.youngs_modulus.is_infinite() {
                    // Two rigid (wall) materials never touch each other; the
                    // entry only fills the table.
                    ma.youngs_modulus = 1.0;
                    mb.youngs_modulus = 1.0;
                    // a wall material may have density 0 (it never moves)
                    ma.density = 1.0;
                    mb.density = 1.0;
                }
                let m = ContactModel::new(&ma, &mb, &props(lo, hi))
                    .map_err(|e| WorldError::Contact(format!("materials {lo} and {hi}: {e}")))?;
                models.push(m);
            }
        }
        let rolling = models.iter().any(|m| m.has_rolling());
        Ok(Self { n, models, rolling })
    }

    /// The model for materials `a` and `b`.
    #[inline(always)]
    pub fn get(&self, a: u16, b: u16) -> &ContactModel {
        &self.models[a as usize * self.n + b as usize]
    }

    /// Index of the model for materials `a` and `b` (see [`Self::by_index`]).
    #[inline(always)]
    pub fn index(&self, a: u16, b: u16) -> u32 {
        (a as usize * self.n + b as usize) as u32
    }

    /// The model at `index` (from [`Self::index`]).
    #[inline(always)]
    pub fn by_index(&self, index: u32) -> &ContactModel {
        &self.models[index as usize]
    }

    /// Whether some model has a rolling couple.
    pub fn any_rolling(&self) -> bool {
        self.rolling
    }
}

/// Errors while setting up a world.
#[derive(Debug, Error)]
pub enum WorldError {
    /// A contact model could not be built.
    #[error("contact model: {0}")]
    Contact(String),
    /// A reference to a missing template or material.
    #[error("{0}")]
    BadReference(String),
    /// The neighbour grid could not be built.
    #[error("neighbour grid: {0}")]
    Grid(String),
}

/// Aggregates from the last force evaluation (for thermo output).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactStats {
    /// Touching sphere–sphere pairs.
    pub pair_contacts: u64,
    /// Touching sphere–wall contacts.
    pub wall_contacts: u64,
    /// Elastic energy in all contacts, J.
    pub elastic_energy: f64,
    /// Largest overlap divided by the smaller radius of the contact.
    pub max_overlap_ratio: f64,
    /// Global ids of the two bodies of the contact with the largest overlap
    /// ratio (lower storage chunk first on ties); for a sphere–wall contact
    /// the second entry is 0 and [`ContactStats::max_overlap_wall`] names the wall.
    #[serde(default)]
    pub max_overlap_bodies: [u64; 2],
    /// Wall index + 1 of the contact with the largest overlap ratio when it is
    /// a sphere–wall contact, 0 when it is a sphere–sphere contact (or none).
    #[serde(default)]
    pub max_overlap_wall: u32,
    /// Kinetic energy of all bodies at the end of the step, Σ ½ m v·v + ½ ω·L
    /// (after the second half kick, which the gather applies; world frame),
    /// J. Not finite when some body's state is not finite.
    #[serde(default)]
    pub kinetic_energy: f64,
    /// Total mass of the bodies, kg.
    #[serde(default)]
    pub total_mass: f64,
    /// Largest kinetic energy of a single body at the end of the step, J.
    #[serde(default)]
    pub max_body_kinetic_energy: f64,
    /// Global id of the body with the largest kinetic energy (0 = no bodies).
    #[serde(default)]
    pub max_kinetic_body: u64,
    /// Global id of the first body (storage order) whose position, velocity,
    /// angular momentum, force or torque is NaN or infinite; 0 when all are finite.
    #[serde(default)]
    pub non_finite_body: u64,
}

impl ContactStats {
    /// Folds the statistics of the next chunk (in chunk order) into `self`:
    /// counts and energies add up, maxima keep the earlier chunk on ties and
    /// the first non-finite body is kept. Deterministic for a fixed chunking.
    pub fn merge(&mut self, s: &ContactStats) {
        self.pair_contacts += s.pair_contacts;
        self.wall_contacts += s.wall_contacts;
        self.elastic_energy += s.elastic_energy;
        self.kinetic_energy += s.kinetic_energy;
        self.total_mass += s.total_mass;
        if s.max_overlap_ratio > self.max_overlap_ratio {
            self.max_overlap_ratio = s.max_overlap_ratio;
            self.max_overlap_bodies = s.max_overlap_bodies;
            self.max_overlap_wall = s.max_overlap_wall;
        }
        if s.max_body_kinetic_energy > self.max_body_kinetic_energy {
            self.max_body_kinetic_energy = s.max_body_kinetic_energy;
            self.max_kinetic_body = s.max_kinetic_body;
        }
        if self.non_finite_body == 0 {
            self.non_finite_body = s.non_finite_body;
        }
    }
}

/// Per-sphere wall-contact slots (history carried while a contact persists).
pub const WALL_SLOTS: usize = 4;

/// The state of one simulation.
pub struct World {
    /// Global settings.
    pub config: WorldConfig,
    /// Materials.
    pub materials: Vec<Material>,
    /// Contact models per material pair.
    pub contact_table: ContactTable,
    /// Clump templates (body frame).
    pub templates: Vec<ClumpTemplate>,
    /// Material of each template's spheres.
    pub template_material: Vec<u16>,
    /// The bodies.
    pub bodies: Bodies,
    /// The walls.
    pub walls: Vec<Wall>,
    /// Triangle meshes that [`WallShape::Mesh`] walls refer to (static
    /// geometry from the scenario, mesh frame; not checkpointed).
    pub meshes: Vec<TriMesh>,
    /// Load on each wall from the last force evaluation.
    pub wall_loads: Vec<WallLoad>,
    /// Steps taken.
    pub step: u64,
    /// Simulated time, s.
    pub time: f64,
    /// Bodies removed because they left the domain.
    pub lost_bodies: u64,
    /// Aggregates of the last force evaluation.
    pub stats: ContactStats,
    /// Number of neighbour-list builds so far.
    pub rebuilds: u64,
    /// Wall-clock time spent in each stage of the step pipeline so far (a
    /// profiling breakdown; not part of the simulated state).
    pub stage_times: crate::step::StageTimes,
    pub(crate) next_id: u64,
    pub(crate) spheres: Spheres,
    pub(crate) pairs: PairList,
    /// The wall Verlet list: the spheres with a wall to test, and their
    /// sphere–wall contact slots.
    pub(crate) wall_list: crate::neighbor::walls::WallList,
    /// Walls (< 64) that have not moved since the wall list was built: only
    /// these may be left out of a sphere's entry (when one starts to move,
    /// the list is built again).
    pub(crate) wall_cull: u64,
    /// The skin (m) the last neighbour build chose for the motion (0: none
    /// yet); used unless the configuration fixes the skin.
    pub(crate) adapted_skin: f64,
    /// Step of the last neighbour build.
    pub(crate) built_step: u64,
    /// Cumulative per-body cost estimate of the gather (one unit per sphere,
    /// more for a sphere with a wall nearby), `len = bodies + 1`; built with
    /// the wall lists. Splits the per-body loops between threads (see
    /// `step::affinity`).
    pub(crate) body_cost: Vec<u64>,
    /// How the first half step, the pair loop and the gather share their
    /// chunks between threads (learned; never affects results).
    pub(crate) balance: [crate::step::affinity::Balance; 3],
    pub(crate) template_first: Vec<u32>,
    pub(crate) template_offset: Vec<DVec3>,
    pub(crate) template_radius: Vec<f64>,
    pub(crate) reference_position: Vec<DVec3>,
    pub(crate) reference_pose: Vec<(DVec3, DQuat)>,
    pub(crate) history_map: crate::neighbor::pairs::HistoryMap,
    pub(crate) grid: CellGrid,
    pub(crate) topology_dirty: bool,
    /// The first half of the current step is done (fused into the previous
    /// step's gather, inside [`World::run`]), with whether a sphere then
    /// moved more than half the skin. None between public calls.
    pub(crate) first_half_done: Option<bool>,
    pub(crate) forces_ready: bool,
    pub(crate) scratch_perm: Vec<u32>,
    /// Rebuild scratch (reused, so rebuilds do not allocate once warm): which
    /// bodies stay, the permuted bodies, the previous wall list, and per
    /// sphere the entry of that list whose contact slots it continues.
    pub(crate) scratch_keep: Vec<bool>,
    pub(crate) scratch_bodies: Bodies,
    pub(crate) scratch_wall_list: crate::neighbor::walls::WallList,
    pub(crate) scratch_wall_carry: Vec<u32>,
    pub(crate) scratch_wall_live: Vec<u32>,
    pub(crate) scratch_keys: Vec<(u64, u64, u32)>,
    pub(crate) chunk_stats: Vec<ContactStats>,
    pub(crate) chunk_pair_stats: Vec<ContactStats>,
    /// Per body: the pair stage summed its column (`PairBody::col`)
    /// this step.
    pub(crate) body_ready: Vec<bool>,
    pub(crate) chunk_wall_loads: Vec<WallLoad>,
}

impl World {
    /// A new, empty world.
    pub fn new(config: WorldConfig, materials: Vec<Material>, contact_table: ContactTable) -> Self {
        World {
            config,
            materials,
            contact_table,
            templates: Vec::new(),
            template_material: Vec::new(),
            bodies: Bodies::default(),
            walls: Vec::new(),
            meshes: Vec::new(),
            wall_loads: Vec::new(),
            step: 0,
            time: 0.0,
            lost_bodies: 0,
            stats: ContactStats::default(),
            rebuilds: 0,
            stage_times: Default::default(),
            next_id: 1,
            spheres: Spheres::default(),
            pairs: PairList::default(),
            wall_list: Default::default(),
            wall_cull: 0,
            adapted_skin: 0.0,
            built_step: 0,
            body_cost: Vec::new(),
            balance: Default::default(),
            template_first: vec![0],
            template_offset: Vec::new(),
            template_radius: Vec::new(),
            reference_position: Vec::new(),
            reference_pose: Vec::new(),
            history_map: Default::default(),
            grid: CellGrid::default(),
            topology_dirty: true,
            first_half_done: None,
            forces_ready: false,
            scratch_perm: Vec::new(),
            scratch_keep: Vec::new(),
            scratch_bodies: Bodies::default(),
            scratch_wall_list: Default::default(),
            scratch_wall_carry: Vec::new(),
            scratch_wall_live: Vec::new(),
            scratch_keys: Vec::new(),
            chunk_stats: Vec::new(),
            chunk_pair_stats: Vec::new(),
            body_ready: Vec::new(),
            chunk_wall_loads: Vec::new(),
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
        for s in &template.spheres {
            self.template_offset.push(s.center);
            self.template_radius.push(s.radius);
        }
        self.template_first.push(self.template_offset.len() as u32);
        self.templates.push(template);
        self.template_material.push(material);
        Ok(self.templates.len() as u32 - 1)
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
            if mesh as usize >= self.meshes.len() {
                return Err(WorldError::BadReference(format!(
                    "wall '{}' uses mesh {mesh}, which does not exist",
                    wall.name
                )));
            }
        }
        if self.walls.len() >= crate::step::force::MAX_WALLS {
            return Err(WorldError::BadReference(format!(
                "too many walls (at most {})",
                crate::step::force::MAX_WALLS
            )));
        }
        self.walls.push(wall);
        self.wall_loads.push(WallLoad::default());
        self.forces_ready = false;
        Ok(self.walls.len() - 1)
    }

    /// Adds a triangle mesh for [`WallShape::Mesh`] walls; returns its index.
    pub fn add_mesh(&mut self, mesh: TriMesh) -> u32 {
        self.meshes.push(mesh);
        self.meshes.len() as u32 - 1
    }

    /// Adds a body; returns its global id.
    pub fn add_body(&mut self, init: &BodyInit) -> Result<u64, WorldError> {
        let t = self.templates.get(init.template as usize).ok_or_else(|| {
            WorldError::BadReference(format!(
                "body uses template {}, which does not exist",
                init.template
            ))
        })?;
        let id = self.next_id;
        self.next_id += 1;
        self.bodies.push(id, init, t.mass, t.principal_inertia);
        self.topology_dirty = true;
        self.forces_ready = false;
        Ok(id)
    }

    /// The Verlet skin in use, m: the configured one; by default the one
    /// the last neighbour build chose for the motion
    /// ([`crate::neighbor::skin::adapted_skin`]), and before the first build
    /// [`crate::neighbor::skin::SKIN_DEFAULT`] times the smallest sphere
    /// radius of any template (never zero).
    pub fn skin(&self) -> f64 {
        self.config.skin.unwrap_or_else(|| {
            if self.adapted_skin > 0.0 {
                self.adapted_skin
            } else {
                crate::neighbor::skin::SKIN_DEFAULT * self.min_radius()
            }
        })
    }

    /// Smallest sphere radius of any template, m (1 mm without templates).
    pub fn min_radius(&self) -> f64 {
        let r = self
            .template_radius
            .iter()
            .cloned()
            .fold(f64::INFINITY, f64::min);
        if r.is_finite() {
            r
        } else {
            1e-3
        }
    }

    /// Largest sphere radius of any template, m.
    pub fn max_radius(&self) -> f64 {
        self.template_radius.iter().cloned().fold(0.0, f64::max)
    }

    /// The spheres (derived from the bodies at the current step).
    pub fn spheres(&self) -> &Spheres {
        &self.spheres
    }

    /// Candidate and touching sphere pairs.
    pub fn pairs(&self) -> &PairList {
        &self.pairs
    }

    /// Storage index of the body with global id `id`, if present (linear search).
    pub fn body_index(&self, id: u64) -> Option<usize> {
        self.bodies.id.iter().position(|&x| x == id)
    }
}
