//! Clump's device (GPU) path: the step as wgpu compute shaders (WGSL) with
//! f64 state through wgpu's `SHADER_F64` feature (Vulkan's `shaderFloat64`).
//!
//! - `context`: the adapter and device, buffer and pipeline helpers;
//! - `bed`: a bed of tetra clumps in a closed box, all of it on the device;
//! - `steps`: the device as the runner's `StepDevice` (clump-io);
//! - `support`: what the device step runs, refused by scenario key;
//! - `device_world`: a world's arrays on the device, the step's kernels in
//!   order (`shaders/*.wgsl`);
//! - `periodic`: periodic boxes, the host's half (`shaders/periodic.wgsl`);
//! - `average`: `average` multi-contact, the host's half (`shaders/average.wgsl`);
//! - `lost`: bodies leaving through a non-periodic side, removed at
//!   downloads (`shaders/lost.wgsl`);
//! - `transfer`: the copies in and out at events, springs included, and
//!   the stepper a runner hands the steps between its events to.
//!
//! ARCHITECTURE.md ("The device path") describes the device data layout,
//! the kernels in step order and what crosses the bus and when.

mod average;
pub mod bed;
pub mod context;
pub mod device_world;
mod lost;
mod mesh;
pub mod periodic;
pub mod steps;
pub mod support;
pub mod transfer;
mod walls;

pub use context::{Gpu, GpuError};
pub use device_world::{DeviceError, DeviceWorld};
pub use transfer::DeviceStepper;
