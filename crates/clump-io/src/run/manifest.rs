//! The run's records in the output directory: `manifest.json` (version,
//! threads, status, steps, throughput) and `final_state.json` (every body's
//! state with exact bit patterns).

use super::{RunStatus, RunSummary, Runner, VERSION};
use clump_core::world::World;

impl Runner {
    pub(super) fn write_final_state(&mut self) -> std::io::Result<()> {
        if self.out.is_detached() {
            return Ok(());
        }
        if self.world.is_split() {
            return match final_state_json_split(&mut self.world)? {
                Some(json) => crate::atomic::write_atomic(
                    self.out.dir.join("final_state.json"),
                    json.as_bytes(),
                ),
                None => Ok(()),
            };
        }
        let json = final_state_json(&self.world);
        crate::atomic::write_atomic(self.out.dir.join("final_state.json"), json.as_bytes())
    }

    pub(super) fn write_manifest(&self, s: &RunSummary, threads: usize) -> std::io::Result<()> {
        let status = match s.status {
            RunStatus::Completed => "completed".to_string(),
            RunStatus::StepLimit => "step_limit".to_string(),
            RunStatus::Interrupted(sig) => format!("interrupted (signal {sig})"),
        };
        self.write_manifest_status(s, threads, &status)
    }

    pub(super) fn write_manifest_status(
        &self,
        s: &RunSummary,
        threads: usize,
        status: &str,
    ) -> std::io::Result<()> {
        if self.out.is_detached() {
            return Ok(());
        }
        let m = serde_json::json!({
            "program": "clump",
            "version": VERSION,
            "scenario": self.scenario.path.display().to_string(),
            "fingerprint": format!("{:016x}", self.scenario.fingerprint()),
            "threads": threads,
            "status": status,
            "dt": self.world.config.dt,
            "first_step": s.first_step,
            "final_step": s.final_step,
            "steps": s.steps(),
            "total_steps": self.scenario.total_steps(),
            "simulated_time": s.time,
            "wall_time_s": s.wall_time,
            "bodies": s.bodies,
            "spheres": s.spheres,
            "lost_bodies": self.world.lost.total(),
            "lost_by_cause": self.world.lost.by_cause().into_iter().map(|(k, n)| (k.to_string(), serde_json::Value::from(n))).collect::<serde_json::Map<_, _>>(),
            "insertions": self.insertions(),
            "templates": self.scenario.templates.iter().map(|t| t.name.as_str()).collect::<Vec<_>>(),
            "sphere_steps": s.sphere_steps,
            "sphere_steps_per_s": s.throughput(),
            "steps_per_s": if s.wall_time > 0.0 { s.steps() as f64 / s.wall_time } else { 0.0 },
            "checkpoint": s.checkpoint.as_ref().map(|p| p.display().to_string()),
            "device": self.device_name(),
            "adapter": self.device.as_ref().map(|d| d.describe()),
            "segments": self.segments(s),
        });
        let text = serde_json::to_string_pretty(&m).map_err(std::io::Error::other)?;
        crate::atomic::write_atomic(self.out.dir.join("manifest.json"), text.as_bytes())
    }
}

impl Runner {
    /// Where the steps between events ran: `cpu`, or `gpu` with a device
    /// ([`super::device::StepDevice`]).
    fn device_name(&self) -> &'static str {
        if self.device.is_some() {
            "gpu"
        } else {
            "cpu"
        }
    }

    /// The run's segments (a fresh run, then one per resume) with the
    /// device and adapter of each: the earlier segments from the folder's
    /// manifest.json (those that start before this one, ending where it
    /// starts at the latest: a resume that went back to an earlier
    /// checkpoint replaces the steps after it), then this.
    fn segments(&self, s: &RunSummary) -> Vec<serde_json::Value> {
        let earlier: Vec<serde_json::Value> =
            std::fs::read_to_string(self.out.dir.join("manifest.json"))
                .ok()
                .and_then(|t| serde_json::from_str::<serde_json::Value>(&t).ok())
                .and_then(|m| m.get("segments").and_then(|v| v.as_array()).cloned())
                .unwrap_or_default();
        let mut out: Vec<serde_json::Value> = earlier
            .into_iter()
            .filter(|g| {
                g.get("first_step")
                    .and_then(|v| v.as_u64())
                    .is_some_and(|f| f < s.first_step)
            })
            .collect();
        for g in &mut out {
            if g["final_step"].as_u64().is_some_and(|f| f > s.first_step) {
                g["final_step"] = s.first_step.into();
            }
        }
        out.push(serde_json::json!({
            "first_step": s.first_step,
            "final_step": s.final_step,
            "device": self.device_name(),
            "adapter": self.device.as_ref().map(|d| d.describe()),
        }));
        out
    }
}

fn hex3(v: glam::DVec3) -> [String; 3] {
    [
        format!("{:016x}", v.x.to_bits()),
        format!("{:016x}", v.y.to_bits()),
        format!("{:016x}", v.z.to_bits()),
    ]
}

