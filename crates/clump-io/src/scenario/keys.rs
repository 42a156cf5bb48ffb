//! The keys of every scenario table, one declarative list per kind of
//! table, with a short help for each key.
//!
//! The lists follow the fields of [`super::raw`] one to one and in order
//! (a unit test compares them with the field names serde reports), so they
//! are where the allowed keys and the did-you-mean suggestions of unknown
//! keys come from, and the keys that belong to one type of wall, region or
//! insertion only ([`WALL_TYPE_KEYS`], [`REGION_TYPE_KEYS`],
//! [`INSERT_KIND_KEYS`]).

#[allow(unused_imports)] // named in the docs
use super::raw::*;

/// One key of a scenario table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    /// The key as written in the file.
    pub name: &'static str,
    /// What it sets, with its unit and default.
    pub help: &'static str,
}

const fn key(name: &'static str, help: &'static str) -> Key {
    Key { name, help }
}

/// The keys that apply to one type (`type = "..."`) or kind (`kind = "..."`)
/// of a table only, in the order messages list them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KindKeys {
    /// The type or kind, as written in the file.
    pub kind: &'static str,
    /// The names of its own keys.
    pub keys: &'static [&'static str],
}

/// The keys of the top level of the file ([`RawScenario`]).
pub const SCENARIO_KEYS: &[Key] = &[
    key(
        "simulation",
        "`[simulation]`: time step, gravity, duration.",
    ),
    key("domain", "`[domain]`: simulation box and periodic axes."),
    key("integrator", "`[integrator]`: rotation scheme, added mass."),
    key("material", "`[[material]]` entries."),
    key(
        "contact",
        "`[contact]`: default contact properties for pairs not listed.",
    ),
    key(
        "pair",
        "`[[pair]]` entries: contact properties of one pair of materials.",
    ),
    key("template", "`[[template]]` entries: clump shapes."),
    key("mix", "`[[mix]]` entries: particle mixes."),
    key("insert", "`[[insert]]` entries."),
    key("wall", "`[[wall]]` entries."),
    key("stage", "`[[stage]]` entries, run in order."),
    key("output", "`[output]`."),
];

/// The keys of `[simulation]` ([`RawSimulation`]).
pub const SIMULATION_KEYS: &[Key] = &[
    key("dt", "Time step, s, or `\"auto\"` (default `\"auto\"`)."),
    key("dt_fraction", "Fraction of the Rayleigh time used by `dt = \"auto\"` (default 0.2)."),
    key("gravity", "Gravity, world frame, m/s² (default `[0, 0, -9.81]`)."),
    key("duration", "Duration of the single implicit stage when there is no `[[stage]]`, s."),
    key("steps", "Steps of the single implicit stage when there is no `[[stage]]`."),
    key("skin", "Verlet skin, m (default: adapted to the motion at every neighbour build)."),
    key("multi_contact", "Several-contact treatment between two bodies (default `\"sum\"`)."),
    key("max_overlap_ratio", "Largest overlap / smaller sphere radius before the run is stopped as unstable (default 0.15)."),
    key("kinetic_energy_jump", "Largest growth factor of the kinetic energy within about 100 steps before the run is stopped as unstable (default 1000)."),
];

/// The keys of `[domain]` ([`RawDomain`]).
pub const DOMAIN_KEYS: &[Key] = &[
    key("lo", "Lower corner, world frame, m."),
    key("hi", "Upper corner, world frame, m."),
    key(
        "periodic",
        "Periodic axes, e.g. `[\"x\", \"y\"]` (default none).",
    ),
    key(
        "dimension",
        "2 (motion in the x–y plane, rotation about z) or 3 (default).",
    ),
];

/// The keys of `[integrator]` ([`RawIntegrator`]).
pub const INTEGRATOR_KEYS: &[Key] = &[
    key(
        "rotation",
        "Rotation scheme (default the engine's, `\"no_squish\"`).",
    ),
    key("added_mass", "`[integrator.added_mass]`."),
];

