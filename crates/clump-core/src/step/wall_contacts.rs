//! The sphere–wall contacts of a body chunk, in the gather: for each sphere
//! in the wall list, the walls near it (the list's mask), their touches
//! (analytic shapes and meshes, `crate::wall`), each touch's history slot
//! carried from the last step (by face for analytic walls, by contact
//! normal for meshes, so a contact sliding across triangles keeps its
//! spring), the contact law (`crate::contact`), and the sums: the force and
//! torque on the body, the load on the wall, the statistics, the contact
//! records when the step keeps them.
//!
//! The touches are collected body by body ([`WallPass::collect`]) with their
//! geometry and contact-point velocities, and their law runs in batches
//! ([`WallPass::flush`]): as the lanes of one vector loop
//! (`super::wall_lanes`) for the models that have it, the scalar
//! composition for the others (evaluated as they are collected). The sums
//! are then made in the touches' order, as they are collected, so the
//! results do not depend on where a batch ends.

use super::law_lanes::{finish_sliding, run_law};
use super::wall_lanes::{WallLanes, WALL_BATCH};
use crate::body::Bodies;
use crate::contact::geometry::contact_point;
use crate::contact::mdr::SlipProfile;
use crate::contact::record::WallRecord;
use crate::contact::{ContactHistory, ContactInput, ContactOutput, ContactTable};
use crate::multi_contact::{MultiContact, PartnerCounts};
use crate::neighbor::walls::{WallList, WALL_SLOTS};
use crate::neighbor::PairBody;
use crate::par::affinity::MAX_BODY_CHUNK;
use crate::par::shared::{at, SharedMut};
use crate::par::simd::{get3, set3, simd, Simd};
use crate::sphere::{point_velocity, Spheres};
use crate::stats::ContactStats;
use crate::wall::{TriMesh, Wall, WallLoad, WallShape, WallTouch, MAX_TOUCHES_PER_WALL};
use glam::DVec3;
use std::ops::Range;

/// What the gather's wall pass reads and writes, shared by its chunks.
pub(super) struct WallPass<'a> {
    sp: &'a Spheres,
    b: &'a Bodies,
    /// The pair stage's packed copy of the bodies, when the body arrays'
    /// velocities lag behind it (`StepPhase::bodies_lag`).
    lagged: Option<SharedMut<PairBody>>,
    table: &'a ContactTable,
    walls: &'a [Wall],
    meshes: &'a [TriMesh],
    dt: f64,
    nw: usize,
    /// Sphere of each wall-list entry (ascending).
    pub entry_sphere: &'a [u32],
    /// First entry of each body chunk.
    pub chunk_start: &'a [u32],
    mask: &'a [u64],
    /// The active walls among the first 64, as bits.
    active_lo: u64,
    keys: SharedMut<[u32; WALL_SLOTS]>,
    hists: SharedMut<[ContactHistory; WALL_SLOTS]>,
    /// The slots' MDR profiles (empty unless some law keeps them): a
    /// touch's new profile is written as its law runs, in collect.
    slips: SharedMut<[SlipProfile; WALL_SLOTS]>,
    /// Per chunk and wall: the load of the chunk's contacts.
    loads: SharedMut<WallLoad>,
    walls_average: bool,
    recording: bool,
    records: SharedMut<Vec<WallRecord>>,
    /// The vector instructions the law loop may use.
    simd: Simd,
    /// The exact sums of the owned contacts, when this step makes them.
    sums: Option<&'a crate::contact::step_sums::StepSums>,
}

/// A touch collected for the law, summed at the next [`WallPass::flush`];
/// its law's inputs are in the lanes, at the same index. World frame, SI
/// units.
#[derive(Clone, Copy, Default)]
struct Pending {
    /// The body.
    body: u32,
    sphere: u32,
    wall: u32,
    /// Its wall-list entry.
    entry: u32,
    /// Face (analytic wall) or normal code (mesh) of its history slot.
    patch: u16,
    /// Its slot among its entry's new histories; `WALL_SLOTS` for none.
    slot: u8,
    /// Its law ran as it was collected (a model the lanes do not have;
    /// the result is in [`WallScratch::scalar`]).
    done: bool,
    /// Lever arm of the contact point from the body's centre of mass, m.
    lever: DVec3,
    /// Lever arm of the contact point from the wall's motion centre, m.
    wall_lever: DVec3,
    /// Multi-contact scale of its force.
    scale: f64,
    /// Its rolling spring (N m), which the lanes' law leaves as it is.
    rolling: DVec3,
}

