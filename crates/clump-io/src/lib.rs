//! Clump's input and output around the engine (`clump-core`): scenario files
//! (TOML, with located, did-you-mean error messages), LIGGGHTS template files,
//! body CSV files, triangle meshes, ParaView VTK XML output, thermo and
//! trajectory CSV logs, versioned checkpoints, atomic file writes, and the run
//! driver behind `clump run` / `clump resume`.
pub mod append;
pub mod atomic;
pub mod checkpoint;
pub mod mesh_file;
pub mod post;
pub mod run;
pub mod scenario;
pub mod template_file;
pub mod template_json;
pub mod thermo_csv;
pub mod trajectory;
pub mod vti_grid;
pub mod vtk;
pub mod vtk_contacts;
pub mod vtk_pieces;
pub(crate) mod vtp;
pub mod vtu;
