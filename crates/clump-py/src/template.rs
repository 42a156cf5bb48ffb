//! `clump.Template`: a multi-sphere template and its exact mass properties
//! (the same computation and JSON keys as `clump template --json`), read
//! from a LIGGGHTS-format file or generated from a closed mesh as
//! `clump template --from-mesh` does.

use crate::arrays::rows_in;
use crate::errors::scenario_error;
use clump_core::shape::from_mesh::{fidelity, generate, FromMeshOptions};
use clump_core::shape::{mass_properties, Sphere};
use clump_io::mesh_file::{read_mesh_file, MeshTransform};
use clump_io::template_file::read_template_file;
use glam::DVec3;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use pyo3::prelude::*;
use std::path::PathBuf;

/// A multi-sphere template (spheres x, y, z, r in m, input frame) with its
/// exact mass properties, as `clump template`.
#[pyclass(module = "clump._clump")]
pub struct Template {
    spheres: Vec<Sphere>,
    #[pyo3(get)]
    density: f64,
    /// The fidelity report of a template generated from a mesh (JSON text).
    fidelity: Option<String>,
}

fn input_error(py: Python<'_>, file: Option<&std::path::Path>, message: String) -> PyErr {
    scenario_error(
        py,
        message,
        file.map(|f| f.display().to_string()),
        None,
        None,
        None,
    )
}

fn positive(py: Python<'_>, what: &str, v: f64) -> PyResult<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(input_error(
            py,
            None,
            format!("{what} must be finite and > 0, found {v}"),
        ))
    }
}

fn json(py: Python<'_>, text: &str) -> PyResult<PyObject> {
    Ok(py.import("json")?.call_method1("loads", (text,))?.unbind())
}

impl Template {
    fn of(spheres: Vec<Sphere>, density: f64) -> Self {
        Template {
            spheres,
            density,
            fidelity: None,
        }
    }
}

#[pymethods]
impl Template {
    /// A template of `spheres` (rows x, y, z, r; m, input frame) at
    /// `density` (kg/m³).
    #[new]
    #[pyo3(signature = (spheres, density=1.0))]
    fn new(py: Python<'_>, spheres: &Bound<'_, PyAny>, density: f64) -> PyResult<Self> {
        positive(py, "density (kg/m³)", density)?;
        let n = spheres.len()?;
        let rows = rows_in(spheres, n, 4, "spheres")?;
        let spheres = rows
            .chunks_exact(4)
            .map(|r| Sphere::new(DVec3::new(r[0], r[1], r[2]), r[3]))
            .collect();
        Ok(Template::of(spheres, density))
    }

    /// A LIGGGHTS-format template file (`x y z r` per line), lengths times `scale`.
    #[staticmethod]
    #[pyo3(signature = (path, scale=1.0, density=1.0))]
    fn from_file(py: Python<'_>, path: PathBuf, scale: f64, density: f64) -> PyResult<Self> {
        positive(py, "scale", scale)?;
        positive(py, "density (kg/m³)", density)?;
        let spheres = read_template_file(&path)
            .map_err(|e| input_error(py, Some(&path), e.to_string()))?
            .into_iter()
            .map(|s| Sphere::new(s.center * scale, s.radius * scale))
            .collect();
        Ok(Template::of(spheres, density))
    }

    /// A template generated from a closed STL/OBJ mesh, as
    /// `clump template --from-mesh` (same options); `fidelity` holds its report.
    #[staticmethod]
    #[pyo3(signature = (path, spheres=None, tolerance=None, resolution=50, overlap=0.6, min_radius=0.0, refine=20, scale=1.0, density=1.0))]
    #[allow(clippy::too_many_arguments)]
    fn from_mesh(
        py: Python<'_>,
        path: PathBuf,
        spheres: Option<usize>,
        tolerance: Option<f64>,
        resolution: usize,
        overlap: f64,
        min_radius: f64,
        refine: usize,
        scale: f64,
        density: f64,
    ) -> PyResult<Self> {
        positive(py, "scale", scale)?;
        positive(py, "density (kg/m³)", density)?;
        let tr = MeshTransform {
            scale,
            ..Default::default()
        };
        let mesh =
            read_mesh_file(&path, &tr).map_err(|e| input_error(py, Some(&path), e.to_string()))?;
        let opt = FromMeshOptions {
            max_spheres: spheres.unwrap_or(if tolerance.is_some() { 1000 } else { 50 }),
            tolerance,
            resolution,
            overlap,
            min_radius,
            refine_iterations: refine,
        };
        let t0 = std::time::Instant::now();
        let (made, fid) = py
            .allow_threads(|| {
                let s = generate(&mesh, &opt).map_err(|e| e.to_string())?;
                let f = fidelity(&mesh, &s, 20_000).map_err(|e| e.to_string())?;
                Ok::<_, String>((s, f))
            })
            .map_err(|e| input_error(py, Some(&path), format!("{}: {e}", path.display())))?;
        let report =
            clump_io::template_json::fidelity_json(&fid, made.len(), t0.elapsed().as_secs_f64());
        Ok(Template {
            spheres: made,
            density,
            fidelity: Some(report.to_string()),
        })
    }

    /// The spheres, N×4 (x, y, z, r), m, template (input) frame. A copy.
    #[getter]
    fn spheres<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let mut a = Array2::<f64>::zeros((self.spheres.len(), 4));
        for (k, s) in self.spheres.iter().enumerate() {
            a[[k, 0]] = s.center.x;
            a[[k, 1]] = s.center.y;
            a[[k, 2]] = s.center.z;
            a[[k, 3]] = s.radius;
        }
        a.into_pyarray(py)
    }

    /// The fidelity report of a template made by `from_mesh` (else None).
    #[getter]
    fn fidelity(&self, py: Python<'_>) -> PyResult<Option<PyObject>> {
        self.fidelity.as_deref().map(|t| json(py, t)).transpose()
    }

    /// Exact mass properties of the union of the spheres: the keys and
    /// values of `clump template --json` (SI, input frame).
    fn mass_properties(&self, py: Python<'_>) -> PyResult<PyObject> {
        let p = mass_properties(&self.spheres, self.density)
            .map_err(|e| input_error(py, None, format!("template: {e}")))?;
        json(
            py,
            &clump_io::template_json::mass_properties_json(&p).to_string(),
        )
    }

    /// Writes the spheres as a LIGGGHTS-format template file (`x y z r` per
    /// line, m), readable by scenarios and `Template.from_file`.
    fn write(&self, path: PathBuf) -> PyResult<()> {
        let mut text = String::from("# x y z r (m), template frame; written by clump (Python)\n");
        for s in &self.spheres {
            text.push_str(&format!(
                "{:e} {:e} {:e} {:e}\n",
                s.center.x, s.center.y, s.center.z, s.radius
            ));
        }
        std::fs::write(&path, text).map_err(|e| {
            crate::errors::SimulationError::new_err(format!("{}: {e}", path.display()))
        })
    }

    fn __len__(&self) -> usize {
        self.spheres.len()
    }
}
