//! `up colliders`: the default balloon's sphere tree (centres in the body
//! frame, radii, which are leaves) and its mass properties.

use anyhow::Result;
use clap::Args;
use up_scene::build::build_group_model;
use up_scene::scene::Scene;

#[derive(Args, Debug)]
pub struct CollidersArgs {
    /// Print one JSON object (`up_scene::balloon::CollidersReport`) instead of the tables.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &CollidersArgs) -> Result<()> {
    let model = build_group_model(&Scene::default(), 0)?;
    let report = model.colliders_report();
    if args.json {
        println!("{}", serde_json::to_string(&report)?);
    } else {
        println!("{report}");
    }
    Ok(())
}
