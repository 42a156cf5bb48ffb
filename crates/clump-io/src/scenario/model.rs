//! The resolved scenario: everything the run driver needs, with names turned
//! into indices and defaults filled in. SI units throughout.

use super::diag::Diagnostic;
use clump_core::body::BodyInit;
use clump_core::contact::{Material, PairProperties};
use clump_core::health::HealthLimits;
use clump_core::insert::{Mix, PackSpec, StreamSpec};
use clump_core::shape::ClumpTemplate;
use clump_core::wall::{TriMesh, Wall};
use clump_core::world::WorldConfig;
use glam::DVec3;
use std::collections::BTreeMap;
use std::path::PathBuf;

/// A resolved, validated scenario.
#[derive(Debug, Clone)]
pub struct Scenario {
    /// The fluid the particles are in (`[fluid]`), if any.
    pub fluid: Option<clump_core::fluid::Fluid>,
    /// The fluid velocity on a grid (`[fluid] velocity = "file.csv"`), if any.
    pub fluid_grid: Option<std::sync::Arc<clump_core::fluid::VelocityGrid>>,
    /// The scenario file as given.
    pub path: PathBuf,
    /// Its text.
    pub text: String,
    /// Contents of every file the scenario refers to (template and body
    /// files), keyed by the path as written in the scenario.
    pub files: BTreeMap<String, Vec<u8>>,
    /// Material names, index = material id.
    pub material_names: Vec<String>,
    /// Materials.
    pub materials: Vec<Material>,
    /// Contact properties, `n × n` (row-major, symmetric) over materials.
    pub pair_table: Vec<PairProperties>,
    /// Templates, index = template id in the world.
    pub templates: Vec<TemplateDef>,
    /// Particle mixes.
    pub mixes: Vec<MixDef>,
    /// Insertions.
    pub inserts: Vec<InsertDef>,
    /// Walls at the start of the run.
    pub walls: Vec<Wall>,
    /// Triangle meshes of the mesh walls (index = `WallShape::Mesh::mesh`),
    /// read from their files with scale, rotation and offset applied (world
    /// frame at the start of the run, m).
    pub meshes: Vec<TriMesh>,
    /// Per wall (index-aligned with `walls`): the fixed world point (m) about
    /// which its torque is reported in `thermo.csv`; `None`: about its
    /// centre of rotation, which moves with the wall.
    pub torque_points: Vec<Option<DVec3>>,
    /// Engine settings at the start (gravity of the first stage, dt, …).
    pub config: WorldConfig,
    /// How the time step was chosen.
    pub time_step: TimeStep,
    /// Thresholds of the per-step instability check (`max_overlap_ratio`,
    /// `kinetic_energy_jump` of `[simulation]`; the kinetic-energy floor
    /// follows from gravity, the domain and the insertion and wall speeds).
    pub stability: HealthLimits,
    /// The largest overlap expected for the scenario's contacts, from which
    /// the default `max_overlap_ratio` follows (see [`super::guard`]).
    pub overlap_estimate: Option<OverlapEstimate>,
    /// Stages, in order.
    pub stages: Vec<StageDef>,
    /// Output settings.
    pub output: OutputDef,
    /// Warnings (the scenario still runs).
    pub warnings: Vec<Diagnostic>,
    /// Heat transfer (`[heat]`); `None`: off.
    pub heat: Option<HeatDef>,
}

/// The heat of a scenario (`[heat]` and the heat keys of the other tables).
#[derive(Debug, Clone)]
pub struct HeatDef {
    /// The engine's heat model (indices as in the scenario's materials,
    /// templates and walls).
    pub model: clump_core::heat::HeatModel,
    /// Per `[[insert]]`: the initial temperature of its bodies, K (`None`:
    /// their templates').
    pub insert_temperature: Vec<Option<f64>>,
    /// Per `[[insert]]`: the `temperature` column of its body file, one per
    /// body (K; over the insert's and the template's), if it has one.
    pub file_temperature: Vec<Option<Vec<f64>>>,
    /// The thermal stability limit of the time step, s (T-57).
    pub stability_limit: f64,
    /// The template that sets it.
    pub limiting_template: String,
    /// The fluid's thermal properties when `[fluid]` has a temperature:
    /// convection from the fluid (T-90 … T-93).
    pub convection: Option<clump_core::heat::FluidHeat>,
}

