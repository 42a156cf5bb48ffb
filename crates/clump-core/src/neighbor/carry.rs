//! Contact histories carried across a neighbour rebuild that re-sorts the
//! bodies, by storage index instead of a hash map.
//!
//! Before the re-sort, the pairs that hold state are copied out of the old
//! list as compact rows in the old storage order ([`HistoryCarry::save`]).
//! After it, each new sphere learns its old storage index from its body's
//! old index ([`old_body_index`]) and its slot in the body
//! ([`HistoryCarry::map_spheres`]). A pair of the new list then finds its
//! history in the short old row of whichever of its spheres came first
//! ([`HistoryCarry::get`]). Bodies move little between builds, so the new
//! storage order is nearly the old one and these reads run through the old
//! rows nearly in order: on a bed beyond the caches the hash map keyed by
//! global sphere ids cost a cache miss per insert and per lookup, and held
//! about 74 bytes per contact. The map remains for the histories that
//! arrive by global id (a checkpoint, a world joined from its ranks).
//!
//! What is carried is exactly what the map carries: the pairs with a
//! non-zero history, or live ones when a law's contacts outlast touching,
//! re-oriented from the old pair's `i → j` to the new one's (a reversal is a
//! negation, so twice reversed is the same bits).

use crate::contact::mdr::SlipProfile;
use crate::contact::ContactHistory;
use crate::sphere::{Spheres, SPHERE_ID_BITS};
use glam::DVec3;

/// No old body or sphere (a body added since the last build).
pub(crate) const NONE: u32 = u32::MAX;

/// The old list's pairs with state, by old storage index; reused between
/// builds.
#[derive(Debug, Default)]
pub(crate) struct HistoryCarry {
    /// Filled by `save` and mapped by `map_spheres` for the build that
    /// follows; cleared by that build.
    pub active: bool,
    /// Per old sphere, the start of its entries (old sphere count + 1).
    row_start: Vec<u32>,
    /// Partner of each entry: the old storage index `j > i`.
    j: Vec<u32>,
    /// Tangential spring of each entry, world frame, m, oriented `i → j`.
    tangential: Vec<DVec3>,
    /// Rolling spring of each entry, world frame, N m, oriented `i → j`
    /// (empty when the list keeps none).
    rolling: Vec<DVec3>,
    /// MDR profile of each entry, oriented `i → j` (empty when the list
    /// keeps none).
    slip: Vec<SlipProfile>,
    /// Per old body, its first old sphere (old body count + 1).
    old_first: Vec<u32>,
    /// Per new sphere, its old storage index or [`NONE`].
    old_index: Vec<u32>,
}

impl HistoryCarry {
    /// Starts a carry of the list built on spheres whose bodies' first
    /// spheres are `old_first` (old body count + 1).
    pub(crate) fn start(&mut self, old_first: &[u32], n: usize) {
        self.row_start.clear();
        self.j.clear();
        self.tangential.clear();
        self.rolling.clear();
        self.slip.clear();
        self.old_first.clear();
        self.old_first.extend_from_slice(old_first);
        self.row_start.reserve(n + 1);
        self.row_start.push(0);
    }

    /// Adds an entry to the current row: partner `j`, its history and,
    /// where the list keeps them, its rolling spring and MDR profile.
    #[inline]
    pub(crate) fn push(
        &mut self,
        j: u32,
        h: ContactHistory,
        rolling: bool,
        slip: Option<SlipProfile>,
    ) {
        self.j.push(j);
        self.tangential.push(h.tangential);
        if rolling {
            self.rolling.push(h.rolling);
        }
        if let Some(s) = slip {
            self.slip.push(s);
        }
    }

    /// Ends the current row.
    pub(crate) fn end_row(&mut self) {
        self.row_start.push(self.j.len() as u32);
    }

    /// Ends the carry: rows up to `n` spheres, then active.
    pub(crate) fn finish(&mut self, n: usize) {
        self.row_start.resize(n + 1, self.j.len() as u32);
        self.active = true;
    }

    /// Gives each new sphere its old storage index: sphere `k` of new body
    /// `b` was sphere `k` of old body `old_body[b]` (or is new).
    /// `body_first` is the new sphere topology's.
    pub(crate) fn map_spheres(&mut self, old_body: &[u32], body_first: &[u32]) {
        let n = body_first.last().map_or(0, |&s| s as usize);
        self.old_index.clear();
        self.old_index.resize(n, NONE);
        for (b, &ob) in old_body.iter().enumerate() {
            if ob == NONE {
                continue;
            }
            let (s0, s1) = (body_first[b] as usize, body_first[b + 1] as usize);
            let o0 = self.old_first[ob as usize];
            for (k, x) in self.old_index[s0..s1].iter_mut().enumerate() {
                *x = o0 + k as u32;
            }
        }
    }

    /// The carried history of the new pair of spheres `a → b` (new storage
    /// indices), oriented from `a` to `b`; None for a pair without state.
    #[inline]
    pub(crate) fn get(&self, a: usize, b: usize) -> Option<ContactHistory> {
        let (e, forward) = self.entry(a, b)?;
        let h = ContactHistory {
            tangential: self.tangential[e],
            rolling: self.rolling.get(e).copied().unwrap_or_default(),
        };
        Some(if forward { h } else { reversed(h) })
    }

