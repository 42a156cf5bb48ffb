//! The walls on the device: planes, cylinders and axis-aligned boxes, with
//! the motion the CPU path allows (translation, rotation about a centre, a
//! surface velocity).
//!
//! The host advances its own copy of the walls with the CPU path's code
//! (`Wall::advance`, the same bits) and hands the device, before each
//! submission, the geometry of every step of it: row set k is the walls
//! after k steps of the submission, and the device's step k reads it
//! (walls.wgsl `PU_WSTEP`). The device computes no wall motion, so its
//! walls are the CPU path's to the bit, and a download hands the host's
//! copy back to the world.
//!
//! Each wall has one contact slot per face per sphere (a box seen from
//! inside has six faces, a mesh one per contact it keeps (mesh.rs), every
//! other shape one): slot `face_base + face` of the sphere's row of `NF`
//! slots, `NF` the walls' total face count.

use crate::context::Gpu;
use clump_core::wall::{Wall, WallShape};
use glam::DVec3;

/// f64s per wall in `walls` (walls.wgsl `W_*`).
pub(crate) const WALL_ROW: usize = 25;

/// Shape codes of walls.wgsl (`W_KIND`).
const PLANE: f64 = 0.0;
const CYLINDER: f64 = 1.0;
const BOX: f64 = 2.0;
const MESH: f64 = 3.0;

/// Faces of a wall, each with its own contact slot: the six of a box
/// seen from inside (a sphere in a corner touches several), else one.
pub(crate) fn faces(w: &Wall) -> usize {
    match w.shape {
        WallShape::Box { inside: true, .. } => 6,
        WallShape::Mesh { .. } => crate::mesh::MESH_SLOTS,
        _ => 1,
    }
}

/// The first slot of each wall in a sphere's row, and the row's length.
pub(crate) fn face_bases(walls: &[Wall]) -> (Vec<usize>, usize) {
    let mut base = Vec::with_capacity(walls.len());
    let mut n = 0;
    for w in walls {
        base.push(n);
        n += faces(w);
    }
    (base, n)
}

/// Wall `w`'s row: the geometry (two vectors and a radius), the shape,
/// inside, the material, its first slot, then the motion (velocity,
/// angular velocity, centre, surface velocity), world frame, SI units,
/// whether it is active (an inactive wall touches nothing), and whether
/// its `multi_contact` is "average" (average.wgsl `W_AVERAGE`). A mesh
/// wall's geometry is its pose: the position, the orientation's x y z
/// and w, and the mesh index where `inside` would be (mesh.wgsl).
fn row(w: &Wall, base: usize) -> [f64; WALL_ROW] {
    let (kind, a, b, radius, inside) = match w.shape {
        WallShape::Plane { point, normal } => (PLANE, point, normal, 0.0, false),
        WallShape::Cylinder {
            point,
            axis,
            radius,
            inside,
        } => (CYLINDER, point, axis, radius, inside),
        WallShape::Box { lo, hi, inside } => (BOX, lo, hi, 0.0, inside),
        WallShape::Mesh {
            mesh,
            position,
            orientation: q,
        } => {
            let mut r = row_of(
                w,
                base,
                MESH,
                position,
                DVec3::new(q.x, q.y, q.z),
                q.w,
                false,
            );
            r[8] = mesh as f64;
            return r;
        }
    };
    row_of(w, base, kind, a, b, radius, inside)
}

/// A wall row from its parts (see [`row`]).
fn row_of(
    w: &Wall,
    base: usize,
    kind: f64,
    a: DVec3,
    b: DVec3,
    radius: f64,
    inside: bool,
) -> [f64; WALL_ROW] {
    let m = &w.motion;
    let mut r = [0.0; WALL_ROW];
    r[0..3].copy_from_slice(&a.to_array());
    r[3..6].copy_from_slice(&b.to_array());
    r[6] = radius;
    r[7] = kind;
    r[8] = inside as u8 as f64;
    r[9] = w.material as f64;
    r[10] = base as f64;
    r[11..14].copy_from_slice(&m.velocity.to_array());
    r[14..17].copy_from_slice(&m.angular_velocity.to_array());
    r[17..20].copy_from_slice(&m.center.to_array());
    r[20..23].copy_from_slice(&m.surface_velocity.to_array());
    r[23] = w.active as u8 as f64;
    r[24] = (w.multi_contact == clump_core::multi_contact::MultiContact::Average) as u8 as f64;
    r
}

