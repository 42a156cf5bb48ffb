//! Coarse-grained continuum fields of one frame, clump-aware (Weinhart et
//! al. 2012; Goldhirsch 2010; docs/theory.md "Coarse-grained fields"):
//! density, momentum, velocity, kinetic, contact and total stress, fabric,
//! the orientation order tensor of the bodies' long axes, the
//! coordination number and the void fraction, as cell averages on a 1D,
//! 2D or 3D grid.
//!
//! Each body deposits at its centre of mass. The contact stress takes, for
//! every contact and each body on it, the force on that body and the
//! branch vector `l` from the body's centre of mass to the contact point,
//! spread along `l`: a clump with several contacts is right, and a wall
//! contact counts on the body side only, so momentum balance closes at the
//! walls. Stress is compressive positive:
//! `σ = Σ_a m_a v'_a ⊗ v'_a φ_a − Σ_a Σ_c f_c ⊗ l_c ∫₀¹ φ(r − r_a − s l_c) ds`.

use super::frame::{min_image, Frame, Side};
use super::grid::Grid;
use glam::{DMat3, DVec3};

/// The fields on a grid, one value per cell (row-major over the grid's
/// axes, the first axis slowest).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Fields {
    /// Mass density, kg/m³.
    pub density: Vec<f64>,
    /// Momentum density, kg/(m² s).
    pub momentum: Vec<DVec3>,
    /// Kinetic stress `Σ m v ⊗ v φ − p ⊗ p / ρ`, Pa.
    pub kinetic_stress: Vec<DMat3>,
    /// Contact stress, Pa (compressive positive).
    pub contact_stress: Vec<DMat3>,
    /// Contact density `Σ_c φ(r − x_c)` and fabric `Σ_c n ⊗ n φ(r − x_c)`
    /// (1/m³), pair and wall contacts.
    pub contact_density: Vec<f64>,
    /// See [`Self::contact_density`].
    pub fabric_density: Vec<DMat3>,
    /// Number density of bodies, 1/m³.
    pub number_density: Vec<f64>,
    /// `Σ_a (3/2 u_a ⊗ u_a − 1/2 I) φ_a` with the long axis `u_a`, 1/m³.
    pub order_density: Vec<DMat3>,
    /// `Σ_a z_a φ_a` with the coordination number `z_a`, 1/m³.
    pub coordination_density: Vec<f64>,
    /// Solid volume fraction `Σ_a V_a φ_a` with the volume `V_a` of body
    /// `a`'s sphere union (the coarse-graining kernel's void fraction,
    /// T-84: `ε = 1 − Σ_a V_a φ_a`).
    pub solid_fraction: Vec<f64>,
}

impl Fields {
    /// Zeroed fields for `n` cells.
    pub fn zeros(n: usize) -> Fields {
        Fields {
            density: vec![0.0; n],
            momentum: vec![DVec3::ZERO; n],
            kinetic_stress: vec![DMat3::ZERO; n],
            contact_stress: vec![DMat3::ZERO; n],
            contact_density: vec![0.0; n],
            fabric_density: vec![DMat3::ZERO; n],
            number_density: vec![0.0; n],
            order_density: vec![DMat3::ZERO; n],
            coordination_density: vec![0.0; n],
            solid_fraction: vec![0.0; n],
        }
    }

    /// Void fraction `1 − Σ_a V_a φ_a` (T-84); below 0 only where the
    /// kernel is narrower than the bodies' overlap allows.
    pub fn void_fraction(&self) -> Vec<f64> {
        self.solid_fraction.iter().map(|&s| 1.0 - s).collect()
    }

    /// Velocity `p/ρ` per cell (zero where the density is zero), m/s.
    pub fn velocity(&self) -> Vec<DVec3> {
        self.density
            .iter()
            .zip(&self.momentum)
            .map(|(&r, &p)| if r > 0.0 { p / r } else { DVec3::ZERO })
            .collect()
    }

    /// Total stress, kinetic plus contact, Pa.
    pub fn stress(&self) -> Vec<DMat3> {
        self.kinetic_stress
            .iter()
            .zip(&self.contact_stress)
            .map(|(a, b)| *a + *b)
            .collect()
    }

    /// Fabric tensor normalised to unit trace (isotropic: I/3); zero where
    /// there are no contacts.
    pub fn fabric(&self) -> Vec<DMat3> {
        self.contact_density
            .iter()
            .zip(&self.fabric_density)
            .map(|(&n, &f)| if n > 0.0 { f / n } else { DMat3::ZERO })
            .collect()
    }

