//! ParaView-ready VTK XML PolyData (`.vtp`) output with binary appended raw
//! data (`<AppendedData encoding="raw">`, `header_type="UInt64"`, little
//! endian), and `.pvd` time-series collections.
//!
//! Three files per output frame, all in the world frame, SI units:
//! - **spheres**: points = sphere centres (m); point data `radius` (m),
//!   `body_id` (global body id, UInt64), `velocity` (m/s). One vertex cell per
//!   point, so every representation (Point Gaussian, Glyph) works.
//! - **bodies**: points = centres of mass (m); point data `body_id`,
//!   `quaternion` (4 components w, x, y, z, body → world), `ex`, `ey`, `ez`
//!   (the body-frame axes expressed in the world frame, for glyphs: the
//!   rows of the matrix A, LIGGGHTS' `ex_space, ey_space, ez_space`),
//!   `euler` (z-x-z Euler angles phi, theta, psi, rad), `velocity` (m/s),
//!   `angular_velocity` (rad/s, world), `template` (the scenario's template
//!   index, 0-based, in the order of `[[template]]`; the names are listed
//!   in `manifest.json`), `scale` (the body's size factor of a mix's size
//!   distribution, 1 otherwise), `mass` (kg), `volume` (m³), `inertia`
//!   (principal moments, body frame, kg m²), `force` and `torque` (the
//!   total load of the last step, contacts and gravity, N and N m, world),
//!   `coordination` (other bodies touched), `contacts` (sphere–sphere
//!   contacts of its spheres), `wall_contacts` (sphere–wall contacts); the
//!   three counts are −1 where the frame has no force evaluation recorded
//!   (the first frame, bodies inserted at that step); with `[heat]` also
//!   `temperature` (K) and `heat_source` (W). Field data
//!   `template_names`: the names that `template` indexes, so a frame
//!   colours by shape with the names in the legend.
//! - **walls**: one polygon per face: planes clipped to the domain box,
//!   cylinders tessellated with [`CYLINDER_SEGMENTS`] quads over the domain's
//!   extent along their axis, boxes as 6 quads, meshes as their triangles
//!   at the wall's pose; cell data `wall_index` and
//!   `active` (1/0).
//!
//! Sphere positions are recomputed from the body poses (so a frame written
//! right after inserting bodies is correct); they are not wrapped into a
//! periodic box. [`VtkSeries`] writes the three files as
//! `spheres_000123.vtp`, `bodies_000123.vtp`, `walls_000123.vtp` and keeps
//! `spheres.pvd`, `bodies.pvd`, `walls.pvd` up to date. Every file is
//! written atomically ([`crate::atomic`]).

use crate::atomic::write_atomic;
use crate::post::frame::base_templates;
use crate::vtp::Vtp;
use clump_core::boundary::Domain;
use clump_core::wall::WallShape;
use clump_core::world::World;
use glam::DVec3;
use std::fmt::Write as _;
use std::io;
use std::path::{Path, PathBuf};

/// Number of segments around a cylinder wall.
pub const CYLINDER_SEGMENTS: usize = 64;

/// The spheres file (see the [module docs](self)) as bytes.
pub fn spheres_vtp(world: &World) -> Vec<u8> {
    spheres_vtp_of(world, None)
}

/// The indices of the bodies that `keep` keeps (all when `None`), in
/// storage order.
fn kept(n: usize, keep: Option<&[bool]>) -> Vec<usize> {
    (0..n).filter(|&i| keep.map_or(true, |k| k[i])).collect()
}

