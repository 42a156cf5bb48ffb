//! A world on the device: its bodies, spheres, pair table and walls in
//! storage buffers (SoA, ARCHITECTURE.md "The device path"), the step as a
//! sequence of compute dispatches, and the copies in and out at events.

use crate::context::{Gpu, GpuError};
use crate::support::unsupported;
use clump_core::world::World;
use glam::{DQuat, DVec3};

/// The kernels, one WGSL module.
const SHADER: [&str; 12] = [
    include_str!("shaders/common.wgsl"),
    include_str!("shaders/periodic.wgsl"),
    include_str!("shaders/rotation.wgsl"),
    include_str!("shaders/body.wgsl"),
    include_str!("shaders/pairs.wgsl"),
    include_str!("shaders/rolling.wgsl"),
    include_str!("shaders/contact.wgsl"),
    include_str!("shaders/walls.wgsl"),
    include_str!("shaders/mesh.wgsl"),
    include_str!("shaders/average.wgsl"),
    include_str!("shaders/lost.wgsl"),
    include_str!("shaders/scatter.wgsl"),
];
/// Storage bindings of the module (common.wgsl).
const N_BINDINGS: u32 = 31;
/// f64s per contact's springs: tangential (3), then rolling (3)
/// (common.wgsl `ld_hist`, `ld_roll`).
pub(crate) const HIST: usize = 6;
/// f64s per material pair in `laws` (contact.wgsl LAW_ROW).
const LAW_ROW: usize = 11;
/// Pair-table entries reserved per sphere (each pair twice, one entry per side).
pub(crate) const ENTRIES_PER_SPHERE: usize = 16;
/// Index of the integer parameter holding the overflow bits (common.wgsl PU_OVERFLOW).
const PU_OVERFLOW: usize = 11;
/// Index of the count of table builds (common.wgsl PU_BUILDS).
const PU_BUILDS: usize = 14;
/// Most neighbours of one sphere (common.wgsl MAXN).
const MAXN: usize = 32;

/// The kernels in step order (ARCHITECTURE.md lists what each does).
const K_FIRST_HALF: usize = 0;
const K_SPHERES: usize = 1;
const K_SORT_RESET: usize = 2;
const K_SORT_NEXT: usize = 3;
const K_SORT_STEP: usize = 4;
const K_CELLS_CLEAR: usize = 5;
const K_CELLS_BOUNDS: usize = 6;
const K_PAIRS_COUNT: usize = 7;
const K_PAIRS_SCAN: usize = 8;
const K_PAIRS_FILL: usize = 9;
const K_PAIRS_MIRROR: usize = 10;
const K_PAIR_FORCES: usize = 11;
const K_SPHERE_GATHER: usize = 12;
const K_BODY_GATHER: usize = 13;
const K_GATHER_KICK: usize = 14;
const K_REBUILD_ARGS: usize = 15;
const K_TABLE_SAVE: usize = 16;
const K_WALL_STEP: usize = 17;
const K_PAIR_TOUCH: usize = 18;
const K_MARK_LOST: usize = 19;
const K_WHIST_SCATTER: usize = 20;
const ENTRIES: [&str; 21] = [
    "first_half",
    "spheres",
    "sort_reset",
    "sort_next",
    "sort_step",
    "cells_clear",
    "cells_bounds",
    "pairs_count",
    "pairs_scan",
    "pairs_fill",
    "pairs_mirror",
    "pair_forces",
    "sphere_gather",
    "body_gather",
    "gather_kick",
    "rebuild_args",
    "table_save",
    "wall_step",
    "pair_touch",
    "mark_lost",
    "whist_scatter",
];
/// Index of the walls' row set of this step (common.wgsl PU_WSTEP).
const PU_WSTEP: usize = 15;
/// Index of the "a body was marked lost" flag (lost.wgsl PU_LOST), after
/// average.wgsl's PU_AVERAGE.
pub(crate) const PU_LOST: usize = crate::average::PU_AVERAGE + 1;
/// Steps per submission of [`DeviceWorld::run`] (row sets of moving walls: one more).
const BATCH: u64 = 64;
/// The indirect dispatch sizes `rebuild_args` writes (pairs.wgsl): one
/// group per 64 sort slots, cells, spheres, table entries; or one group.
const A_SLOTS: u64 = 0;
const A_CELLS: u64 = 1;
const A_SPHERES: u64 = 2;
const A_ONE: u64 = 3;
const A_ENTRIES: u64 = 4;

