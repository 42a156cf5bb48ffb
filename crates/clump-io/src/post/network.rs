//! The body contact network of one frame: per pair of bodies in contact,
//! the number of sphere contacts between them, the summed force and the
//! branch vector between their centres of mass; per body, its coordination
//! number and sphere contacts. Written as an edge list (CSV) readable by
//! pandas or networkx.

use super::frame::{min_image, Frame, Side};
use glam::DVec3;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// One edge of the network: bodies `body_i < body_j`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Edge {
    /// The smaller global body id.
    pub body_i: u64,
    /// The larger global body id.
    pub body_j: u64,
    /// Sphere contacts between the two bodies.
    pub contacts: usize,
    /// Summed force on `body_i` from `body_j`, world frame, N.
    pub force: DVec3,
    /// Branch vector from `body_i`'s centre of mass to `body_j`'s (minimum
    /// image across periodic boundaries), world frame, m.
    pub branch: DVec3,
}

/// The edges of a frame's contact network, ordered by (body_i, body_j);
/// empty when the frame has no contacts recorded.
pub fn edges(frame: &Frame) -> Vec<Edge> {
    let index = frame.index_by_id();
    let mut map: BTreeMap<(u64, u64), Edge> = BTreeMap::new();
    for c in frame.contacts.iter().flatten() {
        let Side::Body(j) = c.partner else { continue };
        let (a, b, f) = if c.body_i < j {
            (c.body_i, j, c.force)
        } else {
            (j, c.body_i, -c.force)
        };
        let (Some(&ia), Some(&ib)) = (index.get(&a), index.get(&b)) else {
            continue;
        };
        let branch = min_image(
            &frame.domain,
            frame.bodies[ib].position - frame.bodies[ia].position,
        );
        let e = map.entry((a, b)).or_insert(Edge {
            body_i: a,
            body_j: b,
            contacts: 0,
            force: DVec3::ZERO,
            branch,
        });
        e.contacts += 1;
        e.force += f;
    }
    map.into_values().collect()
}

/// Per body (in the frame's body order): the number of other bodies it
/// touches (its coordination number), its sphere–sphere contacts and its
/// sphere–wall contacts; `None` when the frame has no contacts recorded.
pub fn body_counts(frame: &Frame) -> Option<Vec<[u32; 3]>> {
    let contacts = frame.contacts.as_ref()?;
    let index = frame.index_by_id();
    let mut out = vec![[0u32; 3]; frame.bodies.len()];
    for c in contacts {
        let i = index.get(&c.body_i).copied();
        match c.partner {
            Side::Body(j) => {
                for b in [i, index.get(&j).copied()].into_iter().flatten() {
                    out[b][1] += 1;
                }
            }
            Side::Wall(_) => {
                if let Some(i) = i {
                    out[i][2] += 1;
                }
            }
        }
    }
    for e in edges(frame) {
        for id in [e.body_i, e.body_j] {
            if let Some(&b) = index.get(&id) {
                out[b][0] += 1;
            }
        }
    }
    Some(out)
}

/// The header line of the network CSV.
pub const CSV_HEADER: &str =
    "body_i,body_j,contacts,force_x[N],force_y[N],force_z[N],branch_x[m],branch_y[m],branch_z[m]\n";

/// The network as CSV text, one edge per line, with a header.
pub fn csv(frame: &Frame) -> String {
    let mut s = String::from(CSV_HEADER);
    for e in edges(frame) {
        s.push_str(&csv_line(&e));
    }
    s
}

/// One edge's line of the CSV (with its newline).
pub fn csv_line(e: &Edge) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{},{},{},{:e},{:e},{:e},{:e},{:e},{:e}",
        e.body_i,
        e.body_j,
        e.contacts,
        e.force.x,
        e.force.y,
        e.force.z,
        e.branch.x,
        e.branch.y,
        e.branch.z
    );
    s
}
