//! The scenario file as written (serde structures, `deny_unknown_fields`).
//!
//! These types mirror the TOML layout one to one; units are SI and are stated
//! on every field. Each table is declared with [`table!`], which also gives
//! its list of keys ([`super::keys`]): a new key is one field here, with
//! its doc comment. Validation and cross-references are resolved in
//! [`super::resolve`]. See `docs/scenario.md` for the reference.

use super::keys::table;
pub use super::raw_output::{RawEvery, RawFields, RawFlow, RawOutput, RawTrajectory};
use clump_core::contact::{DampingLaw, RollingLaw, TangentialLaw, TwistingLaw};
use clump_core::insert::FractionBasis;
use clump_core::multi_contact::MultiContact;
use clump_core::rotation::RotationScheme;
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer};
use std::fmt;

table! {
    /// The whole scenario file.
    pub struct RawScenario {
        /// `[simulation]`: time step, gravity, duration.
        pub simulation: Option<RawSimulation>,
        /// `[domain]`: simulation box and periodic axes.
        pub domain: Option<RawDomain>,
        /// `[integrator]`: rotation scheme, added mass.
        #[serde(default)]
        pub integrator: RawIntegrator,
        /// `[[material]]` entries.
        #[serde(default)]
        pub material: Vec<RawMaterial>,
        /// `[contact]`: default contact properties for pairs not listed.
        #[serde(default)]
        pub contact: RawContact,
        /// `[[pair]]` entries: contact properties of one pair of materials.
        #[serde(default)]
        pub pair: Vec<RawPair>,
        /// `[[template]]` entries: clump shapes.
        #[serde(default)]
        pub template: Vec<RawTemplate>,
        /// `[[mix]]` entries: particle mixes.
        #[serde(default)]
        pub mix: Vec<RawMix>,
        /// `[[insert]]` entries.
        #[serde(default)]
        pub insert: Vec<RawInsert>,
        /// `[[wall]]` entries.
        #[serde(default)]
        pub wall: Vec<RawWall>,
        /// `[[stage]]` entries, run in order.
        #[serde(default)]
        pub stage: Vec<RawStage>,
        /// `[output]`.
        #[serde(default)]
        pub output: RawOutput,
        /// `[heat]`: heat transfer (off without it).
        pub heat: Option<RawHeat>,
        /// `[fluid]`: the fluid the particles are in (drag, buoyancy,
        /// pressure gradient).
        pub fluid: Option<RawFluid>,
    }
}

table! {
    /// `[heat]`: turns heat transfer on.
    pub struct RawHeat {
        /// Contact conductance: `"batchelor_obrien"` (default, H = 2 k* a) or `"geometric"` (LIGGGHTS' overlap area).
        pub conductance: Option<clump_core::heat::Conductance>,
        /// Initial temperature of bodies whose template gives none, K.
        pub temperature: Option<f64>,
    }
}

table! {
    /// `[fluid]`.
    pub struct RawFluid {
        /// Density, kg/m³.
        pub density: Option<f64>,
        /// Dynamic viscosity, Pa s.
        pub viscosity: Option<f64>,
        /// Interstitial velocity, world frame, m/s: `[ux, uy, uz]` (uniform,
        /// default 0) or a grid file covering the domain, CSV
        /// `x,y,z,ux,uy,uz` on a regular grid or VTK image data (`.vti`),
        /// interpolated at each body (a driver may set it per body).
        pub velocity: Option<RawVelocity>,
        /// Pressure gradient beyond the hydrostatic one, world frame, Pa/m (default 0).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub pressure_gradient: Option<[f64; 3]>,
        /// Drag law: "stokes", "schiller_naumann", "di_felice", "beetstra"
        /// or "gidaspow" (default "schiller_naumann").
        pub drag: Option<String>,
        /// Buoyancy in the hydrostatic pressure field (default true).
        pub buoyancy: Option<bool>,
        /// The fluid's temperature, K: convection from the fluid (needs
        /// `[heat]`, `thermal_conductivity` and `specific_heat`).
        pub temperature: Option<f64>,
        /// The fluid's thermal conductivity, W/(m K).
        pub thermal_conductivity: Option<f64>,
        /// The fluid's specific heat, J/(kg K).
        pub specific_heat: Option<f64>,
    }
}

