//! Contact sub-models users ask for, each against a value from outside the
//! code: LIGGGHTS' tangential rule and `cohesion sjkr` against LIGGGHTS 3.8
//! itself.

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
    g
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
