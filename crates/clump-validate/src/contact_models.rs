//! Contact sub-models users ask for, each against a value from outside the
//! code: LIGGGHTS' tangential rule and `cohesion sjkr` against LIGGGHTS 3.8
//! itself, JKR and twisting resistance against their closed forms.

use crate::case::{Case, Group};
use crate::liggghts::{after_bounce, friction_bounce, spin_error, tutorial, TUTORIAL_STONE};
use crate::Selection;
use clump_core::contact::TangentialLaw;
use std::path::Path;

/// Runs the group.
pub fn run(_sel: Selection, _dir: &Path) -> Group {
    let mut g = Group::default();
    liggghts_rule(&mut g);
    sjkr(&mut g);
    jkr(&mut g);
    twisting(&mut g);
    g
}

/// `twisting = "marshall"` against the closed forms of a spinning sphere
/// resting on a plane.
fn twisting(g: &mut Group) {
    let source = "closed forms of docs/theory.md T-48 (Marshall 2009 constants)";
    match crate::twisting::spin_down(50.0, 1e-5, 0.3, 1000) {
        Ok((sd, rows)) => {
            let (a, b) = (rows[1], rows[rows.len() - 1]);
            g.cases.push(Case::relative(
                "Twisting, slipping: spin-down rate of a 2 mm sphere resting on a plane, ω₀ = 50 rad/s (M_max/I)",
                source,
                sd.m_max / sd.inertia,
                (a.1 - b.1) / (b.0 - a.0),
                1e-9,
                "rad/s²",
            ));
        }
        Err(e) => g.cases.push(Case::error("Twisting, slipping", source, e)),
    }
    match crate::twisting::spin_down(0.5, 1e-5, 0.3, 100) {
        Ok((sd, rows)) => {
            let worst = rows
                .iter()
                .map(|&(t, w)| (w - sd.sticking(0.5, t)).abs() / 0.5)
                .fold(0.0, f64::max);
            g.cases.push(Case::at_most(
                "Twisting, sticking: ω₀ = 0.5 rad/s rings down as the damped torsional oscillator, |ω − ω_closed|/ω₀ over 4 periods (dt = 1e-5 s)",
                source,
                "0",
                worst,
                2e-3,
            ));
        }
        Err(e) => g.cases.push(Case::error("Twisting, sticking", source, e)),
    }
}

/// `cohesion = "jkr"` against the JKR closed forms.
fn jkr(g: &mut Group) {
    let source = "Johnson, Kendall & Roberts (1971); docs/theory.md T-47";
    match crate::cohesion::jkr_loading_cycle() {
        Ok((jkr, rows)) => {
            let fc = jkr.pull_off();
            let worst = rows
                .iter()
                .filter(|r| r.1 != 0.0)
                .map(|r| (r.1 - jkr.force_at(r.0)).abs() / fc)
                .fold(0.0, f64::max);
            g.cases.push(Case::at_most(
                "JKR: driven loading–unloading cycle of two 1 mm spheres (Γ = 0.05 J/m²), |F − F_JKR(δ)|/F_c on both branches",
                source,
                "0",
                worst,
                1e-9,
            ));
            let least = rows.iter().map(|r| r.1).fold(f64::INFINITY, f64::min);
            g.cases.push(Case::relative(
                "JKR: least force of the cycle (pull-off, (3/2)πΓR*)",
                source,
                -fc,
                least,
                1e-6,
                "N",
            ));
            let last = rows
                .iter()
                .filter(|r| r.1 != 0.0)
                .map(|r| r.0)
                .fold(f64::INFINITY, f64::min);
            g.cases.push(Case::relative(
                "JKR: overlap at which the contact breaks (−δ_c = −(3/4)(π²Γ²R*/E*²)^{1/3}; samples δ_c/2000 apart)",
                source,
                -jkr.delta_c(),
                last,
                1e-3,
                "m",
            ));
        }
        Err(e) => g.cases.push(Case::error("JKR loading cycle", source, e)),
    }
    let source = "energy balance of Thornton & Ning (1998), v_s = √(2W/m*) (T-47)";
    let dt = 1e-7;
    let run = |v: f64| crate::cohesion::jkr_impact(v, dt);
    match run(0.0).and_then(|(jkr, m, _)| {
        let vs = jkr.sticking_velocity(m);
        Ok((vs, run(0.97 * vs)?.2, run(1.05 * vs)?.2))
    }) {
        Ok((vs, below, above)) => {
            g.cases.push(Case::at_most(
                "JKR: 1 mm sphere onto a plane at 0.97 v_s, undamped: rebound speed (0 = stuck)",
                source,
                "0 (sticks)",
                below.unwrap_or(0.0),
                0.0,
            ));
            g.cases.push(Case::relative(
                "JKR: the same at 1.05 v_s: rebound speed √(v² − v_s²) (dt = 1e-7 s; the touch and break fall between steps)",
                source,
                vs * (1.05f64 * 1.05 - 1.0).sqrt(),
                above.unwrap_or(0.0),
                3e-3,
                "m/s",
            ));
        }
        Err(e) => g
            .cases
            .push(Case::error("JKR sticking velocity", source, e)),
    }
}