    /// Orientation (nematic) order tensor, traceless (isotropic: 0).
    pub fn order(&self) -> Vec<DMat3> {
        self.number_density
            .iter()
            .zip(&self.order_density)
            .map(|(&n, &q)| if n > 0.0 { q / n } else { DMat3::ZERO })
            .collect()
    }

    /// Mean coordination number of the bodies.
    pub fn coordination(&self) -> Vec<f64> {
        self.number_density
            .iter()
            .zip(&self.coordination_density)
            .map(|(&n, &z)| if n > 0.0 { z / n } else { 0.0 })
            .collect()
    }

    /// The fields of fixed-point sums ([`deposit`]'s terms summed, T-74):
    /// each sum rounded once, the kinetic stress taken about the mean
    /// velocity.
    pub fn from_fixed(g: &super::fields_sum::FixedGrid) -> Fields {
        use field::*;
        let cells = g.cells();
        let mut out = Fields::zeros(cells);
        let vec3 = |c, f| DVec3::from_array(std::array::from_fn(|i| g.value(c, f, i)));
        let mat3 = |c, f| DMat3::from_cols_array(&std::array::from_fn(|i| g.value(c, f, i)));
        for c in 0..cells {
            out.density[c] = g.value(c, DENSITY, 0);
            out.momentum[c] = vec3(c, MOMENTUM);
            out.kinetic_stress[c] = mat3(c, KINETIC);
            out.contact_stress[c] = mat3(c, CONTACT);
            out.contact_density[c] = g.value(c, CONTACTS, 0);
            out.fabric_density[c] = mat3(c, FABRIC);
            out.number_density[c] = g.value(c, NUMBER, 0);
            out.order_density[c] = mat3(c, ORDER);
            out.coordination_density[c] = g.value(c, COORDINATION, 0);
            out.solid_fraction[c] = g.value(c, SOLID, 0);
        }
        out.about_mean_velocity();
        out
    }

    /// Takes the mean velocity's part `p ⊗ p / ρ` off the kinetic stress
    /// `Σ m v ⊗ v φ` (the stress about the local mean velocity).
    pub fn about_mean_velocity(&mut self) {
        for c in 0..self.density.len() {
            let r = self.density[c];
            if r > 0.0 {
                let p = self.momentum[c];
                self.kinetic_stress[c] -= DMat3::from_cols(p * p.x, p * p.y, p * p.z) / r;
            }
        }
    }

    /// Adds `other` times `k` (time averaging).
    pub fn add_scaled(&mut self, other: &Fields, k: f64) {
        fn add<T: Copy + std::ops::Add<Output = T> + std::ops::Mul<f64, Output = T>>(
            a: &mut [T],
            b: &[T],
            k: f64,
        ) {
            for (x, y) in a.iter_mut().zip(b) {
                *x = *x + *y * k;
            }
        }
        add(&mut self.density, &other.density, k);
        add(&mut self.momentum, &other.momentum, k);
        add(&mut self.kinetic_stress, &other.kinetic_stress, k);
        add(&mut self.contact_stress, &other.contact_stress, k);
        add(&mut self.contact_density, &other.contact_density, k);
        add(&mut self.fabric_density, &other.fabric_density, k);
        add(&mut self.number_density, &other.number_density, k);
        add(&mut self.order_density, &other.order_density, k);
        add(
            &mut self.coordination_density,
            &other.coordination_density,
            k,
        );
        add(&mut self.solid_fraction, &other.solid_fraction, k);
    }
}

/// Gauss–Legendre nodes and weights on [0, 1] (4 points).
const GL4: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
    (0.330_009_478_207_571_87, 0.326_072_577_431_273_07),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_07),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
];

/// The fields of `frame` on `grid` (contacts ignored when the frame has
/// none recorded): every body's and contact's terms summed in fixed point
/// ([`super::fields_sum`], T-74), so that the same terms give the same bits
/// in any order, also summed by ranks in pieces.
pub fn coarse_grain(frame: &Frame, grid: &Grid) -> Fields {
    let mut extent = super::fields_sum::Extent::default();
    deposit(frame, grid, None, &mut |k, _, v| extent.see(k, v));
    let mut sums = super::fields_sum::FixedGrid::new(grid.len(), &extent);
    deposit(frame, grid, None, &mut |k, cell, v| sums.add(k, cell, v));
    Fields::from_fixed(&sums)
}

