//! The furniture for the page: every piece's triangles in the world frame
//! (the engine collides with the same ones, in the room's mesh), and the
//! check that a scene's furniture can be built in the browser (a mesh
//! piece names a file the browser cannot read). A second `impl Engine`
//! block beside lib.rs's, one concern apart.

use wasm_bindgen::prelude::*;

use up_scene::scene::Scene;

use crate::error::{named, CallError, WasmError};
use crate::loaded::Loaded;
use crate::Engine;

/// Every piece's vertices (x, y, z each, m) and triangles (three indices
/// into them each, counter-clockwise seen from outside), in scene order.
pub fn furniture_mesh(loaded: &Loaded) -> (Vec<f32>, Vec<u32>) {
    let (mut vertices, mut triangles) = (Vec::new(), Vec::new());
    for piece in &loaded.built.furniture {
        let base = (vertices.len() / 3) as u32;
        vertices.extend(piece.vertices.iter().flat_map(|v| v.to_array()));
        triangles.extend(piece.triangles.iter().flatten().map(|&k| k + base));
    }
    (vertices, triangles)
}

/// `Ok` unless a piece is an OBJ mesh, which the browser cannot read.
pub fn check_for_browser(scene: &Scene) -> Result<(), WasmError> {
    match scene.furniture.iter().position(|p| p.mesh.is_some()) {
        Some(i) => Err(WasmError::Scene(format!(
            "{}: furniture[{i}].mesh: a mesh piece cannot be read in the browser; \
             expected kind = \"table\" or \"chair\"",
            scene.source.name
        ))),
        None => Ok(()),
    }
}

#[wasm_bindgen]
impl Engine {
    /// The furniture's vertices: x, y, z per vertex, m (copied: the page
    /// reads them once a world is built). Empty without furniture.
    pub fn furniture_vertices(&self) -> Result<Vec<f32>, CallError> {
        named("furniture_vertices", self.state.loaded()).map(|l| furniture_mesh(l).0)
    }

    /// The furniture's triangles: three indices into `furniture_vertices`
    /// each, counter-clockwise seen from outside.
    pub fn furniture_triangles(&self) -> Result<Vec<u32>, CallError> {
        named("furniture_triangles", self.state.loaded()).map(|l| furniture_mesh(l).1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::State;

    #[test]
    fn the_page_gets_every_pieces_triangles_and_a_mesh_piece_is_refused() {
        let mut state = State::default();
        let toml = "[[furniture]]\nkind = \"table\"\nposition = [0, 0, 0]\n\
                    [[furniture]]\nkind = \"chair\"\nposition = [1.2, 0, 0]\n";
        state.load_toml(toml).unwrap();
        let loaded = state.loaded().unwrap();
        let (vertices, triangles) = furniture_mesh(loaded);
        let pieces = &loaded.built.furniture;
        let count: usize = pieces.iter().map(|p| p.vertices.len()).sum();
        assert_eq!(vertices.len(), 3 * count);
        let tris: usize = pieces.iter().map(|p| p.triangles.len()).sum();
        assert_eq!(triangles.len(), 3 * tris);
        assert!(triangles.iter().all(|&k| (k as usize) < count));
        // The chair's first corner, after the table's.
        let first = pieces[1].vertices[0].to_array();
        let at = 3 * pieces[0].vertices.len();
        assert_eq!(&vertices[at..at + 3], &first);

        let mesh = "[[furniture]]\nmesh = \"chair.obj\"\nposition = [0, 0, 0]\n";
        let e = state.load_toml(mesh).unwrap_err();
        assert!(e.to_string().contains("furniture[0].mesh"), "{e}");
    }
}