/// Per thread: the touches awaiting their law, the lanes that run it, and
/// the loads of the chunk's bodies.
pub(super) struct WallScratch {
    counts: PartnerCounts,
    buf: [WallTouch; MAX_TOUCHES_PER_WALL],
    pending: [Pending; WALL_BATCH],
    len: usize,
    lanes: WallLanes,
    /// Per touch: its contact model ([`ContactTable::index`]).
    model: [u32; WALL_BATCH],
    /// Per touch: its tangential spring before the law, m.
    spring0: [DVec3; WALL_BATCH],
    /// Per touch whose law ran as it was collected: the result and the
    /// history after it.
    scalar: [(ContactOutput, ContactHistory); WALL_BATCH],
    /// The current entry's histories and MDR profiles before this step
    /// ([`WallPass::old_slots`]; 520 bytes a profile: copied or cleared for
    /// every entry, they were 5 % of the settled tetra bed's instructions).
    old_hist: [ContactHistory; WALL_SLOTS],
    old_slip: [SlipProfile; WALL_SLOTS],
    /// Per body of the chunk, from its first: the force (N) and the torque
    /// about the body's centre of mass (N m), world frame. The gather
    /// seeds a body's before its touches are collected; each touch adds to
    /// them at the flush, in the touches' order.
    pub load: [(DVec3, DVec3); MAX_BODY_CHUNK],
}

impl WallScratch {
    /// Empty.
    pub(super) fn new() -> Self {
        WallScratch {
            counts: PartnerCounts::default(),
            buf: [WallTouch::default(); MAX_TOUCHES_PER_WALL],
            pending: [Pending::default(); WALL_BATCH],
            len: 0,
            lanes: WallLanes::zeroed(),
            model: [0; WALL_BATCH],
            spring0: [DVec3::ZERO; WALL_BATCH],
            scalar: [Default::default(); WALL_BATCH],
            old_hist: [ContactHistory::default(); WALL_SLOTS],
            old_slip: [SlipProfile::default(); WALL_SLOTS],
            load: [(DVec3::ZERO, DVec3::ZERO); MAX_BODY_CHUNK],
        }
    }
}

/// Where a chunk's touches are summed: its index and first body, and its
/// contact statistics.
pub(super) struct ChunkSums<'s> {
    /// The chunk: its row of wall loads and its list of records.
    pub c: usize,
    /// Its first body (the bodies' loads are indexed from it).
    pub b0: usize,
    /// Its contact statistics.
    pub stat: &'s mut ContactStats,
}