/// `cohesion = "sjkr"` against LIGGGHTS' `cohesion sjkr`, side by side.
fn sjkr(g: &mut Group) {
    let source = "LIGGGHTS-PUBLIC 3.8.0 cohesion sjkr run (fixtures sjkr_wall, sjkr_pair)";
    match crate::cohesion::sjkr_wall() {
        Ok((rows, clump)) => g.cases.push(Case::at_most(
            "SJKR: 2 mm sphere dropped onto a plane, sticks (k_c = 2e5 J/m³): largest |Δz|, |Δv_z| relative to LIGGGHTS",
            source,
            "LIGGGHTS' z, v_z",
            crate::cohesion::deviation(&rows, &clump, [1, 2]),
            1e-9,
        )),
        Err(e) => g.cases.push(Case::error("SJKR sphere on a plane", source, e)),
    }
    match crate::cohesion::sjkr_pair() {
        Ok((rows, clump)) => g.cases.push(Case::at_most(
            "SJKR: 2 mm and 1 mm spheres meeting head-on, stick: largest |Δx|, |Δv| relative to LIGGGHTS",
            source,
            "LIGGGHTS' x, v",
            crate::cohesion::deviation(&rows, &clump, [1, 2, 3, 4]),
            1e-9,
        )),
        Err(e) => g.cases.push(Case::error("SJKR sphere pair", source, e)),
    }
}

/// `tangential = "liggghts"` against LIGGGHTS' printed trajectories.
fn liggghts_rule(g: &mut Group) {
    let source = "LIGGGHTS-PUBLIC 3.8.0 run (crates/clump-core/tests/fixtures/liggghts)";
    let (rows, states) = friction_bounce(TangentialLaw::Liggghts);
    match after_bounce(&rows) {
        Some(k) => g.cases.push(Case::at_most(
            "LIGGGHTS' tangential rule: 50-sphere stone sliding onto a plane (μ = 0.5, e = 0.3), |Δω|/|ω| after the bounce",
            source,
            "LIGGGHTS' ω",
            spin_error(&rows, &states, k),
            1e-3,
        )),
        None => g.cases.push(Case::error("LIGGGHTS' tangential rule", source, "no bounce in the fixture")),
    }
    let Ok(text) = std::fs::read_to_string(TUTORIAL_STONE) else {
        g.notes.push(format!(
            "LIGGGHTS' tutorial multisphere_stone_restitution not run: {TUTORIAL_STONE} not found (Debian liggghts-doc)"
        ));
        return;
    };
    for (b, (rows, states)) in tutorial(TangentialLaw::Liggghts, &text).iter().enumerate() {
        let name = format!(
            "LIGGGHTS' tutorial multisphere_stone_restitution, stone {} of 2 (LIGGGHTS' stone, Monte-Carlo mass properties and poses): |Δω|/|ω| after the first bounce",
            b + 1
        );
        match after_bounce(rows) {
            Some(k) => g.cases.push(Case::at_most(
                name,
                source,
                "LIGGGHTS' ω",
                spin_error(rows, states, k),
                1e-3,
            )),
            None => g
                .cases
                .push(Case::error(name, source, "no bounce in the fixture")),
        }
    }
    g.notes.push(
        "LIGGGHTS' rule: only the spring k_t|ξ| is checked against μ|F_n|, the dashpot is dropped while sliding (docs/theory.md T-45); set-up: damping = \"liggghts\", tensile = true, rotation = \"richardson_liggghts\", the same mass properties and start state as LIGGGHTS (its state at step 100)."
            .into(),
    );
}

#[cfg(test)]
mod tests {
    /// Every case of the group passes (the report's rows, run here too).
    #[test]
    fn group_passes() {
        let g = super::run(crate::Selection::Quick, &std::env::temp_dir());
        for c in &g.cases {
            eprintln!("{}: {} ({}) {}", c.name, c.measured, c.tolerance, c.pass);
        }
        assert!(!g.cases.is_empty());
        assert!(g.cases.iter().all(|c| c.pass));
    }
}