/// Body `i`'s entry in `final_state.json`: its object as
/// `serde_json::to_string_pretty` writes it at the depth of the `bodies`
/// array (every line indented by 4 spaces).
fn body_entry(world: &World, i: usize) -> String {
    let b = &world.bodies();
    let q = b.orientation[i];
    let v = serde_json::json!({
        "id": b.id[i],
        "template": b.template[i],
        "position": [b.position[i].x, b.position[i].y, b.position[i].z],
        "position_bits": hex3(b.position[i]),
        "velocity_bits": hex3(b.velocity[i]),
        "orientation_bits": [format!("{:016x}", q.w.to_bits()), format!("{:016x}", q.x.to_bits()), format!("{:016x}", q.y.to_bits()), format!("{:016x}", q.z.to_bits())],
        "angular_momentum_bits": hex3(b.angular_momentum[i]),
    });
    let text = serde_json::to_string_pretty(&v).unwrap_or_default();
    let mut out = String::with_capacity(text.len() + 64);
    for (k, line) in text.lines().enumerate() {
        if k > 0 {
            out.push('\n');
        }
        out.push_str("    ");
        out.push_str(line);
    }
    out
}

/// `final_state.json` of `world`'s counters with the body entries
/// `entries` ([`body_entry`], in the order of their ids): the bytes of
/// `serde_json::to_string_pretty` of the whole document (keys sorted),
/// without building it in memory.
fn final_state_document<'a>(world: &World, entries: impl Iterator<Item = &'a str>) -> String {
    let mut out = String::from("{\n  \"bodies\": [");
    let mut any = false;
    for e in entries {
        out.push_str(if any { ",\n" } else { "\n" });
        out.push_str(e);
        any = true;
    }
    out.push_str(if any { "\n  ],\n" } else { "],\n" });
    let _ = std::fmt::Write::write_fmt(
        &mut out,
        format_args!(
            "  \"lost_bodies\": {},\n  \"step\": {},\n  \"time_bits\": \"{:016x}\"\n}}",
            world.lost.total(),
            world.step,
            world.time.to_bits()
        ),
    );
    out
}

/// Every body's state (sorted by global id) with the exact bit patterns of
/// position, velocity, orientation and angular momentum in hex, as JSON.
pub fn final_state_json(world: &World) -> String {
    let b = &world.bodies();
    let mut idx: Vec<usize> = (0..b.len()).collect();
    idx.sort_by_key(|&i| b.id[i]);
    let entries: Vec<String> = idx.iter().map(|&i| body_entry(world, i)).collect();
    final_state_document(world, entries.iter().map(String::as_str))
}

/// `final_state.json` of a world split over ranks, on rank 0 (a
/// collective call; `None` on the other ranks): each rank's owned bodies'
/// entries are sent to rank 0 only, which orders them by id. The bytes of
/// [`final_state_json`] of the whole world, without gathering it.
pub(super) fn final_state_json_split(world: &mut World) -> std::io::Result<Option<String>> {
    let mask = world.piece_mask().unwrap_or_default();
    let b = world.bodies();
    let mine: Vec<(u64, String)> = (0..b.len())
        .filter(|&i| mask.get(i).copied().unwrap_or(true))
        .map(|i| (b.id[i], body_entry(world, i)))
        .collect();
    let bytes = postcard::to_stdvec(&mine).unwrap_or_default();
    drop(mine);
    let Some(all) = world.gather_to_root(bytes) else {
        return Ok(None);
    };
    let mut entries: Vec<(u64, String)> = Vec::new();
    for (r, part) in all.iter().enumerate() {
        let got = postcard::from_bytes::<Vec<(u64, String)>>(part).map_err(|e| {
            std::io::Error::other(format!("the bodies of rank {r} are unreadable: {e}"))
        })?;
        entries.extend(got);
    }
    drop(all);
    entries.sort_unstable_by_key(|e| e.0);
    let doc = final_state_document(world, entries.iter().map(|e| e.1.as_str()));
    Ok(Some(doc))
}

/// The bodies and spheres of the whole world: this world's, or summed
/// over the ranks' owned ones when it is split (a collective call then).
pub(super) fn whole_counts(world: &mut World) -> (usize, usize) {
    if !world.is_split() {
        return (world.bodies().len(), world.spheres().len());
    }
    let mask = world.piece_mask().unwrap_or_default();
    let b = world.bodies();
    let t = &world.templates;
    let (mut bodies, mut spheres) = (0u64, 0u64);
    for i in (0..b.len()).filter(|&i| mask[i]) {
        let k = b.template[i] as usize;
        bodies += 1;
        spheres += t[k].spheres.len() as u64;
    }
    let mine = [bodies.to_le_bytes(), spheres.to_le_bytes()].concat();
    let all = world.gather_from_ranks(&mine);
    let sum = |k: usize| -> u64 {
        all.iter()
            .map(|m| u64::from_le_bytes(m[8 * k..8 * k + 8].try_into().unwrap_or_default()))
            .sum()
    };
    (sum(0) as usize, sum(1) as usize)
}
