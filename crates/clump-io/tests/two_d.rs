//! `[domain] dimension = 2` (the planar case of docs/theory.md: x, y and one angle θ):
//! a sphere rolling and a planar dimer sliding down an incline against
//! their closed forms, a 2D collision of two dimers conserving momentum and
//! angular momentum about z, and a long run in which every out-of-plane
//! component of every body stays exactly zero.

mod support;
use clump_io::run::{RunOptions, Runner};
use clump_io::scenario;
use glam::DVec3;
use std::f64::consts::PI;
use std::path::PathBuf;

const G: f64 = 9.81;
const E: f64 = 1e7;
const NU: f64 = 0.3;
const RHO: f64 = 2500.0;
const R: f64 = 0.005;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump_2d_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A 2D scenario: gravity `g` (in the plane), contact `(e, μ)`, extra
/// tables `extra` (walls), body file `bodies`, `steps` of dt = 1e-6 s.
fn run(
    name: &str,
    g: [f64; 2],
    (e, mu): (f64, f64),
    extra: &str,
    bodies: &str,
    steps: u64,
) -> Runner {
    let d = dir(name);
    std::fs::write(d.join("bodies.csv"), bodies).unwrap();
    let text = format!(
        r#"
[simulation]
dt = 1e-6
gravity = [{}, {}, 0.0]
[domain]
lo = [-0.5, -0.5, -0.05]
hi = [0.5, 0.5, 0.05]
dimension = 2
[[material]]
name = "m"
youngs_modulus = {E}
poisson_ratio = {NU}
density = {RHO}
[[material]]
name = "rigid"
youngs_modulus = inf
poisson_ratio = {NU}
density = 1000
[contact]
restitution = {e}
friction = {mu}
[[template]]
name = "ball"
material = "m"
shape = "sphere"
radius = {R}
[[template]]
name = "dimer"
material = "m"
spheres = [[-0.004, 0.0, 0.0, {R}], [0.004, 0.0, 0.0, {R}]]
[[template]]
name = "trimer"
material = "m"
spheres = [[0.0, 0.0, 0.0, {R}], [0.007, 0.001, 0.0, 0.004], [-0.002, 0.006, 0.0, 0.003]]
{extra}
[[insert]]
kind = "file"
file = "bodies.csv"
[[stage]]
steps = {steps}
[output]
trajectory = {{ bodies = [1], every_steps = {steps} }}
"#,
        g[0], g[1]
    );
    std::fs::write(d.join("s.toml"), text).unwrap();
    let sc = scenario::load(&d.join("s.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut r = Runner::new(sc, &d.join("out")).unwrap();
    r.run(RunOptions::default()).unwrap();
    r
}

/// An incline at angle α: plane wall through the origin with normal
/// (−sin α, cos α, 0); gravity (0, −g); returns (extra, down-slope unit
/// vector, normal).
fn incline(alpha: f64) -> (String, DVec3, DVec3) {
    let n = DVec3::new(-alpha.sin(), alpha.cos(), 0.0);
    let extra = format!(
        "[[wall]]\nname = \"incline\"\nmaterial = \"rigid\"\ntype = \"plane\"\npoint = [0.0, 0.0, 0.0]\nnormal = [{}, {}, 0.0]",
        n.x, n.y
    );
    (extra, DVec3::new(-alpha.cos(), -alpha.sin(), 0.0), n)
}

/// Hertz overlap of a sphere of radius R on a rigid plane under `load` N.
fn overlap(load: f64) -> f64 {
    let e_star = E / (1.0 - NU * NU);
    (load / (4.0 / 3.0 * e_star * R.sqrt())).powf(2.0 / 3.0)
}

/// A sphere in 2D rolls without slipping down a 20° incline (μ = 0.5 >
/// (2/7) tan α): a = g sin α / (1 + 2/5) = (5/7) g sin α, and ω = v / R.
#[test]
fn sphere_rolls_down_an_incline_at_five_sevenths_g_sin_alpha() {
    let alpha = 20f64.to_radians();
    let (extra, down, n) = incline(alpha);
    let m = RHO * 4.0 / 3.0 * PI * R.powi(3);
    let x = n * (R - overlap(m * G * alpha.cos()));
    let r = run(
        "roll",
        [0.0, -G],
        (0.5, 0.5),
        &extra,
        &format!("template,x,y,z\nball,{},{},0\n", x.x, x.y),
        100_000,
    );
    let w = r.world();
    let t = 0.1;
    let v = w.bodies().velocity[0].dot(down);
    let a = 5.0 / 7.0 * G * alpha.sin();
    eprintln!(
        "2D rolling sphere: v = {v:.6} m/s at t = {t} s, closed form {:.6}; omega_z = {}",
        a * t,
        w.bodies().angular_velocity[0].z
    );
    assert!(((v - a * t) / (a * t)).abs() < 2e-3);
    assert!(((w.bodies().angular_velocity[0].z.abs() - v / R) / (v / R)).abs() < 2e-3);
}

/// A planar dimer lying along a 30° incline (both spheres touching) slides
/// down under Coulomb friction μ = 0.2: a = g (sin α − μ cos α).
#[test]
fn dimer_slides_down_an_incline_at_the_coulomb_rate() {
    let alpha = 30f64.to_radians();
    let (extra, down, n) = incline(alpha);
    let m_sphere = RHO * 4.0 / 3.0 * PI * R.powi(3);
    // each sphere carries about half the weight (the union is a little lighter)
    let x = n * (R - overlap(0.5 * m_sphere * G * alpha.cos()));
    let q = (0.5 * alpha).sin();
    let r = run(
        "slide",
        [0.0, -G],
        (0.5, 0.2),
        &extra,
        &format!(
            "template,x,y,z,qw,qx,qy,qz\ndimer,{},{},0,{},0,0,{q}\n",
            x.x,
            x.y,
            (0.5 * alpha).cos()
        ),
        100_000,
    );
    let w = r.world();
    let t = 0.1;
    let v = w.bodies().velocity[0].dot(down);
    let a = G * (alpha.sin() - 0.2 * alpha.cos());
    eprintln!(
        "2D sliding dimer: v = {v:.6} m/s at t = {t} s, closed form {:.6}; omega_z = {:.3e}",
        a * t,
        w.bodies().angular_velocity[0].z
    );
    assert!(((v - a * t) / (a * t)).abs() < 2e-3);
}

/// Linear momentum (x, y) and angular momentum about z of the system.
fn momenta(w: &clump_core::world::World) -> (DVec3, f64) {
    let b = &w.bodies();
    let mut p = DVec3::ZERO;
    let mut lz = 0.0;
    for i in 0..b.len() {
        p += b.mass[i] * b.velocity[i];
        lz += b.angular_momentum[i].z + b.position[i].cross(b.mass[i] * b.velocity[i]).z;
    }
    (p, lz)
}

/// Every out-of-plane component is exactly zero (or, for z, the start value).
fn assert_in_plane(w: &clump_core::world::World, z0: f64) {
    let b = &w.bodies();
    for i in 0..b.len() {
        let (q, wv, l) = (
            b.orientation[i],
            b.angular_velocity[i],
            b.angular_momentum[i],
        );
        assert_eq!(b.position[i].z, z0, "body {i}");
        assert_eq!(b.velocity[i].z, 0.0, "body {i}");
        assert_eq!((q.x, q.y), (0.0, 0.0), "body {i}");
        assert_eq!((wv.x, wv.y, l.x, l.y), (0.0, 0.0, 0.0, 0.0), "body {i}");
    }
}

/// Two spinning planar dimers collide off-centre (friction, damping, no
/// gravity): total momentum and angular momentum about z are conserved (the
/// contact forces are pairwise opposite and act at one point), and the
/// motion stays in the plane exactly.
#[test]
fn two_dimers_collide_in_the_plane() {
    let bodies = "template,x,y,z,vx,vy,wz,theta,phi,psi\n\
                  dimer,-0.02,0.003,0,0.5,0,20,0,0.3,0\n\
                  trimer,0.02,-0.002,0,-0.4,0.1,-15,0,1.1,0\n";
    let before = run("collide0", [0.0, 0.0], (0.6, 0.4), "", bodies, 1);
    let (p0, l0) = momenta(before.world());
    let r = run("collide", [0.0, 0.0], (0.6, 0.4), "", bodies, 60_000);
    let w = r.world();
    let (p1, l1) = momenta(w);
    let turned = w.bodies().angular_velocity[0].z;
    eprintln!(
        "2D collision: p {p0} -> {p1}, Lz {l0:.9e} -> {l1:.9e}; dimer omega_z 20 -> {turned}"
    );
    assert!(
        turned != 20.0 && w.bodies().velocity[0].x < 0.5,
        "they must collide"
    );
    assert!((p1 - p0).length() < 1e-12 * p0.length());
    assert!((l1 - l0).abs() < 1e-10 * l0.abs());
    assert_in_plane(w, 0.0);
}

/// A long run: six clumps bouncing in a box under in-plane gravity, 400 000
/// steps; every out-of-plane component stays exactly zero, and the
/// trajectory's θ is the body's angle about z.
#[test]
fn long_run_stays_exactly_in_the_plane() {
    let walls: String = [([0.0, -0.05], [0.0, 1.0]), ([0.0, 0.05], [0.0, -1.0]), ([-0.05, 0.0], [1.0, 0.0]), ([0.05, 0.0], [-1.0, 0.0])]
        .iter()
        .enumerate()
        .map(|(k, (p, n))| format!("[[wall]]\nname = \"w{k}\"\nmaterial = \"rigid\"\ntype = \"plane\"\npoint = [{}, {}, 0.0]\nnormal = [{}, {}, 0.0]\n", p[0], p[1], n[0], n[1]))
        .collect();
    let mut bodies = String::from("template,x,y,z,vx,vy,wz,qw,qx,qy,qz\n");
    for k in 0..6 {
        let (x, y) = (-0.03 + 0.012 * k as f64, 0.02 * ((k % 2) as f64) - 0.01);
        let a = 0.7 * k as f64;
        let t = ["dimer", "trimer", "ball"][k % 3];
        bodies.push_str(&format!(
            "{t},{x},{y},0.001,{},{},{},{},0,0,{}\n",
            0.3 - 0.1 * k as f64,
            0.2,
            10.0 - 3.0 * k as f64,
            (0.5 * a).cos(),
            (0.5 * a).sin()
        ));
    }
    let r = run("long", [2.0, -G], (0.8, 0.3), &walls, &bodies, 400_000);
    let w = r.world();
    assert_in_plane(w, 0.001);
    let theta = support::last_value(&r.outdir().join("traj_1.csv"), "theta_2d");
    let b = w.body_index(1).unwrap();
    let q = w.bodies().orientation[b];
    // the planar A_θ: the body x axis in the world is (cos θ, sin θ)
    let ex = q * DVec3::X;
    assert!((ex.x - theta.cos()).abs() < 1e-12 && (ex.y - theta.sin()).abs() < 1e-12);
    eprintln!("long 2D run: 6 bodies in the plane after 400000 steps; body 1 at theta = {theta}");
}

/// 2D input errors name the key: a template off its plane, a body turned
/// about x, a packing, a wrong dimension.
#[test]
fn two_d_input_errors() {
    let base = |dimension: &str, spheres: &str, insert: &str| {
        format!(
            "[simulation]\ndt = 1e-6\ngravity = [0.0, -9.81, 0.0]\n[domain]\nlo = [-1.0, -1.0, -1.0]\nhi = [1.0, 1.0, 1.0]\ndimension = {dimension}\n[[material]]\nname = \"m\"\nyoungs_modulus = 1e7\npoisson_ratio = 0.3\ndensity = 2500\n[[template]]\nname = \"t\"\nmaterial = \"m\"\nspheres = {spheres}\n{insert}\n[[stage]]\nsteps = 1\n"
        )
    };
    let file = "[[insert]]\nkind = \"file\"\nfile = \"b.csv\"\ntemplate = \"t\"";
    let parse = |text: String, body: &str| {
        let mut files = std::collections::BTreeMap::new();
        files.insert("b.csv".to_string(), body.as_bytes().to_vec());
        scenario::parse(
            std::path::Path::new("t.toml"),
            text,
            scenario::Files::embedded(files),
        )
        .map(|_| ())
        .map_err(|e| e.to_string())
    };
    let flat = "[[0.0, 0.0, 0.0, 0.01], [0.01, 0.0, 0.0, 0.01]]";
    assert!(parse(base("2", flat, file), "x,y,z\n0,0,0\n").is_ok());
    let e = parse(
        base(
            "2",
            "[[0.0, 0.0, 0.0, 0.01], [0.01, 0.0, 0.002, 0.01]]",
            file,
        ),
        "x,y,z\n0,0,0\n",
    )
    .unwrap_err();
    assert!(
        e.contains("cannot be used in 2D") && e.contains("sphere 2 lies"),
        "{e}"
    );
    let e = parse(
        base("2", flat, file),
        "x,y,z,qw,qx,qy,qz\n0,0,0,0.9,0.1,0,0\n",
    )
    .unwrap_err();
    assert!(e.contains("turned about an axis other than z"), "{e}");
    let pack = "[[insert]]\nkind = \"pack\"\ntemplate = \"t\"\ncount = 1\nregion = { type = \"box\", lo = [-0.5, -0.5, -0.5], hi = [0.5, 0.5, 0.5] }";
    let e = parse(base("2", flat, pack), "").unwrap_err();
    assert!(e.contains("in 2D bodies come from a body file"), "{e}");
    let e = parse(base("4", flat, file), "x,y,z\n0,0,0\n").unwrap_err();
    assert!(e.contains("dimension must be 2 or 3"), "{e}");
}
