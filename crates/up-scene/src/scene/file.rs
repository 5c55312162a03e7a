//! Scene files: `.toml` or `.json` by extension, at most `MAX_SCENE_BYTES`,
//! UTF-8; paths in the scene (`room.mesh`) resolve against the file's folder.

use std::path::{Path, PathBuf};

use super::Scene;
use crate::error::SceneError;

/// Largest scene file read, bytes (1 MiB: the full documented example is
/// about 2 KiB). A bigger file, or a device that never ends, is refused.
pub const MAX_SCENE_BYTES: u64 = 1 << 20;
impl Scene {
    /// Reads a `.toml` or `.json` scene file and validates it.
    pub fn from_path(path: impl AsRef<Path>) -> Result<Scene, SceneError> {
        let path = path.as_ref();
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let is_toml = match ext.as_deref() {
            Some("toml") => true,
            Some("json") => false,
            _ => {
                return Err(SceneError::UnknownFormat {
                    path: path.to_path_buf(),
                })
            }
        };
        let text = read_scene_text(path)?;
        let name = path.display().to_string();
        let mut scene = if is_toml {
            Self::from_toml_str(&text, &name)
        } else {
            Self::from_json_str(&text, &name)
        }?;
        scene.source.dir = Some(match path.parent() {
            Some(dir) if !dir.as_os_str().is_empty() => dir.to_path_buf(),
            _ => PathBuf::from("."),
        });
        Ok(scene)
    }

    /// The room mesh path resolved against the scene file's directory.
    pub fn room_mesh_path(&self) -> Option<PathBuf> {
        let mesh = Path::new(self.room.mesh.as_ref()?);
        Some(match &self.source.dir {
            Some(dir) if mesh.is_relative() => dir.join(mesh),
            _ => mesh.to_path_buf(),
        })
    }
}

/// The text of a scene file: at most `MAX_SCENE_BYTES`, UTF-8.
fn read_scene_text(path: &Path) -> Result<String, SceneError> {
    use std::io::Read as _;
    let read_error = |source| SceneError::Read {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::open(path).map_err(read_error)?;
    let mut bytes = Vec::new();
    file.take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(read_error)?;
    if bytes.len() as u64 > MAX_SCENE_BYTES {
        return Err(SceneError::TooLarge {
            path: path.to_path_buf(),
            max: MAX_SCENE_BYTES,
        });
    }
    String::from_utf8(bytes).map_err(|e| {
        read_error(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!(
                "not UTF-8 text (invalid byte at offset {})",
                e.utf8_error().valid_up_to()
            ),
        ))
    })
}
