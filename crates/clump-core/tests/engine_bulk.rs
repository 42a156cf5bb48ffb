//! Engine-level checks on many bodies: energy conservation in an elastic gas
//! of clumps, a settling bed, thread-count determinism, and the several-contact
//! treatments on a dimer dropped flat.

mod common;
use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{Material, NormalLaw, PairProperties};
use clump_core::multi_contact::MultiContact;
use clump_core::rotation::RotationScheme;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::world::World;
use common::*;
use glam::DVec3;

fn tetra(r: f64, edge: f64, density: f64) -> ClumpTemplate {
    clump_validate::setup::tetra(r, edge, density).unwrap()
}

fn bench_material() -> Material {
    Material {
        youngs_modulus: 5e6,
        poisson_ratio: 0.3,
        density: 2500.0,
    }
}

/// Bodies on a jittered lattice in `[lo, hi]` with spacing `a`.
fn lattice(
    w: &mut World,
    t: u32,
    lo: DVec3,
    hi: DVec3,
    a: f64,
    max: usize,
    vel: f64,
    rng: &mut Lcg,
) {
    let n = ((hi - lo) / a).floor();
    let mut count = 0;
    for k in 0..n.z as usize {
        for j in 0..n.y as usize {
            for i in 0..n.x as usize {
                if count == max {
                    return;
                }
                let x = lo + DVec3::new(i as f64 + 0.5, j as f64 + 0.5, k as f64 + 0.5) * a;
                let v =
                    DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 2.0 * vel;
                let om =
                    DVec3::new(rng.next() - 0.5, rng.next() - 0.5, rng.next() - 0.5) * 2.0 * vel
                        / a;
                let init = BodyInit {
                    velocity: v,
                    angular_velocity: om,
                    ..BodyInit::at_rest(t, x, rng.quat())
                };
                w.add_body(&init).unwrap();
                count += 1;
            }
        }
    }
}

fn total_energy(w: &World) -> f64 {
    let t = w.thermo();
    t.kinetic_translational + t.kinetic_rotational + t.elastic + t.potential
}

/// Frictionless, elastic (e = 1) gas of clumps in a periodic box conserves
/// kinetic plus elastic energy to 1e-3 over 10⁴ steps at dt = t_c/50.
#[test]
fn elastic_gas_conserves_energy() {
    for scheme in [
        RotationScheme::default(),
        RotationScheme::Richardson,
        RotationScheme::NoSquish,
        RotationScheme::ZhaoVanWachem,
    ] {
        let mat = bench_material();
        let props = PairProperties {
            restitution: 1.0,
            friction: 0.0,
            ..PairProperties::default()
        };
        let r = 1e-3;
        let tmpl = tetra(r, 1.2e-3, mat.density);
        let vel = 0.5;
        // Hertz contact time at the typical closing speed
        let e_star = mat.youngs_modulus / (2.0 * (1.0 - 0.09));
        let m_star = tmpl.mass / 2.0;
        let r_star = r / 2.0;
        let v = 2.0 * vel;
        let dmax = (15.0 * m_star * v * v / (16.0 * e_star * r_star.sqrt())).powf(0.4);
        let tc = 2.9432 * dmax / v;
        let dt = tc / 50.0;
        let l = 0.02;
        let dom = Domain {
            lo: DVec3::ZERO,
            hi: DVec3::splat(l),
            periodic: [true; 3],
        };
        let mut w = world(mat, props, dt, dom, DVec3::ZERO);
        w.config.rotation = scheme;
        let t = w.add_template(tmpl, 0).unwrap();
        let mut rng = Lcg(7);
        lattice(
            &mut w,
            t,
            DVec3::ZERO,
            DVec3::splat(l),
            3.5e-3,
            200,
            vel,
            &mut rng,
        );
        w.prepare().unwrap();
        let e0 = total_energy(&w);
        let mut max_dev: f64 = 0.0;
        let mut contacts = 0;
        for _ in 0..10_000 {
            w.step().unwrap();
            contacts += w.stats.pair_contacts;
            max_dev = max_dev.max((total_energy(&w) - e0).abs() / e0);
        }
        eprintln!("elastic gas, {scheme:?}: dt {dt:.3e} (t_c {tc:.3e}), contact-steps {contacts}, max |ΔE|/E = {max_dev:.3e}");
        assert!(contacts > 1000, "the gas must collide");
        if scheme == RotationScheme::default() {
            assert!(max_dev < 1e-3, "energy drift {max_dev}");
        }
    }
}

