//! Reading a checkpoint in pieces ([`crate::state_pieces`]) one piece at a
//! time, keeping a rank's share of the world: the bodies whose wrapped
//! build position lies in its region or within the halo of it (its owned
//! bodies and its ghosts), with their build poses, wall slots and the
//! histories of their pairs; or every body, for one process.
//!
//! A reader on ranks first looks at every piece's *outline* (a sample of
//! its bodies' build positions with their sphere counts, and the box of
//! those positions): the regions are balanced on the samples, alike on
//! every rank, and a rank then reads only the pieces whose box comes within
//! the halo of its region. What a reader holds at any time is one decoded
//! piece and the share kept so far; [`ShareReader::finish`] sorts the share
//! into the whole world's storage order (a second copy of the share's body
//! arrays, for the sort).

use crate::body::Bodies;
use crate::boundary::Domain;
use crate::partition::Regions;
use crate::sphere::SPHERE_ID_BITS;
use crate::state::WorldState;
use crate::state_pieces::RankPiece;
use crate::world::World;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Largest number of sample points an outline holds.
const SAMPLE: usize = 256;

/// Where a piece's bodies are: a sample for the balance and their box.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PieceOutline {
    /// The first body of each run of bodies in storage order (a spatial
    /// order), at its wrapped build position (world frame, m), and the
    /// run's sphere count.
    pub sample: Vec<(DVec3, u32)>,
    /// The box of the bodies' wrapped build positions (world frame, m);
    /// `lo > hi` for a piece without bodies.
    pub lo: DVec3,
    /// See `lo`.
    pub hi: DVec3,
}

/// Which bodies a rank keeps.
struct Filter {
    regions: Regions,
    domain: Domain,
    halo: f64,
    me: usize,
}

impl Filter {
    /// True for a body at the wrapped build position `x` that rank `me`
    /// owns or holds as a ghost (as `Roles::of` decides).
    fn keeps(&self, x: DVec3, near: &mut Vec<usize>) -> bool {
        if self.regions.owner(x) == self.me {
            return true;
        }
        self.regions.near(x, self.halo, near);
        near.contains(&self.me)
    }
}

/// A rank's share of a checkpoint in pieces, read one piece at a time.
pub struct ShareReader {
    /// `None`: every body (one process).
    filter: Option<Filter>,
    /// The templates' first sphere (each body's sphere count).
    first: Vec<u32>,
    global: WorldState,
    order: Vec<(u64, u64)>,
    bodies: Bodies,
    reference_pose: Vec<(DVec3, glam::DQuat)>,
    /// Per kept body, its first sphere in the wall-slot arrays.
    sphere_first: Vec<usize>,
    state: WorldState,
    slip: Option<bool>,
}

impl World {
    /// The outline of a piece of this world's checkpoint (its templates
    /// give the sphere counts).
    pub fn piece_outline(&self, piece: &RankPiece) -> Result<PieceOutline, String> {
        let b = &piece.state.bodies;
        let first = &self.templates.first;
        let d = &self.config.domain;
        let mut out = PieceOutline {
            sample: Vec::new(),
            lo: DVec3::INFINITY,
            hi: DVec3::NEG_INFINITY,
        };
        if piece.state.reference_pose.len() != b.len() {
            return Err(format!(
                "{} build poses for {} bodies",
                piece.state.reference_pose.len(),
                b.len()
            ));
        }
        let stride = b.len().div_ceil(SAMPLE).max(1);
        for (k, &(x, _)) in piece.state.reference_pose.iter().enumerate() {
            let t = b.template[k] as usize;
            if t + 1 >= first.len() {
                return Err(format!("template {t}, which the scenario lacks"));
            }
            let x = d.wrap(x);
            out.lo = out.lo.min(x);
            out.hi = out.hi.max(x);
            let n = first[t + 1] - first[t];
            if k % stride == 0 {
                out.sample.push((x, n));
            } else if let Some(last) = out.sample.last_mut() {
                last.1 += n;
            }
        }
        Ok(out)
    }

