//! Verlet-skin rebuild trigger.
//!
//! The list must be rebuilt when any sphere moved more than `skin / 2` (m)
//! from its position at the last build. Measuring sphere centres (not body
//! centres) counts rotation: a sphere at distance R from the centre of mass
//! of a body that turns by an angle α moves by up to αR. The check runs in
//! the integration pass that moves the spheres
//! (`crate::step::integrate::initial`): first per body, from its pose now
//! and at the build ([`body_displacement_bound`]), which clears most bodies
//! without reading their spheres' reference positions; the spheres of a
//! body the bound does not clear take the exact test ([`moved_too_far`]).
//! The rebuilds come at the same steps as with the exact test alone.
//!
//! Unless the scenario fixes it, the skin follows the motion
//! ([`adapted_skin`]): a thick skin while the bed moves fast (fewer
//! rebuilds), a thin one once it has settled (fewer candidate pairs).

use glam::{DQuat, DVec3};

/// `(skin/2)²`, m², the squared displacement that triggers a rebuild.
#[inline(always)]
pub fn trigger_distance2(skin: f64) -> f64 {
    0.25 * skin * skin
}

/// True when a sphere now at `x` (world, m) moved farther than allowed from
/// its position `x_ref` at the last build; `limit2` from [`trigger_distance2`].
#[inline(always)]
pub fn moved_too_far(x: DVec3, x_ref: DVec3, limit2: f64) -> bool {
    x.distance_squared(x_ref) > limit2
}

/// An upper bound (m) on how far any sphere of a rigid body moved since the
/// last build, from the body's pose alone: centre `x` and orientation `q`
/// now, `x_ref` and `q_ref` at the build (world frame, body → world), the
/// farthest sphere centre `reach` (m) from the centre of mass.
///
/// A sphere at body-frame offset `b` moved by
/// `Δx + R(q_ref) (R(p) b − b)`, with `p = q_ref⁻¹ q` the rotation since the
/// build, and a rotation by θ moves `b` along a chord of length
/// `2 |sin(θ/2)| |b⊥| ≤ 2 |vec(p)| reach` (`|vec(p)| = |sin(θ/2)|` for a unit
/// quaternion, whatever its sign). So every sphere moved at most
/// `|Δx| + 2 reach |vec(p)|`: the skin check of a body reads its two poses,
/// not each sphere's reference position.
#[inline(always)]
pub fn body_displacement_bound(x: DVec3, q: DQuat, x_ref: DVec3, q_ref: DQuat, reach: f64) -> f64 {
    let (v, v_ref) = (
        DVec3::new(q.x, q.y, q.z),
        DVec3::new(q_ref.x, q_ref.y, q_ref.z),
    );
    // vector part of conj(q_ref) q
    let turn = q_ref.w * v - q.w * v_ref - v_ref.cross(v);
    (x - x_ref).length() + 2.0 * reach * turn.length()
}

/// True when a body whose spheres moved at most `bound` (m,
/// [`body_displacement_bound`]) surely has none beyond half the skin
/// `half_skin` (m) by the exact test [`moved_too_far`], rounding included:
/// the bound must stay below the limit by a relative 1e-9 and by 1e-12 of
/// `scale` (m, the largest coordinate of the body's centre plus its reach),
/// about a thousand times the rounding of a sphere's computed position.
/// Otherwise (also for a NaN bound) the caller runs the exact test, so the
/// two tests together trigger a rebuild at exactly the steps the exact test
/// alone would.
#[inline(always)]
pub fn surely_within(bound: f64, half_skin: f64, scale: f64) -> bool {
    bound < half_skin * (1.0 - 1e-9) - 1e-12 * scale
}

/// Default skin as a fraction of the smallest sphere radius: the skin of
/// the first neighbour build.
pub const SKIN_DEFAULT: f64 = 0.2;
/// Thinnest adapted skin, fraction of the smallest sphere radius.
pub const SKIN_MIN: f64 = 0.05;
/// Thickest adapted skin, fraction of the largest sphere radius (LIGGGHTS'
/// tetra-bed input uses 0.5), further limited so that a periodic axis keeps
/// three neighbour cells ([`crate::world::World::max_adapted_skin`]).
pub const SKIN_MAX: f64 = 0.5;
/// `2 R / c` of the cost model in [`adapted_skin`] for clumps of `k`
/// spheres, in units of the smallest radius: a rebuild costs `R` steps, and
/// the candidate pairs of a skin one radius thick cost `c` steps' work.
///
/// Both depend on the shape. On a clump of a few spheres the neighbour
/// search scans the spheres of the 27 cells around each sphere; clumps of
/// many spheres are searched by body pairs ([`super::body_search`]), so `R`
/// grows far less with `k` than the spheres in a cell do. The candidates
/// of many-sphere clumps are mostly buried inside their clump, with no
/// partner across a gap, so `c` does not grow with `k` either. Measured
/// in phase B (one thread):
///
/// | bed | k | R, steps | c, steps per r_min of skin | 2R/c |
/// |---|---|---|---|---|
/// | settled tetra bed, 2 000 clumps | 4 | 13 | 0.66 | 39 |
/// | stone pile, 200 stones | 50 | 11 | | 50 |
///
/// The tetra bed's point is from `clump bench` at two skins (its stage
/// shares and rebuild counts). The stone pile's `R` is from its stage
/// shares (62 rebuilds at 6.8 % of phase B); its `2R/c` is the fastest of
/// the skins an in-process A/B compared (2R/c of 20 to 144 against 288,
/// the old model's: 50 ran 5.7 % faster on one thread and 3.8 % on two).
/// The line through the two points, `2R/c = 38.94 + 0.240 (k − 4)`, is
/// used for every `k`; a bed of single spheres gets 38.2. Only the speed
/// depends on it: any skin gives the same contacts.
fn skin_cost(k: usize) -> f64 {
    // (k, 2R/c) of the tetra bed and of the stone pile
    const TETRA: (f64, f64) = (4.0, 38.94);
    const STONES: (f64, f64) = (50.0, 50.0);
    let slope = (STONES.1 - TETRA.1) / (STONES.0 - TETRA.0);
    TETRA.1 + (k as f64 - TETRA.0) * slope
}

