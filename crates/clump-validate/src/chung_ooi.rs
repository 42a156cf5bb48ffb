//! Chung & Ooi (2011) impact benchmarks (REFERENCE.md §3; tests 4–6 after
//! the paper's oblique-impact tests, with the analytic rigid-body impulse
//! solution on the gross-sliding branch), through the full engine: one-sphere
//! clumps, the step pipeline, a rigid plane wall (normal +z, world frame).

use crate::case::{rel_err, Case, Group};
use crate::ode::impact_restitution;
use crate::plot::{draw, Chart, Series, Style};
use crate::setup::*;
use crate::Selection;
use clump_core::contact::{DampingLaw, Material, NormalLaw, PairProperties};
use clump_core::multi_contact::MultiContact;
use glam::{DQuat, DVec3};
use std::path::Path;

const SRC3: &str = "REFERENCE.md §3 (Chung & Ooi 2011)";
/// What the test-5 failure is (investigated with a probe of the impulses).
/// What test 5 checks beyond test 4 (strong damping, e = 0.5).
const TEST5_NOTE: &str = "Test 5 (e = 0.5) has strong dashpots: the tangential dashpot γ_t|v_t| exceeds μF_n for much of the contact and the normal dashpot would make F_n tensile near separation. It passes because the normal force is clamped at zero (non-cohesive, the default; then ∫F_n dt = (1+e)m v_n exactly) and a sliding contact stores the limited force in its elastic spring, ξ = −F_t/k_t, so it carries |F_t| = μF_n at every step although k_t ∝ √δ grows during loading (contact::tangential). Before these two changes ω' came out 2–11 % low (the Coulomb limit acted on |F_n| in the tensile phase, and the Luding truncation ξ = −(F_t + γ_t v_t)/k_t left a forward-pointing spring that pulled the trial force below the limit).";
const SRC_IMPULSE: &str = "Chung & Ooi 2011; rigid impulse theory, gross sliding";

fn glass() -> Material {
    material(4.8e10, 0.20, 2800.0)
}
fn limestone() -> Material {
    material(2.0e10, 0.25, 2500.0)
}
fn al_alloy() -> Material {
    material(7.0e10, 0.30, 2699.0)
}
fn mg_alloy() -> Material {
    material(4.0e10, 0.35, 1800.0)
}
pub(crate) fn alumina() -> Material {
    material(3.8e11, 0.23, 4000.0)
}
fn cast_iron() -> Material {
    material(1.0e11, 0.25, 7000.0)
}

/// Test 1: two identical spheres of radius 0.01 m at ±10 m/s, built from
/// clumps of `n` coincident spheres; returns the impact and the rebound speed.
fn two_spheres(mat: Material, n: usize, multi: MultiContact) -> Result<(Impact, f64), String> {
    let r = 0.01;
    let mut w = world(mat, props(1.0, 0.0), 4.0e-8, open_box(1.0), DVec3::ZERO)?;
    w.config.multi_contact = multi;
    let t = w
        .add_template(coincident_spheres(n, r, mat.density)?, PARTICLE)
        .map_err(|e| e.to_string())?;
    let mut add = |x: f64, v: f64| {
        w.add_body(&body(
            t,
            DVec3::new(x, 0.0, 0.0),
            DQuat::IDENTITY,
            DVec3::new(v, 0.0, 0.0),
            DVec3::ZERO,
        ))
    };
    let a = add(-r - 1e-5, 10.0).map_err(|e| e.to_string())?;
    let b = add(r + 1e-5, -10.0).map_err(|e| e.to_string())?;
    let imp = run_impact(&mut w, a, r, 100_000)?;
    let rebound = 0.5 * (motion(&w, b)?.0.x - motion(&w, a)?.0.x);
    Ok((imp, rebound))
}

