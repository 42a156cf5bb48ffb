// Bindings shared by every kernel of the device step (one bind group, one
// layout): the SoA arrays described in ARCHITECTURE.md, "The device path".
// Vectors are stored as 3 (or 4, quaternions x y z w) consecutive f64s.
// All arithmetic is written out in glam's operation order (dot, cross,
// matrix product, quaternion to matrix) so that the device computes what
// the CPU path computes, operation for operation.

@group(0) @binding(0) var<storage, read_write> pf: array<f64>;    // float parameters (PF_*)
@group(0) @binding(1) var<storage, read_write> pu: array<u32>;    // integer parameters and counters (PU_*)
@group(0) @binding(2) var<storage, read_write> bx: array<f64>;    // body centre of mass, world, m (3/body)
@group(0) @binding(3) var<storage, read_write> bv: array<f64>;    // velocity, world, m/s (3/body)
@group(0) @binding(4) var<storage, read_write> bq: array<f64>;    // orientation body->world, x y z w (4/body)
@group(0) @binding(5) var<storage, read_write> bl: array<f64>;    // angular momentum, world, kg m^2/s (3/body)
@group(0) @binding(6) var<storage, read_write> bw: array<f64>;    // angular velocity, world, rad/s (3/body)
@group(0) @binding(7) var<storage, read_write> bft: array<f64>;   // force N, torque N m, world (6/body)
@group(0) @binding(8) var<storage, read_write> bm: array<f64>;    // mass, I (3), 1/I (3), dt/(2m), DOF flag bits and driven bit 6 (9/body)
@group(0) @binding(9) var<storage, read_write> bfirst: array<u32>; // first sphere of each body (nb+1)
@group(0) @binding(10) var<storage, read_write> sown: array<u32>; // owner body, material (2/sphere)
@group(0) @binding(11) var<storage, read_write> sref: array<f64>; // body-frame offset (3), radius (4/sphere)
@group(0) @binding(12) var<storage, read_write> sx: array<f64>;   // sphere centre, world, m (3/sphere)
@group(0) @binding(13) var<storage, read_write> sarm: array<f64>; // sphere centre - body centre, world (3/sphere)
@group(0) @binding(14) var<storage, read_write> keys: array<u32>; // cell key per sorted slot (npow2)
@group(0) @binding(15) var<storage, read_write> idx: array<u32>;  // sphere per sorted slot (npow2)
@group(0) @binding(16) var<storage, read_write> cells: array<u32>; // first, end slot per cell (2/cell)
@group(0) @binding(17) var<storage, read_write> noff: array<u32>; // neighbour count, then offset (ns+1)
@group(0) @binding(18) var<storage, read_write> nbr: array<u32>;  // neighbour sphere per entry (cap)
@group(0) @binding(19) var<storage, read_write> hist: array<f64>; // tangential spring, world, m (3), EPSD rolling spring, world, N m (3) (6/entry)
@group(0) @binding(20) var<storage, read_write> old_off: array<u32>; // last step's noff
@group(0) @binding(21) var<storage, read_write> old_nbr: array<u32>; // last step's nbr
@group(0) @binding(22) var<storage, read_write> old_hist: array<f64>; // last step's hist (6/entry)
@group(0) @binding(23) var<storage, read_write> mirror: array<u32>; // entry (j,i) of entry (i,j), j < i
@group(0) @binding(24) var<storage, read_write> pout: array<f64>; // force on i, torque on i's and j's body (9/entry)
@group(0) @binding(25) var<storage, read_write> sft: array<f64>;  // pair force, torque, wall force, torque (12/sphere)
@group(0) @binding(26) var<storage, read_write> walls: array<f64>; // per step of a submission, per wall: geometry, motion (walls.wgsl, WALL_ROW/wall)
@group(0) @binding(27) var<storage, read_write> whist: array<f64>; // wall tangential (3) and rolling (3) spring (6/(sphere, wall face))
@group(0) @binding(28) var<storage, read_write> laws: array<f64>; // SlidingLaw, rolling law per material pair (LAW_ROW/pair)
@group(0) @binding(29) var<storage, read_write> sx0: array<f64>;  // sphere centre at the last table build (3/sphere)

