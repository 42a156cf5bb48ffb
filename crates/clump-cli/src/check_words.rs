//! The parts of `clump check`'s report that describe the setup in words:
//! walls, contact parameters per material pair, time-step margins, the
//! overlap guard and the outputs (never Rust debug text).

use clump_core::contact::NormalLaw;
use clump_core::wall::{Wall, WallShape};
use clump_core::world::World;
use clump_io::scenario::Scenario;
use glam::DVec3;

/// Largest `dt` / impact duration without a warning: LIGGGHTS'
/// `check/timestep/gran` asks for at most 0.1 (10 steps per contact).
const MAX_DT_FRACTION: f64 = 0.1;

fn v(x: DVec3) -> String {
    format!("({:.4}, {:.4}, {:.4}) m", x.x, x.y, x.z)
}

fn dir(x: DVec3) -> String {
    format!("({:.3}, {:.3}, {:.3})", x.x, x.y, x.z)
}

/// A wall's shape and motion in words.
pub fn wall(sc: &Scenario, w: &Wall) -> String {
    let side = |inside: bool| if inside { "inside" } else { "outside" };
    let mut s = match &w.shape {
        WallShape::Plane { point, normal } => {
            format!("plane through {} with normal {}", v(*point), dir(*normal))
        }
        WallShape::Cylinder {
            point,
            axis,
            radius,
            inside,
        } => format!(
            "cylinder of radius {radius:.4} m, axis {} through {}, particles {}",
            dir(*axis),
            v(*point),
            side(*inside)
        ),
        WallShape::Box { lo, hi, inside } => format!(
            "box from {} to {}, particles {}",
            v(*lo),
            v(*hi),
            side(*inside)
        ),
        WallShape::Mesh { mesh, .. } => match sc.meshes.get(*mesh as usize) {
            Some(m) => {
                let (lo, hi) = m.bounds();
                format!(
                    "mesh: {} triangles ({} of zero area dropped), {} vertices, bounds {} .. {}, merge angle {:.1} deg",
                    m.triangles().len(),
                    m.dropped_triangles(),
                    m.vertices().len(),
                    v(lo),
                    v(hi),
                    m.merge_angle.to_degrees()
                )
            }
            None => "mesh".to_string(),
        },
    };
    let mo = &w.motion;
    if mo.velocity != DVec3::ZERO {
        s += &format!(", moving at {} m/s", dir(mo.velocity));
    }
    if mo.angular_velocity != DVec3::ZERO {
        s += &format!(
            ", turning at {} rad/s about {}",
            dir(mo.angular_velocity),
            v(mo.center)
        );
    }
    if mo.surface_velocity != DVec3::ZERO {
        s += &format!(", surface moving at {} m/s", dir(mo.surface_velocity));
    }
    s + &format!(", material '{}'", sc.material_names[w.material as usize])
}

/// The output settings in words.
pub fn outputs(sc: &Scenario) -> String {
    let dt = sc.time_step.dt;
    let every = |n: Option<u64>| match n {
        Some(n) => format!("every {n} steps ({:.4e} s)", n as f64 * dt),
        None => "off".to_string(),
    };
    let o = &sc.output;
    let traj = match &o.trajectory {
        Some(t) => format!("bodies {:?} {}", t.bodies, every(Some(t.every))),
        None => "off".to_string(),
    };
    format!(
        "  VTK frames   {}\n  thermo.csv   {}\n  checkpoints  {}\n  trajectories {traj}",
        every(o.vtk),
        every(o.thermo),
        every(o.checkpoint)
    )
}

/// The smallest sphere radius (m) and the lightest mass (kg) of the
/// templates made of material `m`, if any.
fn particles_of(sc: &Scenario, m: usize) -> Option<(f64, f64)> {
    sc.templates
        .iter()
        .filter(|t| t.material as usize == m)
        .map(|t| (t.template.min_radius, t.template.mass))
        .reduce(|a, b| (a.0.min(b.0), a.1.min(b.1)))
}

