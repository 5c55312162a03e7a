//! `up run`: simulate a scene headless.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use up_physics::World;
use up_scene::build::{build_world, BuiltScene};
use up_scene::scene::Scene;

use crate::scene_arg::SceneArgs;
use crate::summary::{measure, print_table, RunSummary};
use up_scene::atomic_file::{write_atomically, AtomicFile};

/// Longest run `--seconds` accepts, s (one simulated day).
const MAX_SECONDS: f64 = 86_400.0;

#[derive(Args, Debug)]
pub struct RunArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Simulated seconds; the scene's `sim.duration_s` (10 s by default) if left out.
    #[arg(long, value_name = "S")]
    pub seconds: Option<f64>,
    /// Write the trajectory as CSV: `t,id,x,y,z,qx,qy,qz,qw` (s, m, unit quaternion; Y up).
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Write the ribbons' points as CSV: `t,balloon,point,x,y,z` (s, the
    /// balloon's id as in --out, the point from 0 at the knot to the free end, m).
    #[arg(long, value_name = "FILE.csv")]
    pub ribbons_out: Option<PathBuf>,
    /// Write a CSV row set every K steps, to --out and --ribbons-out (the
    /// first and last steps are always written).
    #[arg(long, value_name = "K", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub every: u64,
    /// End with one JSON object on the last line of standard output.
    #[arg(long)]
    pub json: bool,
    /// Save the world at the end as a snapshot file.
    #[arg(long, value_name = "FILE")]
    pub save_state: Option<PathBuf>,
    /// Start from a snapshot saved with --save-state instead of the scene's
    /// spawn (the scene still gives the room for the summary).
    #[arg(long, value_name = "FILE")]
    pub load_state: Option<PathBuf>,
}

/// Builds the scene's world, or restores it from the snapshot `load_state`
/// (saved with `--save-state`) when given; the scene still gives the room.
pub fn build_or_restore(scene: &Scene, load_state: Option<&Path>) -> Result<BuiltScene> {
    let mut built = build_world(scene)?;
    if let Some(path) = load_state {
        let bytes = std::fs::read(path)
            .with_context(|| format!("cannot read the state file {}", path.display()))?;
        built.world = World::restore(&bytes).with_context(|| format!("{}", path.display()))?;
    }
    Ok(built)
}

/// Refuses `--balloons` with `--load-state`: a snapshot fixes its bodies.
pub fn check_load_state_alone(load_state: Option<&Path>, balloons: Option<u64>) -> Result<()> {
    if load_state.is_some() && balloons.is_some() {
        bail!("--balloons cannot change a world loaded with --load-state");
    }
    Ok(())
}