/// A sphere of radius `r` released just above the plane z = 0 with velocity
/// `v` and angular velocity `omega` (world frame); returns the impact and
/// the motion after it.
pub(crate) fn onto_wall(
    mat: Material,
    p: PairProperties,
    r: f64,
    v: DVec3,
    omega: DVec3,
    dt: f64,
) -> Result<(Impact, DVec3, DVec3), String> {
    let mut w = world(mat, p, dt, open_box(10.0), DVec3::ZERO)?;
    let t = w
        .add_template(coincident_spheres(1, r, mat.density)?, PARTICLE)
        .map_err(|e| e.to_string())?;
    let id = w
        .add_body(&body(
            t,
            DVec3::new(0.0, 0.0, r + 1e-7),
            DQuat::IDENTITY,
            v,
            omega,
        ))
        .map_err(|e| e.to_string())?;
    w.add_wall(plane(DVec3::ZERO, DVec3::Z))
        .map_err(|e| e.to_string())?;
    let imp = run_impact(&mut w, id, r, 2_000_000)?;
    let (v1, w1) = motion(&w, id)?;
    Ok((imp, v1, w1))
}

/// Hertz reference force–time curve of a normal impact (engine-independent
/// RK4 of `m* δ'' = −(4/3)E*√R* δ^{3/2}`): `(t s, F N)`.
fn hertz_force_time(e_star: f64, r_star: f64, m_star: f64, v: f64) -> Vec<(f64, f64)> {
    let k = 4.0 / 3.0 * e_star * r_star.sqrt();
    let t_s = (m_star / (k * v.sqrt())).powf(0.4);
    let x_s = v * t_s;
    let (_, samples) = impact_restitution(1.5, 0.25, 0.0, false, 1e-3, 20);
    samples
        .iter()
        .map(|s| (s[0] * t_s, k * (x_s * s[1].max(0.0)).powf(1.5)))
        .collect()
}

fn hertz_cases(g: &mut Group, label: &str, imp: &Impact, theory: (f64, f64, f64)) {
    let (dmax, fmax, tc) = theory;
    g.cases.push(Case::relative(
        format!("{label}: δmax"),
        SRC3,
        dmax * 1e6,
        imp.max_overlap * 1e6,
        0.005,
        "µm",
    ));
    g.cases.push(Case::relative(
        format!("{label}: Fmax"),
        SRC3,
        fmax / 1e3,
        imp.max_force / 1e3,
        0.005,
        "kN",
    ));
    g.cases.push(Case::relative(
        format!("{label}: t_c"),
        SRC3,
        tc * 1e6,
        imp.duration * 1e6,
        0.02,
        "µs",
    ));
}

