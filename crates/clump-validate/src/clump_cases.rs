//! Clump-specific dynamics on a rigid plane z = 0 (normal +z, world
//! frame): a dimer rolling about its axis down an incline, the
//! slip-to-roll transition of a sphere, the rest overlap of a dimer, and
//! the restitution of a dimer dropped flat under `sum` and `average`.

use crate::case::{Case, Group};
use crate::mass::dimer_formula;
use crate::ode::{damping_for_restitution, impact_restitution, slope};
use crate::plot::{draw, Chart, Series, Style};
use crate::setup::*;
use crate::Selection;
use clump_core::contact::{Material, NormalLaw, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::world::World;
use glam::{DQuat, DVec3};
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

const G: f64 = 9.81;
/// Sphere radius (m) and half distance between the dimer's centres (m).
const R: f64 = 1e-3;
const HALF_GAP: f64 = 0.5e-3;

fn soft() -> Material {
    material(1e7, 0.3, 2500.0)
}

/// A world with the dimer (axis along world y) or a sphere resting on the
/// plane z = 0 at height `z`; returns the world and the body id.
fn on_plane(
    p: PairProperties,
    gravity: DVec3,
    dimer_body: bool,
    z: f64,
    v: DVec3,
    dt: f64,
) -> Result<(World, u64), String> {
    let mat = soft();
    let mut w = world(mat, p, dt, open_box(10.0), gravity)?;
    let t = if dimer_body {
        dimer(R, HALF_GAP, mat.density)?
    } else {
        coincident_spheres(1, R, mat.density)?
    };
    let t = w.add_template(t, PARTICLE).map_err(|e| e.to_string())?;
    // body x (the dimer axis, smallest moment) along world y
    let q = DQuat::from_rotation_z(FRAC_PI_2);
    let id = w
        .add_body(&body(t, DVec3::new(0.0, 0.0, z), q, v, DVec3::ZERO))
        .map_err(|e| e.to_string())?;
    w.add_wall(plane(DVec3::ZERO, DVec3::Z))
        .map_err(|e| e.to_string())?;
    w.prepare().map_err(|e| e.to_string())?;
    Ok((w, id))
}

fn incline(g: &mut Group, dir: &Path) -> Result<(), String> {
    let theta = 20f64.to_radians();
    let gravity = DVec3::new(G * theta.sin(), 0.0, -G * theta.cos());
    let dt = 2e-6;
    let (mut w, id) = on_plane(props(0.5, 0.5), gravity, true, R, DVec3::ZERO, dt)?;
    let (v, ia, _) = dimer_formula(R, HALF_GAP, soft().density);
    let kappa = ia / (soft().density * v * R * R);
    let a_exp = G * theta.sin() / (1.0 + kappa);
    let mut hist = Vec::new();
    // 25 000 steps, sampled every 50 (the run loop stops at each sample)
    for _ in 0..500 {
        w.run(50).map_err(|e| e.to_string())?;
        hist.push((w.time, motion(&w, id)?.0.x));
    }
    let fit: Vec<(f64, f64)> = hist.iter().copied().filter(|p| p.0 >= 0.01).collect();
    let a = slope(&fit);
    g.cases.push(Case::relative(
        format!("dimer rolling about its axis down a 20° incline: acceleration (κ = I_axis/mR² = {kappa:.5})"),
        "a = g sinθ/(1 + I_axis/mR²), I_axis from REFERENCE.md §2",
        a_exp,
        a,
        0.01,
        "m/s²",
    ));
    let c = Chart {
        title: "Dimer rolling about its axis down a 20° incline".into(),
        x_label: "time (s)".into(),
        y_label: "velocity down the slope (m/s)".into(),
        series: vec![
            Series::new("engine", hist.clone(), Style::Points),
            Series::new(
                "g sinθ/(1 + I_axis/mR²) · t",
                vec![(0.0, 0.0), (w.time, a_exp * w.time)],
                Style::Dashed,
            ),
            Series::new(
                "sliding without rotation, g sinθ · t",
                vec![(0.0, 0.0), (w.time, G * theta.sin() * w.time)],
                Style::Dashed,
            ),
        ],
    };
    g.plot(
        "clump_dimer_incline.png",
        "Dimer (R = 1 mm, centres 1 mm apart) rolling about its axis down a 20° incline (μ = 0.5)",
        draw(&dir.join("clump_dimer_incline.png"), &c),
    );
    Ok(())
}

fn slip_to_roll(g: &mut Group, dir: &Path) -> Result<(), String> {
    let v0 = 0.5;
    let mu = 0.3;
    let (mut w, id) = on_plane(
        props(0.5, mu),
        DVec3::new(0.0, 0.0, -G),
        false,
        R,
        DVec3::new(v0, 0.0, 0.0),
        4e-6,
    )?;
    let (mut hv, mut hw) = (Vec::new(), Vec::new());
    // 40 000 steps, sampled every 400 (the run loop stops at each sample)
    for _ in 0..100 {
        w.run(400).map_err(|e| e.to_string())?;
        let (v, om) = motion(&w, id)?;
        hv.push((w.time, v.x));
        hw.push((w.time, om.y * R));
    }
    let (v, om) = motion(&w, id)?;
    let vf = v0 / (1.0 + 0.4);
    let src = "v_f = v0/(1 + κ), κ = 2/5 (angular momentum about the contact point)";
    g.cases.push(Case::relative(
        "sphere slip-to-roll on a flat (v0 = 0.5 m/s, μ = 0.3): final velocity",
        src,
        vf,
        v.x,
        0.01,
        "m/s",
    ));
    g.cases.push(Case::relative(
        "sphere slip-to-roll: final rolling speed ω_y R",
        src,
        vf,
        om.y * R,
        0.01,
        "m/s",
    ));
    let t_roll = 2.0 * v0 / (7.0 * mu * G);
    let theory_v = vec![(0.0, v0), (t_roll, vf), (w.time, vf)];
    let theory_w = vec![(0.0, 0.0), (t_roll, vf), (w.time, vf)];
    let c = Chart {
        title: "Sphere sliding into rolling on a flat (v0 = 0.5 m/s, μ = 0.3)".into(),
        x_label: "time (s)".into(),
        y_label: "speed (m/s)".into(),
        series: vec![
            Series::new("engine v_x", hv, Style::Points),
            Series::new("engine ω_y R", hw, Style::Points),
            Series::new("theory v_x", theory_v, Style::Dashed),
            Series::new("theory ω_y R", theory_w, Style::Dashed),
        ],
    };
    g.plot("clump_slip_to_roll.png", "Slip-to-roll transition: centre speed and rolling speed against the Coulomb-sliding solution", draw(&dir.join("clump_slip_to_roll.png"), &c));
    Ok(())
}

fn rest_overlap(g: &mut Group) -> Result<(), String> {
    let (mut w, id) = on_plane(
        props(0.3, 0.5),
        DVec3::new(0.0, 0.0, -G),
        true,
        R,
        DVec3::ZERO,
        4e-6,
    )?;
    w.run(10_000).map_err(|e| e.to_string())?;
    let b = w.body_index(id).ok_or("body lost")?;
    let delta = R - w.bodies().position[b].z;
    let f = 0.5 * w.bodies().mass[b] * G;
    let e_star = effective_modulus(&soft(), &Material::rigid());
    let expected = (3.0 * f / (4.0 * e_star * R.sqrt())).powf(2.0 / 3.0);
    g.cases.push(Case::relative(
        "dimer at rest on a plane: overlap of each sphere (F = Mg/2)",
        "Hertz δ = (3F/(4E*√R))^(2/3)",
        expected * 1e9,
        delta * 1e9,
        0.005,
        "nm",
    ));
    Ok(())
}

/// Rebound speed ratio of a dimer (R = 1 mm, centres 1.2 mm apart) dropped
/// flat at 1 m/s onto the plane (both spheres hit together).
fn dimer_drop(normal: NormalLaw, e: f64, multi: MultiContact) -> Result<f64, String> {
    let mat = material(1e8, 0.3, 2500.0);
    let p = PairProperties {
        restitution: e,
        friction: 0.0,
        normal,
        ..PairProperties::default()
    };
    let mut w = world(mat, p, 2e-8, open_box(1.0), DVec3::ZERO)?;
    let t = w
        .add_template(dimer(R, 0.6e-3, mat.density)?, PARTICLE)
        .map_err(|e| e.to_string())?;
    let id = w
        .add_body(&body(
            t,
            DVec3::new(0.0, 0.0, R + 1e-7),
            DQuat::IDENTITY,
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::ZERO,
        ))
        .map_err(|e| e.to_string())?;
    let mut wall = plane(DVec3::ZERO, DVec3::Z);
    wall.multi_contact = multi;
    w.add_wall(wall).map_err(|e| e.to_string())?;
    run_impact(&mut w, id, R, 10_000_000)?;
    Ok(motion(&w, id)?.0.z)
}

fn dimer_flat(g: &mut Group, quick: bool) -> Result<(), String> {
    let es: &[f64] = if quick { &[0.5] } else { &[0.3, 0.5, 0.8] };
    let lin = NormalLaw::Linear { kn: 2e4, kt: 0.0 };
    for &e in es {
        // The contact force is clamped at zero (non-cohesive, the default):
        // the reference ODEs clamp it too. Damping constant for one contact
        // from e, then ×√2 for two contacts summed on the same body mass.
        let h = 1e-4;
        let sum_e = |p: f64, q: f64| {
            let c = damping_for_restitution(p, q, e, true, h);
            impact_restitution(p, q, 2f64.sqrt() * c, true, h, usize::MAX).0
        };
        let e_sum_lin = sum_e(1.0, 0.0);
        let e_sum_hertz = sum_e(1.5, 0.25);
        let src_avg = "`average`: one contact's stiffness and damping, so e_out = e_in";
        let src_lin = "`sum`: linear x'' = −max(x + c x', 0) with c ×√2 (RK4, engine-independent; closed form exp(−2ζA(ζ)), ζ = √2ζ₁)";
        let src_h =
            "`sum`: Hertz–Tsuji x'' = −max(x^1.5 + c x^¼ x', 0) with c ×√2 (RK4, engine-independent)";
        for (law, normal, multi, exp, src) in [
            ("linear", lin, MultiContact::Average, e, src_avg),
            ("linear", lin, MultiContact::Sum, e_sum_lin, src_lin),
            ("Hertz", NormalLaw::Hertz, MultiContact::Average, e, src_avg),
            (
                "Hertz",
                NormalLaw::Hertz,
                MultiContact::Sum,
                e_sum_hertz,
                src_h,
            ),
        ] {
            let got = dimer_drop(normal, e, multi)?;
            let m = if multi == MultiContact::Sum {
                "sum"
            } else {
                "average"
            };
            g.cases.push(Case::absolute(
                format!("dimer dropped flat, {law}, `{m}`, e_in = {e}: restitution"),
                src,
                exp,
                got,
                0.01,
                "",
            ));
        }
    }
    Ok(())
}

/// Runs the clump-specific group.
pub fn run(sel: Selection, dir: &Path) -> Group {
    let mut g = Group::default();
    g.notes.push("Material E = 1e7 Pa, ν = 0.3, ρ = 2500 kg/m³ on a rigid plane (dimer drop: E = 1e8 Pa, linear k_n = 2e4 N/m); Hertz normal law with exact damping, normal force clamped at zero (the default); dimer = two spheres R = 1 mm, centres 1 mm apart (drop: 1.2 mm). The incline is modelled by tilting gravity, g = 9.81 (sin 20°, 0, −cos 20°) m/s²; the acceleration is a least-squares fit of v(t) for t ≥ 10 ms.".into());
    let quick = sel == Selection::Quick;
    if let Err(e) = incline(&mut g, dir) {
        g.cases
            .push(Case::error("dimer on an incline", "analytic", e));
    }
    if let Err(e) = slip_to_roll(&mut g, dir) {
        g.cases.push(Case::error("slip-to-roll", "analytic", e));
    }
    if let Err(e) = rest_overlap(&mut g) {
        g.cases.push(Case::error("rest overlap", "Hertz", e));
    }
    if let Err(e) = dimer_flat(&mut g, quick) {
        g.cases
            .push(Case::error("dimer dropped flat", "analytic", e));
    }
    g
}