/// `[fluid] velocity`: a uniform vector or the name of a grid file.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(untagged)]
pub enum RawVelocity {
    /// `[ux, uy, uz]`, m/s.
    Uniform(Vec<f64>),
    /// A CSV file relative to the scenario.
    File(String),
}

/// A time step: a number of seconds or `"auto"`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DtSpec {
    /// Explicit time step, s.
    Fixed(f64),
    /// `dt_fraction` × the Rayleigh time of the smallest sphere.
    Auto,
}

impl<'de> Deserialize<'de> for DtSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = DtSpec;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a time step in s (a number such as 1e-5) or \"auto\"")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<DtSpec, E> {
                Ok(DtSpec::Fixed(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<DtSpec, E> {
                Ok(DtSpec::Fixed(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<DtSpec, E> {
                Ok(DtSpec::Fixed(v as f64))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<DtSpec, E> {
                if v == "auto" {
                    Ok(DtSpec::Auto)
                } else {
                    Err(E::invalid_value(de::Unexpected::Str(v), &self))
                }
            }
        }
        d.deserialize_any(V)
    }
}

table! {
    /// `[simulation]`.
    pub struct RawSimulation {
        /// Time step, s, or `"auto"` (default `"auto"`).
        pub dt: Option<DtSpec>,
        /// Fraction of the Rayleigh time used by `dt = "auto"` (default 0.2).
        pub dt_fraction: Option<f64>,
        /// Gravity, world frame, m/s² (default `[0, 0, -9.81]`).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub gravity: Option<[f64; 3]>,
        /// Duration of the single implicit stage when there is no `[[stage]]`, s.
        pub duration: Option<f64>,
        /// Steps of the single implicit stage when there is no `[[stage]]`.
        pub steps: Option<u64>,
        /// Verlet skin, m (default: adapted to the motion at every neighbour
        /// build, `clump_core::neighbor::skin::adapted_skin`).
        pub skin: Option<f64>,
        /// Several-contact treatment between two bodies (default `"sum"`).
        pub multi_contact: Option<MultiContact>,
        /// Largest overlap / smaller sphere radius before the run is stopped as
        /// unstable (default 0.15).
        pub max_overlap_ratio: Option<f64>,
        /// Largest growth factor of the kinetic energy within about 100 steps
        /// before the run is stopped as unstable (default 1000).
        pub kinetic_energy_jump: Option<f64>,
    }
}

/// A coordinate axis name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AxisName {
    /// x.
    X,
    /// y.
    Y,
    /// z.
    Z,
}

table! {
    /// `[domain]`.
    pub struct RawDomain {
        /// Lower corner, world frame, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub lo: Option<[f64; 3]>,
        /// Upper corner, world frame, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub hi: Option<[f64; 3]>,
        /// Periodic axes, e.g. `["x", "y"]` (default none).
        #[serde(default)]
        pub periodic: Vec<AxisName>,
        /// 2 (motion in the x–y plane, rotation about z) or 3 (default).
        pub dimension: Option<u8>,
    }
}

table! {
    /// `[integrator]`.
    pub struct RawIntegrator {
        /// Rotation scheme (default the engine's, `"no_squish"`).
        pub rotation: Option<RotationScheme>,
        /// `[integrator.added_mass]`.
        pub added_mass: Option<RawAddedMass>,
    }
}

table! {
    /// `[integrator.added_mass]`.
    pub struct RawAddedMass {
        /// Added-mass coefficient (dimensionless, default 0.5).
        pub coefficient: Option<f64>,
        /// Fluid density, kg/m³.
        pub fluid_density: Option<f64>,
    }
}

table! {
    /// `[[material]]`.
    pub struct RawMaterial {
        /// Name used by templates, walls and pairs.
        pub name: Option<String>,
        /// Young's modulus, Pa.
        pub youngs_modulus: Option<f64>,
        /// Poisson's ratio (dimensionless).
        pub poisson_ratio: Option<f64>,
        /// Density, kg/m³.
        pub density: Option<f64>,
        /// Thermal conductivity, W/(m K) (with `[heat]`).
        pub thermal_conductivity: Option<f64>,
        /// Specific heat capacity, J/(kg K) (with `[heat]`).
        pub specific_heat: Option<f64>,
    }
}

/// Cohesion model name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CohesionName {
    /// No cohesion.
    None,
    /// LIGGGHTS' simplified JKR (needs `cohesion_energy_density`).
    Sjkr,
    /// JKR (needs `surface_energy`).
    Jkr,
}

/// Normal force law name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LawName {
    /// Hertz–Mindlin.
    Hertz,
    /// Linear spring–dashpot (needs `kn`, `kt`).
    Linear,
}

/// The contact-law keys shared by `[contact]` and `[[pair]]`, declared
/// here once: `contact_law_keys!(m! { args })` expands to
/// `m! { args [keys] }`, so that [`table!`] appends them to both structs
/// and [`RawPair::law`] copies them. A new key of the contact law is one
/// entry here (its value type must be `Copy`).
macro_rules! contact_law_keys {
    ($then:ident! { $($args:tt)* }) => {
        $then! { $($args)* [
            /// Coefficient of restitution (dimensionless).
            pub restitution: Option<f64>,
            /// Sliding friction coefficient (dimensionless).
            pub friction: Option<f64>,
            /// Rolling friction coefficient (dimensionless).
            pub rolling_friction: Option<f64>,
            /// Normal law.
            pub law: Option<LawName>,
            /// Linear normal stiffness, N/m.
            pub kn: Option<f64>,
            /// Linear tangential stiffness, N/m.
            pub kt: Option<f64>,
            /// Damping law.
            pub damping: Option<DampingLaw>,
            /// Rolling resistance law.
            pub rolling: Option<RollingLaw>,
            /// Whether the normal force may be tensile (no clamp at zero).
            pub tensile: Option<bool>,
            /// Tangential rule: `"clump"` (default), `"liggghts"`,
            /// `"mindlin_deresiewicz"` (micro-slip, Thornton–Yin) or `"mdr"`
            /// (micro-slip, exact for any load history).
            pub tangential: Option<TangentialLaw>,
            /// Cohesion model: `"none"` (default), `"sjkr"` or `"jkr"`.
            pub cohesion: Option<CohesionName>,
            /// SJKR cohesion energy density, J/m³.
            pub cohesion_energy_density: Option<f64>,
            /// JKR work of adhesion, J/m².
            pub surface_energy: Option<f64>,
            /// Twisting resistance: `"none"` (default) or `"marshall"`.
            pub twisting: Option<TwistingLaw>,
        ] }
    };
}

contact_law_keys!(table! {
    /// `[contact]`: the contact law of every pair of materials not listed
    /// in a `[[pair]]`.
    pub struct RawContact {}
});

contact_law_keys!(table! {
    /// `[[pair]]`: the contact law of one pair of materials (keys left out
    /// keep the `[contact]` value).
    pub struct RawPair {
        /// The two material names.
        pub materials: Option<Vec<String>>,
    }
});

/// `RawContact { key: $pair.key, … }` over the contact-law keys.
macro_rules! copy_law {
    ($pair:ident; [$($(#[doc = $doc:literal])+ pub $key:ident: $ty:ty,)*]) => {
        RawContact { $($key: $pair.$key,)* }
    };
}

impl RawPair {
    /// The pair's contact-law keys, as a `[contact]` table.
    pub fn law(&self) -> RawContact {
        let pair = self;
        contact_law_keys!(copy_law! { pair; })
    }
}

/// Built-in template shape name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ShapeName {
    /// One sphere.
    Sphere,
    /// `n` spheres in a row.
    Rod,
    /// 4 spheres on a regular tetrahedron.
    Tetrahedron,
    /// 8 spheres on the corners of a cube.
    CubeOctet,
}

table! {
    /// `[[template]]`.
    pub struct RawTemplate {
        /// Name.
        pub name: Option<String>,
        /// Material name.
        pub material: Option<String>,
        /// Inline spheres `[x, y, z, r]`, m (input frame).
        #[serde(default, deserialize_with = "super::exact::rows")]
        pub spheres: Option<Vec<[f64; 4]>>,
        /// LIGGGHTS `x y z r` file, relative to the scenario file.
        pub file: Option<String>,
        /// Built-in shape.
        pub shape: Option<ShapeName>,
        /// Sphere radius of a built-in shape, m.
        pub radius: Option<f64>,
        /// Number of spheres of a rod.
        pub n: Option<u32>,
        /// Centre spacing of a rod, m.
        pub spacing: Option<f64>,
        /// Edge of a tetrahedron or cube, m.
        pub edge: Option<f64>,
        /// Length scale factor applied to the spheres (dimensionless, default 1).
        pub scale: Option<f64>,
        /// Mass override, kg (needs `inertia`).
        pub mass: Option<f64>,
        /// Inertia tensor override about the centre of mass, input frame, kg m².
        #[serde(default, deserialize_with = "super::exact::matrix")]
        pub inertia: Option<[[f64; 3]; 3]>,
        /// Centre of mass override, input frame, m (with `mass` and `inertia`,
        /// which is then taken about this point).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub center_of_mass: Option<[f64; 3]>,
        /// Force flags per world axis of this template's bodies (LIGGGHTS `fflag`).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub force_flags: Option<[bool; 3]>,
        /// Torque flags per world axis of this template's bodies (LIGGGHTS `tflag`).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub torque_flags: Option<[bool; 3]>,
        /// Initial temperature of its bodies, K (with `[heat]`).
        pub temperature: Option<f64>,
        /// Volumetric heat source of its bodies, W/m³ (with `[heat]`, default 0).
        pub heat_source: Option<f64>,
    }
}

/// Size distribution kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SizeKind {
    /// A fixed scale.
    Fixed,
    /// Uniform in `[min, max]`.
    Uniform,
    /// Normal truncated to `[min, max]`.
    Normal,
}

table! {
    /// Size distribution of one mix component (scale factors, dimensionless).
    pub struct RawSize {
        /// Kind of distribution.
        pub distribution: Option<SizeKind>,
        /// Scale of a fixed distribution.
        pub scale: Option<f64>,
        /// Smallest scale.
        pub min: Option<f64>,
        /// Largest scale.
        pub max: Option<f64>,
        /// Mean scale (normal).
        pub mean: Option<f64>,
        /// Standard deviation of the scale (normal).
        pub std: Option<f64>,
    }
}

table! {
    /// One `[[mix.component]]`.
    pub struct RawComponent {
        /// Template name.
        pub template: Option<String>,
        /// Relative share (by number or mass), default 1.
        pub fraction: Option<f64>,
        /// Size distribution (default: the template as is).
        pub size: Option<RawSize>,
    }
}

table! {
    /// `[[mix]]`.
    pub struct RawMix {
        /// Name.
        pub name: Option<String>,
        /// `"number"` (default) or `"mass"`.
        pub basis: Option<FractionBasis>,
        /// Components.
        #[serde(default)]
        pub component: Vec<RawComponent>,
    }
}

/// Region kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RegionKind {
    /// Axis-aligned box.
    Box,
    /// Finite cylinder.
    Cylinder,
}

table! {
    /// An insertion region.
    pub struct RawRegion {
        /// `"box"` or `"cylinder"`.
        #[key = "type"]
        pub kind: Option<RegionKind>,
        /// Box lower corner, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub lo: Option<[f64; 3]>,
        /// Box upper corner, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub hi: Option<[f64; 3]>,
        /// Cylinder: centre of the bottom disc, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub base: Option<[f64; 3]>,
        /// Cylinder axis (unit vector, default `[0, 0, 1]`).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub axis: Option<[f64; 3]>,
        /// Cylinder radius, m.
        pub radius: Option<f64>,
        /// Cylinder height, m.
        pub height: Option<f64>,
    }
}

/// The frame a body file's orientation quaternions map to the world frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OrientationFrame {
    /// The template's principal body frame (Clump's own convention).
    Body,
    /// The frame the template's spheres were given in (a LIGGGHTS template
    /// file, inline spheres): the quaternion maps those coordinates, relative
    /// to the centre of mass, to the world frame, as in LIGGGHTS and in the
    /// shared tetra-bed initial conditions.
    Input,
}

