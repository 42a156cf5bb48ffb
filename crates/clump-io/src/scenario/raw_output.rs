//! The `[output]` table of the scenario file as written (serde structures,
//! `deny_unknown_fields`), declared with [`table!`] as the tables of
//! [`super::raw`]: intervals, trajectories, contact frames, coarse-grained
//! fields and flow probes. Units are SI and stated on every field.

use super::keys::table;

table! {
    /// An output interval.
    pub struct RawEvery {
        /// Interval, s.
        pub every: Option<f64>,
        /// Interval, steps.
        pub every_steps: Option<u64>,
    }
}

table! {
    /// `[output.trajectory]`.
    pub struct RawTrajectory {
        /// Body ids (1-based global ids, in insertion order).
        #[serde(default)]
        pub bodies: Vec<u64>,
        /// Interval, s.
        pub every: Option<f64>,
        /// Interval, steps.
        pub every_steps: Option<u64>,
        /// Also write the z-x-z Euler angles and the rows of A.
        pub euler: Option<bool>,
        /// Also write the body's force and torque.
        pub loads: Option<bool>,
    }
}

table! {
    /// `[output]`.
    pub struct RawOutput {
        /// Output directory, relative to the working directory (default `out`).
        pub directory: Option<String>,
        /// VTK interval.
        pub vtk: Option<RawEvery>,
        /// Thermo interval.
        pub thermo: Option<RawEvery>,
        /// Checkpoint interval.
        pub checkpoint: Option<RawEvery>,
        /// Trajectories.
        pub trajectory: Option<RawTrajectory>,
        /// File format of the VTK frames: `"vtp"` (default) or `"vtu"` (for readers without
        /// PolyData, e.g. meshio).
        pub vtk_format: Option<crate::vtu::VtkFormat>,
        /// Contact frames interval: contacts_<step>.vtp (one line per contact),
        /// network_<step>.csv and a bodies frame at the same step.
        pub contacts: Option<RawEvery>,
        /// Coarse-grained fields (`[output.fields]`).
        pub fields: Option<RawFields>,
        /// Flow measurement probes (`[[output.flow]]`), written to flow.csv.
        #[serde(default)]
        pub flow: Vec<RawFlow>,
    }
}

table! {
    /// `[[output.flow]]`.
    pub struct RawFlow {
        /// Name of the probe (prefix of its flow.csv columns).
        pub name: Option<String>,
        /// `"plane"` (bodies crossing, with direction) or `"region"` (bodies held, size
        /// distribution).
        #[key = "type"]
        pub kind: Option<String>,
        /// A point of the plane, m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub point: Option<[f64; 3]>,
        /// Normal of the plane; crossings along it count as positive.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub normal: Option<[f64; 3]>,
        /// Lower corner of the region (box), m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub lo: Option<[f64; 3]>,
        /// Upper corner of the region (box), m.
        #[serde(default, deserialize_with = "super::exact::array")]
        pub hi: Option<[f64; 3]>,
        /// Edges of the volume-equivalent diameter bins of the region's size distribution, m,
        /// ascending.
        pub bins: Option<Vec<f64>>,
        /// Sampling interval, s (the same for every probe).
        pub every: Option<f64>,
        /// Sampling interval, steps.
        pub every_steps: Option<u64>,
    }
}

table! {
    /// `[output.fields]`.
    pub struct RawFields {
        /// Interval, s.
        pub every: Option<f64>,
        /// Interval, steps.
        pub every_steps: Option<u64>,
        /// Grid axes, 1 to 3 of `"x"`, `"y"`, `"z"`; the fields are averaged over the others.
        #[serde(default)]
        pub axes: Vec<String>,
        /// Cells along each grid axis (≥ 1).
        #[serde(default)]
        pub cells: Vec<i64>,
        /// Lower end along each grid axis, m (default: the domain's).
        pub lo: Option<Vec<f64>>,
        /// Upper end along each grid axis, m (default: the domain's).
        pub hi: Option<Vec<f64>>,
        /// `"gaussian"` (cut at 3 widths, default) or `"lucy"`.
        pub kernel: Option<crate::post::kernel::Kernel>,
        /// Kernel width (standard deviation), m.
        pub width: Option<f64>,
        /// Also write the time average over the frames (default false).
        pub average: Option<bool>,
    }
}
