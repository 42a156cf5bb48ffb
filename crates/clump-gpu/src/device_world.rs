//! A world on the device: its bodies, spheres, pair table and walls in
//! storage buffers (SoA, ARCHITECTURE.md "The device path"), the step as a
//! sequence of compute dispatches, and the copies in and out at events.

use crate::context::{Gpu, GpuError};
use crate::support::unsupported;
use clump_core::world::World;
use glam::{DQuat, DVec3};

/// The kernels, one WGSL module.
const SHADER: [&str; 5] = [
    include_str!("shaders/common.wgsl"),
    include_str!("shaders/rotation.wgsl"),
    include_str!("shaders/body.wgsl"),
    include_str!("shaders/pairs.wgsl"),
    include_str!("shaders/contact.wgsl"),
];
/// Storage bindings of the module (common.wgsl).
const N_BINDINGS: u32 = 29;
/// Pair-table entries reserved per sphere (each pair twice, one entry per side).
const ENTRIES_PER_SPHERE: usize = 16;
/// Index of the integer parameter holding the overflow bits (common.wgsl PU_OVERFLOW).
const PU_OVERFLOW: usize = 11;
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
const ENTRIES: [&str; 15] = [
    "first_half", "spheres", "sort_reset", "sort_next", "sort_step", "cells_clear", "cells_bounds",
    "pairs_count", "pairs_scan", "pairs_fill", "pairs_mirror", "pair_forces", "sphere_gather",
    "body_gather", "gather_kick",
];

/// Why a world cannot run on, or a step failed on, the device.
#[derive(Debug)]
pub enum DeviceError {
    Gpu(GpuError),
    /// Features the device path does not have yet, by scenario key.
    Unsupported(Vec<crate::support::Unsupported>),
    /// The pair table or a sphere's neighbour list ran full.
    Overflow(String),
}

impl std::fmt::Display for DeviceError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DeviceError::Gpu(e) => write!(f, "{e}"),
            DeviceError::Unsupported(list) => {
                let lines: Vec<String> = list.iter().map(|u| u.to_string()).collect();
                write!(f, "the GPU path cannot run this scenario:\n  {}", lines.join("\n  "))
            }
            DeviceError::Overflow(e) => write!(f, "{e}"),
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
}