/// Tests 1 and 2 with their force–overlap and force–time plots.
fn tests_1_2(g: &mut Group, dir: &Path) -> Result<(), String> {
    let mut fd = Vec::new();
    let mut ft = Vec::new();
    // Test 1: published δmax (total), Fmax, t_c.
    for (name, mat, pubd) in [
        ("glass", glass(), (274.1e-6, 10.70e3, 40.3e-6)),
        ("limestone", limestone(), (368.3e-6, 7.108e3, 54.2e-6)),
    ] {
        let (imp, rebound) = two_spheres(mat, 1, MultiContact::Sum)?;
        hertz_cases(g, &format!("test 1 {name}"), &imp, pubd);
        g.cases.push(Case::relative(
            format!("test 1 {name}: rebound speed"),
            SRC3,
            10.0,
            rebound,
            1e-3,
            "m/s",
        ));
        if name == "glass" {
            let (four, _) = two_spheres(mat, 4, MultiContact::Average)?;
            g.cases.push(Case::relative(
                "test 1 glass, clumps of 4 coincident spheres, `average`: Fmax",
                SRC3,
                pubd.1 / 1e3,
                four.max_force / 1e3,
                0.005,
                "kN",
            ));
            let e_star = effective_modulus(&mat, &mat);
            let m = sphere_mass(0.01, mat.density);
            fd.push(Series::new(
                "test 1 glass (engine)",
                imp.history
                    .iter()
                    .map(|h| (h[1] * 1e6, h[2] / 1e3))
                    .collect(),
                Style::Points,
            ));
            ft.push(Series::new(
                "test 1 glass (engine)",
                imp.history
                    .iter()
                    .map(|h| (h[0] * 1e6, h[2] / 1e3))
                    .collect(),
                Style::Points,
            ));
            ft.push(Series::new(
                "Hertz theory (RK4)",
                hertz_force_time(e_star, 0.005, m / 2.0, 20.0)
                    .iter()
                    .map(|p| (p.0 * 1e6, p.1 / 1e3))
                    .collect(),
                Style::Line,
            ));
            let k = 4.0 / 3.0 * e_star * 0.005f64.sqrt();
            let dmax = imp.max_overlap;
            fd.push(Series::new(
                "Hertz F = (4/3)E*√R* δ^1.5",
                (0..=50)
                    .map(|i| dmax * i as f64 / 50.0)
                    .map(|d| (d * 1e6, k * d.powf(1.5) / 1e3))
                    .collect(),
                Style::Line,
            ));
        }
    }
    // Test 2: sphere R = 0.1 m on a rigid wall at 0.2 m/s.
    for (name, mat, pubd) in [
        ("Al alloy", al_alloy(), (49.72e-6, 11.37e3, 731.7e-6)),
        ("Mg alloy", mg_alloy(), (52.12e-6, 7.233e3, 767.1e-6)),
    ] {
        let (imp, v1, _) = onto_wall(
            mat,
            props(1.0, 0.0),
            0.1,
            DVec3::new(0.0, 0.0, -0.2),
            DVec3::ZERO,
            5e-7,
        )?;
        hertz_cases(g, &format!("test 2 {name}"), &imp, pubd);
        g.cases.push(Case::relative(
            format!("test 2 {name}: rebound speed"),
            SRC3,
            0.2,
            v1.z,
            1e-3,
            "m/s",
        ));
        if name == "Al alloy" {
            let e_star = effective_modulus(&mat, &Material::rigid());
            let k = 4.0 / 3.0 * e_star * 0.1f64.sqrt();
            let m = sphere_mass(0.1, mat.density);
            let mut c = Chart {
                title: "Chung & Ooi test 2 (Al alloy on a rigid wall): force vs time".into(),
                x_label: "time since first contact (µs)".into(),
                y_label: "contact force (kN)".into(),
                series: vec![Series::new(
                    "engine",
                    imp.history
                        .iter()
                        .step_by(10)
                        .map(|h| (h[0] * 1e6, h[2] / 1e3))
                        .collect(),
                    Style::Points,
                )],
            };
            c.series.push(Series::new(
                "Hertz theory (RK4)",
                hertz_force_time(e_star, 0.1, m, 0.2)
                    .iter()
                    .map(|p| (p.0 * 1e6, p.1 / 1e3))
                    .collect(),
                Style::Line,
            ));
            g.plot(
                "chung_ooi_test2_force_time.png",
                "Test 2, Al alloy: contact force vs time, engine against the Hertz solution",
                draw(&dir.join("chung_ooi_test2_force_time.png"), &c),
            );
            let dmax = imp.max_overlap;
            let c2 = Chart {
                title: "Chung & Ooi test 2 (Al alloy): force vs overlap".into(),
                x_label: "overlap δ (µm)".into(),
                y_label: "contact force (kN)".into(),
                series: vec![
                    Series::new(
                        "engine",
                        imp.history
                            .iter()
                            .step_by(10)
                            .map(|h| (h[1] * 1e6, h[2] / 1e3))
                            .collect(),
                        Style::Points,
                    ),
                    Series::new(
                        "Hertz F = (4/3)E*√R δ^1.5",
                        (0..=50)
                            .map(|i| dmax * i as f64 / 50.0)
                            .map(|d| (d * 1e6, k * d.powf(1.5) / 1e3))
                            .collect(),
                        Style::Line,
                    ),
                ],
            };
            g.plot(
                "chung_ooi_test2_force_overlap.png",
                "Test 2, Al alloy: force vs overlap against Hertz",
                draw(&dir.join("chung_ooi_test2_force_overlap.png"), &c2),
            );
        }
    }
    let c = Chart {
        title: "Chung & Ooi test 1 (glass spheres, ±10 m/s): force vs overlap".into(),
        x_label: "total overlap δ (µm)".into(),
        y_label: "contact force (kN)".into(),
        series: fd,
    };
    g.plot(
        "chung_ooi_test1_force_overlap.png",
        "Test 1, glass: force vs overlap against Hertz",
        draw(&dir.join("chung_ooi_test1_force_overlap.png"), &c),
    );
    let c = Chart {
        title: "Chung & Ooi test 1 (glass spheres, ±10 m/s): force vs time".into(),
        x_label: "time since first contact (µs)".into(),
        y_label: "contact force (kN)".into(),
        series: ft,
    };
    g.plot(
        "chung_ooi_test1_force_time.png",
        "Test 1, glass: force vs time against the Hertz solution",
        draw(&dir.join("chung_ooi_test1_force_time.png"), &c),
    );
    Ok(())
}

