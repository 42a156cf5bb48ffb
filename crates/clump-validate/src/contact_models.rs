//! Contact sub-models users ask for, each against a value from outside the
//! code: LIGGGHTS' tangential rule and `cohesion sjkr` against LIGGGHTS 3.8
//! itself, JKR and twisting resistance against their closed forms, the
//! micro-slip tangential model against Maw, Barber & Fawcett (1976) and the
//! rigid impulse solution.

use crate::case::{rel_err, Case, Group};
use crate::liggghts::{after_bounce, friction_bounce, spin_error, tutorial, TUTORIAL_STONE};
use crate::plot::{draw, Chart, Series, Style};
use crate::Selection;
use clump_core::contact::TangentialLaw;
use std::path::Path;

/// Runs the group.
pub fn run(sel: Selection, dir: &Path) -> Group {
    let mut g = Group::default();
    liggghts_rule(&mut g);
    sjkr(&mut g);
    jkr(&mut g);
    twisting(&mut g);
    if let Err(e) = micro_slip(&mut g, sel, dir) {
        g.cases.push(Case::error(
            "Micro-slip (Mindlin–Deresiewicz), Chung & Ooi test 4",
            MBF_SOURCE,
            e,
        ));
    }
    g
}

const MBF_SOURCE: &str = "Maw, Barber & Fawcett (1976), solved by the method of dimensionality reduction (crates/clump-validate/src/mbf.rs)";