fn settle_world(n: usize, seed: u64) -> World {
    let mat = bench_material();
    let props = PairProperties {
        restitution: 0.5,
        friction: 0.5,
        ..PairProperties::default()
    };
    let dom = Domain {
        lo: DVec3::new(-0.01, -0.01, -0.001),
        hi: DVec3::new(0.01, 0.01, 0.1),
        periodic: [false; 3],
    };
    let mut w = world(mat, props, 1e-5, dom, DVec3::new(0.0, 0.0, -9.81));
    let t = w.add_template(tetra(1e-3, 1.2e-3, mat.density), 0).unwrap();
    for (p, nrm) in [
        (DVec3::ZERO, DVec3::Z),
        (DVec3::new(-0.008, 0.0, 0.0), DVec3::X),
        (DVec3::new(0.008, 0.0, 0.0), -DVec3::X),
        (DVec3::new(0.0, -0.008, 0.0), DVec3::Y),
        (DVec3::new(0.0, 0.008, 0.0), -DVec3::Y),
    ] {
        w.add_wall(plane(p, nrm, MultiContact::Sum)).unwrap();
    }
    let mut rng = Lcg(seed);
    lattice(
        &mut w,
        t,
        DVec3::new(-0.008, -0.008, 0.001),
        DVec3::new(0.008, 0.008, 0.08),
        3.3e-3,
        n,
        0.0,
        &mut rng,
    );
    w
}

/// A bed of a few hundred clumps settles under gravity on a plane and comes
/// to rest: kinetic energy < 1e-6 of the potential-energy drop.
#[test]
fn settled_bed_comes_to_rest() {
    let mut w = settle_world(300, 3);
    w.prepare().unwrap();
    let pe0 = w.thermo().potential;
    let n = w.bodies().len();
    for _ in 0..60_000 {
        w.step().unwrap();
    }
    let t = w.thermo();
    let drop = pe0 - t.potential;
    let ke = t.kinetic_translational + t.kinetic_rotational;
    eprintln!("settled bed: {n} clumps, PE drop {drop:.4e} J, KE {ke:.3e} J (trans {:.3e}, rot {:.3e}), ratio {:.3e}, contacts {}+{}, lost {}", t.kinetic_translational, t.kinetic_rotational, ke / drop, t.pair_contacts, t.wall_contacts, t.lost_bodies);
    assert_eq!(t.lost_bodies, 0);
    assert!(drop > 0.0);
    assert!(ke < 1e-6 * drop, "KE/PE drop = {}", ke / drop);
}

/// Body states (bits) after the bed has fallen and packed (11 000 steps),
/// then 1000 more steps of the dense bed; also the contact counts then.
/// `World::run` (whose steps each take the next one's first half in their
/// gather), or with `stepwise` one `World::step` at a time (no fusion).
fn bed_state(threads: usize, stepwise: bool) -> (Vec<u64>, u64, u64) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut w = settle_world(400, 11);
        if stepwise {
            for _ in 0..12_000 {
                w.step().unwrap();
            }
        } else {
            w.run(11_000).unwrap();
            w.run(1000).unwrap();
        }
        let bits = state_bits(&w);
        (bits, w.stats.pair_contacts, w.stats.wall_contacts)
    })
}

/// The bits of every body's state (`testbed::state_bits`) and of the summed
/// statistics.
fn state_bits(w: &World) -> Vec<u64> {
    let mut bits = clump_core::testbed::state_bits(w);
    // the chunked sums of the statistics too
    let st = &w.stats;
    bits.extend([st.elastic_energy, st.kinetic_energy, st.max_overlap_ratio].map(f64::to_bits));
    bits
}