/// Why a world cannot run on, or a step failed on, the device.
#[derive(Debug)]
pub enum DeviceError {
    Gpu(GpuError),
    /// Features the device path does not have yet, by scenario key.
    Unsupported(Vec<crate::support::Unsupported>),
    /// The pair table or a sphere's neighbour list ran full.
    Overflow(String),
    /// The box cannot be binned (a periodic axis shorter than three cells).
    Grid(String),
}

impl std::fmt::Display for DeviceError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DeviceError::Gpu(e) => write!(f, "{e}"),
            DeviceError::Unsupported(list) => {
                let lines: Vec<String> = list.iter().map(|u| u.to_string()).collect();
                write!(
                    f,
                    "the GPU path cannot run this scenario:\n  {}",
                    lines.join("\n  ")
                )
            }
            DeviceError::Overflow(e) | DeviceError::Grid(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for DeviceError {}

impl From<GpuError> for DeviceError {
    fn from(e: GpuError) -> Self {
        DeviceError::Gpu(e)
    }
}

/// Sizes of the device arrays.
#[derive(Debug, Clone, Copy)]
struct Sizes {
    nb: usize,
    ns: usize,
    npow2: usize,
    cells: usize,
    cap: usize,
    /// Wall contact slots per sphere.
    nwf: usize,
}

/// A world's state on the device and the step's pipelines.
pub struct DeviceWorld {
    pub gpu: Gpu,
    n: Sizes,
    /// Buffers by binding of group 0.
    buffers: Vec<wgpu::Buffer>,
    /// Group 0, every kernel's arrays.
    group: wgpu::BindGroup,
    /// Group 1 of `rebuild_args`: the indirect dispatch sizes of the
    /// table build, which the build's dispatches read as their sizes.
    args_group: wgpu::BindGroup,
    args: wgpu::Buffer,
    kernels: Kernels,
    /// Global id of each body, in device order (ascending id, see [`by_id`]).
    pub ids: Vec<u64>,
    /// Steps taken (the world's count at upload plus the device's).
    pub step: u64,
    /// Simulated time, s.
    pub time: f64,
    /// Pair-table builds so far (a sphere left half the skin), as of the
    /// last batch.
    pub builds: u64,
    dt: f64,
    /// The walls at `step` (the host advances them, walls.rs).
    pub(crate) walls: crate::walls::WallTable,
    /// `simulation.multi_contact = "average"`: the pairs' touches are
    /// counted before their forces (average.wgsl).
    average: bool,
}

/// The step's compiled kernels and their layouts: made once per device,
/// kept across uploads (a re-upload at an event binds new buffers only).
pub(crate) struct Kernels {
    layout: wgpu::BindGroupLayout,
    args_layout: wgpu::BindGroupLayout,
    pipelines: Vec<wgpu::ComputePipeline>,
}

impl Kernels {
    /// Compiles the module and makes one pipeline per entry point.
    pub(crate) fn new(gpu: &Gpu) -> Result<Kernels, DeviceError> {
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let layout = gpu
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("clump step"),
                entries: &(0..N_BINDINGS)
                    .map(crate::context::storage_entry)
                    .collect::<Vec<_>>(),
            });
        let args_layout = gpu
            .device
            .create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
                label: Some("clump build sizes"),
                entries: &[crate::context::storage_entry(0)],
            });
        let pl = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("clump step"),
                bind_group_layouts: &[Some(&layout)],
                immediate_size: 0,
            });
        let pl_args = gpu
            .device
            .create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some("clump build sizes"),
                bind_group_layouts: &[Some(&layout), Some(&args_layout)],
                immediate_size: 0,
            });
        let module = gpu
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("clump step"),
                source: wgpu::ShaderSource::Wgsl(SHADER.concat().into()),
            });
        let pipelines = ENTRIES
            .iter()
            .map(|e| {
                gpu.device
                    .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                        label: Some(e),
                        layout: Some(if *e == "rebuild_args" { &pl_args } else { &pl }),
                        module: &module,
                        entry_point: Some(e),
                        compilation_options: Default::default(),
                        cache: None,
                    })
            })
            .collect();
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Device(format!("compiling the device step: {e}")).into());
        }
        Ok(Kernels {
            layout,
            args_layout,
            pipelines,
        })
    }
}

