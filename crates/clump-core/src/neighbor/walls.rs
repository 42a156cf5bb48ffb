//! The wall Verlet list: the spheres that have a wall to test, each with
//! the walls to test and its sphere–wall contact slots.
//!
//! Built with the pair list, at the spheres' positions at the build: a sphere
//! gets an entry when a wall (< 64) lies within its radius plus the skin, when
//! a wall moves (it may come near any sphere before the next build), when the
//! world has more than 64 walls (those beyond 64 are tested for every
//! sphere), or when it carries a contact history. Until the next build a
//! sphere moves less than half the skin, so skipping the spheres without an
//! entry removes only tests that would find no contact.
//!
//! Only the entries hold contact slots (a key and a history per slot), in
//! ascending sphere order, so the gather streams through them instead of
//! visiting the slots of every sphere: in a settled bed about one sphere in
//! ten is near a wall.

use crate::contact::mdr::SlipProfile;
use crate::contact::ContactHistory;
use crate::wall::{Wall, WallTouch, MAX_TOUCHES_PER_WALL};
use rayon::prelude::*;

/// Per-sphere wall-contact slots (history carried while a contact persists).
pub const WALL_SLOTS: usize = 4;

/// Marks a sphere without a carried entry in [`WallList::build`]'s `carry`.
pub const NO_ENTRY: u32 = u32::MAX;

/// Spheres whose near walls the build finds in one parallel pass.
const NEAR_BLOCK: usize = 8192;

/// Entries of the wall Verlet list (structure of arrays, ascending sphere).
#[derive(Debug, Default, Clone)]
pub struct WallList {
    /// Sphere (storage index) of each entry.
    pub sphere: Vec<u32>,
    /// Walls (< 64) to test for the entry's sphere: bit `w` for wall `w`.
    pub mask: Vec<u64>,
    /// Slot keys of the entry's wall contacts (0 = empty; see
    /// `step::force`), slots in use first.
    pub key: Vec<[u32; WALL_SLOTS]>,
    /// Contact histories of the slots (world frame).
    pub hist: Vec<[ContactHistory; WALL_SLOTS]>,
    /// MDR profiles of the slots (`tangential = "mdr"`,
    /// [`crate::contact::mdr`]): one per slot of `hist` while some law
    /// keeps them ([`WallList::keep_slip`]), else empty.
    pub slip: Vec<[SlipProfile; WALL_SLOTS]>,
    /// First entry of each chunk of `chunk` bodies, `len = chunks + 1`.
    pub chunk_start: Vec<u32>,
    /// Per sphere of one block of the build: the walls (< 64) near it
    /// (build scratch).
    near: Vec<u64>,
}

impl WallList {
    /// Removes every entry (the slots with them).
    pub fn clear(&mut self) {
        self.sphere.clear();
        self.mask.clear();
        self.key.clear();
        self.hist.clear();
        self.slip.clear();
        self.chunk_start.clear();
    }

    /// Gives every entry's slots an MDR profile (empty) if the list has
    /// none.
    pub fn keep_slip(&mut self) {
        if self.slip.len() != self.hist.len() {
            self.slip.clear();
            self.slip
                .resize(self.hist.len(), [SlipProfile::default(); WALL_SLOTS]);
        }
    }

    /// The entry of each sphere (storage index) whose slots hold a contact,
    /// else [`NO_ENTRY`]: `out` gets one value per sphere of `n`.
    pub fn live_entries(&self, n: usize, out: &mut Vec<u32>) {
        out.clear();
        out.resize(n, NO_ENTRY);
        for (e, (&s, key)) in self.sphere.iter().zip(&self.key).enumerate() {
            if key[0] != 0 && (s as usize) < n {
                out[s as usize] = e as u32;
            }
        }
    }

    /// Appends to `out`, for each sphere of `spheres` (storage indices of
    /// this list's build), its entry when its slots hold a contact, else
    /// [`NO_ENTRY`]: [`WallList::live_entries`] for one body's spheres,
    /// without a table over all spheres.
    pub fn append_live_entries(&self, spheres: std::ops::Range<usize>, out: &mut Vec<u32>) {
        let mut e = self
            .sphere
            .partition_point(|&s| (s as usize) < spheres.start);
        for s in spheres {
            if self.sphere.get(e).is_some_and(|&x| x as usize == s) {
                out.push(if self.key[e][0] != 0 {
                    e as u32
                } else {
                    NO_ENTRY
                });
                e += 1;
            } else {
                out.push(NO_ENTRY);
            }
        }
    }

    /// The MDR profiles of every sphere's slots (storage order, `n`
    /// spheres; the checkpoint form of [`Self::slip`]): with `keep` (some
    /// law keeps profiles) one per sphere, empty profiles where the list
    /// holds none (a list without entries has no profiles yet, and a part
    /// joined with others must still give one per sphere); else empty.
    pub fn slip_per_sphere(&self, n: usize, keep: bool) -> Vec<[SlipProfile; WALL_SLOTS]> {
        if !keep {
            return Vec::new();
        }
        let mut out = vec![[SlipProfile::default(); WALL_SLOTS]; n];
        if self.slip.len() == self.sphere.len() {
            for (e, &s) in self.sphere.iter().enumerate() {
                out[s as usize] = self.slip[e];
            }
        }
        out
    }

