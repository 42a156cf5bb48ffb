//! Mesh walls on the device: the triangle meshes that mesh walls refer
//! to, in the mesh frame, with what the CPU path's contact search reads
//! (`clump_core::wall::mesh`: triangles, unit normals, the triangles at
//! each vertex) and a uniform grid of the triangles, built once here at
//! upload, in place of the CPU path's bounding-volume hierarchy.
//!
//! A mesh is static in its own frame; a mesh wall's pose (position,
//! orientation) is in its wall row (walls.rs), which the host advances
//! with the CPU path's `Wall::advance`. The device maps a sphere centre
//! into the mesh frame with the pose, as `WallShape::contacts` does, and
//! looks up the grid cells within the sphere's radius of it. A triangle
//! is listed in every cell its bounding box overlaps, and visited only
//! from the first cell of the overlap of its cells and the sphere's, so
//! each triangle near the sphere is tested exactly once; the set of
//! triangles tested contains every triangle the hierarchy would report
//! within the radius, and the CPU path's contact rule does not depend on
//! the order they come in (its gather keeps the deepest by a total
//! order).
//!
//! `mesh_u` (binding 30, mesh.wgsl) holds, in u32s: a header (`M_*`),
//! one row of `MESH_ROW` per mesh, the index arrays, then the wall slot
//! keys (one per sphere and wall slot, `step/wall_contacts.rs`
//! `slot_key`: a mesh contact's slot is matched by its normal). The
//! meshes' f64s (grid origin and cell, merge cosine, vertices, normals)
//! follow the wall row sets in `walls` (binding 26), which are written
//! from the start of the buffer and never reach them.

use clump_core::wall::mesh::MAX_MESH_CONTACTS;
use clump_core::wall::TriMesh;
use glam::DVec3;

/// u32s of the header of `mesh_u` (mesh.wgsl `M_*`).
const HEAD: usize = 4;
/// u32s per mesh row (mesh.wgsl `MR_*`).
const MESH_ROW: usize = 16;
/// Contact slots of a mesh wall per sphere: one per contact the CPU path
/// keeps (`MAX_MESH_CONTACTS`).
pub(crate) const MESH_SLOTS: usize = MAX_MESH_CONTACTS;
/// The CPU path's largest angle between a mesh contact's normal and a
/// slot's stored normal for the contact to continue that slot
/// (`step/wall_contacts.rs` `MESH_MATCH_ANGLE`, 30°).
const MATCH_ANGLE: f64 = std::f64::consts::PI / 6.0;
/// Most grid cells of one mesh.
const MAX_CELLS: usize = 1 << 22;

/// The meshes in the device's layout.
pub(crate) struct MeshArrays {
    /// `mesh_u` without the slot keys (they start at `u.len()`).
    pub u: Vec<u32>,
    /// The meshes' f64s, to append to `walls`.
    pub f: Vec<f64>,
    /// Where they start in `walls`.
    walls_len: usize,
}

/// Grid of one mesh's triangles (mesh frame): origin, cell edge, cells
/// per axis, and each triangle's first and last cell per axis.
struct Grid {
    lo: DVec3,
    h: f64,
    dims: [usize; 3],
    span: Vec<([usize; 3], [usize; 3])>,
}

/// Cell of coordinate `x` along an axis of origin `lo`, edge `h`, `n`
/// cells (clamped; mesh.wgsl `mesh_cell` computes the same).
fn cell(x: f64, lo: f64, h: f64, n: usize) -> usize {
    let c = ((x - lo) / h).floor();
    c.clamp(0.0, (n - 1) as f64) as usize
}

impl Grid {
    /// Cells of about the triangles' mean size, at least a sphere
    /// diameter (`rmax` the largest radius, m), at most `MAX_CELLS`.
    fn of(m: &TriMesh, rmax: f64) -> Grid {
        let (lo, hi) = m.bounds();
        let boxes: Vec<(DVec3, DVec3)> = (0..m.triangles().len() as u32)
            .map(|t| {
                let [a, b, c] = m.corners(t);
                (a.min(b).min(c), a.max(b).max(c))
            })
            .collect();
        let mean = boxes
            .iter()
            .map(|(a, b)| (*b - *a).max_element())
            .sum::<f64>()
            / boxes.len() as f64;
        let mut h = mean
            .max(2.0 * rmax)
            .max(1e-9 * (hi - lo).max_element())
            .max(f64::MIN_POSITIVE);
        let dims_of =
            |h: f64| [0, 1, 2].map(|k| (((hi[k] - lo[k]) / h).floor() as usize + 1).max(1));
        while dims_of(h).iter().product::<usize>() > MAX_CELLS {
            h *= 2.0;
        }
        let dims = dims_of(h);
        let span = boxes
            .iter()
            .map(|(a, b)| {
                (
                    [0, 1, 2].map(|k| cell(a[k], lo[k], h, dims[k])),
                    [0, 1, 2].map(|k| cell(b[k], lo[k], h, dims[k])),
                )
            })
            .collect();
        Grid { lo, h, dims, span }
    }