    /// A reader of this rank's share of a checkpoint in pieces whose global
    /// part this world holds already ([`World::restore_state`] of the
    /// manifest's world): on a partitioned world, the regions are balanced
    /// on the pieces' `outlines` (every rank gives the same, so every rank
    /// cuts alike) and kept for [`World::restore_rank_share`]; without a
    /// partition, the reader keeps every body.
    pub fn share_reader(&mut self, global: &WorldState, outlines: &[PieceOutline]) -> ShareReader {
        let halo = self.share_halo();
        let domain = self.config.domain;
        let filter = self.part.as_mut().map(|p| {
            let (at, cost): (Vec<DVec3>, Vec<u32>) = outlines
                .iter()
                .flat_map(|o| o.sample.iter().copied())
                .unzip();
            p.regions = Regions::balance(&domain, &at, &cost, p.comm.size());
            Filter {
                regions: p.regions.clone(),
                domain,
                halo,
                me: p.comm.rank(),
            }
        });
        ShareReader {
            filter,
            first: self.templates.first.clone(),
            global: global.clone().into_global(),
            order: Vec::new(),
            bodies: Bodies::default(),
            reference_pose: Vec::new(),
            sphere_first: vec![0],
            state: global.clone().into_global(),
            slip: None,
        }
    }
}

impl ShareReader {
    /// True when this rank needs bodies of the piece with `outline`: its
    /// box comes within the halo of the rank's region (always without a
    /// partition).
    pub fn wants(&self, outline: &PieceOutline) -> bool {
        let Some(f) = &self.filter else {
            return true;
        };
        if outline.lo.cmpgt(outline.hi).any() {
            return false;
        }
        f.regions
            .box_near_region(outline.lo, outline.hi, f.halo, f.me)
    }

    /// Keeps this rank's bodies of piece `r` (checked first: its step, its
    /// arrays' lengths, its templates), with their build poses, wall slots
    /// and the histories of the pairs with a kept body.
    pub fn add(&mut self, r: usize, piece: RankPiece) -> Result<(), String> {
        let s = &piece.state;
        if s.step != self.global.step {
            return Err(format!(
                "piece {r} is of step {}, the checkpoint of step {}",
                s.step, self.global.step
            ));
        }
        let nb = s.bodies.len();
        let lens = [
            piece.order.len(),
            s.reference_pose.len(),
            s.bodies.template.len(),
        ];
        if lens.iter().any(|&l| l != nb) {
            return Err(format!(
                "piece {r}: body arrays of inconsistent lengths ({nb} ids, {lens:?})"
            ));
        }
        let mut f = vec![0usize];
        for &t in &s.bodies.template {
            let t = t as usize;
            if t + 1 >= self.first.len() {
                return Err(format!(
                    "piece {r} refers to template {t}, which the scenario lacks"
                ));
            }
            f.push(f.last().unwrap() + (self.first[t + 1] - self.first[t]) as usize);
        }
        let ns = *f.last().unwrap();
        let slip = !s.wall_slip.is_empty();
        if nb > 0 && *self.slip.get_or_insert(slip) != slip {
            return Err(format!(
                "piece {r}: wall slip profiles where another piece has none, or the reverse"
            ));
        }
        if s.wall_key.len() != ns || s.wall_hist.len() != ns || (slip && s.wall_slip.len() != ns) {
            return Err(format!(
                "piece {r}: {} wall slots for {ns} spheres",
                s.wall_key.len()
            ));
        }
        let mut near = Vec::new();
        let keep: Vec<u32> = (0..nb as u32)
            .filter(|&k| {
                self.filter.as_ref().map_or(true, |fl| {
                    fl.keeps(fl.domain.wrap(s.reference_pose[k as usize].0), &mut near)
                })
            })
            .collect();
        let mut kept = Bodies::default();
        s.bodies.permute_into(&keep, &mut kept);
        self.bodies.append(&kept);
        let ids: rustc_hash::FxHashSet<u64> = kept.id.iter().copied().collect();
        let out = &mut self.state;
        for &k in &keep {
            let k = k as usize;
            self.order.push(piece.order[k]);
            self.reference_pose.push(s.reference_pose[k]);
            let sp = f[k]..f[k + 1];
            out.wall_key.extend_from_slice(&s.wall_key[sp.clone()]);
            out.wall_hist.extend_from_slice(&s.wall_hist[sp.clone()]);
            if slip {
                out.wall_slip.extend_from_slice(&s.wall_slip[sp]);
            }
            let last = *self.sphere_first.last().unwrap();
            self.sphere_first.push(last + f[k + 1] - f[k]);
        }
        let all = self.filter.is_none();
        let mine = |&(a, b): &(u64, u64)| {
            all || ids.contains(&(a >> SPHERE_ID_BITS)) || ids.contains(&(b >> SPHERE_ID_BITS))
        };
        let RankPiece { state, .. } = piece;
        let hist = state.pair_history.into_iter().filter(|e| mine(&e.0));
        out.pair_history.extend(hist);
        let slip = state.pair_slip.into_iter().filter(|e| mine(&e.0));
        out.pair_slip.extend(slip);
        Ok(())
    }