/// Bit-identical body states for 1, 2 and 3 threads after 1000 steps of a
/// dense bed (400 tetrahedral clumps that have fallen and packed for 11 000
/// steps first; the contact count shows the bed is dense). The threads'
/// shares of each loop are learned from measured times, so they differ from
/// run to run: only the results may not.
#[test]
fn one_two_and_three_threads_are_bit_identical() {
    let (a, pc, wc) = bed_state(1, false);
    assert!(pc > 500, "the bed is not dense: {pc} contacts");
    for threads in [2, 3] {
        let (b, pc2, wc2) = bed_state(threads, false);
        eprintln!("thread identity: 400 clumps, {pc} sphere-sphere + {wc} sphere-wall contacts at the end; 1 vs {threads} threads identical: {}", a == b);
        assert_eq!((pc, wc), (pc2, wc2));
        assert_eq!(a.len(), b.len());
        assert!(a == b, "states differ between 1 and {threads} threads");
    }
}

/// `World::run` fuses each step's final kick with the next step's first half
/// (one pass over the bodies); single steps do not. Both give the same bits,
/// on one thread and on two (where the pair loads of the bodies on the seam
/// between the threads' runs are summed by the gather instead).
#[test]
fn run_and_single_steps_are_bit_identical() {
    let (a, pc, wc) = bed_state(1, false);
    assert!(pc > 500, "the bed is not dense: {pc} contacts");
    for threads in [1, 2] {
        let (b, pc2, wc2) = bed_state(threads, true);
        assert_eq!((pc, wc), (pc2, wc2));
        assert!(a == b, "run and single steps differ ({threads} threads)");
    }
}

/// Restitution of a dimer (two overlapping spheres) dropped flat onto a
/// plane, so both spheres hit at once.
fn dimer_drop(normal: NormalLaw, e: f64, multi: MultiContact, tensile: bool) -> f64 {
    let mat = Material {
        youngs_modulus: 1e8,
        poisson_ratio: 0.3,
        density: 2500.0,
    };
    let props = PairProperties {
        restitution: e,
        friction: 0.0,
        normal,
        tensile,
        ..PairProperties::default()
    };
    let r = 1e-3;
    let s = [
        Sphere {
            center: DVec3::new(-0.6e-3, 0.0, 0.0),
            radius: r,
        },
        Sphere {
            center: DVec3::new(0.6e-3, 0.0, 0.0),
            radius: r,
        },
    ];
    let tmpl = ClumpTemplate::from_spheres("dimer", &s, mat.density).unwrap();
    let mut w = world(mat, props, 2e-8, open_domain(1.0), DVec3::ZERO);
    let t = w.add_template(tmpl, 0).unwrap();
    // template principal frame: long axis is the smallest moment → body x; keep it along world x
    let id = w
        .add_body(&moving(
            t,
            DVec3::new(0.0, 0.0, r + 1e-7),
            DVec3::new(0.0, 0.0, -1.0),
            DVec3::ZERO,
        ))
        .unwrap();
    w.add_wall(plane(DVec3::ZERO, DVec3::Z, multi)).unwrap();
    run_impact(&mut w, id, r, 10_000_000);
    let b = w.body_index(id).unwrap();
    w.bodies().velocity[b].z / 1.0
}

/// Restitution of the non-dimensional Hertz–Tsuji impact x'' = −x^{3/2} − c x^{1/4} x'
/// (test-local RK4, independent of the engine). `clamped`: the force cannot
/// pull, so the body leaves where it first reaches zero on the way out.
fn hertz_tsuji_restitution(c: f64, clamped: bool) -> f64 {
    let (mut x, mut v) = (0.0f64, 1.0f64);
    let h = 2e-5;
    let f = |x: f64, v: f64| -x.max(0.0).powf(1.5) - c * x.max(0.0).powf(0.25) * v;
    // an overdamped impact creeps back towards x = 0 without crossing it: e = 0
    for _ in 0..20_000_000 {
        let (k1x, k1v) = (v, f(x, v));
        let (k2x, k2v) = (v + 0.5 * h * k1v, f(x + 0.5 * h * k1x, v + 0.5 * h * k1v));
        let (k3x, k3v) = (v + 0.5 * h * k2v, f(x + 0.5 * h * k2x, v + 0.5 * h * k2v));
        let (k4x, k4v) = (v + h * k3v, f(x + h * k3x, v + h * k3v));
        let xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        let vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        if xn <= 0.0 && vn < 0.0 {
            // linear interpolation of v at x = 0
            let s = x / (x - xn);
            return -(v + s * (vn - v));
        }
        if clamped && vn < 0.0 && f(xn, vn) >= 0.0 {
            // the force reaches zero: linear interpolation of v there
            let (a0, a1) = (f(x, v), f(xn, vn));
            let s = if a0 < 0.0 { -a0 / (a1 - a0) } else { 0.0 };
            return -(v + s * (vn - v));
        }
        x = xn;
        v = vn;
    }
    0.0
}

