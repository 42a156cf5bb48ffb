//! The device: adapter, logical device with `SHADER_F64`, and the buffer,
//! pipeline and read-back helpers the kernels share.

use std::fmt;

use wgpu::util::DeviceExt;

/// Why the device path cannot run here.
#[derive(Debug)]
pub enum GpuError {
    /// No adapter on any backend compiled in (Vulkan, Metal, DX12).
    NoAdapter(String),
    /// The adapter lacks f64 in shaders (Vulkan's `shaderFloat64`).
    NoF64 { adapter: String },
    /// The device could not be opened or a map or poll failed.
    Device(String),
}

impl fmt::Display for GpuError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GpuError::NoAdapter(e) => write!(
                f,
                "no GPU adapter found ({e}); the device path needs Vulkan, Metal or DX12 \
                 (on Linux without a GPU: Mesa's lavapipe, package mesa-vulkan-drivers)"
            ),
            GpuError::NoF64 { adapter } => write!(
                f,
                "adapter '{adapter}' has no f64 in shaders (wgpu feature SHADER_F64, \
                 Vulkan shaderFloat64); the device path keeps physical state in f64"
            ),
            GpuError::Device(e) => write!(f, "GPU device error: {e}"),
        }
    }
}

impl std::error::Error for GpuError {}

/// An open device with f64 shaders, and what it is.
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
    /// Bytes copied host to device and device to host so far (integer
    /// counters: what crosses the bus, ARCHITECTURE.md).
    traffic: [std::sync::atomic::AtomicU64; 2],
}