    /// Restores [`Self::slip`] from its per-sphere form (after
    /// [`Self::from_per_sphere`] with the same slots); an empty `slip`
    /// leaves the list without profiles.
    pub fn set_slip_per_sphere(&mut self, slip: &[[SlipProfile; WALL_SLOTS]]) {
        self.slip.clear();
        if slip.is_empty() {
            return;
        }
        for &s in &self.sphere {
            self.slip
                .push(slip.get(s as usize).copied().unwrap_or_default());
        }
    }

    /// The slots of every sphere (storage order, `n` spheres): empty for a
    /// sphere without an entry (the checkpoint form).
    pub fn per_sphere(
        &self,
        n: usize,
    ) -> (Vec<[u32; WALL_SLOTS]>, Vec<[ContactHistory; WALL_SLOTS]>) {
        let mut key = vec![[0; WALL_SLOTS]; n];
        let mut hist = vec![[ContactHistory::default(); WALL_SLOTS]; n];
        for (e, &s) in self.sphere.iter().enumerate() {
            key[s as usize] = self.key[e];
            hist[s as usize] = self.hist[e];
        }
        (key, hist)
    }

    /// A list holding the given per-sphere slots (the checkpoint form),
    /// one entry per sphere with a contact; no walls to test until the next
    /// [`build`](Self::build).
    pub fn from_per_sphere(
        key: &[[u32; WALL_SLOTS]],
        hist: &[[ContactHistory; WALL_SLOTS]],
    ) -> Self {
        let mut l = WallList::default();
        for (s, (k, h)) in key.iter().zip(hist).enumerate() {
            if k[0] != 0 {
                l.sphere.push(s as u32);
                l.mask.push(0);
                l.key.push(*k);
                l.hist.push(*h);
            }
        }
        l
    }

    /// Builds the list for spheres at `state`'s centres (m, world) with
    /// `radius` (m) and skin `skin` (m); `moving` has the bits of the walls
    /// (< 64) that move. Sphere `s` continues the slots of entry `carry[s]` of
    /// `old` (or starts empty: [`NO_ENTRY`]). `body_first` gives each body's
    /// first sphere (`len = bodies + 1`); the chunk starts are for chunks of
    /// `chunk` bodies.
    #[allow(clippy::too_many_arguments)]
    pub fn build(
        &mut self,
        walls: &[Wall],
        meshes: &[crate::wall::TriMesh],
        state: &[crate::sphere::SphereState],
        radius: &[f64],
        skin: f64,
        moving: u64,
        carry: &[u32],
        old: &WallList,
        body_first: &[u32],
        chunk: usize,
    ) {
        let n = state.len();
        self.clear();
        let all = walls.len() > 64;
        let slip = !old.slip.is_empty() && old.slip.len() == old.hist.len();
        // the near walls of a block of spheres at a time (in parallel), then
        // the block's entries in sphere order: the scratch is one block,
        // not 8 bytes for every sphere
        for b0 in (0..n).step_by(NEAR_BLOCK) {
            let b1 = (b0 + NEAR_BLOCK).min(n);
            self.near.clear();
            self.near.resize(b1 - b0, 0);
            self.near
                .par_iter_mut()
                .enumerate()
                .with_min_len(1024)
                .for_each(|(k, near)| {
                    let s = b0 + k;
                    let mut buf = [WallTouch::default(); MAX_TOUCHES_PER_WALL];
                    let mut m = 0u64;
                    for (wi, wall) in walls.iter().enumerate().take(64) {
                        if wall
                            .shape
                            .contacts(meshes, state[s].position, radius[s], skin, &mut buf)
                            > 0
                        {
                            m |= 1 << wi;
                        }
                    }
                    *near = m;
                });
            for s in b0..b1 {
                let mask = self.near[s - b0] | moving;
                let from = carry.get(s).copied().unwrap_or(NO_ENTRY);
                if mask == 0 && !all && from == NO_ENTRY {
                    continue;
                }
                self.sphere.push(s as u32);
                self.mask.push(mask);
                match old.key.get(from as usize) {
                    Some(k) => {
                        self.key.push(*k);
                        self.hist.push(old.hist[from as usize]);
                        if slip {
                            self.slip.push(old.slip[from as usize]);
                        }
                    }
                    None => {
                        self.key.push([0; WALL_SLOTS]);
                        self.hist.push([ContactHistory::default(); WALL_SLOTS]);
                        if slip {
                            self.slip.push([SlipProfile::default(); WALL_SLOTS]);
                        }
                    }
                }
            }
        }
        let nb = body_first.len().saturating_sub(1);
        let mut e = 0usize;
        for c in 0..nb.div_ceil(chunk) {
            let s0 = body_first[c * chunk];
            while e < self.sphere.len() && self.sphere[e] < s0 {
                e += 1;
            }
            self.chunk_start.push(e as u32);
        }
        self.chunk_start.push(self.sphere.len() as u32);
    }
}