/// The keys of `[integrator.added_mass]` ([`RawAddedMass`]).
pub const ADDED_MASS_KEYS: &[Key] = &[
    key(
        "coefficient",
        "Added-mass coefficient (dimensionless, default 0.5).",
    ),
    key("fluid_density", "Fluid density, kg/m³."),
];

/// The keys of `[[material]]` ([`RawMaterial`]).
pub const MATERIAL_KEYS: &[Key] = &[
    key("name", "Name used by templates, walls and pairs."),
    key("youngs_modulus", "Young's modulus, Pa."),
    key("poisson_ratio", "Poisson's ratio (dimensionless)."),
    key("density", "Density, kg/m³."),
];

/// The keys of `[contact]` ([`RawContact`]).
pub const CONTACT_KEYS: &[Key] = &[
    key("restitution", "Coefficient of restitution (dimensionless)."),
    key("friction", "Sliding friction coefficient (dimensionless)."),
    key(
        "rolling_friction",
        "Rolling friction coefficient (dimensionless).",
    ),
    key("law", "Normal law."),
    key("kn", "Linear normal stiffness, N/m."),
    key("kt", "Linear tangential stiffness, N/m."),
    key("damping", "Damping law."),
    key("rolling", "Rolling resistance law."),
    key(
        "tensile",
        "Whether the normal force may be tensile (no clamp at zero).",
    ),
    key(
        "tangential",
        "Tangential rule: `\"clump\"` (default), `\"liggghts\"`, `\"mindlin_deresiewicz\"` (micro-slip, Thornton–Yin) or `\"mdr\"` (micro-slip, exact for any load history).",
    ),
    key(
        "cohesion",
        "Cohesion model: `\"none\"` (default), `\"sjkr\"` or `\"jkr\"`.",
    ),
    key(
        "cohesion_energy_density",
        "SJKR cohesion energy density, J/m³.",
    ),
    key("surface_energy", "JKR work of adhesion, J/m²."),
    key(
        "twisting",
        "Twisting resistance: `\"none\"` (default) or `\"marshall\"`.",
    ),
];

/// The keys of `[[pair]]` ([`RawPair`]).
pub const PAIR_KEYS: &[Key] = &[
    key("materials", "The two material names."),
    key("restitution", "Coefficient of restitution (dimensionless)."),
    key("friction", "Sliding friction coefficient (dimensionless)."),
    key(
        "rolling_friction",
        "Rolling friction coefficient (dimensionless).",
    ),
    key("law", "Normal law."),
    key("kn", "Linear normal stiffness, N/m."),
    key("kt", "Linear tangential stiffness, N/m."),
    key("damping", "Damping law."),
    key("rolling", "Rolling resistance law."),
    key(
        "tensile",
        "Whether the normal force may be tensile (no clamp at zero).",
    ),
    key(
        "tangential",
        "Tangential rule: `\"clump\"` (default), `\"liggghts\"`, `\"mindlin_deresiewicz\"` (micro-slip, Thornton–Yin) or `\"mdr\"` (micro-slip, exact for any load history).",
    ),
    key(
        "cohesion",
        "Cohesion model: `\"none\"` (default), `\"sjkr\"` or `\"jkr\"`.",
    ),
    key(
        "cohesion_energy_density",
        "SJKR cohesion energy density, J/m³.",
    ),
    key("surface_energy", "JKR work of adhesion, J/m²."),
    key(
        "twisting",
        "Twisting resistance: `\"none\"` (default) or `\"marshall\"`.",
    ),
];

