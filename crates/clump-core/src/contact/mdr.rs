//! Micro-slip tangential model by the method of dimensionality reduction
//! (MDR): the Cattaneo–Mindlin problem of a Hertz contact under arbitrary
//! histories of normal and tangential load, solved per contact on its
//! one-dimensional equivalent (Popov & Heß 2015, "Method of Dimensionality
//! Reduction in Contact Mechanics and Friction", Springer, ch. 5 and 8).
//! Selected with `tangential = "mdr"` ([`super::TangentialLaw::Mdr`]);
//! docs/theory.md (T-50).
//!
//! # The 1-D foundation
//! The sphere's profile maps to `g(x) = x²/R*`; a row of independent
//! springs over `|x| ≤ a`, `a = √(R*δ)`, with normal stiffness `E*` and
//! tangential stiffness `G̃ = 4G*` per unit length (`2aG̃ = 8G*a`, Mindlin's
//! stiffness). Each spring in contact follows the tangential displacement
//! of the contact, `u(x) += Δu`, and slips where the local Coulomb limit is
//! reached, `G̃|u(x)| ≤ μE*(δ − x²/R*)`; a spring leaving the contact is
//! released (`u = 0`), a spring entering it starts at `u = 0`. The
//! tangential force resisting the displacement is `T = G̃ ∫_{−a}^{a} u dx`
//! (the force on `i` is `−T`).
//!
//! # The exact state: a piecewise-linear profile in `ξ = x²`
//! In the variable `ξ = x²` (`A = a²`) the slip limit is a straight line,
//! `|u(ξ)| ≤ λ(A − ξ)`, `λ = μE*/(G̃R*)`, and
//! `T = G̃ ∫_0^A u(ξ) ξ^{−1/2} dξ`. A profile that is piecewise linear in
//! `ξ` stays so under every operation of the rules: the rigid shift of the
//! stuck springs, the clipping against the limit line (new nodes where a
//! segment crosses it), the release of springs beyond a shrinking `A`, and
//! the entry of springs over a growing `A`, which within one step is a
//! straight ramp from the old edge (it took the step's full `Δu`) to the
//! new one (`u = 0`) — exact when `Δu` is proportional to `ΔA` within the
//! step, i.e. to first order in the step like every DEM increment. So the
//! profile, stored as nodes `(ξ_k, u_k)`, is the exact MDR state of the
//! step-discretised history; the force integrates it in closed form
//! (`∫ξ^{−1/2}`, `∫ξ^{1/2}`). Slip erases memory (Masing's rule): the nodes
//! under a slip zone fall on the limit line and are merged into one
//! segment; nodes that have become collinear are merged (relative
//! tolerance 10⁻¹²).
//!
//! # The bound
//! At most [`MDR_NODES`] nodes are kept (plus the edge `(A, 0)`, implicit).
//! While the contact grows and sticks with a tangential displacement that
//! is not proportional to the growth of `A`, every step adds a node; above
//! the bound the interior node whose removal changes the force least is
//! removed (its hat function's weight times its distance from the chord of
//! its neighbours; the change is exactly that product, so each removal's
//! error in `T` is known and is the smallest available). The unit tests
//! and `crates/clump-core/tests/micro_slip.rs` measure the effect.
//!
//! # Clump's choices (not in the source)
//! - `λ = 3μN/(4G̃a³)`, with `N = |F_n|` the pair's clamped normal force:
//!   `λ(A − ξ)` integrates to the Coulomb limit `μN`; for an elastic
//!   contact (`N` Hertz's force) it is MDR's `μE*/(G̃R*)`, with a normal
//!   dashpot the limit line is scaled with the normal force.
//! - In 3-D each node holds a vector in the tangent plane (world frame),
//!   rotated into the current plane each step as the default spring is
//!   ([`rotate_into_plane`]); each node is clipped radially to the limit,
//!   crossings are found on the straight segment between two nodes. For a
//!   straight tangential path (every validation case) this is the 1-D rule
//!   exactly; for a curved path the profile between nodes is interpolated.
//! - No tangential dashpot; the stored energy is reported as
//!   `|T|²/(2·8G*a)` (as the Thornton–Yin scheme does).

