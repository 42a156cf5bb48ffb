//! Side by side with LIGGGHTS' `fix heat/gran/conduction` (`contact_area
//! overlap`, `area_correction no`; Debian's `liggghts`): a small bed of 64
//! spheres of two materials, held in place with jittered overlaps, its
//! half x < 0 at 400 K and the rest at 300 K, conducts for 1000 steps under
//! the geometric-area conductance (T-54). Every temperature agrees to
//! 1e-6 relative (the sums differ in order only). Skips, saying so, when
//! `liggghts` is not installed.

use clump_core::body::BodyInit;
use clump_core::boundary::Domain;
use clump_core::contact::{ContactTable, Material, PairProperties};
use clump_core::heat::{Conductance, HeatModel, ThermalMaterial};
use clump_core::multi_contact::MultiContact;
use clump_core::shape::{ClumpTemplate, Sphere};
use clump_core::world::{AddedMass, World, WorldConfig};
use glam::{DQuat, DVec3};
use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;

const R: f64 = 1e-3;
const K: [f64; 2] = [2.0, 30.0];
const CP: [f64; 2] = [800.0, 500.0];
const RHO: [f64; 2] = [2500.0, 7800.0];
const DT: f64 = 5e-3;
const STEPS: u64 = 1000;

/// The bed: (material, centre) of 64 spheres on a jittered cubic lattice
/// of spacing 0.995 · 2R (a fixed pseudo-random jitter of ±0.4 % of R).
fn bed() -> Vec<(usize, DVec3)> {
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut jitter = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        ((state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0) * 0.004 * R
    };
    let d = 2.0 * R * 0.995;
    let mut out = Vec::new();
    for i in 0..4 {
        for j in 0..4 {
            for k in 0..4 {
                let c = |n: i32| (n as f64 - 1.5) * d;
                let x = DVec3::new(c(i) + jitter(), c(j) + jitter(), c(k) + jitter());
                let m = if out.len() % 3 == 1 { 1 } else { 0 };
                out.push((m, x));
            }
        }
    }
    out
}

fn initial_temperature(x: DVec3) -> f64 {
    if x.x < 0.0 {
        400.0
    } else {
        300.0
    }
}

/// The LIGGGHTS input of the bed.
fn liggghts_input(bed: &[(usize, DVec3)]) -> String {
    let mut s = String::from(
        "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n\
         communicate single vel yes\nunits si\n\
         region domain block -0.01 0.01 -0.01 0.01 -0.01 0.01 units box\ncreate_box 2 domain\n\
         neighbor 0.0002 bin\nneigh_modify delay 0\n\
         fix m1 all property/global youngsModulus peratomtype 1e8 2e8\n\
         fix m2 all property/global poissonsRatio peratomtype 0.3 0.25\n\
         fix m3 all property/global coefficientRestitution peratomtypepair 2 0.5 0.5 0.5 0.5\n\
         fix m4 all property/global coefficientFriction peratomtypepair 2 0.5 0.5 0.5 0.5\n",
    );
    writeln!(
        s,
        "fix tc all property/global thermalConductivity peratomtype {:?} {:?}",
        K[0], K[1]
    )
    .unwrap();
    writeln!(
        s,
        "fix cap all property/global thermalCapacity peratomtype {:?} {:?}",
        CP[0], CP[1]
    )
    .unwrap();
    s.push_str("pair_style gran model hertz tangential history\npair_coeff * *\n");
    writeln!(s, "timestep {DT:?}").unwrap();
    for (m, x) in bed {
        writeln!(
            s,
            "create_atoms {} single {:?} {:?} {:?} units box",
            m + 1,
            x.x,
            x.y,
            x.z
        )
        .unwrap();
    }
    for m in 0..2 {
        writeln!(
            s,
            "set type {} diameter {:?} density {:?}",
            m + 1,
            2.0 * R,
            RHO[m]
        )
        .unwrap();
    }
    // no integrator: the spheres stay where they are; the temperatures
    // are set once the fix exists (after a run of 0 steps)
    s.push_str(
        "fix heat all heat/gran/conduction initial_temperature 300 contact_area overlap area_correction no\n\
         run 0\nregion hot block -0.01 0.0 -0.01 0.01 -0.01 0.01 units box\n\
         set region hot property/atom Temp 400\n",
    );
    writeln!(s, "dump d all custom {STEPS} temps.dump id f_Temp").unwrap();
    s.push_str("dump_modify d format \"%d %.17g\"\n");
    writeln!(s, "run {STEPS}").unwrap();
    s
}

