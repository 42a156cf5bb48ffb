//! Wall geometry and sphere–wall contact detection.

use super::mesh::{MeshContact, TriMesh, MAX_MESH_CONTACTS};
use glam::{DQuat, DVec3};
use serde::{Deserialize, Serialize};

/// At most this many faces of one wall can touch one sphere (an inside box
/// corner touches three; a mesh up to [`MAX_MESH_CONTACTS`]).
pub const MAX_TOUCHES_PER_WALL: usize = MAX_MESH_CONTACTS;

/// Geometry of a wall, world frame, m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", tag = "type")]
pub enum WallShape {
    /// An infinite plane through `point`; spheres live on the side `normal`
    /// points to (unit normal).
    Plane {
        /// A point on the plane, m.
        point: DVec3,
        /// Unit normal pointing into the granular side.
        normal: DVec3,
    },
    /// An infinite circular cylinder with axis through `point` along `axis`
    /// (unit), radius `radius`. `inside = true`: spheres are inside (a drum);
    /// `false`: outside (a pin or pipe).
    Cylinder {
        /// A point on the axis, m.
        point: DVec3,
        /// Unit axis direction.
        axis: DVec3,
        /// Radius, m.
        radius: f64,
        /// Spheres inside (`true`) or outside (`false`).
        inside: bool,
    },
    /// An axis-aligned box `[lo, hi]`. `inside = true`: a container, each of
    /// its six faces is a one-sided plane and a sphere in a corner touches
    /// up to three faces; `false`: a solid obstacle.
    Box {
        /// Lower corner, m.
        lo: DVec3,
        /// Upper corner, m.
        hi: DVec3,
        /// Spheres inside (`true`) or outside (`false`).
        inside: bool,
    },
    /// A triangle mesh (two-sided): `World::meshes`](crate::world::World::meshes)`[mesh`
    /// placed at the pose `x_world = position + orientation · x_mesh`. The
    /// pose moves with the wall's motion; the mesh is static geometry. See
    /// [`super::mesh`] for the contact rules.
    Mesh {
        /// Index into `World::meshes`.
        mesh: u32,
        /// Position of the mesh-frame origin, world frame, m.
        position: DVec3,
        /// Rotation mesh frame → world frame (unit quaternion).
        orientation: DQuat,
    },
}

/// One touching face of a wall.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct WallTouch {
    /// Face index within the wall (0 for single-faced shapes; 0..6 for box faces).
    pub face: u8,
    /// Unit normal from the wall towards the sphere centre, world frame.
    pub normal: DVec3,
    /// Overlap δ > 0, m.
    pub overlap: f64,
}

impl WallShape {
    /// Like [`WallShape::contacts`] without the mesh table: a
    /// [`WallShape::Mesh`] reports no touch here. Use `contacts` with
    /// `&world.walls.meshes` wherever mesh walls may occur.
    pub fn touches(
        &self,
        x: DVec3,
        r: f64,
        margin: f64,
        out: &mut [WallTouch; MAX_TOUCHES_PER_WALL],
    ) -> usize {
        self.contacts(&[], x, r, margin, out)
    }

