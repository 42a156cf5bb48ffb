//! The run's records in the output directory: `manifest.json` (version,
//! threads, status, steps, throughput) and `final_state.json` (every body's
//! state with exact bit patterns).

use super::{RunStatus, RunSummary, Runner, VERSION};
use clump_core::world::World;

impl Runner {
    pub(super) fn write_final_state(&self) -> std::io::Result<()> {
        if self.out.is_detached() {
            return Ok(());
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
        });
        let text = serde_json::to_string_pretty(&m).map_err(std::io::Error::other)?;
        crate::atomic::write_atomic(self.out.dir.join("manifest.json"), text.as_bytes())
    }
}

fn hex3(v: glam::DVec3) -> [String; 3] {
    [
        format!("{:016x}", v.x.to_bits()),
        format!("{:016x}", v.y.to_bits()),
        format!("{:016x}", v.z.to_bits()),
    ]
}

/// Every body's state (sorted by global id) with the exact bit patterns of
/// position, velocity, orientation and angular momentum in hex, as JSON.
pub fn final_state_json(world: &World) -> String {
    let b = &world.bodies();
    let mut idx: Vec<usize> = (0..b.len()).collect();
    idx.sort_by_key(|&i| b.id[i]);
    let bodies: Vec<serde_json::Value> = idx
        .iter()
        .map(|&i| {
            let q = b.orientation[i];
            serde_json::json!({
                "id": b.id[i],
                "template": b.template[i],
                "position": [b.position[i].x, b.position[i].y, b.position[i].z],
                "position_bits": hex3(b.position[i]),
                "velocity_bits": hex3(b.velocity[i]),
                "orientation_bits": [format!("{:016x}", q.w.to_bits()), format!("{:016x}", q.x.to_bits()), format!("{:016x}", q.y.to_bits()), format!("{:016x}", q.z.to_bits())],
                "angular_momentum_bits": hex3(b.angular_momentum[i]),
            })
        })
        .collect();
    let v = serde_json::json!({
        "step": world.step,
        "time_bits": format!("{:016x}", world.time.to_bits()),
        "lost_bodies": world.lost.total(),
        "bodies": bodies,
    });
    serde_json::to_string_pretty(&v).unwrap_or_default()
}
