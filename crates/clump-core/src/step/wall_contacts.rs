//! The sphere–wall contacts of one body, in the gather: for each of its
//! spheres in the wall list, the walls near it (the list's mask), their
//! touches (analytic shapes and meshes, `crate::wall`), each touch's history
//! slot carried from the last step (by face for analytic walls, by contact
//! normal for meshes, so a contact sliding across triangles keeps its
//! spring), the contact law (`crate::contact`), and the sums: the force and
//! torque on the body, the load on the wall, the statistics, the contact
//! records when the step keeps them.

use crate::body::Bodies;
use crate::contact::geometry::contact_point;
use crate::contact::record::WallRecord;
use crate::contact::{ContactHistory, ContactInput, ContactTable};
use crate::multi_contact::{MultiContact, PartnerCounts};
use crate::neighbor::walls::{WallList, WALL_SLOTS};
use crate::neighbor::PairBody;
use crate::par::shared::{at, SharedMut};
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
    /// Per chunk and wall: the load of the chunk's contacts.
    loads: SharedMut<WallLoad>,
    walls_average: bool,
    recording: bool,
    records: SharedMut<Vec<WallRecord>>,
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
            loads,
            walls_average: walls
                .iter()
                .any(|x| x.multi_contact == MultiContact::Average),
            recording,
            records: SharedMut::new(records),
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

    /// The wall contacts of body `bi` (centre of mass `com`), whose
    /// wall-list entries are `entries`, in chunk `c`: adds their force and
    /// torque about `com` to `f` and `m`, their loads to the chunk's wall
    /// loads and their statistics to `stat`, and carries their history
    /// slots.
    ///
    /// # Safety
    /// Body `bi` and the entries are chunk `c`'s, handled by one thread.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    pub(super) unsafe fn body(
        &self,
        bi: usize,
        com: DVec3,
        entries: Range<usize>,
        c: usize,
        wcounts: &mut PartnerCounts,
        buf: &mut [WallTouch; MAX_TOUCHES_PER_WALL],
        mut stat: Option<&mut ContactStats>,
        f: &mut DVec3,
        m: &mut DVec3,
    ) {
        let (e0, e) = (entries.start, entries.end);
        if self.walls_average {
            wcounts.clear();
            let mut buf = [WallTouch::default(); MAX_TOUCHES_PER_WALL];
            for q in e0..e {
                let s = self.entry_sphere[q] as usize;
                for wi in self.candidates(q) {
                    let k = self.walls[wi].shape.contacts(
                        self.meshes,
                        self.sp.position(s),
                        self.sp.state[s].radius,
                        0.0,
                        &mut buf,
                    );
                    for _ in 0..k {
                        wcounts.add(wi as u64);
                    }
                }
            }
        }
        let ctx = WallCtx {
            sp: self.sp,
            b: self.b,
            lagged: self.lagged,
            table: self.table,
            walls: self.walls,
            dt: self.dt,
            bi,
            com,
        };
        for q in e0..e {
            // SAFETY: entry q is of body bi, handled by this
            // chunk only.
            let (s, key, hist) = unsafe {
                (
                    at(self.entry_sphere, q) as usize,
                    self.keys.get(q),
                    self.hists.get(q),
                )
            };
            let mut cand = self.candidates(q).peekable();
            if cand.peek().is_none() {
                // no wall to test: only clear what a contact left
                if key[0] != 0 {
                    *key = [0; WALL_SLOTS];
                    *hist = [ContactHistory::default(); WALL_SLOTS];
                }
                continue;
            }
            let mut new_key = [0u32; WALL_SLOTS];
            let mut new_hist = [ContactHistory::default(); WALL_SLOTS];
            let mut n_new = 0;
            let mut used = [false; WALL_SLOTS];
            for wi in cand {
                let wall = &self.walls[wi];
                let r = self.sp.state[s].radius;
                // a JKR contact lives on while apart by less than its reach
                let reach = if self.table.any_reach() && key.iter().any(|&x| slot_wall(x) == wi) {
                    self.table.get(self.sp.material[s], wall.material).reach(r)
                } else {
                    0.0
                };
                let k = wall
                    .shape
                    .contacts(self.meshes, self.sp.position(s), r, reach, buf);
                let is_mesh = matches!(wall.shape, WallShape::Mesh { .. });
                for touch in &buf[..k] {
                    let (patch, old) = if is_mesh {
                        let patch = oct_encode(touch.normal);
                        (patch, match_mesh_slot(key, &used, wi, touch.normal))
                    } else {
                        let patch = touch.face as u16;
                        let slot_key = slot_key(wi, patch);
                        (patch, key.iter().position(|&x| x == slot_key))
                    };
                    let slot_key = slot_key(wi, patch);
                    if touch.overlap <= 0.0 && old.is_none() {
                        // a near miss within the reach, not a live contact
                        continue;
                    }
                    let mut h = match old {
                        Some(o) => {
                            used[o] = true;
                            hist[o]
                        }
                        None => ContactHistory::default(),
                    };
                    let scale = if wall.multi_contact == MultiContact::Average {
                        1.0 / wcounts.get(wi as u64) as f64
                    } else {
                        1.0
                    };
                    let (fw, mw, tw, energy, fn_w) = ctx.evaluate(s, wi, touch, &mut h);
                    if self.recording {
                        // SAFETY: chunk c's list is written by chunk c only.
                        unsafe { self.records.get(c) }.push(WallRecord {
                            sphere: s as u32,
                            wall: wi as u32,
                            patch,
                            normal: touch.normal,
                            overlap: touch.overlap,
                            force: fw * scale,
                            normal_force: fn_w * scale,
                            spring: h.tangential,
                        });
                    }
                    *f += fw * scale;
                    *m += mw * scale;
                    // a ghost body (partitioned world) adds neither: its
                    // owner does
                    if let Some(stat) = stat.as_deref_mut() {
                        // SAFETY: row c of the chunk loads belongs to this chunk only.
                        let load = unsafe { self.loads.get(c * self.nw + wi) };
                        load.force -= fw * scale;
                        load.torque -= tw * scale;
                        stat.wall_contacts += 1;
                        stat.elastic_energy += energy * scale;
                        let ratio = touch.overlap / self.sp.state[s].radius;
                        if ratio > stat.max_overlap_ratio {
                            stat.max_overlap_ratio = ratio;
                            stat.max_overlap_bodies = [self.b.id[bi], 0];
                            stat.max_overlap_wall = wi as u32 + 1;
                        }
                    }
                    if n_new < WALL_SLOTS {
                        new_key[n_new] = slot_key;
                        new_hist[n_new] = h;
                        n_new += 1;
                    }
                }
            }
            // most spheres touch no wall: skip the write then
            if n_new > 0 || key[0] != 0 {
                *key = new_key;
                *hist = new_hist;
            }
        }
    }
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