/// The spheres file of the bodies that `keep` (per body, storage order)
/// keeps, all when `None`: a rank's piece of a frame ([`crate::vtk_pieces`]).
pub fn spheres_vtp_of(world: &World, keep: Option<&[bool]>) -> Vec<u8> {
    let b = &world.bodies();
    let mut pos = Vec::new();
    let mut vel = Vec::new();
    let mut rad = Vec::new();
    let mut ids = Vec::new();
    for i in kept(b.len(), keep) {
        let t = &world.templates[b.template[i] as usize];
        let (x, q, v, w) = (
            b.position[i],
            b.orientation[i],
            b.velocity[i],
            b.angular_velocity[i],
        );
        for s in &t.spheres {
            let c = x + q * s.center;
            pos.push(c);
            vel.push(v + w.cross(c - x));
            rad.push(s.radius);
            ids.push(b.id[i]);
        }
    }
    let mut f = Vtp::default();
    f.set_points(&pos);
    f.point_f64("radius", 1, rad.into_iter());
    f.point_u64("body_id", ids.into_iter());
    f.point_vec3("velocity", &vel);
    f.vertex_cells();
    f.finish()
}

/// The bodies file (see the [module docs](self)) as bytes, without contact
/// counts.
pub fn bodies_vtp(world: &World) -> Vec<u8> {
    bodies_vtp_counted(world, None)
}

/// Per body id: its coordination number, sphere–sphere contacts and
/// sphere–wall contacts ([`crate::post::network::body_counts`]).
pub type BodyCounts = std::collections::HashMap<u64, [u32; 3]>;

/// The bodies file with the contact counts of `counts` (bodies missing
/// there, or all when `None`, get −1: no force evaluation recorded).
pub fn bodies_vtp_counted(world: &World, counts: Option<&BodyCounts>) -> Vec<u8> {
    bodies_vtp_of(world, counts, None)
}

/// [`bodies_vtp_counted`] of the bodies that `keep` (per body, storage
/// order) keeps, all when `None`: a rank's piece of a frame.
pub fn bodies_vtp_of(world: &World, counts: Option<&BodyCounts>, keep: Option<&[bool]>) -> Vec<u8> {
    let b = &world.bodies();
    let idx = kept(b.len(), keep);
    // the kept entries of a per-body slice
    fn pick<T: Copy>(v: &[T], idx: &[usize]) -> Vec<T> {
        idx.iter().map(|&i| v[i]).collect()
    }
    let (id, orientation, template) = (
        pick(&b.id, &idx),
        pick(&b.orientation, &idx),
        pick(&b.template, &idx),
    );
    let mut f = Vtp::default();
    let base = base_templates(world);
    let names: Vec<String> = (0..base.len())
        .filter(|&k| base[k] == k)
        .map(|k| world.templates[k].name.clone())
        .collect();
    f.field_strings("template_names", &names);
    f.set_points(&pick(&b.position, &idx));
    f.point_u64("body_id", id.iter().copied());
    f.point_f64(
        "quaternion",
        4,
        orientation.iter().flat_map(|q| [q.w, q.x, q.y, q.z]),
    );
    for (name, axis) in [("ex", DVec3::X), ("ey", DVec3::Y), ("ez", DVec3::Z)] {
        let v: Vec<DVec3> = orientation.iter().map(|q| *q * axis).collect();
        f.point_vec3(name, &v);
    }
    f.point_f64(
        "euler",
        3,
        orientation.iter().flat_map(|&q| {
            let (phi, theta, psi) = clump_core::math::quat_to_euler(q);
            [phi, theta, psi]
        }),
    );
    f.point_vec3("velocity", &pick(&b.velocity, &idx));
    f.point_vec3("angular_velocity", &pick(&b.angular_velocity, &idx));
    // with a fluid: its force on each body at the last step (drag,
    // buoyancy, pressure gradient), N, world frame
    if world.fluid().is_some() && world.fluid_forces().len() == b.len() {
        f.point_vec3("fluid_force", &pick(world.fluid_forces(), &idx));
    }
    f.point_i32(
        "template",
        template.iter().map(|&t| base[t as usize] as i32),
    );
    f.point_f64(
        "scale",
        1,
        template.iter().map(|&t| {
            let (own, of_base) = (
                &world.templates[t as usize],
                &world.templates[base[t as usize]],
            );
            own.max_radius / of_base.max_radius
        }),
    );
    f.point_f64("mass", 1, idx.iter().map(|&i| b.mass[i]));
    f.point_f64(
        "volume",
        1,
        template.iter().map(|&t| world.templates[t as usize].volume),
    );
    f.point_vec3("inertia", &pick(&b.inertia, &idx));
    f.point_vec3("force", &pick(&b.force, &idx));
    f.point_vec3("torque", &pick(&b.torque, &idx));
    for (k, name) in ["coordination", "contacts", "wall_contacts"]
        .into_iter()
        .enumerate()
    {
        f.point_i32(
            name,
            id.iter()
                .map(|id| counts.and_then(|c| c.get(id)).map_or(-1, |n| n[k] as i32)),
        );
    }
    if world.heat.is_some() {
        f.point_f64("temperature", 1, idx.iter().map(|&i| b.temperature[i]));
        f.point_f64("heat_source", 1, idx.iter().map(|&i| b.heat_source[i]));
    }
    f.vertex_cells();
    f.finish()
}