use super::tangential::rotate_into_plane;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Most nodes of a stored profile (the edge not counted).
pub const MDR_NODES: usize = 16;
/// Working nodes of one evaluation: the stored ones, the old and new edge,
/// and up to two crossings of the limit line per segment.
const WORK: usize = 3 * (MDR_NODES + 2);
/// Relative distance from the chord under which a node is merged.
const MERGE_TOL: f64 = 1e-12;

/// The MDR state of one contact (module docs): the edge `A = a²` of the last
/// evaluation and the profile nodes `(ξ_k, u_k)`, `0 = ξ_0 < ξ_1 < … < A`
/// (m², m; `u_k` world frame, in the tangent plane of the last
/// evaluation, displacement of `i` relative to `j`). `len = 0`: no contact.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SlipProfile {
    /// `A = a² = R*δ` at the last evaluation, m².
    pub edge: f64,
    /// Number of nodes in use.
    pub len: u32,
    /// Node positions `ξ_k = x_k²`, m².
    pub xi: [f64; MDR_NODES],
    /// Spring displacements at the nodes, m, world frame.
    pub u: [DVec3; MDR_NODES],
}

impl Default for SlipProfile {
    fn default() -> Self {
        Self {
            edge: 0.0,
            len: 0,
            xi: [0.0; MDR_NODES],
            u: [DVec3::ZERO; MDR_NODES],
        }
    }
}

impl SlipProfile {
    /// The profile seen from the other side (`j` to `i`): displacements
    /// negated.
    pub fn reversed(mut self) -> Self {
        for u in &mut self.u {
            *u = -*u;
        }
        self
    }

    /// Whether the contact has no state (a new contact).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }
}

/// The working profile of one evaluation (on the stack).
struct Work {
    xi: [f64; WORK],
    u: [DVec3; WORK],
    len: usize,
}

impl Work {
    fn push(&mut self, xi: f64, u: DVec3) {
        self.xi[self.len] = xi;
        self.u[self.len] = u;
        self.len += 1;
    }

    fn remove(&mut self, k: usize) {
        self.xi.copy_within(k + 1..self.len, k);
        self.u.copy_within(k + 1..self.len, k);
        self.len -= 1;
    }
}

/// Weights `(w_a, w_b)` of `∫_{ξa}^{ξb} u(ξ) ξ^{−1/2} dξ = w_a u_a + w_b u_b`
/// for `u` linear in `ξ` (m): with `p = √ξa`, `q = √ξb`,
/// `w_a = (2/3)(q − p)(2q + p)/(q + p)`, `w_b = (2/3)(q − p)(q + 2p)/(q + p)`.
#[inline]
fn weights(xa: f64, xb: f64) -> (f64, f64) {
    let (p, q) = (xa.sqrt(), xb.sqrt());
    let s = q + p;
    if s <= 0.0 {
        return (0.0, 0.0);
    }
    let c = 2.0 / 3.0 * (q - p) / s;
    (c * (2.0 * q + p), c * (q + 2.0 * p))
}

/// Value at `x` of the segment from `(xa, ua)` to `(xb, ub)` (`xa < xb`).
#[inline]
fn lerp(xa: f64, ua: DVec3, xb: f64, ub: DVec3, x: f64) -> DVec3 {
    ua + (ub - ua) * ((x - xa) / (xb - xa))
}

/// The roots `s ∈ (0, 1)` of `|ua + s d| = La + s dL` on one segment, in
/// ascending order (`NaN` where none); `ga`, `gb` are `|u| − L` at its ends.
fn crossings(ua: DVec3, d: DVec3, la: f64, dl: f64, ga: f64, gb: f64) -> [f64; 2] {
    // (d·d − dL²) s² + 2(ua·d − La dL) s + (ua·ua − La²) = 0; |u| − L is
    // convex on the segment, so it is ≤ 0 on one interval
    let qa = d.length_squared() - dl * dl;
    let qb = ua.dot(d) - la * dl;
    let qc = ua.length_squared() - la * la;
    let disc = qb * qb - qa * qc;
    let mut out = [f64::NAN; 2];
    if disc < 0.0 {
        return out;
    }
    let sq = disc.sqrt();
    // the two roots without cancellation
    let t = -(qb + qb.signum() * sq);
    let (r1, r2) = if t != 0.0 {
        (qc / t, if qa != 0.0 { t / qa } else { f64::NAN })
    } else {
        (0.0, 0.0)
    };
    let (lo, hi) = if r1 <= r2 { (r1, r2) } else { (r2, r1) };
    let inside = |s: f64| s > 0.0 && s < 1.0;
    match (ga > 0.0, gb > 0.0) {
        // one crossing: the root where the sign changes
        (true, false) => out[0] = if inside(lo) { lo } else { hi },
        (false, true) => out[0] = if inside(hi) { hi } else { lo },
        // both ends slipping: a stuck interval inside, or none
        (true, true) if inside(lo) && inside(hi) && lo < hi => out = [lo, hi],
        _ => {}
    }
    for s in &mut out {
        if !inside(*s) {
            *s = f64::NAN;
        }
    }
    out
}