impl<'a> WallPass<'a> {
    /// The pass over `wall_list`, summing wall loads into `loads` (chunk ×
    /// wall) and, with `recording`, each chunk's contacts into `records`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(
        sp: &'a Spheres,
        b: &'a Bodies,
        lagged: Option<SharedMut<PairBody>>,
        table: &'a ContactTable,
        walls: &'a [Wall],
        meshes: &'a [TriMesh],
        dt: f64,
        wall_list: &'a mut WallList,
        loads: SharedMut<WallLoad>,
        records: &'a mut [Vec<WallRecord>],
        recording: bool,
        sums: Option<&'a crate::contact::step_sums::StepSums>,
    ) -> Self {
        let mut active_lo = 0u64;
        for (wi, wall) in walls.iter().enumerate().take(64) {
            active_lo |= (wall.active as u64) << wi;
        }
        let WallList {
            sphere,
            mask,
            key,
            hist,
            slip,
            chunk_start,
            ..
        } = wall_list;
        WallPass {
            sp,
            b,
            lagged,
            table,
            walls,
            meshes,
            dt,
            nw: walls.len(),
            entry_sphere: sphere,
            chunk_start,
            mask,
            active_lo,
            keys: SharedMut::new(key),
            hists: SharedMut::new(hist),
            slips: SharedMut::new(slip),
            loads,
            walls_average: walls
                .iter()
                .any(|x| x.multi_contact == MultiContact::Average),
            recording,
            records: SharedMut::new(records),
            simd: simd(),
            sums,
        }
    }

    /// Walls to test for entry `e` of the wall list, in ascending order: of
    /// the first 64, the active ones of its mask (near its sphere, or
    /// moving; see `neighbor::walls`); then every active wall beyond 64.
    #[inline(always)]
    fn candidates(&self, e: usize) -> impl Iterator<Item = usize> + '_ {
        // SAFETY: e is an entry of the list, one mask per entry.
        let lo = BitIter(unsafe { at(self.mask, e) } & self.active_lo);
        lo.chain((64..self.nw).filter(|&wi| self.walls[wi].active))
    }

    /// Body `bi`'s velocity and angular velocity (world frame) as the
    /// step's pair stage saw them.
    #[inline(always)]
    fn body_velocity(&self, bi: usize) -> (DVec3, DVec3) {
        match &self.lagged {
            // SAFETY: a body of the pair list, which is built for these
            // bodies whenever they lag
            Some(pb) => unsafe {
                let pb = pb.ptr(bi);
                ((*pb).velocity, (*pb).angular_velocity)
            },
            None => (self.b.velocity[bi], self.b.angular_velocity[bi]),
        }
    }

    /// Collects the wall touches of body `bi` (centre of mass `com`), whose
    /// wall-list entries are `entries`, into `ws`, and carries their
    /// history slots: each entry's new keys are written here, its new
    /// histories when the law has run. A full batch is flushed into `sums`
    /// on the way; the body's load in `ws` must be seeded before.
    ///
    /// # Safety
    /// Body `bi` and the entries are chunk `sums.c`'s, handled by one thread.
    #[inline(always)]
    pub(super) unsafe fn collect(
        &self,
        ws: &mut WallScratch,
        bi: usize,
        com: DVec3,
        entries: Range<usize>,
        sums: &mut ChunkSums,
    ) {
        if self.walls_average {
            self.count_touches(ws, entries.clone());
        }
        let (v, wb) = self.body_velocity(bi);
        let keep_slip = self.slips.len() != 0;
        let mass = self.b.mass[bi];
        for q in entries {
            // SAFETY: entry q is of body bi, handled by this chunk only;
            // its slots are read here, and written only where no other
            // reference to them lives (a flush writes its histories)
            let (s, old_key) = unsafe { (at(self.entry_sphere, q) as usize, *self.keys.get(q)) };
            let mut cand = self.candidates(q).peekable();
            if cand.peek().is_none() {
                // no wall to test: only clear what a contact left
                if old_key[0] != 0 {
                    // SAFETY: as above
                    unsafe { self.store_keys(q, [0; WALL_SLOTS], 0, keep_slip) };
                }
                continue;
            }
            // the histories and profiles before this step: a flush may
            // write the new ones before this entry's last touch is matched
            // SAFETY: as above
            unsafe { self.old_slots(ws, q, old_key, keep_slip) };
            let mut new_key = [0u32; WALL_SLOTS];
            let mut n_new = 0;
            let mut used = [false; WALL_SLOTS];
            let (x, r) = (self.sp.position(s), self.sp.state[s].radius);
            for wi in cand {
                let wall = &self.walls[wi];
                // a JKR contact lives on while apart by less than its reach
                let reach = if self.table.any_reach() && old_key.iter().any(|&k| slot_wall(k) == wi)
                {
                    self.table.get(self.sp.material[s], wall.material).reach(r)
                } else {
                    0.0
                };
                let k = wall.shape.contacts(self.meshes, x, r, reach, &mut ws.buf);
                let is_mesh = matches!(wall.shape, WallShape::Mesh { .. });
                for t in 0..k {
                    let touch = ws.buf[t];
                    let (patch, old) = if is_mesh {
                        let patch = oct_encode(touch.normal);
                        (patch, match_mesh_slot(&old_key, &used, wi, touch.normal))
                    } else {
                        let patch = touch.face as u16;
                        let slot_key = slot_key(wi, patch);
                        (patch, old_key.iter().position(|&k| k == slot_key))
                    };
                    if touch.overlap <= 0.0 && old.is_none() {
                        // a near miss within the reach, not a live contact
                        continue;
                    }
                    let history = match old {
                        Some(o) => {
                            used[o] = true;
                            ws.old_hist[o]
                        }
                        None => ContactHistory::default(),
                    };
                    let slot = if n_new < WALL_SLOTS {
                        new_key[n_new] = slot_key(wi, patch);
                        n_new += 1;
                        n_new - 1
                    } else {
                        WALL_SLOTS
                    };
                    let n = touch.normal;
                    let xc = contact_point(x, n, r, touch.overlap);
                    let v_body = point_velocity(com, v, wb, xc);
                    let mut v_wall = wall.surface_velocity_at(xc);
                    v_wall -= n * n.dot(wall.motion.surface_velocity);
                    let vrel = v_body - v_wall;
                    let model = self.table.index(self.sp.material[s], wall.material);
                    let t = ws.len;
                    let l = &mut ws.lanes;
                    set3(&mut l.normal, t, n);
                    l.overlap[t] = touch.overlap;
                    set3(&mut l.vrel, t, vrel);
                    l.radius[t] = r;
                    l.mass[t] = mass;
                    set3(&mut l.spring, t, history.tangential);
                    ws.spring0[t] = history.tangential;
                    ws.model[t] = model;
                    let law = self.table.by_index(model);
                    let done = law.is_extended() || law.has_rolling() || scalar_only();
                    if done {
                        let mut slip = match old {
                            Some(o) if keep_slip => ws.old_slip[o],
                            _ => SlipProfile::default(),
                        };
                        let mut h = history;
                        let input = ContactInput {
                            normal: n,
                            overlap: touch.overlap,
                            rel_velocity: vrel,
                            rel_omega: wb - wall.motion.angular_velocity,
                            radius: r,
                            radius_sum: f64::INFINITY,
                            mass,
                            dt: self.dt,
                        };
                        ws.scalar[t] = (law.evaluate_slip(&input, &mut h, &mut slip), h);
                        if keep_slip && slot < WALL_SLOTS {
                            // SAFETY: entry q is of this chunk; its old
                            // profiles were copied above
                            unsafe { self.slips.get(q)[slot] = slip };
                        }
                    }
                    ws.pending[t] = Pending {
                        body: bi as u32,
                        sphere: s as u32,
                        wall: wi as u32,
                        entry: q as u32,
                        patch,
                        slot: slot as u8,
                        done,
                        lever: xc - com,
                        wall_lever: xc - wall.motion.center,
                        scale: if wall.multi_contact == MultiContact::Average {
                            1.0 / ws.counts.get(wi as u64) as f64
                        } else {
                            1.0
                        },
                        rolling: history.rolling,
                    };
                    ws.len += 1;
                    if ws.len == WALL_BATCH {
                        self.flush(ws, sums);
                    }
                }
            }
            if n_new > 0 || old_key[0] != 0 {
                // SAFETY: as above
                unsafe { self.store_keys(q, new_key, n_new, keep_slip) };
            }
        }
    }

    /// Entry `q`'s histories and (where the law keeps them) MDR profiles
    /// before this step, into `ws.old_hist` and `ws.old_slip`, when it held
    /// a contact (`old_key`, its keys before this step). Else nothing is
    /// copied: the keys are stored from the first slot on, so an entry
    /// whose first key is empty has none, and no touch finds an old slot.
    ///
    /// # Safety
    /// Entry `q` is the calling chunk's, and no reference to its slots lives.
    #[inline(always)]
    unsafe fn old_slots(
        &self,
        ws: &mut WallScratch,
        q: usize,
        old_key: [u32; WALL_SLOTS],
        keep_slip: bool,
    ) {
        if old_key[0] != 0 {
            ws.old_hist = *self.hists.get(q);
            if keep_slip {
                ws.old_slip = *self.slips.get(q);
            }
        }
    }

    /// `average` walls: the number of touches of each wall with the
    /// spheres of `entries` (one body's), into `ws.counts`.
    #[inline(always)]
    fn count_touches(&self, ws: &mut WallScratch, entries: Range<usize>) {
        ws.counts.clear();
        for q in entries {
            let s = self.entry_sphere[q] as usize;
            for wi in self.candidates(q) {
                let k = self.walls[wi].shape.contacts(
                    self.meshes,
                    self.sp.position(s),
                    self.sp.state[s].radius,
                    0.0,
                    &mut ws.buf,
                );
                for _ in 0..k {
                    ws.counts.add(wi as u64);
                }
            }
        }
    }

    /// Entry `q`'s new slot keys `key`, its histories (and profiles) from
    /// slot `n_new` on cleared; the flush writes the others.
    ///
    /// # Safety
    /// Entry `q` is the calling chunk's, and no reference to its slots lives.
    #[inline(always)]
    unsafe fn store_keys(&self, q: usize, key: [u32; WALL_SLOTS], n_new: usize, keep_slip: bool) {
        *self.keys.get(q) = key;
        for h in &mut self.hists.get(q)[n_new..] {
            *h = ContactHistory::default();
        }
        if keep_slip {
            for p in &mut self.slips.get(q)[n_new..] {
                *p = SlipProfile::default();
            }
        }
    }

    /// Runs the law of the touches in `ws` and sums them, in their order,
    /// into the bodies' loads, the chunk's wall loads and statistics, the
    /// records and the entries' history slots; empties `ws`.
    ///
    /// # Safety
    /// The touches are of chunk `sums.c`'s bodies, handled by one thread.
    pub(super) unsafe fn flush(&self, ws: &mut WallScratch, sums: &mut ChunkSums) {
        let len = ws.len;
        if len == 0 {
            return;
        }
        ws.len = 0;
        // the law over every lane (those already evaluated are not read)
        let first = ws.model[0];
        let law = if ws.model[..len].iter().all(|&m| m == first) {
            Some(*self.table.by_index(first).sliding_law())
        } else {
            for (k, &m) in ws.model[..len].iter().enumerate() {
                self.table
                    .by_index(m)
                    .sliding_law()
                    .store_lane(&mut ws.lanes.law, k);
            }
            None
        };
        let l = &mut ws.lanes;
        run_law(l, len, law.as_ref(), self.dt, self.simd);
        let spring0 = &ws.spring0;
        finish_sliding(l, len, law.as_ref(), self.dt, |k| spring0[k]);
        let c = sums.c;
        for (t, p) in ws.pending[..len].iter().enumerate() {
            let (out, history) = if p.done {
                ws.scalar[t]
            } else {
                (
                    ContactOutput {
                        force: get3(&l.force, t),
                        torque: DVec3::ZERO,
                        elastic_energy: l.energy[t],
                        normal_force: l.normal_force[t],
                    },
                    ContactHistory {
                        tangential: get3(&l.spring, t),
                        rolling: p.rolling,
                    },
                )
            };
            let scale = p.scale;
            let (wi, bi) = (p.wall as usize, p.body as usize);
            let fw = out.force;
            let mw = p.lever.cross(fw) + out.torque;
            let tw = p.wall_lever.cross(fw) + out.torque;
            if self.recording {
                // SAFETY: chunk c's list is written by chunk c only.
                unsafe { self.records.get(c) }.push(WallRecord {
                    sphere: p.sphere,
                    wall: p.wall,
                    patch: p.patch,
                    normal: get3(&l.normal, t),
                    overlap: l.overlap[t],
                    force: fw * scale,
                    normal_force: out.normal_force * scale,
                    spring: history.tangential,
                });
            }
            let (f, m) = &mut ws.load[bi - sums.b0];
            *f += fw * scale;
            *m += mw * scale;
            // SAFETY: row c of the chunk loads belongs to this chunk only.
            let load = unsafe { self.loads.get(c * self.nw + wi) };
            load.force -= fw * scale;
            load.torque -= tw * scale;
            let stat = &mut *sums.stat;
            stat.wall_contacts += 1;
            stat.elastic_energy += out.elastic_energy * scale;
            if let Some(s) = self.sums {
                s.add_elastic(out.elastic_energy * scale);
                s.add_wall(wi, -(fw * scale), -(tw * scale));
            }
            let ratio = l.overlap[t] / l.radius[t];
            if ratio > stat.max_overlap_ratio {
                stat.max_overlap_ratio = ratio;
                stat.max_overlap_bodies = [self.b.id[bi], 0];
                stat.max_overlap_wall = p.wall + 1;
            }
            if (p.slot as usize) < WALL_SLOTS {
                // SAFETY: the entry is of chunk c's bodies.
                unsafe { self.hists.get(p.entry as usize)[p.slot as usize] = history };
            }
        }
    }
}

