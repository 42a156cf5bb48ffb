//! Cohesion (`contact::cohesion`): SJKR against LIGGGHTS' own `cohesion
//! sjkr` (LIGGGHTS-PUBLIC 3.8.0, fixtures `sjkr_wall.*`, `sjkr_pair.*`) and
//! its closed form; JKR against the closed forms of Johnson, Kendall &
//! Roberts (1971) and the sticking velocity of Thornton & Ning (1998).

use clump_core::contact::cohesion::lens_radius_sq;
use clump_core::contact::{CohesionLaw, ContactHistory, ContactInput, ContactModel};
use clump_validate::cohesion::{
    deviation, jkr_impact, jkr_loading_cycle, sjkr_contact, sjkr_pair, sjkr_wall,
};
use glam::DVec3;
use std::f64::consts::PI;

/// SJKR's normal force at rest is the Hertz force minus `k_c π a²`, with
/// `a` the intersection circle's radius (direct geometry), for a wall and
/// for two unequal spheres.
#[test]
fn sjkr_force_is_its_closed_form() {
    let (mat, props) = sjkr_contact();
    let model = ContactModel::new(&mat, &mat, &props).unwrap();
    let CohesionLaw::Sjkr { energy_density: k } = props.cohesion else {
        unreachable!()
    };
    let e_star = model.effective_modulus();
    for (ri, rj) in [(2e-3, f64::INFINITY), (2e-3, 1e-3)] {
        let (r_star, sum) = if rj.is_finite() {
            (ri * rj / (ri + rj), ri + rj)
        } else {
            (ri, f64::INFINITY)
        };
        for delta in [1e-7, 1e-5, 1e-4] {
            let c = ContactInput {
                normal: DVec3::Z,
                overlap: delta,
                rel_velocity: DVec3::ZERO,
                rel_omega: DVec3::ZERO,
                radius: r_star,
                radius_sum: sum,
                mass: 1e-4,
                dt: 1e-6,
            };
            let out = model.evaluate(&c, &mut ContactHistory::default());
            // the circle where the undeformed spheres (or sphere and plane) cut
            let a2 = if rj.is_finite() {
                let d = sum - delta;
                let x = (d * d + ri * ri - rj * rj) / (2.0 * d);
                ri * ri - x * x
            } else {
                ri * ri - (ri - delta) * (ri - delta)
            };
            let want = 4.0 / 3.0 * e_star * r_star.sqrt() * delta.powf(1.5) - k * PI * a2;
            assert!(
                (out.normal_force - want).abs() < 1e-9 * want.abs(),
                "{ri} {rj} {delta}: {} vs {want}",
                out.normal_force
            );
            assert!((lens_radius_sq(r_star, sum, delta) - a2).abs() < 1e-9 * a2);
        }
    }
}

/// A sphere dropped onto a plane and two unequal spheres meeting head-on,
/// both with SJKR (they stick): Clump's trajectory against LIGGGHTS'.
#[test]
fn sjkr_reproduces_liggghts() {
    let (rows, clump) = sjkr_wall().unwrap();
    let dev_wall = deviation(&rows, &clump, [1, 2]);
    let (prow, pclump) = sjkr_pair().unwrap();
    let dev_pair = deviation(&prow, &pclump, [1, 2, 3, 4]);
    eprintln!(
        "SJKR vs LIGGGHTS: sphere on a wall, largest |dz|, |dvz| relative {dev_wall:.2e}; two spheres {dev_pair:.2e}"
    );
    // both stick: the sphere rests in contact, the pair moves as one
    let last = rows.last().unwrap();
    assert!(last[1] < 0.002 && last[2].abs() < 1e-4, "{last:?}");
    let last = prow.last().unwrap();
    assert!((last[2] - last[4]).abs() < 1e-6, "{last:?}");
    assert!(
        dev_wall < 1e-12 && dev_pair < 1e-12,
        "{dev_wall:e} {dev_pair:e}"
    );
}

