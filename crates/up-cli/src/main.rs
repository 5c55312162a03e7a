//! `up`: headless runs, benchmarks, scene checks and exports for the UP
//! balloon simulator. One file per subcommand; this file only dispatches.
//!
//! Exit codes: 0 on success; 2 on any error (a bad scene or argument, a file
//! that cannot be read or written), with a message on standard error that
//! starts with `error:`.

mod air;
mod bench;
mod colliders;
mod export_gltf;
mod export_obj;
mod fit_spheres;
mod forecast;
mod heap_meter;
mod probe;
mod run;
mod scene_arg;
mod soak;
mod summary;
mod validate;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// Counts the bytes held on the heap, for `up soak`'s leak check.
#[global_allocator]
static HEAP: heap_meter::HeapMeter = heap_meter::HeapMeter;

/// UP: helium balloons in a closed room, simulated headless.
#[derive(Parser)]
#[command(name = "up", version, about, propagate_version = true)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Threads that step the world (rayon's pool); all cores if left out,
    /// or RAYON_NUM_THREADS. The results are the same on any number.
    #[arg(long, global = true, value_name = "T", value_parser = clap::value_parser!(u16).range(1..=1024))]
    threads: Option<u16>,
}

#[derive(Subcommand)]
enum Command {
    /// Simulate a scene headless; print a summary (and JSON with --json).
    Run(run::RunArgs),
    /// Run a scene over hours (a time-lapse) and say per balloon group when
    /// its balloons leave the ceiling and when they are on the floor.
    ///
    /// A balloon is on the floor when its lowest point is within 3 cm of the
    /// room's lowest; at the ceiling when its centre is within 0.3 m of the
    /// highest it has been and it has risen at least 0.5 m; hovering
    /// otherwise. Times are hours from the start of the run (a group's
    /// `filled_hours_before` lies before it); "half" is the ⌈n/2⌉-th balloon
    /// of a group of n; "> H h": not within the run; "never up": no balloon
    /// of the group reached the ceiling.
    Forecast(forecast::ForecastArgs),
    /// Print the room's moving air (its fans, vents and draughts) at points:
    /// the velocity, m/s, and the speed.
    Air(air::AirArgs),
    /// Time the UP engine alone on a scene, with per-stage counters.
    Bench(bench::BenchArgs),
    /// Show the default balloon's sphere tree and mass properties.
    Colliders(colliders::CollidersArgs),
    /// Check a scene file and print what it describes.
    Validate(validate::ValidateArgs),
    /// Write a scene as OBJ + MTL, ribbons included (for Blender), with the
    /// balloon and room meshes the web app renders.
    ///
    /// Writes into DIR: scene.obj and scene.mtl, the scene's balloons where
    /// they are (one object each, balloon_<id>) and its ribbons as flat 5 mm
    /// strips (one object each, ribbon_<id> with its balloon's id), each with
    /// a material of its colour; room.obj and room.mtl; balloon.obj with
    /// balloon_<colour>.mtl for every named colour. Blender imports scene.obj
    /// and room.obj as they are (File > Import > Wavefront (.obj), Y up).
    ExportObj(export_obj::ExportObjArgs),
    /// Write a run as an animated glTF 2.0 binary (.glb) for Blender.
    ///
    /// Each balloon a node balloon-<id> (the id --out uses) with its mesh
    /// and a PBR material of its finish, translation and rotation channels
    /// at F frames a second (a scale channel where the gas shrinks it);
    /// each ribbon a strip skinned to joints ribbon-<id>-<k>, its points;
    /// weights as nodes weight-<id>; the room, a camera and the page's
    /// lights. Keys start at 0; the scene's extras.up gives start_s and
    /// sim_seconds_per_second.
    ExportGltf(export_gltf::ExportGltfArgs),
    /// Fit a sphere tree to a closed OBJ mesh and write it as JSON.
    FitSpheres(fit_spheres::FitSpheresArgs),
    /// A long run checking health as it goes: finite, inside, overlap, memory.
    Soak(soak::SoakArgs),
}

/// Exit status for every error: bad input, unreadable or unwritable files.
const EXIT_ERROR: u8 = 2;

fn main() -> ExitCode {
    let cli = Cli::parse();
    if let Some(threads) = cli.threads {
        let pool = rayon::ThreadPoolBuilder::new().num_threads(usize::from(threads));
        if let Err(e) = pool.build_global() {
            eprintln!("error: --threads {threads}: cannot start the threads: {e}");
            return ExitCode::from(EXIT_ERROR);
        }
    }
    let result = match cli.command {
        Command::Run(args) => run::run(&args),
        Command::Forecast(args) => forecast::run(&args),
        Command::Air(args) => air::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Colliders(args) => colliders::run(&args),
        Command::Validate(args) => validate::run(&args),
        Command::ExportObj(args) => export_obj::run(&args),
        Command::ExportGltf(args) => export_gltf::run(&args),
        Command::FitSpheres(args) => fit_spheres::run(&args),
        Command::Soak(args) => soak::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(EXIT_ERROR)
        }
    }
}
