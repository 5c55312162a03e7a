//! What the scene tests share: where the repository's example scenes are.

use std::path::PathBuf;

/// `assets/scenes/<name>` of the repository.
pub fn asset(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes")
        .join(name)
}