fn flat3(v: &[DVec3]) -> Vec<f64> {
    v.iter().flat_map(|a| [a.x, a.y, a.z]).collect()
}

impl DeviceWorld {
    /// Copies `world` to the device (bodies, spheres from the templates,
    /// walls, the contact laws) and computes the forces of its state, as
    /// `World::prepare` does. Tangential springs start at zero.
    pub fn upload(gpu: Gpu, world: &World) -> Result<DeviceWorld, DeviceError> {
        let refused = unsupported(world);
        if !refused.is_empty() {
            return Err(DeviceError::Unsupported(refused));
        }
        let kernels = Kernels::new(&gpu)?;
        let mut dw = DeviceWorld::bind(gpu, kernels, world, None)?;
        dw.submit(0, true)?;
        Ok(dw)
    }

    /// The buffers of `world` bound to `kernels`; with `springs`, the
    /// world's contact springs in the pair table and the wall slots (its
    /// forces then come from the world, not from the device).
    pub(crate) fn bind(
        gpu: Gpu,
        kernels: Kernels,
        world: &World,
        springs: Option<Springs>,
    ) -> Result<DeviceWorld, DeviceError> {
        let (host, n) = HostArrays::new(world)?;
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let (buffers, sparse) = host.buffers(&gpu, n, springs);
        let entries: Vec<wgpu::BindGroupEntry> = (0..N_BINDINGS as usize)
            .map(|b| wgpu::BindGroupEntry {
                binding: b as u32,
                resource: buffers[b].as_entire_binding(),
            })
            .collect();
        let group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &kernels.layout,
            entries: &entries,
        });
        let args = gpu.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("build sizes"),
            size: 15 * 4,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDIRECT,
            mapped_at_creation: false,
        });
        let args_group = gpu.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &kernels.args_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: args.as_entire_binding(),
            }],
        });
        crate::walls::scatter(&gpu, &kernels.pipelines[K_WHIST_SCATTER], &group, sparse);
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Device(format!("setting up the device step: {e}")).into());
        }
        Ok(DeviceWorld {
            gpu,
            kernels,
            n,
            buffers,
            group,
            args_group,
            args,
            ids: by_id(world).id,
            step: world.step,
            time: world.time,
            builds: 0,
            dt: world.config.dt,
            walls: crate::walls::WallTable::new(&world.walls, world.config.dt),
            average: crate::average::pairs_average(world),
        })
    }

    /// The device and the compiled kernels, for the next upload.
    pub(crate) fn into_parts(self) -> (Gpu, Kernels) {
        (self.gpu, self.kernels)
    }

    /// Takes `steps` steps on the device, in batches of one submission
    /// each; the host reads back only the overflow flags between batches.
    pub fn run(&mut self, steps: u64) -> Result<(), DeviceError> {
        let mut left = steps;
        while left > 0 {
            let k = left.min(BATCH);
            self.submit(k, false)?;
            left -= k;
        }
        Ok(())
    }

    /// One submission: with `prepare`, the forces of the current state;
    /// then `steps` whole steps. Checks the overflow flags after it.
    fn submit(&mut self, steps: u64, prepare: bool) -> Result<(), DeviceError> {
        if self.walls.moving {
            // the walls of each step of this submission, from row set 0
            let rows = self.walls.advance(steps);
            self.gpu.write(&self.buffers[26], &rows);
            self.gpu
                .write_at(&self.buffers[1], (PU_WSTEP * 4) as u64, &[0u32]);
        }
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        if prepare {
            self.encode_positions(&mut enc, false);
            self.encode_forces(&mut enc, K_BODY_GATHER);
        }
        for _ in 0..steps {
            self.encode_positions(&mut enc, true);
            self.encode_forces(&mut enc, K_GATHER_KICK);
        }
        self.gpu.queue.submit(Some(enc.finish()));
        for _ in 0..steps {
            self.step += 1;
            self.time += self.dt;
        }
        let pu: Vec<u32> = self.gpu.read(&self.buffers[1])?;
        self.builds = pu[PU_BUILDS] as u64;
        match pu[PU_OVERFLOW] {
            0 => Ok(()),
            bits => Err(DeviceError::Overflow(format!(
                "device pair table full by step {} (flags {bits}: 1 = a sphere touches more than {MAXN} others, \
                 2 = more than {} contact entries in all)",
                self.step, self.n.cap
            ))),
        }
    }

    fn dispatch(&self, pass: &mut wgpu::ComputePass<'_>, k: usize, n: usize) {
        pass.set_pipeline(&self.kernels.pipelines[k]);
        pass.set_bind_group(0, &self.group, &[]);
        pass.dispatch_workgroups(n.div_ceil(64).max(1) as u32, 1, 1);
    }

    /// A kernel of the table build, its size from `rebuild_args` (zero
    /// groups while the table is good).
    fn dispatch_build(&self, pass: &mut wgpu::ComputePass<'_>, k: usize, size: u64) {
        pass.set_pipeline(&self.kernels.pipelines[k]);
        pass.set_bind_group(0, &self.group, &[]);
        pass.dispatch_workgroups_indirect(&self.args, 12 * size);
    }

    /// Stages 1-2 of the step (with `first_half`) or the positions of the
    /// current state: the first half per body, the sphere centres with
    /// the skin check, and the sizes of this step's table build. A pass of
    /// its own: the build's dispatches read those sizes.
    fn encode_positions(&self, enc: &mut wgpu::CommandEncoder, first_half: bool) {
        let n = self.n;
        let mut pass = enc.begin_compute_pass(&Default::default());
        if first_half {
            self.dispatch(&mut pass, K_FIRST_HALF, n.nb);
            if self.walls.moving {
                self.dispatch(&mut pass, K_WALL_STEP, 1);
            }
        }
        self.dispatch(&mut pass, K_SPHERES, n.npow2);
        pass.set_pipeline(&self.kernels.pipelines[K_REBUILD_ARGS]);
        pass.set_bind_group(0, &self.group, &[]);
        pass.set_bind_group(1, &self.args_group, &[]);
        pass.dispatch_workgroups(1, 1, 1);
    }

    /// Stages 3-5 on the device: the table build when a sphere left half
    /// the skin (bitonic sort, cell ranges, the table with its carried
    /// springs), the pair forces, the gather per sphere, and `last` (the
    /// body gather, with or without the final kick).
    fn encode_forces(&self, enc: &mut wgpu::CommandEncoder, last: usize) {
        let n = self.n;
        let mut pass = enc.begin_compute_pass(&Default::default());
        // bodies beyond a non-periodic side leave at a build (lost.wgsl)
        self.dispatch_build(&mut pass, K_MARK_LOST, A_SPHERES);
        self.dispatch_build(&mut pass, K_SORT_RESET, A_ONE);
        let p = n.npow2.trailing_zeros() as usize;
        for _ in 0..p * (p + 1) / 2 {
            self.dispatch_build(&mut pass, K_SORT_NEXT, A_ONE);
            self.dispatch_build(&mut pass, K_SORT_STEP, A_SLOTS);
        }
        self.dispatch_build(&mut pass, K_CELLS_CLEAR, A_CELLS);
        self.dispatch_build(&mut pass, K_CELLS_BOUNDS, A_SPHERES);
        self.dispatch_build(&mut pass, K_TABLE_SAVE, A_ENTRIES);
        self.dispatch_build(&mut pass, K_PAIRS_COUNT, A_SPHERES);
        // one workgroup of 256
        self.dispatch_build(&mut pass, K_PAIRS_SCAN, A_ONE);
        self.dispatch_build(&mut pass, K_PAIRS_FILL, A_SPHERES);
        self.dispatch_build(&mut pass, K_PAIRS_MIRROR, A_SPHERES);
        if self.average {
            self.dispatch(&mut pass, K_PAIR_TOUCH, n.ns);
        }
        self.dispatch(&mut pass, K_PAIR_FORCES, n.ns);
        self.dispatch(&mut pass, K_SPHERE_GATHER, n.ns);
        self.dispatch(&mut pass, last, n.nb);
    }

    /// Body centres of mass, world frame, m (storage order of the world
    /// uploaded).
    pub fn positions(&self) -> Result<Vec<DVec3>, DeviceError> {
        let x: Vec<f64> = self.gpu.read(&self.buffers[2])?;
        Ok(x.chunks(3)
            .take(self.n.nb)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect())
    }

    /// Copies the bodies' state back into `world` (an event: output,
    /// checkpoint, steering): positions, orientations, velocities, angular
    /// momenta and velocities, the step count and time, matched by body id.
    pub fn download(&self, world: &mut World) -> Result<(), DeviceError> {
        let at: std::collections::HashMap<u64, usize> = world
            .bodies()
            .id
            .iter()
            .enumerate()
            .map(|(k, &id)| (id, k))
            .collect();
        let read =
            |b: usize| -> Result<Vec<f64>, DeviceError> { Ok(self.gpu.read(&self.buffers[b])?) };
        let (x, v, q, l, w) = (read(2)?, read(3)?, read(4)?, read(5)?, read(6)?);
        let bad =
            |e: clump_core::world::WorldError| DeviceError::Overflow(format!("device state: {e}"));
        for i in 0..self.n.nb {
            let k = *at.get(&self.ids[i]).ok_or_else(|| {
                DeviceError::Overflow(format!(
                    "body {} left the world while on the device",
                    self.ids[i]
                ))
            })?;
            let d3 = |a: &[f64]| DVec3::new(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
            let quat = DQuat::from_xyzw(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);
            world.set_body_pose_at(k, d3(&x), quat).map_err(bad)?;
            world.set_body_velocity_at(k, d3(&v)).map_err(bad)?;
            world
                .set_body_angular_state_at(k, d3(&w), d3(&l))
                .map_err(bad)?;
        }
        world.walls.clone_from_slice(&self.walls.walls);
        world.step = self.step;
        world.time = self.time;
        self.remove_lost(world)
    }

    /// The f64 array at `binding` (common.wgsl), whole.
    pub(crate) fn read_f64(&self, binding: usize) -> Result<Vec<f64>, GpuError> {
        self.gpu.read(&self.buffers[binding])
    }

    /// The u32 array at `binding` (common.wgsl), whole.
    pub(crate) fn read_u32(&self, binding: usize) -> Result<Vec<u32>, GpuError> {
        self.gpu.read(&self.buffers[binding])
    }

    /// The current pair table: offsets per sphere, neighbour and spring
    /// per entry, the entries in use only (the offsets say how many).
    pub(crate) fn table(&self) -> Result<(Vec<u32>, Vec<u32>, Vec<f64>), GpuError> {
        let noff: Vec<u32> = self.gpu.read(&self.buffers[17])?;
        let used = (noff[self.n.ns] as usize).min(self.n.cap);
        let nbr = self.gpu.read_prefix(&self.buffers[18], used)?;
        let hist = self.gpu.read_prefix(&self.buffers[19], HIST * used)?;
        Ok((noff, nbr, hist))
    }

    /// The mesh wall slots' keys (mesh.rs), one per (sphere, wall slot).
    pub(crate) fn mesh_keys(&self) -> Result<Vec<u32>, GpuError> {
        let u = self.gpu.read(&self.buffers[30])?;
        Ok(crate::mesh::keys_of(u, self.n.ns * self.n.nwf))
    }

    /// Number of spheres on the device.
    pub fn spheres(&self) -> usize {
        self.n.ns
    }
}

