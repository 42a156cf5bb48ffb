//! Micro-slip tangential model: Mindlin–Deresiewicz with loading, unloading
//! and reloading history, in the incremental form of Thornton & Yin (1991)
//! as restated by Thornton, Cummins & Cleary (2011), "An investigation of
//! the comparative behaviour of alternative contact force models during
//! elastic collisions", Powder Technol. 210, 189–197 (their "TY" tangential
//! model). Selected with `tangential = "mindlin_deresiewicz"`
//! ([`super::TangentialLaw::MindlinDeresiewicz`]); docs/theory.md (T-49).
//!
//! # Equations (1-D, along the loading direction `e`)
//! With the contact radius `a = √(R*δ)`, `G*` the effective shear modulus,
//! `N` the normal force, `ΔN = N − N_old` its change over the step, `Δδ`
//! the tangential displacement increment (`v_t Δt`) and `T` the tangential
//! force that resists it (the force on `i` is `−T`):
//!
//! ```text
//! ΔT = 8G* a θ Δδ + (−1)^k μ ΔN (1 − θ)        k = 1 unloading, 0 otherwise
//! loading:    θ³ = 1 − (T + μΔN)/(μN)
//! unloading:  θ³ = 1 − (T* − T + 2μΔN)/(2μN)
//! reloading:  θ³ = 1 − (T − T** + 2μΔN)/(2μN)
//! θ = 1 when |8G*a Δδ| < μΔN (ΔN > 0: the new annulus sticks, no micro-slip)
//! T* ← T* + μΔN,  T** ← T** − μΔN          (turning points follow N)
//! |T| ≤ μN                                  (gross sliding)
//! ```
//!
//! `T*` is the force where loading turned into unloading, `T**` where
//! unloading turned into reloading. Reloading becomes loading again when
//! `T` reaches `T*`; unloading that reaches `−μN` (full reverse slip) is
//! loading in the opposite direction. A reversal during reloading starts a
//! new unloading from the current force (the scheme keeps one loop). The
//! arguments of the cube roots are clamped to `[0, 1]`. At constant `N`
//! this integrates to Mindlin–Deresiewicz's closed forms (unit tests):
//! loading `T = μN(1 − (1 − δ_t/δ_μ)^{3/2})`, `δ_μ = 3μN/(16G*a)`, and the
//! unloading and reloading branches by Masing's rule (the loading curve
//! scaled by two about the turning point).
//!
//! # Clump's choices (not in the source)
//! - `N` is the pair's normal force after the tensile clamp, `|F_n|` (the
//!   same force the Coulomb limit of the other rules uses); `N_old`, the
//!   normal force of the previous step, is re-evaluated at the previous
//!   overlap `δ + v_nΔt` with the current normal velocity (the history has
//!   no slot for it; for an elastic contact it is the elastic force at the
//!   previous overlap exactly).
//! - In 3-D the scheme runs along the direction of the tangential force:
//!   `Δδ` is the vector increment, the mode (loading, unloading, reloading)
//!   follows from the sign of its component along `e`, and the `ΔN` term
//!   acts along `e`. For a straight tangential path (every test below) it
//!   is the 1-D scheme exactly.
//! - No tangential dashpot (the model's dissipation is the micro-slip); the
//!   stored energy is reported as `|T|²/(2·8G*a)`.
//!
//! # Storage
//! The history has two vector slots ([`super::ContactHistory`]); this
//! model uses both, so it cannot be combined with EPSD rolling or twisting
//! resistance ([`super::ContactModel::new`] refuses the pair):
//! - `tangential = T + c n_old`: the force `T` (N, in the tangent plane)
//!   and, along the normal of the step that wrote it, `c = T** + μN ≥ 0`
//!   (reloading; 0 otherwise);
//! - `rolling = q n_old`, a pure normal vector: `|q| = μN − T*` (unloading
//!   or reloading; 0 while loading) and `sign q` tells whether `e` is along
//!   `T` or against it.
//!
//! `T* − μN` and `T** + μN` are the invariants of the turning-point updates,
//! so no old normal force is stored. `rolling` gives `n_old` exactly
//! (`|q|` is kept ≥ 10⁻²⁰⁰ N while a turning point exists), so `c` and `T`
//! separate exactly; `T` is then rotated into the current tangent plane as
//! the default spring is ([`rotate_into_plane`]). Swapping `i` and `j`
//! negates both slots and the normal, which leaves `q`, `c` and the loop
//! unchanged (the force on `j` is `−T`).

