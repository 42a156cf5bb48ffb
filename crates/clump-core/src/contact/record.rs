//! Per-contact records: what a step keeps of each contact it evaluated when
//! a driver asks for them (read through `World::contacts`, see
//! `crate::recorded_contacts`). Written by the pair kernel and the gather.

use glam::DVec3;

/// One sphere–sphere contact as the pair kernel evaluated it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PairRecord {
    /// Unit normal from sphere `j` to sphere `i`, world frame.
    pub normal: DVec3,
    /// Overlap, m.
    pub overlap: f64,
    /// Force on sphere `i`, multi-contact scale applied, world frame, N.
    pub force: DVec3,
    /// Signed normal force on `i`, scale applied, N.
    pub normal_force: f64,
}

/// One sphere–wall contact as the gather evaluated it.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WallRecord {
    /// Storage index of the sphere.
    pub sphere: u32,
    /// Wall index.
    pub wall: u32,
    /// Face of an analytic wall (box faces 0..6, else 0); for a mesh wall
    /// the octahedral code of the contact normal (its patch).
    pub patch: u16,
    /// Unit normal from the wall to the sphere centre, world frame.
    pub normal: DVec3,
    /// Overlap, m.
    pub overlap: f64,
    /// Force on the sphere, multi-contact scale applied, world frame, N.
    pub force: DVec3,
    /// Signed normal force on the sphere, scale applied, N.
    pub normal_force: f64,
    /// Tangential spring after the evaluation, world frame, m.
    pub spring: DVec3,
}

/// The records of the last step that was asked to keep them.
#[derive(Debug, Clone, Default)]
pub struct ContactRecords {
    /// The step now running stores records.
    pub recording: bool,
    /// The world step the records describe (the step count after the step
    /// that stored them); `None`: no records.
    pub step: Option<u64>,
    /// Per pair of the pair list (valid where the pair touches).
    pub pair: Vec<PairRecord>,
    /// Per gather chunk, its wall contacts in the gather's order.
    pub wall: Vec<Vec<WallRecord>>,
    /// Exact sums of the requested step's contacts (thermo rows).
    pub sums: super::step_sums::StepSums,
}

impl ContactRecords {
    /// Whether the coming step stores records.
    pub fn set_recording(&mut self, on: bool) {
        self.recording = on;
    }

    /// When the step now running stores records: one empty list of wall
    /// contacts per gather chunk of `nchunks`. Returns whether it stores.
    pub(crate) fn start_wall_chunks(&mut self, nchunks: usize) -> bool {
        if self.recording {
            self.wall.resize_with(nchunks, Vec::new);
            self.wall.truncate(nchunks);
            self.wall.iter_mut().for_each(Vec::clear);
        }
        self.recording
    }
}
