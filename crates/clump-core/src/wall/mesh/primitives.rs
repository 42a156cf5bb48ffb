//! Procedural triangle meshes (mesh frame, m): surfaces of revolution
//! (cylinders, drums, hoppers), flat plates, icospheres and seeded
//! rock-like shapes. Used to generate the example meshes and in tests; each
//! returns `(vertices, triangles)` for [`TriMesh::new`](super::TriMesh::new)
//! or an STL writer.
//!
//! Closed shapes are wound with outward normals (right-hand rule).

use glam::DVec3;
use std::collections::HashMap;
use std::f64::consts::TAU;

/// Vertices (mesh frame, m) and triangles (vertex indices).
pub type MeshData = (Vec<DVec3>, Vec<[u32; 3]>);

/// A surface of revolution about the mesh z axis: the polyline `profile` of
/// `(radius, z)` points (m) swept through a full turn in `segments` facets.
/// Each profile edge is split into `ceil(length / max_edge)` rings. A profile
/// point with radius 0 becomes one vertex on the axis (a pole), so that
/// `[(0, z0), (R, z0), (R, z1), (0, z1)]` is a closed cylinder. With the
/// profile running upward on the outside of the body (as in that example),
/// the normals point outward.
pub fn revolve(profile: &[(f64, f64)], segments: usize, max_edge: f64) -> MeshData {
    let segments = segments.max(3);
    // subdivide the profile
    let mut pts: Vec<(f64, f64)> = Vec::new();
    for (k, w) in profile.windows(2).enumerate() {
        let ((r0, z0), (r1, z1)) = (w[0], w[1]);
        let len = ((r1 - r0).powi(2) + (z1 - z0).powi(2)).sqrt();
        let n = if max_edge > 0.0 {
            ((len / max_edge).ceil() as usize).max(1)
        } else {
            1
        };
        if k == 0 {
            pts.push((r0, z0));
        }
        for j in 1..=n {
            let s = j as f64 / n as f64;
            pts.push((r0 + s * (r1 - r0), z0 + s * (z1 - z0)));
        }
    }
    if profile.len() == 1 {
        pts.push(profile[0]);
    }
    let mut v: Vec<DVec3> = Vec::new();
    // first vertex of each ring; a pole has one vertex
    let mut ring: Vec<(u32, bool)> = Vec::with_capacity(pts.len());
    for &(r, z) in &pts {
        let start = v.len() as u32;
        if r == 0.0 {
            v.push(DVec3::new(0.0, 0.0, z));
            ring.push((start, true));
        } else {
            for j in 0..segments {
                let a = TAU * j as f64 / segments as f64;
                v.push(DVec3::new(r * a.cos(), r * a.sin(), z));
            }
            ring.push((start, false));
        }
    }
    let at = |(s, pole): (u32, bool), j: usize| if pole { s } else { s + (j % segments) as u32 };
    let mut t: Vec<[u32; 3]> = Vec::new();
    for w in ring.windows(2) {
        let (a, b) = (w[0], w[1]);
        if a.1 && b.1 {
            continue;
        }
        for j in 0..segments {
            let (a0, a1, b0, b1) = (at(a, j), at(a, j + 1), at(b, j), at(b, j + 1));
            if !a.1 {
                t.push([a0, a1, b1]);
            }
            if !b.1 {
                t.push([a0, b1, b0]);
            }
        }
    }
    (v, t)
}

/// A closed circular cylinder about the mesh z axis, radius `radius`, from
/// `z = −length/2` to `length/2` (m), with flat end caps; `segments` facets
/// round, side edges at most `max_edge` long (m).
pub fn cylinder(radius: f64, length: f64, segments: usize, max_edge: f64) -> MeshData {
    let h = 0.5 * length;
    revolve(
        &[(0.0, -h), (radius, -h), (radius, h), (0.0, h)],
        segments,
        max_edge,
    )
}