/// Test 3: restitution out vs in, Hertz and linear laws with exact damping,
/// Hertz with the LIGGGHTS damping shown for contrast.
fn test_3(g: &mut Group, dir: &Path) -> Result<(), String> {
    let (r, v) = (2.5e-3, 3.9);
    let mut series = vec![Series::new(
        "1:1 (input e)",
        vec![(0.0, 0.0), (1.0, 1.0)],
        Style::Dashed,
    )];
    for (name, mat) in [("alumina", alumina()), ("cast iron", cast_iron())] {
        let m = sphere_mass(r, mat.density);
        let kn = 1e7;
        let tc_lin = std::f64::consts::PI * (m / kn).sqrt();
        let laws = [
            ("Hertz", NormalLaw::Hertz, DampingLaw::Exact, 1e-8),
            (
                "linear",
                NormalLaw::Linear {
                    kn,
                    kt: 2.0 / 7.0 * kn,
                },
                DampingLaw::Exact,
                tc_lin / 2000.0,
            ),
            (
                "Hertz, LIGGGHTS damping",
                NormalLaw::Hertz,
                DampingLaw::Liggghts,
                1e-8,
            ),
        ];
        for (law, normal, damping, dt) in laws {
            let mut pts = Vec::new();
            let mut worst: f64 = 0.0;
            for k in 0..=5 {
                let e = 0.2 * k as f64;
                let p = PairProperties {
                    restitution: e,
                    friction: 0.0,
                    normal,
                    damping,
                    ..PairProperties::default()
                };
                let (_, v1, _) = onto_wall(mat, p, r, DVec3::new(0.0, 0.0, -v), DVec3::ZERO, dt)?;
                let e_out = (v1.z / v).max(0.0);
                pts.push((e, e_out));
                if k >= 1 {
                    worst = worst.max((e_out - e).abs());
                }
            }
            if damping == DampingLaw::Exact {
                g.cases.push(Case::at_most(
                    format!("test 3 {name}, {law}: max |e_out − e_in|, e_in ∈ {{0.2,…,1}}"),
                    SRC3,
                    "0 (1:1 line)",
                    worst,
                    0.01,
                ));
            } else {
                g.notes.push(format!("test 3 {name}, {law}: max |e_out − e_in| = {worst:.4} (the ln e formula is biased upwards under the tensile clamp, for Hertz and linear alike; exact without it; REFERENCE.md §3; reported, not a case)"));
            }
            if name == "alumina" || damping == DampingLaw::Exact {
                series.push(Series::new(
                    format!("{name}, {law}"),
                    pts,
                    Style::LinePoints,
                ));
            }
        }
    }
    let c = Chart {
        title: "Chung & Ooi test 3: restitution out vs in (R = 2.5 mm, 3.9 m/s)".into(),
        x_label: "input restitution e_in".into(),
        y_label: "measured restitution e_out".into(),
        series,
    };
    g.plot("chung_ooi_test3_restitution.png", "Test 3: measured vs input restitution, Hertz and linear laws (exact damping) on the 1:1 line", draw(&dir.join("chung_ooi_test3_restitution.png"), &c));
    Ok(())
}

/// Analytic rebound of a sphere (κ = 2/5) on a plane with normal +z when the
/// contact slides throughout: impulse `μ(1+e)m v_n` against the slip
/// direction (along x). Returns `(v_x', v_z', ω_y')`.
pub(crate) fn gross_sliding(v: DVec3, omega_y: f64, r: f64, e: f64, mu: f64) -> (f64, f64, f64) {
    let vn = -v.z;
    let slip = v.x - r * omega_y; // contact-point velocity along x
    let j = mu * (1.0 + e) * vn * slip.signum();
    (v.x - j, e * vn, omega_y + 2.5 * j / r)
}