/// Polygon (3–6 vertices, ordered) of the plane through `p` with unit
/// normal `n` clipped to the box; a domain-sized square centred on the
/// projection of the box centre when the plane misses the box.
fn clip_plane(p: DVec3, n: DVec3, d: &Domain) -> Vec<DVec3> {
    let (lo, hi) = (d.lo, d.hi);
    let corner = |k: usize| {
        DVec3::new(
            if k & 1 == 0 { lo.x } else { hi.x },
            if k & 2 == 0 { lo.y } else { hi.y },
            if k & 4 == 0 { lo.z } else { hi.z },
        )
    };
    let mut pts: Vec<DVec3> = Vec::new();
    for a in 0..8usize {
        for bit in [1usize, 2, 4] {
            if a & bit != 0 {
                continue;
            }
            let (ca, cb) = (corner(a), corner(a | bit));
            let (sa, sb) = ((ca - p).dot(n), (cb - p).dot(n));
            if sa == 0.0 {
                pts.push(ca);
            }
            if sb == 0.0 {
                pts.push(cb);
            }
            if (sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0) {
                pts.push(ca + (cb - ca) * (sa / (sa - sb)));
            }
        }
    }
    let tol = 1e-12 * (hi - lo).length();
    let mut uniq: Vec<DVec3> = Vec::new();
    for q in pts {
        if !uniq.iter().any(|u| (*u - q).length() <= tol) {
            uniq.push(q);
        }
    }
    let (e1, e2) = n.any_orthonormal_pair();
    if uniq.len() < 3 {
        let c0 = 0.5 * (lo + hi);
        let c = c0 - n * (c0 - p).dot(n);
        let h = 0.5 * (hi - lo).max_element();
        return vec![
            c - e1 * h - e2 * h,
            c + e1 * h - e2 * h,
            c + e1 * h + e2 * h,
            c - e1 * h + e2 * h,
        ];
    }
    let c = uniq.iter().fold(DVec3::ZERO, |s, q| s + *q) / uniq.len() as f64;
    uniq.sort_by(|a, b| {
        let fa = (*a - c).dot(e2).atan2((*a - c).dot(e1));
        let fb = (*b - c).dot(e2).atan2((*b - c).dot(e1));
        fa.total_cmp(&fb)
    });
    uniq
}

