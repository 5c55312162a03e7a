//! `up run`: simulate a scene headless.

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{bail, Context, Result};
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use up_physics::divergence::{body_hash_header, body_hash_line};
use up_physics::World;
use up_scene::build::{build_world, BuiltScene};
use up_scene::scene::Scene;

use crate::scene_arg::SceneArgs;
use crate::summary::{measure, print_table, RunSummary};
use up_scene::atomic_file::{write_atomically, AtomicFile};

/// Longest run `--seconds` accepts, s (one simulated day).
const MAX_SECONDS: f64 = 86_400.0;
/// Longest run `--hours` accepts, h (the scenes' `filled_hours_before` range).
pub const MAX_HOURS: f64 = 2000.0;
/// s of simulated time per `World::advance` call of a time-lapse: a CSV row
/// set, a progress tick and a penetration sample each.
pub const LAPSE_CHUNK_S: f64 = 60.0;

#[derive(Args, Debug)]
pub struct RunArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Simulated seconds; the scene's `sim.duration_s` (10 s by default) if left out.
    #[arg(
        long,
        value_name = "S",
        conflicts_with = "hours",
        allow_negative_numbers = true
    )]
    pub seconds: Option<f64>,
    /// Simulated hours, in (0, 2000], as a time-lapse: the same physics as a
    /// stepped run (`World::advance`: every step while anything moves; while
    /// every balloon sleeps, only the gas goes on, a minute at a time, until
    /// its lift change wakes them). CSV rows every K simulated minutes.
    #[arg(long, value_name = "H", allow_negative_numbers = true)]
    pub hours: Option<f64>,
    /// Write the trajectory as CSV: `t,id,x,y,z,qx,qy,qz,qw` (s, m, unit quaternion; Y up).
    #[arg(long, value_name = "FILE.csv")]
    pub out: Option<PathBuf>,
    /// Write the ribbons' points as CSV: `t,balloon,point,x,y,z` (s, the
    /// balloon's id as in --out, the point from 0 at the knot to the free end, m).
    #[arg(long, value_name = "FILE.csv")]
    pub ribbons_out: Option<PathBuf>,
    /// Write a CSV row set every K steps (with --hours: every K simulated
    /// minutes), to --out and --ribbons-out (the first and last steps are
    /// always written).
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
    /// Write every body's state hashes at the start and after each step
    /// (`up_physics::divergence::body_hash_line`: a line a step, after a
    /// header): two runs whose end hashes differ compare these to find the
    /// first step and body where they part (web/determinism/check.mjs does).
    #[arg(long, value_name = "FILE", conflicts_with = "hours")]
    pub body_hashes: Option<PathBuf>,
    #[command(flatten)]
    pub probe: crate::probe::ProbeArgs,
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

/// `--hours`, checked: finite, in (0, MAX_HOURS].
pub fn check_hours(hours: f64) -> Result<f64> {
    if !(hours.is_finite() && hours > 0.0 && hours <= MAX_HOURS) {
        bail!("--hours: expected a number of hours in (0, {MAX_HOURS}], found {hours}");
    }
    Ok(hours)
}

/// How long a run goes and how: stepping every frame, or a time-lapse.
#[derive(Clone, Copy, Debug)]
enum Length {
    Steps(u64),
    Lapse { seconds: f64 },
}

pub fn run(args: &RunArgs) -> Result<()> {
    check_load_state_alone(args.load_state.as_deref(), args.scene.balloons)?;
    let hours = args.hours.map(check_hours).transpose()?;
    let scene = args.scene.load()?;
    let mut built = build_or_restore(&scene, args.load_state.as_deref())?;
    let world = &mut built.world;
    let length = match hours {
        Some(hours) => Length::Lapse {
            seconds: hours * 3600.0,
        },
        None => {
            let seconds = args.seconds.unwrap_or(f64::from(scene.sim.duration_s));
            if !(seconds.is_finite() && seconds > 0.0 && seconds <= MAX_SECONDS) {
                bail!("--seconds: expected a number in (0, {MAX_SECONDS}], found {seconds}");
            }
            let dt = f64::from(world.def().dt);
            Length::Steps((seconds / dt).round().max(1.0) as u64)
        }
    };

    // Create output files first: a bad path fails before the simulation runs.
    let mut probe = crate::probe::ProbeCsv::create(&args.probe, world)?;
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
    let mut body_hashes = CsvOut::create(
        args.body_hashes.as_deref(),
        &body_hash_header(),
        write_body_hash_line,
    )?;
    if let Some(out) = &mut body_hashes {
        out.write(world)?;
    }
    if let Some(path) = &args.save_state {
        // Probe the directory now rather than after a long run.
        AtomicFile::create(path)?;
    }

    let mut write_rows = |world: &World| -> Result<()> {
        for out in [&mut csv, &mut ribbons_csv].into_iter().flatten() {
            out.write(world)?;
        }
        Ok(())
    };
    write_rows(world)?;
    let start_time = world.time();
    let started = Instant::now();
    let ran = match length {
        Length::Steps(steps) => {
            let mut each_step = |world: &World| -> Result<()> {
                if let Some(p) = &mut probe {
                    p.write(world)?;
                }
                body_hashes.as_mut().map_or(Ok(()), |out| out.write(world))
            };
            step_every_frame(world, steps, args.every, &mut write_rows, &mut each_step)?
        }
        Length::Lapse { seconds } => time_lapse(world, seconds, args.every, &mut write_rows)?,
    };
    let wall = started.elapsed().as_secs_f64();
    for out in [csv, ribbons_csv, body_hashes].into_iter().flatten() {
        out.commit()?;
    }
    if let Some(probe) = probe {
        probe.commit()?;
    }
    if let Some(path) = &args.save_state {
        write_atomically(path, &world.snapshot())?;
    }

    let end = measure(world, &built.room);
    let summary = RunSummary {
        scene: args.scene.name(),
        balloons: world.body_count(),
        steps: ran.steps,
        jumps: ran.jumps,
        sim_seconds: world.time(),
        sim_time_s: world.time() - start_time,
        wall_seconds: wall,
        ms_per_step: wall * 1000.0 / ran.steps.max(1) as f64,
        max_penetration_m: ran.max_penetration,
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
        mean_lift_fraction: mean_lift_fraction(world),
    };
    print_table("up run", &summary.rows());
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    }
    Ok(())
}

