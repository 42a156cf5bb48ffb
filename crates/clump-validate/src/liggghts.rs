//! LIGGGHTS' stone bounces (`crates/clump-core/tests/fixtures/liggghts`):
//! the stone and its state read from LIGGGHTS' printed rows, run in Clump
//! row by row. Shared by the engine tests and the validation cases.

use crate::setup::{body, open_box, plane, world};
use clump_core::contact::{DampingLaw, Material, PairProperties, TangentialLaw};
use clump_core::rotation::RotationScheme;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::world::World;
use glam::{DMat3, DQuat, DVec3};

/// Numeric rows of a LIGGGHTS output file (`#` lines skipped).
pub fn table(text: &str) -> Vec<Vec<f64>> {
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

/// `(x, y, z)` at columns `k..k + 3` of a row.
pub fn v3(r: &[f64], k: usize) -> DVec3 {
    DVec3::new(r[k], r[k + 1], r[k + 2])
}

/// Clump's body state at one of LIGGGHTS' rows (world frame).
#[derive(Debug, Clone, Copy)]
pub struct State {
    /// Centre of mass, m.
    pub x: DVec3,
    /// Velocity, m/s.
    pub v: DVec3,
    /// Orientation (LIGGGHTS' body frame → world).
    pub q: DQuat,
    /// Angular velocity, rad/s.
    pub w: DVec3,
}

/// The bounce of a fixture: `rows` as LIGGGHTS prints them
/// (`t x y z vx vy vz qw qx qy qz wx wy wz Lx Ly Lz I1 I2 I3`, every
/// `every` steps of `dt`), the stone's spheres from LIGGGHTS' world
/// positions at the first row (`id x y z r`), body mass `mass` (kg);
/// Clump starts from the first row and returns its state at every row.
/// `wall_material`: 1 (the rigid wall material of [`world`]) or 0 (the
/// stone's own material, as LIGGGHTS' tutorial).
#[allow(clippy::too_many_arguments)]
pub fn run_bounce(
    rows: &[Vec<f64>],
    spheres_text: &str,
    mass: f64,
    mat: Material,
    props: PairProperties,
    wall_material: u16,
    scheme: RotationScheme,
    dt: f64,
    every: usize,
) -> Vec<State> {
    let r0 = &rows[0];
    let (x0, q0) = (v3(r0, 1), DQuat::from_xyzw(r0[8], r0[9], r0[10], r0[7]));
    let inertia = v3(r0, 17);
    // body-frame sphere centres from LIGGGHTS' world positions at the same step
    let spheres: Vec<Sphere> = table(spheres_text)
        .iter()
        .filter(|r| r.len() == 5)
        .map(|r| Sphere::new(q0.conjugate() * (v3(r, 1) - x0), r[4]))
        .collect();
    let tmpl = body_frame_template(&spheres, mat.density, mass, inertia);
    let mut w = stone_world(mat, props, wall_material, scheme, dt);
    assert_eq!(tmpl.input_to_body, DQuat::IDENTITY);
    let t = w.add_template(tmpl, 0).unwrap();
    let id = add_stone(&mut w, t, r0, DQuat::IDENTITY);
    let mut out = Vec::with_capacity(rows.len());
    out.push(state(&w, id, DQuat::IDENTITY));
    for _ in &rows[1..] {
        w.run(every as u64).unwrap();
        out.push(state(&w, id, DQuat::IDENTITY));
    }
    out
}

/// A template whose spheres are given in LIGGGHTS' body frame (centre of
/// mass at the origin, principal axes along x, y, z), with LIGGGHTS' mass
/// (kg) and principal moments (kg m²). Clump's body frame is LIGGGHTS' up
/// to the order of the axes (Clump sorts the moments ascending, LIGGGHTS
/// does not): the template's `input_to_body` rotation, which
/// [`add_stone`] and [`state`] take.
pub fn body_frame_template(
    spheres: &[Sphere],
    density: f64,
    mass: f64,
    inertia: DVec3,
) -> ClumpTemplate {
    let tmpl = ClumpTemplate::with_override_about(
        "stone",
        spheres,
        density,
        mass,
        DMat3::from_diagonal(inertia),
        DVec3::ZERO,
    )
    .unwrap();
    // the moment about LIGGGHTS' axis i is Clump's about the axis it maps to
    for (i, axis) in [DVec3::X, DVec3::Y, DVec3::Z].into_iter().enumerate() {
        let a = (tmpl.input_to_body * axis).abs();
        let j = if a.x > 0.5 {
            0
        } else if a.y > 0.5 {
            1
        } else {
            2
        };
        let clump = tmpl.principal_inertia[j];
        assert!(
            (clump - inertia[i]).abs() <= 1e-14 * inertia[i],
            "{i}: {clump} vs {}",
            inertia[i]
        );
    }
    tmpl
}

/// A world for LIGGGHTS' stone bounces: gravity 9.81 m/s² along −z, the
/// plane z = 0 of material `wall_material` (see [`run_bounce`]), rotation
/// scheme `scheme`, time step `dt` (s).
pub fn stone_world(
    mat: Material,
    props: PairProperties,
    wall_material: u16,
    scheme: RotationScheme,
    dt: f64,
) -> World {
    let mut w = world(mat, props, dt, open_box(0.5), DVec3::new(0.0, 0.0, -9.81)).unwrap();
    w.config.rotation = scheme;
    let mut floor = plane(DVec3::ZERO, DVec3::Z);
    floor.material = wall_material;
    w.add_wall(floor).unwrap();
    w
}

/// Adds a body of template `t` in the state of LIGGGHTS' row `r` (pose,
/// velocity, angular velocity and momentum); returns its id. `frame`: the
/// template's `input_to_body` ([`body_frame_template`]).
pub fn add_stone(w: &mut World, t: u32, r: &[f64], frame: DQuat) -> u64 {
    let q = DQuat::from_xyzw(r[8], r[9], r[10], r[7]);
    let id = w
        .add_body(&body(
            t,
            v3(r, 1),
            q * frame.conjugate(),
            v3(r, 4),
            v3(r, 11),
        ))
        .unwrap();
    let b = w.body_index(id).unwrap();
    let omega = w.bodies().angular_velocity[b];
    w.set_body_angular_state_at(b, omega, v3(r, 14)).unwrap();
    id
}

/// Body `id`'s state, its orientation that of LIGGGHTS' body frame
/// (`frame` as in [`add_stone`]).
pub fn state(w: &World, id: u64, frame: DQuat) -> State {
    let b = w.body_index(id).unwrap();
    State {
        x: w.bodies().position[b],
        v: w.bodies().velocity[b],
        q: w.bodies().orientation[b] * frame,
        w: w.bodies().angular_velocity[b],
    }
}

/// Largest deviation of `states` from `rows` after the first: centre of
/// mass (m), velocity (m/s), quaternion, angular velocity relative to |ω|.
pub fn deviation(rows: &[Vec<f64>], states: &[State]) -> [f64; 4] {
    let mut dev = [0.0f64; 4];
    for (r, s) in rows.iter().zip(states).skip(1) {
        let ql = DQuat::from_xyzw(r[8], r[9], r[10], r[7]);
        dev[0] = dev[0].max((s.x - v3(r, 1)).length());
        dev[1] = dev[1].max((s.v - v3(r, 4)).length());
        dev[2] = dev[2].max((s.q - ql).length().min((s.q + ql).length()));
        dev[3] = dev[3].max((s.w - v3(r, 11)).length() / v3(r, 11).length());
    }
    dev
}

/// Where the fixtures live (the engine's tests own them).
macro_rules! fixture {
    ($f:literal) => {
        include_str!(concat!("../../clump-core/tests/fixtures/liggghts/", $f))
    };
}

/// LIGGGHTS' own stone of the tutorial `multisphere_stone_restitution`
/// (Debian liggghts-doc; GPL, read from the install, never copied into the
/// repository), 50 spheres in mm.
pub const TUTORIAL_STONE: &str = "/usr/share/doc/liggghts/examples/LIGGGHTS/Tutorials_public/multisphere_stone_restitution/data/stone1.multisphere";

/// The stone material and contact of LIGGGHTS' tutorial (E = 10 MPa,
/// ν = 0.45, ρ = 2500 kg/m³; e = 0.3, μ = 0.5, LIGGGHTS damping,
/// `limitForce off`), with tangential rule `rule`.
pub fn tutorial_contact(rule: TangentialLaw) -> (Material, PairProperties) {
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

/// Index of the first row after the end of the first bounce: the stone
/// rises (vz > 0) and its velocity changes by gravity alone until the next
/// row (rows 1 ms apart). `None` without such a row.
pub fn after_bounce(rows: &[Vec<f64>]) -> Option<usize> {
    let rising = rows.iter().position(|r| r[6] > 0.0)?;
    (rising..rows.len() - 1).find(|&k| {
        let dv = v3(&rows[k + 1], 4) - v3(&rows[k], 4);
        (dv - DVec3::new(0.0, 0.0, -9.81e-3)).length() < 1e-9
    })
}

/// Relative deviation of Clump's angular velocity from LIGGGHTS' at row `k`.
pub fn spin_error(rows: &[Vec<f64>], states: &[State], k: usize) -> f64 {
    (states[k].w - v3(&rows[k], 11)).length() / v3(&rows[k], 11).length()
}

/// The fixture `friction.*` (the asymmetric stone of `stone.txt` arriving
/// spinning and sliding on a plane of its own material, set up as the
/// tutorial) run with tangential rule `rule`: LIGGGHTS' rows and Clump's
/// states at them.
pub fn friction_bounce(rule: TangentialLaw) -> (Vec<Vec<f64>>, Vec<State>) {
    let rows = table(fixture!("friction.dat"));
    let (mat, props) = tutorial_contact(rule);
    let spheres = fixture!("friction_spheres_step100.txt");
    let scheme = RotationScheme::RichardsonLiggghts;
    let states = run_bounce(&rows, spheres, 0.01, mat, props, 0, scheme, 1e-5, 100);
    (rows, states)
}

/// LIGGGHTS' tutorial itself (`tutorial.in` → `tutorial_body*.dat`,
/// `tutorial_frame.txt`): its two stones from LIGGGHTS' state at step 100,
/// with LIGGGHTS' stone `stone_text` (the file [`TUTORIAL_STONE`], mm),
/// Monte-Carlo mass properties and body frame, run with tangential rule
/// `rule` to the last row; per stone, LIGGGHTS' rows and Clump's states.
pub fn tutorial(rule: TangentialLaw, stone_text: &str) -> [(Vec<Vec<f64>>, Vec<State>); 2] {
    let frame = table(fixture!("tutorial_frame.txt"));
    let c = v3(&frame[0], 0);
    let rot = DMat3::from_cols(v3(&frame[1], 0), v3(&frame[2], 0), v3(&frame[3], 0)).transpose();
    // input frame (mm) → LIGGGHTS' body frame (m)
    let spheres: Vec<Sphere> = table(stone_text)
        .iter()
        .map(|r| Sphere::new(rot * (v3(r, 0) * 0.001 - c), r[3] * 0.001))
        .collect();
    assert_eq!(spheres.len(), 50);
    let rows = [
        table(fixture!("tutorial_body1.dat")),
        table(fixture!("tutorial_body2.dat")),
    ];
    let (mat, props) = tutorial_contact(rule);
    let mut w = stone_world(mat, props, 0, RotationScheme::RichardsonLiggghts, 1e-5);
    let r0 = &rows[0][0];
    let tmpl = body_frame_template(&spheres, mat.density, r0[20], v3(r0, 17));
    let frame = tmpl.input_to_body;
    let t = w.add_template(tmpl, 0).unwrap();
    let ids = [0, 1].map(|b| add_stone(&mut w, t, &rows[b][0], frame));
    let mut states = ids.map(|id| vec![state(&w, id, frame)]);
    for _ in 1..rows[0].len() {
        w.run(100).unwrap();
        for b in 0..2 {
            states[b].push(state(&w, ids[b], frame));
        }
    }
    let [s0, s1] = states;
    let [r0, r1] = rows;
    [(r0, s0), (r1, s1)]
}