/// The walls file (see the [module docs](self)) as bytes.
pub fn walls_vtp(world: &World) -> Vec<u8> {
    let d = &world.config.domain;
    let mut pts: Vec<DVec3> = Vec::new();
    let mut polys: Vec<Vec<i64>> = Vec::new();
    let mut wall_index = Vec::new();
    let mut active = Vec::new();
    for (wi, w) in world.walls.iter().enumerate() {
        let first = polys.len();
        match w.shape {
            WallShape::Plane { point, normal } => {
                let poly = clip_plane(point, normal, d);
                let base = pts.len() as i64;
                polys.push((0..poly.len() as i64).map(|k| base + k).collect());
                pts.extend(poly);
            }
            WallShape::Cylinder {
                point,
                axis,
                radius,
                ..
            } => {
                let (mut t0, mut t1) = (f64::INFINITY, f64::NEG_INFINITY);
                for k in 0..8 {
                    let c = DVec3::new(
                        if k & 1 == 0 { d.lo.x } else { d.hi.x },
                        if k & 2 == 0 { d.lo.y } else { d.hi.y },
                        if k & 4 == 0 { d.lo.z } else { d.hi.z },
                    );
                    let t = (c - point).dot(axis);
                    t0 = t0.min(t);
                    t1 = t1.max(t);
                }
                let (e1, e2) = axis.any_orthonormal_pair();
                let base = pts.len() as i64;
                let m = CYLINDER_SEGMENTS;
                for k in 0..m {
                    let phi = std::f64::consts::TAU * k as f64 / m as f64;
                    let r = (e1 * phi.cos() + e2 * phi.sin()) * radius;
                    pts.push(point + axis * t0 + r);
                    pts.push(point + axis * t1 + r);
                }
                for k in 0..m {
                    let k2 = (k + 1) % m;
                    let (a0, a1, b0, b1) = (2 * k, 2 * k + 1, 2 * k2, 2 * k2 + 1);
                    polys.push(vec![
                        base + a0 as i64,
                        base + b0 as i64,
                        base + b1 as i64,
                        base + a1 as i64,
                    ]);
                }
            }
            WallShape::Mesh {
                mesh,
                position,
                orientation,
            } => {
                if let Some(m) = world.walls.meshes().get(mesh as usize) {
                    let base = pts.len() as i64;
                    pts.extend(m.vertices_at(position, orientation));
                    for t in m.triangles() {
                        polys.push(t.iter().map(|&i| base + i as i64).collect());
                    }
                }
            }
            WallShape::Box { lo, hi, .. } => {
                let base = pts.len() as i64;
                // vertex k takes hi along axis a when bit a of k is set
                pts.extend(clump_core::wall::mesh::primitives::cuboid(lo, hi).0);
                for face in [
                    [0, 2, 6, 4],
                    [1, 5, 7, 3],
                    [0, 4, 5, 1],
                    [2, 3, 7, 6],
                    [0, 1, 3, 2],
                    [4, 6, 7, 5],
                ] {
                    polys.push(face.iter().map(|&i| base + i).collect());
                }
            }
        }
        for _ in first..polys.len() {
            wall_index.push(wi as i32);
            active.push(w.active as u8);
        }
    }
    let mut f = Vtp::default();
    f.set_points(&pts);
    f.polygons(&polys);
    f.cell_i32("wall_index", wall_index.into_iter());
    f.cell_u8("active", active.into_iter());
    f.finish()
}

/// Writes the spheres file to `path` (atomically).
pub fn write_spheres(path: impl AsRef<Path>, world: &World) -> io::Result<()> {
    write_atomic(path, &spheres_vtp(world))
}

/// Writes the bodies file to `path` (atomically).
pub fn write_bodies(path: impl AsRef<Path>, world: &World) -> io::Result<()> {
    write_atomic(path, &bodies_vtp(world))
}

/// Writes the walls file to `path` (atomically).
pub fn write_walls(path: impl AsRef<Path>, world: &World) -> io::Result<()> {
    write_atomic(path, &walls_vtp(world))
}

/// A ParaView `.pvd` collection (time series), rewritten atomically on every
/// append.
#[derive(Debug, Clone)]
pub struct PvdWriter {
    path: PathBuf,
    /// (time in s, file name relative to the .pvd's directory).
    entries: Vec<(f64, String)>,
}

impl PvdWriter {
    /// A new, empty collection at `path` (written at the first append).
    pub fn new(path: impl Into<PathBuf>) -> Self {
        PvdWriter {
            path: path.into(),
            entries: Vec::new(),
        }
    }

