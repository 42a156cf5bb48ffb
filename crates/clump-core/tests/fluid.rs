//! Particles in a fluid (docs/theory.md §16) against closed forms written
//! here from the papers, independently of `clump_core::fluid`: the terminal
//! velocity of a sphere for each drag law, hindered settling against
//! Richardson & Zaki (1954), a clump against its volume-equivalent sphere
//! with the Hölzer–Sommerfeld correction, the stability of the drag when
//! the particle response time is shorter than the step, and the external
//! loads a coupled code sets.

mod common;
use clump_core::body::BodyInit;
use clump_core::contact::{Material, PairProperties};
use clump_core::fluid::void::{VoidField, VoidGrid};
use clump_core::fluid::{DragLaw, Fluid, VelocityGrid};
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::world::World;
use common::*;
use glam::{DQuat, DVec3};
use std::f64::consts::PI;

const G: f64 = 9.81;
const RHO_P: f64 = 2500.0;
const RHO_F: f64 = 1000.0;
const MU: f64 = 1e-3;

fn glass() -> Material {
    Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: RHO_P,
    }
}

fn water(drag: DragLaw) -> Fluid {
    Fluid {
        density: RHO_F,
        viscosity: MU,
        velocity: DVec3::ZERO,
        pressure_gradient: DVec3::ZERO,
        drag,
        buoyancy: true,
    }
}

/// A world holding one body of template `t` at rest at the origin, in
/// `fluid`, with step `dt`.
fn settling(t: ClumpTemplate, fluid: Fluid, dt: f64) -> World {
    let mut w = world(
        glass(),
        PairProperties::default(),
        dt,
        open_domain(100.0),
        DVec3::new(0.0, 0.0, -G),
    );
    let ti = w.add_template(t, 0).unwrap();
    w.add_body(&BodyInit::at_rest(ti, DVec3::ZERO, DQuat::IDENTITY))
        .unwrap();
    w.set_fluid(Some(fluid)).unwrap();
    w
}

fn sphere(d: f64) -> ClumpTemplate {
    ClumpTemplate::from_spheres("sphere", &[Sphere::new(DVec3::ZERO, d / 2.0)], RHO_P).unwrap()
}

/// Steps until the settling speed changes by less than 1e-12 of itself in
/// 100 steps; returns it (m/s, downwards positive).
fn terminal(w: &mut World, max_steps: usize) -> f64 {
    let mut last = f64::INFINITY;
    for k in 0..max_steps {
        w.step().unwrap();
        if k % 100 == 99 {
            let v = -w.bodies().velocity[0].z;
            if (v - last).abs() <= 1e-12 * v.abs() {
                return v;
            }
            last = v;
        }
    }
    panic!("no terminal velocity in {max_steps} steps (last {last})");
}

