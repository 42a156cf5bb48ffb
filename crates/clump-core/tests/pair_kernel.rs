//! The batched, vectorised pair kernel against the scalar contact law: a
//! random dense cloud of clumps of two materials, with three different
//! models (Hertz without rolling resistance, Hertz with EPSD, linear with CDT
//! and no tensile clamp), so that batches mix models and carry rolling
//! couples. Every body's force and torque after `prepare` must equal a brute
//! force sum of `ContactModel::evaluate` over all touching sphere pairs of
//! different bodies, under both multi-contact rules. Again with LIGGGHTS'
//! tangential rule on the pairs of material 1 (EPSD and CDT rolling), which
//! the kernel evaluates with the scalar composition beside vectorised lanes.

mod common;
use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::ContactTable;
use clump_core::contact::{
    ContactHistory, ContactInput, DampingLaw, Material, NormalLaw, PairProperties, RollingLaw,
    TangentialLaw, TwistingLaw,
};
use clump_core::multi_contact::MultiContact;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::world::World;
use common::Lcg;
use glam::DVec3;
use std::collections::HashMap;

fn materials() -> Vec<Material> {
    vec![
        Material {
            youngs_modulus: 1e7,
            poisson_ratio: 0.3,
            density: 2500.0,
        },
        Material {
            youngs_modulus: 3e7,
            poisson_ratio: 0.25,
            density: 1500.0,
        },
    ]
}

/// The three models; `rule` is the tangential rule of the pairs with
/// material 1.
fn pair_props(a: usize, b: usize, rule: TangentialLaw) -> PairProperties {
    match (a, b) {
        (0, 0) => PairProperties {
            restitution: 0.5,
            friction: 0.5,
            ..PairProperties::default()
        },
        (0, 1) => PairProperties {
            restitution: 0.3,
            friction: 0.3,
            rolling_friction: 0.1,
            rolling: RollingLaw::Epsd,
            tangential: rule,
            ..PairProperties::default()
        },
        _ => PairProperties {
            restitution: 0.7,
            friction: 0.4,
            rolling_friction: 0.2,
            rolling: RollingLaw::Cdt,
            normal: NormalLaw::Linear { kn: 2e4, kt: 1e4 },
            damping: DampingLaw::Liggghts,
            tensile: true,
            tangential: rule,
            // with LIGGGHTS' rule also twisting resistance (its couple
            // comes with the scalar path's)
            twisting: if rule == TangentialLaw::Liggghts {
                TwistingLaw::Marshall
            } else {
                TwistingLaw::None
            },
            ..PairProperties::default()
        },
    }
}

/// A dense random cloud of 2-sphere (material 0) and 3-sphere (material 1)
/// clumps in a 3 cm box, moving and spinning at random.
fn cloud(multi: MultiContact, rule: TangentialLaw) -> World {
    let mats = materials();
    let table = ContactTable::new(&mats, |a, b| pair_props(a, b, rule)).expect("table");
    let domain = Domain {
        lo: DVec3::splat(-0.05),
        hi: DVec3::splat(0.05),
        periodic: [false; 3],
    };
    let mut w = common::world(mats[0], PairProperties::default(), 1e-5, domain, DVec3::Z);
    // two particle materials, their three models, no wall material
    w.materials = mats;
    w.contact_table = table;
    w.config.gravity = DVec3::new(0.0, 0.0, -9.81);
    w.config.multi_contact = multi;
    let r = 1e-3;
    let dimer = ClumpTemplate::from_spheres(
        "dimer",
        &[
            Sphere {
                center: DVec3::new(-0.6 * r, 0.0, 0.0),
                radius: r,
            },
            Sphere {
                center: DVec3::new(0.6 * r, 0.0, 0.0),
                radius: 0.8 * r,
            },
        ],
        2500.0,
    )
    .expect("dimer");
    let tri = ClumpTemplate::from_spheres(
        "tri",
        &[
            Sphere {
                center: DVec3::new(0.0, 0.7 * r, 0.0),
                radius: 1.2 * r,
            },
            Sphere {
                center: DVec3::new(0.6 * r, -0.35 * r, 0.0),
                radius: r,
            },
            Sphere {
                center: DVec3::new(-0.6 * r, -0.35 * r, 0.2 * r),
                radius: 0.9 * r,
            },
        ],
        1500.0,
    )
    .expect("tri");
    let t0 = w.add_template(dimer, 0).expect("template");
    let t1 = w.add_template(tri, 1).expect("template");
    let mut g = Lcg(7);
    for k in 0..300 {
        let q = g.quat();
        w.add_body(&BodyInit {
            velocity: g.vec(0.5),
            angular_velocity: g.vec(300.0),
            ..BodyInit::at_rest(if k % 2 == 0 { t0 } else { t1 }, g.vec(0.007), q)
        })
        .expect("body");
    }
    w
}