/// Under `average` the dimer rebounds with the input e. Under `sum`, two
/// contacts in parallel double the stiffness and the damping while the
/// dashpot was sized for one contact with the whole body mass, so the damping
/// ratio ζ = −β grows by √2:
/// - linear law, clamped (default): e_sum = exp(−2ζ₂A(ζ₂)), ζ₂ = √2 ζ
///   (`damping::clamped_restitution`); tensile: e_sum = exp(−√2 ζ π/√(1 − 2ζ²))
///   with ζ = −ln e/√(ln²e + π²);
/// - Hertz with the δ^¼ dashpot: e_sum is the restitution of the same
///   non-dimensional problem (clamped or not) with its damping constant
///   multiplied by √2.
#[test]
fn dimer_dropped_flat_sum_and_average() {
    use clump_core::contact::damping::{clamped_beta, clamped_restitution};
    let lin = NormalLaw::Linear { kn: 2e4, kt: 0.0 };
    for tensile in [false, true] {
        for e in [0.3, 0.5, 0.8] {
            let avg_lin = dimer_drop(lin, e, MultiContact::Average, tensile);
            let sum_lin = dimer_drop(lin, e, MultiContact::Sum, tensile);
            let sum_lin_theory = if tensile {
                let zeta = -e.ln() / (e.ln().powi(2) + std::f64::consts::PI.powi(2)).sqrt();
                let z2 = 2f64.sqrt() * zeta;
                (-z2 * std::f64::consts::PI / (1.0 - z2 * z2).sqrt()).exp()
            } else {
                clamped_restitution(2f64.sqrt() * clamped_beta(e))
            };
            let avg_h = dimer_drop(NormalLaw::Hertz, e, MultiContact::Average, tensile);
            let sum_h = dimer_drop(NormalLaw::Hertz, e, MultiContact::Sum, tensile);
            // find c for e by bisection on the test-local model, then predict with √2 c
            let (mut lo, mut hi) = (0.0, 5.0);
            for _ in 0..40 {
                let mid = 0.5 * (lo + hi);
                if hertz_tsuji_restitution(mid, !tensile) > e {
                    lo = mid
                } else {
                    hi = mid
                }
            }
            let sum_h_theory = hertz_tsuji_restitution(0.5 * (lo + hi) * 2f64.sqrt(), !tensile);
            eprintln!("dimer tensile={tensile} e={e}: linear avg {avg_lin:.4} sum {sum_lin:.4} (theory {sum_lin_theory:.4}); hertz avg {avg_h:.4} sum {sum_h:.4} (theory {sum_h_theory:.4})");
            assert!((avg_lin - e).abs() < 0.01);
            assert!((avg_h - e).abs() < 0.01);
            assert!((sum_lin - sum_lin_theory).abs() < 0.01);
            assert!((sum_h - sum_h_theory).abs() < 0.01);
        }
    }
}

/// A state saved with `World::save_state` and restored into the same world,
/// after it has moved on, repeats the same steps bit for bit (`clump bench
/// --scaling` times repetitions of a round this way).
#[test]
fn restore_into_the_same_world_repeats_the_steps() {
    let mut w = settle_world(400, 11);
    w.run(11_000).unwrap();
    let saved = w.save_state().unwrap();
    w.run(1000).unwrap();
    let first = state_bits(&w);
    assert!(w.stats.pair_contacts > 500, "the bed is not dense");
    w.restore_state(saved).unwrap();
    w.run(1000).unwrap();
    assert!(first == state_bits(&w), "the repetition differs");
}