/// The speed `v` where `drag(v) = (ρ_p − ρ_f) V g`, by bisection.
fn balance(d: f64, drag: impl Fn(f64) -> f64) -> f64 {
    let weight = (RHO_P - RHO_F) * PI / 6.0 * d.powi(3) * G;
    let (mut lo, mut hi) = (0.0, 100.0);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if drag(mid) < weight {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Drag from a drag coefficient: `½ ρ C_d (π d²/4) v²`.
fn cd_drag(d: f64, v: f64, cd: f64) -> f64 {
    0.5 * RHO_F * cd * PI * d * d / 4.0 * v * v
}

/// Reynolds number of the single particle.
fn re(d: f64, v: f64) -> f64 {
    RHO_F * v * d / MU
}

/// Schiller & Naumann (1933), Re < 1000.
fn cd_schiller_naumann(re: f64) -> f64 {
    24.0 / re * (1.0 + 0.15 * re.powf(0.687))
}

/// Dallavalle (1948), as Di Felice (1994) uses it.
fn cd_dallavalle(re: f64) -> f64 {
    (0.63 + 4.8 / re.sqrt()).powi(2)
}

/// Beetstra et al. (2007) at zero solids fraction: `F/F_Stokes`.
fn beetstra_single(re: f64) -> f64 {
    1.0 + 0.413 * re / 24.0 * (1.0 + 8.4 * re.powf(-0.343)) / (1.0 + re.powf(-0.5))
}

fn check(law: DragLaw, d: f64, dt: f64, expected: f64) {
    let mut w = settling(sphere(d), water(law), dt);
    let v = terminal(&mut w, 200_000);
    let err = rel(v, expected);
    println!(
        "{law:?}: d = {d} m, v_t = {v:.6e} m/s, closed form {expected:.6e}, rel. error {err:.2e}"
    );
    assert!(err < 0.01, "{law:?}: {v} against {expected}");
}

#[test]
fn terminal_velocity_stokes() {
    // v_t = (ρ_p − ρ_f) g d² / (18 μ) (Stokes 1851)
    let d = 50e-6;
    let vt = (RHO_P - RHO_F) * G * d * d / (18.0 * MU);
    check(DragLaw::Stokes, d, 1e-5, vt);
}

#[test]
fn terminal_velocity_schiller_naumann() {
    let d = 1e-3;
    let vt = balance(d, |v| cd_drag(d, v, cd_schiller_naumann(re(d, v))));
    assert!(re(d, vt) > 50.0 && re(d, vt) < 1000.0, "Re {}", re(d, vt));
    check(DragLaw::SchillerNaumann, d, 1e-4, vt);
}

#[test]
fn terminal_velocity_di_felice_is_dallavalle_at_eps_1() {
    let d = 1e-3;
    let vt = balance(d, |v| cd_drag(d, v, cd_dallavalle(re(d, v))));
    check(DragLaw::DiFelice, d, 1e-4, vt);
}

#[test]
fn terminal_velocity_beetstra_at_eps_1() {
    let d = 1e-3;
    let vt = balance(d, |v| 3.0 * PI * MU * d * v * beetstra_single(re(d, v)));
    check(DragLaw::Beetstra, d, 1e-4, vt);
}

#[test]
fn terminal_velocity_gidaspow_is_wen_yu_at_eps_1() {
    // Wen & Yu at ε = 1 is Schiller–Naumann
    let d = 1e-3;
    let vt = balance(d, |v| cd_drag(d, v, cd_schiller_naumann(re(d, v))));
    check(DragLaw::Gidaspow, d, 1e-4, vt);
}

/// The drag is stable and exact at the terminal velocity with a step five
/// times the particle response time `τ = ρ_p d²/(18 μ)`, where an explicit
/// drag (amplification `1 − dt/τ` per step) would diverge.
#[test]
fn drag_stable_for_response_time_below_step() {
    let d = 50e-6;
    let tau = RHO_P * d * d / (18.0 * MU);
    let vt = (RHO_P - RHO_F) * G * d * d / (18.0 * MU);
    let mut w = settling(sphere(d), water(DragLaw::Stokes), 5.0 * tau);
    let mut max = 0.0f64;
    for _ in 0..200 {
        w.step().unwrap();
        max = max.max(-w.bodies().velocity[0].z);
    }
    let v = -w.bodies().velocity[0].z;
    println!("dt/τ = 5: v = {v:.6e}, closed form {vt:.6e}, largest {max:.6e}");
    assert!(rel(v, vt) < 1e-9, "{v} against {vt}");
    assert!(max < 1.01 * vt, "overshoot to {max}");
}

/// Hindered settling of a uniform suspension at void fraction ε: one
/// sphere stands for all, the fluid's pressure gradient carries the
/// suspension's weight (`∇p = ρ_mix g`, the excess over the hydrostatic
/// `ρ_f g` given as `pressure_gradient`), and the fluid moves up so that
/// the net volume flux is zero, `ε u + (1 − ε) v = 0` (a one-line fluid
/// solver, called at every step through the coupling methods). Richardson
/// & Zaki (1954): `v/v_t = εⁿ`, `n ≈ 4.65` for `Re < 0.2`; Di Felice's law
/// gives `n → 1 + χ = 4.7` as `Re → 0`. At `d = 10 µm` (`Re_t ≈ 4·10⁻³`);
/// at `d = 50 µm` (`Re_t ≈ 0.09`) the law gives `n` = 4.55 to 4.59, as
/// Dallavalle's `C_d Re = (0.63 √Re + 4.8)²` falls with the slip `Re`
/// (docs/theory.md T-62).
#[test]
fn hindered_settling_richardson_zaki() {
    let d = 10e-6;
    let v1 = settle_hindered(d, 1.0);
    for eps in [0.6, 0.8] {
        let v = settle_hindered(d, eps);
        let n = (v / v1).ln() / eps.ln();
        println!(
            "ε = {eps}: v/v_t = {:.4}, n = {n:.3} (Richardson–Zaki 4.65)",
            v / v1
        );
        assert!((n - 4.65).abs() < 0.1, "n = {n} at ε = {eps}");
    }
}

fn settle_hindered(d: f64, eps: f64) -> f64 {
    settle_hindered_in(d, eps, |w| w.set_body_void_fractions(&[eps]).unwrap())
}

/// The steady settling speed at void fraction `eps` (given to the world
/// by `set_eps`), the fluid moving up to conserve volume.
fn settle_hindered_in(d: f64, eps: f64, set_eps: impl Fn(&mut World)) -> f64 {
    let mut fluid = water(DragLaw::DiFelice);
    fluid.pressure_gradient = DVec3::new(0.0, 0.0, -(1.0 - eps) * (RHO_P - RHO_F) * G);
    let mut w = settling(sphere(d), fluid, 2e-5);
    set_eps(&mut w);
    let mut last = f64::INFINITY;
    for k in 0..100_000 {
        let v = w.bodies().velocity[0];
        w.set_body_fluid_velocities(&[-(1.0 - eps) / eps * v])
            .unwrap();
        w.step().unwrap();
        if k % 100 == 99 {
            let s = -w.bodies().velocity[0].z;
            if (s - last).abs() <= 1e-12 * s {
                return s;
            }
            last = s;
        }
    }
    panic!("no steady settling at ε = {eps}");
}

/// Two overlapping spheres (radius r, centres s apart): union volume and
/// surface area in closed form, `V = 2 (4/3 π r³) − π (4r + s)(2r − s)²/12`,
/// `A = 2 (4π r²) − 2 (2π r h)`, `h = r − s/2`.
fn dumbbell(r: f64, s: f64) -> (ClumpTemplate, f64, f64) {
    let spheres = [
        Sphere::new(DVec3::new(-s / 2.0, 0.0, 0.0), r),
        Sphere::new(DVec3::new(s / 2.0, 0.0, 0.0), r),
    ];
    let t = ClumpTemplate::from_spheres("dumbbell", &spheres, RHO_P).unwrap();
    let v = 2.0 * 4.0 / 3.0 * PI * r.powi(3) - PI * (4.0 * r + s) * (2.0 * r - s).powi(2) / 12.0;
    let a = 2.0 * 4.0 * PI * r * r - 2.0 * 2.0 * PI * r * (r - s / 2.0);
    (t, v, a)
}

/// Hölzer & Sommerfeld (2008), their eq. (15).
fn cd_holzer_sommerfeld(re: f64, phi: f64, phi_perp: f64) -> f64 {
    8.0 / re / phi_perp.sqrt()
        + 16.0 / re / phi.sqrt()
        + 3.0 / re.sqrt() / phi.powf(0.75)
        + 0.42 * 10f64.powf(0.4 * (-phi.log10()).powf(0.2)) / phi_perp
}

/// A dumbbell clump and its volume-equivalent sphere settle under the
/// Schiller–Naumann law: the sphere at the law's terminal velocity, the
/// clump slower by the Hölzer–Sommerfeld ratio of its sphericity (taken
/// as the crosswise one too), found here from the closed-form volume and
/// area of the union.
#[test]
fn clump_against_volume_equivalent_sphere() {
    let (r, s) = (0.5e-3, 0.8e-3);
    let (t, vol, area) = dumbbell(r, s);
    let dv = (6.0 * vol / PI).cbrt();
    let phi = PI * dv * dv / area;
    let mut w = settling(t, water(DragLaw::SchillerNaumann), 1e-4);
    let tf = w.template_fluid(0).unwrap();
    println!(
        "dumbbell: φ = {:.5} (closed form {phi:.5}), d_v = {:.6e} ({dv:.6e})",
        tf.sphericity, tf.diameter
    );
    assert!((tf.sphericity - phi).abs() < 1e-3);
    assert!(rel(tf.diameter, dv) < 1e-3);
    let v_clump = terminal(&mut w, 200_000);
    let mut ws = settling(sphere(dv), water(DragLaw::SchillerNaumann), 1e-4);
    let v_sphere = terminal(&mut ws, 200_000);
    let k = |v: f64| {
        cd_holzer_sommerfeld(re(dv, v), phi, phi) / cd_holzer_sommerfeld(re(dv, v), 1.0, 1.0)
    };
    let expected = balance(dv, |v| {
        cd_drag(dv, v, cd_schiller_naumann(re(dv, v)) * k(v))
    });
    let sphere_cf = balance(dv, |v| cd_drag(dv, v, cd_schiller_naumann(re(dv, v))));
    println!(
        "v_clump = {v_clump:.6e} (closed form {expected:.6e}), v_sphere = {v_sphere:.6e} ({sphere_cf:.6e}), ratio {:.4} (predicted {:.4})",
        v_clump / v_sphere,
        expected / sphere_cf
    );
    assert!(rel(v_clump, expected) < 0.01);
    assert!(rel(v_sphere, sphere_cf) < 0.01);
    assert!(
        v_clump < 0.99 * v_sphere,
        "the shape correction slows the clump"
    );
}

/// A persistent external force `F` on a free body (no gravity) gives
/// `v = F t / m` exactly (velocity Verlet is exact for a constant force);
/// a next-step-only force gives the impulse `F dt` once.
#[test]
fn external_loads_persistent_and_next_step() {
    let d = 1e-3;
    let mut w = world(
        glass(),
        PairProperties::default(),
        1e-4,
        open_domain(100.0),
        DVec3::ZERO,
    );
    let ti = w.add_template(sphere(d), 0).unwrap();
    for x in [-0.1, 0.1] {
        w.add_body(&BodyInit::at_rest(
            ti,
            DVec3::new(x, 0.0, 0.0),
            DQuat::IDENTITY,
        ))
        .unwrap();
    }
    let m = w.bodies().mass[0];
    w.prepare().unwrap();
    let f = DVec3::new(1e-6, 0.0, 0.0);
    let i0 = w.bodies().id.iter().position(|&id| id == 1).unwrap();
    w.set_external_load_at(i0, f, DVec3::ZERO).unwrap();
    let mut once = vec![DVec3::ZERO; 2];
    once[1 - i0] = f;
    w.set_next_step_loads(&once, &[DVec3::ZERO; 2]).unwrap();
    for _ in 0..10 {
        w.step().unwrap();
    }
    let dt = w.config.dt;
    let (k0, k1) = (w.body_index(1).unwrap(), w.body_index(2).unwrap());
    // the first step's first half kick used the load of the evaluation before the force was set
    let v_persistent = f.x * (10.0 * dt - 0.5 * dt) / m;
    let v_once = f.x * dt / m;
    println!(
        "persistent {:.6e} ({v_persistent:.6e}), once {:.6e} ({v_once:.6e})",
        w.bodies().velocity[k0].x,
        w.bodies().velocity[k1].x
    );
    assert!(rel(w.bodies().velocity[k0].x, v_persistent) < 1e-12);
    assert!(rel(w.bodies().velocity[k1].x, v_once) < 1e-12);
    assert!(
        w.set_external_loads(&[f], &[DVec3::ZERO]).is_err(),
        "one entry for two bodies"
    );
}

#[test]
fn bad_fluid_values_are_refused() {
    let mut w = settling(sphere(1e-3), water(DragLaw::Stokes), 1e-4);
    let mut f = water(DragLaw::Stokes);
    f.viscosity = -1.0;
    let e = w.set_fluid(Some(f)).unwrap_err().to_string();
    assert!(e.contains("viscosity"), "{e}");
    assert!(w.set_body_void_fractions(&[1.5]).is_err());
    assert_eq!(DragLaw::from_name("darcy"), None);
    assert_eq!(DragLaw::from_name("di_felice"), Some(DragLaw::DiFelice));
}

/// The void fraction on a grid (T-69): a sphere centred on the corner
/// shared by eight cells puts `V/8` in each (the lattice is symmetric), a
/// sphere inside one cell puts its whole volume there, and a dumbbell's
/// solid volume is its union's closed form to the lattice's resolution.
#[test]
fn void_fraction_on_a_grid() {
    let h: f64 = 0.01;
    let grid = VoidGrid {
        lo: DVec3::splat(-h),
        cell: DVec3::splat(h),
        n: [2, 2, 2],
        periodic: [false; 3],
    };
    let r: f64 = 0.004;
    let v = 4.0 / 3.0 * PI * r.powi(3);
    let mut out = Vec::new();
    grid.void_fraction([vec![(DVec3::ZERO, r)]], &mut out);
    for e in &out {
        assert!((e - (1.0 - v / 8.0 / h.powi(3))).abs() < 1e-12, "{e}");
    }
    grid.void_fraction([vec![(DVec3::splat(-0.005), r)]], &mut out);
    assert!((out[0] - (1.0 - v / h.powi(3))).abs() < 1e-12 && out[1..].iter().all(|&e| e == 1.0));
    let (s, rd) = (0.003, 0.002);
    let (_, vu, _) = dumbbell(rd, s);
    let c = DVec3::splat(-0.005);
    grid.void_fraction(
        [vec![
            (c - DVec3::X * s / 2.0, rd),
            (c + DVec3::X * s / 2.0, rd),
        ]],
        &mut out,
    );
    let solid = (1.0 - out[0]) * h.powi(3);
    println!(
        "dumbbell solid volume {solid:.6e}, union closed form {vu:.6e}, rel. {:.2e}",
        rel(solid, vu)
    );
    assert!(rel(solid, vu) < 0.03);
}

/// The nodes of the grid `x_i = o + i h` (`n` nodes an axis) with the
/// velocity `u(x)`.
fn grid_nodes(o: DVec3, h: DVec3, n: [usize; 3], u: impl Fn(DVec3) -> DVec3) -> VelocityGrid {
    let mut nodes = Vec::new();
    // z slowest, then x, then y: the grid must not depend on the order
    for k in 0..n[2] {
        for i in 0..n[0] {
            for j in 0..n[1] {
                let p = o + DVec3::new(i as f64, j as f64, k as f64) * h;
                nodes.push((p, u(p)));
            }
        }
    }
    VelocityGrid::from_nodes(&nodes).unwrap()
}

#[test]
fn velocity_grid_interpolates_a_linear_field_exactly() {
    // trilinear interpolation reproduces any field linear in x, y, z;
    // u = (a z, b x + c y, 0), s⁻¹ times m
    let (a, b, c) = (3.0, -1.5, 0.25);
    let u = |p: DVec3| DVec3::new(a * p.z, b * p.x + c * p.y, 0.0);
    let o = DVec3::new(-0.1, -0.2, 0.05);
    let h = DVec3::new(0.05, 0.1, 0.0375);
    let g = grid_nodes(o, h, [5, 3, 9], u);
    let (lo, hi) = g.bounds();
    assert!(
        (lo - o).length() < 1e-15 && (hi - (o + h * DVec3::new(4.0, 2.0, 8.0))).length() < 1e-15
    );
    let mut s = 0x2545_f491_4f6c_dd1du64;
    let mut r = || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64
    };
    for _ in 0..1000 {
        let p = lo + DVec3::new(r(), r(), r()) * (hi - lo);
        let e = g.sample(p) - u(p);
        assert!(e.length() < 1e-14, "at {p}: {} vs {}", g.sample(p), u(p));
    }
    // outside the grid: the value at the nearest point of it
    let q = DVec3::new(0.0, 0.0, 1.0);
    assert!((g.sample(q) - u(DVec3::new(0.0, 0.0, hi.z))).length() < 1e-14);
}

#[test]
fn velocity_grid_refuses_an_irregular_grid() {
    let p = |x: f64| (DVec3::new(x, 0.0, 0.0), DVec3::ZERO);
    let e = VelocityGrid::from_nodes(&[p(0.0), p(1.0), p(3.0)]).unwrap_err();
    assert!(e.contains("not equally spaced"), "{e}");
    let q = |x: f64, y: f64| (DVec3::new(x, y, 0.0), DVec3::ZERO);
    let e = VelocityGrid::from_nodes(&[q(0.0, 0.0), q(1.0, 0.0), q(0.0, 1.0)]).unwrap_err();
    assert!(e.contains("need 4 nodes, found 3"), "{e}");
}

#[test]
fn settling_in_a_uniform_grid_field_matches_the_uniform_velocity() {
    // a Stokes sphere in an upward flow U: terminal velocity U − v_t
    // (Stokes 1851, v_t = (ρ_p − ρ_f) g d² / 18 μ); the same flow given as
    // a grid gives the same bits (the interpolation returns a uniform
    // field exactly)
    let d = 50e-6;
    let up = 2e-3;
    let vt = (RHO_P - RHO_F) * G * d * d / (18.0 * MU);
    let mut f = water(DragLaw::Stokes);
    f.velocity = DVec3::new(0.0, 0.0, up);
    let mut uniform = settling(sphere(d), f, 1e-5);
    let mut gridded = settling(sphere(d), water(DragLaw::Stokes), 1e-5);
    let u = DVec3::new(0.0, 0.0, up);
    let g = grid_nodes(DVec3::splat(-1.0), DVec3::splat(0.5), [5, 5, 5], |_| u);
    gridded
        .set_fluid_velocity_grid(Some(std::sync::Arc::new(g)))
        .unwrap();
    for _ in 0..3000 {
        uniform.step().unwrap();
        gridded.step().unwrap();
    }
    let (a, b) = (uniform.bodies(), gridded.bodies());
    assert_eq!(
        a.velocity[0].to_array().map(f64::to_bits),
        b.velocity[0].to_array().map(f64::to_bits)
    );
    assert_eq!(
        a.position[0].to_array().map(f64::to_bits),
        b.position[0].to_array().map(f64::to_bits)
    );
    let v = b.velocity[0].z;
    assert!((v - (up - vt)).abs() < 1e-9 * vt, "{v} vs {}", up - vt);
}

/// A 1 × 1 × 2 void-fraction field around the origin: `eps` in the upper
/// cell (z in [−5, 5) mm, holding a body near the origin), 0.3 below it.
fn two_cell_field(eps: f64, shift: DVec3) -> std::sync::Arc<VoidField> {
    let grid = VoidGrid {
        lo: DVec3::new(-0.005, -0.005, -0.015) + shift,
        cell: DVec3::splat(0.01),
        n: [1, 1, 2],
        periodic: [false; 3],
    };
    std::sync::Arc::new(VoidField::new(grid, vec![0.3, eps]).unwrap())
}

#[test]
fn void_fraction_field_gives_hindered_settling() {
    // a field set by a CFD code is read at the body: Richardson & Zaki
    // (1954), n ≈ 4.65 at low Re, and the same bits as the value set per body
    let d = 10e-6;
    let v1 = settle_hindered(d, 1.0);
    let eps = 0.8;
    let v = settle_hindered_in(d, eps, |w| {
        w.set_void_fraction_field(Some(two_cell_field(eps, DVec3::ZERO)))
            .unwrap()
    });
    let n = (v / v1).ln() / f64::ln(eps);
    println!(
        "field ε = {eps}: v/v_t = {:.4}, n = {n:.3} (Richardson–Zaki 4.65)",
        v / v1
    );
    assert!((n - 4.65).abs() < 0.1, "n = {n}");
    assert_eq!(v.to_bits(), settle_hindered(d, eps).to_bits());
}

#[test]
fn void_fraction_field_outside_the_body_or_overridden_reads_as_set() {
    // a body outside the field's grid settles as at ε = 1, bit for bit; a
    // per-body value takes precedence over the field
    let d = 10e-6;
    let run = |set: &dyn Fn(&mut World)| {
        let mut w = settling(sphere(d), water(DragLaw::DiFelice), 2e-5);
        set(&mut w);
        for _ in 0..500 {
            w.step().unwrap();
        }
        w.bodies().velocity[0].to_array().map(f64::to_bits)
    };
    let plain = run(&|_| {});
    let outside = run(&|w| {
        w.set_void_fraction_field(Some(two_cell_field(0.5, DVec3::X)))
            .unwrap()
    });
    assert_eq!(plain, outside);
    let per_body = run(&|w| w.set_body_void_fractions(&[0.7]).unwrap());
    let both = run(&|w| {
        w.set_void_fraction_field(Some(two_cell_field(0.5, DVec3::ZERO)))
            .unwrap();
        w.set_body_void_fractions(&[0.7]).unwrap();
    });
    assert_eq!(per_body, both);
    assert_ne!(plain, per_body);
    // refused fields
    let g = two_cell_field(0.5, DVec3::ZERO).grid().clone();
    let e = VoidField::new(g, vec![0.5]).unwrap_err();
    assert!(e.contains("need 2 void fractions, found 1"), "{e}");
    let e = VoidField::new(g, vec![0.5, 1.5]).unwrap_err();
    assert!(e.contains("cell 1 must be in (0, 1]"), "{e}");
    let mut w = settling(sphere(d), water(DragLaw::DiFelice), 2e-5);
    w.set_fluid(None).unwrap();
    assert!(w
        .set_void_fraction_field(Some(two_cell_field(0.5, DVec3::ZERO)))
        .is_err());
}

#[test]
fn velocity_grid_from_arrays_interpolates_a_linear_field_exactly() {
    // the grid a CFD code hands over (origin, spacing, counts, x fastest)
    // reproduces a linear field; the same grid given as nodes samples alike
    let u = |p: DVec3| DVec3::new(2.0 * p.y - p.z, 0.5 * p.x, 4.0 * p.x + p.y);
    let (o, h, n) = (
        DVec3::new(0.1, -0.3, 0.0),
        DVec3::new(0.02, 0.05, 0.1),
        [4, 6, 3],
    );
    let mut vals = Vec::new();
    for k in 0..n[2] {
        for j in 0..n[1] {
            for i in 0..n[0] {
                vals.push(u(o + DVec3::new(i as f64, j as f64, k as f64) * h));
            }
        }
    }
    let g = VelocityGrid::regular(o, h, n, vals.clone()).unwrap();
    assert_eq!(g.counts(), n);
    let (lo, hi) = g.bounds();
    for t in [0.0, 0.13, 0.5, 0.77, 1.0] {
        let p = lo + DVec3::new(t, 1.0 - t, t * t) * (hi - lo);
        assert!((g.sample(p) - u(p)).length() < 1e-14, "at {p}");
    }
    let e = VelocityGrid::regular(o, h, n, vals[1..].to_vec()).unwrap_err();
    assert!(e.contains("need 72 velocities, found 71"), "{e}");
    let e = VelocityGrid::regular(o, DVec3::new(0.02, 0.0, 0.1), n, vals.clone()).unwrap_err();
    assert!(e.contains("spacing along y must be > 0"), "{e}");
    vals[5].x = f64::NAN;
    let e = VelocityGrid::regular(o, h, n, vals).unwrap_err();
    assert!(e.contains("node 5 is not finite"), "{e}");
}
