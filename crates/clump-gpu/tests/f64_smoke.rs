//! The toolchain: a WGSL kernel in f64 on the adapter (lavapipe in CI)
//! against the same arithmetic on the CPU. IEEE 754 makes +, -, *, / and
//! sqrt correctly rounded; Vulkan requires f64 +, -, * and / correctly
//! rounded too, so the results must be bit-equal where the compiler does
//! not contract a*b+c into a fused multiply-add.

const SHADER: &str = r#"
@group(0) @binding(0) var<storage, read> x: array<f64>;
@group(0) @binding(1) var<storage, read_write> y: array<f64>;
@compute @workgroup_size(64)
fn main(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&x)) { return; }
    let a = x[i];
    // 1/3 is not representable in f32: an f32 path would fail the test.
    y[i] = a / 3.0lf + sqrt(a) - a * a;
}
"#;

#[test]
fn f64_kernel_matches_cpu_bits() {
    let gpu = match clump_gpu::Gpu::new() {
        Ok(g) => g,
        Err(e) => panic!("{e}"),
    };
    eprintln!("adapter: {}", gpu.describe());
    let n = 1000usize;
    let x: Vec<f64> = (0..n).map(|i| 1.0 + i as f64 * 0.7306).collect();
    let bx = gpu.buffer("x", &x);
    let by = gpu.zeroed::<f64>("y", n);
    let p = gpu.pipeline("smoke", SHADER, "main");
    let bg = gpu.bind(&p, &[&bx, &by]);
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(&p);
        pass.set_bind_group(0, &bg, &[]);
        pass.dispatch_workgroups(n.div_ceil(64) as u32, 1, 1);
    }
    gpu.queue.submit(Some(enc.finish()));
    let y: Vec<f64> = gpu.read(&by).unwrap();
    let mut worst = 0.0f64;
    let mut unequal = 0;
    for i in 0..n {
        let a = x[i];
        let cpu = a / 3.0 + a.sqrt() - a * a;
        if cpu.to_bits() != y[i].to_bits() {
            unequal += 1;
            worst = worst.max(((cpu - y[i]) / cpu).abs());
        }
    }
    eprintln!("{unequal} of {n} differ in the last bits; worst relative difference {worst:e}");
    // f32 arithmetic would differ by ~1e-8 relative; contraction into an
    // FMA by ~1 ulp of a*a relative to the result.
    assert!(
        worst < 1e-14,
        "worst relative difference {worst:e}: not f64 arithmetic"
    );
}
