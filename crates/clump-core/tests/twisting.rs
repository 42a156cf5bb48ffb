//! Twisting resistance (`contact::twisting`, Marshall 2009): a sphere
//! resting on a plane and spinning about the normal spins down as the
//! closed forms say — at the constant rate `M_max/I` while the contact
//! slips, as a damped torsional oscillator while it sticks.

use clump_validate::twisting::spin_down;

/// While the contact slips the couple is `−M_max`: the spin falls at
/// exactly `M_max/I` (after the spring's short build-up at the start).
#[test]
fn slipping_spin_decays_linearly() {
    let dt = 1e-5;
    let w0 = 50.0;
    let (sd, rows) = spin_down(w0, dt, 0.3, 1000).unwrap();
    let t_stop = sd.inertia * w0 / sd.m_max;
    let rate = sd.m_max / sd.inertia;
    // every 10 ms from 10 ms on: the rate between rows
    let mut worst = 0.0f64;
    for w in rows.windows(2).skip(1) {
        let measured = (w[0].1 - w[1].1) / (w[1].0 - w[0].0);
        worst = worst.max((measured - rate).abs() / rate);
    }
    eprintln!(
        "twisting, slipping: M_max = {:.4e} N m, I = {:.4e} kg m², rate M_max/I = {rate:.6e} rad/s², stops at {t_stop:.4} s; largest relative departure of the rate {worst:.2e} over {} rows",
        sd.m_max,
        sd.inertia,
        rows.len()
    );
    assert!(t_stop > 0.35, "the run must stay in the slipping phase");
    assert!(rows.last().unwrap().1 < 0.3 * w0, "it spins down");
    assert!(worst < 1e-9, "{worst:e}");
}

/// While the contact sticks the spin rings down as the damped torsional
/// oscillator `Iθ'' + γ_tw θ' + k_tw θ = 0`; the departure is the time
/// step's (it shrinks with `dt`).
#[test]
fn sticking_spin_rings_down_as_a_damped_oscillator() {
    let w0 = 0.5;
    let run = |dt: f64| {
        let (sd, rows) = spin_down(w0, dt, 0.3, (1e-3 / dt) as usize).unwrap();
        let mut worst = 0.0f64;
        let mut crossings = 0;
        for w in rows.windows(2) {
            let (t, om) = w[1];
            worst = worst.max((om - sd.sticking(w0, t)).abs() / w0);
            crossings += (w[0].1 > 0.0 && om <= 0.0) as usize;
        }
        (sd, worst, crossings)
    };
    let (sd, e1, crossings) = run(1e-5);
    let (_, e4, _) = run(2.5e-6);
    // the spring never reaches the slider's limit
    let amp = w0 * (sd.k * sd.inertia).sqrt() + sd.c * w0;
    assert!(amp < 0.8 * sd.m_max, "{amp:e} vs {:e}", sd.m_max);
    eprintln!(
        "twisting, sticking: ω_n = {:.3} rad/s, ζ = {:.3e}; {crossings} periods; largest |ω − ω_closed|/ω₀ = {e1:.2e} (dt = 1e-5 s), {e4:.2e} (dt/4)",
        (sd.k / sd.inertia).sqrt(),
        sd.c / (2.0 * (sd.k * sd.inertia).sqrt())
    );
    assert!(crossings >= 3);
    assert!(e1 < 2e-3, "{e1:e}");
    assert!(e4 < 0.35 * e1, "{e4:e} vs {e1:e}");
}