struct WallCtx<'a> {
    sp: &'a Spheres,
    b: &'a Bodies,
    lagged: Option<SharedMut<PairBody>>,
    table: &'a ContactTable,
    walls: &'a [Wall],
    dt: f64,
    bi: usize,
    com: DVec3,
}

impl WallCtx<'_> {
    /// One sphere–wall contact: returns (force on the body, torque on the body
    /// about its centre of mass, torque on the wall about its motion centre
    /// *from the body's side* i.e. of the force on the body, elastic energy,
    /// signed normal force on the body).
    #[inline]
    fn evaluate(
        &self,
        s: usize,
        wi: usize,
        touch: &WallTouch,
        h: &mut ContactHistory,
    ) -> (DVec3, DVec3, DVec3, f64, f64) {
        let wall = &self.walls[wi];
        let r = self.sp.state[s].radius;
        let n = touch.normal;
        let xc = contact_point(self.sp.position(s), n, r, touch.overlap);
        let bi = self.bi;
        let (v, wb) = match &self.lagged {
            // SAFETY: a body of the pair list, which is built for these
            // bodies whenever they lag
            Some(pb) => unsafe {
                let pb = pb.ptr(bi);
                ((*pb).velocity, (*pb).angular_velocity)
            },
            None => (self.b.velocity[bi], self.b.angular_velocity[bi]),
        };
        let v_body = point_velocity(self.com, v, wb, xc);
        let mut v_wall = wall.surface_velocity_at(xc);
        let sv = wall.motion.surface_velocity;
        v_wall -= n * n.dot(sv);
        let input = ContactInput {
            normal: n,
            overlap: touch.overlap,
            rel_velocity: v_body - v_wall,
            rel_omega: wb - wall.motion.angular_velocity,
            radius: r,
            radius_sum: f64::INFINITY,
            mass: self.b.mass[bi],
            dt: self.dt,
        };
        let model = self.table.get(self.sp.material[s], wall.material);
        let out = model.evaluate(&input, h);
        let m_body = (xc - self.com).cross(out.force) + out.torque;
        let m_wall_from_body = (xc - wall.motion.center).cross(out.force) + out.torque;
        (
            out.force,
            m_body,
            m_wall_from_body,
            out.elastic_energy,
            out.normal_force,
        )
    }
}