/// JKR through a quasi-static loading and unloading cycle (two spheres,
/// one driven): no force while they approach apart, the JKR curve from
/// the touch (`δ = 0`, where the force jumps to `−(4/3)πΓR*`) on loading
/// and all the way to `−δ_c` on unloading, the pull-off force
/// `(3/2)πΓR*` as the least force, and the break at `−δ_c` with
/// `−(5/6)πΓR*` — every value from the closed forms (computed in
/// `clump_validate::cohesion::Jkr`, independently of the engine's solver).
#[test]
fn jkr_force_overlap_cycle() {
    let (jkr, rows) = jkr_loading_cycle().unwrap();
    let (fc, dc) = (jkr.pull_off(), jkr.delta_c());
    // the closed forms of the engine agree with the independent ones
    let model = {
        let (mat, props) = clump_validate::cohesion::jkr_contact();
        ContactModel::new(&mat, &mat, &props).unwrap()
    };
    assert!((model.reach(jkr.r) - dc).abs() < 1e-12 * dc);
    assert!((model.pull_off_force(jkr.r) - fc).abs() < 1e-12 * fc);
    let step = dc / 2000.0;
    let (mut worst, mut min_f) = (0.0f64, f64::INFINITY);
    let mut touched = false;
    let mut last_bound = f64::NAN;
    let mut first_free = f64::NAN;
    for &(d, f, loading) in &rows {
        touched |= d >= 0.0;
        let bound = f != 0.0;
        if loading && !touched {
            assert_eq!(f, 0.0, "force before touching at δ = {d:e}");
            continue;
        }
        if !loading && !bound {
            if first_free.is_nan() {
                first_free = d;
            }
            continue;
        }
        assert!(first_free.is_nan(), "the contact came back at δ = {d:e}");
        worst = worst.max((f - jkr.force_at(d)).abs() / fc);
        if !loading {
            min_f = min_f.min(f);
            last_bound = d;
        }
    }
    eprintln!(
        "JKR cycle: {} steps, |F − F_JKR(δ)|/F_c ≤ {worst:.2e}; least force {:.6e} N (−F_c = {:.6e} N); \
         last bound δ {:.6e} m, first free δ {:.6e} m (−δ_c = {:.6e} m)",
        rows.len(),
        min_f,
        -fc,
        last_bound,
        first_free,
        -dc
    );
    assert!(worst < 1e-9, "{worst:e}");
    // the minimum of the sampled curve: the curve is flat there, so the
    // samples δ_c/2000 apart find it to ~1e-7
    assert!((min_f + fc).abs() < 1e-6 * fc, "{min_f:e} vs {:e}", -fc);
    // breaks between the samples that straddle −δ_c
    assert!(
        last_bound >= -dc && first_free < -dc,
        "{last_bound:e} {first_free:e}"
    );
    assert!(last_bound - first_free < 1.01 * step);
    // at the break the force is −(5/6)πΓR* (= −(5/9) F_c): the engine's
    // law just inside −δ_c, and no force just outside (near −δ_c the force
    // changes as √(δ + δ_c), so the samples above do not resolve it)
    let at = |d: f64| {
        let c = ContactInput {
            normal: DVec3::X,
            overlap: d,
            rel_velocity: DVec3::ZERO,
            rel_omega: DVec3::ZERO,
            radius: jkr.r,
            radius_sum: 4.0 * jkr.r,
            mass: 1e-5,
            dt: 1e-6,
        };
        model
            .evaluate(&c, &mut ContactHistory::default())
            .normal_force
    };
    let f_break = at(-dc * (1.0 - 1e-12));
    assert!((f_break + 5.0 / 9.0 * fc).abs() < 1e-5 * fc, "{f_break:e}");
    assert_eq!(at(-dc * (1.0 + 1e-12)), 0.0);
}