/// Prints the contact parameters of every material pair that can touch,
/// the time-step margins and the overlap guard.
pub fn contacts(sc: &Scenario, world: &World) {
    let dt = sc.time_step.dt;
    let speed = sc
        .overlap_estimate
        .as_ref()
        .map_or(0.0, |e| e.speed)
        .max((2.0 * sc.stability.specific_energy_floor).sqrt());
    outln!(
        "\ncontacts (R* = effective radius and m* = effective mass of the smallest spheres and lightest bodies; stiffness at an overlap of 1 % of R*; impacts at {speed:.3} m/s, the largest speed the scenario allows: free fall across the domain, insertion and wall speeds):"
    );
    let n = sc.materials.len();
    for a in 0..n {
        for b in a..n {
            let (pa, pb) = (particles_of(sc, a), particles_of(sc, b));
            let (r_star, m_star) = match (pa, pb) {
                (Some((ra, ma)), Some((rb, mb))) => (ra * rb / (ra + rb), ma * mb / (ma + mb)),
                (Some(p), None) | (None, Some(p)) => p,
                (None, None) => continue,
            };
            let model = world.contact_table.get(a as u16, b as u16);
            let p = model.properties();
            let law = match p.normal {
                NormalLaw::Hertz => "Hertz–Mindlin".to_string(),
                NormalLaw::Linear { kn, kt } => {
                    format!("linear (k_n = {kn:.3e} N/m, k_t = {kt:.3e} N/m)")
                }
            };
            let k = model.normal_stiffness(r_star, 0.01 * r_star);
            outln!(
                "  {} – {}: {law}{}{}, e = {}, mu = {}, mu_r = {}{}, damping ratio {:.3}, E* = {:.3e} Pa, k_n = {k:.3e} N/m (R* = {r_star:.3e} m, m* = {m_star:.3e} kg)",
                sc.material_names[a],
                sc.material_names[b],
                match p.tangential {
                    clump_core::contact::TangentialLaw::Clump => "",
                    clump_core::contact::TangentialLaw::Liggghts => " (LIGGGHTS' tangential rule)",
                    clump_core::contact::TangentialLaw::MindlinDeresiewicz => " (micro-slip tangential model, Mindlin–Deresiewicz after Thornton & Yin)",
                    clump_core::contact::TangentialLaw::Mdr => " (micro-slip tangential model, exact for any load history by the method of dimensionality reduction)",
                },
                match p.cohesion {
                    clump_core::contact::CohesionLaw::None => String::new(),
                    clump_core::contact::CohesionLaw::Sjkr { energy_density } =>
                        format!(", SJKR cohesion k_c = {energy_density:.3e} J/m^3"),
                    clump_core::contact::CohesionLaw::Jkr { surface_energy } =>
                        format!(", JKR cohesion (work of adhesion {surface_energy:.3e} J/m^2, pull-off force {:.3e} N)", model.pull_off_force(r_star)),
                } + match p.twisting {
                    clump_core::contact::TwistingLaw::None => "",
                    clump_core::contact::TwistingLaw::Marshall => ", twisting resistance (Marshall)",
                },
                p.restitution,
                p.friction,
                p.rolling_friction,
                match p.rolling {
                    clump_core::contact::RollingLaw::None => String::new(),
                    r => format!(" ({})", format!("{r:?}").to_lowercase()),
                },
                -model.damping_ratio(),
                model.effective_modulus(),
            );
            if speed > 0.0 {
                let tc = model.contact_time(r_star, m_star, speed);
                if tc.is_finite() {
                    let frac = dt / tc;
                    outln!(
                        "      an impact at {speed:.3} m/s lasts {tc:.3e} s = {:.0} steps: dt is {:.1} % of it{}",
                        tc / dt,
                        100.0 * frac,
                        if frac > MAX_DT_FRACTION {
                            format!(" — above {:.0} %, the impact is poorly resolved: use a smaller dt", 100.0 * MAX_DT_FRACTION)
                        } else {
                            format!(" (at most {:.0} %, as LIGGGHTS' check/timestep/gran asks)", 100.0 * MAX_DT_FRACTION)
                        }
                    );
                }
            }
        }
    }
    let guard = sc.stability.max_overlap_ratio;
    match &sc.overlap_estimate {
        Some(e) => outln!(
            "\noverlap guard: a run stops when an overlap exceeds {guard:.3} of the smaller sphere radius; the largest expected overlap is {:.3} ({} at {:.3} m/s, undamped)",
            e.ratio,
            e.what,
            e.speed
        ),
        None => outln!(
            "\noverlap guard: a run stops when an overlap exceeds {guard:.3} of the smaller sphere radius"
        ),
    }
}
