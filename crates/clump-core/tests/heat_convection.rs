//! Convection from the fluid (docs/theory.md T-90 … T-93) against the
//! lumped-capacitance closed form `T(t) = T_f + (T₀ − T_f) exp(−h A t / (m c))`,
//! with `h` from the Ranz–Marshall correlation written here from the paper
//! (Nu = 2 + 0.6 Re^½ Pr^⅓, Re = ρ_f w d / μ, Pr = c_f μ / k_f), for a
//! sphere held in a uniform flow, in still fluid, with the fluid velocity
//! set per body, and a dumbbell clump on its volume-equivalent diameter
//! and its true (union) surface area in closed form.

mod common;
use clump_core::body::BodyInit;
use clump_core::contact::{Material, PairProperties};
use clump_core::fluid::{DragLaw, Fluid};
use clump_core::heat::{Conductance, FluidHeat, HeatModel, ThermalMaterial};
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::world::World;
use common::*;
use glam::{DQuat, DVec3};
use std::f64::consts::PI;

/// Glass particles.
const RHO_P: f64 = 2500.0;
const CP_P: f64 = 800.0;
const K_P: f64 = 1.0;
/// Water at about 20 °C.
const RHO_F: f64 = 1000.0;
const MU: f64 = 1e-3;
const K_F: f64 = 0.6;
const CP_F: f64 = 4180.0;
const T_F: f64 = 350.0;
const T0: f64 = 300.0;

fn glass() -> Material {
    Material {
        youngs_modulus: 1e7,
        poisson_ratio: 0.3,
        density: RHO_P,
    }
}

fn water(u: DVec3) -> Fluid {
    Fluid {
        density: RHO_F,
        viscosity: MU,
        velocity: u,
        pressure_gradient: DVec3::ZERO,
        drag: DragLaw::SchillerNaumann,
        buoyancy: true,
    }
}

fn fluid_heat() -> FluidHeat {
    FluidHeat {
        temperature: T_F,
        conductivity: K_F,
        specific_heat: CP_F,
    }
}

/// Ranz & Marshall (1952): the heat transfer coefficient, W/(m² K), of a
/// body of volume-equivalent diameter `d` at slip speed `w` in water.
fn h_ranz_marshall(d: f64, w: f64) -> f64 {
    let re = RHO_F * w * d / MU;
    let pr = CP_F * MU / K_F;
    (2.0 + 0.6 * re.sqrt() * pr.powf(1.0 / 3.0)) * K_F / d
}

/// A world holding one body of template `t` in place at the origin, in a
/// fluid of velocity `u` at `T_F`, with heat on (the body at `T0`).
fn held_in_flow(t: ClumpTemplate, u: DVec3, dt: f64) -> World {
    let mut w = world(
        glass(),
        PairProperties::default(),
        dt,
        open_domain(1.0),
        DVec3::ZERO,
    );
    let ti = w.add_template(t, 0).unwrap();
    let thermal = ThermalMaterial {
        conductivity: K_P,
        specific_heat: CP_P,
    };
    w.enable_heat(HeatModel {
        conductance: Conductance::BatchelorObrien,
        materials: vec![Some(thermal), None],
        wall_temperature: vec![],
        template_temperature: vec![T0],
        template_source: vec![0.0],
    })
    .unwrap();
    w.add_body(&BodyInit {
        force_flag: [false; 3],
        torque_flag: [false; 3],
        ..BodyInit::at_rest(ti, DVec3::ZERO, DQuat::IDENTITY)
    })
    .unwrap();
    w.set_fluid(Some(water(u))).unwrap();
    w.set_fluid_heat(Some(fluid_heat())).unwrap();
    w
}

fn sphere(d: f64) -> ClumpTemplate {
    ClumpTemplate::from_spheres("sphere", &[Sphere::new(DVec3::ZERO, d / 2.0)], RHO_P).unwrap()
}

/// Steps `w` `steps` times and returns the worst relative error of
/// `T − T_f` against the closed form with rate `lambda` (1/s).
fn worst_against_closed_form(w: &mut World, steps: usize, lambda: f64) -> f64 {
    let dt = w.config.dt;
    let mut worst = 0.0f64;
    for n in 1..=steps {
        w.step().unwrap();
        let t = w.bodies().temperature[0];
        let exact = T_F + (T0 - T_F) * (-lambda * dt * n as f64).exp();
        worst = worst.max(rel(t - T_F, exact - T_F));
    }
    worst
}

/// A 2 mm glass sphere held in water flowing at 0.1 m/s (Re = 200,
/// Pr = 6.97): its temperature follows the lumped closed form with the
/// Ranz–Marshall h and the sphere's area, to round-off (the step is exact
/// for convection alone, T-93), also at a step twice the relaxation time
/// (an explicit Euler step would diverge there).
#[test]
fn sphere_in_uniform_flow_follows_the_lumped_closed_form() {
    let (d, u) = (2e-3, 0.1);
    let h = h_ranz_marshall(d, u);
    let (area, mass) = (PI * d * d, RHO_P * PI * d.powi(3) / 6.0);
    let lambda = h * area / (mass * CP_P);
    println!(
        "h = {h:.6} W/(m² K), relaxation time {:.6e} s",
        1.0 / lambda
    );
    for (x, steps) in [(1e-3, 3000), (2.0, 3)] {
        let mut w = held_in_flow(sphere(d), DVec3::new(u, 0.0, 0.0), x / lambda);
        let worst = worst_against_closed_form(&mut w, steps, lambda);
        println!("λ dt = {x}: worst relative error of T − T_f {worst:.3e}");
        assert!(worst < 1e-10, "λ dt = {x}: {worst:e}");
        let q = w.heat.as_ref().unwrap().fluid_flow;
        let t = w.bodies().temperature[0];
        // the last step's flow at the step's start temperature: below
        // h A (T_f − T) at its end, as the body warmed over the step
        assert!(q > h * area * (T_F - t), "fluid flow {q} W");
    }
}

