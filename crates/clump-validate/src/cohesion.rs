//! Cohesion against values from outside the code: LIGGGHTS' own
//! `cohesion sjkr` run side by side (fixtures `sjkr_wall.*`, `sjkr_pair.*`
//! in `crates/clump-core/tests/fixtures/liggghts`), and JKR against its
//! closed forms (Johnson, Kendall & Roberts 1971; Thornton & Ning 1998).

use crate::liggghts::table;
use crate::setup::{body, coincident_spheres, material, open_box, plane, world, PARTICLE};
use clump_core::contact::{CohesionLaw, DampingLaw, Material, PairProperties};
use clump_core::world::World;
use glam::{DQuat, DVec3};
use std::f64::consts::PI;

/// The material and contact of the SJKR fixtures: E = 10 MPa, ν = 0.3,
/// ρ = 2500 kg/m³; e = 0.5, μ = 0.5, LIGGGHTS damping, `limitForce off`,
/// `cohesionEnergyDensity` 2·10⁵ J/m³.
pub fn sjkr_contact() -> (Material, PairProperties) {
    let mat = material(1e7, 0.3, 2500.0);
    let props = PairProperties {
        restitution: 0.5,
        friction: 0.5,
        damping: DampingLaw::Liggghts,
        tensile: true,
        cohesion: CohesionLaw::Sjkr {
            energy_density: 2e5,
        },
        ..PairProperties::default()
    };
    (mat, props)
}

/// A world with the SJKR fixtures' contact, `dt` = 1e-6 s, gravity `g`
/// (m/s², world), no walls.
fn sjkr_world(g: DVec3) -> Result<World, String> {
    let (mat, props) = sjkr_contact();
    world(mat, props, 1e-6, open_box(0.05), g)
}

/// Adds a sphere of radius `r` (m) at `x` (m) moving at `v` (m/s).
fn add_sphere(w: &mut World, r: f64, x: DVec3, v: DVec3) -> Result<u64, String> {
    let t = coincident_spheres(1, r, w.materials[0].density)?;
    let t = w.add_template(t, PARTICLE).map_err(|e| e.to_string())?;
    w.add_body(&body(t, x, DQuat::IDENTITY, v, DVec3::ZERO))
        .map_err(|e| e.to_string())
}

/// Body `id`'s position and velocity (m, m/s, world).
fn motion(w: &World, id: u64) -> (DVec3, DVec3) {
    let b = w.body_index(id).expect("body");
    (w.bodies().position[b], w.bodies().velocity[b])
}

/// `sjkr_wall.in`: a 2 mm sphere dropped at 0.3 m/s onto a plane of its
/// own material, LIGGGHTS' rows `t z vz fz` every 20 steps and Clump's
/// `[z, vz]` at the same steps.
pub fn sjkr_wall() -> Result<(Vec<Vec<f64>>, Vec<[f64; 2]>), String> {
    let rows = table(include_str!(
        "../../clump-core/tests/fixtures/liggghts/sjkr_wall.dat"
    ));
    let mut w = sjkr_world(DVec3::new(0.0, 0.0, -9.81))?;
    let mut floor = plane(DVec3::ZERO, DVec3::Z);
    floor.material = PARTICLE;
    w.add_wall(floor).map_err(|e| e.to_string())?;
    let id = add_sphere(
        &mut w,
        0.002,
        DVec3::new(0.0, 0.0, 0.0021),
        DVec3::new(0.0, 0.0, -0.3),
    )?;
    let mut out = Vec::with_capacity(rows.len());
    for _ in &rows {
        w.run(20).map_err(|e| e.to_string())?;
        let (x, v) = motion(&w, id);
        out.push([x.z, v.z]);
    }
    Ok((rows, out))
}

/// `sjkr_pair.in`: spheres of 2 and 1 mm meeting head-on at 0.2 m/s each,
/// no gravity; LIGGGHTS' rows `t x1 vx1 x2 vx2 fx1` every 20 steps and
/// Clump's `[x1, vx1, x2, vx2]` at the same steps.
pub fn sjkr_pair() -> Result<(Vec<Vec<f64>>, Vec<[f64; 4]>), String> {
    let rows = table(include_str!(
        "../../clump-core/tests/fixtures/liggghts/sjkr_pair.dat"
    ));
    let mut w = sjkr_world(DVec3::ZERO)?;
    let a = add_sphere(
        &mut w,
        0.002,
        DVec3::new(-0.0021, 0.0, 0.0),
        DVec3::new(0.2, 0.0, 0.0),
    )?;
    let b = add_sphere(
        &mut w,
        0.001,
        DVec3::new(0.0011, 0.0, 0.0),
        DVec3::new(-0.2, 0.0, 0.0),
    )?;
    let mut out = Vec::with_capacity(rows.len());
    for _ in &rows {
        w.run(20).map_err(|e| e.to_string())?;
        let ((xa, va), (xb, vb)) = (motion(&w, a), motion(&w, b));
        out.push([xa.x, va.x, xb.x, vb.x]);
    }
    Ok((rows, out))
}

