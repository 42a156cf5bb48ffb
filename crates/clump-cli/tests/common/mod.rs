//! A small scenario shared by the fault and output tests: 20 tetrahedral
//! clumps packed in a box fall onto a floor.

/// The scenario text: `steps` steps of 2e-5 s; `output` is the body of its
/// `[output]` table.
pub fn fall(steps: u64, output: &str) -> String {
    format!(
        r#"
[simulation]
dt = 2e-5
steps = {steps}

[domain]
lo = [-0.03, -0.03, -0.01]
hi = [0.03, 0.03, 0.1]

[[material]]
name = "rock"
youngs_modulus = 5e6
poisson_ratio = 0.3
density = 2500

[contact]
restitution = 0.3
friction = 0.5

[[template]]
name = "tetra"
material = "rock"
shape = "tetrahedron"
radius = 0.002
edge = 0.0025

[[wall]]
name = "floor"
material = "rock"
type = "plane"
point = [0.0, 0.0, 0.0]
normal = [0.0, 0.0, 1.0]

[[insert]]
kind = "pack"
template = "tetra"
count = 20
region = {{ type = "box", lo = [-0.02, -0.02, 0.005], hi = [0.02, 0.02, 0.05] }}
seed = 3

[output]
{output}"#
    )
}