    /// The triangles of each cell (CSR: starts, then triangles ascending).
    fn cells(&self) -> (Vec<u32>, Vec<u32>) {
        let [nx, ny, nz] = self.dims;
        let mut lists: Vec<Vec<u32>> = vec![Vec::new(); nx * ny * nz];
        for (t, (a, b)) in self.span.iter().enumerate() {
            for z in a[2]..=b[2] {
                for y in a[1]..=b[1] {
                    for x in a[0]..=b[0] {
                        lists[(z * ny + y) * nx + x].push(t as u32);
                    }
                }
            }
        }
        let mut start = vec![0u32];
        let mut tris = Vec::new();
        for l in &lists {
            tris.extend(l);
            start.push(tris.len() as u32);
        }
        (start, tris)
    }
}

impl MeshArrays {
    /// The meshes of a world (`WallSet::meshes`); `rmax` is its largest
    /// sphere radius, m; their f64s go after the `walls_len` f64s of the
    /// wall row sets in `walls`.
    pub(crate) fn new(meshes: &[TriMesh], rmax: f64, walls_len: usize) -> MeshArrays {
        let mut u = vec![0u32; HEAD + MESH_ROW * meshes.len()];
        u[1] = meshes.len() as u32;
        // global f64s: the cosine of the slot match angle
        let mut f = vec![MATCH_ANGLE.cos()];
        for (k, m) in meshes.iter().enumerate() {
            let g = Grid::of(m, rmax);
            let (cell_start, cell_tri) = g.cells();
            let nv = m.vertices().len();
            let mut row = [0u32; MESH_ROW];
            row[0] = m.triangles().len() as u32;
            row[1] = nv as u32;
            let mut put = |slot: usize, data: &[u32], u: &mut Vec<u32>| {
                row[slot] = u.len() as u32;
                u.extend_from_slice(data);
            };
            let tris: Vec<u32> = m.triangles().iter().flatten().copied().collect();
            put(2, &tris, &mut u);
            let mut vt_start = vec![0u32];
            let mut vt = Vec::new();
            for v in 0..nv as u32 {
                vt.extend_from_slice(m.vertex_triangles(v));
                vt_start.push(vt.len() as u32);
            }
            put(3, &vt_start, &mut u);
            put(4, &vt, &mut u);
            put(5, &cell_start, &mut u);
            put(6, &cell_tri, &mut u);
            let lo_cells: Vec<u32> = g
                .span
                .iter()
                .flat_map(|(a, _)| a.map(|c| c as u32))
                .collect();
            put(7, &lo_cells, &mut u);
            row[8..11].copy_from_slice(&g.dims.map(|d| d as u32));
            row[11] = f.len() as u32;
            f.extend(g.lo.to_array());
            f.push(g.h);
            f.push(m.merge_angle.cos());
            f.extend(m.vertices().iter().flat_map(|v| v.to_array()));
            f.extend(m.normals().iter().flat_map(|n| n.to_array()));
            u[HEAD + MESH_ROW * k..HEAD + MESH_ROW * (k + 1)].copy_from_slice(&row);
        }
        MeshArrays { u, f, walls_len }
    }

    /// `mesh_u` whole: the arrays, then the `slots` slot keys (one per
    /// sphere and wall slot) from `keys`, zero after them; the offsets of
    /// the keys and of the meshes' f64s go in the header.
    pub(crate) fn with_keys(&self, keys: &[u32], slots: usize) -> Vec<u32> {
        let mut u = self.u.clone();
        u[0] = u.len() as u32;
        u[2] = self.walls_len as u32;
        u.extend_from_slice(keys);
        u.resize(u[0] as usize + slots.max(keys.len()).max(1), 0);
        u
    }
}

/// The slot keys of `mesh_u` as read back (`slots` of them).
pub(crate) fn keys_of(mesh_u: Vec<u32>, slots: usize) -> Vec<u32> {
    let at = mesh_u[0] as usize;
    mesh_u[at..at + slots].to_vec()
}