const PF_DT: u32 = 0u;
const PF_G: u32 = 1u;       // gravity, 3
const PF_LO: u32 = 4u;      // grid origin, 3
const PF_CELL: u32 = 7u;    // cell size
const PF_SKIN: u32 = 8u;    // Verlet skin, m
const PU_NB: u32 = 0u;
const PU_NS: u32 = 1u;
const PU_NPOW2: u32 = 2u;
const PU_GRID: u32 = 3u;    // nx, ny, nz
const PU_CAP: u32 = 6u;
const PU_NW: u32 = 7u;
const PU_NMAT: u32 = 8u;
const PU_SORT_K: u32 = 9u;
const PU_SORT_J: u32 = 10u;
const PU_OVERFLOW: u32 = 11u; // 1: a sphere had more than MAXN neighbours, 2: the table exceeded cap
const PU_ROT: u32 = 12u;      // rotation scheme: 0 richardson_liggghts, 1 no_squish, 2 richardson
const PU_STALE: u32 = 13u;    // 1: a sphere moved more than half the skin since the last build
const PU_BUILDS: u32 = 14u;   // table builds so far
const PU_WSTEP: u32 = 15u;    // this step's row set of `walls` (walls.wgsl)
const PU_NWF: u32 = 16u;      // wall contact slots per sphere (walls.rs faces)
// pf 9-14 and pu 17: periodic.wgsl
const MAXN: u32 = 32u;
const WG: u32 = 64u;