/// The keys of `[[template]]` ([`RawTemplate`]).
pub const TEMPLATE_KEYS: &[Key] = &[
    key("name", "Name."),
    key("material", "Material name."),
    key("spheres", "Inline spheres `[x, y, z, r]`, m (input frame)."),
    key(
        "file",
        "LIGGGHTS `x y z r` file, relative to the scenario file.",
    ),
    key("shape", "Built-in shape."),
    key("radius", "Sphere radius of a built-in shape, m."),
    key("n", "Number of spheres of a rod."),
    key("spacing", "Centre spacing of a rod, m."),
    key("edge", "Edge of a tetrahedron or cube, m."),
    key(
        "scale",
        "Length scale factor applied to the spheres (dimensionless, default 1).",
    ),
    key("mass", "Mass override, kg (needs `inertia`)."),
    key(
        "inertia",
        "Inertia tensor override about the centre of mass, input frame, kg m².",
    ),
    key(
        "center_of_mass",
        "Centre of mass override, input frame, m (with `mass` and `inertia`, taken about it).",
    ),
    key(
        "force_flags",
        "Force flags per world axis of the template's bodies (LIGGGHTS `fflag`).",
    ),
    key(
        "torque_flags",
        "Torque flags per world axis of the template's bodies (LIGGGHTS `tflag`).",
    ),
];

/// The keys of the `size` of a `[[mix.component]]` ([`RawSize`]).
pub const SIZE_KEYS: &[Key] = &[
    key("distribution", "Kind of distribution."),
    key("scale", "Scale of a fixed distribution."),
    key("min", "Smallest scale."),
    key("max", "Largest scale."),
    key("mean", "Mean scale (normal)."),
    key("std", "Standard deviation of the scale (normal)."),
];

/// The keys of `[[mix.component]]` ([`RawComponent`]).
pub const COMPONENT_KEYS: &[Key] = &[
    key("template", "Template name."),
    key("fraction", "Relative share (by number or mass), default 1."),
    key("size", "Size distribution (default: the template as is)."),
];

/// The keys of `[[mix]]` ([`RawMix`]).
pub const MIX_KEYS: &[Key] = &[
    key("name", "Name."),
    key("basis", "`\"number\"` (default) or `\"mass\"`."),
    key("component", "Components."),
];

/// The keys of the `region` of an `[[insert]]` ([`RawRegion`]).
pub const REGION_KEYS: &[Key] = &[
    key("type", "`\"box\"` or `\"cylinder\"`."),
    key("lo", "Box lower corner, m."),
    key("hi", "Box upper corner, m."),
    key("base", "Cylinder: centre of the bottom disc, m."),
    key("axis", "Cylinder axis (unit vector, default `[0, 0, 1]`)."),
    key("radius", "Cylinder radius, m."),
    key("height", "Cylinder height, m."),
];

/// The keys of `[[insert]]` ([`RawInsert`]).
pub const INSERT_KEYS: &[Key] = &[
    key("kind", "`\"file\"`, `\"pack\"` or `\"stream\"`."),
    key("stage", "Stage in which it happens (default the first)."),
    key(
        "file",
        "Body file (kind = \"file\"), relative to the scenario file.",
    ),
    key(
        "format",
        "Layout of the body file (kind = \"file\"; default `csv`).",
    ),
    key(
        "orientation_frame",
        "Frame the body file's quaternions start from (kind = \"file\"; default `body`).",
    ),
    key("mix", "Mix name."),
    key("template", "Template name (instead of a mix)."),
    key("count", "Number of bodies (pack; stream: optional limit)."),
    key(
        "volume_fraction",
        "Solid volume fraction of the region (pack).",
    ),
    key("region", "Region."),
    key("seed", "Random seed (default 1)."),
    key("velocity", "Initial velocity, world frame, m/s."),
    key(
        "orientation",
        "Fixed orientation quaternion `[w, x, y, z]` (default random).",
    ),
    key("bodies_per_second", "Stream rate, bodies/s."),
    key("kg_per_second", "Stream rate, kg/s."),
    key("start", "Stream start, s after the stage start."),
    key(
        "end",
        "Stream end, s after the stage start (default the end of the stage).",
    ),
    key("max_attempts", "Placement attempts per body."),
    key(
        "euler",
        "Fixed orientation as z-x-z Euler angles `[phi, theta, psi]`, rad (pack, stream).",
    ),
    key(
        "angular_velocity",
        "Initial angular velocity, world frame, rad/s (pack, stream).",
    ),
    key(
        "force_flags",
        "Force flags per world axis (over the template's).",
    ),
    key(
        "torque_flags",
        "Torque flags per world axis (over the template's).",
    ),
    key(
        "fixed",
        "The bodies never move (LIGGGHTS `fix freeze`); they still make contacts.",
    ),
    key(
        "driven",
        "The bodies keep their initial velocity and angular velocity.",
    ),
    key(
        "start_after",
        "Stream: seconds each body moves ballistically after insertion.",
    ),
];

