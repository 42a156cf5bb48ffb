//! The copies between a host world and the device at events, springs
//! included, so that a download followed by an upload continues the run
//! as if it had stayed on the device, and a world downloaded from the
//! device continues on the CPU path (or is checkpointed) with its contact
//! history.
//!
//! Both directions go through the checkpoint form of the state
//! ([`clump_core::state::WorldState`]): pair springs keyed by (lower,
//! higher) global sphere id and oriented from the lower to the higher id,
//! wall springs per sphere in slots keyed by wall. On the device a pair's
//! spring lives in its owning entry (i, j > i by device sphere index) and
//! is the spring of the force on i; a wall spring lives in slot
//! (sphere, wall).

use crate::context::Gpu;
use crate::device_world::{DeviceError, DeviceWorld, Kernels, Springs, ENTRIES_PER_SPHERE, HIST};
use crate::support::unsupported;
use clump_core::contact::ContactHistory;
use clump_core::neighbor::walls::WALL_SLOTS;
use clump_core::sphere::sphere_gid;
use clump_core::world::World;
use glam::{DQuat, DVec3};
use std::collections::HashMap;

/// Global sphere id of each device sphere (bodies in ascending id,
/// spheres in template order, as `HostArrays::new` lays them out).
fn device_gids(world: &World) -> Vec<u64> {
    let b = &crate::device_world::by_id(world);
    let mut out = Vec::new();
    for i in 0..b.len() {
        let t = b.template[i] as usize;
        for k in 0..world.templates[t].spheres.len() {
            out.push(sphere_gid(b.id[i], k as u32));
        }
    }
    out
}

/// The key of a wall slot (`step/wall_contacts.rs` `slot_key`:
/// `(wall << 16 | patch) + 1`, the patch of an analytic wall its face).
fn slot_key(wall: usize, face: usize) -> u32 {
    (((wall as u32) << 16) | face as u32) + 1
}

/// The wall and face of a slot key.
fn slot_wall(key: u32) -> (usize, usize) {
    (((key - 1) >> 16) as usize, ((key - 1) & 0xffff) as usize)
}

/// The tangential and rolling springs of contact `k` of a device spring
/// array (`HIST` f64s per contact).
fn springs_at(a: &[f64], k: usize) -> (DVec3, DVec3) {
    let o = HIST * k;
    (
        DVec3::new(a[o], a[o + 1], a[o + 2]),
        DVec3::new(a[o + 3], a[o + 4], a[o + 5]),
    )
}

fn is_mesh(w: &clump_core::wall::Wall) -> bool {
    matches!(w.shape, clump_core::wall::WallShape::Mesh { .. })
}

fn bad_state(e: impl std::fmt::Display) -> DeviceError {
    DeviceError::Overflow(format!("device state: {e}"))
}