/// The skin (m) for the next neighbour list, from the motion since the last
/// build: the largest sphere displacement `d_max` (m) over `steps` steps,
/// for clumps of up to `k` spheres.
///
/// With the spheres moving at up to `u = d_max/steps` per step, a list of
/// skin `s` lasts `s/(2u)` steps; per step it costs a rebuild share
/// `2uR/s` plus candidate pairs `c s`. The sum is least at
/// `s = √(2Ru/c)` (`skin_cost`), clamped to [`SKIN_MIN`] times the
/// smallest radius `r_min` (m) below and to `s_max` (m) above. Depends only
/// on the state and the templates, so every thread count, every rank count
/// and a restarted run choose the same skin.
pub fn adapted_skin(r_min: f64, s_max: f64, d_max: f64, steps: u64, k: usize) -> f64 {
    let u = d_max / steps.max(1) as f64;
    let s = (skin_cost(k) * u * r_min).sqrt();
    s.min(s_max).max(SKIN_MIN * r_min)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The optimum of the cost model, and its clamps: a settled bed gets
    /// the thinnest skin, a fast one the thickest, and in between the skin
    /// grows with the square root of the speed, thicker for clumps of many
    /// spheres (whose rebuilds cost more steps).
    #[test]
    fn skin_follows_the_motion() {
        let (r, top) = (1e-3, 2e-3);
        assert_eq!(adapted_skin(r, top, 1e-9, 1000, 4), SKIN_MIN * r);
        assert_eq!(adapted_skin(r, top, 1e-2, 10, 4), top);
        // u = 1e-7 m per step, k = 4: s = √(38.94 · 1e-7 · 1e-3)
        let s = adapted_skin(r, top, 1e-5, 100, 4);
        assert!((s - (38.94f64 * 1e-10).sqrt()).abs() < 1e-12, "{s}");
        let s4 = adapted_skin(r, top, 4e-5, 100, 4);
        assert!((s4 / s - 2.0).abs() < 1e-12);
        let stone = adapted_skin(r, top, 1e-5, 100, 50);
        assert!((stone / s - (50.0f64 / 38.94).sqrt()).abs() < 1e-12);
    }

    /// The body bound holds for every sphere of random rigid motions, and
    /// is reached where the geometry says it should be: a pure turn by θ
    /// moves a sphere at distance R perpendicular to the axis along the
    /// chord 2 R sin(θ/2), and a pure shift moves every sphere by the shift.
    #[test]
    fn body_bound_covers_every_sphere_and_is_tight() {
        use glam::{DMat3, DQuat};
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let unit = |rng: &mut rand_chacha::ChaCha8Rng| {
            DVec3::new(
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
                rng.gen_range(-1.0..1.0),
            )
        };
        for _ in 0..2000 {
            let offsets: Vec<DVec3> = (0..5).map(|_| unit(&mut rng) * 0.01).collect();
            let reach = offsets.iter().map(|o| o.length()).fold(0.0, f64::max);
            let x0 = unit(&mut rng);
            let q0 = DQuat::from_scaled_axis(unit(&mut rng) * 3.0);
            let x1 = x0 + unit(&mut rng) * rng.gen_range(0.0..0.02);
            let turn = DQuat::from_scaled_axis(unit(&mut rng) * rng.gen_range(0.0..3.0));
            // either sign of the stored quaternion is the same orientation
            let q1 = if rng.gen_bool(0.5) {
                turn * q0
            } else {
                -(turn * q0)
            };
            let bound = body_displacement_bound(x1, q1, x0, q0, reach);
            let (r0, r1) = (DMat3::from_quat(q0), DMat3::from_quat(q1));
            for &b in &offsets {
                let moved = (x1 + r1 * b).distance(x0 + r0 * b);
                assert!(moved <= bound * (1.0 + 1e-12), "{moved} > {bound}");
            }
        }
        let (r, theta) = (0.003, 0.4);
        let q0 = DQuat::from_rotation_y(0.7);
        let q1 = DQuat::from_rotation_z(theta) * q0;
        let chord = 2.0 * r * (0.5 * theta).sin();
        let b = body_displacement_bound(DVec3::ZERO, q1, DVec3::ZERO, q0, r);
        assert!((b - chord).abs() < 1e-15, "{b} against {chord}");
        let shift = DVec3::new(1e-4, -2e-4, 3e-4);
        let b = body_displacement_bound(shift, q0, DVec3::ZERO, q0, r);
        assert!((b - shift.length()).abs() < 1e-18, "{b}");
        // the exact test decides near the limit, and a NaN never passes
        assert!(surely_within(0.999e-4, 1e-4, 1.0));
        assert!(!surely_within(1e-4 * (1.0 - 1e-10), 1e-4, 1.0));
        assert!(!surely_within(f64::NAN, 1e-4, 1.0));
    }
}
