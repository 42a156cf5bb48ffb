//! A scenario stage that sets a body's velocity (`[[stage.body]]`) and a
//! driver's steering hook doing the same at the same step boundary give the
//! same run bit for bit: the scenario runner and every other driver go
//! through one run loop (`clump_core::step::run`).

use clump_core::step::run::{Driver, Event, Flow, StepHook};
use clump_core::world::World;
use clump_io::run::{RunOptions, Runner};
use clump_io::scenario::{self, InsertSpec};
use glam::DVec3;
use std::path::PathBuf;

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("clump_steer_{}_{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

const BODIES: &str = "template,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
dimer,0.000,0,0.006,1,0,0,0,0,0,0,0,0,0
dimer,0.012,0,0.006,0.9238795,0,0.3826834,0,0,0,0,0,0,0
dimer,0.006,0.010,0.015,1,0,0,0,0,0,0,0,0,0
";

fn scenario_text(body_change: &str) -> String {
    format!(
        r#"
[simulation]
dt = 5e-6
gravity = [0.0, 0.0, -9.81]

[domain]
lo = [-0.05, -0.05, -0.01]
hi = [0.05, 0.05, 0.08]

[[material]]
name = "grain"
youngs_modulus = 1e7
poisson_ratio = 0.3
density = 2500

[[material]]
name = "steel"
youngs_modulus = inf
poisson_ratio = 0.3
density = 7800

[contact]
restitution = 0.5
friction = 0.4

[[template]]
name = "dimer"
material = "grain"
spheres = [[-0.002, 0.0, 0.0, 0.003], [0.002, 0.0, 0.0, 0.003]]

[[wall]]
name = "floor"
material = "steel"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[insert]]
kind = "file"
file = "bodies.csv"

[[stage]]
name = "settle"
steps = 3000

[[stage]]
name = "kicked"
steps = 4000
{body_change}

[output]
thermo = {{ every_steps = 500 }}
"#
    )
}

/// Sets body 2's velocity and angular velocity at step `at`.
struct Kick {
    at: u64,
    end: u64,
}

impl StepHook for Kick {}

impl Driver for Kick {
    fn at_boundary(&mut self, w: &mut World) -> Flow {
        if w.step == self.at {
            w.set_body_velocity(2, DVec3::new(0.2, -0.1, 0.3)).unwrap();
            w.set_body_angular_velocity(2, DVec3::new(0.0, 30.0, 5.0))
                .unwrap();
        }
        if w.step >= self.end {
            Flow::Stop
        } else {
            Flow::Continue
        }
    }

    fn next_event(&mut self, w: &World) -> Event {
        Event::at(if w.step < self.at { self.at } else { self.end })
    }
}

fn bits(w: &World) -> Vec<u64> {
    let b = &w.bodies();
    let mut out = Vec::new();
    for i in 0..b.len() {
        for v in [b.position[i], b.velocity[i], b.angular_momentum[i]] {
            out.extend(v.to_array().map(f64::to_bits));
        }
        out.extend(b.orientation[i].to_array().map(f64::to_bits));
    }
    out
}

#[test]
fn a_stage_body_change_equals_a_steering_hook() {
    let d = dir("stage");
    std::fs::write(d.join("bodies.csv"), BODIES).unwrap();
    let change = r#"
[[stage.body]]
id = 2
velocity = [0.2, -0.1, 0.3]
angular_velocity = [0.0, 30.0, 5.0]
"#;
    std::fs::write(d.join("staged.toml"), scenario_text(change)).unwrap();
    std::fs::write(d.join("plain.toml"), scenario_text("")).unwrap();

    let staged = scenario::load(&d.join("staged.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut run = Runner::new(staged, &d.join("out")).unwrap();
    run.run(RunOptions::default()).unwrap();
    let a = run.world();
    assert_eq!(a.step, 7000);

    // the same scenario without the change, driven by a hook
    let plain = scenario::load(&d.join("plain.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut w = plain.build_world().unwrap();
    for ins in &plain.inserts {
        if let InsertSpec::File { bodies } = &ins.kind {
            for b in bodies {
                w.add_body(b).unwrap();
            }
        }
    }
    w.run_driven(&mut Kick {
        at: 3000,
        end: 7000,
    })
    .unwrap();
    assert!(
        bits(a) == bits(&w),
        "the staged run and the steered run differ"
    );
    // and the kick mattered: without it body 2 ends elsewhere
    let mut unkicked = plain.build_world().unwrap();
    for ins in &plain.inserts {
        if let InsertSpec::File { bodies } = &ins.kind {
            for b in bodies {
                unkicked.add_body(b).unwrap();
            }
        }
    }
    unkicked.run(7000).unwrap();
    assert!(bits(&unkicked) != bits(&w));
}

#[test]
fn a_stage_body_change_naming_a_missing_body_is_an_input_error() {
    let d = dir("missing");
    std::fs::write(d.join("bodies.csv"), BODIES).unwrap();
    let change = "[[stage.body]]\nid = 9\nvelocity = [1.0, 0.0, 0.0]\n";
    std::fs::write(d.join("s.toml"), scenario_text(change)).unwrap();
    let sc = scenario::load(&d.join("s.toml")).unwrap_or_else(|e| panic!("{e}"));
    let mut run = Runner::new(sc, &d.join("out")).unwrap();
    let e = run.run(RunOptions::default()).unwrap_err();
    let msg = e.to_string();
    assert!(e.is_input(), "{msg}");
    assert!(
        msg.contains("no body with id 9") && msg.contains("s.toml"),
        "{msg}"
    );
}