/// Tests only: every touch takes the scalar composition (the lanes off).
#[cfg(test)]
pub(super) static SCALAR_ONLY: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

/// Tests only: whether every touch takes the scalar composition.
#[inline(always)]
fn scalar_only() -> bool {
    #[cfg(test)]
    return SCALAR_ONLY.load(std::sync::atomic::Ordering::SeqCst);
    #[cfg(not(test))]
    false
}

/// The indices of the set bits of a mask, ascending.
struct BitIter(u64);

impl Iterator for BitIter {
    type Item = usize;
    #[inline(always)]
    fn next(&mut self) -> Option<usize> {
        if self.0 == 0 {
            return None;
        }
        let i = self.0.trailing_zeros() as usize;
        self.0 &= self.0 - 1;
        Some(i)
    }
}

/// Largest angle (rad) between a mesh contact's normal and the normal stored
/// with a slot of the previous step for the contact to continue that slot's
/// history (30°; larger than the mesh merge angle, so that a contact patch
/// moving onto the next facet keeps its history).
pub const MESH_MATCH_ANGLE: f64 = std::f64::consts::PI / 6.0;

/// Key of a sphere–wall contact slot (0 = empty): wall index in the high 16
/// bits, and in the low 16 bits the face (analytic walls) or the octahedral
/// code of the contact normal (mesh walls), plus one.
#[inline(always)]
fn slot_key(wi: usize, sub: u16) -> u32 {
    ((wi as u32) << 16 | sub as u32) + 1
}

