//! Triangle-mesh files: STL (ASCII and binary) and Wavefront OBJ, read into a
//! [`TriMesh`] with a scale, a rotation and an offset; and STL writers.
//!
//! # Formats
//! - **Binary STL**: 80-byte header, `u32` triangle count, then 50 bytes per
//!   triangle (normal, three vertices as little-endian `f32`, attribute
//!   `u16`). A file is binary when its size is exactly `84 + 50 n`; otherwise
//!   it is read as ASCII (binary files may also begin with `solid`).
//! - **ASCII STL**: `solid … facet normal … outer loop vertex x y z ×3 endloop
//!   endfacet … endsolid`; several solids may follow each other. Stored
//!   normals are ignored (the winding defines the normal; mesh walls are
//!   two-sided anyway).
//! - **OBJ**: `v x y z [w]` vertices and `f` faces with 1-based (or negative,
//!   relative) indices in any of the `i`, `i/t`, `i//n`, `i/t/n` forms;
//!   polygons are fan-triangulated; all other statements are ignored.
//!
//! STL stores every triangle's corners separately; corners with bit-identical
//! coordinates are merged into one vertex, which gives the mesh its
//! connectivity (needed for one-contact-per-patch detection and for the
//! closed-mesh check of template generation). OBJ vertices are used as given.
//!
//! # Transform
//! A file point `p` (file units) becomes `offset + rotation · (scale · p)`
//! (m), see [`MeshTransform`].
//!
//! # Choice of implementation
//! Candidates were `stl_io` (STL only, f32, own vertex indexing), `tobj`
//! (OBJ only, with materials and texture handling we do not need) and
//! `parry3d-f64` (a full collision library: `TriMesh` with a QBVH and
//! closest-point queries with feature ids). The parsers needed here are a few
//! dozen lines each, so they are written here without dependencies; the
//! contact side (BVH, closest feature, one-contact-per-patch rules, history
//! keyed by contact patch) lives in `clump_core::wall::mesh`, where the
//! DEM-specific rules have to be written anyway and parry's types would have
//! to be converted on every query. This keeps the build small and the
//! behaviour deterministic and under our control.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clump_core::wall::{MeshError, TriMesh};
use glam::{DQuat, DVec3};

/// Placement of a mesh file: `x = offset + rotation · (scale · p)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshTransform {
    /// Factor from file units to m (e.g. 0.001 for a file in mm).
    pub scale: f64,
    /// Rotation applied after scaling.
    pub rotation: DQuat,
    /// Translation applied last, m.
    pub offset: DVec3,
}

impl Default for MeshTransform {
    fn default() -> Self {
        MeshTransform {
            scale: 1.0,
            rotation: DQuat::IDENTITY,
            offset: DVec3::ZERO,
        }
    }
}

impl MeshTransform {
    /// Applies the transform to a file point.
    #[inline]
    pub fn apply(&self, p: DVec3) -> DVec3 {
        self.offset + self.rotation * (self.scale * p)
    }
}

/// Why a mesh file could not be read.
#[derive(Debug, thiserror::Error)]
pub enum MeshFileError {
    /// The file could not be read.
    #[error("{path}: cannot read mesh file: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The underlying error.
        #[source]
        source: std::io::Error,
    },
    /// The extension is neither `.stl` nor `.obj`.
    #[error("{path}: unknown mesh format (expected a .stl or .obj file)")]
    UnknownFormat {
        /// The file.
        path: PathBuf,
    },
    /// A syntax error (1-based line; 0 for binary STL).
    #[error("{path}:{line}: {message}")]
    Syntax {
        /// The file.
        path: PathBuf,
        /// 1-based line number (0 when not applicable).
        line: usize,
        /// What was wrong.
        message: String,
    },
    /// The triangles do not form a valid mesh.
    #[error("{path}: {source}")]
    Mesh {
        /// The file.
        path: PathBuf,
        /// The problem.
        #[source]
        source: MeshError,
    },
    /// Invalid transform (scale not finite and > 0).
    #[error("{path}: mesh scale must be finite and > 0, found {scale}")]
    BadScale {
        /// The file.
        path: PathBuf,
        /// The scale.
        scale: f64,
    },
}

/// Raw mesh data: vertices (file units) and triangles.
pub type RawMesh = (Vec<DVec3>, Vec<[u32; 3]>);

/// Reads a `.stl` or `.obj` file (by extension, case-insensitive) and places
/// it with `t`.
pub fn read_mesh_file(path: impl AsRef<Path>, t: &MeshTransform) -> Result<TriMesh, MeshFileError> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|source| MeshFileError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_mesh_bytes(&bytes, path, t)
}