/// The keys of the `rotation` of a mesh `[[wall]]` ([`RawRotation`]).
pub const ROTATION_KEYS: &[Key] = &[
    key(
        "axis",
        "Rotation axis, world frame (normalised; need not be unit).",
    ),
    key(
        "angle",
        "Rotation angle, degrees (positive: counter-clockwise looking down the axis).",
    ),
];

/// The keys of `[[wall]]` ([`RawWall`]).
pub const WALL_KEYS: &[Key] = &[
    key("name", "Name."),
    key("material", "Material name."),
    key("type", "`\"plane\"`, `\"cylinder\"`, `\"box\"`, `\"mesh\"`."),
    key("file", "Mesh: STL or OBJ file, relative to the scenario file."),
    key("scale", "Mesh: factor from file units to m (default 1)."),
    key("rotation", "Mesh: rotation applied after scaling (file frame → world frame)."),
    key("offset", "Mesh: translation applied last, world frame, m (default 0)."),
    key("merge_angle", "Mesh: contacts whose normals are closer than this angle are one contact patch, degrees (default 15)."),
    key("torque_point", "Point about which the torque on the wall is reported, world frame, m (default: the centre of rotation, moving with the wall)."),
    key("point", "Plane: a point; cylinder: a point on the axis, m."),
    key("normal", "Plane unit normal (towards the particles)."),
    key("axis", "Cylinder unit axis."),
    key("radius", "Cylinder radius, m."),
    key("inside", "Cylinder/box: particles inside (default true)."),
    key("lo", "Box lower corner, m."),
    key("hi", "Box upper corner, m."),
    key("velocity", "Translation velocity, m/s."),
    key("angular_velocity", "Angular velocity about `center`, rad/s."),
    key("center", "Centre of rotation, m."),
    key("surface_velocity", "Extra tangential surface velocity, m/s."),
    key("multi_contact", "Several-contact treatment."),
    key("active", "Whether the wall is active at the start (default true)."),
];

/// The keys of `[[stage.wall]]` ([`RawWallChange`]).
pub const WALL_CHANGE_KEYS: &[Key] = &[
    key("name", "Wall name."),
    key("active", "Set active/inactive."),
    key("velocity", "New translation velocity, m/s."),
    key("angular_velocity", "New angular velocity, rad/s."),
    key("center", "New centre of rotation, m."),
    key("surface_velocity", "New surface velocity, m/s."),
];

/// The keys of `[[stage]]` ([`RawStage`]).
pub const STAGE_KEYS: &[Key] = &[
    key("name", "Name (default `stage1`, `stage2`, …)."),
    key("duration", "Duration, s."),
    key("steps", "Duration in steps."),
    key("gravity", "New gravity from this stage on, m/s²."),
    key("wall", "Wall changes."),
    key("body", "Body changes."),
];

/// The keys of `[[stage.body]]` ([`RawBodyChange`]).
pub const BODY_CHANGE_KEYS: &[Key] = &[
    key("id", "Global body id (1-based, in insertion order)."),
    key("velocity", "New centre-of-mass velocity, m/s."),
    key(
        "angular_velocity",
        "New angular velocity (world frame), rad/s.",
    ),
];

/// The keys of `[output.vtk]`, `[output.thermo]`, `[output.checkpoint]` and `[output.contacts]` ([`RawEvery`]).
pub const EVERY_KEYS: &[Key] = &[
    key("every", "Interval, s."),
    key("every_steps", "Interval, steps."),
];