/// What a run did.
struct Ran {
    steps: u64,
    jumps: u64,
    /// m: the deepest overlap seen (every step, or each chunk's last in a time-lapse).
    max_penetration: f32,
}

/// Steps `steps` frames, writing rows every `every` and after the last,
/// and `each_step`'s after every step.
fn step_every_frame(
    world: &mut World,
    steps: u64,
    every: u64,
    write_rows: &mut dyn FnMut(&World) -> Result<()>,
    each_step: &mut dyn FnMut(&World) -> Result<()>,
) -> Result<Ran> {
    let progress = progress_bar(steps, "steps");
    let mut max_penetration = 0.0f32;
    for step in 1..=steps {
        world.step();
        each_step(world)?;
        max_penetration = max_penetration.max(world.stats().max_penetration);
        if step % every == 0 || step == steps {
            write_rows(world)?;
        }
        if let Some(bar) = &progress {
            if step % 16 == 0 {
                bar.set_position(step);
            }
        }
    }
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }
    Ok(Ran {
        steps,
        jumps: 0,
        max_penetration,
    })
}

/// Advances `seconds` of simulated time by `World::advance`, a chunk of
/// `LAPSE_CHUNK_S` at a time, writing rows every `every` chunks and after the last.
fn time_lapse(
    world: &mut World,
    seconds: f64,
    every: u64,
    write_rows: &mut dyn FnMut(&World) -> Result<()>,
) -> Result<Ran> {
    let chunks = (seconds / LAPSE_CHUNK_S).ceil().max(1.0) as u64;
    let progress = progress_bar(chunks, "simulated min");
    let mut ran = Ran {
        steps: 0,
        jumps: 0,
        max_penetration: 0.0,
    };
    let mut left = seconds;
    for chunk in 1..=chunks {
        let ask = if chunk == chunks { left } else { LAPSE_CHUNK_S };
        let (steps, jumps) = advance_fully(world, ask);
        ran.steps += steps;
        ran.jumps += jumps;
        left -= ask;
        ran.max_penetration = ran.max_penetration.max(world.stats().max_penetration);
        if chunk % every == 0 || chunk == chunks {
            write_rows(world)?;
        }
        if let Some(bar) = &progress {
            bar.set_position(chunk);
        }
    }
    if let Some(bar) = progress {
        bar.finish_and_clear();
    }
    Ok(ran)
}

/// `World::advance` until `seconds` have passed (it stops early when its
/// step budget runs out); returns the steps and jumps taken.
pub fn advance_fully(world: &mut World, seconds: f64) -> (u64, u64) {
    // Steps per call: a minute stepped at 1/60 s is 3,600; the budget only
    // bounds one call's time, the loop goes on.
    const MAX_STEPS: u64 = 1 << 20;
    let (mut steps, mut jumps, mut left) = (0, 0, seconds);
    while left > 0.0 {
        let done = world.advance(left, MAX_STEPS);
        steps += done.steps;
        jumps += done.jumps;
        if done.seconds <= 0.0 {
            // Nothing moved the clock: stop rather than spin.
            break;
        }
        left -= done.seconds;
    }
    (steps, jumps)
}

/// Mean over the balloons that carry gas of `Gas::lift_fraction` in the
/// room's air now; None when none does.
pub fn mean_lift_fraction(world: &World) -> Option<f64> {
    let air = world.air();
    let (sum, n) = world
        .body_ids()
        .iter()
        .filter_map(|&id| world.gas(id))
        .fold((0.0, 0u64), |(sum, n), gas| {
            (sum + gas.lift_fraction(&air), n + 1)
        });
    (n > 0).then(|| sum / n as f64)
}

/// A CSV (or other line) file being written, whole or not at all, and how its rows are made.
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

/// The world's `body_hash_line`: the step, the state hash, each body's field hashes.
fn write_body_hash_line(world: &World, out: &mut AtomicFile) -> std::io::Result<()> {
    writeln!(out, "{}", body_hash_line(world))
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

/// A progress bar of `len` `unit` on standard error, only when it is a terminal.
pub fn progress_bar(len: u64, unit: &str) -> Option<ProgressBar> {
    if !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::stderr());
    let template = format!("{{bar:40}} {{pos}}/{{len}} {unit}  {{elapsed}} (eta {{eta}})");
    if let Ok(style) = ProgressStyle::with_template(&template) {
        bar.set_style(style);
    }
    Some(bar)
}
