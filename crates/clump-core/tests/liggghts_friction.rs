//! LIGGGHTS' tangential rule (`TangentialLaw::Liggghts`) against LIGGGHTS
//! itself (LIGGGHTS-PUBLIC 3.8.0): the asymmetric 50-sphere stone of
//! `fixtures/liggghts` arrives spinning and sliding on a plane of its own
//! material with friction (μ = 0.5, e = 0.3, E = 10 MPa, ν = 0.45, Hertz,
//! `tangential history`, LIGGGHTS damping, `limitForce off`: the set-up of
//! LIGGGHTS' tutorial `multisphere_stone_restitution`), `friction.in` →
//! `friction.dat`. Clump starts from LIGGGHTS' state at step 100 with the
//! same mass properties and rotation scheme (`richardson_liggghts`).

use clump_core::contact::TangentialLaw;
use clump_validate::liggghts::{
    after_bounce, deviation, friction_bounce, spin_error, tutorial, v3, TUTORIAL_STONE,
};

#[test]
fn liggghts_rule_reproduces_liggghts_bounce_with_friction() {
    let (rows, states) = friction_bounce(TangentialLaw::Liggghts);
    let k = after_bounce(&rows).expect("a bounce");
    let rel_spin = spin_error(&rows, &states, k);
    let dev = deviation(&rows, &states);
    eprintln!(
        "LIGGGHTS' rule: spin after the first bounce (t = {} s) |dω|/|ω| = {rel_spin:.2e}; over the run |dx| {:.2e} m, |dv| {:.2e} m/s, |dq| {:.2e}, |dω|/|ω| {:.2e}",
        rows[k][0], dev[0], dev[1], dev[2], dev[3]
    );
    let (_, clump) = friction_bounce(TangentialLaw::Clump);
    let rel_clump = spin_error(&rows, &clump, k);
    eprintln!("Clump's rule: spin after the first bounce |dω|/|ω| = {rel_clump:.2e}");
    // the fixture holds a bounce that changes the spin by more than it is
    assert!(rows[0][6] < -0.9);
    assert!((v3(&rows[k], 11) - v3(&rows[0], 11)).length() > 20.0);
    // asked: 1e-3; the same arithmetic as LIGGGHTS gives its printed digits
    assert!(rel_spin < 1e-12, "spin after the bounce: {rel_spin:e}");
    assert!(
        dev[0] < 1e-13 && dev[1] < 1e-12 && dev[2] < 1e-12 && dev[3] < 1e-12,
        "{dev:?}"
    );
    // Clump's own rule (spring plus dashpot limited) gives another spin
    assert!(rel_clump > 10.0 * rel_spin, "{rel_clump:e} vs {rel_spin:e}");
}

/// LIGGGHTS' tutorial `multisphere_stone_restitution` itself: its two
/// stones (LIGGGHTS' stone, its Monte-Carlo mass properties and body frame,
/// its random insertion poses) from LIGGGHTS' state at step 100
/// (`tutorial.in` → `tutorial_body*.dat`, `tutorial_frame.txt`), to the end
/// of their second bounce.
#[test]
fn liggghts_tutorial_two_stones() {
    let Ok(text) = std::fs::read_to_string(TUTORIAL_STONE) else {
        eprintln!("SKIPPED: {TUTORIAL_STONE} not found (apt-get install liggghts-doc)");
        return;
    };
    for rule in [TangentialLaw::Liggghts, TangentialLaw::Clump] {
        for (b, (rows, states)) in tutorial(rule, &text).iter().enumerate() {
            let k = after_bounce(rows).expect("a bounce");
            let spin = spin_error(rows, states, k);
            let dev = deviation(rows, states);
            eprintln!(
                "tutorial, {rule:?}, stone {}: spin after the first bounce (t = {} s) |dω|/|ω| = {spin:.2e}; to t = {} s: |dx| {:.2e} m, |dv| {:.2e} m/s, |dq| {:.2e}, |dω|/|ω| {:.2e}",
                b + 1, rows[k][0], rows[rows.len() - 1][0], dev[0], dev[1], dev[2], dev[3]
            );
            match rule {
                // asked: 1e-3; LIGGGHTS' printed digits are reproduced
                TangentialLaw::Liggghts => {
                    assert!(
                        spin < 1e-10 && dev[3] < 1e-10,
                        "stone {b}: {spin:e} {dev:?}"
                    )
                }
                TangentialLaw::Clump => assert!(spin > 1e-2, "stone {b}: {spin:e}"),
                TangentialLaw::MindlinDeresiewicz | TangentialLaw::Mdr => {
                    unreachable!("not run here")
                }
            }
        }
    }
}
