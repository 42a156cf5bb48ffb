//! Bounding spheres of many-sphere bodies, for the pair search by body
//! pairs ([`super::body_search`]): a body pair whose bounding spheres are
//! more than the skin apart has no candidate pair, and a sphere that does
//! not reach a body's bounding sphere has no candidate on that body.

use glam::DVec3;

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

    /// The centre (world frame, m) and radius (m) of body `b`'s bounding
    /// sphere.
    #[inline(always)]
    pub(crate) fn get(&self, b: usize) -> (DVec3, f64) {
        let [cx, cy, cz, rb] = self.bound[b];
        (DVec3::new(cx, cy, cz), rb)
    }

    /// Largest radius of a bounding sphere, m (0 without bodies).
    pub(crate) fn largest(&self) -> f64 {
        self.bound.iter().map(|b| b[3]).fold(0.0, f64::max)
    }

    /// True when no sphere of body `a` is within `skin` (m) of a sphere of
    /// body `b` (minimum image as in [`BodyBounds::out_of_reach`]): a
    /// sphere `i` of `a` lies within `r_a − r_i` of `c_a`, so a sphere `i`
    /// that reaches `b`'s bounding sphere (`|x_i − c_b| < r_i + skin +
    /// r_b`) gives `|c_a − c_b| < r_a + skin + r_b`.
    #[inline(always)]
    pub(crate) fn apart(
        &self,
        a: usize,
        b: usize,
        skin: f64,
        periodic: [bool; 3],
        length: DVec3,
    ) -> bool {
        let (ca, ra) = self.get(a);
        self.out_of_reach(b, ca, ra + skin, periodic, length)
    }
}
