//! The C API of Clump (`libclump_capi`, header `include/clump.h`, generated
//! by cbindgen; docs/c_api.md): a scenario's run driven by a host program,
//! such as a CFD code in a coupling loop. A `ClumpSim` handle holds the run
//! (the runner of `clump run`, stepped as the Python package steps it, so a
//! run cut into pieces gives the bits of one `clump run`), its last error
//! message, and the id order of its bodies.
//!
//! Every function returns a status code (`CLUMP_OK` or a `CLUMP_ERR_…`)
//! and keeps the message of a failure in the handle
//! ([`clump_sim_error_message`]). No function unwinds into the host: each
//! body runs inside `catch_unwind`, and a panic comes back as
//! `CLUMP_ERR_PANIC` with its message.
//!
//! Arrays cross the boundary as flat `double` arrays in *id order*: body
//! `k` is the body with the `k`-th smallest id (`clump_sim_body_ids`), sphere
//! `k` the sphere with the `k`-th smallest sphere id; vectors are 3
//! consecutive values (x, y, z, world frame), quaternions 4 (w, x, y, z).
//! The order changes only when bodies are inserted or removed.

mod arrays;
mod fields;
mod handle;

pub use arrays::*;
pub use fields::*;
pub use handle::*;

/// Success.
pub const CLUMP_OK: i32 = 0;
/// A pointer argument was NULL.
pub const CLUMP_ERR_NULL: i32 = 1;
/// The scenario or checkpoint cannot be used (the message names the file,
/// line and key).
pub const CLUMP_ERR_SCENARIO: i32 = 2;
/// An argument is out of range (a length, a non-finite value, a void
/// fraction outside (0, 1], a mode).
pub const CLUMP_ERR_VALUE: i32 = 3;
/// The run failed while stepping or writing (an I/O error).
pub const CLUMP_ERR_RUNTIME: i32 = 4;
/// The run became unstable (the message says which body and why).
pub const CLUMP_ERR_UNSTABLE: i32 = 5;
/// The handle holds no simulation (none loaded, or loading failed).
pub const CLUMP_ERR_NO_SIMULATION: i32 = 6;
/// Clump panicked: a bug; the handle should be freed.
pub const CLUMP_ERR_PANIC: i32 = 7;

/// External loads that act at every step until set again.
pub const CLUMP_LOAD_PERSISTENT: i32 = 0;
/// External loads that act in the next step only.
pub const CLUMP_LOAD_NEXT_STEP: i32 = 1;

/// Body field: centre of mass, m (3 per body).
pub const CLUMP_BODY_POSITION: i32 = 0;
/// Body field: centre-of-mass velocity, m/s (3 per body).
pub const CLUMP_BODY_VELOCITY: i32 = 1;
/// Body field: angular velocity, rad/s (3 per body).
pub const CLUMP_BODY_ANGULAR_VELOCITY: i32 = 2;
/// Body field: orientation body → world, unit quaternion w, x, y, z (4 per body).
pub const CLUMP_BODY_ORIENTATION: i32 = 3;
/// Body field: mass, kg (1 per body).
pub const CLUMP_BODY_MASS: i32 = 4;
/// Body field: total force of the last step (contacts, gravity, fluid,
/// external), N (3 per body).
pub const CLUMP_BODY_FORCE: i32 = 5;
/// Body field: total torque of the last step about the centre of mass, N m (3 per body).
pub const CLUMP_BODY_TORQUE: i32 = 6;
/// Body field: fluid force of the last step (drag, buoyancy, pressure
/// gradient), N (3 per body; zeros without a fluid).
pub const CLUMP_BODY_FLUID_FORCE: i32 = 7;
/// Body field: volume, m³ (1 per body: the union of its spheres).
pub const CLUMP_BODY_VOLUME: i32 = 8;

/// Sphere field: centre, m (3 per sphere).
pub const CLUMP_SPHERE_POSITION: i32 = 0;
/// Sphere field: velocity of the centre, v + ω × (x − x_cm), m/s (3 per sphere).
pub const CLUMP_SPHERE_VELOCITY: i32 = 1;
/// Sphere field: radius, m (1 per sphere).
pub const CLUMP_SPHERE_RADIUS: i32 = 2;