/// The keys of `[output.trajectory]` ([`RawTrajectory`]).
pub const TRAJECTORY_KEYS: &[Key] = &[
    key(
        "bodies",
        "Body ids (1-based global ids, in insertion order).",
    ),
    key("every", "Interval, s."),
    key("every_steps", "Interval, steps."),
    key(
        "euler",
        "Also write the z-x-z Euler angles and the rows of A.",
    ),
    key("loads", "Also write the body's force and torque."),
];

/// The keys of `[output]` ([`RawOutput`]).
pub const OUTPUT_KEYS: &[Key] = &[
    key(
        "directory",
        "Output directory, relative to the working directory (default `out`).",
    ),
    key("vtk", "VTK interval."),
    key("thermo", "Thermo interval."),
    key("checkpoint", "Checkpoint interval."),
    key("trajectory", "Trajectories."),
    key(
        "vtk_format",
        "File format of the VTK frames: `\"vtp\"` (default) or `\"vtu\"` (for readers without PolyData, e.g. meshio).",
    ),
    key(
        "contacts",
        "Contact frames interval: contacts_<step>.vtp (one line per contact), network_<step>.csv and a bodies frame at the same step.",
    ),
    key("fields", "Coarse-grained fields (`[output.fields]`)."),
    key("flow", "Flow measurement probes (`[[output.flow]]`), written to flow.csv."),
];

/// The keys of `[[output.flow]]` ([`RawFlow`]).
pub const FLOW_KEYS: &[Key] = &[
    key("name", "Name of the probe (prefix of its flow.csv columns)."),
    key("type", "`\"plane\"` (bodies crossing, with direction) or `\"region\"` (bodies held, size distribution)."),
    key("point", "A point of the plane, m."),
    key("normal", "Normal of the plane; crossings along it count as positive."),
    key("lo", "Lower corner of the region (box), m."),
    key("hi", "Upper corner of the region (box), m."),
    key("bins", "Edges of the volume-equivalent diameter bins of the region's size distribution, m, ascending."),
    key("every", "Sampling interval, s (the same for every probe)."),
    key("every_steps", "Sampling interval, steps."),
];

/// The keys of `[output.fields]` ([`RawFields`]).
pub const FIELDS_KEYS: &[Key] = &[
    key("every", "Interval, s."),
    key("every_steps", "Interval, steps."),
    key(
        "axes",
        "Grid axes, 1 to 3 of `\"x\"`, `\"y\"`, `\"z\"`; the fields are averaged over the others.",
    ),
    key("cells", "Cells along each grid axis (≥ 1)."),
    key(
        "lo",
        "Lower end along each grid axis, m (default: the domain's).",
    ),
    key(
        "hi",
        "Upper end along each grid axis, m (default: the domain's).",
    ),
    key(
        "kernel",
        "`\"gaussian\"` (cut at 3 widths, default) or `\"lucy\"`.",
    ),
    key("width", "Kernel width (standard deviation), m."),
    key(
        "average",
        "Also write the time average over the frames (default false).",
    ),
];
/// The keys of each `[[wall]]` type (the other keys of [`WALL_KEYS`] apply
/// to every wall).
pub const WALL_TYPE_KEYS: &[KindKeys] = &[
    KindKeys {
        kind: "plane",
        keys: &["point", "normal"],
    },
    KindKeys {
        kind: "cylinder",
        keys: &["point", "axis", "radius", "inside"],
    },
    KindKeys {
        kind: "box",
        keys: &["lo", "hi", "inside"],
    },
    KindKeys {
        kind: "mesh",
        keys: &["file", "scale", "rotation", "offset", "merge_angle"],
    },
];

/// The keys of each insertion `region` type (besides `type`).
pub const REGION_TYPE_KEYS: &[KindKeys] = &[
    KindKeys {
        kind: "box",
        keys: &["lo", "hi"],
    },
    KindKeys {
        kind: "cylinder",
        keys: &["base", "axis", "radius", "height"],
    },
];

