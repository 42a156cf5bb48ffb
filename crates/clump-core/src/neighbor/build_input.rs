//! What a neighbour build reads: the spheres as they stand at the build,
//! and the histories carried to the new lists by global sphere id.

use crate::contact::mdr::SlipProfile;
use crate::contact::ContactHistory;
use std::collections::HashMap;

/// Contact histories keyed by (lower, higher) global sphere id.
pub type HistoryMap = HashMap<(u64, u64), ContactHistory, rustc_hash::FxBuildHasher>;

/// MDR profiles ([`crate::contact::mdr`]) carried by global sphere ids,
/// as [`HistoryMap`] (lower id first, oriented from the lower to the higher).
pub type SlipMap = HashMap<(u64, u64), SlipProfile, rustc_hash::FxBuildHasher>;

/// Inputs describing the spheres for a build.
pub struct BuildInput<'a> {
    /// Sphere states: their centres at the build (world frame, m) are the
    /// ones read.
    pub state: &'a [crate::sphere::SphereState],
    /// Radii, m.
    pub radius: &'a [f64],
    /// Owner body (storage index).
    pub body: &'a [u32],
    /// First sphere of each body; the last entry is the number of spheres
    /// (a body's spheres are contiguous).
    pub body_first: &'a [u32],
    /// Global sphere ids.
    pub gid: &'a [u64],
    /// Verlet skin, m.
    pub skin: f64,
    /// Keep rolling springs: some law of the contact table has rolling
    /// resistance or is composed by the scalar path.
    pub rolling: bool,
    /// Keep MDR profiles (some law is `tangential = "mdr"`), with the
    /// profiles carried by global id (may be empty); `None`: keep none.
    pub slip: Option<&'a SlipMap>,
    /// Per body: owned by this rank. A rank's part (ghosts among its
    /// bodies) leaves out the pairs between two bodies it does not own;
    /// `None`: every pair.
    pub owned: Option<&'a [bool]>,
}
