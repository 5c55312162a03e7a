//! What the scene tests share: parsing that must fail, and the example scenes.

use super::Scene;
use crate::error::SceneError;

pub(super) fn toml_err(text: &str) -> SceneError {
    match Scene::from_toml_str(text, "test.toml") {
        Ok(scene) => panic!("expected an error, got {scene:?}"),
        Err(e) => e,
    }
}

pub(super) fn json_err(text: &str) -> SceneError {
    match Scene::from_json_str(text, "test.json") {
        Ok(scene) => panic!("expected an error, got {scene:?}"),
        Err(e) => e,
    }
}

pub(super) fn asset(name: &str) -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes")
        .join(name)
}