/// The keys of each `[[insert]]` kind (besides `kind` and `stage`).
pub const INSERT_KIND_KEYS: &[KindKeys] = &[
    KindKeys {
        kind: "file",
        keys: &[
            "file",
            "template",
            "format",
            "orientation_frame",
            "force_flags",
            "torque_flags",
            "fixed",
            "driven",
        ],
    },
    KindKeys {
        kind: "pack",
        keys: &[
            "mix",
            "template",
            "count",
            "volume_fraction",
            "region",
            "seed",
            "velocity",
            "orientation",
            "max_attempts",
            "euler",
            "angular_velocity",
            "force_flags",
            "torque_flags",
            "fixed",
            "driven",
        ],
    },
    KindKeys {
        kind: "stream",
        keys: &[
            "mix",
            "template",
            "count",
            "region",
            "seed",
            "velocity",
            "orientation",
            "bodies_per_second",
            "kg_per_second",
            "start",
            "end",
            "max_attempts",
            "euler",
            "angular_velocity",
            "force_flags",
            "torque_flags",
            "fixed",
            "driven",
            "start_after",
        ],
    },
];

/// Every table's keys.
pub const TABLES: &[&[Key]] = &[
    SCENARIO_KEYS,
    SIMULATION_KEYS,
    DOMAIN_KEYS,
    INTEGRATOR_KEYS,
    ADDED_MASS_KEYS,
    MATERIAL_KEYS,
    CONTACT_KEYS,
    PAIR_KEYS,
    TEMPLATE_KEYS,
    SIZE_KEYS,
    COMPONENT_KEYS,
    MIX_KEYS,
    REGION_KEYS,
    INSERT_KEYS,
    ROTATION_KEYS,
    WALL_KEYS,
    WALL_CHANGE_KEYS,
    STAGE_KEYS,
    BODY_CHANGE_KEYS,
    EVERY_KEYS,
    TRAJECTORY_KEYS,
    OUTPUT_KEYS,
    FIELDS_KEYS,
    FLOW_KEYS,
];

/// The table whose keys are `names`, in order (serde lists a struct's
/// fields in this order when it meets an unknown key).
pub fn table_with(names: &[String]) -> Option<&'static [Key]> {
    TABLES
        .iter()
        .copied()
        .find(|t| t.len() == names.len() && t.iter().zip(names).all(|(k, n)| k.name == n))
}

/// The keys of `kind` in `kinds` (none for a kind not listed).
pub fn kind_keys(kinds: &[KindKeys], kind: &str) -> &'static [&'static str] {
    kinds
        .iter()
        .find(|k| k.kind == kind)
        .map_or(&[], |k| k.keys)
}

