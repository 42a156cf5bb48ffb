//! Cohesion (`contact::cohesion`): SJKR against LIGGGHTS' own `cohesion
//! sjkr` (LIGGGHTS-PUBLIC 3.8.0, fixtures `sjkr_wall.*`, `sjkr_pair.*`) and
//! its closed form; JKR against the closed forms of Johnson, Kendall &
//! Roberts (1971) and the sticking velocity of Thornton & Ning (1998).

use clump_core::contact::cohesion::lens_radius_sq;
use clump_core::contact::{CohesionLaw, ContactHistory, ContactInput, ContactModel};
use clump_validate::cohesion::{deviation, sjkr_contact, sjkr_pair, sjkr_wall};
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