/// Clips the profile `w` (nodes on `[0, A]`) to `|u| ≤ λ(A − ξ)`, adding a
/// node where a segment crosses the limit line; writes the result to `out`.
fn clip(w: &Work, a2: f64, lam: f64, out: &mut Work) {
    out.len = 0;
    let lim = |x: f64| (lam * (a2 - x)).max(0.0);
    let clipped = |u: DVec3, l: f64| {
        let m = u.length();
        if m > l {
            u * (l / m)
        } else {
            u
        }
    };
    for k in 0..w.len {
        let (xa, ua) = (w.xi[k], w.u[k]);
        let la = lim(xa);
        out.push(xa, clipped(ua, la));
        if k + 1 == w.len {
            break;
        }
        let (xb, ub) = (w.xi[k + 1], w.u[k + 1]);
        let lb = lim(xb);
        let (ga, gb) = (ua.length() - la, ub.length() - lb);
        if ga <= 0.0 && gb <= 0.0 {
            continue;
        }
        for s in crossings(ua, ub - ua, la, lb - la, ga, gb) {
            if s.is_nan() {
                continue;
            }
            let x = xa + s * (xb - xa);
            if x > xa && x < xb {
                out.push(x, clipped(ua + s * (ub - ua), lim(x)));
            }
        }
    }
}

/// The change of `∫u ξ^{−1/2}dξ` (m², norm) when interior node `k` is
/// replaced by the chord of its neighbours.
fn removal_error(w: &Work, k: usize) -> f64 {
    let (xa, xm, xb) = (w.xi[k - 1], w.xi[k], w.xi[k + 1]);
    let off = w.u[k] - lerp(xa, w.u[k - 1], xb, w.u[k + 1], xm);
    let hat = weights(xa, xm).1 + weights(xm, xb).0;
    off.length() * hat
}

/// Merges the interior nodes that lie on the chord of their neighbours
/// (within `tol`, m), then removes the least significant interior nodes
/// while more than `max` nodes remain.
fn simplify(w: &mut Work, tol: f64, max: usize) {
    let mut k = 1;
    while k + 1 < w.len {
        let (xa, xb) = (w.xi[k - 1], w.xi[k + 1]);
        let chord = lerp(xa, w.u[k - 1], xb, w.u[k + 1], w.xi[k]);
        if (w.u[k] - chord).length() <= tol || w.xi[k] <= xa || w.xi[k] >= xb {
            w.remove(k);
        } else {
            k += 1;
        }
    }
    while w.len > max {
        let mut best = (f64::INFINITY, 1);
        for k in 1..w.len - 1 {
            let e = removal_error(w, k);
            if e < best.0 {
                best = (e, k);
            }
        }
        w.remove(best.1);
    }
}