/// Insertion kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum InsertKind {
    /// Bodies listed in a CSV file.
    File,
    /// Random packing of a region.
    Pack,
    /// Stream through a region at a rate.
    Stream,
}

table! {
    /// `[[insert]]`.
    pub struct RawInsert {
        /// `"file"`, `"pack"` or `"stream"`.
        pub kind: Option<InsertKind>,
        /// Stage in which it happens (default the first).
        pub stage: Option<String>,
        /// Body file (kind = "file"), relative to the scenario file.
        pub file: Option<String>,
        /// Layout of the body file (kind = "file"; default `csv`).
        pub format: Option<super::BodyFileFormat>,
        /// Frame the body file's quaternions start from (kind = "file"; default `body`).
        pub orientation_frame: Option<OrientationFrame>,
        /// Mix name.
        pub mix: Option<String>,
        /// Template name (instead of a mix).
        pub template: Option<String>,
        /// Number of bodies (pack; stream: optional limit).
        pub count: Option<u64>,
        /// Solid volume fraction of the region (pack).
        pub volume_fraction: Option<f64>,
        /// Region.
        pub region: Option<RawRegion>,
        /// Random seed (default 1).
        pub seed: Option<u64>,
        /// Initial velocity, world frame, m/s.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub velocity: Option<[f64; 3]>,
        /// Fixed orientation quaternion `[w, x, y, z]` (default random).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub orientation: Option<[f64; 4]>,
        /// Stream rate, bodies/s.
        pub bodies_per_second: Option<f64>,
        /// Stream rate, kg/s.
        pub kg_per_second: Option<f64>,
        /// Stream start, s after the stage start.
        pub start: Option<f64>,
        /// Stream end, s after the stage start (default the end of the stage).
        pub end: Option<f64>,
        /// Placement attempts per body.
        pub max_attempts: Option<u32>,
        /// Fixed orientation as z-x-z Euler angles `[phi, theta, psi]`, rad (pack, stream).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub euler: Option<[f64; 3]>,
        /// Initial angular velocity, world frame, rad/s (pack, stream).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub angular_velocity: Option<[f64; 3]>,
        /// Force flags per world axis (override the template's).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub force_flags: Option<[bool; 3]>,
        /// Torque flags per world axis (override the template's).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub torque_flags: Option<[bool; 3]>,
        /// The bodies never move (LIGGGHTS `fix freeze`); they still make contacts.
        pub fixed: Option<bool>,
        /// The bodies keep their initial velocity and angular velocity.
        pub driven: Option<bool>,
        /// Stream: seconds each body moves ballistically after insertion.
        pub start_after: Option<f64>,
        /// Initial temperature of the inserted bodies, K (with `[heat]`; default the template's).
        pub temperature: Option<f64>,
    }
}