/// Largest deviation of Clump's columns from LIGGGHTS' (`cols[k]` is the
/// LIGGGHTS column of Clump's value `k`), relative to each column's
/// largest magnitude.
pub fn deviation<const N: usize>(rows: &[Vec<f64>], clump: &[[f64; N]], cols: [usize; N]) -> f64 {
    let mut worst = 0.0f64;
    for (k, &c) in cols.iter().enumerate() {
        let scale = rows.iter().map(|r| r[c].abs()).fold(0.0, f64::max);
        for (r, s) in rows.iter().zip(clump) {
            worst = worst.max((s[k] - r[c]).abs() / scale);
        }
    }
    worst
}

/// JKR set-up: E = 10 MPa, ν = 0.3, ρ = 2500 kg/m³, work of adhesion
/// Γ = 0.05 J/m², no damping (e = 1, so the force is the JKR force alone),
/// no friction.
pub fn jkr_contact() -> (Material, PairProperties) {
    let mat = material(1e7, 0.3, 2500.0);
    let props = PairProperties {
        restitution: 1.0,
        friction: 0.0,
        cohesion: CohesionLaw::Jkr {
            surface_energy: 0.05,
        },
        ..PairProperties::default()
    };
    (mat, props)
}

/// The JKR relations computed here independently of the engine
/// (Johnson, Kendall & Roberts 1971): for work of adhesion `g` (J/m²),
/// `R*` (m) and `E*` (Pa).
#[derive(Debug, Clone, Copy)]
pub struct Jkr {
    /// Work of adhesion Γ, J/m².
    pub g: f64,
    /// Effective radius R*, m.
    pub r: f64,
    /// Effective modulus E*, Pa.
    pub e: f64,
}