/// Every key that belongs to some kinds only, each once, in the order the
/// kinds first name it: the order in which misplaced keys are reported.
pub fn kind_specific(kinds: &[KindKeys]) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for k in kinds.iter().flat_map(|k| k.keys) {
        if !out.contains(k) {
            out.push(k);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::de::DeserializeOwned;

    /// The field names serde accepts for `T`, from its unknown-field error.
    fn serde_fields<T: DeserializeOwned + std::fmt::Debug>() -> Vec<String> {
        let e = toml::from_str::<T>("not_a_key_of_any_table = 0").unwrap_err();
        let msg = e.message().to_string();
        let tail = msg
            .strip_prefix("unknown field `not_a_key_of_any_table`, expected ")
            .unwrap_or_else(|| panic!("unexpected serde message: {msg}"));
        tail.split('`')
            .skip(1)
            .step_by(2)
            .map(str::to_string)
            .collect()
    }

    fn names(t: &[Key]) -> Vec<String> {
        t.iter().map(|k| k.name.to_string()).collect()
    }

    #[test]
    fn every_table_lists_the_fields_of_its_raw_struct_in_order() {
        macro_rules! case {
            ($raw:ident, $table:expr) => {
                (stringify!($raw), $table, serde_fields::<$raw>())
            };
        }
        let cases: Vec<(&str, &[Key], Vec<String>)> = vec![
            case!(RawScenario, SCENARIO_KEYS),
            case!(RawSimulation, SIMULATION_KEYS),
            case!(RawDomain, DOMAIN_KEYS),
            case!(RawIntegrator, INTEGRATOR_KEYS),
            case!(RawAddedMass, ADDED_MASS_KEYS),
            case!(RawMaterial, MATERIAL_KEYS),
            case!(RawContact, CONTACT_KEYS),
            case!(RawPair, PAIR_KEYS),
            case!(RawTemplate, TEMPLATE_KEYS),
            case!(RawSize, SIZE_KEYS),
            case!(RawComponent, COMPONENT_KEYS),
            case!(RawMix, MIX_KEYS),
            case!(RawRegion, REGION_KEYS),
            case!(RawInsert, INSERT_KEYS),
            case!(RawRotation, ROTATION_KEYS),
            case!(RawWall, WALL_KEYS),
            case!(RawWallChange, WALL_CHANGE_KEYS),
            case!(RawStage, STAGE_KEYS),
            case!(RawBodyChange, BODY_CHANGE_KEYS),
            case!(RawEvery, EVERY_KEYS),
            case!(RawTrajectory, TRAJECTORY_KEYS),
            case!(RawOutput, OUTPUT_KEYS),
            case!(RawFields, FIELDS_KEYS),
            case!(RawFlow, FLOW_KEYS),
        ];
        assert_eq!(cases.len(), TABLES.len(), "every table is checked");
        for (raw, table, fields) in cases {
            assert!(fields.len() > 1, "{raw}: serde listed {fields:?}");
            assert_eq!(
                names(table),
                fields,
                "the key table of {raw} vs its serde fields"
            );
            assert!(
                table.iter().all(|k| !k.help.is_empty()),
                "{raw}: every key has a help"
            );
            assert_eq!(
                table_with(&fields),
                Some(table),
                "{raw} is found by its fields"
            );
        }
    }

    #[test]
    fn kind_keys_are_keys_of_their_table_and_kinds_are_accepted_values() {
        let cases: [(&str, &[Key], &[KindKeys], &str); 3] = [
            ("wall", WALL_KEYS, WALL_TYPE_KEYS, "type"),
            ("region", REGION_KEYS, REGION_TYPE_KEYS, "type"),
            ("insert", INSERT_KEYS, INSERT_KIND_KEYS, "kind"),
        ];
        for (what, table, kinds, tag) in cases {
            for k in kinds {
                for n in k.keys {
                    assert!(
                        table.iter().any(|t| t.name == *n),
                        "{what} {tag} \"{}\": '{n}' is not a key of the table",
                        k.kind
                    );
                }
                let text = format!("{tag} = \"{}\"", k.kind);
                let ok = match what {
                    "wall" => toml::from_str::<RawWall>(&text).is_ok(),
                    "region" => toml::from_str::<RawRegion>(&text).is_ok(),
                    _ => toml::from_str::<RawInsert>(&text).is_ok(),
                };
                assert!(ok, "{what}: {text} is not accepted");
            }
        }
        // every wall type and insert kind has its list
        for v in ["plane", "cylinder", "box", "mesh"] {
            assert!(!kind_keys(WALL_TYPE_KEYS, v).is_empty(), "wall type {v}");
        }
        for v in ["file", "pack", "stream"] {
            assert!(
                !kind_keys(INSERT_KIND_KEYS, v).is_empty(),
                "insert kind {v}"
            );
        }
    }

    #[test]
    fn kind_specific_keys_keep_the_first_order() {
        assert_eq!(
            kind_specific(WALL_TYPE_KEYS),
            [
                "point",
                "normal",
                "axis",
                "radius",
                "inside",
                "lo",
                "hi",
                "file",
                "scale",
                "rotation",
                "offset",
                "merge_angle"
            ]
        );
        assert_eq!(
            kind_specific(REGION_TYPE_KEYS),
            ["lo", "hi", "base", "axis", "radius", "height"]
        );
    }
}