/// The wall of a history slot's key ([`slot_key`]); `usize::MAX` for an
/// empty slot (key 0).
fn slot_wall(key: u32) -> usize {
    if key == 0 {
        usize::MAX
    } else {
        ((key - 1) >> 16) as usize
    }
}

/// History slot of the previous step that continues a mesh contact with
/// normal `n` on wall `wi`: the unused slot of that wall whose stored normal
/// is closest, within [`MESH_MATCH_ANGLE`]. Mesh contacts are keyed by contact
/// patch (normal), not by triangle, so the history follows a contact that
/// slides from one triangle onto the next; the contact law rotates it into
/// the new tangent plane.
#[inline]
fn match_mesh_slot(
    key: &[u32; WALL_SLOTS],
    used: &[bool; WALL_SLOTS],
    wi: usize,
    n: glam::DVec3,
) -> Option<usize> {
    let cos_min = MESH_MATCH_ANGLE.cos();
    let mut best: Option<(usize, f64)> = None;
    for (k, &x) in key.iter().enumerate() {
        if x == 0 || used[k] || ((x - 1) >> 16) as usize != wi {
            continue;
        }
        let c = oct_decode(((x - 1) & 0xFFFF) as u16).dot(n);
        if c > cos_min && best.map_or(true, |b| c > b.1) {
            best = Some((k, c));
        }
    }
    best.map(|b| b.0)
}

