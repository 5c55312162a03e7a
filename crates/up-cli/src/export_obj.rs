//! `up export-obj`: write the balloon mesh (one material per colour) and the
//! room mesh as OBJ + MTL, the files the web app renders.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use up_scene::build::build_room;
use up_scene::obj_export::{export_balloon_assets, export_room_obj};

use crate::scene_arg::load_scene;

#[derive(Args, Debug)]
pub struct ExportObjArgs {
    /// Directory to write into (created if missing).
    pub dir: PathBuf,
    /// Take the room from this scene file instead of the original room.
    #[arg(long, value_name = "SCENE")]
    pub scene: Option<PathBuf>,
}

pub fn run(args: &ExportObjArgs) -> Result<()> {
    let scene = load_scene(args.scene.as_deref(), None, None)?;
    let room = build_room(&scene)?;
    std::fs::create_dir_all(&args.dir)
        .with_context(|| format!("cannot create the directory {}", args.dir.display()))?;
    let mut written = export_balloon_assets(&args.dir)
        .with_context(|| format!("cannot write the balloon into {}", args.dir.display()))?;
    written.extend(
        export_room_obj(&args.dir, &room)
            .with_context(|| format!("cannot write the room into {}", args.dir.display()))?,
    );
    for path in written {
        println!("{}", path.display());
    }
    Ok(())
}