    /// Reopens the collection at `path` for a resumed run, keeping the
    /// entries with time ≤ `max_time` (s) and deleting the files of the
    /// later ones (plain names beside the collection). A missing or
    /// unreadable file starts an empty collection.
    pub fn resume(path: impl Into<PathBuf>, max_time: f64) -> Self {
        let path = path.into();
        let mut entries = Vec::new();
        if let Ok(text) = std::fs::read_to_string(&path) {
            for line in text.lines() {
                let (Some(t), Some(f)) = (attr(line, "timestep"), attr(line, "file")) else {
                    continue;
                };
                if let Ok(t) = t.parse::<f64>() {
                    let f = unescape(&f);
                    if t <= max_time {
                        entries.push((t, f));
                    } else if let (Some(dir), false) = (path.parent(), f.contains(['/', '\\'])) {
                        // a frame after the restart belongs to the run that is
                        // being rewound: delete it rather than leave it orphaned
                        if f.ends_with(".pvtp") || f.ends_with(".pvtu") {
                            for piece in
                                crate::vtk_pieces::sources(&dir.join(&f)).unwrap_or_default()
                            {
                                let _ = std::fs::remove_file(piece);
                            }
                        }
                        let _ = std::fs::remove_file(dir.join(&f));
                    }
                }
            }
        }
        PvdWriter { path, entries }
    }

    /// The collection's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The entries: (time in s, file name).
    pub fn entries(&self) -> &[(f64, String)] {
        &self.entries
    }

    /// Adds a data set at `time` (s), `file` relative to the .pvd's
    /// directory, and rewrites the collection.
    pub fn append(&mut self, time: f64, file: &str) -> io::Result<()> {
        self.entries.push((time, file.to_string()));
        self.write()
    }

    /// Rewrites the collection file atomically.
    pub fn write(&self) -> io::Result<()> {
        let mut x = String::from(
            "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n",
        );
        for (t, f) in &self.entries {
            let _ = writeln!(
                x,
                "    <DataSet timestep=\"{t:e}\" group=\"\" part=\"0\" file=\"{}\"/>",
                escape(f)
            );
        }
        x.push_str("  </Collection>\n</VTKFile>\n");
        write_atomic(&self.path, x.as_bytes())
    }
}