/// A world's state on the device and the step's pipelines.
pub struct DeviceWorld {
    pub gpu: Gpu,
    n: Sizes,
    /// Buffers by binding; 17..=22 swap between the two bind groups.
    buffers: Vec<wgpu::Buffer>,
    /// Bind group 0 for even and odd steps: the pair table (noff, nbr,
    /// hist) of one step is the old table (old_off, old_nbr, old_hist) of
    /// the next, without a copy.
    groups: [wgpu::BindGroup; 2],
    pipelines: Vec<wgpu::ComputePipeline>,
    /// Which group holds the current table as its new one.
    parity: usize,
    /// Global id of each body, in device order (the world's storage order
    /// at upload; the CPU path reorders its bodies at rebuilds, the device
    /// keeps this order).
    pub ids: Vec<u64>,
    /// Steps taken (the world's count at upload plus the device's).
    pub step: u64,
    /// Simulated time, s.
    pub time: f64,
    dt: f64,
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
        let (host, n) = HostArrays::new(world);
        let scope = gpu.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let buffers = host.buffers(&gpu, n);
        let layout = gpu.device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("clump step"),
            entries: &(0..N_BINDINGS)
                .map(|b| wgpu::BindGroupLayoutEntry {
                    binding: b,
                    visibility: wgpu::ShaderStages::COMPUTE,
                    ty: wgpu::BindingType::Buffer {
                        ty: wgpu::BufferBindingType::Storage { read_only: false },
                        has_dynamic_offset: false,
                        min_binding_size: None,
                    },
                    count: None,
                })
                .collect::<Vec<_>>(),
        });
        let pl = gpu.device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("clump step"),
            bind_group_layouts: &[Some(&layout)],
            immediate_size: 0,
        });
        let module = gpu.device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some("clump step"),
            source: wgpu::ShaderSource::Wgsl(SHADER.concat().into()),
        });
        let pipelines = ENTRIES
            .iter()
            .map(|e| {
                gpu.device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                    label: Some(e),
                    layout: Some(&pl),
                    module: &module,
                    entry_point: Some(e),
                    compilation_options: Default::default(),
                    cache: None,
                })
            })
            .collect();
        let group = |swap: bool| {
            let entries: Vec<wgpu::BindGroupEntry> = (0..N_BINDINGS as usize)
                .map(|b| {
                    // 17..=19 (new table) and 20..=22 (old table) trade places
                    let src = match (swap, b) {
                        (true, 17..=19) => b + 3,
                        (true, 20..=22) => b - 3,
                        _ => b,
                    };
                    wgpu::BindGroupEntry { binding: b as u32, resource: buffers[src].as_entire_binding() }
                })
                .collect();
            gpu.device.create_bind_group(&wgpu::BindGroupDescriptor { label: None, layout: &layout, entries: &entries })
        };
        let groups = [group(false), group(true)];
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(GpuError::Device(format!("setting up the device step: {e}")).into());
        }
        let mut dw = DeviceWorld {
            gpu,
            n,
            buffers,
            groups,
            pipelines,
            parity: 0,
            ids: world.bodies().id.clone(),
            step: world.step,
            time: world.time,
            dt: world.config.dt,
        };
        dw.submit(0, true)?;
        Ok(dw)
    }

    /// Takes `steps` steps on the device, in batches of one submission
    /// each; the host reads back only the overflow flags between batches.
    pub fn run(&mut self, steps: u64) -> Result<(), DeviceError> {
        const BATCH: u64 = 64;
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
        let mut enc = self.gpu.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            if prepare {
                self.encode_forces(&mut pass);
                self.dispatch(&mut pass, K_BODY_GATHER, self.n.nb);
            }
            for _ in 0..steps {
                self.parity ^= 1;
                self.dispatch(&mut pass, K_FIRST_HALF, self.n.nb);
                self.encode_forces(&mut pass);
                self.dispatch(&mut pass, K_GATHER_KICK, self.n.nb);
            }
        }
        self.gpu.queue.submit(Some(enc.finish()));
        for _ in 0..steps {
            self.step += 1;
            self.time += self.dt;
        }
        let pu: Vec<u32> = self.gpu.read(&self.buffers[1])?;
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
        pass.set_pipeline(&self.pipelines[k]);
        pass.set_bind_group(0, &self.groups[self.parity], &[]);
        pass.dispatch_workgroups(n.div_ceil(64).max(1) as u32, 1, 1);
    }

    /// Stages 3-5 of the step on the device: sphere centres and cell keys,
    /// the bitonic sort, cell ranges, the pair table with its carried
    /// springs, the pair forces, and the gather per sphere.
    fn encode_forces(&self, pass: &mut wgpu::ComputePass<'_>) {
        let n = self.n;
        self.dispatch(pass, K_SPHERES, n.npow2);
        self.dispatch(pass, K_SORT_RESET, 1);
        let p = n.npow2.trailing_zeros() as usize;
        for _ in 0..p * (p + 1) / 2 {
            self.dispatch(pass, K_SORT_NEXT, 1);
            self.dispatch(pass, K_SORT_STEP, n.npow2);
        }
        self.dispatch(pass, K_CELLS_CLEAR, n.cells);
        self.dispatch(pass, K_CELLS_BOUNDS, n.ns);
        self.dispatch(pass, K_PAIRS_COUNT, n.ns);
        // one workgroup of 256
        pass.set_pipeline(&self.pipelines[K_PAIRS_SCAN]);
        pass.dispatch_workgroups(1, 1, 1);
        self.dispatch(pass, K_PAIRS_FILL, n.ns);
        self.dispatch(pass, K_PAIRS_MIRROR, n.ns);
        self.dispatch(pass, K_PAIR_FORCES, n.ns);
        self.dispatch(pass, K_SPHERE_GATHER, n.ns);
    }

    /// Body centres of mass, world frame, m (storage order of the world
    /// uploaded).
    pub fn positions(&self) -> Result<Vec<DVec3>, DeviceError> {
        let x: Vec<f64> = self.gpu.read(&self.buffers[2])?;
        Ok(x.chunks(3).take(self.n.nb).map(|c| DVec3::new(c[0], c[1], c[2])).collect())
    }

    /// Copies the bodies' state back into `world` (an event: output,
    /// checkpoint, steering): positions, orientations, velocities, angular
    /// momenta and velocities, the step count and time, matched by body id.
    pub fn download(&self, world: &mut World) -> Result<(), DeviceError> {
        let at: std::collections::HashMap<u64, usize> =
            world.bodies().id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
        let read = |b: usize| -> Result<Vec<f64>, DeviceError> { Ok(self.gpu.read(&self.buffers[b])?) };
        let (x, v, q, l, w) = (read(2)?, read(3)?, read(4)?, read(5)?, read(6)?);
        let bad = |e: clump_core::world::WorldError| DeviceError::Overflow(format!("device state: {e}"));
        for i in 0..self.n.nb {
            let k = *at.get(&self.ids[i]).ok_or_else(|| {
                DeviceError::Overflow(format!("body {} left the world while on the device", self.ids[i]))
            })?;
            let d3 = |a: &[f64]| DVec3::new(a[3 * i], a[3 * i + 1], a[3 * i + 2]);
            let quat = DQuat::from_xyzw(q[4 * i], q[4 * i + 1], q[4 * i + 2], q[4 * i + 3]);
            world.set_body_pose_at(k, d3(&x), quat).map_err(bad)?;
            world.set_body_velocity_at(k, d3(&v)).map_err(bad)?;
            world.set_body_angular_state_at(k, d3(&w), d3(&l)).map_err(bad)?;
        }
        world.step = self.step;
        world.time = self.time;
        Ok(())
    }

    /// Number of spheres on the device.
    pub fn spheres(&self) -> usize {
        self.n.ns
    }
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
}