/// Like [`read_mesh_file`] for the `bytes` of a file named `path` (the
/// format is taken from the extension of `path`; it is also the name used in
/// errors). Used for meshes referenced by scenario files, whose bytes are
/// stored in checkpoints.
pub fn read_mesh_bytes(
    bytes: &[u8],
    path: &Path,
    t: &MeshTransform,
) -> Result<TriMesh, MeshFileError> {
    let pb = || path.to_path_buf();
    if !(t.scale.is_finite() && t.scale > 0.0) {
        return Err(MeshFileError::BadScale {
            path: pb(),
            scale: t.scale,
        });
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(|e| e.to_ascii_lowercase());
    let syntax = |(line, message): (usize, String)| MeshFileError::Syntax {
        path: pb(),
        line,
        message,
    };
    let (v, tri) = match ext.as_deref() {
        Some("stl") => parse_stl(bytes).map_err(syntax)?,
        Some("obj") => parse_obj(bytes).map_err(syntax)?,
        _ => return Err(MeshFileError::UnknownFormat { path: pb() }),
    };
    let v = v.into_iter().map(|p| t.apply(p)).collect();
    TriMesh::new(v, tri).map_err(|source| MeshFileError::Mesh { path: pb(), source })
}

/// Parses STL bytes (binary or ASCII, see the [module docs](self)); errors
/// are `(line, message)`.
pub fn parse_stl(bytes: &[u8]) -> Result<RawMesh, (usize, String)> {
    if bytes.len() >= 84 {
        let n = u32::from_le_bytes([bytes[80], bytes[81], bytes[82], bytes[83]]) as usize;
        if n.checked_mul(50).and_then(|x| x.checked_add(84)) == Some(bytes.len()) {
            return Ok(parse_stl_binary(&bytes[84..], n));
        }
    }
    let head = String::from_utf8_lossy(&bytes[..bytes.len().min(512)]);
    if !head.trim_start().starts_with("solid") {
        return Err((
            0,
            if bytes.len() >= 84 {
                "neither a binary STL (size does not match 84 + 50 × triangle count) nor an ASCII STL (does not start with 'solid')".into()
            } else {
                "too short for a binary STL and does not start with 'solid' (ASCII STL)".into()
            },
        ));
    }
    parse_stl_ascii(bytes)
}

fn parse_stl_binary(body: &[u8], n: usize) -> RawMesh {
    let mut weld: HashMap<[u32; 3], u32> = HashMap::with_capacity(n);
    let mut v = Vec::with_capacity(n / 2 + 3);
    let mut t = Vec::with_capacity(n);
    let f = |b: &[u8], o: usize| f32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]);
    for k in 0..n {
        let rec = &body[50 * k..50 * k + 50];
        let mut tri = [0u32; 3];
        for (c, slot) in tri.iter_mut().enumerate() {
            let o = 12 + 12 * c;
            let p = [f(rec, o), f(rec, o + 4), f(rec, o + 8)];
            // +0.0 and −0.0 are the same point
            let key = p.map(|x| if x == 0.0 { 0 } else { x.to_bits() });
            *slot = *weld.entry(key).or_insert_with(|| {
                v.push(DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64));
                v.len() as u32 - 1
            });
        }
        t.push(tri);
    }
    (v, t)
}

fn parse_stl_ascii(bytes: &[u8]) -> Result<RawMesh, (usize, String)> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        (line, "not valid UTF-8 text (ASCII STL)".to_string())
    })?;
    let mut weld: HashMap<[u64; 3], u32> = HashMap::new();
    let mut v = Vec::new();
    let mut t = Vec::new();
    let mut corners: Vec<u32> = Vec::with_capacity(3);
    let mut in_facet = false;
    let mut facet_line = 0;
    for (i, line) in text.lines().enumerate() {
        let ln = i + 1;
        let mut w = line.split_whitespace();
        match w.next() {
            Some("facet") => {
                if in_facet {
                    return Err((ln, "'facet' before the previous facet's 'endfacet'".into()));
                }
                in_facet = true;
                facet_line = ln;
                corners.clear();
            }
            Some("vertex") => {
                if !in_facet {
                    return Err((ln, "'vertex' outside a facet".into()));
                }
                let mut p = [0.0f64; 3];
                for c in &mut p {
                    let s = w
                        .next()
                        .ok_or((ln, "'vertex' needs three coordinates".to_string()))?;
                    *c = s
                        .parse()
                        .map_err(|_| (ln, format!("'{s}' is not a number")))?;
                }
                if !p.iter().all(|x| x.is_finite()) {
                    return Err((ln, "vertex coordinates must be finite".into()));
                }
                if corners.len() == 3 {
                    return Err((ln, "a facet has more than three vertices".into()));
                }
                let key = p.map(|x| if x == 0.0 { 0 } else { x.to_bits() });
                corners.push(*weld.entry(key).or_insert_with(|| {
                    v.push(DVec3::from_array(p));
                    v.len() as u32 - 1
                }));
            }
            Some("endfacet") => {
                if corners.len() != 3 {
                    return Err((
                        ln,
                        format!(
                            "the facet starting on line {facet_line} has {} vertices, expected 3",
                            corners.len()
                        ),
                    ));
                }
                t.push([corners[0], corners[1], corners[2]]);
                in_facet = false;
            }
            _ => {}
        }
    }
    if in_facet {
        return Err((facet_line, "facet without 'endfacet'".into()));
    }
    if t.is_empty() {
        return Err((0, "no facet found".into()));
    }
    Ok((v, t))
}

