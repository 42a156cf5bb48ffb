//! After each step: ghosts take their owners' new state (with heat, their
//! temperature too); the step's statistics and wall loads are then summed
//! over the ranks (`super::step_stats`).

use crate::world::World;
use glam::{DQuat, DVec3};

/// f64 values per body state sent: position, velocity, orientation (4),
/// angular momentum, angular velocity, force, torque.
const STATE_LEN: usize = 22;

fn put3(out: &mut Vec<u8>, v: DVec3) {
    for x in v.to_array() {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

fn take(bytes: &[u8], k: &mut usize) -> f64 {
    let x = f64::from_le_bytes(bytes[*k..*k + 8].try_into().expect("8 bytes"));
    *k += 8;
    x
}

fn take3(bytes: &[u8], k: &mut usize) -> DVec3 {
    DVec3::new(take(bytes, k), take(bytes, k), take(bytes, k))
}

/// Sends the state of every owned body that another rank holds as a ghost
/// to that rank, and overwrites every ghost with its owner's.
pub(crate) fn refresh(w: &mut World) {
    let part = w.part.as_mut().expect("a partitioned world");
    let b = &mut w.bodies;
    // with heat, the temperature follows the state
    let heat = w.heat.is_some();
    let sends: Vec<(usize, Vec<u8>)> = part
        .send
        .iter()
        .map(|(r, list)| {
            let mut out = Vec::with_capacity(list.len() * (STATE_LEN + heat as usize) * 8);
            for &i in list {
                let i = i as usize;
                put3(&mut out, b.position[i]);
                put3(&mut out, b.velocity[i]);
                for x in b.orientation[i].to_array() {
                    out.extend_from_slice(&x.to_le_bytes());
                }
                put3(&mut out, b.angular_momentum[i]);
                put3(&mut out, b.angular_velocity[i]);
                put3(&mut out, b.force[i]);
                put3(&mut out, b.torque[i]);
                if heat {
                    out.extend_from_slice(&b.temperature[i].to_le_bytes());
                }
            }
            (*r, out)
        })
        .collect();
    for (_, m) in &sends {
        part.traffic.ghost_bytes += m.len() as u64;
        part.traffic.ghost_messages += 1;
    }
    let from: Vec<usize> = part.recv.iter().map(|(r, _)| *r).collect();
    let got = part.comm.exchange(&sends, &from);
    for ((_, list), bytes) in part.recv.iter().zip(&got) {
        let mut k = 0;
        for &i in list {
            let i = i as usize;
            b.position[i] = take3(bytes, &mut k);
            b.velocity[i] = take3(bytes, &mut k);
            let q = [
                take(bytes, &mut k),
                take(bytes, &mut k),
                take(bytes, &mut k),
                take(bytes, &mut k),
            ];
            b.orientation[i] = DQuat::from_array(q);
            b.angular_momentum[i] = take3(bytes, &mut k);
            b.angular_velocity[i] = take3(bytes, &mut k);
            b.force[i] = take3(bytes, &mut k);
            b.torque[i] = take3(bytes, &mut k);
            if heat {
                b.temperature[i] = take(bytes, &mut k);
            }
        }
    }
    let ghosts = part.owned.iter().filter(|&&o| !o).count() as u64;
    part.traffic.ghost_body_steps += ghosts;
    part.traffic.local_body_steps += part.owned.len() as u64;
    part.traffic.pair_steps += w.neighbors.pairs.topo.len() as u64;
    part.traffic.ghost_pair_steps += w.neighbors.pairs.left_out as u64;
    part.traffic.steps += 1;
}
