//! `--device gpu` of `clump check` and `clump bench`: the device path
//! (crate clump-gpu, Cargo feature `gpu`). Without the feature the option
//! is refused with how to build it.

use clap::ValueEnum;

/// Where the step runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum, Default)]
pub enum Device {
    /// The CPU path (threads).
    #[default]
    Cpu,
    /// The GPU path: wgpu compute shaders with f64 state (Vulkan, Metal, DX12).
    Gpu,
}

#[cfg(not(feature = "gpu"))]
const NOT_BUILT: &str = "this clump was built without the GPU path: build it with \
     `cargo build --release -p clump-cli --features gpu` (needs a Vulkan, Metal or DX12 driver \
     with f64 shaders; on Linux without a GPU, Mesa's lavapipe: package mesa-vulkan-drivers)";

/// `clump check --device gpu`: names the adapter and refuses, at the key,
/// what the GPU path does not run yet. Prints the diagnostics; false when
/// the scenario cannot run on the device.
#[cfg(feature = "gpu")]
pub fn check(sc: &clump_io::scenario::Scenario) -> bool {
    use clump_gpu::support::KeySeg;
    use clump_io::scenario::{Seg, Source};
    outln!("\ndevice (--device gpu):");
    let mut ok = match clump_gpu::Gpu::new() {
        Ok(g) => {
            outln!("  adapter {}", g.describe());
            true
        }
        Err(e) => {
            err!("error: {e}\n");
            false
        }
    };
    let world = match sc.build_world() {
        Ok(w) => w,
        Err(e) => {
            err!("error: {e}\n");
            return false;
        }
    };
    let mut refused = clump_gpu::support::unsupported(&world);
    if sc.fluid.is_some() {
        refused.push(clump_gpu::support::Unsupported {
            path: vec![KeySeg::Key("fluid")],
            allowed: "no fluid".into(),
        });
    }
    let src = Source::new(&sc.path, sc.text.clone());
    for u in &refused {
        let segs: Vec<Seg> = u
            .path
            .iter()
            .map(|s| match s {
                KeySeg::Key(k) => Seg::K(k),
                KeySeg::Index(i) => Seg::I(*i),
            })
            .collect();
        let d = src.error_at_key(&segs, format!("'{}' is not on the GPU path yet", u.key()));
        err!(
            "{}",
            d.note(format!("allowed on the GPU path: {}", u.allowed))
        );
        ok = false;
    }
    if ok {
        outln!("  the scenario's settings run on the GPU path");
    }
    ok
}

#[cfg(not(feature = "gpu"))]
pub fn check(_sc: &clump_io::scenario::Scenario) -> bool {
    errln!("error: --device gpu: {NOT_BUILT}");
    false
}

/// `clump bench --device gpu`: the clumps of `clump_gpu::bed` in a closed
/// box (the shared tetra bed uses the exact Richardson rotation, which the
/// GPU path does not run yet), about `n` clumps, `steps` steps on the
/// device and on the CPU path with `threads` threads; sphere-steps/s of
/// both and the largest position difference between them.
#[cfg(feature = "gpu")]
pub fn bench(n: usize, steps: u64, threads: usize) -> anyhow::Result<()> {
    use std::time::Instant;
    let side = ((n as f64).cbrt().round() as usize).max(1);
    let world = clump_gpu::bed::box_bed(side, side, clump_core::rotation::RotationScheme::NoSquish);
    let gpu = clump_gpu::Gpu::new()?;
    outln!("device: {}", gpu.describe());
    let t = Instant::now();
    let mut dev = clump_gpu::DeviceWorld::upload(gpu, &world)?;
    let ns = dev.spheres() as f64;
    outln!(
        "box bed of {side}x{side}x{side} clumps (tetra and 3-sphere rods in turn, {ns} spheres), {steps} steps; upload and first forces {:.3} s",
        t.elapsed().as_secs_f64()
    );
    let t = Instant::now();
    dev.run(steps)?;
    let x_dev = dev.positions()?;
    let gpu_rate = ns * steps as f64 / t.elapsed().as_secs_f64();
    outln!(
        "gpu: {:.3} M sphere-steps/s ({} pair-table builds)",
        gpu_rate / 1e6,
        dev.builds
    );
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()?;
    let mut cpu = world;
    let t = Instant::now();
    pool.install(|| -> anyhow::Result<()> {
        cpu.prepare()?;
        cpu.run(steps)?;
        Ok(())
    })?;
    let cpu_rate = ns * steps as f64 / t.elapsed().as_secs_f64();
    outln!(
        "cpu ({threads} threads): {:.3} M sphere-steps/s",
        cpu_rate / 1e6
    );
    let b = cpu.bodies();
    let at: std::collections::HashMap<u64, usize> =
        b.id.iter().enumerate().map(|(k, &id)| (id, k)).collect();
    let dev_max = dev
        .ids
        .iter()
        .zip(&x_dev)
        .map(|(id, x)| (*x - b.position[at[id]]).abs().max_element())
        .fold(0.0, f64::max);
    outln!(
        "largest |x_gpu - x_cpu| / domain size after {steps} steps: {:.3e}",
        dev_max / cpu.config.domain.size().max_element()
    );
    Ok(())
}

#[cfg(not(feature = "gpu"))]
pub fn bench(_n: usize, _steps: u64, _threads: usize) -> anyhow::Result<()> {
    anyhow::bail!("--device gpu: {NOT_BUILT}")
}
