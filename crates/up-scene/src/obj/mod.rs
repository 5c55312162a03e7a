//! Wavefront OBJ: reading meshes (`read`: rooms, the shapes `up fit-spheres`
//! fits), writing the web app's balloon and room assets (`export`), and
//! writing a whole built scene at one moment (`scene_obj`).

pub mod export;
mod read;
pub mod scene_obj;

pub use read::{parse_obj_mesh, read_obj_mesh, ObjError, ObjMesh, MAX_OBJ_BYTES};

#[cfg(test)]
mod export_tests;
#[cfg(test)]
mod read_tests;