/// A template with its name and material.
#[derive(Debug, Clone)]
pub struct TemplateDef {
    /// Name.
    pub name: String,
    /// Material index.
    pub material: u16,
    /// The template, body frame, SI.
    pub template: ClumpTemplate,
    /// Force and torque flags of its bodies (`force_flags`, `torque_flags`).
    pub dof: clump_core::dof::Dof,
    /// `mass` and `inertia` (and maybe `center_of_mass`) were given.
    pub given_mass_properties: bool,
}

/// A named particle mix (template indices refer to [`Scenario::templates`]).
#[derive(Debug, Clone)]
pub struct MixDef {
    /// Name.
    pub name: String,
    /// The mix.
    pub mix: Mix,
}

/// The size distributions that `mixes` give template `t`.
pub fn template_sizes(
    mixes: &[MixDef],
    t: usize,
) -> impl Iterator<Item = &clump_core::insert::SizeDistribution> {
    mixes
        .iter()
        .flat_map(|m| &m.mix.entries)
        .filter(move |e| e.template as usize == t)
        .map(|e| &e.size)
}

/// How the time step was chosen.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeStep {
    /// The time step, s.
    pub dt: f64,
    /// Whether `dt = "auto"`.
    pub auto: bool,
    /// `dt_fraction` (used for `auto`).
    pub fraction: f64,
    /// Rayleigh time of the smallest sphere, s (None without templates).
    pub rayleigh_time: Option<f64>,
    /// Radius of the smallest sphere (with the smallest size scale), m.
    pub smallest_radius: Option<f64>,
    /// Template holding the smallest sphere.
    pub smallest_template: Option<String>,
    /// The damped-contact stability limit of the templates (None without
    /// templates or contact models).
    pub stability: Option<StabilityLimit>,
}

/// The stability limit `dt_c` of the explicit step for the scenario's most
/// demanding contact (docs/theory.md T-52).
#[derive(Debug, Clone, PartialEq)]
pub struct StabilityLimit {
    /// `dt_c`, s.
    pub dt: f64,
    /// The contact it comes from (templates, spheres, wall material).
    pub contact: String,
    /// The larger mobility factor `κ` of the contact (1 for spheres).
    pub kappa: f64,
}

/// One insertion.
#[derive(Debug, Clone)]
pub struct InsertDef {
    /// Stage index in which it happens.
    pub stage: usize,
    /// What to insert.
    pub kind: InsertSpec,
}

/// What an insertion does.
#[derive(Debug, Clone)]
pub enum InsertSpec {
    /// Bodies from a CSV file, added at the start of the stage.
    File {
        /// The bodies (template indices refer to the scenario's templates).
        bodies: Vec<BodyInit>,
    },
    /// Random packing at the start of the stage.
    Pack {
        /// The packing.
        spec: PackSpec,
        /// Seed.
        seed: u64,
        /// Expected number of bodies.
        expected_bodies: f64,
    },
    /// A stream during the stage (times in the spec are absolute, s).
    Stream {
        /// The stream.
        spec: StreamSpec,
        /// Seed.
        seed: u64,
        /// Expected number of bodies.
        expected_bodies: f64,
    },
}

/// A change to one wall at the start of a stage.
#[derive(Debug, Clone, PartialEq)]
pub struct WallChange {
    /// Wall index.
    pub wall: usize,
    /// New active flag.
    pub active: Option<bool>,
    /// New translation velocity, world frame, m/s.
    pub velocity: Option<DVec3>,
    /// New angular velocity, world frame, rad/s.
    pub angular_velocity: Option<DVec3>,
    /// New centre of rotation, world frame, m.
    pub center: Option<DVec3>,
    /// New surface velocity, world frame, m/s.
    pub surface_velocity: Option<DVec3>,
}

/// A change to one body at the start of a stage.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyChange {
    /// Global body id.
    pub id: u64,
    /// New centre-of-mass velocity, world frame, m/s.
    pub velocity: Option<DVec3>,
    /// New angular velocity, world frame, rad/s.
    pub angular_velocity: Option<DVec3>,
}

/// One stage.
#[derive(Debug, Clone, PartialEq)]
pub struct StageDef {
    /// Name.
    pub name: String,
    /// Steps in this stage.
    pub steps: u64,
    /// Global step at which the stage starts.
    pub first_step: u64,
    /// New gravity, world frame, m/s² (None: unchanged).
    pub gravity: Option<DVec3>,
    /// Wall changes applied at the start.
    pub walls: Vec<WallChange>,
    /// Body changes applied at the start (after the wall changes).
    pub bodies: Vec<BodyChange>,
}

