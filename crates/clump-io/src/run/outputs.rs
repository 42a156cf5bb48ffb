//! The output files of a run: VTK series, thermo.csv with the wall columns,
//! trajectories; opened fresh or resumed, and written at their intervals.

use super::error::rt;
use super::outdir;
use super::{RunError, Runner};
use crate::scenario::Scenario;
use crate::thermo_csv::{ThermoWriter, WallColumns};
use crate::trajectory::TrajectoryWriter;
use crate::vtk::VtkSeries;
use crate::vtk_contacts::ContactSeries;
use clump_core::thermo::Thermo;
use clump_core::world::World;
use glam::DVec3;
use std::path::{Path, PathBuf};

/// The thermo columns of every wall: a power column for the walls that move
/// at the start or are set moving by a stage.
pub(super) fn wall_columns(scenario: &Scenario) -> Vec<WallColumns> {
    let moving = |v: DVec3| v != DVec3::ZERO;
    scenario
        .walls
        .iter()
        .enumerate()
        .map(|(i, w)| {
            let staged = scenario.stages.iter().flat_map(|s| &s.walls).any(|c| {
                c.wall == i
                    && (c.velocity.is_some_and(moving) || c.angular_velocity.is_some_and(moving))
            });
            WallColumns {
                name: w.name.clone(),
                power: staged || moving(w.motion.velocity) || moving(w.motion.angular_velocity),
            }
        })
        .collect()
}

/// The walls' names, by index.
fn wall_names(scenario: &Scenario) -> Vec<String> {
    scenario.walls.iter().map(|w| w.name.clone()).collect()
}

/// The world's thermo row with each wall's torque taken about its torque
/// point (`T_P = T_c + (c − P) × F`, world frame), and the power each wall's
/// rigid motion delivers to the particles, `−(F·v + T_c·ω)` (W).
pub(super) fn wall_thermo(world: &World, torque_points: &[Option<DVec3>]) -> (Thermo, Vec<f64>) {
    with_wall_columns(world, world.thermo(), torque_points)
}

/// The thermo row `t` of `world` with each wall's torque taken about its
/// torque point, and each wall's power.
pub(super) fn with_wall_columns(
    world: &World,
    mut t: Thermo,
    torque_points: &[Option<DVec3>],
) -> (Thermo, Vec<f64>) {
    let mut power = Vec::with_capacity(t.wall_loads.len());
    for (i, (l, w)) in t.wall_loads.iter_mut().zip(&world.walls).enumerate() {
        let m = &w.motion;
        power.push(-(l.force.dot(m.velocity) + l.torque.dot(m.angular_velocity)));
        if let Some(p) = torque_points.get(i).copied().flatten() {
            l.torque += (m.center - p).cross(l.force);
        }
    }
    (t, power)
}

/// The open output files of a run.
pub(super) struct Outputs {
    pub(super) dir: PathBuf,
    pub(super) vtk: Option<VtkSeries>,
    pub(super) contacts: Option<ContactSeries>,
    pub(super) fields: Option<crate::post::spec::FieldSeries>,
    pub(super) flow: Option<crate::append::AppendLog>,
    pub(super) thermo: Option<ThermoWriter>,
    pub(super) trajectory: Option<TrajectoryWriter>,
    pub(super) last_checkpoint: Option<PathBuf>,
    /// The run's id (see [`super::outdir`]).
    pub(super) run_id: String,
    /// The folder lock, held while the run lives; `None` for a run
    /// without an output folder ([`Outputs::detached`]).
    pub(super) lock: Option<outdir::FolderLock>,
}

/// Whether a run starts fresh or resumes from a checkpoint.
#[derive(Clone, Copy)]
pub(super) enum Start<'a> {
    /// A new run: new output files (`overwrite`: another run's files in
    /// the folder are deleted first, else they are an error).
    Fresh { overwrite: bool },
    /// A run resumed from `checkpoint`, whose world is at `step` and `time`
    /// (s): the existing output files are continued from that point.
    Resume {
        checkpoint: &'a Path,
        step: u64,
        time: f64,
        /// The run id the checkpoint carries (absent in older ones).
        run_id: Option<&'a str>,
        /// What the caller allows (rewinding, the folder).
        opts: super::ResumeOptions,
    },
}

