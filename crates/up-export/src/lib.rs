//! A run of the UP balloon simulator as an animated glTF 2.0 binary
//! (`.glb`), for Blender and other tools: `up export-gltf` and the page's
//! "Export last 10 s" write it through the same code.
//!
//! A `Recording` holds the scene's looks (`SceneLooks`: meshes, colours,
//! finishes, the room) and the frames a recorder fills one at a time
//! (`Recording::record` on a `World`); `glb` turns it into the file, whole,
//! in memory. The document is built with gltf-json's types (`document.rs`),
//! its binary buffer by `glb.rs`.
//!
//! Metres, +Y up, origin at the centre of the floor, as the engine has them.

mod builder;
mod document;
mod glb;
pub mod looks;
mod materials;
pub mod recording;
mod ribbons;

pub use document::{document, glb};
pub use looks::SceneLooks;
pub use recording::{Frame, Mismatch, Recording};

/// Why a recording could not be written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ExportError {
    /// Nothing was recorded.
    NoFrames,
    /// The document could not be serialised (it should always be).
    Json(String),
}

impl std::fmt::Display for ExportError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ExportError::NoFrames => write!(f, "nothing was recorded: no frame to export"),
            ExportError::Json(e) => write!(f, "the glTF document could not be written: {e}"),
        }
    }
}

impl std::error::Error for ExportError {}
