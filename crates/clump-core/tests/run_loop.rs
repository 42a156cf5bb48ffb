//! The run loop's hooks and the contact iterator, checked against what the
//! engine sums itself: the wall loads and the body forces are built from the
//! same contacts, in other orders, so the contacts must add up to them to
//! round-off; and observing or steering must not change the physics.

use clump_core::recorded_contacts::{Contact, Partner};
use clump_core::step::run::{Driver, Event, Flow, StepHook, StepReport};
use clump_core::testbed::tetra_lattice_bed;
use clump_core::world::World;
use clump_core::DVec3;

/// A bed of 6×6×3 tetrahedra falling onto the floor (wall 0), run far
/// enough that every body rests on the floor or on others.
fn bed() -> World {
    let mut w = tetra_lattice_bed(6, 6, 3, None);
    w.run(1500).unwrap();
    w
}

fn bits(w: &World) -> Vec<u64> {
    let b = &w.bodies();
    (0..b.len())
        .flat_map(|i| {
            let (x, v, l, q) = (
                b.position[i],
                b.velocity[i],
                b.angular_momentum[i],
                b.orientation[i],
            );
            [
                x.x, x.y, x.z, v.x, v.y, v.z, l.x, l.y, l.z, q.x, q.y, q.z, q.w,
            ]
            .map(f64::to_bits)
        })
        .collect()
}

/// Observes the contacts every `every` steps: the floor's load from the
/// contacts, compared with the engine's wall load, and every body's force
/// rebuilt from its contacts plus gravity, compared with the engine's.
struct Observer {
    end: u64,
    every: u64,
    checked: usize,
    wall_contacts: usize,
    pair_contacts: usize,
}

impl StepHook for Observer {}

impl Driver for Observer {
    fn at_boundary(&mut self, w: &mut World) -> Flow {
        if w.step >= self.end {
            return Flow::Stop;
        }
        if w.step % self.every != 0 || w.step == 0 {
            return Flow::Continue;
        }
        let contacts: Vec<Contact> = w.contacts().expect("recorded").collect();
        // the floor: the load it feels is minus the sum of its contacts' forces
        let floor: DVec3 = contacts
            .iter()
            .filter(|c| matches!(c.partner, Partner::Wall { wall: 0, .. }))
            .map(|c| -c.force())
            .sum();
        let load = w.walls.loads()[0].force;
        assert!(load.z < 0.0, "the bed rests on the floor: {load}");
        assert!(
            (floor - load).length() <= 1e-12 * load.length(),
            "step {}: floor load from contacts {floor} vs engine {load}",
            w.step
        );
        // every body: Σ contact forces on its spheres + m g = its force
        let mut f = vec![DVec3::ZERO; w.bodies().len()];
        let index = |id: u64| w.body_index(id).unwrap();
        for c in &contacts {
            f[index(c.body_id)] += c.force();
            if let Partner::Sphere { body_id, .. } = c.partner {
                f[index(body_id)] -= c.force();
            }
            assert!(c.overlap > 0.0 && (c.normal.length() - 1.0).abs() < 1e-12);
            assert!(
                c.force_normal.cross(c.normal).length() <= 1e-9 * c.force_normal.length(),
                "normal force along the normal"
            );
            assert!(
                c.force_tangential.dot(c.normal).abs() <= 1e-9 * c.force().length() + 1e-300,
                "tangential force in the tangent plane"
            );
        }
        let scale = w.bodies().mass[0] * 9.81;
        for (i, fi) in f.iter().enumerate() {
            let expect = w.bodies().force[i];
            let got = *fi + w.bodies().mass[i] * w.config.gravity;
            assert!(
                (got - expect).length() <= 1e-9 * scale,
                "step {}: body {} force from contacts {got} vs engine {expect}",
                w.step,
                w.bodies().id[i]
            );
        }
        self.checked += 1;
        self.wall_contacts += contacts
            .iter()
            .filter(|c| matches!(c.partner, Partner::Wall { .. }))
            .count();
        self.pair_contacts += contacts
            .iter()
            .filter(|c| matches!(c.partner, Partner::Sphere { .. }))
            .count();
        Flow::Continue
    }

    fn next_event(&mut self, w: &World) -> Event {
        let next = (w.step / self.every + 1) * self.every;
        Event {
            step: next.min(self.end),
            contacts: true,
        }
    }
}

#[test]
fn contacts_add_up_to_the_floor_load_and_the_body_forces() {
    let mut w = bed();
    let start = w.step;
    let mut obs = Observer {
        end: start + 300,
        every: 7,
        checked: 0,
        wall_contacts: 0,
        pair_contacts: 0,
    };
    w.run_driven(&mut obs).unwrap();
    assert!(obs.checked >= 40, "{} boundaries checked", obs.checked);
    assert!(
        obs.wall_contacts > 100 && obs.pair_contacts > 100,
        "{} wall and {} pair contacts seen",
        obs.wall_contacts,
        obs.pair_contacts
    );
    // the same steps without observing give the same bits
    let mut plain = bed();
    plain.run(300).unwrap();
    assert!(bits(&plain) == bits(&w), "observing changed the run");
}