use super::tangential::rotate_into_plane;
use super::ContactHistory;
use glam::DVec3;

/// Smallest stored `|q|`, N: keeps the sign and `n_old` of a turning point
/// at the sliding limit.
const Q_FLOOR: f64 = 1e-200;

/// The loading state of the loop (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    Loading,
    Unloading,
    Reloading,
}

/// The decoded history: force `T` (N, current tangent plane), the
/// direction `e`, the mode, `A* = T* − μN` and `B** = T** + μN` (N).
struct Loop {
    t: DVec3,
    e: DVec3,
    mode: Mode,
    a_star: f64,
    b_star: f64,
}

fn decode(h: &ContactHistory, n: DVec3) -> Loop {
    let q_abs = h.rolling.length();
    let (n_old, q) = if q_abs > 0.0 {
        let s = if h.rolling.dot(n) < 0.0 { -1.0 } else { 1.0 };
        (h.rolling * (s / q_abs), s * q_abs)
    } else {
        (n, 0.0)
    };
    let c = h.tangential.dot(n_old);
    let t = rotate_into_plane(h.tangential - c * n_old, n);
    let tl = t.length();
    if q == 0.0 || tl == 0.0 {
        return Loop {
            t,
            e: if tl > 0.0 { t / tl } else { DVec3::ZERO },
            mode: Mode::Loading,
            a_star: 0.0,
            b_star: 0.0,
        };
    }
    Loop {
        t,
        e: t * (q.signum() / tl),
        mode: if c > 0.0 {
            Mode::Reloading
        } else {
            Mode::Unloading
        },
        a_star: -q.abs(),
        b_star: c.max(0.0),
    }
}

fn encode(h: &mut ContactHistory, n: DVec3, l: &Loop) {
    let tl = l.t.length();
    if l.mode == Mode::Loading || tl == 0.0 {
        h.tangential = l.t;
        h.rolling = DVec3::ZERO;
        return;
    }
    let s = if l.e.dot(l.t) < 0.0 { -1.0 } else { 1.0 };
    h.rolling = (s * (-l.a_star).max(Q_FLOOR)) * n;
    let c = if l.mode == Mode::Reloading {
        l.b_star.max(Q_FLOOR)
    } else {
        0.0
    };
    h.tangential = l.t + c * n;
}

