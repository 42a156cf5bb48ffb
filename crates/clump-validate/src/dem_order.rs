//! Order of accuracy of every rotation scheme inside the DEM step, against
//! a dt → 0 reference run of the same scheme (dt/64): (a) an asymmetric
//! clump dropped spinning onto a plane, where it bounces and rocks;
//! (b) an off-centre collision of two spinning asymmetric clumps. Contacts
//! are elastic and frictionless (forces depend on positions only, as
//! velocity Verlet assumes). The error of a run is the largest of the
//! centre-of-mass error / 0.02 m, the orientation error (rad) and the
//! angular-velocity error / 10 rad/s at the end time.
//!
//! Theory: the velocity-Verlet schemes are second order; Zhao–van Wachem
//! inside the DEM step holds the start-of-step torque over the step (the
//! contact torque cannot be evaluated at the predicted midpoint without a
//! second force pass), a forward-Euler update of L: first order (Seelen,
//! Padding & Kuipers 2016). See docs/rotation_schemes.md.

use crate::case::{Case, Group};
use crate::setup::{body, material, plane, props, world};
use crate::Selection;
use clump_core::rotation::RotationScheme;
use clump_core::shape::{ClumpTemplate, Sphere};
use glam::{DQuat, DVec3};
use std::path::Path;

/// An asymmetric four-sphere clump (three distinct principal moments).
pub fn stone() -> Result<ClumpTemplate, String> {
    let s = [
        Sphere::new(DVec3::new(0.0, 0.0, 0.0), 0.010),
        Sphere::new(DVec3::new(0.013, 0.0, 0.0), 0.008),
        Sphere::new(DVec3::new(0.0, 0.010, 0.003), 0.006),
        Sphere::new(DVec3::new(-0.006, -0.004, 0.008), 0.005),
    ];
    ClumpTemplate::from_spheres("stone", &s, 2500.0).map_err(|e| e.to_string())
}

/// The final (position, orientation, angular velocity) of every body.
type Final = Vec<(DVec3, DQuat, DVec3)>;

/// Case `'a'` (bounce on a plane under gravity) or `'b'` (clump–clump
/// collision) with `scheme` at `dt` until `t_end` (s).
pub fn run_case(case: char, scheme: RotationScheme, dt: f64, t_end: f64) -> Result<Final, String> {
    let g = if case == 'a' {
        DVec3::new(0.0, 0.0, -9.81)
    } else {
        DVec3::ZERO
    };
    let mut w = world(
        material(1e7, 0.3, 2500.0),
        props(1.0, 0.0),
        dt,
        crate::setup::open_box(1.0),
        g,
    )?;
    w.config.rotation = scheme;
    w.config.skin = Some(0.002);
    let t = w.add_template(stone()?, 0).map_err(|e| e.to_string())?;
    let q0 = DQuat::from_axis_angle(DVec3::new(0.3, -0.5, 0.8).normalize(), 0.9);
    let bodies = if case == 'a' {
        w.add_wall(plane(DVec3::ZERO, DVec3::Z))
            .map_err(|e| e.to_string())?;
        vec![body(
            t,
            DVec3::new(0.0, 0.0, 0.025),
            q0,
            DVec3::new(0.2, 0.0, -0.3),
            DVec3::new(3.0, -8.0, 5.0),
        )]
    } else {
        let q1 = DQuat::from_axis_angle(DVec3::new(-0.7, 0.2, 0.4).normalize(), 2.1);
        vec![
            body(
                t,
                DVec3::new(-0.025, 0.004, 0.0),
                q0,
                DVec3::new(0.8, 0.0, 0.0),
                DVec3::new(2.0, 5.0, -4.0),
            ),
            body(
                t,
                DVec3::new(0.025, -0.004, 0.003),
                q1,
                DVec3::new(-0.8, 0.0, 0.0),
                DVec3::new(-6.0, 1.0, 3.0),
            ),
        ]
    };
    for b in &bodies {
        w.add_body(b).map_err(|e| e.to_string())?;
    }
    w.run((t_end / dt).round() as u64)
        .map_err(|e| e.to_string())?;
    (1..=bodies.len() as u64)
        .map(|id| {
            let b = w.body_index(id).ok_or("body lost")?;
            Ok((
                w.bodies().position[b],
                w.bodies().orientation[b],
                w.bodies().angular_velocity[b],
            ))
        })
        .collect()
}