impl Outputs {
    /// Creates `outdir` with a copy of the scenario and opens the outputs
    /// the scenario asks for, new or continued as `start` says.
    pub(super) fn open(
        scenario: &Scenario,
        outdir: &Path,
        start: Start,
    ) -> Result<Outputs, RunError> {
        let (lock, run_id) = match start {
            Start::Fresh { overwrite } => outdir::prepare_fresh(outdir, overwrite, &scenario.path)?,
            Start::Resume {
                checkpoint,
                run_id,
                step,
                opts,
                ..
            } => outdir::prepare_resume(outdir, run_id, checkpoint, step, opts)?,
        };
        crate::atomic::write_atomic(outdir.join("scenario.toml"), scenario.text.as_bytes())
            .map_err(rt("cannot copy the scenario"))?;
        let o = &scenario.output;
        let wall_columns = wall_columns(scenario);
        Ok(Outputs {
            dir: outdir.to_path_buf(),
            vtk: match (o.vtk, start) {
                (None, _) => None,
                (Some(_), Start::Fresh { .. }) => Some(
                    VtkSeries::new(outdir)
                        .map_err(rt("cannot start VTK output"))?
                        .with_format(o.vtk_format),
                ),
                (Some(_), Start::Resume { time, .. }) => Some(
                    VtkSeries::resume(outdir, time)
                        .map_err(rt("cannot resume VTK output"))?
                        .with_format(o.vtk_format),
                ),
            },
            contacts: match (o.contacts, start) {
                (None, _) => None,
                (Some(_), Start::Fresh { .. }) => Some(
                    ContactSeries::new(outdir, wall_names(scenario), &scenario.config.domain)
                        .map_err(rt("cannot start contact output"))?,
                ),
                (Some(_), Start::Resume { time, .. }) => Some(
                    ContactSeries::resume(outdir, wall_names(scenario), time)
                        .map_err(rt("cannot resume contact output"))?,
                ),
            },
            fields: o
                .fields
                .as_ref()
                .map(|(_, spec)| crate::post::spec::FieldSeries::new(outdir, spec.clone())),
            flow: match &o.flow {
                None => None,
                Some((_, probes)) => Some(
                    crate::post::flow::open_csv(
                        &outdir.join("flow.csv"),
                        &crate::post::flow::header(probes),
                        match start {
                            Start::Fresh { .. } => None,
                            Start::Resume { step, .. } => Some(step),
                        },
                    )
                    .map_err(rt("cannot open flow.csv"))?,
                ),
            },
            thermo: match (o.thermo, start) {
                (None, _) => None,
                (Some(_), Start::Fresh { .. }) => Some(
                    ThermoWriter::create_columns(
                        outdir.join("thermo.csv"),
                        &wall_columns,
                        scenario.heat.is_some(),
                        scenario.fluid.is_some(),
                    )
                    .map_err(rt("cannot create thermo.csv"))?,
                ),
                (Some(_), Start::Resume { step, .. }) => Some(
                    ThermoWriter::resume_columns(
                        outdir.join("thermo.csv"),
                        &wall_columns,
                        step,
                        scenario.heat.is_some(),
                        scenario.fluid.is_some(),
                    )
                    .map_err(rt("cannot resume thermo.csv"))?,
                ),
            },
            trajectory: match (&o.trajectory, start) {
                (Some(t), Start::Fresh { .. }) if !t.bodies.is_empty() => Some(
                    TrajectoryWriter::create_with(outdir, &t.bodies, t.extras)
                        .map_err(rt("cannot create trajectory files"))?,
                ),
                (Some(t), Start::Resume { time, .. }) if !t.bodies.is_empty() => Some(
                    TrajectoryWriter::resume_with(outdir, &t.bodies, time, t.extras)
                        .map_err(rt("cannot resume trajectory files"))?,
                ),
                _ => None,
            },
            last_checkpoint: match start {
                Start::Fresh { .. } => None,
                Start::Resume { checkpoint, .. } => Some(checkpoint.to_path_buf()),
            },
            run_id,
            lock: Some(lock),
        })
    }
}

impl Outputs {
    /// No output folder: nothing is written at boundaries (a session driven
    /// from Python or another program that reads the world itself).
    pub(super) fn detached() -> Outputs {
        Outputs {
            dir: PathBuf::new(),
            vtk: None,
            thermo: None,
            trajectory: None,
            contacts: None,
            fields: None,
            flow: None,
            last_checkpoint: None,
            run_id: String::new(),
            lock: None,
        }
    }

    /// True without an output folder.
    pub(super) fn is_detached(&self) -> bool {
        self.lock.is_none()
    }
}