/// Wall kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum WallKind {
    /// Infinite plane.
    Plane,
    /// Infinite cylinder.
    Cylinder,
    /// Axis-aligned box.
    Box,
    /// Triangle mesh from an STL or OBJ file.
    Mesh,
}

table! {
    /// A rotation given as an axis and an angle (right-hand rule).
    pub struct RawRotation {
        /// Rotation axis, world frame (normalised; need not be unit).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub axis: Option<[f64; 3]>,
        /// Rotation angle, degrees (positive: counter-clockwise looking down the axis).
        pub angle: Option<f64>,
    }
}

table! {
    /// `[[wall]]`.
    pub struct RawWall {
        /// Name.
        pub name: Option<String>,
        /// Material name.
        pub material: Option<String>,
        /// `"plane"`, `"cylinder"`, `"box"`, `"mesh"`.
        #[key = "type"]
        pub kind: Option<WallKind>,
        /// Mesh: STL or OBJ file, relative to the scenario file.
        pub file: Option<String>,
        /// Mesh: factor from file units to m (default 1).
        pub scale: Option<f64>,
        /// Mesh: rotation applied after scaling (file frame → world frame).
        pub rotation: Option<RawRotation>,
        /// Mesh: translation applied last, world frame, m (default 0).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub offset: Option<[f64; 3]>,
        /// Mesh: contacts whose normals are closer than this angle are one
        /// contact patch, degrees (default 15).
        pub merge_angle: Option<f64>,
        /// Point about which the torque on the wall is reported, world frame, m
        /// (default: the centre of rotation, moving with the wall).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub torque_point: Option<[f64; 3]>,
        /// Plane: a point; cylinder: a point on the axis, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub point: Option<[f64; 3]>,
        /// Plane unit normal (towards the particles).
        #[serde(default, deserialize_with = "super::exact::array")]
        pub normal: Option<[f64; 3]>,
        /// Cylinder unit axis.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub axis: Option<[f64; 3]>,
        /// Cylinder radius, m.
        pub radius: Option<f64>,
        /// Cylinder/box: particles inside (default true).
        pub inside: Option<bool>,
        /// Box lower corner, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub lo: Option<[f64; 3]>,
        /// Box upper corner, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub hi: Option<[f64; 3]>,
        /// Translation velocity, m/s.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub velocity: Option<[f64; 3]>,
        /// Angular velocity about `center`, rad/s.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub angular_velocity: Option<[f64; 3]>,
        /// Centre of rotation, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub center: Option<[f64; 3]>,
        /// Extra tangential surface velocity, m/s.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub surface_velocity: Option<[f64; 3]>,
        /// Several-contact treatment.
        pub multi_contact: Option<MultiContact>,
        /// Whether the wall is active at the start (default true).
        pub active: Option<bool>,
        /// Fixed temperature, K (with `[heat]`; default adiabatic).
        pub temperature: Option<f64>,
    }
}

