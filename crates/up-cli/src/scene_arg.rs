//! The scene a command works on: a file, or the default (the original), with
//! the command line's overrides applied and validated.

use std::path::{Path, PathBuf};

use anyhow::Result;
use up_scene::scene::Scene;

/// Reads `path` (or takes the default scene) and applies `--seed` and `--balloons`.
pub fn load_scene(path: Option<&Path>, seed: Option<u64>, balloons: Option<u64>) -> Result<Scene> {
    let mut scene = match path {
        Some(path) => Scene::from_path(path)?,
        None => Scene::default(),
    };
    if let Some(seed) = seed {
        scene.sim.seed = seed;
        scene.validate()?;
    }
    if let Some(total) = balloons {
        scene = scene.with_total_balloons(total)?;
    }
    Ok(scene)
}

/// How a scene is named in output.
pub fn scene_name(path: Option<&PathBuf>) -> String {
    path.map_or_else(
        || "default (the original room)".to_string(),
        |p| p.display().to_string(),
    )
}