impl Runner {
    pub(super) fn write_outputs(&mut self, finished: bool) -> Result<(), RunError> {
        let step = self.world.step;
        let o = self.scenario.output.clone();
        // a frame without bodies has nothing to show (and VTK series start
        // at their first frame with bodies)
        let captured = self.snap.take();
        let snap = captured.as_ref().filter(|f| !f.bodies.is_empty());
        // a contact frame (only where the step recorded its contacts) comes
        // with a bodies frame at the same step, for `clump post`
        let mut contact_frame = false;
        let contacts_in_pieces = self.contacts_in_pieces();
        if let (Some(every), Some(cs)) = (o.contacts, self.out.contacts.as_mut()) {
            let due =
                step >= self.st.next_contacts || (finished && self.st.last_contacts != Some(step));
            // on ranks every rank takes part, also one without bodies
            let frame = if contacts_in_pieces {
                captured.as_ref()
            } else {
                snap
            };
            if let (true, Some(frame)) = (due, frame) {
                let written = if contacts_in_pieces {
                    super::contact_ranks::write_contacts_in_pieces(&mut self.world, cs, frame)?
                } else {
                    cs.write_frame(frame)
                        .map_err(rt("cannot write contact output"))?;
                    true
                };
                if written {
                    self.st.last_contacts = Some(step);
                    self.st.next_contacts = step + every;
                    contact_frame = true;
                }
            }
        }
        let fields_in_pieces = self.fields_in_pieces();
        if let (Some((every, _)), Some(fs)) = (&o.fields, self.out.fields.as_mut()) {
            let due =
                step >= self.st.next_fields || (finished && self.st.last_fields != Some(step));
            // on ranks every rank takes part, also one without bodies
            let frame = if fields_in_pieces {
                captured.as_ref()
            } else {
                snap
            };
            if let (true, Some(frame)) = (due, frame) {
                let written = if fields_in_pieces {
                    super::fields_ranks::write_fields_in_pieces(&mut self.world, fs, frame)?
                } else {
                    fs.add(frame)
                        .map_err(rt("cannot write the coarse-grained fields"))?;
                    true
                };
                if written {
                    self.st.last_fields = Some(step);
                    self.st.next_fields = step + *every;
                }
            }
        }
        if let (Some((every, probes)), Some(log)) = (&o.flow, self.out.flow.as_mut()) {
            if step >= self.st.next_flow {
                let frame = crate::post::frame::Frame::bodies_only(&self.world);
                let row = crate::post::flow::sample(probes, &mut self.st.flow, &frame);
                log.append(format!("{row}\n").as_bytes())
                    .map_err(rt("cannot write flow.csv"))?;
                self.st.next_flow = step + every;
            }
        }
        let vtk_in_pieces = self.vtk_in_pieces();
        if let (Some(every), Some(vtk)) = (o.vtk, self.out.vtk.as_mut()) {
            if step >= self.st.next_vtk
                || contact_frame
                || (finished && self.st.last_vtk != Some(step))
            {
                let counts: Option<crate::vtk::BodyCounts> = snap.and_then(|f| {
                    let n = crate::post::network::body_counts(f)?;
                    Some(f.bodies.iter().map(|b| b.id).zip(n).collect())
                });
                if vtk_in_pieces {
                    super::vtk_ranks::write_frame_in_pieces(
                        &mut self.world,
                        vtk,
                        step,
                        counts.as_ref(),
                    )?;
                } else {
                    vtk.write_frame_counted(&self.world, step, counts.as_ref())
                        .map_err(rt("cannot write VTK output"))?;
                }
                self.st.last_vtk = Some(step);
                if step >= self.st.next_vtk {
                    self.st.next_vtk = step + every;
                }
            }
        }
        if let (Some(every), Some(th)) = (o.thermo, self.out.thermo.as_mut()) {
            if step >= self.st.next_thermo || (finished && self.st.last_thermo != Some(step)) {
                // a split world's row from exact sums over the ranks
                let t = self
                    .world
                    .thermo_of_ranks()
                    .map_err(|e| RunError::Runtime(format!("step {step}: {e}")))?;
                let (thermo, power) =
                    with_wall_columns(&self.world, t, &self.scenario.torque_points);
                th.write_row(&thermo, &power)
                    .map_err(rt("cannot write thermo.csv"))?;
                self.st.last_thermo = Some(step);
                self.st.next_thermo = step + every;
            }
        }
        if let (Some(t), Some(tw)) = (&o.trajectory, self.out.trajectory.as_mut()) {
            if step >= self.st.next_trajectory {
                super::traj_ranks::write_rows(&mut self.world, tw)?;
                self.st.next_trajectory = step + t.every;
            }
        }
        Ok(())
    }
}
