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
    run_text(&d, &text)
}

/// Writes scenario `text` into folder `d` and runs it to its end.
fn run_text(d: &std::path::Path, text: &str) -> Runner {
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
    assert!(parse(base("2", flat, pack), "").is_ok());
    let e = parse(
        base("2", flat, &format!("{pack}\nvelocity = [0.0, 0.0, 0.1]")),
        "",
    )
    .unwrap_err();
    assert!(e.contains("z component of the velocity must be 0"), "{e}");
    let tilted = format!("{pack}\norientation = [0.9, 0.1, 0.0, 0.0]");
    let e = parse(base("2", flat, &tilted), "").unwrap_err();
    assert!(e.contains("turn about z only"), "{e}");
    let stream = "[[insert]]\nkind = \"stream\"\ntemplate = \"t\"\nbodies_per_second = 10.0\nvelocity = [0.0, -0.1, 0.0]\nangular_velocity = [1.0, 0.0, 0.0]\nregion = { type = \"box\", lo = [-0.5, -0.5, -0.5], hi = [0.5, 0.5, 0.5] }";
    let e = parse(base("2", flat, stream), "").unwrap_err();
    assert!(
        e.contains("x and y components of the angular velocity"),
        "{e}"
    );
    let e = parse(base("4", flat, file), "x,y,z\n0,0,0\n").unwrap_err();
    assert!(e.contains("dimension must be 2 or 3"), "{e}");
}

/// Half-width of the 2D heap's pedestal (a row of fixed discs), m.
const PEDESTAL: f64 = 0.03;

/// A 2D heap poured onto a rough pedestal: 31 touching fixed discs of
/// 1 mm radius at y = 0 (|x| ≤ 30 mm), planar triangular clumps (three
/// spheres of 1 mm radius at the corners of a triangle of side 1.6 mm,
/// scaled by 0.9–1.1, uniform), friction `mu`, e = 0.3, gravity −y; what
/// does not stay on the pedestal falls off and leaves the domain.
/// `insert` is the `[[insert]]` of the poured clumps; stage "pour" then
/// stage "settle".
fn heap(name: &str, insert: &str, pour: f64, mu: f64) -> Runner {
    let d = dir(name);
    let mut pedestal = String::from("x,y,z\n");
    for k in -15..=15 {
        pedestal.push_str(&format!("{},0,0\n", 0.002 * k as f64));
    }
    std::fs::write(d.join("pedestal.csv"), pedestal).unwrap();
    let text = format!(
        r#"
[simulation]
dt = 2e-5
gravity = [0.0, -{G}, 0.0]
[domain]
lo = [-0.06, -0.02, -0.004]
hi = [0.06, 0.12, 0.004]
dimension = 2
[[material]]
name = "grain"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500
[contact]
restitution = 0.3
friction = {mu}
[[template]]
name = "base"
material = "grain"
shape = "sphere"
radius = 0.001
[[template]]
name = "tri"
material = "grain"
spheres = [[0.000924, 0.0, 0.0, 0.001], [-0.000462, 0.0008, 0.0, 0.001], [-0.000462, -0.0008, 0.0, 0.001]]
[[mix]]
name = "grains"
[[mix.component]]
template = "tri"
fraction = 1
size = {{ distribution = "uniform", min = 0.9, max = 1.1 }}
[[insert]]
kind = "file"
file = "pedestal.csv"
template = "base"
fixed = true
{insert}
[[stage]]
name = "pour"
duration = {pour}
[[stage]]
name = "settle"
duration = 0.4
"#
    );
    run_text(&d, &text)
}

/// The heap's angle of repose, rad, from its free surface: on each flank
/// (0.1 to 0.9 of the pedestal's half-width from the axis) the highest
/// centre of mass in each of 8 bins, fitted by least squares against |x|;
/// the two flanks' angles.
fn surface_angles(w: &clump_core::world::World) -> [f64; 2] {
    const BINS: usize = 8;
    let width = 0.8 * PEDESTAL / BINS as f64;
    let mut top = [[f64::NAN; BINS]; 2];
    for x in &w.bodies().position {
        let k = ((x.x.abs() - 0.1 * PEDESTAL) / width).floor();
        // the pedestal's discs lie at y = 0
        if x.y > 0.0 && (0.0..BINS as f64).contains(&k) {
            let t = &mut top[(x.x > 0.0) as usize][k as usize];
            if !(*t >= x.y) {
                *t = x.y;
            }
        }
    }
    top.map(|tops| {
        let pts: Vec<(f64, f64)> = (0..BINS)
            .filter(|&k| tops[k].is_finite())
            .map(|k| (0.1 * PEDESTAL + (k as f64 + 0.5) * width, tops[k]))
            .collect();
        assert!(pts.len() >= 6, "a flank: {} bins hold bodies", pts.len());
        let n = pts.len() as f64;
        let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
        let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
        let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
        let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
        (-sxy / sxx).atan()
    })
}