/// Trajectory output.
#[derive(Debug, Clone, PartialEq)]
pub struct TrajectoryDef {
    /// Global body ids.
    pub bodies: Vec<u64>,
    /// Interval, steps.
    pub every: u64,
    /// Optional columns (`euler`, `loads`).
    pub extras: crate::trajectory::Extras,
}

/// Output settings (intervals in steps).
#[derive(Debug, Clone, PartialEq)]
pub struct OutputDef {
    /// Output directory from the scenario (the command line overrides it).
    pub directory: Option<String>,
    /// VTK interval, steps.
    pub vtk: Option<u64>,
    /// Thermo interval, steps.
    pub thermo: Option<u64>,
    /// Checkpoint interval, steps.
    pub checkpoint: Option<u64>,
    /// Trajectories.
    pub trajectory: Option<TrajectoryDef>,
    /// File format of the VTK frames (`.vtp` or `.vtu`).
    pub vtk_format: crate::vtu::VtkFormat,
    /// Contact frames interval, steps.
    pub contacts: Option<u64>,
    /// Coarse-grained fields: interval (steps) and request.
    pub fields: Option<(u64, crate::post::spec::FieldSpec)>,
    /// Flow measurement: interval (steps) and probes.
    pub flow: Option<(u64, Vec<crate::post::flow::FlowProbe>)>,
}

impl Scenario {
    /// Total steps over all stages.
    pub fn total_steps(&self) -> u64 {
        self.stages.iter().map(|s| s.steps).sum()
    }

    /// Simulated duration of all stages, s.
    pub fn duration(&self) -> f64 {
        self.total_steps() as f64 * self.config.dt
    }

    /// Expected number of bodies inserted over the whole run.
    pub fn expected_bodies(&self) -> f64 {
        self.inserts
            .iter()
            .map(|i| match &i.kind {
                InsertSpec::File { bodies } => bodies.len() as f64,
                InsertSpec::Pack {
                    expected_bodies, ..
                }
                | InsertSpec::Stream {
                    expected_bodies, ..
                } => *expected_bodies,
            })
            .sum()
    }

    /// Expected number of spheres over the whole run.
    pub fn expected_spheres(&self) -> f64 {
        self.inserts.iter().map(|i| self.insert_spheres(i)).sum()
    }

    /// Spheres of the pack and file inserts: bodies placed whole when their
    /// stage begins, so the run holds them all unless some leave.
    pub fn placed_spheres(&self) -> f64 {
        self.inserts
            .iter()
            .filter(|i| !matches!(i.kind, InsertSpec::Stream { .. }))
            .map(|i| self.insert_spheres(i))
            .sum()
    }

    /// Expected number of spheres one insert brings.
    fn insert_spheres(&self, insert: &InsertDef) -> f64 {
        let mean_spheres = |mix: &Mix| {
            let mut w = 0.0;
            let mut s = 0.0;
            for e in &mix.entries {
                let t = &self.templates[e.template as usize].template;
                let wt = match mix.basis {
                    clump_core::insert::FractionBasis::Number => e.fraction,
                    clump_core::insert::FractionBasis::Mass => {
                        e.fraction / (t.mass * e.size.mean_cube())
                    }
                };
                w += wt;
                s += wt * t.spheres.len() as f64;
            }
            s / w
        };
        match &insert.kind {
            InsertSpec::File { bodies } => bodies
                .iter()
                .map(|b| self.templates[b.template as usize].template.spheres.len() as f64)
                .sum(),
            InsertSpec::Pack {
                spec,
                expected_bodies,
                ..
            } => expected_bodies * mean_spheres(&spec.mix),
            InsertSpec::Stream {
                spec,
                expected_bodies,
                ..
            } => expected_bodies * mean_spheres(&spec.mix),
        }
    }
}

/// The largest expected overlap of a scenario's contacts.
#[derive(Debug, Clone, PartialEq)]
pub struct OverlapEstimate {
    /// Overlap / smaller sphere radius of the worst contact.
    pub ratio: f64,
    /// The impact speed assumed, m/s.
    pub speed: f64,
    /// The worst contact, in words (e.g. "template 'stone' on wall material 'steel'").
    pub what: String,
}