impl Gpu {
    /// Opens the first high-performance adapter and a device with
    /// `SHADER_F64` and the adapter's own limits (storage buffer sizes and
    /// counts above WebGPU's defaults are needed for large beds).
    pub fn new() -> Result<Gpu, GpuError> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            ..Default::default()
        }))
        .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        let info = adapter.get_info();
        if !adapter.features().contains(wgpu::Features::SHADER_F64) {
            return Err(GpuError::NoF64 {
                adapter: info.name.clone(),
            });
        }
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("clump"),
            required_features: wgpu::Features::SHADER_F64,
            required_limits: adapter.limits(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| GpuError::Device(e.to_string()))?;
        Ok(Gpu {
            device,
            queue,
            info,
            traffic: Default::default(),
        })
    }

    /// "name (backend, driver driver_info)", for `clump check` and reports.
    pub fn describe(&self) -> String {
        format!(
            "{} ({:?}, {:?}, driver {} {})",
            self.info.name,
            self.info.backend,
            self.info.device_type,
            self.info.driver,
            self.info.driver_info
        )
    }

    /// Bytes copied so far: (host to device, device to host).
    pub fn traffic(&self) -> (u64, u64) {
        let get = |k: usize| self.traffic[k].load(std::sync::atomic::Ordering::Relaxed);
        (get(0), get(1))
    }

    /// Counts `bytes` copied host to device (`k` 0) or back (`k` 1).
    fn count(&self, k: usize, bytes: u64) {
        self.traffic[k].fetch_add(bytes, std::sync::atomic::Ordering::Relaxed);
    }

    /// A storage buffer holding `data`, readable back by `read`.
    pub fn buffer<T: bytemuck::Pod>(&self, label: &str, data: &[T]) -> wgpu::Buffer {
        // wgpu refuses zero-sized bindings: an empty array still gets one element's room.
        let bytes: &[u8] = bytemuck::cast_slice(data);
        let mut contents = bytes.to_vec();
        if contents.is_empty() {
            contents.resize(std::mem::size_of::<T>().max(4), 0);
        }
        self.count(0, contents.len() as u64);
        self.device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents: &contents,
                usage: wgpu::BufferUsages::STORAGE
                    | wgpu::BufferUsages::COPY_SRC
                    | wgpu::BufferUsages::COPY_DST,
            })
    }

    /// A zeroed storage buffer of `n` elements of `T`. Nothing crosses
    /// the bus: wgpu clears a new buffer on the device.
    pub fn zeroed<T: bytemuck::Pod + bytemuck::Zeroable>(
        &self,
        label: &str,
        n: usize,
    ) -> wgpu::Buffer {
        let size = (n.max(1) * std::mem::size_of::<T>()).max(4) as u64;
        self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some(label),
            size: size.next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT),
            usage: wgpu::BufferUsages::STORAGE
                | wgpu::BufferUsages::COPY_SRC
                | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        })
    }

    /// A zeroed storage buffer of `n` elements of `T` that starts with
    /// `data` (`data.len() <= n`): only `data` crosses the bus.
    pub fn buffer_prefix<T: bytemuck::Pod + bytemuck::Zeroable>(
        &self,
        label: &str,
        data: &[T],
        n: usize,
    ) -> wgpu::Buffer {
        debug_assert!(data.len() <= n.max(1));
        let buffer = self.zeroed::<T>(label, n);
        self.write(&buffer, data);
        buffer
    }

    /// A compute pipeline for `entry` of `wgsl`, its bind group laid out
    /// from the shader (group 0).
    pub fn pipeline(&self, label: &str, wgsl: &str, entry: &str) -> wgpu::ComputePipeline {
        let module = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(wgsl.into()),
            });
        self.device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(label),
                layout: None,
                module: &module,
                entry_point: Some(entry),
                compilation_options: Default::default(),
                cache: None,
            })
    }

    /// A bind group for group 0 of `pipeline`, binding i = `buffers[i]`.
    pub fn bind(
        &self,
        pipeline: &wgpu::ComputePipeline,
        buffers: &[&wgpu::Buffer],
    ) -> wgpu::BindGroup {
        let entries: Vec<wgpu::BindGroupEntry> = buffers
            .iter()
            .enumerate()
            .map(|(i, b)| wgpu::BindGroupEntry {
                binding: i as u32,
                resource: b.as_entire_binding(),
            })
            .collect();
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &entries,
        })
    }

    /// Copies `buffer` to the host (blocks until the queue is idle).
    pub fn read<T: bytemuck::Pod>(&self, buffer: &wgpu::Buffer) -> Result<Vec<T>, GpuError> {
        let n = buffer.size() as usize / std::mem::size_of::<T>();
        self.read_prefix(buffer, n)
    }

    /// Copies the first `n` elements of `buffer` to the host (blocks
    /// until the queue is idle).
    pub fn read_prefix<T: bytemuck::Pod>(
        &self,
        buffer: &wgpu::Buffer,
        n: usize,
    ) -> Result<Vec<T>, GpuError> {
        if n == 0 {
            return Ok(Vec::new());
        }
        let bytes = (n * std::mem::size_of::<T>()) as u64;
        let size = bytes
            .next_multiple_of(wgpu::COPY_BUFFER_ALIGNMENT)
            .clamp(wgpu::COPY_BUFFER_ALIGNMENT, buffer.size());
        self.count(1, size);
        let staging = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("staging"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        enc.copy_buffer_to_buffer(buffer, 0, &staging, 0, size);
        self.queue.submit(Some(enc.finish()));
        let slice = staging.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.device
            .poll(wgpu::PollType::Wait {
                submission_index: None,
                timeout: None,
            })
            .map_err(|e| GpuError::Device(e.to_string()))?;
        rx.recv()
            .map_err(|e| GpuError::Device(e.to_string()))?
            .map_err(|e| GpuError::Device(e.to_string()))?;
        let out = {
            let view = slice
                .get_mapped_range()
                .map_err(|e| GpuError::Device(e.to_string()))?;
            let t: &[T] = bytemuck::cast_slice(&view);
            t[..n.min(t.len())].to_vec()
        };
        staging.unmap();
        Ok(out)
    }

    /// Overwrites the start of `buffer` with `data`.
    pub fn write<T: bytemuck::Pod>(&self, buffer: &wgpu::Buffer, data: &[T]) {
        self.write_at(buffer, 0, data);
    }

    /// Overwrites `buffer` from byte `offset` on with `data`.
    pub fn write_at<T: bytemuck::Pod>(&self, buffer: &wgpu::Buffer, offset: u64, data: &[T]) {
        self.count(0, std::mem::size_of_val(data) as u64);
        self.queue
            .write_buffer(buffer, offset, bytemuck::cast_slice(data));
    }
}

/// A read-write storage buffer at `binding`, seen by compute shaders.
pub(crate) fn storage_entry(binding: u32) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::COMPUTE,
        ty: wgpu::BindingType::Buffer {
            ty: wgpu::BufferBindingType::Storage { read_only: false },
            has_dynamic_offset: false,
            min_binding_size: None,
        },
        count: None,
    }
}
