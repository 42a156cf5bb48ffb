//! `--device gpu` of `clump check`, `run`, `resume` and `bench`: the device
//! path (crate clump-gpu, Cargo feature `gpu`). Without the feature the option
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
    if refuse(sc, &world) {
        ok = false;
    }
    if ok {
        outln!("  the scenario's settings run on the GPU path");
    }
    ok
}

/// Prints a diagnostic at the scenario's key for each setting of `world`
/// (built from `sc`) that the GPU path does not run; true when any.
#[cfg(feature = "gpu")]
fn refuse(sc: &clump_io::scenario::Scenario, world: &clump_core::world::World) -> bool {
    use clump_gpu::support::KeySeg;
    use clump_io::scenario::{Seg, Source};
    let mut refused = clump_gpu::support::unsupported_settings(world);
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
    }
    !refused.is_empty()
}

/// `clump run|resume --device gpu`: the device for the runner of `world`
/// (built from, or resumed with, `sc`), or an error message (the
/// settings the GPU path refuses are printed at their keys) before
/// anything is written. `ranks`: the run's MPI ranks.
#[cfg(feature = "gpu")]
pub fn stepper(
    sc: &clump_io::scenario::Scenario,
    world: &clump_core::world::World,
    ranks: usize,
) -> Result<Box<dyn clump_io::run::device::StepDevice>, String> {
    if ranks > 1 {
        return Err(format!(
            "--device gpu runs on one process; this run has {ranks} MPI ranks"
        ));
    }
    if refuse(sc, world) {
        return Err(
            "the scenario has settings the GPU path does not run (above); nothing was written"
                .into(),
        );
    }
    clump_gpu::steps::gpu_steps(world)
}

#[cfg(not(feature = "gpu"))]
pub fn stepper(
    _sc: &clump_io::scenario::Scenario,
    _world: &clump_core::world::World,
    _ranks: usize,
) -> Result<Box<dyn clump_io::run::device::StepDevice>, String> {
    Err(format!("--device gpu: {NOT_BUILT}"))
}

#[cfg(not(feature = "gpu"))]
pub fn check(_sc: &clump_io::scenario::Scenario) -> bool {
    errln!("error: --device gpu: {NOT_BUILT}");
    false
}

/// `clump bench --device gpu`: the world of `scenario` (`--scenario`, e.g.
/// the shared tetra bed), else the clumps of `clump_gpu::bed` in a closed
/// box, about `n` clumps; `steps` steps on the
/// device and on the CPU path with `threads` threads; sphere-steps/s of
/// both and the largest position difference between them.
#[cfg(feature = "gpu")]
pub fn bench(
    n: usize,
    steps: u64,
    threads: usize,
    scenario: Option<clump_core::world::World>,
) -> anyhow::Result<()> {
    use std::time::Instant;
    let side = ((n as f64).cbrt().round() as usize).max(1);
    let what = match &scenario {
        Some(w) => format!("the scenario's world ({} bodies)", w.bodies().len()),
        None => format!("box bed of {side}x{side}x{side} clumps (tetra and 3-sphere rods in turn)"),
    };
    let world = scenario.unwrap_or_else(|| {
        clump_gpu::bed::box_bed(side, side, clump_core::rotation::RotationScheme::NoSquish)
    });
    let gpu = clump_gpu::Gpu::new()?;
    outln!("device: {}", gpu.describe());
    let t = Instant::now();
    let mut dev = clump_gpu::DeviceWorld::upload(gpu, &world)?;
    let ns = dev.spheres() as f64;
    outln!(
        "{what}, {ns} spheres, {steps} steps; upload and first forces {:.3} s",
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
    // the nearest image in a periodic box (the paths wrap at different steps)
    let domain = cpu.config.domain;
    let dev_max = dev
        .ids
        .iter()
        .zip(&x_dev)
        .map(|(id, x)| {
            clump_gpu::periodic::nearest_image(&domain, *x - b.position[at[id]])
                .abs()
                .max_element()
        })
        .fold(0.0, f64::max);
    outln!(
        "largest |x_gpu - x_cpu| / domain size after {steps} steps: {:.3e}",
        dev_max / cpu.config.domain.size().max_element()
    );
    Ok(())
}

#[cfg(not(feature = "gpu"))]
pub fn bench(
    _n: usize,
    _steps: u64,
    _threads: usize,
    _scenario: Option<clump_core::world::World>,
) -> anyhow::Result<()> {
    anyhow::bail!("--device gpu: {NOT_BUILT}")
}
