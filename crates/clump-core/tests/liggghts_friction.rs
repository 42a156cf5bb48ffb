//! LIGGGHTS' tangential rule (`TangentialLaw::Liggghts`) against LIGGGHTS
//! itself (LIGGGHTS-PUBLIC 3.8.0): the asymmetric 50-sphere stone of
//! `fixtures/liggghts` arrives spinning and sliding on a plane of its own
//! material with friction (μ = 0.5, e = 0.3, E = 10 MPa, ν = 0.45, Hertz,
//! `tangential history`, LIGGGHTS damping, `limitForce off`: the set-up of
//! LIGGGHTS' tutorial `multisphere_stone_restitution`), `friction.in` →
//! `friction.dat`. Clump starts from LIGGGHTS' state at step 100 with the
//! same mass properties and rotation scheme (`richardson_liggghts`).

mod common;
use clump_core::contact::{DampingLaw, Material, PairProperties, TangentialLaw};
use clump_core::rotation::RotationScheme;
use clump_core::shape::Sphere;
use common::liggghts::{
    add_stone, body_frame_template, deviation, run_bounce, state, stone_world, table, v3, State,
};

/// The stone material and contact of LIGGGHTS' tutorial, with tangential
/// rule `rule`.
fn tutorial_contact(rule: TangentialLaw) -> (Material, PairProperties) {
    let mat = Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.45,
        density: 2500.0,
    };
    let props = PairProperties {
        restitution: 0.3,
        friction: 0.5,
        damping: DampingLaw::Liggghts,
        tensile: true,
        tangential: rule,
        ..PairProperties::default()
    };
    (mat, props)
}

/// Clump's run of the fixture with tangential rule `rule`.
fn run(rule: TangentialLaw) -> (Vec<Vec<f64>>, Vec<State>) {
    let rows = table(include_str!("fixtures/liggghts/friction.dat"));
    let (mat, props) = tutorial_contact(rule);
    let spheres = include_str!("fixtures/liggghts/friction_spheres_step100.txt");
    let states = run_bounce(
        &rows,
        spheres,
        0.01,
        mat,
        props,
        0,
        RotationScheme::RichardsonLiggghts,
        1e-5,
        100,
    );
    (rows, states)
}

/// Index of the first row after the end of the first bounce: the stone
/// rises (vz > 0) and its velocity changes by gravity alone until the next
/// row (rows 1 ms apart).
fn after_bounce(rows: &[Vec<f64>]) -> usize {
    let rising = rows.iter().position(|r| r[6] > 0.0).expect("a bounce");
    (rising..rows.len() - 1)
        .find(|&k| {
            let dv = v3(&rows[k + 1], 4) - v3(&rows[k], 4);
            (dv - glam::DVec3::new(0.0, 0.0, -9.81e-3)).length() < 1e-9
        })
        .expect("the stone leaves the floor")
}

#[test]
fn liggghts_rule_reproduces_liggghts_bounce_with_friction() {
    let (rows, states) = run(TangentialLaw::Liggghts);
    let k = after_bounce(&rows);
    let rel_spin = (states[k].w - v3(&rows[k], 11)).length() / v3(&rows[k], 11).length();
    let dev = deviation(&rows, &states);
    eprintln!(
        "LIGGGHTS' rule: spin after the first bounce (t = {} s) |dω|/|ω| = {rel_spin:.2e}; over the run |dx| {:.2e} m, |dv| {:.2e} m/s, |dq| {:.2e}, |dω|/|ω| {:.2e}",
        rows[k][0], dev[0], dev[1], dev[2], dev[3]
    );
    let (_, clump) = run(TangentialLaw::Clump);
    let rel_clump = (clump[k].w - v3(&rows[k], 11)).length() / v3(&rows[k], 11).length();
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

/// LIGGGHTS' own stone (Debian liggghts-doc; GPL, read from the install,
/// never copied into the repository), 50 spheres in mm.
const STONE: &str = "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public/multisphere_stone_restitution/data/stone1.multisphere";

/// LIGGGHTS' tutorial `multisphere_stone_restitution` itself: its two
/// stones (LIGGGHTS' stone, its Monte-Carlo mass properties and body frame,
/// its random insertion poses) from LIGGGHTS' state at step 100
/// (`tutorial.in` → `tutorial_body*.dat`, `tutorial_frame.txt`), to the end
/// of their second bounce.
#[test]
fn liggghts_tutorial_two_stones() {
    let Ok(text) = std::fs::read_to_string(STONE) else {
        eprintln!("SKIPPED: {STONE} not found (apt-get install liggghts-doc)");
        return;
    };
    let frame = table(include_str!("fixtures/liggghts/tutorial_frame.txt"));
    let c = v3(&frame[0], 0);
    let rot =
        glam::DMat3::from_cols(v3(&frame[1], 0), v3(&frame[2], 0), v3(&frame[3], 0)).transpose();
    // input frame (mm) → LIGGGHTS' body frame (m)
    let spheres: Vec<Sphere> = table(&text)
        .iter()
        .map(|r| Sphere::new(rot * (v3(r, 0) * 0.001 - c), r[3] * 0.001))
        .collect();
    assert_eq!(spheres.len(), 50);
    let rows = [
        table(include_str!("fixtures/liggghts/tutorial_body1.dat")),
        table(include_str!("fixtures/liggghts/tutorial_body2.dat")),
    ];
    for rule in [TangentialLaw::Liggghts, TangentialLaw::Clump] {
        let (mat, props) = tutorial_contact(rule);
        let mut w = stone_world(mat, props, 0, RotationScheme::RichardsonLiggghts, 1e-5);
        let r0 = &rows[0][0];
        let tmpl = body_frame_template(&spheres, 2500.0, r0[20], v3(r0, 17));
        let frame = tmpl.input_to_body;
        let t = w.add_template(tmpl, 0).unwrap();
        let ids = rows.clone().map(|r| add_stone(&mut w, t, &r[0], frame));
        let mut states = ids.map(|id| vec![state(&w, id, frame)]);
        for _ in 1..rows[0].len() {
            w.run(100).unwrap();
            for b in 0..2 {
                states[b].push(state(&w, ids[b], frame));
            }
        }
        for b in 0..2 {
            let r = &rows[b];
            let k = after_bounce(r);
            let spin = (states[b][k].w - v3(&r[k], 11)).length() / v3(&r[k], 11).length();
            let dev = deviation(r, &states[b]);
            eprintln!(
                "tutorial, {rule:?}, stone {}: spin after the first bounce (t = {} s) |dω|/|ω| = {spin:.2e}; to t = {} s: |dx| {:.2e} m, |dv| {:.2e} m/s, |dq| {:.2e}, |dω|/|ω| {:.2e}",
                b + 1, r[k][0], r[r.len() - 1][0], dev[0], dev[1], dev[2], dev[3]
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
            }
        }
    }
}