fn attr(line: &str, name: &str) -> Option<String> {
    let key = format!(" {name}=\"");
    let i = line.find(&key)? + key.len();
    let j = line[i..].find('"')?;
    Some(line[i..i + j].to_string())
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

fn unescape(s: &str) -> String {
    s.replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&")
}

/// Writes spheres/bodies/walls frames into one directory and keeps the three
/// `.pvd` collections current.
#[derive(Debug, Clone)]
pub struct VtkSeries {
    dir: PathBuf,
    spheres: PvdWriter,
    bodies: PvdWriter,
    walls: PvdWriter,
    format: crate::vtu::VtkFormat,
}

impl VtkSeries {
    /// A new series in `dir` (created if missing).
    pub fn new(dir: impl Into<PathBuf>) -> io::Result<Self> {
        let dir = dir.into();
        std::fs::create_dir_all(&dir).map_err(|e| {
            io::Error::new(e.kind(), format!("cannot create {}: {e}", dir.display()))
        })?;
        let s = VtkSeries {
            spheres: PvdWriter::new(dir.join("spheres.pvd")),
            bodies: PvdWriter::new(dir.join("bodies.pvd")),
            walls: PvdWriter::new(dir.join("walls.pvd")),
            dir,
            format: Default::default(),
        };
        // the collections exist from the start (the spheres and bodies ones
        // stay empty until the first body, see `write_frame`)
        s.spheres.write()?;
        s.bodies.write()?;
        s.walls.write()?;
        Ok(s)
    }

    /// The series writing its frames in `format` (`.vtp` by default).
    pub fn with_format(mut self, format: crate::vtu::VtkFormat) -> Self {
        self.format = format;
        self
    }

    /// Reopens a series in `dir` for a resumed run: collection entries after
    /// `max_time` (s) are dropped (their frame files are overwritten later).
    pub fn resume(dir: impl Into<PathBuf>, max_time: f64) -> io::Result<Self> {
        let dir = dir.into();
        std::fs::create_dir_all(&dir).map_err(|e| {
            io::Error::new(e.kind(), format!("cannot create {}: {e}", dir.display()))
        })?;
        let s = VtkSeries {
            spheres: PvdWriter::resume(dir.join("spheres.pvd"), max_time),
            bodies: PvdWriter::resume(dir.join("bodies.pvd"), max_time),
            walls: PvdWriter::resume(dir.join("walls.pvd"), max_time),
            dir,
            format: Default::default(),
        };
        s.spheres.write()?;
        s.bodies.write()?;
        s.walls.write()?;
        Ok(s)
    }

    /// The output directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The format of the frames.
    pub fn format(&self) -> crate::vtu::VtkFormat {
        self.format
    }

    /// Rank 0's part of a frame written in pieces ([`crate::vtk_pieces`]),
    /// once every rank's piece is on disk: `spheres_<label>.pvtp` and
    /// `bodies_<label>.pvtp` (`.pvtu` in that format) listing the pieces
    /// of the ranks `listed` (of `n`), with the arrays declared in rank 0's
    /// pieces `headers` (spheres, bodies, in the series' format), appended
    /// to the collections; the walls frame whole, in the series' format.
    /// `bodies`: the frame's bodies over all ranks (the spheres and bodies
    /// series start at the first frame with bodies, as in
    /// [`Self::write_frame`]).
    pub fn write_parallel_frame(
        &mut self,
        world: &World,
        label: u64,
        headers: [&[u8]; 2],
        listed: &[usize],
        n: usize,
        bodies: usize,
    ) -> io::Result<()> {
        use crate::vtk_pieces::{collection_name, parallel_file, piece_name};
        let ext = self.format.extension();
        if bodies > 0 || !self.spheres.entries().is_empty() {
            for (k, (kind, head)) in ["spheres", "bodies"].into_iter().zip(headers).enumerate() {
                let sources: Vec<String> = listed
                    .iter()
                    .map(|&r| piece_name(kind, label, r, n, ext))
                    .collect();
                let x = parallel_file(head, &sources)
                    .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))?;
                let name = collection_name(kind, label, ext);
                write_atomic(self.dir.join(&name), &x)?;
                let pvd = if k == 0 {
                    &mut self.spheres
                } else {
                    &mut self.bodies
                };
                pvd.append(world.time, &name)?;
            }
        }
        let name = format!("walls_{label:06}.{ext}");
        write_atomic(self.dir.join(&name), &self.format.encode(walls_vtp(world)))?;
        self.walls.append(world.time, &name)
    }

    /// Whether the spheres and bodies series have started (see
    /// [`Self::write_frame`]).
    pub fn started(&self) -> bool {
        !self.spheres.entries().is_empty()
    }

    /// Writes `spheres_<label>.vtp`, `bodies_<label>.vtp`, `walls_<label>.vtp`
    /// (label zero-padded to 6 digits, e.g. the step number; `.vtu` in that
    /// format) at `world.time` and appends them to the collections.
    ///
    /// The spheres and bodies series start at the first frame with bodies:
    /// VTK drops the arrays of a piece without points, so a first frame
    /// without bodies would leave `radius` out of ParaView's Glyph menu
    /// (ParaView shows a series' first frame at earlier times). Frames
    /// without bodies after that (e.g. an emptied hopper) are written.
    pub fn write_frame(&mut self, world: &World, label: u64) -> io::Result<()> {
        self.write_frame_counted(world, label, None)
    }

    /// [`Self::write_frame`] with the bodies' contact counts.
    pub fn write_frame_counted(
        &mut self,
        world: &World,
        label: u64,
        counts: Option<&BodyCounts>,
    ) -> io::Result<()> {
        let ext = self.format.extension();
        let names = [
            format!("spheres_{label:06}.{ext}"),
            format!("bodies_{label:06}.{ext}"),
            format!("walls_{label:06}.{ext}"),
        ];
        let write =
            |name: &str, vtp: Vec<u8>| write_atomic(self.dir.join(name), &self.format.encode(vtp));
        if !world.bodies().is_empty() || !self.spheres.entries().is_empty() {
            write(&names[0], spheres_vtp(world))?;
            write(&names[1], bodies_vtp_counted(world, counts))?;
            self.spheres.append(world.time, &names[0])?;
            self.bodies.append(world.time, &names[1])?;
        }
        write(&names[2], walls_vtp(world))?;
        self.walls.append(world.time, &names[2])
    }
}
