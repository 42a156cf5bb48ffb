//! The walls of a world, the triangle meshes mesh walls refer to, and the
//! load each wall felt in the last force evaluation.

use super::{TriMesh, Wall, WallLoad};

/// The walls, in scenario order (a wall's index names it in contacts and
/// loads). Reads and writes like a slice of walls: changing a wall's motion
/// or switching it on or off between steps is allowed (the step notices a
/// wall that starts to move); walls and meshes are added through
/// `World::add_wall` and `World::add_mesh`.
#[derive(Debug, Clone, Default)]
pub struct WallSet {
    pub(crate) list: Vec<Wall>,
    /// Meshes of [`super::WallShape::Mesh`] walls (static geometry from the
    /// scenario, mesh frame; not checkpointed).
    pub(crate) meshes: Vec<TriMesh>,
    /// Load on each wall from the last force evaluation, world frame.
    pub(crate) loads: Vec<WallLoad>,
}

impl WallSet {
    /// The triangle meshes that mesh walls refer to.
    pub fn meshes(&self) -> &[TriMesh] {
        &self.meshes
    }

    /// The load on each wall from the last force evaluation (force and
    /// torque exerted by the particles, world frame).
    pub fn loads(&self) -> &[WallLoad] {
        &self.loads
    }
}

impl std::ops::Deref for WallSet {
    type Target = [Wall];
    fn deref(&self) -> &[Wall] {
        &self.list
    }
}

impl std::ops::DerefMut for WallSet {
    fn deref_mut(&mut self) -> &mut [Wall] {
        &mut self.list
    }
}

impl<'a> IntoIterator for &'a WallSet {
    type Item = &'a Wall;
    type IntoIter = std::slice::Iter<'a, Wall>;
    fn into_iter(self) -> Self::IntoIter {
        self.list.iter()
    }
}

impl<'a> IntoIterator for &'a mut WallSet {
    type Item = &'a mut Wall;
    type IntoIter = std::slice::IterMut<'a, Wall>;
    fn into_iter(self) -> Self::IntoIter {
        self.list.iter_mut()
    }
}
