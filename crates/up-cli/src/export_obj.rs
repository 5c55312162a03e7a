//! `up export-obj`: write the meshes of a scene as OBJ + MTL: the balloon
//! model (one material file per colour) and the room, the files the web app
//! renders, and the whole scene in one file, every balloon where it is and
//! every ribbon as a thin strip of its colour: how a scene goes to Blender.

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Args;
use up_scene::build::build_world;
use up_scene::obj_export::{export_balloon_assets, export_room_obj};
use up_scene::scene_obj::export_scene_obj;

use crate::scene_arg::load_scene;

/// Longest `--seconds` before the export, s (one simulated hour).
const MAX_SECONDS: f64 = 3600.0;

#[derive(Args, Debug)]
pub struct ExportObjArgs {
    /// Directory to write into (created if missing).
    pub dir: PathBuf,
    /// The scene to export (its room, balloons and ribbons); the original
    /// room with its 50 balloons if left out.
    #[arg(long, value_name = "SCENE")]
    pub scene: Option<PathBuf>,
    /// Simulate the scene this many seconds first (0: as it starts, every
    /// ribbon hanging straight down).
    #[arg(long, value_name = "S", default_value_t = 0.0)]
    pub seconds: f64,
}

pub fn run(args: &ExportObjArgs) -> Result<()> {
    if !(args.seconds.is_finite() && (0.0..=MAX_SECONDS).contains(&args.seconds)) {
        bail!(
            "--seconds: expected a number in [0, {MAX_SECONDS}], found {}",
            args.seconds
        );
    }
    let scene = load_scene(args.scene.as_deref(), None, None)?;
    let mut built = build_world(&scene)?;
    let steps = (args.seconds / f64::from(built.world.def().dt)).round() as u64;
    for _ in 0..steps {
        built.world.step();
    }
    std::fs::create_dir_all(&args.dir)
        .with_context(|| format!("cannot create the directory {}", args.dir.display()))?;
    let mut written = export_balloon_assets(&args.dir)
        .with_context(|| format!("cannot write the balloon into {}", args.dir.display()))?;
    written.extend(
        export_room_obj(&args.dir, &built.room)
            .with_context(|| format!("cannot write the room into {}", args.dir.display()))?,
    );
    written.extend(
        export_scene_obj(&args.dir, &built)
            .with_context(|| format!("cannot write the scene into {}", args.dir.display()))?,
    );
    for path in written {
        println!("{}", path.display());
    }
    Ok(())
}
