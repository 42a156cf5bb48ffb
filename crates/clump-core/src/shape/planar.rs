//! Templates for the 2D mode (the planar case of docs/theory.md: two coordinates of the
//! centre of mass and one rotation angle): every sphere centre lies in the
//! plane `z = const` of the input frame, and the body frame is re-chosen so
//! that body z is the input z axis exactly (the plane normal, a principal
//! axis of any planar clump by mirror symmetry) and body x, y are the
//! in-plane principal axes. Then a body turned only about world z has a
//! quaternion with zero x and y parts, and every out-of-plane component of
//! the motion stays exactly zero (see docs/scenario.md, "2D mode").

use glam::{DMat3, DVec3};

use super::template::ClumpTemplate;

/// Why a template cannot be used in 2D.
#[derive(Debug, Clone, PartialEq)]
pub enum PlanarError {
    /// A sphere centre lies off the plane `z = z0` of the first sphere (m).
    OffPlane {
        /// Index of the sphere.
        sphere: usize,
        /// Its distance from the plane, m.
        offset: f64,
    },
    /// The (given) inertia tensor does not have the plane normal as a
    /// principal axis (`I_xz`, `I_yz` in kg m²).
    NormalNotPrincipal {
        /// Input-frame `I_xz`, `I_yz`, kg m².
        products: [f64; 2],
    },
}

impl std::fmt::Display for PlanarError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PlanarError::OffPlane { sphere, offset } => write!(
                f,
                "sphere {} lies {offset:.3e} m off the plane z = const of the first sphere; in 2D every sphere centre must lie in one plane of the input frame",
                sphere + 1
            ),
            PlanarError::NormalNotPrincipal { products } => write!(
                f,
                "the inertia tensor's products I_xz = {:.3e}, I_yz = {:.3e} kg m^2 are not zero: in 2D the plane normal (input z) must be a principal axis",
                products[0], products[1]
            ),
        }
    }
}

impl ClumpTemplate {
    /// This template with its body frame chosen for the 2D mode (see the
    /// [module docs](self)): body z = input z, body x and y the in-plane
    /// principal axes (smaller moment first), centre of mass in the plane,
    /// sphere centres with body z exactly 0.
    pub fn planar(&self) -> Result<ClumpTemplate, PlanarError> {
        let input: Vec<_> = self.input_spheres();
        let z0 = input[0].center.z;
        let scale = self.bounding_radius.max(f64::MIN_POSITIVE);
        for (k, s) in input.iter().enumerate() {
            let offset = (s.center.z - z0).abs();
            if offset > 1e-9 * scale {
                return Err(PlanarError::OffPlane { sphere: k, offset });
            }
        }
        let mut p = self.properties;
        let i = p.inertia;
        let (ixz, iyz) = (i.x_axis.z, i.y_axis.z);
        let tol = 1e-9 * i.x_axis.x.abs().max(i.y_axis.y.abs()).max(i.z_axis.z.abs());
        if ixz.abs() > tol || iyz.abs() > tol {
            return Err(PlanarError::NormalNotPrincipal {
                products: [ixz, iyz],
            });
        }
        // in-plane principal axes of the 2×2 block
        let (ixx, iyy, ixy) = (i.x_axis.x, i.y_axis.y, i.y_axis.x);
        let mut a = 0.5 * (2.0 * ixy).atan2(ixx - iyy);
        let moment = |a: f64| {
            let (s, c) = a.sin_cos();
            c * c * ixx + s * s * iyy + 2.0 * s * c * ixy
        };
        if moment(a) > moment(a + std::f64::consts::FRAC_PI_2) {
            a += std::f64::consts::FRAC_PI_2;
        }
        let (s, c) = a.sin_cos();
        p.principal_moments = DVec3::new(
            moment(a),
            moment(a + std::f64::consts::FRAC_PI_2),
            i.z_axis.z,
        );
        // rows = body axes in the input frame
        p.principal_axes = DMat3::from_cols(
            DVec3::new(c, -s, 0.0),
            DVec3::new(s, c, 0.0),
            DVec3::new(0.0, 0.0, 1.0),
        );
        p.center_of_mass.z = z0;
        let mut t = ClumpTemplate::from_properties(&self.name, &input, self.density, p);
        for sp in &mut t.spheres {
            sp.center.z = 0.0;
        }
        Ok(t)
    }

    /// The spheres in the input frame (m).
    fn input_spheres(&self) -> Vec<super::Sphere> {
        let back = self.body_to_input();
        self.spheres
            .iter()
            .map(|s| super::Sphere::new(back * s.center + self.input_center_of_mass, s.radius))
            .collect()
    }
}