impl Springs {
    /// The springs of `state`, saved from `world` just before.
    fn of(
        world: &World,
        state: &clump_core::state::WorldState,
        cap: usize,
    ) -> Result<Springs, DeviceError> {
        let gids = device_gids(world);
        let ns = gids.len();
        let at: HashMap<u64, u32> = gids
            .iter()
            .enumerate()
            .map(|(d, &g)| (g, d as u32))
            .collect();
        let find = |g: u64| {
            at.get(&g)
                .copied()
                .ok_or_else(|| bad_state(format!("sphere {g} has a spring but no body")))
        };
        let mut rows: Vec<Vec<(u32, ContactHistory)>> = vec![Vec::new(); ns];
        for &((gi, gj), h) in &state.pair_history {
            let (di, dj) = (find(gi)?, find(gj)?);
            if di < dj {
                rows[di as usize].push((dj, h));
            } else {
                // the springs of the force on the other sphere (carry.rs)
                let flip = ContactHistory {
                    tangential: -h.tangential,
                    rolling: -h.rolling,
                };
                rows[dj as usize].push((di, flip));
            }
        }
        let mut noff = Vec::with_capacity(ns + 1);
        let (mut nbr, mut hist) = (Vec::new(), Vec::new());
        for row in &mut rows {
            row.sort_by_key(|e| e.0);
            noff.push(nbr.len() as u32);
            for &(j, h) in row.iter() {
                nbr.push(j);
                hist.extend(h.tangential.to_array());
                hist.extend(h.rolling.to_array());
            }
        }
        noff.push(nbr.len() as u32);
        if nbr.len() > cap {
            return Err(DeviceError::Overflow(format!(
                "{} pair springs do not fit the device table of {cap} entries",
                nbr.len()
            )));
        }
        let nw = world.walls.len();
        let (base, nwf) = crate::walls::face_bases(&world.walls);
        let mut whist = vec![0.0; HIST * ns * nwf];
        let mut wkey = vec![0u32; ns * nwf];
        let cpu_gid = &world.spheres().gid;
        for (s, (keys, hs)) in state.wall_key.iter().zip(&state.wall_hist).enumerate() {
            // a mesh wall's slots in the order of its keys (mesh.rs)
            let mut mesh_used = HashMap::new();
            for (&key, h) in keys.iter().zip(hs) {
                let (w, mut face) = if key == 0 { (nw, 0) } else { slot_wall(key) };
                if w >= nw {
                    continue;
                }
                if is_mesh(&world.walls[w]) {
                    let used = mesh_used.entry(w).or_insert(0);
                    face = *used;
                    *used += 1;
                }
                if face >= crate::walls::faces(&world.walls[w]) {
                    continue;
                }
                let slot = find(cpu_gid[s])? as usize * nwf + base[w] + face;
                if is_mesh(&world.walls[w]) {
                    wkey[slot] = key;
                }
                let o = HIST * slot;
                whist[o..o + 3].copy_from_slice(&h.tangential.to_array());
                whist[o + 3..o + 6].copy_from_slice(&h.rolling.to_array());
            }
        }
        Ok(Springs {
            noff,
            nbr,
            hist,
            whist,
            wkey,
        })
    }
}

impl DeviceWorld {
    /// Continues `world` on the device: its bodies with the forces of its
    /// last evaluation (the CPU path evaluates them first if it has none)
    /// and its contact springs. The device evaluates nothing at upload, so
    /// its next step is the step the CPU path would take.
    pub fn continue_from(gpu: Gpu, world: &mut World) -> Result<DeviceWorld, DeviceError> {
        let refused = unsupported(world);
        if !refused.is_empty() {
            return Err(DeviceError::Unsupported(refused));
        }
        let kernels = Kernels::new(&gpu)?;
        DeviceWorld::load(gpu, kernels, world)
    }

    /// [`Self::continue_from`] on this device with its compiled kernels
    /// (an event changed the world on the host).
    pub fn reload(self, world: &mut World) -> Result<DeviceWorld, DeviceError> {
        let refused = unsupported(world);
        if !refused.is_empty() {
            return Err(DeviceError::Unsupported(refused));
        }
        let (gpu, kernels) = self.into_parts();
        DeviceWorld::load(gpu, kernels, world)
    }

    fn load(gpu: Gpu, kernels: Kernels, world: &mut World) -> Result<DeviceWorld, DeviceError> {
        let state = world.save_state().map_err(bad_state)?;
        let cap = table_capacity(world);
        let springs = Springs::of(world, &state, cap)?;
        DeviceWorld::bind(gpu, kernels, world, Some(springs))
    }