/// The heap's angle by the fixed-base method of clump-validate's 3D heaps
/// (bulk/repose.rs), rad: a full heap on the pedestal fills a triangle of
/// half-width `L` (the pedestal's edge, 31 mm) whose centroid lies a third
/// of its height `L tan θ` above the base (the pedestal's top, y = 1 mm),
/// so `θ = atan(3 ȳ / L)` with `ȳ` the mean height of the centres of mass
/// above the base (biased high by the bodies' size on a heap a few bodies
/// deep, alike for every heap). Taken on each half (x < 0, x > 0), with the
/// number of bodies on the pedestal.
fn centroid_angles(w: &clump_core::world::World) -> ([f64; 2], usize) {
    let edge = PEDESTAL + 0.001;
    let (mut sum, mut count) = ([0.0; 2], [0usize; 2]);
    for x in &w.bodies().position {
        if x.y > 0.0 && x.x.abs() <= edge {
            let side = (x.x > 0.0) as usize;
            sum[side] += x.y - 0.001;
            count[side] += 1;
        }
    }
    let angle = |k: usize| (3.0 * sum[k] / count[k].max(1) as f64 / edge).atan();
    ([angle(0), angle(1)], count[0] + count[1])
}

/// Every out-of-plane component of every body is exactly zero at the end
/// of a run in the plane z = 0: position z, velocity z, quaternion x and y,
/// angular velocity and momentum about x and y, force z, torque about x
/// and y (the last step's loads).
fn assert_exactly_planar(w: &clump_core::world::World) {
    assert_in_plane(w, 0.0);
    let b = &w.bodies();
    for i in 0..b.len() {
        assert_eq!((b.torque[i].x, b.torque[i].y), (0.0, 0.0), "body {i}");
        assert_eq!(b.force[i].z, 0.0, "body {i}");
    }
}

/// 2D heaps of planar triangular clumps poured onto a rough pedestal from
/// a random packing (a column that collapses) and from a stream (a pour).
/// Every out-of-plane component is exactly zero at the end. At μ = 0.5
/// both heaps' free surfaces stand between 15° and 40° (a plausibility
/// range for angular grains, not a published value for this case: none
/// was found). At μ = 0.1 the poured heap is lower: its fixed-base angle
/// falls by more than twice the combined error (each heap's error is half
/// the difference of its halves' angles; the criterion of clump-validate's
/// 3D heaps): the angle of repose rises with sliding friction (Zhou, Xu,
/// Yu & Zulli 2001, Phys. Rev. E 64:021301). The collapse and the pour
/// are not required to agree (the angle depends on how a heap is made).
#[test]
fn heaps_from_pack_and_stream_stand_at_the_angle_of_repose() {
    let region = |lo: [f64; 2], hi: [f64; 2]| {
        format!(
            "region = {{ type = \"box\", lo = [{}, {}, -0.002], hi = [{}, {}, 0.002] }}",
            lo[0], lo[1], hi[0], hi[1]
        )
    };
    let pack = format!(
        "[[insert]]\nkind = \"pack\"\nmix = \"grains\"\ncount = 150\nseed = 3\n{}",
        region([-0.02, 0.006], [0.02, 0.11])
    );
    let stream = format!(
        "[[insert]]\nkind = \"stream\"\nmix = \"grains\"\nbodies_per_second = 300\ncount = 150\nvelocity = [0.0, -0.3, 0.0]\nseed = 3\n{}",
        region([-0.006, 0.08], [0.006, 0.09])
    );
    let deg = |a: [f64; 2]| a.map(f64::to_degrees);
    let mut centroid = Vec::new();
    for (name, insert, pour, mu) in [
        ("heap_pack", &pack, 0.25, 0.5),
        ("heap_stream", &stream, 0.6, 0.5),
        ("heap_stream_mu01", &stream, 0.6, 0.1),
    ] {
        let r = heap(name, insert, pour, mu);
        let w = r.world();
        let surface = deg(surface_angles(w));
        let (halves, on) = centroid_angles(w);
        let halves = deg(halves);
        let c = (
            0.5 * (halves[0] + halves[1]),
            0.5 * (halves[0] - halves[1]).abs(),
        );
        let s = 0.5 * (surface[0] + surface[1]);
        eprintln!(
            "2D heap ({name}, mu {mu}): {on} bodies on the pedestal; free surface {:.1}° and {:.1}° (mean {s:.1}°); fixed-base {:.1}° ± {:.1}°",
            surface[0], surface[1], c.0, c.1
        );
        assert_exactly_planar(w);
        assert!(on > 40, "{name}: {on} bodies on the pedestal");
        if mu == 0.5 {
            assert!((15.0..40.0).contains(&s), "{name}: free surface at {s:.1}°");
        }
        centroid.push(c);
    }
    let (high, low) = (centroid[1], centroid[2]);
    assert!(
        high.0 - low.0 > 2.0 * high.1.hypot(low.1),
        "fixed-base angle at mu 0.5: {high:?}, at mu 0.1: {low:?} (degrees)"
    );
}