/// The MDR tangential force on `i` (N, world) and the stored energy (J),
/// updating the profile `p` (module docs).
///
/// - `n`: unit normal (world); `v_t`: tangential relative velocity of the
///   contact points (m/s, world, in the tangent plane); `dt` (s);
/// - `a2`: `A = a² = R*δ` (m²); `g_lin`: the foundation's tangential
///   stiffness per unit length `G̃ = 4G*` (Pa, `2aG̃ = 8G*a`);
/// - `mu`: friction coefficient; `f_n`: the normal force (N, ≥ 0).
#[allow(clippy::too_many_arguments)]
pub fn mdr_tangential(
    p: &mut SlipProfile,
    n: DVec3,
    v_t: DVec3,
    dt: f64,
    a2: f64,
    g_lin: f64,
    mu: f64,
    f_n: f64,
) -> (DVec3, f64) {
    if !(a2 > 0.0 && g_lin > 0.0) {
        *p = SlipProfile::default();
        return (DVec3::ZERO, 0.0);
    }
    let a = a2.sqrt();
    let lam = (0.75 * mu * f_n / (g_lin * a2 * a)).max(0.0);
    let du = v_t * dt;
    // the stored nodes shifted by Δu, the old edge (which took Δu too)
    let mut w = Work {
        xi: [0.0; WORK],
        u: [DVec3::ZERO; WORK],
        len: 0,
    };
    let len = (p.len as usize).min(MDR_NODES);
    for k in 0..len {
        w.push(p.xi[k], rotate_into_plane(p.u[k], n) + du);
    }
    if len == 0 || p.edge > w.xi[w.len - 1] {
        w.push(if len == 0 { 0.0 } else { p.edge }, du);
    }
    // the new edge: springs entering on a ramp, or released beyond it
    let last = w.len - 1;
    if a2 > w.xi[last] {
        w.push(a2, DVec3::ZERO);
    } else {
        let mut k = last;
        while w.xi[k - 1] >= a2 {
            k -= 1;
        }
        let u = lerp(w.xi[k - 1], w.u[k - 1], w.xi[k], w.u[k], a2);
        w.len = k;
        w.push(a2, u);
    }
    let mut c = Work {
        xi: [0.0; WORK],
        u: [DVec3::ZERO; WORK],
        len: 0,
    };
    clip(&w, a2, lam, &mut c);
    simplify(&mut c, MERGE_TOL * lam * a2, MDR_NODES + 1);
    // the force, and the stored nodes (the edge, u = 0, implicit)
    let mut t = DVec3::ZERO;
    for k in 0..c.len - 1 {
        let (wa, wb) = weights(c.xi[k], c.xi[k + 1]);
        t += wa * c.u[k] + wb * c.u[k + 1];
    }
    t *= g_lin;
    p.edge = a2;
    p.len = (c.len - 1) as u32;
    p.xi[..c.len - 1].copy_from_slice(&c.xi[..c.len - 1]);
    p.u[..c.len - 1].copy_from_slice(&c.u[..c.len - 1]);
    (-t, 0.25 * t.length_squared() / (g_lin * a))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Drives one contact at constant `A` and `N` along x by `steps`
    /// increments of `dx` (m); returns the force resisting it (N).
    fn drive(p: &mut SlipProfile, g: f64, a2: f64, mu_n: f64, dx: f64, steps: usize) -> f64 {
        let mut t = 0.0;
        for _ in 0..steps {
            let (f, _) =
                mdr_tangential(p, DVec3::Z, DVec3::new(dx, 0.0, 0.0), 1.0, a2, g, 1.0, mu_n);
            t = -f.x;
        }
        t
    }

    /// Cattaneo–Mindlin at constant N: loading
    /// `T = μN(1 − (1 − δ/δ_μ)^{3/2})`, `δ_μ = 3μN/(2k0)`, `k0 = 2aG̃`;
    /// unloading and reloading by Masing's rule. A constant `A` profile
    /// is exact at any increment (the rule has no time-step error there):
    /// the tolerance is round-off.
    #[test]
    fn cattaneo_mindlin_cycle_is_exact() {
        let (g, a2, lim): (f64, f64, f64) = (1.0e9, 1.0e-8, 1.0);
        let k0 = 2.0 * a2.sqrt() * g;
        let dm = 1.5 * lim / k0;
        let load = |x: f64| lim * (1.0 - (1.0 - x / dm).max(0.0).powf(1.5));
        let mut p = SlipProfile::default();
        // first contact at this A: one step of zero displacement
        drive(&mut p, g, a2, lim, 0.0, 1);
        let steps = 400;
        let dx = 0.8 * dm / steps as f64;
        let mut worst: f64 = 0.0;
        let mut x = 0.0;
        for _ in 0..steps {
            let t = drive(&mut p, g, a2, lim, dx, 1);
            x += dx;
            worst = worst.max((t - load(x)).abs());
        }
        let (x1, t1) = (x, load(x));
        for _ in 0..600 {
            let t = drive(&mut p, g, a2, lim, -dx, 1);
            x -= dx;
            let r = t1 - 2.0 * lim * (1.0 - (1.0 - (x1 - x) / (2.0 * dm)).powf(1.5));
            worst = worst.max((t - r).abs());
        }
        let (x2, t2) = (
            x,
            t1 - 2.0 * lim * (1.0 - (1.0 - (x1 - x) / (2.0 * dm)).powf(1.5)),
        );
        for _ in 0..800 {
            let t = drive(&mut p, g, a2, lim, dx, 1);
            x += dx;
            let r = if x <= x1 {
                t2 + 2.0 * lim * (1.0 - (1.0 - (x - x2) / (2.0 * dm)).powf(1.5))
            } else {
                load(x)
            };
            worst = worst.max((t - r).abs());
        }
        assert!((drive(&mut p, g, a2, lim, dx, 1) - lim).abs() < 1e-12);
        assert!(worst < 1e-12 * lim, "largest deviation {worst}");
        assert!(p.len as usize <= 4, "{}", p.len);
    }

    /// No slip: a contact growing with `Δu` proportional to `ΔA` (slope
    /// below λ) carries `T = G̃∫u dx` of the ramp `u = s(A − ξ)`,
    /// `T = (4/3)G̃ s a³`, with one segment whatever the number of steps.
    #[test]
    fn proportional_growth_is_one_segment() {
        let (g, mu_n_per_a3) = (1.0e9, 2.0e9); // λ = 1.5 /m
        let s = 0.3; // du/dA, 1/m
        let mut p = SlipProfile::default();
        let mut a2: f64 = 0.0;
        for _ in 0..500 {
            let a2n = a2 + 1e-11;
            let mu_n = mu_n_per_a3 * a2n.powf(1.5);
            let (f, _) = mdr_tangential(
                &mut p,
                DVec3::Z,
                DVec3::new(s * (a2n - a2), 0.0, 0.0),
                1.0,
                a2n,
                g,
                1.0,
                mu_n,
            );
            a2 = a2n;
            let exact = 4.0 / 3.0 * g * s * a2.powf(1.5);
            assert!((-f.x - exact).abs() < 1e-10 * exact, "{} {exact}", -f.x);
        }
        assert_eq!(p.len, 1);
    }

    /// Gross sliding carries exactly μN along the motion; a contact whose
    /// normal force vanishes carries nothing.
    #[test]
    fn gross_sliding_and_release() {
        let mut p = SlipProfile::default();
        let (f, _) = mdr_tangential(
            &mut p,
            DVec3::Z,
            DVec3::new(1.0, 1.0, 0.0),
            1.0,
            1e-8,
            1e9,
            0.5,
            2.0,
        );
        let e = DVec3::new(1.0, 1.0, 0.0).normalize();
        assert!((f + e).length() < 1e-14, "{f}");
        let (f, _) = mdr_tangential(&mut p, DVec3::Z, DVec3::ZERO, 1.0, 1e-8, 1e9, 0.5, 0.0);
        assert_eq!(f, DVec3::ZERO);
        let (f, _) = mdr_tangential(&mut p, DVec3::Z, DVec3::X, 1.0, 0.0, 1e9, 0.5, 1.0);
        assert_eq!((f, p), (DVec3::ZERO, SlipProfile::default()));
    }

    /// Swapping i and j (profile and normal negated) gives the opposite
    /// force, step for step.
    #[test]
    fn swap_keeps_the_profile() {
        let mut a = SlipProfile::default();
        let mut b = SlipProfile::default();
        for k in 0..300 {
            let a2 = 1e-8 * (1.0 + (k as f64 * 0.03).sin().abs());
            let v = DVec3::new((k as f64 * 0.05).cos() * 1e-9, 0.3e-9, 0.0);
            let (fa, _) = mdr_tangential(
                &mut a,
                DVec3::Z,
                v,
                1.0,
                a2,
                1e9,
                0.3,
                1e3 * a2.powf(1.5) * 1e6,
            );
            let (fb, _) = mdr_tangential(
                &mut b,
                -DVec3::Z,
                -v,
                1.0,
                a2,
                1e9,
                0.3,
                1e3 * a2.powf(1.5) * 1e6,
            );
            assert!((fa + fb).length() <= 1e-12 * fa.length(), "{fa} {fb}");
            assert_eq!(a.reversed().u, b.u);
        }
    }
}