// 3-vector loads and stores per array (WGSL passes no storage pointers).
fn ld_bl(i: u32) -> vec3<f64> { return vec3<f64>(bl[3u * i], bl[3u * i + 1u], bl[3u * i + 2u]); }
fn st_bl(i: u32, v: vec3<f64>) { bl[3u * i] = v.x; bl[3u * i + 1u] = v.y; bl[3u * i + 2u] = v.z; }
fn ld_bv(i: u32) -> vec3<f64> { return vec3<f64>(bv[3u * i], bv[3u * i + 1u], bv[3u * i + 2u]); }
fn st_bv(i: u32, v: vec3<f64>) { bv[3u * i] = v.x; bv[3u * i + 1u] = v.y; bv[3u * i + 2u] = v.z; }
fn ld_bw(i: u32) -> vec3<f64> { return vec3<f64>(bw[3u * i], bw[3u * i + 1u], bw[3u * i + 2u]); }
fn st_bw(i: u32, v: vec3<f64>) { bw[3u * i] = v.x; bw[3u * i + 1u] = v.y; bw[3u * i + 2u] = v.z; }
fn ld_bx(i: u32) -> vec3<f64> { return vec3<f64>(bx[3u * i], bx[3u * i + 1u], bx[3u * i + 2u]); }
fn st_bx(i: u32, v: vec3<f64>) { bx[3u * i] = v.x; bx[3u * i + 1u] = v.y; bx[3u * i + 2u] = v.z; }
// a contact's springs: the tangential one at 6 i, the rolling one at 6 i + 3
fn ld_hist(i: u32) -> vec3<f64> { return vec3<f64>(hist[6u * i], hist[6u * i + 1u], hist[6u * i + 2u]); }
fn st_hist(i: u32, v: vec3<f64>) { hist[6u * i] = v.x; hist[6u * i + 1u] = v.y; hist[6u * i + 2u] = v.z; }
fn ld_roll(i: u32) -> vec3<f64> { return vec3<f64>(hist[6u * i + 3u], hist[6u * i + 4u], hist[6u * i + 5u]); }
fn st_roll(i: u32, v: vec3<f64>) { hist[6u * i + 3u] = v.x; hist[6u * i + 4u] = v.y; hist[6u * i + 5u] = v.z; }
fn ld_sx0(i: u32) -> vec3<f64> { return vec3<f64>(sx0[3u * i], sx0[3u * i + 1u], sx0[3u * i + 2u]); }
fn st_sx0(i: u32, v: vec3<f64>) { sx0[3u * i] = v.x; sx0[3u * i + 1u] = v.y; sx0[3u * i + 2u] = v.z; }
fn ld_old_hist(i: u32) -> vec3<f64> { return vec3<f64>(old_hist[6u * i], old_hist[6u * i + 1u], old_hist[6u * i + 2u]); }
fn ld_old_roll(i: u32) -> vec3<f64> { return vec3<f64>(old_hist[6u * i + 3u], old_hist[6u * i + 4u], old_hist[6u * i + 5u]); }
fn st_old_springs(i: u32, h: vec3<f64>, r: vec3<f64>) {
    old_hist[6u * i] = h.x; old_hist[6u * i + 1u] = h.y; old_hist[6u * i + 2u] = h.z;
    old_hist[6u * i + 3u] = r.x; old_hist[6u * i + 4u] = r.y; old_hist[6u * i + 5u] = r.z;
}
fn ld_sarm(i: u32) -> vec3<f64> { return vec3<f64>(sarm[3u * i], sarm[3u * i + 1u], sarm[3u * i + 2u]); }
fn st_sarm(i: u32, v: vec3<f64>) { sarm[3u * i] = v.x; sarm[3u * i + 1u] = v.y; sarm[3u * i + 2u] = v.z; }
fn ld_sx(i: u32) -> vec3<f64> { return vec3<f64>(sx[3u * i], sx[3u * i + 1u], sx[3u * i + 2u]); }
fn st_sx(i: u32, v: vec3<f64>) { sx[3u * i] = v.x; sx[3u * i + 1u] = v.y; sx[3u * i + 2u] = v.z; }
fn ld_whist(i: u32) -> vec3<f64> { return vec3<f64>(whist[6u * i], whist[6u * i + 1u], whist[6u * i + 2u]); }
fn st_whist(i: u32, v: vec3<f64>) { whist[6u * i] = v.x; whist[6u * i + 1u] = v.y; whist[6u * i + 2u] = v.z; }
fn ld_wroll(i: u32) -> vec3<f64> { return vec3<f64>(whist[6u * i + 3u], whist[6u * i + 4u], whist[6u * i + 5u]); }
fn st_wroll(i: u32, v: vec3<f64>) { whist[6u * i + 3u] = v.x; whist[6u * i + 4u] = v.y; whist[6u * i + 5u] = v.z; }
// glam DVec3::dot: (x x' + y y') + z z'
fn dot3(a: vec3<f64>, b: vec3<f64>) -> f64 {
    return (a.x * b.x + a.y * b.y) + a.z * b.z;
}
// glam DVec3::cross
fn cross3(a: vec3<f64>, b: vec3<f64>) -> vec3<f64> {
    return vec3<f64>(a.y * b.z - b.y * a.z, a.z * b.x - b.z * a.x, a.x * b.y - b.x * a.y);
}
struct Mat3 { x: vec3<f64>, y: vec3<f64>, z: vec3<f64> }
// glam DMat3::from_quat (columns)
fn mat_from_quat(q: vec4<f64>) -> Mat3 {
    let x2 = q.x + q.x;
    let y2 = q.y + q.y;
    let z2 = q.z + q.z;
    let xx = q.x * x2;
    let xy = q.x * y2;
    let xz = q.x * z2;
    let yy = q.y * y2;
    let yz = q.y * z2;
    let zz = q.z * z2;
    let wx = q.w * x2;
    let wy = q.w * y2;
    let wz = q.w * z2;
    let one = 1.0lf;
    return Mat3(vec3<f64>(one - (yy + zz), xy + wz, xz - wy),
                vec3<f64>(xy - wz, one - (xx + zz), yz + wx),
                vec3<f64>(xz + wy, yz - wx, one - (xx + yy)));
}
// glam DMat3 * DVec3: ((x_axis v.x) + (y_axis v.y)) + z_axis v.z
fn mat_mul(m: Mat3, v: vec3<f64>) -> vec3<f64> {
    return (m.x * v.x + m.y * v.y) + m.z * v.z;
}
// body b's force flags (bits 0-2) and torque flags (bits 3-5) per world
// axis (dof.rs, T-15): false freezes that component of v or L
fn dof_flags(b: u32) -> array<vec3<bool>, 2> {
    let f = u32(bm[9u * b + 8u]);
    return array<vec3<bool>, 2>(vec3<bool>((f & 1u) != 0u, (f & 2u) != 0u, (f & 4u) != 0u),
                                vec3<bool>((f & 8u) != 0u, (f & 16u) != 0u, (f & 32u) != 0u));
}
// body b is driven or fixed (bit 6; dof.rs DRIVEN): forces never act,
// it moves at its prescribed velocity and world angular velocity
fn driven(b: u32) -> bool {
    return (u32(bm[9u * b + 8u]) & 64u) != 0u;
}
fn ldq(i: u32) -> vec4<f64> {
    return vec4<f64>(bq[4u * i], bq[4u * i + 1u], bq[4u * i + 2u], bq[4u * i + 3u]);
}
