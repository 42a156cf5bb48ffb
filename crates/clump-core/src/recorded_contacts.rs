//! Read access to the current contacts: every touching sphere–sphere and
//! sphere–wall contact of the last force evaluation, with its geometry and
//! its force, in a deterministic order.
//!
//! There is no per-contact force array in a plain step (the pair kernel adds
//! each contact into its bodies' sums at once). A driver asks for contacts
//! by an [`crate::step::run::Event`] with `contacts = true`: the step that
//! ends at that event then also stores each contact's normal, overlap and
//! force as the kernels computed them (one store per contact, in that step
//! only), and [`World::contacts`] reads those records at the boundary. The
//! forces are therefore the very ones summed into the bodies and walls, bit
//! for bit. The order: sphere–sphere contacts in the pair list's order
//! (rows ascending, which follows the bodies' storage order), then
//! sphere–wall contacts in the gather's order (bodies ascending, walls
//! ascending per sphere). It depends only on the state, never on the thread
//! count.

use crate::contact::geometry::contact_point;
use crate::neighbor::topo::RowWalk;
use crate::sphere::SPHERE_ID_BITS;
use crate::world::World;
use glam::DVec3;
use thiserror::Error;

/// Why [`World::contacts`] has nothing to give.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
pub enum ContactsError {
    /// The step that ended here did not record contacts (ask for them with
    /// an event whose `contacts` is true), or bodies were added or removed
    /// since.
    #[error("no contact records for step {step}: ask for them with the event that ends there (Event {{ contacts: true, .. }})")]
    NotRecorded {
        /// The world's step.
        step: u64,
    },
}

/// The other side of a contact.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Partner {
    /// Another body's sphere.
    Sphere {
        /// Global sphere id (`body_id << 16 | index in template`).
        sphere_id: u64,
        /// Global body id.
        body_id: u64,
    },
    /// A wall.
    Wall {
        /// Wall index (scenario order).
        wall: usize,
        /// Face of an analytic wall (box faces 0..6, else 0); for a mesh
        /// wall the 16-bit octahedral code of the contact normal.
        patch: u16,
    },
}

/// One touching contact, seen from its sphere `i`. World frame, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Global sphere id of sphere `i`.
    pub sphere_id: u64,
    /// Global body id of sphere `i`'s body.
    pub body_id: u64,
    /// The other side.
    pub partner: Partner,
    /// Contact point, m: on the line of centres (or the wall normal), at
    /// `x_i − (r_i − δ/2) n`.
    pub point: DVec3,
    /// Unit normal from the partner to sphere `i`.
    pub normal: DVec3,
    /// Overlap `δ`, m.
    pub overlap: f64,
    /// Normal force on sphere `i` (the partner gets its negative), N.
    pub force_normal: DVec3,
    /// Tangential force on sphere `i`: the total minus the normal part, N.
    pub force_tangential: DVec3,
    /// Tangential spring `ξ` after the step, m (in the tangent plane).
    pub tangential_spring: DVec3,
    /// The contact slides: its tangential force is at the Coulomb limit,
    /// `|F_t| ≥ (1 − 10⁻⁹) μ|F_n|` with the pair's friction coefficient `μ`
    /// (docs/theory.md T-30). The law caps `|F_t|` at exactly `μ|F_n|` when
    /// the trial force exceeds it, and both are scaled alike by the
    /// multi-contact rule, so the test reads the law's own branch back to
    /// round-off. A frictionless contact (`μ = 0`) always slides.
    pub sliding: bool,
}

/// Whether a contact with normal force `fnv` and tangential force `ftv`
/// under friction coefficient `mu` is at the Coulomb limit (see
/// [`Contact::sliding`]).
fn at_coulomb_limit(fnv: DVec3, ftv: DVec3, mu: f64) -> bool {
    ftv.length() >= (1.0 - 1e-9) * mu * fnv.length()
}

impl Contact {
    /// Total force on sphere `i`, N.
    pub fn force(&self) -> DVec3 {
        self.force_normal + self.force_tangential
    }
}

/// Iterator over the contacts of the current step ([`World::contacts`]).
pub struct Contacts<'a> {
    world: &'a World,
    /// Next pair index to look at.
    pair: usize,
    /// The rows of the pairs looked at.
    rows: RowWalk<'a>,
    /// Next wall chunk and entry within it.
    chunk: usize,
    entry: usize,
}

impl Iterator for Contacts<'_> {
    type Item = Contact;

    fn next(&mut self) -> Option<Contact> {
        let w = self.world;
        let sp = &w.spheres;
        let pairs = &w.neighbors.pairs;
        let rec = &w.neighbors.records;
        while self.pair < pairs.topo.len() {
            let p = self.pair;
            self.pair += 1;
            let t = pairs.topo[p];
            let i = self.rows.next(p, t);
            if !t.live() {
                continue;
            }
            let r = rec.pair[p];
            let j = t.j as usize;
            let fnv = r.normal * r.normal_force;
            let mu = w
                .contact_table
                .get(sp.material[i], sp.material[j])
                .sliding_law()
                .friction;
            return Some(Contact {
                sphere_id: sp.gid[i],
                body_id: sp.gid[i] >> SPHERE_ID_BITS,
                partner: Partner::Sphere {
                    sphere_id: sp.gid[j],
                    body_id: sp.gid[j] >> SPHERE_ID_BITS,
                },
                point: contact_point(sp.position(i), r.normal, sp.radius[i], r.overlap),
                normal: r.normal,
                overlap: r.overlap,
                force_normal: fnv,
                force_tangential: r.force - fnv,
                tangential_spring: pairs.tangential[p],
                sliding: at_coulomb_limit(fnv, r.force - fnv, mu),
            });
        }
        while self.chunk < rec.wall.len() {
            let list = &rec.wall[self.chunk];
            if self.entry >= list.len() {
                self.chunk += 1;
                self.entry = 0;
                continue;
            }
            let r = list[self.entry];
            self.entry += 1;
            let s = r.sphere as usize;
            let fnv = r.normal * r.normal_force;
            let mu = w
                .contact_table
                .get(sp.material[s], w.walls[r.wall as usize].material)
                .sliding_law()
                .friction;
            return Some(Contact {
                sphere_id: sp.gid[s],
                body_id: sp.gid[s] >> SPHERE_ID_BITS,
                partner: Partner::Wall {
                    wall: r.wall as usize,
                    patch: r.patch,
                },
                point: contact_point(sp.position(s), r.normal, sp.radius[s], r.overlap),
                normal: r.normal,
                overlap: r.overlap,
                force_normal: fnv,
                force_tangential: r.force - fnv,
                tangential_spring: r.spring,
                sliding: at_coulomb_limit(fnv, r.force - fnv, mu),
            });
        }
        None
    }
}

impl World {
    /// The touching contacts of the step that ended at the current step
    /// boundary, when that step recorded them (see the module docs).
    pub fn contacts(&self) -> Result<Contacts<'_>, ContactsError> {
        if self.neighbors.records.step != Some(self.step) || self.phase.topology_dirty() {
            return Err(ContactsError::NotRecorded { step: self.step });
        }
        Ok(Contacts {
            world: self,
            pair: 0,
            rows: RowWalk::new(&self.neighbors.pairs.row_start),
            chunk: 0,
            entry: 0,
        })
    }
}