/// `tangential = "mindlin_deresiewicz"` on Chung & Ooi's test 4: the
/// micro-slip branch against MBF (beside the default no-slip spring), the
/// gross-sliding branch against the rigid impulse solution.
fn micro_slip(g: &mut Group, sel: Selection, dir: &Path) -> Result<(), String> {
    use crate::micro_slip::{engine, incident, table, DT, MU, R};
    let degs = [5.0, 10.0, 15.0, 20.0, 25.0, 30.0];
    let elastic = table(&degs, 1.0)?;
    let test4 = table(&degs, 0.98)?;
    for r in &elastic {
        let (dn, d_old) = ((r.new.0 - r.mbf.0).abs(), (r.old.0 - r.mbf.0).abs());
        g.cases.push(Case {
            name: format!(
                "Micro-slip, Chung & Ooi test 4 (e = 1), θ = {}°: v_t'/v_t closer to MBF than the no-slip Mindlin spring's",
                r.deg
            ),
            source: MBF_SOURCE.into(),
            expected: format!("MBF {:.4}; no-slip spring {:.4} (off by {:.4})", r.mbf.0, r.old.0, d_old),
            measured: format!("{:.4} (off by {:.4})", r.new.0, dn),
            tolerance: "no farther than the no-slip spring".into(),
            pass: dn <= d_old,
        });
        if r.deg >= 15.0 {
            g.cases.push(Case::absolute(
                format!(
                    "Micro-slip, Chung & Ooi test 4 (e = 1), θ = {}°: v_t'/v_t",
                    r.deg
                ),
                MBF_SOURCE,
                r.mbf.0,
                r.new.0,
                5e-3,
                "",
            ));
            g.cases.push(Case::relative(
                format!(
                    "Micro-slip, Chung & Ooi test 4 (e = 1), θ = {}°: rebound spin ω'",
                    r.deg
                ),
                MBF_SOURCE,
                r.mbf.1,
                r.new.1,
                5e-3,
                "rad/s",
            ));
        }
    }
    // the exact micro-slip model (tangential = "mdr") at every angle
    for r in &elastic {
        for (what, mbf, mdr) in [
            ("v_t'/v_t", r.mbf.0, r.mdr.0),
            ("rebound spin ω'", r.mbf.1, r.mdr.1),
        ] {
            g.cases.push(Case::relative(
                format!(
                    "Exact micro-slip (mdr), Chung & Ooi test 4 (e = 1), θ = {}°: {what}",
                    r.deg
                ),
                MBF_SOURCE,
                mbf,
                mdr,
                1e-2,
                "",
            ));
        }
    }
    let row = |r: &crate::micro_slip::Row| {
        format!(
            "| {} | {:.4} | {:.4} | {:.4} | {:.4} | {:.1} | {:.1} | {:.1} | {:.1} |",
            r.deg, r.mdr.0, r.new.0, r.old.0, r.mbf.0, r.mdr.1, r.new.1, r.old.1, r.mbf.1
        )
    };
    let head = "| θ (°) | v_t'/v_t mdr | Thornton–Yin | no-slip spring | MBF | ω' mdr (rad/s) | Thornton–Yin | no-slip spring | MBF |\n|---|---|---|---|---|---|---|---|---|";
    g.notes.push(format!(
        "Micro-slip (tangential = \"mindlin_deresiewicz\", docs/theory.md T-49) on Chung & Ooi's test 4 (alumina, R = 2.5 mm, 3.9 m/s, μ = 0.092, no spin), e = 1 (MBF's problem is elastic), dt = {DT:e} s; MBF by its own discretisation (2000 springs over 1.2 a_max, 20000 steps per contact time; halving both changes v_t'/v_t by < 1e-7):\n\n{head}\n{}",
        elastic.iter().map(row).collect::<Vec<_>>().join("\n")
    ));
    g.notes.push(format!(
        "The same with the test's e = 0.98 for the engine (MBF elastic, so this is test 4 as specified beside the elastic solution):\n\n{head}\n{}",
        test4.iter().map(row).collect::<Vec<_>>().join("\n")
    ));
    g.notes.push("Finding (not asserted): below 15° the micro-slip model is much closer to MBF than the no-slip spring but not within 0.005: θ = 10°: 0.6495 against 0.6399; θ = 5°: 0.8016 against 0.7416 (ω' 67 against 88 rad/s); converged in dt (dt/8 changes v_t'/v_t by 1e-3). The deviation is the Thornton–Yin increment under a falling normal force: driven with a prescribed Hertz loading–unloading and a steady tangential displacement, it follows the exact solution while N rises and carries less tangential force while N falls (6.14 N against 6.56 N at 0.75 t_c); at small θ, where the contact sticks for most of the impact, that is most of the tangential impulse. Dropping the μΔN(1−θ) term while N falls makes it worse (0.845 at 5°).".into());
    // the gross-sliding branch, as Chung & Ooi's test 4 with e = 0.98
    let e = 0.98;
    let angles: Vec<f64> = if sel == Selection::Quick {
        vec![40.0, 60.0, 80.0]
    } else {
        (7..=17).map(|k| 5.0 * k as f64).collect()
    };
    for deg in angles {
        let v = incident(deg);
        if !crate::chung_ooi::slides_throughout(v, 0.0, R, e, MU) {
            continue;
        }
        let (vx, vz, wy) = crate::chung_ooi::gross_sliding(v, 0.0, R, e, MU);
        for (label, rule) in [
            ("Micro-slip", TangentialLaw::MindlinDeresiewicz),
            ("Exact micro-slip (mdr)", TangentialLaw::Mdr),
        ] {
            let m = engine(deg, e, rule, DT)?;
            let err = rel_err(m.0, vx).max(rel_err(m.2, wy)).max(rel_err(m.1, vz));
            g.cases.push(Case {
                name: format!("{label}, Chung & Ooi test 4 (e = 0.98), θ = {deg}° (gross sliding): v_t', v_n', ω'"),
                source: "Chung & Ooi 2011; rigid impulse theory, gross sliding".into(),
                expected: format!("{vx:.4} m/s, {vz:.4} m/s, {wy:.2} rad/s"),
                measured: format!("{:.4} m/s, {:.4} m/s, {:.2} rad/s (max rel. err {err:.2e})", m.0, m.1, m.2),
                tolerance: "±1 % each".into(),
                pass: err <= 0.01,
            });
        }
    }
    let pts =
        |f: fn(&crate::micro_slip::Row) -> f64| elastic.iter().map(|r| (r.deg, f(r))).collect();
    let c = Chart {
        title: "Chung & Ooi test 4 (e = 1): tangential restitution, micro-slip branch".into(),
        x_label: "impact angle from the normal θ (deg)".into(),
        y_label: "v_t' / v_t".into(),
        series: vec![
            Series::new("MBF (1976), elastic", pts(|r| r.mbf.0), Style::Dashed),
            Series::new(
                "exact micro-slip (mdr)",
                pts(|r| r.mdr.0),
                Style::LinePoints,
            ),
            Series::new(
                "micro-slip (mindlin_deresiewicz)",
                pts(|r| r.new.0),
                Style::Points,
            ),
            Series::new(
                "no-slip Mindlin spring (clump)",
                pts(|r| r.old.0),
                Style::LinePoints,
            ),
        ],
    };
    g.plot(
        "micro_slip_test4.png",
        "Micro-slip model against MBF and the default no-slip spring, Chung & Ooi test 4 at e = 1",
        draw(&dir.join("micro_slip_test4.png"), &c),
    );
    Ok(())
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