/// Force and torque on every body (by id) from the scalar law, summed over
/// all touching sphere pairs of different bodies, plus gravity, with the
/// models of `table`.
fn reference(w: &World, table: &ContactTable, multi: MultiContact) -> HashMap<u64, (DVec3, DVec3)> {
    let (b, sp) = (&w.bodies(), w.spheres());
    let n = sp.len();
    let mut contacts = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            let (bi, bj) = (sp.body[i] as usize, sp.body[j] as usize);
            let d = sp.position(i) - sp.position(j);
            let rsum = sp.radius[i] + sp.radius[j];
            if bi != bj && d.length_squared() < rsum * rsum {
                contacts.push((i, j));
            }
        }
    }
    let mut per_body_pair: HashMap<(usize, usize), usize> = HashMap::new();
    for &(i, j) in &contacts {
        let (bi, bj) = (sp.body[i] as usize, sp.body[j] as usize);
        *per_body_pair.entry((bi.min(bj), bi.max(bj))).or_default() += 1;
    }
    let mut load: Vec<(DVec3, DVec3)> = (0..b.len())
        .map(|k| (b.mass[k] * w.config.gravity, DVec3::ZERO))
        .collect();
    for &(i, j) in &contacts {
        let (bi, bj) = (sp.body[i] as usize, sp.body[j] as usize);
        let (ri, rj) = (sp.radius[i], sp.radius[j]);
        let d = sp.position(i) - sp.position(j);
        let dist = d.length();
        let nrm = d / dist;
        let overlap = ri + rj - dist;
        let xc = sp.position(i) - nrm * (ri - 0.5 * overlap);
        let vc = |k: usize| b.velocity[k] + b.angular_velocity[k].cross(xc - b.position[k]);
        let input = ContactInput {
            normal: nrm,
            overlap,
            rel_velocity: vc(bi) - vc(bj),
            rel_omega: b.angular_velocity[bi] - b.angular_velocity[bj],
            radius: ri * rj / (ri + rj),
            radius_sum: f64::INFINITY,
            mass: b.mass[bi] * b.mass[bj] / (b.mass[bi] + b.mass[bj]),
            dt: w.config.dt,
        };
        let model = table.get(sp.material[i], sp.material[j]);
        let out = model.evaluate(&input, &mut ContactHistory::default());
        let scale = match multi {
            MultiContact::Sum => 1.0,
            MultiContact::Average => 1.0 / per_body_pair[&(bi.min(bj), bi.max(bj))] as f64,
        };
        let (f, c) = (out.force * scale, out.torque * scale);
        load[bi].0 += f;
        load[bi].1 += (xc - b.position[bi]).cross(f) + c;
        load[bj].0 -= f;
        load[bj].1 += (xc - b.position[bj]).cross(-f) - c;
    }
    (0..b.len()).map(|k| (b.id[k], load[k])).collect()
}

#[test]
fn batched_kernel_equals_the_scalar_law_with_mixed_models_and_rolling() {
    for rule in [TangentialLaw::Clump, TangentialLaw::Liggghts] {
        for multi in [MultiContact::Sum, MultiContact::Average] {
            compare(multi, rule);
        }
    }
}

/// The kernel's loads against [`reference`]'s, for one rule and
/// multi-contact rule.
fn compare(multi: MultiContact, rule: TangentialLaw) {
    let mut w = cloud(multi, rule);
    w.prepare().expect("prepare");
    let want = reference(&w, &w.contact_table, multi);
    let stats = w.thermo();
    assert!(
        stats.pair_contacts > 300,
        "the cloud must be dense: {} contacts",
        stats.pair_contacts
    );
    // force and torque scales of the cloud, for the tolerance
    let b = &w.bodies();
    let fmax = (0..b.len())
        .map(|k| want[&b.id[k]].0.length())
        .fold(0.0, f64::max);
    let tmax = (0..b.len())
        .map(|k| want[&b.id[k]].1.length())
        .fold(0.0, f64::max);
    let worst = |r: &HashMap<u64, (DVec3, DVec3)>| {
        let mut worst = (0.0f64, 0.0f64);
        for k in 0..b.len() {
            let (f, t) = r[&b.id[k]];
            worst.0 = worst.0.max((b.force[k] - f).length() / fmax);
            worst.1 = worst.1.max((b.torque[k] - t).length() / tmax);
        }
        worst
    };
    let dev = worst(&want);
    eprintln!(
        "{multi:?}, {rule:?}: {} contacts, largest force {fmax:.3e} N, torque {tmax:.3e} N m; \
         worst relative deviation force {:.1e}, torque {:.1e}",
        stats.pair_contacts, dev.0, dev.1
    );
    // the same law summed in another order: round-off only
    assert!(dev.0 < 1e-12 && dev.1 < 1e-12, "{dev:?}");
    if rule == TangentialLaw::Liggghts {
        // the rule makes a difference here: Clump's rule is not what ran
        let mats = materials();
        let clump =
            ContactTable::new(&mats, |a, b| pair_props(a, b, TangentialLaw::Clump)).expect("table");
        let other = worst(&reference(&w, &clump, multi));
        eprintln!(
            "  against Clump's rule: force {:.1e}, torque {:.1e}",
            other.0, other.1
        );
        assert!(other.0 > 1e-6 || other.1 > 1e-6, "{other:?}");
    }
}