/// Whether the contact of [`gross_sliding`] still slips at the end of the impact.
pub(crate) fn slides_throughout(v: DVec3, omega_y: f64, r: f64, e: f64, mu: f64) -> bool {
    let slip = v.x - r * omega_y;
    slip.abs() > 3.5 * mu * (1.0 + e) * (-v.z)
}

fn oblique(
    g: &mut Group,
    label: &str,
    mat: Material,
    r: f64,
    e: f64,
    mu: f64,
    v: DVec3,
    omega_y: f64,
    dt: f64,
) -> Result<(f64, f64), String> {
    let (_, v1, w1) = onto_wall(mat, props(e, mu), r, v, DVec3::new(0.0, omega_y, 0.0), dt)?;
    if slides_throughout(v, omega_y, r, e, mu) {
        let (vx, vz, wy) = gross_sliding(v, omega_y, r, e, mu);
        let err = rel_err(v1.x, vx)
            .max(rel_err(w1.y, wy))
            .max(rel_err(v1.z, vz));
        g.cases.push(Case {
            name: format!("{label}: v_t', v_n', ω'"),
            source: SRC_IMPULSE.into(),
            expected: format!("{:.4} m/s, {:.4} m/s, {:.2} rad/s", vx, vz, wy),
            measured: format!(
                "{:.4} m/s, {:.4} m/s, {:.2} rad/s (max rel. err {:.2e})",
                v1.x, v1.z, w1.y, err
            ),
            tolerance: "±1 % each".into(),
            pass: err <= 0.01,
        });
    }
    Ok((v1.x, w1.y))
}

/// Tests 4–6: oblique impacts, friction, spin.
fn tests_4_to_6(g: &mut Group, dir: &Path, quick: bool) -> Result<(), String> {
    // Test 4: alumina, R = 2.5 mm, |v| = 3.9 m/s, e = 0.98, μ = 0.092, angle from the normal.
    let (r, e, mu, speed) = (2.5e-3, 0.98, 0.092, 3.9);
    let angles: Vec<f64> = if quick {
        vec![40.0, 60.0, 80.0]
    } else {
        (1..=17).map(|k| 5.0 * k as f64).collect()
    };
    let mut sim = Vec::new();
    for deg in angles {
        let th = f64::to_radians(deg);
        let v = DVec3::new(speed * th.sin(), 0.0, -speed * th.cos());
        let (vx, _) = oblique(
            g,
            &format!("test 4, θ = {deg}°"),
            alumina(),
            r,
            e,
            mu,
            v,
            0.0,
            1e-8,
        )?;
        sim.push((deg, vx / v.x));
    }
    let theory: Vec<(f64, f64)> = (1..=89)
        .map(|d| {
            let t = f64::to_radians(d as f64);
            (d as f64, (1.0 - mu * (1.0 + e) / t.tan()).max(5.0 / 7.0))
        })
        .collect();
    let c = Chart {
        title: "Chung & Ooi test 4: tangential restitution vs impact angle".into(),
        x_label: "impact angle from the normal θ (deg)".into(),
        y_label: "v_t' / v_t".into(),
        series: vec![
            Series::new("engine", sim, Style::Points),
            Series::new(
                "rigid theory: 1 − μ(1+e)/tanθ, or 5/7 (rolling)",
                theory,
                Style::Dashed,
            ),
        ],
    };
    g.plot("chung_ooi_test4_tangential.png", "Test 4: v_t'/v_t against the rigid-body solution (exact on the gross-sliding branch θ ≳ 32.5°; below it tangential compliance makes the engine differ from the 5/7 rigid limit, as in the paper)", draw(&dir.join("chung_ooi_test4_tangential.png"), &c));
    // Test 5: Al alloy R = 0.1 m at 0.2 m/s, 60° from the normal, e = 0.5, several μ
    // (about 1500 steps each; --quick runs the largest μ).
    let mus: &[f64] = if quick {
        &[0.3]
    } else {
        &[0.05, 0.1, 0.2, 0.3]
    };
    for &mu in mus {
        let th = f64::to_radians(60.0);
        let v = DVec3::new(0.2 * th.sin(), 0.0, -0.2 * th.cos());
        oblique(
            g,
            &format!("test 5, Al alloy, θ = 60°, e = 0.5, μ = {mu}"),
            al_alloy(),
            0.1,
            0.5,
            mu,
            v,
            0.0,
            5e-7,
        )?;
    }
    // Test 6: alumina with back-spin and strong top-spin (friction reverses).
    for (spin, name) in [
        (-200.0, "back-spin −200 rad/s"),
        (1000.0, "top-spin +1000 rad/s (slip reversed)"),
    ] {
        let v = DVec3::new(1.0, 0.0, -1.0);
        oblique(
            g,
            &format!("test 6, alumina, v = (1, −1) m/s, {name}"),
            alumina(),
            r,
            e,
            mu,
            v,
            spin,
            1e-8,
        )?;
    }
    Ok(())
}

