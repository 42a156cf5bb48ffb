//! Clump's device (GPU) path: the step as wgpu compute shaders (WGSL) with
//! f64 state through wgpu's `SHADER_F64` feature (Vulkan's `shaderFloat64`).
//!
//! `context` opens the adapter and device and holds the buffer and
//! pipeline helpers every kernel uses. ARCHITECTURE.md ("The device path")
//! describes the device data layout, the kernels in step order and what
//! crosses the bus and when.

pub mod context;

pub use context::{Gpu, GpuError};