/// The springs of a world in the device's layout: the pair table's
/// owning entries (offsets per sphere, neighbour, springs) and the wall
/// slots ([`HIST`] f64s per entry and per (sphere, wall): tangential,
/// rolling).
pub(crate) struct Springs {
    pub noff: Vec<u32>,
    pub nbr: Vec<u32>,
    pub hist: Vec<f64>,
    pub whist: Vec<f64>,
    /// Mesh wall slots' keys (mesh.rs), one per (sphere, wall slot).
    pub wkey: Vec<u32>,
}

/// The bodies of `world` in ascending id: the device's order, whatever
/// the host's storage order (which the CPU path changes at its rebuilds),
/// so that a download and an upload keep each sphere's neighbour order
/// and with it the order of its force sums.
pub(crate) fn by_id(world: &World) -> clump_core::body::Bodies {
    let b = world.bodies();
    let mut perm: Vec<u32> = (0..b.len() as u32).collect();
    perm.sort_by_key(|&k| b.id[k as usize]);
    let mut out = b.clone();
    out.permute(&perm);
    out
}

/// The force flags (bits 0-2) and torque flags (bits 3-5) per world axis
/// (common.wgsl `dof_flags`) and whether the body is driven (bit 6,
/// common.wgsl `driven`), as an f64 of `bm`.
fn dof_bits(force: [bool; 3], torque: [bool; 3], start_step: u64) -> f64 {
    let driven = ((start_step == clump_core::dof::DRIVEN) as u32) << 6;
    (0..3)
        .map(|k| (force[k] as u32) << k | (torque[k] as u32) << (k + 3))
        .sum::<u32>() as f64
        + driven as f64
}