    /// Copies the device's state into `world` (an event: output,
    /// checkpoint, insertion): every body's pose, velocities, angular
    /// momentum and the forces and torques of the last evaluation, the
    /// pair and wall springs, the step count and time, matched by body and
    /// sphere id. The world's neighbour list is rebuilt around the new
    /// poses. Its contact statistics and wall loads stay those of its own
    /// last evaluation (the runner's step at the event renews them).
    pub fn download_state(&self, world: &mut World) -> Result<(), DeviceError> {
        let mut s = world.save_state().map_err(bad_state)?;
        let read = |b: usize| -> Result<Vec<f64>, DeviceError> { Ok(self.read_f64(b)?) };
        let (x, v, q, l, w, ft) = (read(2)?, read(3)?, read(4)?, read(5)?, read(6)?, read(7)?);
        let at: HashMap<u64, usize> = s
            .bodies
            .id
            .iter()
            .enumerate()
            .map(|(k, &id)| (id, k))
            .collect();
        let b = &mut s.bodies;
        for (i, id) in self.ids.iter().enumerate() {
            let k = *at.get(id).ok_or_else(|| {
                bad_state(format!("body {id} left the world while on the device"))
            })?;
            let d3 = |a: &[f64], n: usize, o: usize| {
                DVec3::new(a[n * i + o], a[n * i + o + 1], a[n * i + o + 2])
            };
            b.position[k] = d3(&x, 3, 0);
            b.velocity[k] = d3(&v, 3, 0);
            b.orientation[k] = DQuat::from_xyzw(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);
            b.angular_momentum[k] = d3(&l, 3, 0);
            b.angular_velocity[k] = d3(&w, 3, 0);
            b.force[k] = d3(&ft, 6, 0);
            b.torque[k] = d3(&ft, 6, 3);
        }
        s.reference_pose = (0..b.len())
            .map(|k| (b.position[k], b.orientation[k]))
            .collect();
        let gids = device_gids(world);
        s.pair_history = self.pair_springs(&gids)?;
        (s.wall_key, s.wall_hist) = self.wall_springs(world, &gids)?;
        s.walls = self.walls.walls.clone();
        s.step = self.step;
        s.time = self.time;
        s.built_step = self.step;
        world.restore_state(s).map_err(bad_state)?;
        self.remove_lost(world)
    }

    /// The springs of the pair table's owning entries that are not zero,
    /// keyed and oriented as in a checkpoint.
    fn pair_springs(&self, gids: &[u64]) -> Result<Vec<((u64, u64), ContactHistory)>, DeviceError> {
        let (noff, nbr, hist) = self.table()?;
        let cap = nbr.len();
        let mut out = Vec::new();
        for i in 0..gids.len() {
            for e in noff[i] as usize..(noff[i + 1] as usize).min(cap) {
                let j = nbr[e] as usize;
                let (t, r) = springs_at(&hist, e);
                if j <= i || (t == DVec3::ZERO && r == DVec3::ZERO) {
                    continue;
                }
                let (gi, gj) = (gids[i], gids[j]);
                let (key, t, r) = if gi < gj {
                    ((gi, gj), t, r)
                } else {
                    ((gj, gi), -t, -r)
                };
                out.push((
                    key,
                    ContactHistory {
                        tangential: t,
                        rolling: r,
                    },
                ));
            }
        }
        out.sort_by_key(|e| e.0);
        Ok(out)
    }

    /// The wall springs that are not zero, per sphere of `world` in its
    /// storage order, in slots by ascending wall.
    #[allow(clippy::type_complexity)]
    fn wall_springs(
        &self,
        world: &World,
        gids: &[u64],
    ) -> Result<(Vec<[u32; WALL_SLOTS]>, Vec<[ContactHistory; WALL_SLOTS]>), DeviceError> {
        let whist = self.read_f64(27)?;
        let wkey = self.mesh_keys()?;
        let (base, nwf) = crate::walls::face_bases(&world.walls);
        let at: HashMap<u64, usize> = gids.iter().enumerate().map(|(d, &g)| (g, d)).collect();
        let cpu_gid = &world.spheres().gid;
        let mut keys = vec![[0u32; WALL_SLOTS]; cpu_gid.len()];
        let mut hists = vec![[ContactHistory::default(); WALL_SLOTS]; cpu_gid.len()];
        for (s, g) in cpu_gid.iter().enumerate() {
            let d = *at
                .get(g)
                .ok_or_else(|| bad_state(format!("sphere {g} is not on the device")))?;
            let mut used = 0;
            for (w, face) in (0..world.walls.len())
                .flat_map(|w| (0..crate::walls::faces(&world.walls[w])).map(move |f| (w, f)))
            {
                let slot = d * nwf + base[w] + face;
                let (t, r) = springs_at(&whist, slot);
                // a mesh slot is kept with its key (the stored normal
                // matters to the next step's match, whatever its springs)
                let key = if is_mesh(&world.walls[w]) {
                    wkey[slot]
                } else if t != DVec3::ZERO || r != DVec3::ZERO {
                    slot_key(w, face)
                } else {
                    0
                };
                if key != 0 && used < WALL_SLOTS {
                    keys[s][used] = key;
                    hists[s][used] = ContactHistory {
                        tangential: t,
                        rolling: r,
                    };
                    used += 1;
                }
            }
        }
        Ok((keys, hists))
    }
}

