//! The balloon models' surfaces for the page: a foil group's balloons are
//! drawn with the engine's own foil pillow (`up_scene::foil_mesh`), which no
//! asset file holds, so the page reads it here (latex balloons are drawn
//! with the OBJ the page loads, and need nothing from this module).
//!
//! `write_model_mesh(model)` fills three arrays, each a view of wasm memory
//! until the next call: positions and normals, `MESH_VERTEX_FLOATS` per
//! vertex in the body frame (the frame the poses place), and triangle
//! indices, three per triangle, counter-clockwise seen from outside.

use crate::error::WasmError;
use crate::loaded::Loaded;

/// Floats per mesh vertex position (and per normal): x, y, z.
pub const MESH_VERTEX_FLOATS: usize = 3;

/// Model `model`'s surface as the page reads it (see the module).
#[derive(Default)]
pub struct MeshBuffers {
    pub positions: Vec<f32>,
    pub normals: Vec<f32>,
    pub indices: Vec<u32>,
}

/// Whether each balloon model (one per group, in group order) is drawn from
/// its own surface (foil balloons, meshes of one's own).
pub fn model_foil(loaded: &Loaded) -> Vec<bool> {
    loaded
        .built
        .balloon_models
        .iter()
        .map(|m| m.drawn_from_mesh)
        .collect()
}

impl MeshBuffers {
    /// Writes model `model`'s surface; returns the vertex count. Refused
    /// (the last surface kept) for a model the scene lacks.
    pub fn write(&mut self, loaded: &Loaded, model: u32) -> Result<usize, WasmError> {
        let models = &loaded.built.balloon_models;
        let m = models.get(model as usize).ok_or_else(|| {
            WasmError::OutOfRange(format!(
                "balloon model {model}: the scene has {} models",
                models.len()
            ))
        })?;
        self.positions.clear();
        self.normals.clear();
        self.indices.clear();
        self.positions
            .extend(m.mesh.positions.iter().flat_map(|p| p.to_array()));
        self.normals
            .extend(m.mesh.normals.iter().flat_map(|n| n.to_array()));
        self.indices.extend(m.mesh.indices.iter().flatten());
        Ok(m.mesh.positions.len())
    }
}

#[cfg(test)]
#[path = "model_mesh_tests.rs"]
mod tests;