/// A flat rectangular plate in the plane `z = 0` (mesh frame), centred on
/// the origin, `size_x × size_y` (m), split into `nx × ny` squares of two
/// triangles each (normals +z).
pub fn plate(size_x: f64, size_y: f64, nx: usize, ny: usize) -> MeshData {
    let (nx, ny) = (nx.max(1), ny.max(1));
    let mut v = Vec::with_capacity((nx + 1) * (ny + 1));
    for j in 0..=ny {
        for i in 0..=nx {
            v.push(DVec3::new(
                size_x * (i as f64 / nx as f64 - 0.5),
                size_y * (j as f64 / ny as f64 - 0.5),
                0.0,
            ));
        }
    }
    let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
    let mut t = Vec::with_capacity(2 * nx * ny);
    for j in 0..ny {
        for i in 0..nx {
            t.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            t.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (v, t)
}

/// The closed axis-aligned box with corners `lo` and `hi` (mesh frame, m):
/// 8 vertices (vertex `k` takes `hi` along axis `a` when bit `a` of `k` is
/// set), 12 triangles, outward winding.
pub fn cuboid(lo: DVec3, hi: DVec3) -> MeshData {
    let v = (0..8)
        .map(|k| {
            DVec3::new(
                if k & 1 == 0 { lo.x } else { hi.x },
                if k & 2 == 0 { lo.y } else { hi.y },
                if k & 4 == 0 { lo.z } else { hi.z },
            )
        })
        .collect();
    let quads: [[u32; 4]; 6] = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let t = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    (v, t)
}

/// The unit icosphere: an icosahedron subdivided `level` times (each level
/// splits every triangle in four), vertices on the unit sphere, outward
/// winding; `20 · 4^level` triangles.
pub fn icosphere(level: usize) -> MeshData {
    let p = (1.0 + 5f64.sqrt()) / 2.0;
    let mut v: Vec<DVec3> = [
        (-1.0, p, 0.0),
        (1.0, p, 0.0),
        (-1.0, -p, 0.0),
        (1.0, -p, 0.0),
        (0.0, -1.0, p),
        (0.0, 1.0, p),
        (0.0, -1.0, -p),
        (0.0, 1.0, -p),
        (p, 0.0, -1.0),
        (p, 0.0, 1.0),
        (-p, 0.0, -1.0),
        (-p, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let mut t: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
        let mut nt = Vec::with_capacity(t.len() * 4);
        for tri in &t {
            let mut m = [0u32; 3];
            for k in 0..3 {
                let (a, b) = (tri[k], tri[(k + 1) % 3]);
                m[k] = *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    v.push(((v[a as usize] + v[b as usize]) * 0.5).normalize());
                    v.len() as u32 - 1
                });
            }
            nt.push([tri[0], m[0], m[2]]);
            nt.push([tri[1], m[1], m[0]]);
            nt.push([tri[2], m[2], m[1]]);
            nt.push(m);
        }
        t = nt;
    }
    (v, t)
}

/// SplitMix64: a tiny seeded generator, so that generated shapes are the
/// same on every platform and version.
struct SplitMix(u64);

impl SplitMix {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1).
    fn uniform(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A rock-like closed shape: the icosphere of `level`, each vertex moved
/// along its radius by `1 + amplitude · n(v)`, where `n` is a smooth random
/// field (a sum of 12 plane waves of increasing frequency and decreasing
/// weight, normalised to |n| ≤ 1, drawn from `seed`), then scaled by the
/// semi-axes `axes` (m). The shape stays star-shaped (closed, without
/// self-intersections) for `amplitude < 1`.
pub fn rock(level: usize, amplitude: f64, axes: DVec3, seed: u64) -> MeshData {
    let (mut v, t) = icosphere(level);
    let mut rng = SplitMix(seed);
    let waves: Vec<(DVec3, f64, f64)> = (0..12)
        .map(|k| {
            // a uniform direction
            let z = 2.0 * rng.uniform() - 1.0;
            let a = TAU * rng.uniform();
            let s = (1.0 - z * z).sqrt();
            let dir = DVec3::new(s * a.cos(), s * a.sin(), z);
            let freq = 1.0 + 0.5 * k as f64;
            let phase = TAU * rng.uniform();
            (dir * freq, phase, 1.0 / freq)
        })
        .collect();
    let norm: f64 = waves.iter().map(|w| w.2).sum();
    for p in &mut v {
        let n: f64 = waves
            .iter()
            .map(|&(k, ph, w)| w * (k.dot(*p) + ph).cos())
            .sum::<f64>()
            / norm;
        *p = *p * (1.0 + amplitude * n) * axes;
    }
    (v, t)
}