/// The host's copy of the walls, at the device's step.
pub(crate) struct WallTable {
    pub(crate) walls: Vec<Wall>,
    base: Vec<usize>,
    /// Whether a wall moves (else one row set serves every step).
    pub(crate) moving: bool,
    dt: f64,
}

impl WallTable {
    pub(crate) fn new(walls: &[Wall], dt: f64) -> WallTable {
        let moving = walls.iter().any(|w| {
            let m = &w.motion;
            m.velocity != glam::DVec3::ZERO || m.angular_velocity != glam::DVec3::ZERO
        });
        WallTable {
            walls: walls.to_vec(),
            base: face_bases(walls).0,
            moving,
            dt,
        }
    }

    /// The rows of the walls as they are (one row set).
    pub(crate) fn rows(&self) -> Vec<f64> {
        let mut out = Vec::with_capacity(WALL_ROW * self.walls.len());
        for (w, &b) in self.walls.iter().zip(&self.base) {
            out.extend(row(w, b));
        }
        out
    }

    /// The row sets of the next `steps` steps, the walls as they are
    /// first (set 0, the forces of the current state), then after each
    /// step (`Wall::advance`); the copy ends `steps` steps on.
    pub(crate) fn advance(&mut self, steps: u64) -> Vec<f64> {
        let mut out = self.rows();
        for _ in 0..steps {
            for w in &mut self.walls {
                w.advance(self.dt);
            }
            out.extend(self.rows());
        }
        out
    }
}

/// The wall springs `whist` (6 f64s per slot) as the upload sends them
/// (scatter.wgsl): their count, then per slot not zero its index and its
/// springs; `None` when that does not fit in `room` f64s.
pub(crate) fn sparse_slots(whist: &[f64], room: usize) -> Option<Vec<f64>> {
    let mut out = vec![0.0];
    for (slot, h) in whist.chunks_exact(6).enumerate() {
        if h.iter().any(|&x| x != 0.0) {
            out.push(slot as f64);
            out.extend_from_slice(h);
        }
    }
    out[0] = ((out.len() - 1) / 7) as f64;
    (out.len() <= room).then_some(out)
}

/// `pout` and `whist` of an upload with the wall springs `whist` (6 f64s
/// per slot, `len` f64s in all; none: all zero), and how many springs go
/// sparse in `pout` (`room` f64s) for [`scatter`]; where they do not fit,
/// `whist` is sent whole.
pub(crate) fn spring_buffers(
    gpu: &Gpu,
    whist: Option<&[f64]>,
    room: usize,
    len: usize,
) -> (wgpu::Buffer, wgpu::Buffer, usize) {
    match whist.map(|w| (w, sparse_slots(w, room))) {
        Some((_, Some(s))) => (
            gpu.buffer_prefix("pout", &s, room),
            gpu.zeroed::<f64>("whist", len),
            s[0] as usize,
        ),
        Some((w, None)) => (
            gpu.zeroed::<f64>("pout", room),
            gpu.buffer_prefix("whist", w, len),
            0,
        ),
        None => (
            gpu.zeroed::<f64>("pout", room),
            gpu.zeroed::<f64>("whist", len),
            0,
        ),
    }
}

/// The `count` wall springs sent sparse into their slots (scatter.wgsl
/// `whist_scatter`, its pipeline `scatter`), before the first step.
pub(crate) fn scatter(
    gpu: &Gpu,
    pipeline: &wgpu::ComputePipeline,
    group: &wgpu::BindGroup,
    count: usize,
) {
    if count == 0 {
        return;
    }
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(pipeline);
        pass.set_bind_group(0, group, &[]);
        pass.dispatch_workgroups(count.div_ceil(64) as u32, 1, 1);
    }
    gpu.queue.submit(Some(enc.finish()));
}