impl Jkr {
    /// `δ(a) = a²/R* − √(2πΓa/E*)`, m.
    pub fn overlap(&self, a: f64) -> f64 {
        a * a / self.r - (2.0 * PI * self.g * a / self.e).sqrt()
    }
    /// `F(a) = 4E*a³/(3R*) − √(8πΓE*a³)`, N.
    pub fn force(&self, a: f64) -> f64 {
        4.0 * self.e * a.powi(3) / (3.0 * self.r) - (8.0 * PI * self.g * self.e * a.powi(3)).sqrt()
    }
    /// Contact radius at the minimum of `δ(a)`: `a_f = (πΓR*²/(8E*))^{1/3}`.
    pub fn a_break(&self) -> f64 {
        (PI * self.g * self.r * self.r / (8.0 * self.e)).cbrt()
    }
    /// Critical separation `δ_c = −δ(a_f)` (m, positive).
    pub fn delta_c(&self) -> f64 {
        -self.overlap(self.a_break())
    }
    /// Pull-off force magnitude `(3/2)πΓR*`, N.
    pub fn pull_off(&self) -> f64 {
        1.5 * PI * self.g * self.r
    }
    /// The force (N) at overlap `δ ≥ −δ_c` on the stable branch, by
    /// bisection on `a ∈ [a_f, ∞)` (where `δ(a)` increases).
    pub fn force_at(&self, delta: f64) -> f64 {
        let mut lo = self.a_break();
        let mut hi = lo;
        while self.overlap(hi) < delta {
            hi *= 2.0;
        }
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if self.overlap(mid) < delta {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        self.force(0.5 * (lo + hi))
    }
    /// The work (J) the adhesion takes from a contact stretched from
    /// `δ = 0` to `−δ_c`: `W = ∫_{−δ_c}^0 (−F) dδ`, in closed form
    /// `W = (3·2^{2/3}/5 + 1/10) E* a_u⁵/R*²`, `a_u³ = πΓR*²/E*` (the
    /// integral of `F dδ/da` over `a` from `a_f = a_u/2` to
    /// `a_u·2^{1/3}`, where `δ = 0`).
    pub fn break_work(&self) -> f64 {
        let au = (PI * self.g * self.r * self.r / self.e).cbrt();
        (0.6 * 2f64.powf(2.0 / 3.0) + 0.1) * self.e * au.powi(5) / (self.r * self.r)
    }
    /// Critical sticking velocity of an undamped elastic JKR impact of
    /// effective mass `m` (kg): a sphere arriving slower cannot pay the
    /// work [`Self::break_work`] and stays bound, `v_s = √(2W/m*)`
    /// (the energy balance of Thornton & Ning 1998 for elastic adhesive
    /// spheres). Faster, it leaves with `√(v² − v_s²)`.
    pub fn sticking_velocity(&self, m: f64) -> f64 {
        (2.0 * self.break_work() / m).sqrt()
    }
}

/// A JKR sphere pair pressed together and pulled apart quasi-statically:
/// two 1 mm spheres, the first fixed, the second driven at `u` towards it
/// until the overlap is 4 μm, then back until they are `1.5 δ_c` apart.
/// Returns the JKR relations of the pair and per step `(δ, F_n, loading)`:
/// overlap (m), the normal force on the fixed sphere (N, repulsion
/// positive), and whether the driven sphere was approaching.
pub fn jkr_loading_cycle() -> Result<(Jkr, Vec<(f64, f64, bool)>), String> {
    let (mat, props) = jkr_contact();
    let r = 1e-3;
    let e_star = crate::setup::effective_modulus(&mat, &mat);
    let jkr = Jkr {
        g: 0.05,
        r: 0.5 * r,
        e: e_star,
    };
    let dc = jkr.delta_c();
    let dt = 1e-6;
    // a step moves the overlap by δ_c/2000
    let u = dc / 2000.0 / dt;
    let mut w = world(mat, props, dt, open_box(0.05), DVec3::ZERO)?;
    let t = coincident_spheres(1, r, mat.density)?;
    let t = w.add_template(t, PARTICLE).map_err(|e| e.to_string())?;
    let mut fixed = body(t, DVec3::ZERO, DQuat::IDENTITY, DVec3::ZERO, DVec3::ZERO);
    fixed.start_step = clump_core::dof::DRIVEN;
    let mut driven = body(
        t,
        // (the samples do not fall on −δ_c itself)
        DVec3::new(2.0 * r + 0.5 * dc + 0.37 * u * dt, 0.0, 0.0),
        DQuat::IDENTITY,
        DVec3::new(-u, 0.0, 0.0),
        DVec3::ZERO,
    );
    driven.start_step = clump_core::dof::DRIVEN;
    let a = w.add_body(&fixed).map_err(|e| e.to_string())?;
    let b = w.add_body(&driven).map_err(|e| e.to_string())?;
    let mut out = Vec::new();
    let mut loading = true;
    loop {
        w.run(1).map_err(|e| e.to_string())?;
        let ia = w.body_index(a).ok_or("lost body")?;
        let ib = w.body_index(b).ok_or("lost body")?;
        let delta = 2.0 * r - (w.bodies().position[ib] - w.bodies().position[ia]).length();
        out.push((delta, -w.bodies().force[ia].x, loading));
        if loading && delta > 4e-6 {
            loading = false;
            w.set_body_velocity(b, DVec3::new(u, 0.0, 0.0))
                .map_err(|e| e.to_string())?;
        }
        if !loading && delta < -1.5 * dc {
            break;
        }
    }
    Ok((jkr, out))
}

/// A 1 mm JKR sphere hitting a plane of its own material head-on at `v`
/// (m/s), undamped, no gravity, time step `dt` (s): its JKR relations,
/// effective mass (kg) and its velocity (m/s, away from the plane
/// positive) once it has left the plane's reach or after 20 ms; `None`
/// when still bound then.
pub fn jkr_impact(v: f64, dt: f64) -> Result<(Jkr, f64, Option<f64>), String> {
    let (mat, props) = jkr_contact();
    let r = 1e-3;
    let e_star = crate::setup::effective_modulus(&mat, &mat);
    let jkr = Jkr {
        g: 0.05,
        r,
        e: e_star,
    };
    let dc = jkr.delta_c();
    let mut w = world(mat, props, dt, open_box(0.05), DVec3::ZERO)?;
    let mut floor = plane(DVec3::ZERO, DVec3::Z);
    floor.material = PARTICLE;
    w.add_wall(floor).map_err(|e| e.to_string())?;
    let id = add_sphere(
        &mut w,
        r,
        DVec3::new(0.0, 0.0, r + 0.1 * dc),
        DVec3::new(0.0, 0.0, -v),
    )?;
    let m = w.bodies().mass[w.body_index(id).ok_or("lost body")?];
    let mut touched = false;
    for _ in 0..(0.02 / dt) as usize {
        w.run(1).map_err(|e| e.to_string())?;
        let (x, vel) = motion(&w, id);
        let gap = x.z - r;
        touched |= gap < 0.0;
        if touched && gap > 2.0 * dc {
            return Ok((jkr, m, Some(vel.z)));
        }
    }
    Ok((jkr, m, None))
}