    /// Touching faces for a sphere with centre `x` (world, m) and radius `r`
    /// (m), within the extra distance `margin` ≥ 0 (m; use 0 for real
    /// contacts); `meshes` is the mesh table of the world
    /// (`WallSet::meshes` (`World::walls`)) that
    /// [`WallShape::Mesh`] indexes. Writes into `out` and returns the count. A
    /// touch with `overlap ≤ 0` is only reported when `margin > 0` (it is
    /// then a near miss within the margin). A mesh wall gives one touch per
    /// contact patch, deepest first, with `face = 0`.
    pub fn contacts(
        &self,
        meshes: &[TriMesh],
        x: DVec3,
        r: f64,
        margin: f64,
        out: &mut [WallTouch; MAX_TOUCHES_PER_WALL],
    ) -> usize {
        match *self {
            WallShape::Mesh {
                mesh,
                position,
                orientation,
            } => {
                let Some(m) = meshes.get(mesh as usize) else {
                    return 0;
                };
                let identity = orientation == DQuat::IDENTITY;
                let xl = if identity {
                    x - position
                } else {
                    orientation.inverse() * (x - position)
                };
                let mut buf = [MeshContact::default(); MAX_MESH_CONTACTS];
                let k = m.sphere_contacts(xl, r, margin, &mut buf);
                for (o, c) in out.iter_mut().zip(&buf[..k]) {
                    let normal = if identity {
                        c.normal
                    } else {
                        orientation * c.normal
                    };
                    *o = WallTouch {
                        face: 0,
                        normal,
                        overlap: c.overlap,
                    };
                }
                k
            }
            WallShape::Plane { point, normal } => {
                let dist = (x - point).dot(normal);
                let overlap = r - dist;
                if overlap + margin > 0.0 {
                    out[0] = WallTouch {
                        face: 0,
                        normal,
                        overlap,
                    };
                    1
                } else {
                    0
                }
            }
            WallShape::Cylinder {
                point,
                axis,
                radius,
                inside,
            } => {
                let rel = x - point;
                let rho = rel - axis * rel.dot(axis);
                let d = rho.length();
                let (overlap, normal) = if inside {
                    (d + r - radius, if d > 0.0 { -rho / d } else { DVec3::ZERO })
                } else {
                    (radius + r - d, if d > 0.0 { rho / d } else { DVec3::ZERO })
                };
                if overlap + margin > 0.0 && normal != DVec3::ZERO {
                    out[0] = WallTouch {
                        face: 0,
                        normal,
                        overlap,
                    };
                    1
                } else {
                    0
                }
            }
            WallShape::Box { lo, hi, inside } => {
                if inside {
                    let mut n = 0;
                    for a in 0..3 {
                        for (side, face) in [(0usize, 2 * a), (1, 2 * a + 1)] {
                            let (dist, sign) = if side == 0 {
                                (x[a] - lo[a], 1.0)
                            } else {
                                (hi[a] - x[a], -1.0)
                            };
                            let overlap = r - dist;
                            if overlap + margin > 0.0 && n < MAX_TOUCHES_PER_WALL {
                                let mut normal = DVec3::ZERO;
                                normal[a] = sign;
                                out[n] = WallTouch {
                                    face: face as u8,
                                    normal,
                                    overlap,
                                };
                                n += 1;
                            }
                        }
                    }
                    n
                } else {
                    let c = x.clamp(lo, hi);
                    let d = x - c;
                    let dl = d.length();
                    if dl > 0.0 {
                        let overlap = r - dl;
                        if overlap + margin > 0.0 {
                            out[0] = WallTouch {
                                face: 0,
                                normal: d / dl,
                                overlap,
                            };
                            return 1;
                        }
                        0
                    } else {
                        // centre inside the solid box: push out through the nearest face
                        let mut best = (f64::INFINITY, 0usize, 0.0);
                        for a in 0..3 {
                            let dlo = x[a] - lo[a];
                            let dhi = hi[a] - x[a];
                            if dlo < best.0 {
                                best = (dlo, a, -1.0);
                            }
                            if dhi < best.0 {
                                best = (dhi, a, 1.0);
                            }
                        }
                        let mut normal = DVec3::ZERO;
                        normal[best.1] = best.2;
                        out[0] = WallTouch {
                            face: 0,
                            normal,
                            overlap: r + best.0,
                        };
                        1
                    }
                }
            }
        }
    }

    /// Moves the geometry by `shift` (m, world) and then rotates it by `rot`
    /// about the (pre-shift) centre `center`.
    pub fn transform(&mut self, shift: DVec3, rot: Option<DQuat>, center: DVec3) {
        let c_new = center + shift;
        match self {
            WallShape::Plane { point, normal } => {
                *point += shift;
                if let Some(q) = rot {
                    *point = c_new + q * (*point - c_new);
                    *normal = (q * *normal).normalize();
                }
            }
            WallShape::Cylinder { point, axis, .. } => {
                *point += shift;
                if let Some(q) = rot {
                    *point = c_new + q * (*point - c_new);
                    *axis = (q * *axis).normalize();
                }
            }
            WallShape::Box { lo, hi, .. } => {
                // An axis-aligned box only translates; its angular velocity
                // acts as a surface velocity.
                *lo += shift;
                *hi += shift;
            }
            WallShape::Mesh {
                position,
                orientation,
                ..
            } => {
                *position += shift;
                if let Some(q) = rot {
                    *position = c_new + q * (*position - c_new);
                    *orientation = (q * *orientation).normalize();
                }
            }
        }
    }

    /// For a mesh wall: its mesh index and pose `(mesh, position m,
    /// orientation mesh → world)`; `None` for analytic shapes.
    pub fn mesh_pose(&self) -> Option<(u32, DVec3, DQuat)> {
        match *self {
            WallShape::Mesh {
                mesh,
                position,
                orientation,
            } => Some((mesh, position, orientation)),
            _ => None,
        }
    }

    /// For a mesh wall: its vertices in the world frame at the current pose
    /// and its triangles (e.g. for VTK output); `None` for analytic shapes or
    /// a mesh index not in `meshes`.
    pub fn mesh_at_pose<'m>(&self, meshes: &'m [TriMesh]) -> Option<(Vec<DVec3>, &'m [[u32; 3]])> {
        let (mesh, position, orientation) = self.mesh_pose()?;
        let m = meshes.get(mesh as usize)?;
        Some((m.vertices_at(position, orientation), m.triangles()))
    }
}