fn error(a: &Final, b: &Final) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| {
            let dx = (x.0 - y.0).length() / 0.02;
            let dq = 2.0
                * (x.1 * y.1.conjugate())
                    .normalize()
                    .xyz()
                    .length()
                    .min(1.0)
                    .asin();
            let dw = (x.2 - y.2).length() / 10.0;
            dx.max(dq).max(dw)
        })
        .fold(0.0, f64::max)
}

/// One scheme's errors at dt, dt/2, dt/4 against dt/64, and the observed
/// orders of the two halvings.
pub struct Orders {
    /// The scheme.
    pub scheme: RotationScheme,
    /// Errors at dt, dt/2, dt/4 (dimensionless, see the module docs).
    pub errors: [f64; 3],
    /// log2 of the error ratios.
    pub orders: [f64; 2],
}

/// [`Orders`] of every scheme for case `case` from `dt` (s) to `t_end` (s).
pub fn orders(case: char, dt: f64, t_end: f64) -> Result<Vec<Orders>, String> {
    RotationScheme::ALL
        .iter()
        .map(|&scheme| {
            let reference = run_case(case, scheme, dt / 64.0, t_end)?;
            let mut errors = [0.0; 3];
            for (k, e) in errors.iter_mut().enumerate() {
                *e = error(
                    &run_case(case, scheme, dt / f64::from(1u32 << k), t_end)?,
                    &reference,
                );
            }
            let orders = [
                (errors[0] / errors[1]).log2(),
                (errors[1] / errors[2]).log2(),
            ];
            Ok(Orders {
                scheme,
                errors,
                orders,
            })
        })
        .collect()
}

/// The order the theory gives `scheme` inside the DEM step.
pub fn theory(scheme: RotationScheme) -> f64 {
    if scheme == RotationScheme::ZhaoVanWachem {
        1.0
    } else {
        2.0
    }
}

/// The cases (a) at dt = 1e-4 s for 0.03 s and (b) for 0.02 s.
pub const CASES: [(char, &str, f64); 2] = [
    (
        'a',
        "asymmetric clump bouncing and rocking on a plane",
        0.03,
    ),
    ('b', "clump–clump off-centre collision", 0.02),
];

/// Runs the group: the order of the finest halving for every scheme and
/// case, expected 2 (1 for zhao_van_wachem) within 0.3.
pub fn run(_sel: Selection, _dir: &Path) -> Group {
    let mut g = Group::default();
    for (case, what, t_end) in CASES {
        match orders(case, 1e-4, t_end) {
            Ok(rows) => {
                for o in rows {
                    g.cases.push(Case::absolute(
                        format!(
                            "DEM order ({case}) {what}, {:?}: errors {:.3e}, {:.3e}, {:.3e} at dt = 1e-4, 5e-5, 2.5e-5 s vs dt/64",
                            o.scheme, o.errors[0], o.errors[1], o.errors[2]
                        ),
                        "velocity Verlet: 2; ZvW with the torque held over the step: 1",
                        theory(o.scheme),
                        o.orders[1],
                        0.3,
                        "",
                    ));
                }
            }
            Err(e) => g
                .notes
                .push(format!("DEM order ({case}) could not run: {e}")),
        }
    }
    g.notes.push("DEM order: elastic frictionless Hertz contacts (E = 1e7 Pa), four-sphere asymmetric clump; error = max(|Δx|/0.02 m, orientation angle, |Δω|/10 rad/s) against the same scheme at dt/64. See docs/rotation_schemes.md.".into());
    g
}
