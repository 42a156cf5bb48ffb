//! Triangle meshes: walls of arbitrary shape (imported from STL/OBJ by
//! `clump-io`), and the geometry behind templates generated from a mesh.
//!
//! A [`TriMesh`] is static geometry in its own *mesh frame* (m). A mesh wall
//! ([`super::WallShape::Mesh`]) refers to one by index into
//! `WallSet::meshes` (`World::walls`) and carries the *pose* that
//! maps the mesh frame to the world frame, `x_world = position + orientation ·
//! x_mesh`; the pose moves with the wall's prescribed motion and is part of
//! the checkpointed wall, the mesh itself comes from the scenario.
//!
//! # Contact detection (see [`TriMesh::sphere_contacts`])
//! Candidate triangles come from a bounding-volume hierarchy ([`bvh`]); for
//! each, the closest point and its feature (face, edge, vertex) are computed
//! ([`closest`]). The true contacts are the *local minima* of the distance
//! from the sphere centre to the surface, so that a sphere feels exactly one
//! contact per contact patch:
//! - a **face** contact is always a local minimum;
//! - an **edge** contact (closest point inside an edge) is kept only if no
//!   other triangle sharing that edge has a closer point, i.e. the centre is
//!   not over a neighbouring face: `(x − c)·(w − a) ≤ 0` for the apex `w` of
//!   every other triangle on edge `a–b`;
//! - a **vertex** contact at `v` is kept only if `(x − v)·(w − v) ≤ 0` for
//!   every vertex `w` joined to `v` by an edge (the vertex's Voronoi region).
//!
//! These tests carry a small tolerance in favour of keeping a contact; the
//! near-duplicates this lets through on region boundaries (and the same edge
//! or vertex found from each of its triangles) have parallel normals and are
//! merged: contacts whose normals are within [`TriMesh::merge_angle`] of a
//! deeper one are dropped. The merge also makes a finely faceted, slightly
//! concave surface (a tessellated drum) act like the smooth surface it
//! approximates, while a real concave corner (a hopper floor meeting its
//! wall, normals further apart than the merge angle) gives one contact per
//! face. Meshes are **two-sided**: the normal points from the closest point
//! towards the sphere centre, whatever the triangle winding.

pub mod bvh;
pub mod closest;
mod contact;
pub mod primitives;

pub use contact::{MeshContact, MAX_MESH_CONTACTS};

use bvh::Bvh;
use glam::{DQuat, DVec3};
use std::collections::HashMap;
use thiserror::Error;

/// Default [`TriMesh::merge_angle`]: 15°, in rad.
pub const DEFAULT_MERGE_ANGLE: f64 = 15.0 * std::f64::consts::PI / 180.0;

/// Why a mesh could not be built or is not fit for a purpose.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MeshError {
    /// No triangle (or none of non-zero area).
    #[error("the mesh has no triangle of non-zero area")]
    Empty,
    /// A triangle refers to a vertex that does not exist.
    #[error("triangle {triangle} refers to vertex {index}, but the mesh has {vertices} vertices")]
    BadIndex {
        /// Triangle index (0-based, input order).
        triangle: usize,
        /// The offending vertex index.
        index: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// A vertex coordinate is NaN or infinite.
    #[error("vertex {vertex} has a non-finite coordinate {coords:?}")]
    NonFinite {
        /// Vertex index (0-based).
        vertex: usize,
        /// Its coordinates.
        coords: [f64; 3],
    },
    /// An edge shared by more than two triangles (closed meshes only).
    #[error("non-manifold edge between vertices {a} and {b} (shared by {count} triangles)")]
    NonManifoldEdge {
        /// First vertex (the lower index).
        a: u32,
        /// Second vertex.
        b: u32,
        /// Number of triangles on the edge.
        count: usize,
    },
    /// An edge on only one triangle: the mesh has a hole (closed meshes only).
    #[error("open boundary edge between vertices {a} and {b}: the mesh is not closed")]
    OpenEdge {
        /// First vertex (the lower index).
        a: u32,
        /// Second vertex.
        b: u32,
    },
    /// The triangles of a closed mesh cannot be oriented consistently (a
    /// non-orientable surface).
    #[error("the mesh cannot be oriented consistently (at the edge between vertices {a} and {b})")]
    NonOrientable {
        /// First vertex.
        a: u32,
        /// Second vertex.
        b: u32,
    },
}