    /// The share in the whole world's storage order, with the global part
    /// of the manifest, and each body's place in that order. Checks that no
    /// body came twice.
    pub fn finish(self) -> Result<(WorldState, Vec<(u64, u64)>), String> {
        let mut idx: Vec<u32> = (0..self.order.len() as u32).collect();
        idx.sort_unstable_by_key(|&k| self.order[k as usize]);
        if let Some(w) = idx
            .windows(2)
            .find(|w| self.order[w[0] as usize] == self.order[w[1] as usize])
        {
            return Err(format!(
                "two pieces hold the same body (id {} and {}, place {:?})",
                self.bodies.id[w[0] as usize],
                self.bodies.id[w[1] as usize],
                self.order[w[0] as usize]
            ));
        }
        let mut out = self.global;
        self.bodies.permute_into(&idx, &mut out.bodies);
        drop(self.bodies);
        let s = self.state;
        let slip = !s.wall_slip.is_empty();
        for &k in &idx {
            let k = k as usize;
            out.reference_pose.push(self.reference_pose[k]);
            let sp = self.sphere_first[k]..self.sphere_first[k + 1];
            out.wall_key.extend_from_slice(&s.wall_key[sp.clone()]);
            out.wall_hist.extend_from_slice(&s.wall_hist[sp.clone()]);
            if slip {
                out.wall_slip.extend_from_slice(&s.wall_slip[sp]);
            }
        }
        out.pair_history = s.pair_history;
        out.pair_history.sort_by_key(|e| e.0);
        out.pair_history.dedup_by_key(|e| e.0);
        out.pair_slip = s.pair_slip;
        out.pair_slip.sort_by_key(|e| e.0);
        out.pair_slip.dedup_by_key(|e| e.0);
        let order = idx.iter().map(|&k| self.order[k as usize]).collect();
        Ok((out, order))
    }
}

impl World {
    /// Takes the global part of a checkpoint in pieces (its manifest's
    /// world, which holds no bodies), before its pieces are read: the
    /// settings, counters and skin that [`World::share_reader`] needs. No
    /// lists are built.
    pub fn restore_global_part(&mut self, s: WorldState) -> Result<(), String> {
        if !s.bodies.is_empty() {
            return Err("the global part of a checkpoint in pieces holds no bodies".into());
        }
        self.set_state(s)
    }

    /// Takes this rank's share of a checkpoint in pieces
    /// ([`ShareReader::finish`] of the reader this world made) as its part
    /// of the world split over ranks: the lists are built on the whole
    /// world's grid at the build poses, as a whole restart and the split of
    /// it would build them, so the run continues bit for bit. Every rank
    /// calls it (the grid's extent is reduced over the ranks).
    pub fn restore_rank_share(
        &mut self,
        s: WorldState,
        order: Vec<(u64, u64)>,
    ) -> Result<(), String> {
        if self.part.is_none() {
            return Err("a rank's share needs a partitioned world".into());
        }
        self.set_state(s)?;
        self.keep_rank_share(order).map_err(|e| e.to_string())?;
        self.rebuilds = self.rebuilds.saturating_sub(1);
        self.phase.forces_evaluated();
        Ok(())
    }
}