#[test]
fn contacts_are_refused_when_the_step_did_not_record_them() {
    let mut w = bed();
    assert!(w.contacts().is_err());
    w.run(1).unwrap();
    assert!(w.contacts().is_err());
}

/// Sets one body's velocity at a given step.
struct Kick {
    at: u64,
    end: u64,
    id: u64,
    v: DVec3,
    omega: DVec3,
    steps_seen: u64,
}

impl StepHook for Kick {
    fn end_of_step(&mut self, _r: &StepReport) -> Flow {
        self.steps_seen += 1;
        Flow::Continue
    }
}

impl Driver for Kick {
    fn at_boundary(&mut self, w: &mut World) -> Flow {
        if w.step == self.at {
            w.set_body_velocity(self.id, self.v).unwrap();
            w.set_body_angular_velocity(self.id, self.omega).unwrap();
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

#[test]
fn steering_at_a_boundary_equals_stopping_there_and_setting_the_state() {
    let (v, omega) = (DVec3::new(0.3, -0.1, 0.5), DVec3::new(4.0, 0.0, -2.0));
    let mut a = tetra_lattice_bed(4, 4, 2, None);
    let id = a.bodies().id[5];
    let mut k = Kick {
        at: 400,
        end: 900,
        id,
        v,
        omega,
        steps_seen: 0,
    };
    a.run_driven(&mut k).unwrap();
    assert_eq!(k.steps_seen, 900);
    let mut b = tetra_lattice_bed(4, 4, 2, None);
    for _ in 0..400 {
        b.step().unwrap();
    }
    b.set_body_velocity(id, v).unwrap();
    b.set_body_angular_velocity(id, omega).unwrap();
    for _ in 400..900 {
        b.step().unwrap();
    }
    assert!(bits(&a) == bits(&b), "steered run differs from stepwise");
    assert!(a.set_body_velocity(id, DVec3::NAN).is_err());
    assert!(a.set_body_velocity(u64::MAX, DVec3::ZERO).is_err());
}

#[test]
fn a_removed_body_is_gone_and_the_rest_run_on() {
    let mut w = tetra_lattice_bed(4, 4, 2, None);
    w.run(200).unwrap();
    let n = w.bodies().len();
    let id = w.bodies().id[3];
    w.remove_body(id).unwrap();
    assert_eq!(w.bodies().len(), n - 1);
    assert!(w.body_index(id).is_none());
    w.run(200).unwrap();
    assert_eq!(w.bodies().len(), n - 1);
    assert!(w.spheres().len() == (n - 1) * 4);
    assert!(w.remove_body(id).is_err());
}

/// After a driver removes a body, the rebuild carries every other sphere's
/// wall contacts to that same sphere. The bodies behind the removed one
/// have shifted storage indices while the spheres still hold the old
/// topology, so a carry by index alone would hand them their neighbour's
/// contacts. The reference is the same sliding bed rebuilt and evaluated without
/// the removal: a sphere–wall contact depends on its own body and the wall
/// only, so each remaining sphere's wall springs must be the same bits.
#[test]
fn a_removal_keeps_each_sphere_its_wall_contacts() {
    let wall_springs = |w: &mut World| {
        let s = w.save_state().unwrap();
        let mut by_gid = std::collections::HashMap::new();
        for (g, (keys, hist)) in w
            .spheres()
            .gid
            .iter()
            .zip(s.wall_key.iter().zip(&s.wall_hist))
        {
            for (k, h) in keys.iter().zip(hist) {
                if h.tangential != DVec3::ZERO {
                    by_gid.insert((*g, *k), h.tangential.to_array().map(f64::to_bits));
                }
            }
        }
        by_gid
    };
    // a layer landed on the floor, then slid along it for a few steps:
    // every floor contact holds a spring
    let sliding = || {
        let mut w = tetra_lattice_bed(6, 6, 1, None);
        w.run(6000).unwrap(); // landed on the floor
        for id in w.bodies().id.clone() {
            w.set_body_velocity(id, DVec3::new(0.02, 0.01, 0.0))
                .unwrap();
        }
        w.run(20).unwrap();
        w
    };
    let mut reference = sliding();
    reference.prepare().unwrap(); // a rebuild and an evaluation, as below
    let reference = wall_springs(&mut reference);
    let mut w = sliding();
    // the first body in storage: every other one shifts down by one
    let removed = w.bodies().id[0];
    w.remove_body(removed).unwrap();
    let after = wall_springs(&mut w);
    let expected: std::collections::HashMap<_, _> = reference
        .into_iter()
        .filter(|((g, _), _)| g >> clump_core::sphere::SPHERE_ID_BITS != removed)
        .collect();
    assert!(
        expected.len() > 30,
        "too few wall springs to compare: {}",
        expected.len()
    );
    assert_eq!(after.len(), expected.len(), "wall contacts lost or gained");
    for (key, bits) in &expected {
        assert!(
            after.get(key) == Some(bits),
            "sphere {:#x}, wall slot {}: spring differs",
            key.0,
            key.1
        );
    }
}

/// A driver whose event is not ahead is an error, not a hang.
struct Stuck;
impl StepHook for Stuck {}
impl Driver for Stuck {
    fn at_boundary(&mut self, _w: &mut World) -> Flow {
        Flow::Continue
    }
    fn next_event(&mut self, w: &World) -> Event {
        Event::at(w.step)
    }
}

#[test]
fn an_event_that_is_not_ahead_is_an_error() {
    let mut w = tetra_lattice_bed(2, 2, 1, None);
    assert!(w.run_driven(&mut Stuck).is_err());
}

/// The sliding flag against Coulomb's law from outside the code: bodies
/// on the floor, set sliding along it at 1 m/s, must slide at every
/// floor contact (the spring's trial force `k_t v dt` after one step is far
/// above `μF_n` of a resting tetrahedron), and a flag set means the
/// tangential force carries `μ|F_n|`.
#[test]
fn floor_contacts_of_bodies_set_sliding_slide() {
    let mut w = bed();
    w.run(4000).unwrap();
    let mu = w
        .contact_table
        .get(w.walls[0].material, w.walls[0].material)
        .sliding_law()
        .friction;
    let ids: Vec<u64> = w.bodies().id.clone();
    for id in ids {
        let v = w.bodies().velocity[w.body_index(id).unwrap()];
        w.set_body_velocity(id, v + DVec3::new(1.0, 0.0, 0.0))
            .unwrap();
    }
    recorded_step(&mut w);
    let floor: Vec<Contact> = w
        .contacts()
        .unwrap()
        .filter(|c| matches!(c.partner, Partner::Wall { wall: 0, .. }))
        .collect();
    assert!(floor.len() >= 30, "{} floor contacts", floor.len());
    for c in &floor {
        assert!(c.sliding, "floor contact of body {} sticks", c.body_id);
        let (ft, fnm) = (c.force_tangential.length(), c.force_normal.length());
        assert!(
            mu > 0.0 && (ft - mu * fnm).abs() <= 1e-9 * mu * fnm,
            "{ft} vs μF_n {}",
            mu * fnm
        );
    }
}

/// One step that records its contacts.
fn recorded_step(w: &mut World) {
    struct Quiet;
    impl StepHook for Quiet {}
    let event = Event {
        step: w.step + 1,
        contacts: true,
    };
    w.advance(event, &mut Quiet).unwrap();
}

/// Stops the run after step `0` (as a health trip does).
struct TripAfter(u64);

impl StepHook for TripAfter {
    fn end_of_step(&mut self, r: &StepReport) -> Flow {
        if r.step == self.0 {
            Flow::Stop
        } else {
            Flow::Continue
        }
    }
}

/// A hook that stops the run inside a stretch of fused steps gets the
/// world back with its body arrays current: each body's centre and
/// orientation are the pose its spheres were just placed from (the next
/// step's first half), its angular velocity is `L / I` of that half (a
/// spherical top), and stepping on from there finishes the stretch with the
/// bits of a run that never stopped.
#[test]
fn a_trip_inside_fused_steps_hands_back_current_bodies() {
    use clump_core::step::run::Advance;
    let (mut a, mut b) = (bed(), bed());
    let end = Event::at(a.step + 300);
    let got = a.advance(end, &mut TripAfter(a.step + 170)).unwrap();
    assert_eq!(got, Advance::Tripped);
    let mut spheres = 0;
    for i in 0..a.bodies().len() {
        let t = &a.templates[a.bodies().template[i] as usize];
        let (x, q) = (a.bodies().position[i], a.bodies().orientation[i]);
        let rot = clump_core::DMat3::from_quat(q);
        for (k, s) in a.spheres().of_body(i).enumerate() {
            let want = clump_core::step::kinematics::sphere_position(x, &rot, t.spheres[k].center);
            assert!(
                (a.spheres().position(s) - want).length() < 1e-15,
                "body {i} sphere {k}: {} against {want}",
                a.spheres().position(s)
            );
            spheres += 1;
        }
        let om = a.bodies().angular_momentum[i] / a.bodies().inertia[i].x;
        let got = a.bodies().angular_velocity[i];
        assert!(
            (got - om).length() <= 1e-12 * om.length(),
            "body {i}: ω {got} against L/I {om}"
        );
    }
    assert_eq!(spheres, a.spheres().len());
    assert_eq!(a.advance(end, &mut ()).unwrap(), Advance::Reached);
    b.advance(end, &mut ()).unwrap();
    assert!(
        bits(&a) == bits(&b),
        "stepping on from the trip changed the bits"
    );
}
