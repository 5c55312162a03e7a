//! `up export-gltf`: a run as an animated glTF 2.0 binary (`.glb`) for
//! Blender and other tools, written whole or not at all. The frames are
//! the engine's own poses and ribbon points, recorded every whole number of
//! steps nearest 1/F s (`up_export::Recording`); with `--hours`, once a
//! simulated minute, played at F simulated minutes a second.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::Args;
use up_export::{Recording, SceneLooks};
use up_physics::World;
use up_scene::atomic_file::AtomicFile;
use up_scene::build::build_world;

use crate::run::{advance_fully, check_hours, progress_bar, LAPSE_CHUNK_S};
use crate::scene_arg::load_scene;

/// Longest `--seconds` or `--from`, s (one simulated hour of 30 frames a second is 108,000 frames).
const MAX_SECONDS: f64 = 3600.0;
/// Most frames a second.
const MAX_FPS: f64 = 240.0;

#[derive(Args, Debug)]
pub struct ExportGltfArgs {
    /// The scene file (.toml or .json).
    pub scene: PathBuf,
    /// The .glb to write.
    pub out: PathBuf,
    /// Simulated seconds to record; the scene's `sim.duration_s` (10 s by default) if left out.
    #[arg(
        long,
        value_name = "S",
        conflicts_with = "hours",
        allow_negative_numbers = true
    )]
    pub seconds: Option<f64>,
    /// Simulated hours to record as a time-lapse, in (0, 2000]: a frame a
    /// simulated minute (the balloons shrink as their gas leaks: a scale channel).
    #[arg(long, value_name = "H", allow_negative_numbers = true)]
    pub hours: Option<f64>,
    /// Frames a second of the animation; 30.
    #[arg(
        long,
        value_name = "F",
        default_value_t = 30.0,
        allow_negative_numbers = true
    )]
    pub fps: f64,
    /// Simulate this many seconds first, unrecorded; 0.
    #[arg(
        long,
        value_name = "T",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub from: f64,
}

/// `--fps` and `--from`, checked.
fn check_args(args: &ExportGltfArgs) -> Result<()> {
    if !(args.fps.is_finite() && args.fps > 0.0 && args.fps <= MAX_FPS) {
        bail!(
            "--fps: expected frames a second in (0, {MAX_FPS}], found {}",
            args.fps
        );
    }
    if !(args.from.is_finite() && (0.0..=MAX_SECONDS).contains(&args.from)) {
        bail!(
            "--from: expected seconds in [0, {MAX_SECONDS}], found {}",
            args.from
        );
    }
    if let Some(seconds) = args.seconds {
        if !(seconds.is_finite() && seconds > 0.0 && seconds <= MAX_SECONDS) {
            bail!("--seconds: expected a number in (0, {MAX_SECONDS}], found {seconds}");
        }
    }
    if let Some(hours) = args.hours {
        check_hours(hours)?;
    }
    Ok(())
}

pub fn run(args: &ExportGltfArgs) -> Result<()> {
    check_args(args)?;
    let scene = load_scene(Some(&args.scene), None, None)?;
    let mut built = build_world(&scene)?;
    // Probe the output now rather than after a long run.
    AtomicFile::create(&args.out)?;
    let dt = f64::from(built.world.def().dt);
    for _ in 0..(args.from / dt).round() as u64 {
        built.world.step();
    }
    let mut recording = Recording::new(SceneLooks::of(&scene, &built), None);
    let world = &mut built.world;
    record(&mut recording, world)?;
    match args.hours {
        Some(hours) => {
            recording.time_scale = LAPSE_CHUNK_S * args.fps;
            let chunks = (hours * 3600.0 / LAPSE_CHUNK_S).ceil() as u64;
            let bar = progress_bar(chunks, "simulated min");
            for chunk in 1..=chunks {
                advance_fully(world, LAPSE_CHUNK_S);
                record(&mut recording, world)?;
                if let Some(bar) = &bar {
                    bar.set_position(chunk);
                }
            }
        }
        None => {
            let seconds = args.seconds.unwrap_or(f64::from(scene.sim.duration_s));
            let steps = (seconds / dt).round().max(1.0) as u64;
            let every = (1.0 / (args.fps * dt)).round().max(1.0) as u64;
            let bar = progress_bar(steps, "steps");
            for step in 1..=steps {
                world.step();
                if step % every == 0 || step == steps {
                    record(&mut recording, world)?;
                }
                if let Some(bar) = bar.as_ref().filter(|_| step % 16 == 0) {
                    bar.set_position(step);
                }
            }
        }
    }
    let bytes = up_export::glb(&recording)?;
    let mut file = AtomicFile::create(&args.out)?;
    file.write_all(&bytes)
        .with_context(|| format!("cannot write {}", args.out.display()))?;
    file.commit()?;
    println!(
        "{}: {} frames, {} balloons, {} ribbons, {} bytes",
        args.out.display(),
        recording.frame_count(),
        recording.looks.balloons.len(),
        recording.looks.ribbons.len(),
        bytes.len()
    );
    Ok(())
}

/// Records the world now; the world keeps its bodies through a run.
fn record(recording: &mut Recording, world: &World) -> Result<()> {
    recording
        .record(world)
        .map_err(|_| anyhow::anyhow!("the world's balloons changed during the export"))
}