/// The host's copy of what goes to the device at upload.
struct HostArrays {
    pf: Vec<f64>,
    pu: Vec<u32>,
    bodies: [Vec<f64>; 7],
    bfirst: Vec<u32>,
    sown: Vec<u32>,
    sref: Vec<f64>,
    walls: Vec<f64>,
    laws: Vec<f64>,
    meshes: crate::mesh::MeshArrays,
}

impl HostArrays {
    /// The device arrays of `world` (see common.wgsl for each layout).
    fn new(world: &World) -> Result<(HostArrays, Sizes), DeviceError> {
        let b = &by_id(world);
        let c = &world.config;
        let nb = b.len();
        let mut bfirst = vec![0u32];
        let (mut sown, mut sref) = (Vec::new(), Vec::new());
        let (mut rmax, mut rmin) = (0.0f64, f64::INFINITY);
        for i in 0..nb {
            let t = b.template[i] as usize;
            let mat = world.templates.material(t) as u32;
            for s in &world.templates[t].spheres {
                sown.extend([i as u32, mat]);
                sref.extend([s.center.x, s.center.y, s.center.z, s.radius]);
                rmax = rmax.max(s.radius);
                rmin = rmin.min(s.radius);
            }
            bfirst.push((sown.len() / 2) as u32);
        }
        let ns = sown.len() / 2;
        // cells at least one largest diameter plus the skin wide: a pair of
        // the table lies in neighbouring cells
        // the Verlet skin: the scenario's, else 0.2 of the smallest radius
        // (the CPU path's first build); results do not depend on it
        let skin = c.skin.unwrap_or(0.2 * rmin.min(rmax));
        let size = c.domain.size();
        let mut cell_size = (2.0 * rmax + skin).max(f64::MIN_POSITIVE);
        let dims_of =
            |cs: f64| [size.x, size.y, size.z].map(|l| ((l / cs).floor() as usize).max(1));
        while dims_of(cell_size).iter().product::<usize>() > 1 << 24 {
            cell_size *= 2.0;
        }
        let dims = dims_of(cell_size);
        let n = Sizes {
            nb,
            ns,
            npow2: ns.next_power_of_two().max(2),
            cells: dims[0] * dims[1] * dims[2],
            cap: ns * ENTRIES_PER_SPHERE,
            nwf: crate::walls::face_bases(&world.walls).1,
        };
        let lo = c.domain.lo;
        let mut pf = vec![
            c.dt,
            c.gravity.x,
            c.gravity.y,
            c.gravity.z,
            lo.x,
            lo.y,
            lo.z,
            cell_size,
            skin,
        ];
        // periodic boxes (periodic.rs, periodic.wgsl): PF_LEN, PF_HI
        let periodic_axes = crate::periodic::params(&c.domain, dims, cell_size, &mut pf)
            .map_err(DeviceError::Grid)?;
        let nmat = world.materials.len();
        // the walls' row sets (walls.rs): room for every step of a
        // submission when one moves
        let table = crate::walls::WallTable::new(&world.walls, c.dt);
        let sets = if table.moving { BATCH as usize + 1 } else { 1 };
        let mut walls = table.rows();
        walls.resize(sets * walls.len(), 0.0);
        let meshes = crate::mesh::MeshArrays::new(world.walls.meshes(), rmax, walls.len());
        walls.extend(&meshes.f);
        let nwf = crate::walls::face_bases(&world.walls).1;
        // indices 0-16 common.wgsl, 17 periodic.wgsl, 18 average.wgsl,
        // 19 lost.wgsl
        let mut pu = vec![0u32; PU_LOST + 1];
        pu[crate::average::PU_AVERAGE] = crate::average::pairs_average(world) as u32;
        // common.wgsl PU_NWF
        pu[16] = nwf as u32;
        // common.wgsl PU_ROT (support.rs refuses the other schemes)
        pu[12] = match c.rotation {
            clump_core::rotation::RotationScheme::NoSquish => 1,
            clump_core::rotation::RotationScheme::Richardson => 2,
            _ => 0,
        };
        // PU_STALE: the first step builds the table
        pu[13] = 1;
        pu[crate::periodic::PU_PERIODIC] = periodic_axes;
        pu[..9].copy_from_slice(&[
            nb as u32,
            ns as u32,
            n.npow2 as u32,
            dims[0] as u32,
            dims[1] as u32,
            dims[2] as u32,
            n.cap as u32,
            world.walls.len() as u32,
            nmat as u32,
        ]);
        let mut laws = Vec::with_capacity(LAW_ROW * nmat * nmat);
        for a in 0..nmat {
            for bm in 0..nmat {
                let model = world.contact_table.get(a as u16, bm as u16);
                let l = model.sliding_law();
                laws.extend([
                    if l.hertz { 1.0 } else { 0.0 },
                    l.fn_floor,
                    l.kn_coef,
                    l.kt_coef,
                    l.gn_coef,
                    l.gt_coef,
                    l.energy_factor,
                    l.friction,
                    // rolling.wgsl ROLL_*
                    match model.properties().rolling {
                        clump_core::contact::RollingLaw::None => 0.0,
                        clump_core::contact::RollingLaw::Cdt => 1.0,
                        clump_core::contact::RollingLaw::Epsd => 2.0,
                    },
                    model.properties().rolling_friction,
                    model.rolling_damping(),
                ]);
            }
        }
        let mut bm = Vec::with_capacity(9 * nb);
        let mut load = Vec::with_capacity(6 * nb);
        for i in 0..nb {
            let (m, inertia) = (b.mass[i], b.inertia[i]);
            let inv = clump_core::rotation::inverse_inertia(inertia);
            // kick::HalfKick::new without added mass: (dt/2)/(m * 1)
            bm.extend([
                m,
                inertia.x,
                inertia.y,
                inertia.z,
                inv.x,
                inv.y,
                inv.z,
                (0.5 * c.dt) / (m * 1.0),
                dof_bits(b.force_flag[i], b.torque_flag[i], b.start_step[i]),
            ]);
            load.extend([
                b.force[i].x,
                b.force[i].y,
                b.force[i].z,
                b.torque[i].x,
                b.torque[i].y,
                b.torque[i].z,
            ]);
        }
        let q: Vec<f64> = b
            .orientation
            .iter()
            .flat_map(|q| [q.x, q.y, q.z, q.w])
            .collect();
        let bodies = [
            flat3(&b.position),
            flat3(&b.velocity),
            q,
            flat3(&b.angular_momentum),
            flat3(&b.angular_velocity),
            load,
            bm,
        ];
        Ok((
            HostArrays {
                pf,
                pu,
                bodies,
                bfirst,
                sown,
                sref,
                walls,
                laws,
                meshes,
            },
            n,
        ))
    }

