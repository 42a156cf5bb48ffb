//! The t_handle example (examples/t_handle.toml, the Dzhanibekov flip)
//! against the closed form of the torque-free asymmetric top (Landau &
//! Lifshitz, Mechanics §37): with principal moments I1 < I2 < I3, energy E
//! and |L|, the body-frame angular velocity is a Jacobi elliptic motion of
//! modulus k with time scale 1/λ, and the intermediate component ω2 (an
//! `sn`) changes sign every 2K(k)/λ: that is the flip interval.

mod support;
use clump_io::run::{RunOptions, Runner};
use clump_io::scenario;
use std::path::Path;

/// Complete elliptic integral of the first kind K(k) = π / (2 AGM(1, √(1−k²))).
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    // quadratic convergence: 40 rounds reach round-off for any k < 1
    for _ in 0..40 {
        let an = 0.5 * (a + b);
        b = (a * b).sqrt();
        a = an;
    }
    std::f64::consts::PI / (2.0 * a)
}

/// Time between sign changes of ω2 for moments `i` (ascending) and
/// body-frame angular velocity `w`.
fn flip_interval(i: [f64; 3], w: [f64; 3]) -> f64 {
    let [i1, i2, i3] = i;
    let l2 = (0..3).map(|k| (i[k] * w[k]).powi(2)).sum::<f64>();
    let e2 = (0..3).map(|k| i[k] * w[k] * w[k]).sum::<f64>(); // 2E
    let (lambda, k2) = if l2 > e2 * i2 {
        (
            ((i3 - i2) * (l2 - e2 * i1) / (i1 * i2 * i3)).sqrt(),
            (i2 - i1) * (e2 * i3 - l2) / ((i3 - i2) * (l2 - e2 * i1)),
        )
    } else {
        (
            ((i2 - i1) * (e2 * i3 - l2) / (i1 * i2 * i3)).sqrt(),
            (i3 - i2) * (l2 - e2 * i1) / ((i2 - i1) * (e2 * i3 - l2)),
        )
    };
    2.0 * elliptic_k(k2.sqrt()) / lambda
}

#[test]
fn t_handle_flips_at_the_elliptic_function_period() {
    let ex = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/t_handle.toml");
    let sc = scenario::load(&ex).unwrap_or_else(|e| panic!("{e}"));
    let moments = sc.templates[0].template.principal_inertia;
    let out = std::env::temp_dir().join(format!("clump_t_handle_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let mut run = Runner::new(sc, &out).unwrap();
    run.run(RunOptions::default()).unwrap();
    // the example starts at ω_b = (0.01, 20, 0.01) rad/s, identity orientation
    let theory = flip_interval(moments.to_array(), [0.01, 20.0, 0.01]);
    let text = std::fs::read_to_string(out.join("traj_1.csv")).unwrap();
    let header: Vec<&str> = text.lines().next().unwrap().split(',').collect();
    let (ct, cw) = (
        header.iter().position(|c| *c == "time").unwrap(),
        header.iter().position(|c| *c == "wby").unwrap(),
    );
    let rows: Vec<(f64, f64)> = text
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
            (v[ct], v[cw])
        })
        .collect();
    let crossings: Vec<f64> = rows
        .windows(2)
        .filter(|p| p[0].1.signum() != p[1].1.signum())
        .map(|p| p[0].0 + (p[1].0 - p[0].0) * p[0].1 / (p[0].1 - p[1].1))
        .collect();
    let intervals: Vec<f64> = crossings.windows(2).map(|c| c[1] - c[0]).collect();
    eprintln!("t_handle: moments {moments}, flip interval theory 2K/λ = {theory:.6} s, measured {intervals:?}");
    assert!(intervals.len() >= 2, "{crossings:?}");
    for dt in intervals {
        assert!((dt - theory).abs() < 1e-5 * theory, "{dt} vs {theory}");
    }
    assert_eq!(support::last_value(&out.join("traj_1.csv"), "time"), 6.0);
}