/// A static triangle mesh in its mesh frame (m), with its contact-search
/// structures. See the [module docs](self).
#[derive(Debug, Clone)]
pub struct TriMesh {
    vertices: Vec<DVec3>,
    triangles: Vec<[u32; 3]>,
    normals: Vec<DVec3>,
    vert_tri_start: Vec<u32>,
    vert_tri: Vec<u32>,
    bvh: Bvh,
    dropped: usize,
    /// Contacts of one sphere whose normals are closer than this angle (rad)
    /// are one contact patch: only the deepest is kept. Default
    /// [`DEFAULT_MERGE_ANGLE`]; set it above the angle between neighbouring
    /// facets of a tessellated smooth surface and below the angles of the
    /// real corners of the geometry.
    pub merge_angle: f64,
}

impl TriMesh {
    /// Builds a mesh from vertices (mesh frame, m) and triangles (three vertex
    /// indices each). Triangles of zero area are dropped (see
    /// [`TriMesh::dropped_triangles`]). Errors on an index out of range, a
    /// non-finite coordinate, or no triangle left.
    pub fn new(vertices: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        for (i, v) in vertices.iter().enumerate() {
            if !v.is_finite() {
                return Err(MeshError::NonFinite {
                    vertex: i,
                    coords: v.to_array(),
                });
            }
        }
        let nv = vertices.len();
        let mut kept = Vec::with_capacity(triangles.len());
        let mut normals = Vec::with_capacity(triangles.len());
        for (ti, t) in triangles.iter().enumerate() {
            for &i in t {
                if i as usize >= nv {
                    return Err(MeshError::BadIndex {
                        triangle: ti,
                        index: i,
                        vertices: nv,
                    });
                }
            }
            let (a, b, c) = (
                vertices[t[0] as usize],
                vertices[t[1] as usize],
                vertices[t[2] as usize],
            );
            let n = (b - a).cross(c - a);
            let len = n.length();
            let scale = (b - a).length_squared().max((c - a).length_squared());
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || !(len > 1e-12 * scale) {
                continue;
            }
            // divide (not multiply by the reciprocal) so that axis-aligned
            // normals are exact
            normals.push(n / len);
            kept.push(*t);
        }
        if kept.is_empty() {
            return Err(MeshError::Empty);
        }
        let dropped = triangles.len() - kept.len();
        // vertex → triangle incidence (CSR, triangles ascending)
        let mut count = vec![0u32; nv + 1];
        for t in &kept {
            for &i in t {
                count[i as usize + 1] += 1;
            }
        }
        for i in 0..nv {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let mut vert_tri = vec![0u32; count[nv] as usize];
        for (ti, t) in kept.iter().enumerate() {
            for &i in t {
                vert_tri[fill[i as usize] as usize] = ti as u32;
                fill[i as usize] += 1;
            }
        }
        let (lo, hi): (Vec<DVec3>, Vec<DVec3>) = kept
            .iter()
            .map(|t| {
                let (a, b, c) = (
                    vertices[t[0] as usize],
                    vertices[t[1] as usize],
                    vertices[t[2] as usize],
                );
                (a.min(b).min(c), a.max(b).max(c))
            })
            .unzip();
        let bvh = Bvh::build(&lo, &hi);
        Ok(TriMesh {
            vertices,
            triangles: kept,
            normals,
            vert_tri_start: count,
            vert_tri,
            bvh,
            dropped,
            merge_angle: DEFAULT_MERGE_ANGLE,
        })
    }

    /// Vertices, mesh frame, m.
    pub fn vertices(&self) -> &[DVec3] {
        &self.vertices
    }

    /// Triangles (vertex indices), after dropping zero-area ones.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.triangles
    }

    /// Unit normal of each triangle from its winding (right-hand rule), mesh frame.
    pub fn normals(&self) -> &[DVec3] {
        &self.normals
    }

    /// Number of zero-area triangles dropped by [`TriMesh::new`].
    pub fn dropped_triangles(&self) -> usize {
        self.dropped
    }