table! {
    /// `[[stage.wall]]`: a change to one wall at the start of a stage.
    pub struct RawWallChange {
        /// Wall name.
        pub name: Option<String>,
        /// Set active/inactive.
        pub active: Option<bool>,
        /// New translation velocity, m/s.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub velocity: Option<[f64; 3]>,
        /// New angular velocity, rad/s.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub angular_velocity: Option<[f64; 3]>,
        /// New centre of rotation, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub center: Option<[f64; 3]>,
        /// New surface velocity, m/s.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub surface_velocity: Option<[f64; 3]>,
    }
}

table! {
    /// `[[stage.body]]`: a change to one body at the start of a stage.
    pub struct RawBodyChange {
        /// Global body id (1-based, in insertion order).
        pub id: Option<u64>,
        /// New centre-of-mass velocity, m/s.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub velocity: Option<[f64; 3]>,
        /// New angular velocity (world frame), rad/s.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub angular_velocity: Option<[f64; 3]>,
    }
}

table! {
    /// `[[stage]]`.
    pub struct RawStage {
        /// Name (default `stage1`, `stage2`, …).
        pub name: Option<String>,
        /// Duration, s.
        pub duration: Option<f64>,
        /// Duration in steps.
        pub steps: Option<u64>,
        /// New gravity from this stage on, m/s².
        #[serde(default, deserialize_with = "super::exact::array")]
        pub gravity: Option<[f64; 3]>,
        /// Wall changes.
        #[serde(default)]
        pub wall: Vec<RawWallChange>,
        /// Body changes.
        #[serde(default)]
        pub body: Vec<RawBodyChange>,
    }
}