/// The field indices of [`deposit`]'s terms, in [`Fields`]' order.
pub mod field {
    /// Mass density.
    pub const DENSITY: usize = 0;
    /// Momentum density.
    pub const MOMENTUM: usize = 1;
    /// Kinetic stress (`Σ m v ⊗ v φ`, before the mean velocity's part).
    pub const KINETIC: usize = 2;
    /// Contact stress.
    pub const CONTACT: usize = 3;
    /// Contact density.
    pub const CONTACTS: usize = 4;
    /// Fabric density.
    pub const FABRIC: usize = 5;
    /// Number density.
    pub const NUMBER: usize = 6;
    /// Order density.
    pub const ORDER: usize = 7;
    /// Coordination density.
    pub const COORDINATION: usize = 8;
    /// Solid fraction.
    pub const SOLID: usize = 9;
}

/// Hands every term of the fields of `frame` on `grid` to
/// `sink(field, cell, components)` (a vector's 3, a matrix's 9 columns
/// first; [`field`] numbers the fields): the bodies whose ids `keep`
/// holds and the contacts whose sphere `i` belongs to one of them (all
/// without `keep`). The kinetic stress's terms are `m v ⊗ v φ`; the mean
/// velocity's part is taken off once the sums are made
/// ([`Fields::about_mean_velocity`]).
pub fn deposit(
    frame: &Frame,
    grid: &Grid,
    keep: Option<&std::collections::HashSet<u64>>,
    sink: &mut dyn FnMut(usize, usize, &[f64]),
) {
    use field::*;
    let mut w = Vec::new();
    let counts = super::network::body_counts(frame);
    let kept = |id: u64| keep.is_none_or(|k| k.contains(&id));
    for (k, b) in frame.bodies.iter().enumerate() {
        if !kept(b.id) {
            continue;
        }
        grid.weights(b.position, &mut w);
        let u = b.long_axis();
        let q = DMat3::from_cols(u * u.x, u * u.y, u * u.z) * 1.5 - DMat3::IDENTITY * 0.5;
        let mvv = DMat3::from_cols(
            b.velocity * (b.mass * b.velocity.x),
            b.velocity * (b.mass * b.velocity.y),
            b.velocity * (b.mass * b.velocity.z),
        );
        let z = counts.as_ref().map_or(0.0, |c| c[k][0] as f64);
        for &(cell, p) in &w {
            sink(DENSITY, cell, &[b.mass * p]);
            sink(MOMENTUM, cell, &(b.velocity * (b.mass * p)).to_array());
            sink(KINETIC, cell, &(mvv * p).to_cols_array());
            sink(NUMBER, cell, &[p]);
            sink(ORDER, cell, &(q * p).to_cols_array());
            sink(COORDINATION, cell, &[z * p]);
            sink(SOLID, cell, &[b.volume * p]);
        }
    }
    let index = frame.index_by_id();
    for c in frame.contacts.iter().flatten() {
        if !kept(c.body_i) {
            continue;
        }
        let nn = DMat3::from_cols(
            c.normal * c.normal.x,
            c.normal * c.normal.y,
            c.normal * c.normal.z,
        );
        grid.weights(c.point, &mut w);
        for &(cell, p) in &w {
            sink(CONTACTS, cell, &[p]);
            sink(FABRIC, cell, &(nn * p).to_cols_array());
        }
        let mut sides = [(c.body_i, c.force), (0, DVec3::ZERO)];
        if let Side::Body(j) = c.partner {
            sides[1] = (j, -c.force);
        }
        for (id, force) in sides {
            let Some(&a) = index.get(&id) else { continue };
            let r = frame.bodies[a].position;
            let l = min_image(&frame.domain, c.point - r);
            let fl = DMat3::from_cols(force * l.x, force * l.y, force * l.z);
            // ∫₀¹ φ(r − r_a − s l) ds by composite 4-point Gauss–Legendre,
            // segments no longer than half the width
            let segs = (l.length() / (0.5 * grid.width)).ceil().max(1.0) as usize;
            for s in 0..segs {
                for (x, wt) in GL4 {
                    let t = (s as f64 + x) / segs as f64;
                    grid.weights(r + l * t, &mut w);
                    for &(cell, p) in &w {
                        sink(
                            CONTACT,
                            cell,
                            &(-(fl * (p * wt / segs as f64))).to_cols_array(),
                        );
                    }
                }
            }
        }
    }
}