pub fn run(args: &RunArgs) -> Result<()> {
    check_load_state_alone(args.load_state.as_deref(), args.scene.balloons)?;
    let scene = args.scene.load()?;
    let seconds = args.seconds.unwrap_or(f64::from(scene.sim.duration_s));
    if !(seconds.is_finite() && seconds > 0.0 && seconds <= MAX_SECONDS) {
        bail!("--seconds: expected a number in (0, {MAX_SECONDS}], found {seconds}");
    }
    let mut built = build_or_restore(&scene, args.load_state.as_deref())?;
    let world = &mut built.world;
    let dt = f64::from(world.def().dt);
    let steps = (seconds / dt).round().max(1.0) as u64;

    // Create output files first: a bad path fails before the simulation runs.
    let mut csv = CsvOut::create(
        args.out.as_deref(),
        "t,id,x,y,z,qx,qy,qz,qw",
        write_pose_rows,
    )?;
    let mut ribbons_csv = CsvOut::create(
        args.ribbons_out.as_deref(),
        "t,balloon,point,x,y,z",
        write_ribbon_rows,
    )?;
    if let Some(path) = &args.save_state {
        // Probe the directory now rather than after a long run.
        AtomicFile::create(path)?;
    }

    let progress = progress_bar(steps);
    let write_rows = |world: &World, outs: [&mut Option<CsvOut>; 2]| -> Result<()> {
        for out in outs.into_iter().flatten() {
            out.write(world)?;
        }
        Ok(())
    };
    write_rows(world, [&mut csv, &mut ribbons_csv])?;
    let mut max_penetration = 0.0f32;
    let started = Instant::now();
    for step in 1..=steps {
        world.step();
        max_penetration = max_penetration.max(world.stats().max_penetration);
        if step % args.every == 0 || step == steps {
            write_rows(world, [&mut csv, &mut ribbons_csv])?;
        }
        if let Some(bar) = &progress {
            if step % 16 == 0 {
                bar.set_position(step);
            }
        }
    }
    let wall = started.elapsed().as_secs_f64();
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }
    for out in [csv, ribbons_csv].into_iter().flatten() {
        out.commit()?;
    }
    if let Some(path) = &args.save_state {
        write_atomically(path, &world.snapshot())?;
    }

    let end = measure(world, &built.room);
    let summary = RunSummary {
        scene: args.scene.name(),
        balloons: world.body_count(),
        steps,
        sim_seconds: world.time(),
        wall_seconds: wall,
        ms_per_step: wall * 1000.0 / steps as f64,
        max_penetration_m: max_penetration,
        escaped: end.escaped,
        nan_bodies: end.nan_bodies,
        state_hash: format!("{:016x}", world.state_hash()),
        mean_height_m: end.mean_height_m,
        max_tilt_deg: end.max_tilt_deg,
        median_tilt_deg: end.median_tilt_deg,
        p90_tilt_deg: end.p90_tilt_deg,
        kinetic_energy_j: world.kinetic_energy(),
        awake: world.stats().awake_count,
        ribbons: world.ribbon_count(),
        ribbon_max_stretch: world.ribbon_max_stretch(),
    };
    print_table("up run", &summary.rows());
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    }
    Ok(())
}

/// A CSV file being written, whole or not at all, and how its rows are made.
struct CsvOut<'a> {
    file: AtomicFile,
    path: &'a Path,
    rows: fn(&World, &mut AtomicFile) -> std::io::Result<()>,
}

impl<'a> CsvOut<'a> {
    /// Creates `path` (if given) and writes its header.
    fn create(
        path: Option<&'a Path>,
        header: &str,
        rows: fn(&World, &mut AtomicFile) -> std::io::Result<()>,
    ) -> Result<Option<CsvOut<'a>>> {
        let Some(path) = path else {
            return Ok(None);
        };
        let mut file = AtomicFile::create(path)?;
        writeln!(file, "{header}").with_context(|| format!("cannot write {}", path.display()))?;
        Ok(Some(CsvOut { file, path, rows }))
    }

    /// The rows of the world as it is now.
    fn write(&mut self, world: &World) -> Result<()> {
        (self.rows)(world, &mut self.file)
            .with_context(|| format!("cannot write {}", self.path.display()))
    }

    fn commit(self) -> Result<()> {
        self.file.commit()?;
        Ok(())
    }
}

/// One row per body: time, handle index, position, rotation.
fn write_pose_rows(world: &World, out: &mut AtomicFile) -> std::io::Result<()> {
    let t = world.time();
    for (id, pose) in world.poses() {
        let (p, q) = (pose.position, pose.rotation);
        writeln!(
            out,
            "{t},{},{},{},{},{},{},{},{}",
            id.index, p.x, p.y, p.z, q.x, q.y, q.z, q.w
        )?;
    }
    Ok(())
}

/// One row per ribbon point: time, its balloon's handle index (as in the
/// poses' CSV), the point (0 at the knot), its position.
fn write_ribbon_rows(world: &World, out: &mut AtomicFile) -> std::io::Result<()> {
    let t = world.time();
    for id in world.ribbon_ids() {
        let (Some(body), Some(points)) = (world.ribbon_body(id), world.ribbon_points(id)) else {
            continue;
        };
        for (k, p) in points.iter().enumerate() {
            writeln!(out, "{t},{},{k},{},{},{}", body.index, p.x, p.y, p.z)?;
        }
    }
    Ok(())
}

/// A progress bar on standard error, only when it is a terminal.
pub fn progress_bar(steps: u64) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::with_draw_target(Some(steps), ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("{bar:40} {pos}/{len} steps  {elapsed} (eta {eta})")
    {
        bar.set_style(style);
    }
    Some(bar)
}