    /// Bounding box `(lo, hi)` of the triangles, mesh frame, m.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        self.bvh.bounds().unwrap_or((DVec3::ZERO, DVec3::ZERO))
    }

    /// The bounding-volume hierarchy (mesh frame).
    pub fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// Triangles incident to vertex `v` (ascending).
    #[inline]
    pub fn vertex_triangles(&self, v: u32) -> &[u32] {
        &self.vert_tri
            [self.vert_tri_start[v as usize] as usize..self.vert_tri_start[v as usize + 1] as usize]
    }

    /// The corners of triangle `t`, mesh frame, m.
    #[inline(always)]
    pub fn corners(&self, t: u32) -> [DVec3; 3] {
        let tri = self.triangles[t as usize];
        [
            self.vertices[tri[0] as usize],
            self.vertices[tri[1] as usize],
            self.vertices[tri[2] as usize],
        ]
    }

    /// Vertices in the world frame for the pose (`position` m, `orientation`
    /// mesh → world): `position + orientation · v`. Index-aligned with
    /// [`TriMesh::vertices`]; use with [`TriMesh::triangles`] to draw the mesh.
    pub fn vertices_at(&self, position: DVec3, orientation: DQuat) -> Vec<DVec3> {
        self.vertices
            .iter()
            .map(|&v| position + orientation * v)
            .collect()
    }

    /// A copy with every vertex mapped by `f` (e.g. a scale, rotation and
    /// offset applied on import); normals and search structures are rebuilt.
    pub fn transformed(&self, f: impl Fn(DVec3) -> DVec3) -> Result<Self, MeshError> {
        let mut m = TriMesh::new(
            self.vertices.iter().map(|&v| f(v)).collect(),
            self.triangles.clone(),
        )?;
        m.merge_angle = self.merge_angle;
        m.dropped += self.dropped;
        Ok(m)
    }

    /// Checks that the mesh is a closed 2-manifold: every edge is shared by
    /// exactly two triangles. Reports the first offending edge (by lowest
    /// vertex pair).
    pub fn check_closed(&self) -> Result<(), MeshError> {
        let mut edges: HashMap<(u32, u32), usize> =
            HashMap::with_capacity(self.triangles.len() * 3 / 2);
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *edges.entry((a.min(b), a.max(b))).or_default() += 1;
            }
        }
        let mut bad: Vec<_> = edges.into_iter().filter(|&(_, c)| c != 2).collect();
        bad.sort_unstable();
        match bad.first() {
            None => Ok(()),
            Some(&((a, b), 1)) => Err(MeshError::OpenEdge { a, b }),
            Some(&((a, b), count)) => Err(MeshError::NonManifoldEdge { a, b, count }),
        }
    }

    /// Closed meshes: a copy whose triangles are consistently oriented with
    /// outward normals (positive enclosed volume). Each connected component
    /// is made consistent by a breadth-first walk over shared edges, then
    /// flipped as a whole if its signed volume is negative. Errors if the
    /// mesh is not closed ([`TriMesh::check_closed`]) or not orientable.
    pub fn oriented_outward(&self) -> Result<Self, MeshError> {
        self.check_closed()?;
        let nt = self.triangles.len();
        let mut edge_tris: HashMap<(u32, u32), [u32; 2]> = HashMap::with_capacity(nt * 3 / 2);
        for (ti, t) in self.triangles.iter().enumerate() {
            for k in 0..3 {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                let e = edge_tris
                    .entry((a.min(b), a.max(b)))
                    .or_insert([u32::MAX; 2]);
                if e[0] == u32::MAX {
                    e[0] = ti as u32;
                } else {
                    e[1] = ti as u32;
                }
            }
        }
        let directed =
            |t: &[u32; 3], a: u32, b: u32| (0..3).any(|k| t[k] == a && t[(k + 1) % 3] == b);
        let mut tris = self.triangles.clone();
        let mut comp = vec![u32::MAX; nt];
        let mut ncomp = 0u32;
        let mut queue = std::collections::VecDeque::new();
        for seed in 0..nt {
            if comp[seed] != u32::MAX {
                continue;
            }
            comp[seed] = ncomp;
            queue.push_back(seed);
            while let Some(ti) = queue.pop_front() {
                let t = tris[ti];
                for k in 0..3 {
                    let (a, b) = (t[k], t[(k + 1) % 3]);
                    let pair = edge_tris[&(a.min(b), a.max(b))];
                    let other = if pair[0] as usize == ti {
                        pair[1]
                    } else {
                        pair[0]
                    } as usize;
                    // consistent orientation: the neighbour runs the edge b → a
                    let consistent = directed(&tris[other], b, a);
                    if comp[other] == u32::MAX {
                        if !consistent {
                            tris[other].swap(1, 2);
                        }
                        comp[other] = ncomp;
                        queue.push_back(other);
                    } else if !consistent {
                        return Err(MeshError::NonOrientable {
                            a: a.min(b),
                            b: a.max(b),
                        });
                    }
                }
            }
            ncomp += 1;
        }
        let mut vol = vec![0.0f64; ncomp as usize];
        for (ti, t) in tris.iter().enumerate() {
            let (a, b, c) = (
                self.vertices[t[0] as usize],
                self.vertices[t[1] as usize],
                self.vertices[t[2] as usize],
            );
            vol[comp[ti] as usize] += a.dot(b.cross(c));
        }
        for (ti, t) in tris.iter_mut().enumerate() {
            if vol[comp[ti] as usize] < 0.0 {
                t.swap(1, 2);
            }
        }
        let mut m = TriMesh::new(self.vertices.clone(), tris)?;
        m.merge_angle = self.merge_angle;
        Ok(m)
    }

    /// Closest point of the surface to `p` (mesh frame, m): returns
    /// `(triangle, closest point, distance m)`.
    pub fn closest_point(&self, p: DVec3) -> (u32, DVec3, f64) {
        let (t, d2) = self
            .bvh
            .nearest(p, |t| {
                let [a, b, c] = self.corners(t);
                let (q, _) = closest::closest_point_triangle(p, a, b, c);
                (p - q).length_squared()
            })
            .expect("a TriMesh has at least one triangle");
        let [a, b, c] = self.corners(t);
        (t, closest::closest_point_triangle(p, a, b, c).0, d2.sqrt())
    }

    /// Whether `p` (mesh frame) is inside a closed mesh, by the parity of the
    /// crossings of a ray from `p` along +x (rays through an edge or vertex
    /// are nudged by a tiny deterministic offset).
    pub fn contains(&self, p: DVec3) -> bool {
        let mut xs = Vec::new();
        self.line_crossings(p.y, p.z, &mut xs);
        xs.iter().filter(|&&x| x > p.x).count() % 2 == 1
    }

    /// x coordinates (sorted) where the line `{y = y0, z = z0}` crosses the
    /// mesh, written to `out`. Lines that graze an edge or vertex are retried
    /// with a tiny deterministic offset of `(y0, z0)` (relative 1e-9 of the
    /// mesh size), so that every crossing is counted once.
    pub fn line_crossings(&self, y0: f64, z0: f64, out: &mut Vec<f64>) {
        let (lo, hi) = self.bounds();
        let size = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        let mut eps = 0.0;
        for attempt in 0..8 {
            out.clear();
            let (y, z) = (y0 + eps * 0.7548776662466927, z0 + eps * 0.5698402909980532);
            let mut grazed = false;
            self.bvh.for_each_on_line(DVec3::new(0.0, y, z), 0, |t| {
                if grazed {
                    return;
                }
                let [a, b, c] = self.corners(t);
                // 2D barycentric test in the (y, z) plane
                let (ay, az, by, bz, cy, cz) =
                    (a.y - y, a.z - z, b.y - y, b.z - z, c.y - y, c.z - z);
                let w0 = by * cz - bz * cy; // opposite a
                let w1 = cy * az - cz * ay; // opposite b
                let w2 = ay * bz - az * by; // opposite c
                let s = w0 + w1 + w2;
                if s == 0.0 {
                    return; // triangle parallel to the line
                }
                let inside_pos = w0 > 0.0 && w1 > 0.0 && w2 > 0.0;
                let inside_neg = w0 < 0.0 && w1 < 0.0 && w2 < 0.0;
                if inside_pos || inside_neg {
                    out.push((w0 * a.x + w1 * b.x + w2 * c.x) / s);
                } else if (w0 == 0.0 || w1 == 0.0 || w2 == 0.0)
                    && (w0 >= 0.0 && w1 >= 0.0 && w2 >= 0.0 || w0 <= 0.0 && w1 <= 0.0 && w2 <= 0.0)
                {
                    grazed = true;
                }
            });
            if !grazed {
                break;
            }
            eps = size * 1e-9 * (attempt + 1) as f64;
        }
        out.sort_by(f64::total_cmp);
    }
}
