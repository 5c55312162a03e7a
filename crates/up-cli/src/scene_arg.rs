//! The scene a command works on: a file, or the default (the original), with
//! the command line's overrides applied and validated.

use std::path::{Path, PathBuf};

use anyhow::Result;
use clap::Args;
use up_scene::scene::Scene;

/// The scene, `--balloons` and `--seed` of `up run`, `bench` and `soak`,
/// flattened into each (`#[command(flatten)]`); a command words them its own
/// way with `mut_arg` (`up soak` sizes its room for `--balloons`).
#[derive(Args, Debug)]
pub struct SceneArgs {
    /// Scene file (.toml or .json); the original room with 50 balloons if left out.
    pub scene: Option<PathBuf>,
    /// Total number of balloons, spread over the scene's groups (overrides the scene).
    #[arg(long, value_name = "N")]
    pub balloons: Option<u64>,
    /// Seed of the spawn layout (overrides `sim.seed`).
    #[arg(long, value_name = "K")]
    pub seed: Option<u64>,
}

impl SceneArgs {
    /// The scene file, or the default scene, with `--seed` and `--balloons` applied.
    pub fn load(&self) -> Result<Scene> {
        load_scene(self.scene.as_deref(), self.seed, self.balloons)
    }

    /// How the scene is named in output.
    pub fn name(&self) -> String {
        scene_name(self.scene.as_ref())
    }
}

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
