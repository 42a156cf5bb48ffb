//! The device's f64 sine and cosine (shaders/rotation.wgsl `sin_cos_f64`:
//! WGSL's sin and cos are not defined for f64 on Vulkan) against the CPU's
//! libm, over the angles a rotation can take, to a few ulp.

const KERNEL: &str = r#"
@compute @workgroup_size(64)
fn probe(@builtin(global_invocation_id) gid: vec3<u32>) {
    let n = arrayLength(&pf) / 3u;
    let i = gid.x;
    if (i >= n) { return; }
    let sc = sin_cos_f64(pf[3u * i]);
    pf[3u * i + 1u] = sc.x;
    pf[3u * i + 2u] = sc.y;
}
"#;

#[test]
fn sin_cos_f64_is_within_a_few_ulp_of_libm() {
    let gpu = clump_gpu::Gpu::new().unwrap_or_else(|e| panic!("{e}"));
    let src = [
        include_str!("../src/shaders/common.wgsl"),
        include_str!("../src/shaders/rotation.wgsl"),
        KERNEL,
    ]
    .concat();
    let xs: Vec<f64> = (0..4096)
        .map(|k| (k as f64 - 2048.0) * 0.0123456789 + 1e-3 * (k as f64).sin())
        .collect();
    let data: Vec<f64> = xs.iter().flat_map(|&x| [x, 0.0, 0.0]).collect();
    let buf = gpu.buffer("pf", &data);
    let p = gpu.pipeline("probe", &src, "probe");
    let bg = gpu.bind(&p, &[&buf]);
    let mut enc = gpu.device.create_command_encoder(&Default::default());
    {
        let mut pass = enc.begin_compute_pass(&Default::default());
        pass.set_pipeline(&p);
        pass.set_bind_group(0, &bg, &[]);
        pass.dispatch_workgroups(xs.len().div_ceil(64) as u32, 1, 1);
    }
    gpu.queue.submit(Some(enc.finish()));
    let out: Vec<f64> = gpu.read(&buf).unwrap();
    let mut worst = 0.0f64;
    for (k, &x) in xs.iter().enumerate() {
        let (s, c) = x.sin_cos();
        // absolute error in units of the ulp of 1 (sin and cos are at most 1)
        let e = ((out[3 * k + 1] - s).abs().max((out[3 * k + 2] - c).abs())) / f64::EPSILON;
        worst = worst.max(e);
    }
    eprintln!(
        "largest |device - libm| over {} angles in [-25.3, 25.3] rad: {worst:.2} ulp of 1",
        xs.len()
    );
    assert!(worst <= 2.0, "{worst} ulp");
}
