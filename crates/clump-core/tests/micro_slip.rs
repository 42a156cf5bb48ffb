//! The micro-slip tangential models in the engine. Thornton–Yin's
//! (`contact::micro_slip`, `tangential = "mindlin_deresiewicz"`) keeps its
//! turning points in the contact history, the exact model (`contact::mdr`,
//! `tangential = "mdr"`) its profiles beside the histories: for both, a
//! state saved mid-contact and restored into a fresh world (neighbour lists
//! rebuilt from the stored state) repeats the uninterrupted run bit for
//! bit, for a sphere pair (pair kernel, scalar path) and a sphere on a
//! wall; and neighbour rebuilds carry the profiles.

use clump_core::contact::{PairProperties, TangentialLaw};
use clump_core::state::WorldState;
use clump_core::world::World;
use clump_validate::setup::{
    body, coincident_spheres, material, open_box, plane, props, world, PARTICLE,
};
use glam::{DQuat, DVec3};

const R: f64 = 2.5e-3;

/// Two alumina spheres meeting at 10° from head-on and one striking the
/// plane z = −0.1 m at 10°, with the tangential law `law`: all three
/// contacts start within a few steps.
fn impacts(law: TangentialLaw) -> World {
    let mat = material(3.8e11, 0.23, 4000.0);
    let p = PairProperties {
        tangential: law,
        ..props(0.98, 0.092)
    };
    let mut w = world(mat, p, 1e-8, open_box(1.0), DVec3::ZERO).unwrap();
    let t = w
        .add_template(coincident_spheres(1, R, mat.density).unwrap(), PARTICLE)
        .unwrap();
    let th = 10f64.to_radians();
    let (vn, vt) = (3.9 * th.cos(), 3.9 * th.sin());
    let gap = R + 1e-7;
    for (x, v) in [
        (
            DVec3::new(-gap, 0.0, 0.0),
            DVec3::new(vn / 2.0, vt / 2.0, 0.0),
        ),
        (
            DVec3::new(gap, 0.0, 0.0),
            DVec3::new(-vn / 2.0, -vt / 2.0, 0.0),
        ),
        (DVec3::new(0.5, 0.0, -0.1 + gap), DVec3::new(vt, 0.0, -vn)),
    ] {
        w.add_body(&body(t, x, DQuat::IDENTITY, v, DVec3::new(0.0, 0.0, 30.0)))
            .unwrap();
    }
    w.add_wall(plane(DVec3::new(0.0, 0.0, -0.1), DVec3::Z))
        .unwrap();
    w
}

fn bits(w: &World) -> Vec<u64> {
    let b = &w.bodies();
    (0..b.len())
        .flat_map(|i| {
            [b.position[i], b.velocity[i], b.angular_momentum[i]]
                .into_iter()
                .flat_map(|v| v.to_array().map(f64::to_bits))
        })
        .collect()
}

/// Runs the impacts with `law` for 900 steps whole, and saved at step 420
/// (the contacts mid-way), checked by `mid_contact`, restored into a fresh
/// world and run on: both repeat the whole run bit for bit.
fn restored_run_repeats(law: TangentialLaw, mid_contact: impl Fn(&WorldState)) {
    let total = 900;
    let mut a = impacts(law);
    a.run(total).unwrap();
    let end = bits(&a);
    // the spheres have left each other and the wall, with spin and
    // sideways speed from the tangential force
    assert_eq!(a.stats.pair_contacts + a.stats.wall_contacts, 0);
    assert!(a.bodies().velocity[2].z > 0.0);
    assert!(a.bodies().velocity[2].x < 3.9 * 10f64.to_radians().sin());

    let mut b = impacts(law);
    b.run(420).unwrap();
    let saved = b.save_state().unwrap();
    mid_contact(&saved);
    let mut c = impacts(law);
    c.restore_state(saved).unwrap();
    c.run(total - 420).unwrap();
    assert!(end == bits(&c), "the restored run differs");
    // and the uninterrupted run of the saving world too
    b.run(total - 420).unwrap();
    assert!(end == bits(&b));
}

#[test]
fn turning_points_survive_a_checkpoint() {
    restored_run_repeats(TangentialLaw::MindlinDeresiewicz, |saved| {
        // mid-contact, a contact in unloading or reloading: a turning point
        // stored in the second slot
        let pair_tp = saved
            .pair_history
            .iter()
            .any(|(_, h)| h.rolling != DVec3::ZERO);
        let wall_tp = saved
            .wall_hist
            .iter()
            .flatten()
            .any(|h| h.rolling != DVec3::ZERO);
        assert!(pair_tp && wall_tp, "pair {pair_tp}, wall {wall_tp}");
    });
}

/// `tangential = "mdr"`: mid-contact, the profiles (of several nodes) are
/// in the saved state, and the restored run repeats the uninterrupted one.
#[test]
fn profiles_survive_a_checkpoint() {
    restored_run_repeats(TangentialLaw::Mdr, |saved| {
        // profiles of several nodes (a slip zone and a stuck core at
        // least) for the pair and on the wall
        let pair_nodes = saved.pair_slip.iter().map(|(_, p)| p.len).max();
        let wall_nodes = saved.wall_slip.iter().flatten().map(|p| p.len).max();
        assert!(
            pair_nodes >= Some(3) && wall_nodes >= Some(3),
            "pair {pair_nodes:?}, wall {wall_nodes:?}"
        );
    });
}

/// A skin so thin that the lists are rebuilt nearly every step: each
/// rebuild carries the profiles (by storage index), and the run repeats
/// the one with the default skin bit for bit.
#[test]
fn profiles_survive_rebuilds() {
    let impacts = || impacts(TangentialLaw::Mdr);
    let total = 900;
    let mut a = impacts();
    a.run(total).unwrap();
    let mut b = impacts();
    b.config.skin = Some(2e-8);
    b.run(total).unwrap();
    assert!(
        b.rebuilds > a.rebuilds + 100,
        "{} {}",
        a.rebuilds,
        b.rebuilds
    );
    assert!(bits(&a) == bits(&b), "the rebuilt run differs");
}
