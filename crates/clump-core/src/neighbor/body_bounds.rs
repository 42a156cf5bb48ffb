//! Body bounding spheres for the pair search on many-sphere clumps.
//!
//! A sphere's search stencil on a stone of 50 spheres covers the spheres of
//! several neighbouring stones, most of them far out of reach (on LIGGGHTS'
//! settled stone pile, 254 spheres in the stencil's cells per sphere, for
//! 0.56 candidate pairs). A cell's spheres are in storage order and a
//! body's spheres are contiguous, so a cell holds each body's spheres as
//! one run; a run is passed over without distance tests when sphere `i`
//! cannot reach the bounding sphere of its body. The spheres passed over
//! are ones that would fail the distance test (see
//! [`BodyBounds::out_of_reach`]), so the list, and its order, are the same
//! with or without the filter.

use glam::DVec3;

/// Mean spheres per body from which the search uses the bounding spheres:
/// on tetrahedra (4 spheres) a run is one or two spheres and the extra test
/// would cost more than it saves.
const MIN_SPHERES_PER_BODY: usize = 8;

/// Relative slack on the reach, far above the rounding of the distances
/// (a few ulps of the coordinates), so that a sphere the exact test would
/// take is never skipped.
const SLACK: f64 = 1e-10;

/// Per body a bounding sphere of its spheres at the build. Reused between
/// builds.
#[derive(Debug, Clone, Default)]
pub(crate) struct BodyBounds {
    /// Per body: centre (world frame, m) and radius (m) of a sphere that
    /// holds all its spheres, widened by the slack.
    bound: Vec<[f64; 4]>,
}

impl BodyBounds {
    /// Whether the search uses the filter, for bodies owning the spheres
    /// `body_first[b]..body_first[b + 1]` (the last entry is the number of
    /// spheres).
    pub(crate) fn pays(body_first: &[u32]) -> bool {
        let nb = body_first.len().saturating_sub(1);
        let n = body_first.last().map_or(0, |&n| n as usize);
        nb > 0 && n >= MIN_SPHERES_PER_BODY * nb
    }

    /// Builds the bounding spheres from the spheres' centres (`state`'s,
    /// world frame, m) and radii `radius` (m; body `b` owns
    /// `body_first[b]..body_first[b + 1]`).
    pub(crate) fn build(
        &mut self,
        state: &[crate::sphere::SphereState],
        radius: &[f64],
        body_first: &[u32],
    ) {
        let nb = body_first.len().saturating_sub(1);
        self.bound.clear();
        self.bound.extend((0..nb).map(|b| {
            let s = body_first[b] as usize..body_first[b + 1] as usize;
            let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
            for x in &state[s.clone()] {
                lo = lo.min(x.position);
                hi = hi.max(x.position);
            }
            let c = 0.5 * (lo + hi);
            let r = s
                .map(|k| state[k].position.distance(c) + radius[k])
                .fold(0.0, f64::max);
            // the reach test subtracts coordinates of magnitude |c|: its
            // rounding scales with them, not with the body
            let r = r + SLACK * (r + c.abs().max_element());
            [c.x, c.y, c.z, r]
        }));
    }

    /// True when no sphere of body `b` lies within `reach` (m: the sphere's
    /// radius plus the skin) of the point `x` (world frame, m), the
    /// distance taken as the minimum image on the `periodic` axes of a box
    /// of edges `length` (m).
    /// A sphere `j` of `b` passes the search's test only if
    /// `|x − x_j| < reach + r_j`, and then, by the triangle inequality
    /// (which the minimum image obeys), `|x − c_b| < reach + r_b`.
    #[inline(always)]
    pub(crate) fn out_of_reach(
        &self,
        b: usize,
        x: DVec3,
        reach: f64,
        periodic: [bool; 3],
        length: DVec3,
    ) -> bool {
        let [cx, cy, cz, rb] = self.bound[b];
        let mut d = x - DVec3::new(cx, cy, cz);
        for a in 0..3 {
            if periodic[a] {
                d[a] -= length[a] * (d[a] / length[a]).round();
            }
        }
        let r = reach + rb;
        d.length_squared() > r * r
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::boundary::Domain;
    use crate::neighbor::pairs::{BuildInput, HistoryMap, PairList};
    use crate::neighbor::CellGrid;
    use rand::{Rng, SeedableRng};

    /// Random stones of 12 spheres (radii 0.4–1 mm, centres within 2 mm of
    /// the body's) in a box periodic in x and y: the search with the
    /// bounding spheres finds the same candidates in the same order as the
    /// search without them, and these are exactly the sphere pairs of
    /// different bodies within the cut-off (brute force over all pairs and
    /// periodic images).
    #[test]
    fn the_filter_keeps_every_candidate_in_order() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let domain = Domain {
            lo: DVec3::ZERO,
            hi: DVec3::new(0.02, 0.02, 0.03),
            periodic: [true, true, false],
        };
        let (nb, k, skin) = (120usize, 12usize, 3e-4);
        let (mut position, mut radius, mut body, mut body_first) =
            (Vec::new(), Vec::new(), Vec::new(), vec![0u32]);
        for b in 0..nb {
            // some centres outside the periodic box: the spheres are unwrapped
            let c = DVec3::new(
                rng.gen_range(-0.002..0.022),
                rng.gen_range(-0.002..0.022),
                rng.gen_range(0.002..0.028),
            );
            for _ in 0..k {
                let o = DVec3::new(
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                    rng.gen_range(-1.0..1.0),
                );
                position.push(c + 2e-3 * o.normalize_or_zero() * rng.gen_range(0.0..1.0));
                radius.push(rng.gen_range(4e-4..1e-3));
                body.push(b as u32);
            }
            body_first.push(position.len() as u32);
        }
        let gid: Vec<u64> = (0..position.len() as u64).collect();
        assert!(BodyBounds::pays(&body_first));
        let state = crate::sphere::SphereState::of(&position, &radius);
        let inp = BuildInput {
            state: &state,
            radius: &radius,
            body: &body,
            body_first: &body_first,
            gid: &gid,
            skin,
            rolling: false,
        };
        let grid = CellGrid::new(&domain, &position, 2e-3 + skin).unwrap();
        let mut with = PairList::default();
        with.build(&grid, &domain, &inp, &HistoryMap::default());
        let mut without = PairList::default();
        without.unbounded = true;
        without.build(&grid, &domain, &inp, &HistoryMap::default());
        assert!(with.row_start == without.row_start, "the rows differ");
        assert!(with.topo == without.topo, "the candidates differ");
        // brute force: every pair of different bodies within the cut-off,
        // at the nearest periodic image
        let l = domain.size();
        let mut expected = 0;
        for i in 0..position.len() {
            for j in i + 1..position.len() {
                if body[i] == body[j] {
                    continue;
                }
                let mut d = position[i] - position[j];
                for a in 0..2 {
                    d[a] -= l[a] * (d[a] / l[a]).round();
                }
                let cut = radius[i] + radius[j] + skin;
                if d.length_squared() < cut * cut {
                    expected += 1;
                    assert!(
                        with.row(i).any(|p| with.topo[p].j as usize == j),
                        "pair ({i}, {j}) missing"
                    );
                }
            }
        }
        assert_eq!(with.len(), expected);
        assert!(expected > 200, "too few candidates to test: {expected}");
    }
}