/// Octahedral encoding of a unit vector in 16 bits (8 per coordinate; about
/// 1° resolution), used to remember a mesh contact's normal in its slot key.
#[inline]
pub fn oct_encode(n: glam::DVec3) -> u16 {
    let l1 = n.x.abs() + n.y.abs() + n.z.abs();
    if !(l1 > 0.0) {
        return 0;
    }
    let (mut u, mut v) = (n.x / l1, n.y / l1);
    if n.z < 0.0 {
        let (pu, pv) = (u, v);
        u = (1.0 - pv.abs()) * pu.signum();
        v = (1.0 - pu.abs()) * pv.signum();
    }
    let q = |a: f64| ((a.clamp(-1.0, 1.0) * 0.5 + 0.5) * 255.0).round() as u16;
    q(u) << 8 | q(v)
}

/// Inverse of [`oct_encode`] (unit vector).
#[inline]
pub fn oct_decode(k: u16) -> glam::DVec3 {
    let u = (k >> 8) as f64 / 255.0 * 2.0 - 1.0;
    let v = (k & 0xFF) as f64 / 255.0 * 2.0 - 1.0;
    let z = 1.0 - u.abs() - v.abs();
    let (x, y) = if z < 0.0 {
        ((1.0 - v.abs()) * u.signum(), (1.0 - u.abs()) * v.signum())
    } else {
        (u, v)
    };
    glam::DVec3::new(x, y, z).normalize()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::body::BodyInit;
    use crate::boundary::Domain;
    use crate::contact::{Material, RollingLaw};
    use crate::testbed::{
        state_bits, tetra_contact, tetra_material, tetra_template, LATTICE_PITCH,
    };
    use crate::wall::WallMotion;
    use crate::world::{AddedMass, World, WorldConfig};
    use glam::DQuat;
    use std::sync::atomic::Ordering;

    /// Tetrahedra of two materials thrown sideways into a box open in y:
    /// a floor (Sum), and two side walls of the other material, one of
    /// them averaging its touches per body (Average). The two materials'
    /// pairs have different laws, and one pair a rolling couple (scalar
    /// composition), so that the batches mix models and both paths.
    fn bed() -> World {
        let soft = Material {
            youngs_modulus: 2e6,
            ..tetra_material()
        };
        let mats = vec![tetra_material(), soft];
        let table = ContactTable::new(&mats, |a, b| {
            let mut p = tetra_contact();
            if a != b {
                p.friction = 0.3;
                p.restitution = 0.4;
            }
            if a == 1 && b == 1 {
                p.rolling = RollingLaw::Cdt;
                p.rolling_friction = 0.1;
            }
            p
        })
        .unwrap();
        let (nx, ny, nz) = (8, 8, 2);
        let lx = nx as f64 * LATTICE_PITCH;
        let config = WorldConfig {
            domain: Domain {
                lo: DVec3::new(-0.001, 0.0, -0.001),
                hi: DVec3::new(lx + 0.001, ny as f64 * LATTICE_PITCH, 0.03),
                periodic: [false, true, false],
            },
            gravity: DVec3::new(0.0, 0.0, -9.81),
            dt: 1e-5,
            rotation: Default::default(),
            added_mass: AddedMass::default(),
            skin: None,
            multi_contact: MultiContact::Sum,
        };
        let mut w = World::new(config, mats, table);
        let t = [0, 1].map(|m| w.add_template(tetra_template(), m).unwrap());
        let plane = |name: &str, point: DVec3, normal: DVec3, material, multi_contact| Wall {
            name: name.into(),
            shape: WallShape::Plane { point, normal },
            material,
            motion: WallMotion::default(),
            multi_contact,
            active: true,
        };
        w.add_wall(plane("floor", DVec3::ZERO, DVec3::Z, 0, MultiContact::Sum))
            .unwrap();
        w.add_wall(plane(
            "left",
            DVec3::ZERO,
            DVec3::X,
            1,
            MultiContact::Average,
        ))
        .unwrap();
        let right = DVec3::new(lx, 0.0, 0.0);
        w.add_wall(plane("right", right, -DVec3::X, 1, MultiContact::Sum))
            .unwrap();
        let mut k = 0u32;
        for z in 0..nz {
            for y in 0..ny {
                for x in 0..nx {
                    k += 1;
                    let k = k as f64;
                    let q = DQuat::from_euler(glam::EulerRot::ZXZ, k * 0.7, k * 1.3, k * 0.4);
                    let p =
                        DVec3::new(x as f64 + 0.5, y as f64 + 0.5, z as f64 + 0.45) * LATTICE_PITCH;
                    let side = if x < nx / 2 { -1.0 } else { 1.0 };
                    let init = BodyInit {
                        velocity: DVec3::new(0.1 * side, 0.0, -0.05),
                        angular_velocity: DVec3::new(0.0, 20.0 * side, 0.0),
                        ..BodyInit::at_rest(t[(x + y) % 2], p, q)
                    };
                    w.add_body(&init).unwrap();
                }
            }
        }
        w
    }

    /// The bed steps the same bits, with the same wall loads, whether the
    /// touches' law runs as lanes or one touch at a time through the
    /// contact model; many touches to a chunk (batches flushed part-way
    /// through a body), sliding and sticking, mixed models.
    #[test]
    fn wall_touches_give_the_same_bits_as_lanes_and_one_by_one() {
        let run = |scalar: bool| {
            let mut w = bed();
            SCALAR_ONLY.store(scalar, Ordering::SeqCst);
            let mut most = 0;
            for _ in 0..150 {
                w.run(20).unwrap();
                most = most.max(w.stats.wall_contacts);
            }
            SCALAR_ONLY.store(false, Ordering::SeqCst);
            let loads: Vec<u64> = w
                .walls
                .loads()
                .iter()
                .flat_map(|l| [l.force, l.torque])
                .flat_map(|v| v.to_array().map(f64::to_bits))
                .collect();
            (state_bits(&w), loads, most, w.rebuilds)
        };
        let (lanes, lanes_loads, most, rebuilds) = run(false);
        let (scalar, scalar_loads, _, _) = run(true);
        assert!(most > 3 * WALL_BATCH as u64, "only {most} wall contacts");
        assert!(rebuilds > 3, "only {rebuilds} rebuilds");
        assert!(lanes_loads.iter().any(|&x| x != 0), "no wall load");
        assert!(lanes == scalar, "the lanes changed the bits");
        assert!(
            lanes_loads == scalar_loads,
            "the lanes changed the wall loads"
        );
    }
}
