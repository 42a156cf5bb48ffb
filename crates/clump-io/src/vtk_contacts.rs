//! Contact frames: `contacts_<step>.vtp` with one line cell per touching
//! sphere contact, from the centre of sphere `i` to the centre of sphere
//! `j` (its image next to `i` across a periodic boundary) or to the wall's
//! surface point, kept in `contacts.pvd`; beside each, the body contact
//! network `network_<step>.csv` ([`crate::post::network`]).
//!
//! Cell data, world frame, SI units: `force` (on sphere `i`, N; the
//! partner gets its negative), `normal` (unit, from the partner to `i`),
//! `force_normal` and `force_tangential` (magnitudes, N), `force_magnitude`
//! (N, for a Tube filter's radius), `overlap` (m), `contact_point` (m),
//! `body_i` and `body_j` (global body ids, UInt64; `body_j` = 0 for a wall
//! contact), `wall` (wall index in scenario order, −1 for a sphere
//! contact), `sliding` (1 when the tangential force is at the Coulomb
//! limit). Field data `wall_names`: the walls' names by index.

use crate::atomic::write_atomic;
use crate::post::frame::{Frame, Side};
use crate::vtk::PvdWriter;
use crate::vtp::Vtp;
use glam::DVec3;
use std::io;
use std::path::{Path, PathBuf};

/// The contacts file of a frame as bytes (no contacts recorded: an empty
/// file with the same arrays).
pub fn contacts_vtp(frame: &Frame, wall_names: &[String]) -> Vec<u8> {
    let cs = frame.contacts.as_deref().unwrap_or(&[]);
    let pts: Vec<DVec3> = cs.iter().flat_map(|c| [c.centre_i, c.end_j]).collect();
    let mut f = Vtp::default();
    f.field_strings("wall_names", wall_names);
    f.set_points(&pts);
    f.pair_lines();
    let force: Vec<DVec3> = cs.iter().map(|c| c.force).collect();
    let normal: Vec<DVec3> = cs.iter().map(|c| c.normal).collect();
    let point: Vec<DVec3> = cs.iter().map(|c| c.point).collect();
    f.cell_vec3("force", &force);
    f.cell_vec3("normal", &normal);
    f.cell_f64("force_normal", 1, cs.iter().map(|c| c.normal_force()));
    f.cell_f64(
        "force_tangential",
        1,
        cs.iter().map(|c| c.tangential_force()),
    );
    f.cell_f64("force_magnitude", 1, cs.iter().map(|c| c.force.length()));
    f.cell_f64("overlap", 1, cs.iter().map(|c| c.overlap));
    f.cell_vec3("contact_point", &point);
    f.cell_u64("body_i", cs.iter().map(|c| c.body_i));
    f.cell_u64(
        "body_j",
        cs.iter().map(|c| match c.partner {
            Side::Body(j) => j,
            Side::Wall(_) => 0,
        }),
    );
    f.cell_i32(
        "wall",
        cs.iter().map(|c| match c.partner {
            Side::Body(_) => -1,
            Side::Wall(w) => w as i32,
        }),
    );
    f.cell_u8("sliding", cs.iter().map(|c| c.sliding as u8));
    f.finish()
}

/// Writes contact frames and network files into a run folder and keeps
/// `contacts.pvd` current.
#[derive(Debug, Clone)]
pub struct ContactSeries {
    dir: PathBuf,
    pvd: PvdWriter,
    wall_names: Vec<String>,
}

impl ContactSeries {
    /// A new series in `dir` (the collection is written at once, empty),
    /// with `domain.json`: the domain the frames lie in (for `clump post`).
    pub fn new(
        dir: &Path,
        wall_names: Vec<String>,
        domain: &clump_core::boundary::Domain,
    ) -> io::Result<Self> {
        let json = serde_json::to_string_pretty(domain).map_err(io::Error::other)?;
        write_atomic(dir.join("domain.json"), json.as_bytes())?;
        let s = ContactSeries {
            dir: dir.to_path_buf(),
            pvd: PvdWriter::new(dir.join("contacts.pvd")),
            wall_names,
        };
        s.pvd.write()?;
        Ok(s)
    }

    /// Reopens the series for a run resumed at `max_time` (s).
    pub fn resume(dir: &Path, wall_names: Vec<String>, max_time: f64) -> io::Result<Self> {
        let s = ContactSeries {
            dir: dir.to_path_buf(),
            pvd: PvdWriter::resume(dir.join("contacts.pvd"), max_time),
            wall_names,
        };
        s.pvd.write()?;
        Ok(s)
    }

    /// Writes `contacts_<step>.vtp` and `network_<step>.csv` of `frame`
    /// (step zero-padded to 6 digits) and appends the first to the
    /// collection at the frame's time.
    pub fn write_frame(&mut self, frame: &Frame) -> io::Result<()> {
        let name = format!("contacts_{:06}.vtp", frame.step);
        write_atomic(self.dir.join(&name), &contacts_vtp(frame, &self.wall_names))?;
        write_atomic(
            self.dir.join(format!("network_{:06}.csv", frame.step)),
            crate::post::network::csv(frame).as_bytes(),
        )?;
        self.pvd.append(frame.time, &name)
    }

    /// The folder of the series.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The walls' names (the frames' field data `wall_names`).
    pub fn wall_names(&self) -> &[String] {
        &self.wall_names
    }

    /// Rank 0's part of a contact frame written in pieces (one
    /// `contacts_<step>.rank<r>of<n>.vtp` per rank, see
    /// [`crate::vtk_pieces`]), once every piece is on disk:
    /// `contacts_<step>.pvtp` listing the pieces of the ranks `listed` (of
    /// `n`), with the arrays declared in rank 0's piece `head`, appended
    /// to the collection at `time`; and `network_<step>.csv`, `network`.
    pub fn write_parallel_frame(
        &mut self,
        time: f64,
        step: u64,
        head: &[u8],
        listed: &[usize],
        n: usize,
        network: &str,
    ) -> io::Result<()> {
        use crate::vtk_pieces::{collection_name, parallel_file, piece_name};
        let sources: Vec<String> = listed
            .iter()
            .map(|&r| piece_name("contacts", step, r, n, "vtp"))
            .collect();
        let x = parallel_file(head, &sources)
            .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e))?;
        let name = collection_name("contacts", step, "vtp");
        write_atomic(self.dir.join(&name), &x)?;
        write_atomic(
            self.dir.join(format!("network_{step:06}.csv")),
            network.as_bytes(),
        )?;
        self.pvd.append(time, &name)
    }
}
