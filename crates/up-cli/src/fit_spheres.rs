//! `up fit-spheres`: fit a sphere tree to any closed OBJ mesh (bring your own
//! balloon) and write it, with the fit's quality, as JSON: the same fit a
//! scene's `mesh = "file.obj"` balloon gets (along the axis, or over the
//! mid-surface for a flat mesh).

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Args;
use up_geom::fit::{DEFAULT_LEAVES, MAX_LEAVES};
use up_scene::balloon::surface::{custom_mesh, fit_balloon_tree, is_flat, FLAT_LEAVES};
use up_scene::obj::read_obj_mesh;

use up_scene::atomic_file::write_atomically;

#[derive(Args, Debug)]
pub struct FitSpheresArgs {
    /// A closed, consistently wound triangle mesh (OBJ), in metres.
    pub model: PathBuf,
    /// Number of leaf spheres (1 to 64): head, neck and fillers. A flat mesh
    /// (at most half as thick as wide) gets FLAT_LEAVES (64) over its face.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_LEAVES)]
    pub leaves: usize,
    /// Write the JSON here (atomically) instead of to standard output.
    #[arg(long, value_name = "FILE.json")]
    pub out: Option<PathBuf>,
}

pub fn run(args: &FitSpheresArgs) -> Result<()> {
    if !(1..=MAX_LEAVES).contains(&args.leaves) {
        bail!(
            "--leaves: expected 1 to {MAX_LEAVES}, found {}",
            args.leaves
        );
    }
    let (vertices, triangles) = read_obj_mesh(&args.model)?.into_parts();
    // Checked and fitted as a scene's `mesh` balloon is: refused when open,
    // inside out or degenerate; over its face when flat.
    let name = args.model.display().to_string();
    let mesh = custom_mesh(&name, vertices, triangles, None)?;
    let flat = is_flat(&mesh.positions, &mesh.indices);
    let report = fit_balloon_tree(&mesh.positions, &mesh.indices, flat, args.leaves)
        .with_context(|| name.clone())?;
    if flat {
        eprintln!(
            "{}: flat: {FLAT_LEAVES} spheres over its mid-surface",
            args.model.display()
        );
    }
    let json = serde_json::to_string_pretty(&report)?;
    match &args.out {
        Some(path) => {
            write_atomically(path, format!("{json}\n").as_bytes())?;
            eprintln!(
                "{}: {} leaves, coverage {:.2} %, tightness {:.3} -> {}",
                args.model.display(),
                report.tree.leaves().len(),
                report.coverage * 100.0,
                report.tightness,
                path.display()
            );
        }
        None => println!("{json}"),
    }
    Ok(())
}