    /// The entry of the new pair `a → b` and whether it runs the same way
    /// as the old pair.
    #[inline]
    fn entry(&self, a: usize, b: usize) -> Option<(usize, bool)> {
        let (oa, ob) = (self.old_index[a], self.old_index[b]);
        if oa == NONE || ob == NONE {
            return None;
        }
        let (lo, hi) = if oa < ob { (oa, ob) } else { (ob, oa) };
        let (e0, e1) = (
            self.row_start[lo as usize] as usize,
            self.row_start[lo as usize + 1] as usize,
        );
        let e = e0 + self.j[e0..e1].iter().position(|&j| j == hi)?;
        Some((e, oa < ob))
    }

    /// The carried MDR profile of the new pair `a → b`, oriented from `a`
    /// to `b`; None for a pair without state or a list without profiles.
    #[inline]
    pub(crate) fn get_slip(&self, a: usize, b: usize) -> Option<SlipProfile> {
        let (e, forward) = self.entry(a, b)?;
        let sp = *self.slip.get(e)?;
        Some(if forward { sp } else { sp.reversed() })
    }

    /// Whether some pair carries state.
    pub(crate) fn is_empty(&self) -> bool {
        self.j.is_empty()
    }
}

/// Per body of the new order (`perm[k]`: the current index of new body `k`;
/// `id`: the bodies' global ids, current order), its index in the sphere
/// topology `sp` of the last build, or [`NONE`] for a body added since.
/// The index is found by the body's id: a driver's `remove_body` shifts the
/// current indices of the bodies after the removed one, while the spheres
/// still hold the old topology.
pub(crate) fn old_body_index(sp: &Spheres, id: &[u64], perm: &[u32], out: &mut Vec<u32>) {
    let old_n = sp.body_first.len().saturating_sub(1);
    let old_id = |o: usize| sp.gid[sp.body_first[o] as usize] >> SPHERE_ID_BITS;
    out.clear();
    out.reserve(perm.len());
    // the common case: every old body kept its index (bodies added since
    // come after them)
    let shifted = (0..old_n.min(id.len())).any(|o| old_id(o) != id[o]);
    if !shifted {
        out.extend(
            perm.iter()
                .map(|&cur| if (cur as usize) < old_n { cur } else { NONE }),
        );
        return;
    }
    let by_id: std::collections::HashMap<u64, u32> =
        (0..old_n).map(|o| (old_id(o), o as u32)).collect();
    out.extend(
        perm.iter()
            .map(|&cur| by_id.get(&id[cur as usize]).copied().unwrap_or(NONE)),
    );
}