impl HostArrays {
    /// The device arrays of `world` (see common.wgsl for each layout).
    fn new(world: &World) -> (HostArrays, Sizes) {
        let b = world.bodies();
        let c = &world.config;
        let nb = b.len();
        let mut bfirst = vec![0u32];
        let (mut sown, mut sref) = (Vec::new(), Vec::new());
        let mut rmax = 0.0f64;
        for i in 0..nb {
            let t = b.template[i] as usize;
            let mat = world.templates.material(t) as u32;
            for s in &world.templates[t].spheres {
                sown.extend([i as u32, mat]);
                sref.extend([s.center.x, s.center.y, s.center.z, s.radius]);
                rmax = rmax.max(s.radius);
            }
            bfirst.push((sown.len() / 2) as u32);
        }
        let ns = sown.len() / 2;
        // cells at least one largest diameter wide: a touching pair lies in
        // neighbouring cells
        let size = c.domain.size();
        let mut cell_size = (2.0 * rmax).max(f64::MIN_POSITIVE);
        let dims_of = |cs: f64| [size.x, size.y, size.z].map(|l| ((l / cs).floor() as usize).max(1));
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
        };
        let lo = c.domain.lo;
        let pf = vec![c.dt, c.gravity.x, c.gravity.y, c.gravity.z, lo.x, lo.y, lo.z, cell_size];
        let nmat = world.materials.len();
        let walls: Vec<f64> = world
            .walls
            .iter()
            .flat_map(|w| match w.shape {
                clump_core::wall::WallShape::Plane { point, normal } => {
                    [point.x, point.y, point.z, normal.x, normal.y, normal.z, w.material as f64]
                }
                _ => unreachable!("refused by support::unsupported"),
            })
            .collect();
        let mut pu = vec![0u32; 16];
        // common.wgsl PU_ROT (support.rs refuses the other schemes)
        pu[12] = match c.rotation {
            clump_core::rotation::RotationScheme::NoSquish => 1,
            _ => 0,
        };
        pu[..9].copy_from_slice(&[
            nb as u32, ns as u32, n.npow2 as u32, dims[0] as u32, dims[1] as u32, dims[2] as u32,
            n.cap as u32, world.walls.len() as u32, nmat as u32,
        ]);
        let mut laws = Vec::with_capacity(8 * nmat * nmat);
        for a in 0..nmat {
            for bm in 0..nmat {
                let l = world.contact_table.get(a as u16, bm as u16).sliding_law();
                laws.extend([
                    if l.hertz { 1.0 } else { 0.0 },
                    l.fn_floor,
                    l.kn_coef,
                    l.kt_coef,
                    l.gn_coef,
                    l.gt_coef,
                    l.energy_factor,
                    l.friction,
                ]);
            }
        }
        let mut bm = Vec::with_capacity(8 * nb);
        let mut load = Vec::with_capacity(6 * nb);
        for i in 0..nb {
            let (m, inertia) = (b.mass[i], b.inertia[i]);
            let inv = clump_core::rotation::inverse_inertia(inertia);
            // kick::HalfKick::new without added mass: (dt/2)/(m * 1)
            bm.extend([m, inertia.x, inertia.y, inertia.z, inv.x, inv.y, inv.z, (0.5 * c.dt) / (m * 1.0)]);
            load.extend([b.force[i].x, b.force[i].y, b.force[i].z, b.torque[i].x, b.torque[i].y, b.torque[i].z]);
        }
        let q: Vec<f64> = b.orientation.iter().flat_map(|q| [q.x, q.y, q.z, q.w]).collect();
        let bodies = [
            flat3(&b.position),
            flat3(&b.velocity),
            q,
            flat3(&b.angular_momentum),
            flat3(&b.angular_velocity),
            load,
            bm,
        ];
        (HostArrays { pf, pu, bodies, bfirst, sown, sref, walls, laws }, n)
    }

    /// The 29 storage buffers, by binding.
    fn buffers(&self, gpu: &Gpu, n: Sizes) -> Vec<wgpu::Buffer> {
        let nw = (self.walls.len() / 7).max(1);
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
        for _ in 0..2 {
            out.push(gpu.zeroed::<u32>("noff", n.ns + 1));
            out.push(gpu.zeroed::<u32>("nbr", n.cap));
            out.push(gpu.zeroed::<f64>("hist", 3 * n.cap));
        }
        out.push(gpu.zeroed::<u32>("mirror", n.cap));
        out.push(gpu.zeroed::<f64>("pout", 9 * n.cap));
        out.push(gpu.zeroed::<f64>("sft", 12 * n.ns));
        out.push(gpu.buffer("walls", &self.walls));
        out.push(gpu.zeroed::<f64>("whist", 3 * n.ns * nw));
        out.push(gpu.buffer("laws", &self.laws));
        out
    }
}