    /// The storage buffers of group 0, by binding, and the number of wall
    /// springs sent sparse in `pout` for `whist_scatter` (scatter.wgsl).
    fn buffers(&self, gpu: &Gpu, n: Sizes, springs: Option<Springs>) -> (Vec<wgpu::Buffer>, usize) {
        let nw = n.nwf.max(1);
        let mut out = vec![gpu.buffer("pf", &self.pf), gpu.buffer("pu", &self.pu)];
        for (k, a) in self.bodies.iter().enumerate() {
            out.push(gpu.buffer(["bx", "bv", "bq", "bl", "bw", "bft", "bm"][k], a));
        }
        out.push(gpu.buffer("bfirst", &self.bfirst));
        out.push(gpu.buffer("sown", &self.sown));
        out.push(gpu.buffer("sref", &self.sref));
        out.push(gpu.zeroed::<f64>("sx", 3 * n.ns));
        out.push(gpu.zeroed::<f64>("sarm", 3 * n.ns));
        out.push(gpu.zeroed::<u32>("keys", n.npow2));
        out.push(gpu.zeroed::<u32>("idx", n.npow2));
        out.push(gpu.zeroed::<u32>("cells", 2 * n.cells));
        // the table (the carried springs, if any, which the first build
        // looks up), then its copy at the last build (old_*)
        match &springs {
            Some(sp) => {
                out.push(gpu.buffer("noff", &sp.noff));
                out.push(gpu.buffer_prefix("nbr", &sp.nbr, n.cap));
                out.push(gpu.buffer_prefix("hist", &sp.hist, HIST * n.cap));
            }
            None => {
                out.push(gpu.zeroed::<u32>("noff", n.ns + 1));
                out.push(gpu.zeroed::<u32>("nbr", n.cap));
                out.push(gpu.zeroed::<f64>("hist", HIST * n.cap));
            }
        }
        out.push(gpu.zeroed::<u32>("old_off", n.ns + 1));
        out.push(gpu.zeroed::<u32>("old_nbr", n.cap));
        out.push(gpu.zeroed::<f64>("old_hist", HIST * n.cap));
        out.push(gpu.zeroed::<u32>("mirror", n.cap));
        let whist = springs.as_ref().map(|sp| &sp.whist[..]);
        let (pout, whist, sparse) =
            crate::walls::spring_buffers(gpu, whist, 9 * n.cap, HIST * n.ns * nw);
        out.push(pout);
        out.push(gpu.zeroed::<f64>("sft", 12 * n.ns));
        out.push(gpu.buffer("walls", &self.walls));
        out.push(whist);
        out.push(gpu.buffer("laws", &self.laws));
        out.push(gpu.zeroed::<f64>("sx0", 3 * n.ns));
        let keys = springs.map(|sp| sp.wkey).unwrap_or_default();
        out.push(gpu.buffer("mesh_u", &self.meshes.with_keys(&keys, n.ns * nw)));
        (out, sparse)
    }
}
