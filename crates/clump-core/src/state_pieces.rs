//! A checkpoint of a world split over ranks without gathering it: each rank
//! saves the state of the bodies it owns (with their build poses, wall
//! slots and the histories of the pairs with an owned sphere) as one
//! *piece*, and the pieces of every rank merge into the whole world's
//! state, in one process's storage order, at any rank count (or in one
//! process).
//!
//! The bodies, build poses, wall slots, pair histories, counters and skin
//! of the merged state are one process's, bit for bit. Its statistics and
//! wall loads are those of the rank's last step: summed per rank, then over
//! the ranks in rank order (the step before such a checkpoint is a rank's
//! step, not a whole one); nothing that follows reads them before the next
//! step recomputes them (the thermo row of that boundary is written before
//! its checkpoint, and a resumed run does not write it again).

use crate::body::Bodies;
use crate::state::WorldState;
use crate::step::StepError;
use crate::world::World;
use serde::{Deserialize, Serialize};

/// One rank's piece of a world's state.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RankPiece {
    /// Per body, its place in the whole world's storage order (a key that
    /// sorts as that order over every rank's pieces of one step).
    pub order: Vec<(u64, u64)>,
    /// The state: the owned bodies and what travels with them, and the
    /// global part (the same on every rank).
    pub state: WorldState,
}

impl WorldState {
    /// The global part of this state (settings, counters, walls, wall
    /// loads, statistics, skin) with no bodies: a split checkpoint's
    /// manifest.
    pub fn into_global(mut self) -> WorldState {
        self.bodies = Bodies::default();
        self.reference_pose = Vec::new();
        self.pair_history = Vec::new();
        self.wall_key = Vec::new();
        self.wall_hist = Vec::new();
        self.pair_slip = Vec::new();
        self.wall_slip = Vec::new();
        self
    }
}

impl World {
    /// This rank's piece of the world's state (the world split over ranks,
    /// at a step boundary): its owned bodies and the global part.
    pub fn save_rank_piece(&mut self) -> Result<RankPiece, StepError> {
        if !self.is_split() {
            return Err(StepError::Neighbor(
                "partition: a rank piece needs a world split over ranks".into(),
            ));
        }
        // as `save_state`: the forces of the state saved (after an insertion)
        self.prepare_split()?;
        let mut o = self.owned_part();
        o.pair_history.sort_by_key(|e| e.0);
        o.pair_slip.sort_by_key(|e| e.0);
        Ok(RankPiece {
            order: o.order,
            state: WorldState {
                bodies: o.bodies,
                reference_pose: o.reference_pose,
                pair_history: o.pair_history,
                wall_key: o.wall_key,
                wall_hist: o.wall_hist,
                pair_slip: o.pair_slip,
                wall_slip: o.wall_slip,
                ..self.global_state()
            },
        })
    }

    /// The whole world's state from every rank's piece of one step, with
    /// the global part of `global` (a split checkpoint's manifest): bodies
    /// in the whole world's storage order, pair histories sorted by key
    /// (a pair whose spheres two ranks own is in both pieces, alike), each
    /// sphere's wall slots. Checks that the pieces are of one step and hold
    /// every body once; the templates of this world give each body's
    /// sphere count.
    pub fn merge_pieces(
        &self,
        global: &WorldState,
        pieces: Vec<RankPiece>,
    ) -> Result<WorldState, String> {
        let first = &self.templates.first;
        let slip = pieces.iter().any(|p| !p.state.wall_slip.is_empty());
        let mut order: Vec<((u64, u64), usize, usize)> = Vec::new();
        let mut sphere_first: Vec<Vec<usize>> = Vec::with_capacity(pieces.len());
        for (r, p) in pieces.iter().enumerate() {
            let s = &p.state;
            if s.step != global.step {
                return Err(format!(
                    "piece {r} is of step {}, the checkpoint of step {}",
                    s.step, global.step
                ));
            }
            let nb = s.bodies.len();
            let lens = [
                p.order.len(),
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
                if t + 1 >= first.len() {
                    return Err(format!(
                        "piece {r} refers to template {t}, which the scenario lacks"
                    ));
                }
                f.push(f.last().unwrap() + (first[t + 1] - first[t]) as usize);
            }
            let ns = *f.last().unwrap();
            let slip_ok = !slip || s.wall_slip.len() == ns;
            if s.wall_key.len() != ns || s.wall_hist.len() != ns || !slip_ok {
                return Err(format!(
                    "piece {r}: {} wall slots for {ns} spheres",
                    s.wall_key.len()
                ));
            }
            sphere_first.push(f);
            order.extend(p.order.iter().enumerate().map(|(k, &g)| (g, r, k)));
        }
        order.sort_unstable();
        if let Some(w) = order.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(format!(
                "pieces {} and {} hold the same body (place {:?})",
                w[0].1, w[1].1, w[0].0
            ));
        }
        let mut all = Bodies::default();
        let mut base = Vec::with_capacity(pieces.len());
        for p in &pieces {
            base.push(all.len());
            all.append(&p.state.bodies);
        }
        let perm: Vec<u32> = order
            .iter()
            .map(|&(_, r, k)| (base[r] + k) as u32)
            .collect();
        let mut out = global.clone().into_global();
        all.permute_into(&perm, &mut out.bodies);
        for &(_, r, k) in &order {
            let s = &pieces[r].state;
            out.reference_pose.push(s.reference_pose[k]);
            let sp = sphere_first[r][k]..sphere_first[r][k + 1];
            out.wall_key.extend_from_slice(&s.wall_key[sp.clone()]);
            out.wall_hist.extend_from_slice(&s.wall_hist[sp.clone()]);
            if slip {
                out.wall_slip.extend_from_slice(&s.wall_slip[sp]);
            }
        }
        for p in pieces {
            out.pair_history.extend(p.state.pair_history);
            out.pair_slip.extend(p.state.pair_slip);
        }
        out.pair_history.sort_by_key(|e| e.0);
        out.pair_history.dedup_by_key(|e| e.0);
        out.pair_slip.sort_by_key(|e| e.0);
        out.pair_slip.dedup_by_key(|e| e.0);
        Ok(out)
    }
}
