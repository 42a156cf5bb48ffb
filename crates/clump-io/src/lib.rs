//! io
pub mod atomic;
pub mod checkpoint;
pub mod mesh_file;
pub mod run;
pub mod scenario;
pub mod template_file;
pub mod thermo_csv;
pub mod trajectory;
pub mod vtk;