/// In still fluid (and with the fluid moving with a body that has no
/// velocity set per body) Nu = 2: h = 2 k_f / d. The fluid velocity a
/// driver sets per body replaces the uniform one, to the bit.
#[test]
fn still_fluid_and_per_body_velocity() {
    let d = 1e-3;
    let lambda0 = h_ranz_marshall(d, 0.0) * 6.0 / (d * RHO_P * CP_P);
    assert!(rel(h_ranz_marshall(d, 0.0), 2.0 * K_F / d) < 1e-15);
    let mut still = held_in_flow(sphere(d), DVec3::ZERO, 1e-3 / lambda0);
    assert!(worst_against_closed_form(&mut still, 500, lambda0) < 1e-10);

    let u = DVec3::new(0.0, 0.03, -0.04);
    let mut uniform = held_in_flow(sphere(d), u, 1e-3 / lambda0);
    let mut per_body = held_in_flow(sphere(d), DVec3::ZERO, 1e-3 / lambda0);
    per_body.set_body_fluid_velocities(&[u]).unwrap();
    for _ in 0..200 {
        uniform.step().unwrap();
        per_body.step().unwrap();
    }
    let (a, b) = (
        uniform.bodies().temperature[0],
        per_body.bodies().temperature[0],
    );
    assert_eq!(a.to_bits(), b.to_bits());
    let lambda = h_ranz_marshall(d, 0.05) * 6.0 / (d * RHO_P * CP_P);
    let exact = T_F + (T0 - T_F) * (-lambda * 200.0 * 1e-3 / lambda0).exp();
    assert!(rel(a - T_F, exact - T_F) < 1e-10, "{a} {exact}");
}

/// A dumbbell (two spheres of radius r, centres s apart) in a flow: h on
/// its volume-equivalent diameter, A its union's surface area, both in
/// closed form here: `V = 2 (4/3 π r³) − π (4r + s)(2r − s)²/12`,
/// `A = 2 (4π r²) − 2 (2π r (r − s/2))`. The code finds the union's area on
/// a lattice of 8192 points per sphere, so the rate agrees to ~1e-4.
#[test]
fn clump_on_its_volume_equivalent_diameter_and_true_area() {
    let (r, s, u) = (0.5e-3, 0.8e-3, 0.05);
    let spheres = [
        Sphere::new(DVec3::new(-s / 2.0, 0.0, 0.0), r),
        Sphere::new(DVec3::new(s / 2.0, 0.0, 0.0), r),
    ];
    let t = ClumpTemplate::from_spheres("dumbbell", &spheres, RHO_P).unwrap();
    let vol = 2.0 * 4.0 / 3.0 * PI * r.powi(3) - PI * (4.0 * r + s) * (2.0 * r - s).powi(2) / 12.0;
    let area = 2.0 * 4.0 * PI * r * r - 2.0 * 2.0 * PI * r * (r - s / 2.0);
    let dv = (6.0 * vol / PI).cbrt();
    let lambda = h_ranz_marshall(dv, u) * area / (RHO_P * vol * CP_P);
    let mut w = held_in_flow(t, DVec3::new(0.0, u, 0.0), 1e-3 / lambda);
    let worst = worst_against_closed_form(&mut w, 2000, lambda);
    println!("dumbbell: worst relative error of T − T_f {worst:.3e}");
    assert!(worst < 1e-3, "{worst:e}");
    // the area is the union's, not the volume-equivalent sphere's (which
    // would be slower by the sphericity, here 0.96)
    let lambda_v = h_ranz_marshall(dv, u) * PI * dv * dv / (RHO_P * vol * CP_P);
    assert!(lambda_v < 0.97 * lambda);
}

/// Convection needs heat and a fluid, and positive fluid properties.
#[test]
fn bad_convection_is_refused() {
    let mut w = world(
        glass(),
        PairProperties::default(),
        1e-5,
        open_domain(1.0),
        DVec3::ZERO,
    );
    let e = w
        .set_fluid_heat(Some(fluid_heat()))
        .unwrap_err()
        .to_string();
    assert!(e.contains("set_fluid first"), "{e}");
    let mut w = held_in_flow(sphere(1e-3), DVec3::ZERO, 1e-5);
    for (bad, what) in [
        (
            FluidHeat {
                temperature: 0.0,
                ..fluid_heat()
            },
            "temperature must be > 0 K",
        ),
        (
            FluidHeat {
                conductivity: -1.0,
                ..fluid_heat()
            },
            "conductivity must be > 0",
        ),
        (
            FluidHeat {
                specific_heat: f64::NAN,
                ..fluid_heat()
            },
            "specific heat must be > 0",
        ),
    ] {
        let e = w.set_fluid_heat(Some(bad)).unwrap_err().to_string();
        assert!(e.contains(what), "{e}");
    }
    assert_eq!(w.fluid_heat(), Some(fluid_heat()));
}