/// LIGGGHTS' temperatures by atom id (1-based, the bed's order) after the
/// run, or `None` (with the reason printed) when it cannot run.
fn liggghts_temperatures(bed: &[(usize, DVec3)]) -> Option<Vec<f64>> {
    let exe = ["/usr/bin/liggghts", "liggghts"]
        .into_iter()
        .find(|e| Command::new(e).arg("-h").output().is_ok());
    let Some(exe) = exe else {
        println!("skipped: LIGGGHTS is not installed (apt-get install liggghts)");
        return None;
    };
    let dir = std::env::temp_dir().join(format!("clump-heat-liggghts-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("in.heat"), liggghts_input(bed)).unwrap();
    let out = Command::new(exe)
        .args(["-echo", "none", "-log", "none", "-in", "in.heat"])
        .current_dir(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "LIGGGHTS failed: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    let text = std::fs::read_to_string(dir.join("temps.dump")).unwrap();
    let _ = std::fs::remove_dir_all(Path::new(&dir));
    // the last frame
    let last = text.rfind("ITEM: ATOMS").unwrap();
    let mut t = vec![f64::NAN; bed.len()];
    for line in text[last..].lines().skip(1) {
        let mut f = line.split_whitespace();
        let id: usize = f.next().unwrap().parse().unwrap();
        t[id - 1] = f.next().unwrap().parse().unwrap();
    }
    Some(t)
}

/// Clump's temperatures in the bed's order after the run.
fn clump_temperatures(bed: &[(usize, DVec3)]) -> Vec<f64> {
    let mats: Vec<Material> = (0..2)
        .map(|m| Material {
            youngs_modulus: [1e8, 2e8][m],
            poisson_ratio: [0.3, 0.25][m],
            density: RHO[m],
        })
        .collect();
    let table = ContactTable::new(&mats, |_, _| PairProperties::default()).unwrap();
    let config = WorldConfig {
        domain: Domain {
            lo: DVec3::splat(-0.01),
            hi: DVec3::splat(0.01),
            periodic: [false; 3],
        },
        gravity: DVec3::ZERO,
        dt: DT,
        rotation: Default::default(),
        added_mass: AddedMass::default(),
        skin: None,
        multi_contact: MultiContact::Sum,
    };
    let mut w = World::new(config, mats, table);
    for m in 0..2 {
        let s = [Sphere {
            center: DVec3::ZERO,
            radius: R,
        }];
        w.add_template(
            ClumpTemplate::from_spheres("sphere", &s, RHO[m]).unwrap(),
            m as u16,
        )
        .unwrap();
    }
    w.enable_heat(HeatModel {
        conductance: Conductance::Geometric,
        materials: (0..2)
            .map(|m| {
                Some(ThermalMaterial {
                    conductivity: K[m],
                    specific_heat: CP[m],
                })
            })
            .collect(),
        wall_temperature: vec![],
        template_temperature: vec![300.0, 300.0],
        template_source: vec![0.0, 0.0],
    })
    .unwrap();
    let ids: Vec<u64> = bed
        .iter()
        .map(|&(m, x)| {
            let init = BodyInit {
                force_flag: [false; 3],
                torque_flag: [false; 3],
                ..BodyInit::at_rest(m as u32, x, DQuat::IDENTITY)
            };
            let id = w.add_body(&init).unwrap();
            w.set_body_temperature(id, initial_temperature(x)).unwrap();
            id
        })
        .collect();
    w.run(STEPS).unwrap();
    ids.iter()
        .map(|&id| w.bodies().temperature[w.body_index(id).unwrap()])
        .collect()
}

#[test]
fn bed_temperatures_match_liggghts_heat_gran_conduction() {
    let bed = bed();
    let Some(theirs) = liggghts_temperatures(&bed) else {
        return;
    };
    let ours = clump_temperatures(&bed);
    let mut worst = 0.0f64;
    let mut moved = 0.0f64;
    for (k, (a, b)) in ours.iter().zip(&theirs).enumerate() {
        let rel = ((a - b) / b).abs();
        worst = worst.max(rel);
        moved = moved.max((a - initial_temperature(bed[k].1)).abs());
        assert!(rel < 1e-6, "sphere {k}: Clump {a} K, LIGGGHTS {b} K");
    }
    println!(
        "64 spheres, {STEPS} steps: largest temperature change {moved:.4} K, largest relative difference to LIGGGHTS {worst:.3e}"
    );
    // the comparison means something: heat has flowed
    assert!(moved > 1.0, "{moved}");
}