/// Parses OBJ text (see the [module docs](self)); errors are `(line, message)`.
pub fn parse_obj(bytes: &[u8]) -> Result<RawMesh, (usize, String)> {
    let text = std::str::from_utf8(bytes).map_err(|e| {
        let line = 1 + bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        (line, "not valid UTF-8 text (OBJ)".to_string())
    })?;
    let mut v = Vec::new();
    let mut t = Vec::new();
    let mut face: Vec<u32> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let ln = i + 1;
        let line = line.split('#').next().unwrap_or("");
        let mut w = line.split_whitespace();
        match w.next() {
            Some("v") => {
                let mut p = [0.0f64; 3];
                for c in &mut p {
                    let s = w
                        .next()
                        .ok_or((ln, "'v' needs three coordinates".to_string()))?;
                    *c = s
                        .parse()
                        .map_err(|_| (ln, format!("'{s}' is not a number")))?;
                }
                if !p.iter().all(|x| x.is_finite()) {
                    return Err((ln, "vertex coordinates must be finite".into()));
                }
                v.push(DVec3::from_array(p));
            }
            Some("f") => {
                face.clear();
                for s in w {
                    let idx = s.split('/').next().unwrap_or("");
                    let k: i64 = idx
                        .parse()
                        .map_err(|_| (ln, format!("'{s}' is not a vertex index")))?;
                    let n = v.len() as i64;
                    let abs = if k > 0 {
                        k - 1
                    } else if k < 0 {
                        n + k
                    } else {
                        -1
                    };
                    if abs < 0 || abs >= n {
                        return Err((
                            ln,
                            format!("vertex index {k} out of range (1..={n} defined so far)"),
                        ));
                    }
                    face.push(abs as u32);
                }
                if face.len() < 3 {
                    return Err((
                        ln,
                        format!("a face needs at least 3 vertices, found {}", face.len()),
                    ));
                }
                for k in 1..face.len() - 1 {
                    t.push([face[0], face[k], face[k + 1]]);
                }
            }
            _ => {}
        }
    }
    if t.is_empty() {
        return Err((0, "no face found".into()));
    }
    Ok((v, t))
}

/// Binary STL bytes of the triangles of `(vertices, triangles)` (coordinates
/// written as `f32`; normals from the winding).
pub fn stl_binary(vertices: &[DVec3], triangles: &[[u32; 3]]) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * triangles.len());
    let mut header = [0u8; 80];
    let h = b"binary STL written by clump";
    header[..h.len()].copy_from_slice(h);
    out.extend_from_slice(&header);
    out.extend_from_slice(&(triangles.len() as u32).to_le_bytes());
    for t in triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        for p in [n, a, b, c] {
            for x in p.to_array() {
                out.extend_from_slice(&(x as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// ASCII STL text of `(vertices, triangles)`, solid `name`, coordinates
/// written with 17 significant digits (exact round trip).
pub fn stl_ascii(name: &str, vertices: &[DVec3], triangles: &[[u32; 3]]) -> String {
    let mut s = format!("solid {name}\n");
    for t in triangles {
        let [a, b, c] = t.map(|i| vertices[i as usize]);
        let n = (b - a).cross(c - a).normalize_or_zero();
        let _ = writeln!(
            s,
            "  facet normal {:e} {:e} {:e}\n    outer loop",
            n.x, n.y, n.z
        );
        for p in [a, b, c] {
            let _ = writeln!(s, "      vertex {:.16e} {:.16e} {:.16e}", p.x, p.y, p.z);
        }
        s.push_str("    endloop\n  endfacet\n");
    }
    let _ = writeln!(s, "endsolid {name}");
    s
}