/// The history of a pair seen from the other side (`j` to `i`): both springs
/// are relative quantities of `i` with respect to `j`, so they change sign.
#[inline]
pub(crate) fn reversed(h: ContactHistory) -> ContactHistory {
    ContactHistory {
        tangential: -h.tangential,
        rolling: -h.rolling,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::boundary::Domain;
    use crate::neighbor::pairs::{BuildInput, HistoryMap, PairList, SlipMap};
    use crate::neighbor::CellGrid;
    use crate::sphere::sphere_gid;
    use rand::{Rng, SeedableRng};

    /// Spheres of the bodies `ids` (4 each, offsets from `centre[id]`) in
    /// this order: positions, body, body_first, gid.
    fn topology(ids: &[u64], centre: &[DVec3]) -> (Vec<DVec3>, Vec<u32>, Spheres) {
        let mut sp = Spheres::default();
        let mut position = Vec::new();
        let mut body = Vec::new();
        sp.body_first.push(0);
        for (b, &id) in ids.iter().enumerate() {
            for k in 0..4u32 {
                let o = DVec3::new(k as f64, (k * k) as f64, (3 - k) as f64) * 2e-4;
                position.push(centre[id as usize] + o);
                body.push(b as u32);
                sp.gid.push(sphere_gid(id, k));
            }
            sp.body_first.push(position.len() as u32);
        }
        (position, body, sp)
    }

    /// Bodies re-sorted, one removed by a driver (the bodies after it
    /// shift down) and one added: the histories carried by storage index
    /// are, pair by pair and bit by bit, those carried by global sphere id
    /// (with springs, rolling springs, MDR profiles, live flags, and both
    /// orientations), and a pair with a profile and no spring (a contact
    /// whose tangential force is exactly zero) keeps its profile.
    #[test]
    fn carried_by_index_as_by_global_id() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let domain = Domain {
            lo: DVec3::ZERO,
            hi: DVec3::splat(0.01),
            periodic: [true, true, true],
        };
        let nb = 200usize;
        let centre: Vec<DVec3> = (0..=nb)
            .map(|_| DVec3::new(rng.gen(), rng.gen(), rng.gen()) * 0.01)
            .collect();
        let build = |ids: &[u64],
                     pairs: &mut PairList,
                     carried: Option<&HistoryCarry>,
                     map: &HistoryMap,
                     slips: &SlipMap| {
            let (position, body, sp) = topology(ids, &centre);
            let radius = vec![3e-4; position.len()];
            let state = crate::sphere::SphereState::of(&position, &radius);
            let inp = BuildInput {
                state: &state,
                radius: &radius,
                body: &body,
                body_first: &sp.body_first,
                gid: &sp.gid,
                skin: 2e-4,
                rolling: true,
                slip: Some(slips),
                owned: None,
            };
            let grid = CellGrid::new(&domain, &position, 8e-4).unwrap();
            match carried {
                Some(c) => pairs.build_carried(&grid, &domain, &inp, c),
                None => pairs.build(&grid, &domain, &inp, map),
            }
            sp
        };
        // the old list, with state on about two pairs in three
        let old_ids: Vec<u64> = (0..nb as u64).collect();
        let mut old = PairList::default();
        let no_slip = SlipMap::default();
        let old_sp = build(&old_ids, &mut old, None, &HistoryMap::default(), &no_slip);
        let profile = |rng: &mut rand_chacha::ChaCha8Rng| {
            let mut sp = SlipProfile {
                edge: 1e-8,
                len: 3,
                ..Default::default()
            };
            for k in 0..3 {
                sp.xi[k] = k as f64 * 3e-9;
                sp.u[k] = DVec3::new(rng.gen(), rng.gen(), rng.gen()) - 0.5;
            }
            sp
        };
        let mut profile_only = 0;
        for p in 0..old.len() {
            match rng.gen_range(0..4) {
                0 => {}
                1 => old.topo[p].set_live(true),
                2 => {
                    old.topo[p].set_live(true);
                    old.slip[p] = profile(&mut rng);
                    profile_only += 1;
                }
                _ => {
                    old.tangential[p] = DVec3::new(rng.gen(), rng.gen(), rng.gen()) - 0.5;
                    old.rolling[p] = DVec3::new(rng.gen(), rng.gen(), rng.gen()) - 0.5;
                    old.slip[p] = profile(&mut rng);
                }
            }
        }
        assert!(
            profile_only > 100,
            "too few profiles without spring: {profile_only}"
        );
        assert!(old.len() > 500, "too few pairs to test: {}", old.len());
        // the driver removes body 17: the current bodies are the old ones
        // without it, then body nb is added; the rebuild re-sorts them
        let current: Vec<u64> = (0..nb as u64)
            .filter(|&i| i != 17)
            .chain([nb as u64])
            .collect();
        let mut perm: Vec<u32> = (0..current.len() as u32).collect();
        for i in (1..perm.len()).rev() {
            perm.swap(i, rng.gen_range(0..=i));
        }
        let new_ids: Vec<u64> = perm.iter().map(|&c| current[c as usize]).collect();
        for keep_live in [false, true] {
            let mut map = HistoryMap::default();
            old.save_history(&old_sp.gid, keep_live, &mut map);
            let mut slips = SlipMap::default();
            old.save_slip(&old_sp.gid, &mut slips);
            let mut by_id = PairList::default();
            build(&new_ids, &mut by_id, None, &map, &slips);
            let mut carry = HistoryCarry::default();
            old.save_carry(&mut carry, &old_sp, keep_live);
            let mut old_body = Vec::new();
            old_body_index(&old_sp, &current, &perm, &mut old_body);
            assert_eq!(old_body.iter().filter(|&&o| o == NONE).count(), 1);
            let (_, _, new_sp) = topology(&new_ids, &centre);
            carry.map_spheres(&old_body, &new_sp.body_first);
            let mut by_index = PairList::default();
            build(
                &new_ids,
                &mut by_index,
                Some(&carry),
                &HistoryMap::default(),
                &no_slip,
            );
            assert!(
                by_index.topo == by_id.topo,
                "live flags differ (keep_live {keep_live})"
            );
            let same = |a: &[DVec3], b: &[DVec3]| {
                a.len() == b.len()
                    && a.iter().zip(b).all(|(x, y)| {
                        x.to_array().map(f64::to_bits) == y.to_array().map(f64::to_bits)
                    })
            };
            assert!(
                same(&by_index.tangential, &by_id.tangential),
                "springs differ"
            );
            assert!(
                same(&by_index.rolling, &by_id.rolling),
                "rolling springs differ"
            );
            assert!(by_index.slip == by_id.slip, "profiles differ");
            let carried = by_id.topo.iter().filter(|t| t.live()).count();
            assert!(carried > 100, "too few histories carried: {carried}");
            // the pairs that kept a profile without a spring: about those
            // of the old list (less the removed body's pairs)
            let kept_profile_only = (0..by_index.len())
                .filter(|&p| by_index.tangential[p] == DVec3::ZERO && !by_index.slip[p].is_empty())
                .count();
            assert!(
                kept_profile_only > profile_only * 9 / 10 && kept_profile_only <= profile_only,
                "profiles without spring: {kept_profile_only} of {profile_only} kept"
            );
        }
    }
}