/// An undamped JKR sphere hitting a plane sticks below the critical
/// sticking velocity `v_s = √(2W/m*)` (W: the adhesion work of breaking
/// the contact, the energy balance of Thornton & Ning 1998) and rebounds
/// above it with `√(v² − v_s²)`. The rebound speed converges to it as
/// `dt` shrinks: the force jumps at the touch (to `−(4/3)πΓR*`) and at the
/// break, and a fixed step puts each jump up to a step late (measured:
/// 1.7e-3 at dt = 1e-7 s, 1.3e-4 at dt/4).
#[test]
fn jkr_sticks_below_the_critical_velocity() {
    let dt = 1e-7;
    let (jkr, m, _) = jkr_impact(0.0, dt).unwrap();
    let vs = jkr.sticking_velocity(m);
    let (_, _, below) = jkr_impact(0.97 * vs, dt).unwrap();
    let want = vs * (1.05f64 * 1.05 - 1.0).sqrt();
    let err = |dt: f64| {
        let (_, _, above) = jkr_impact(1.05 * vs, dt).unwrap();
        let v_out = above.expect("bound above v_s");
        (v_out - want) / want
    };
    let (e1, e4) = (err(dt), err(dt / 4.0));
    eprintln!(
        "JKR impact: v_s = {vs:.6e} m/s; at 0.97 v_s: {below:?} (bound); at 1.05 v_s the rebound speed departs from √(v² − v_s²) = {want:.6e} m/s by {e1:.2e} (dt = {dt:e} s), {e4:.2e} (dt/4)"
    );
    assert!(below.is_none(), "rebounded below v_s: {below:?}");
    assert!(e1.abs() < 3e-3, "{e1:e}");
    // the departure is the time step's: it shrinks with it
    assert!(e4.abs() < 0.3 * e1.abs(), "{e4:e} vs {e1:e}");
}

/// A JKR contact stretched apart (negative overlap, no spring: head-on)
/// survives neighbour rebuilds: the pair list carries live pairs when a
/// model has a reach. The force stays the JKR force at that overlap.
#[test]
fn stretched_jkr_contact_survives_a_rebuild() {
    use clump_core::dof::DRIVEN;
    use clump_validate::setup::{body, coincident_spheres, open_box, world, PARTICLE};
    use glam::DQuat;
    let (mat, props) = clump_validate::cohesion::jkr_contact();
    let r = 1e-3;
    let model = ContactModel::new(&mat, &mat, &props).unwrap();
    let dc = model.reach(0.5 * r);
    let mut w = world(mat, props, 1e-6, open_box(0.05), DVec3::ZERO).unwrap();
    let t = w
        .add_template(coincident_spheres(1, r, mat.density).unwrap(), PARTICLE)
        .unwrap();
    let at = |x: f64| {
        let mut b = body(
            t,
            DVec3::new(x, 0.0, 0.0),
            DQuat::IDENTITY,
            DVec3::ZERO,
            DVec3::ZERO,
        );
        b.start_step = DRIVEN;
        b
    };
    let a = w.add_body(&at(0.0)).unwrap();
    let b = w.add_body(&at(2.0 * r - 1e-6)).unwrap();
    w.run(1).unwrap();
    let force = |w: &clump_core::world::World| -w.bodies().force[w.body_index(a).unwrap()].x;
    assert!(force(&w) > 0.0, "pressed together");
    // pulled apart to half the critical separation
    let d = -0.5 * dc;
    w.set_body_pose(b, DVec3::new(2.0 * r - d, 0.0, 0.0), DQuat::IDENTITY)
        .unwrap();
    w.run(1).unwrap();
    let want = {
        let c = ContactInput {
            normal: DVec3::X,
            overlap: d,
            rel_velocity: DVec3::ZERO,
            rel_omega: DVec3::ZERO,
            radius: 0.5 * r,
            radius_sum: 2.0 * r,
            mass: 1.0,
            dt: 1e-6,
        };
        model
            .evaluate(&c, &mut ContactHistory::default())
            .normal_force
    };
    assert!(want < 0.0);
    // (the overlap from the centres differs from d by round-off)
    let close = |f: f64| (f - want).abs() < 1e-9 * want.abs();
    assert!(
        close(force(&w)),
        "stretched contact: {} vs {want}",
        force(&w)
    );
    // a third body: the topology changes, the lists are rebuilt
    w.add_body(&at(0.02)).unwrap();
    w.run(1).unwrap();
    assert!(
        close(force(&w)),
        "after the rebuild: {} vs {want}",
        force(&w)
    );
    // beyond δ_c it breaks, and does not form again while apart
    w.set_body_pose(
        b,
        DVec3::new(2.0 * r + 1.01 * dc, 0.0, 0.0),
        DQuat::IDENTITY,
    )
    .unwrap();
    w.run(1).unwrap();
    assert_eq!(force(&w), 0.0);
    w.set_body_pose(b, DVec3::new(2.0 * r + 0.5 * dc, 0.0, 0.0), DQuat::IDENTITY)
        .unwrap();
    w.run(1).unwrap();
    assert_eq!(force(&w), 0.0, "an apart pair that was not in contact");
}