/// Test 7: head-on impact with spins that make the contact surfaces move
/// together (REFERENCE.md §3): no slip, spins and tangential velocities unchanged.
fn test_7(g: &mut Group) -> Result<(), String> {
    let (r, omega, mat) = (0.1, 10.0, al_alloy());
    let mut w = world(mat, props(0.5, 0.4), 5e-7, open_box(10.0), DVec3::ZERO)?;
    let t = w
        .add_template(coincident_spheres(1, r, mat.density)?, PARTICLE)
        .map_err(|e| e.to_string())?;
    let mut add = |s: f64| {
        w.add_body(&body(
            t,
            DVec3::new(s * (r + 1e-6), 0.0, 0.0),
            DQuat::IDENTITY,
            DVec3::new(-s * 0.2, 0.0, 0.0),
            DVec3::new(0.0, 0.0, -s * omega),
        ))
    };
    let a = add(-1.0).map_err(|e| e.to_string())?;
    let b = add(1.0).map_err(|e| e.to_string())?;
    run_impact(&mut w, a, r, 1_000_000)?;
    let ((va, wa), (vb, wb)) = (motion(&w, a)?, motion(&w, b)?);
    let spin_err = ((wa.z - omega).abs() / omega).max((wb.z + omega).abs() / omega);
    g.cases.push(Case::at_most(
        "test 7: spin change |ω' − ω|/ω",
        SRC3,
        "0",
        spin_err,
        1e-6,
    ));
    g.cases.push(Case::at_most(
        "test 7: tangential centre velocity (m/s)",
        SRC3,
        "0",
        va.y.abs().max(vb.y.abs()),
        1e-9,
    ));
    Ok(())
}

/// Runs the Chung & Ooi group.
pub fn run(sel: Selection, dir: &Path) -> Group {
    let mut g = Group::default();
    g.notes.push("Sphere–wall cases: a rigid plane z = 0, normal +z; angles from the normal; ω about world y. Tests 4–6 are asserted only where the contact slides throughout the impact, where the rigid impulse solution is exact: v_t' = v_t − μ(1+e)v_n·sgn(slip), ω' = ω + (5/2)μ(1+e)v_n·sgn(slip)/R.".into());
    g.notes.push(TEST5_NOTE.into());
    let quick = sel == Selection::Quick;
    type Step<'a> = Box<dyn Fn(&mut Group) -> Result<(), String> + 'a>;
    let steps: Vec<(&str, Step)> = vec![
        ("tests 1-2", Box::new(|g: &mut Group| tests_1_2(g, dir))),
        ("test 3", Box::new(|g: &mut Group| test_3(g, dir))),
        (
            "tests 4-6",
            Box::new(|g: &mut Group| tests_4_to_6(g, dir, quick)),
        ),
        ("test 7", Box::new(test_7)),
    ];
    for (name, f) in steps {
        if let Err(e) = f(&mut g) {
            g.cases.push(Case::error(name, SRC3, e));
        }
    }
    g
}