/// A device that takes the steps between a runner's events: the world is
/// uploaded at the start of each stretch and downloaded at its end (both
/// with the springs), the compiled kernels are kept.
pub struct DeviceStepper {
    parts: Option<DeviceWorld>,
    gpu: Option<Gpu>,
    /// `CLUMP_GPU_TRAFFIC` set: each stretch reports on stderr the bytes
    /// it copied each way (the measurement of docs/testing.md).
    report: bool,
    /// Bytes copied (host to device, device to host) by the stretches so far.
    pub traffic: (u64, u64),
}

impl DeviceStepper {
    /// A stepper on `gpu`; nothing is compiled until the first stretch.
    pub fn new(gpu: Gpu) -> DeviceStepper {
        DeviceStepper {
            parts: None,
            gpu: Some(gpu),
            report: std::env::var_os("CLUMP_GPU_TRAFFIC").is_some(),
            traffic: (0, 0),
        }
    }

    /// Takes `world` from its step to step `to` on the device, checking
    /// `stop` between submissions; returns the steps taken (fewer than
    /// asked when `stop` answered true). `world` holds the device's state
    /// afterwards. While a body is still before its start step (a stream's
    /// ballistic entry), the CPU path takes the steps.
    pub fn advance(
        &mut self,
        world: &mut World,
        to: u64,
        stop: &mut dyn FnMut() -> bool,
    ) -> Result<u64, DeviceError> {
        const SUBMISSIONS: u64 = 256;
        // bodies of a stream move ballistically to their start step (the
        // CPU path's `start_step`), which the device does not do: those
        // steps run on the CPU path
        let first = world.step;
        let late = crate::support::late_start(world);
        if late > world.step {
            let k = late.min(to) - world.step;
            world.run(k).map_err(bad_state)?;
            if world.step >= to || stop() {
                return Ok(world.step - first);
            }
        }
        let before = match (&self.parts, &self.gpu) {
            (Some(d), _) => d.gpu.traffic(),
            (None, Some(g)) => g.traffic(),
            (None, None) => (0, 0),
        };
        let mut dev = match (self.parts.take(), self.gpu.take()) {
            (Some(d), _) => d.reload(world)?,
            (None, Some(g)) => DeviceWorld::continue_from(g, world)?,
            (None, None) => {
                return Err(DeviceError::Overflow(
                    "the device was lost at an earlier error".into(),
                ))
            }
        };
        while dev.step < to {
            dev.run((to - dev.step).min(SUBMISSIONS))?;
            if stop() {
                break;
            }
        }
        dev.download_state(world)?;
        let after = dev.gpu.traffic();
        let (up, down) = (after.0 - before.0, after.1 - before.1);
        self.traffic = (self.traffic.0 + up, self.traffic.1 + down);
        if self.report {
            eprintln!(
                "device stretch to step {}: {up} bytes to the device, {down} bytes back ({} bodies, {} spheres)",
                dev.step,
                dev.ids.len(),
                dev.spheres()
            );
        }
        let done = dev.step - first;
        self.parts = Some(dev);
        Ok(done)
    }
}

/// Entries of the device pair table for `world`.
fn table_capacity(world: &World) -> usize {
    let b = world.bodies();
    (0..b.len())
        .map(|i| world.templates[b.template[i] as usize].spheres.len())
        .sum::<usize>()
        * ENTRIES_PER_SPHERE
}