/// The micro-slip tangential force on `i` (N, world) and the stored energy
/// (J), updating the history `h` (both slots; module docs, "Storage").
///
/// - `n`: unit normal (world); `v_t`: tangential relative velocity of the
///   contact points (m/s, world, in the tangent plane); `dt` (s);
/// - `k0`: the no-slip Mindlin stiffness `8G*a` (N/m, ≥ 0);
/// - `mu`: friction coefficient; `f_n`, `f_n_old`: the normal force now
///   and at the previous step (N, ≥ 0).
#[allow(clippy::too_many_arguments)]
pub fn micro_slip(
    h: &mut ContactHistory,
    n: DVec3,
    v_t: DVec3,
    dt: f64,
    k0: f64,
    mu: f64,
    f_n: f64,
    f_n_old: f64,
) -> (DVec3, f64) {
    let lim = mu * f_n;
    if !(k0 > 0.0 && lim > 0.0) {
        *h = ContactHistory::default();
        return (DVec3::ZERO, 0.0);
    }
    let mut l = decode(h, n);
    let dd = v_t * dt;
    let dn = mu * (f_n - f_n_old); // μΔN
    let lim_old = mu * f_n_old;
    if l.e == DVec3::ZERO {
        let m = dd.length();
        if m > 0.0 {
            l.e = dd / m;
        }
    }
    let p = l.t.dot(l.e);
    let d = dd.dot(l.e);
    // reversals
    match l.mode {
        Mode::Loading if d < 0.0 => {
            if p > 0.0 {
                l.mode = Mode::Unloading;
                l.a_star = p - lim_old;
            } else {
                l.e = -l.e;
            }
        }
        Mode::Unloading if d > 0.0 => {
            l.mode = Mode::Reloading;
            l.b_star = p + lim_old;
        }
        Mode::Reloading if d < 0.0 => {
            l.mode = Mode::Unloading;
            l.a_star = p - lim_old;
        }
        _ => {}
    }
    let p = l.t.dot(l.e);
    let (arg, sign) = match l.mode {
        Mode::Loading => (1.0 - (p + dn) / lim, 1.0),
        Mode::Unloading => {
            let t_star = l.a_star + lim_old;
            (1.0 - (t_star - p + 2.0 * dn) / (2.0 * lim), -1.0)
        }
        Mode::Reloading => {
            let t_star2 = l.b_star - lim_old;
            (1.0 - (p - t_star2 + 2.0 * dn) / (2.0 * lim), 1.0)
        }
    };
    let theta = if dn > 0.0 && k0 * dd.length() < dn {
        1.0
    } else {
        arg.clamp(0.0, 1.0).cbrt()
    };
    l.t += k0 * theta * dd + (sign * dn * (1.0 - theta)) * l.e;
    // leaving the loop
    let p = l.t.dot(l.e);
    match l.mode {
        Mode::Reloading if p >= l.a_star + lim => l.mode = Mode::Loading,
        Mode::Unloading if p <= -lim => l.mode = Mode::Loading,
        _ => {}
    }
    // gross sliding
    let tl = l.t.length();
    if tl > lim {
        l.t *= lim / tl;
        l.mode = Mode::Loading;
    }
    if l.mode == Mode::Loading {
        let tl = l.t.length();
        if tl > 0.0 {
            l.e = l.t / tl;
        }
    }
    encode(h, n, &l);
    (-l.t, 0.5 * l.t.length_squared() / k0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Drives one contact at constant `N` along x by `steps` increments of
    /// `dx` (m) each; returns the force resisting the displacement (N).
    fn drive(h: &mut ContactHistory, k0: f64, lim: f64, dx: f64, steps: usize) -> f64 {
        let mut t = 0.0;
        for _ in 0..steps {
            let (f, _) = micro_slip(
                h,
                DVec3::Z,
                DVec3::new(dx, 0.0, 0.0),
                1.0,
                k0,
                1.0,
                lim,
                lim,
            );
            t = -f.x;
        }
        t
    }

    /// Mindlin–Deresiewicz at constant N: loading `T = μN(1 − (1 − δ/δ_μ)^{3/2})`
    /// with `δ_μ = 3μN/(2k0)`; unloading from `(δ*, T*)` by Masing's rule
    /// `T = T* − 2μN(1 − (1 − (δ* − δ)/(2δ_μ))^{3/2})`; reloading from
    /// `(δ**, T**)` `T = T** + 2μN(1 − (1 − (δ − δ**)/(2δ_μ))^{3/2})`, which
    /// returns to `(δ*, T*)` and continues on the loading curve.
    #[test]
    fn mindlin_deresiewicz_constant_normal_force() {
        let (k0, lim) = (1.0e6, 1.0); // 8G*a, μN
        let dm = 1.5 * lim / k0;
        let load = |x: f64| lim * (1.0 - (1.0 - x / dm).max(0.0).powf(1.5));
        let steps = 200_000;
        let dx = 0.8 * dm / steps as f64;
        let mut h = ContactHistory::default();
        let mut worst: f64 = 0.0;
        let mut x = 0.0;
        // loading to 0.8 δ_μ
        for _ in 0..steps {
            let t = drive(&mut h, k0, lim, dx, 1);
            x += dx;
            worst = worst.max((t - load(x)).abs());
        }
        let (x1, t1) = (x, load(x));
        // unloading by 1.2 δ_μ (to below zero force)
        for _ in 0..(1.5 * steps as f64) as usize {
            let t = drive(&mut h, k0, lim, -dx, 1);
            x -= dx;
            let r = t1 - 2.0 * lim * (1.0 - (1.0 - (x1 - x) / (2.0 * dm)).powf(1.5));
            worst = worst.max((t - r).abs());
        }
        let (x2, t2) = (
            x,
            t1 - 2.0 * lim * (1.0 - (1.0 - (x1 - x) / (2.0 * dm)).powf(1.5)),
        );
        assert!(t2 < 0.0, "{t2}");
        // reloading past the first turning point
        for _ in 0..(2.0 * steps as f64) as usize {
            let t = drive(&mut h, k0, lim, dx, 1);
            x += dx;
            let r = if x <= x1 {
                t2 + 2.0 * lim * (1.0 - (1.0 - (x - x2) / (2.0 * dm)).powf(1.5))
            } else {
                load(x)
            };
            worst = worst.max((t - r).abs());
        }
        // at the end: full slip at μN
        assert!((drive(&mut h, k0, lim, dx, 1) - lim).abs() < 1e-12);
        eprintln!("MD cycle: largest deviation {:.2e} muN", worst / lim);
        assert!(worst < 1e-5 * lim, "max deviation {worst}");
    }

    /// The first-step stiffness is Mindlin's `8G*a`, and the loading curve
    /// converges to the closed form at first order in the increment.
    #[test]
    fn initial_stiffness_and_convergence() {
        let (k0, lim) = (1.0e6, 1.0);
        let dm = 1.5 * lim / k0;
        let mut h = ContactHistory::default();
        let t = drive(&mut h, k0, lim, 1e-12, 1);
        assert!((t - k0 * 1e-12).abs() < 1e-18);
        let err = |steps: usize| {
            let mut h = ContactHistory::default();
            let t = drive(&mut h, k0, lim, 0.5 * dm / steps as f64, steps);
            (t - lim * (1.0 - 0.5f64.powf(1.5))).abs()
        };
        let (e1, e2) = (err(1000), err(2000));
        assert!(e2 < 0.6 * e1 && e2 < 1e-4, "{e1} {e2}");
    }

    /// Swapping i and j (both slots and the normal negated) keeps the loop:
    /// the force on the other side is the negative, step for step.
    #[test]
    fn swap_keeps_the_loop() {
        let (k0, lim) = (1.0e6, 1.0);
        let dx = 1e-8;
        let mut a = ContactHistory::default();
        drive(&mut a, k0, lim, dx, 100);
        drive(&mut a, k0, lim, -dx, 150);
        drive(&mut a, k0, lim, dx, 20); // reloading
        let mut b = ContactHistory {
            tangential: -a.tangential,
            rolling: -a.rolling,
        };
        for k in 0..200 {
            let v = DVec3::new(if k < 100 { dx } else { -dx }, 0.0, 0.0);
            let (fa, _) = micro_slip(&mut a, DVec3::Z, v, 1.0, k0, 1.0, lim, lim);
            let (fb, _) = micro_slip(&mut b, -DVec3::Z, -v, 1.0, k0, 1.0, lim, lim);
            assert!((fa + fb).length() < 1e-15, "{fa} {fb}");
        }
    }

    /// Growing N with no tangential motion leaves T unchanged (θ = 1 branch),
    /// and the sliding limit follows μN.
    #[test]
    fn growing_normal_force_alone_does_not_load() {
        let mut h = ContactHistory::default();
        let v = DVec3::new(1e-8, 0.0, 0.0);
        micro_slip(&mut h, DVec3::Z, v, 1.0, 1e6, 0.5, 1.0, 1.0);
        let t0 = h.tangential;
        micro_slip(&mut h, DVec3::Z, DVec3::ZERO, 1.0, 1e6, 0.5, 1.5, 1.0);
        assert_eq!(h.tangential, t0);
        // pushed far: gross sliding at μN
        let (f, _) = micro_slip(&mut h, DVec3::Z, v * 1e4, 1.0, 1e6, 0.5, 1.5, 1.5);
        assert!((f.length() - 0.75).abs() < 1e-15);
    }
}
