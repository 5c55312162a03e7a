//! `up bench`: time the UP engine alone on a scene, stage by stage.

use std::path::PathBuf;
use std::time::Instant;

use anyhow::{bail, Result};
use clap::Args;
use serde::Serialize;

use crate::run::{build_or_restore, check_load_state_alone, progress_bar};
use crate::scene_arg::SceneArgs;
use crate::summary::print_table;

/// Most steps `--steps` accepts.
const MAX_STEPS: u64 = 10_000_000;

#[derive(Args, Debug)]
pub struct BenchArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Steps to time (after the scene is built; building is not timed).
    #[arg(long, value_name = "K", default_value_t = 600)]
    pub steps: u64,
    /// End with one JSON object on the last line of standard output.
    #[arg(long)]
    pub json: bool,
    /// Time a world saved with `up run --save-state` (a pile mid-arrival,
    /// say) instead of the scene's spawn; the scene still gives the room.
    #[arg(long, value_name = "FILE")]
    pub load_state: Option<PathBuf>,
}

/// Mean time of one stage of the step.
#[derive(Debug, Serialize)]
pub struct StageTime {
    pub name: String,
    pub ms_per_step: f64,
}

/// The last line of `up bench --json`. Times in ms per step.
#[derive(Debug, Serialize)]
pub struct BenchSummary {
    pub scene: String,
    pub balloons: usize,
    /// Threads that stepped the world.
    pub threads: usize,
    pub steps: u64,
    pub sim_seconds: f64,
    pub wall_seconds: f64,
    pub ms_per_step: f64,
    pub median_ms: f64,
    pub p95_ms: f64,
    pub max_ms: f64,
    /// Mean ms per step in each stage, in the order a step runs them (the
    /// engine's own counters, one per stage under its name; `total` is the
    /// engine's timing of the whole step).
    pub stages: Vec<StageTime>,
    /// The same summed by phase (broadphase, solve, ribbons, ...), each
    /// where its first stage runs, then `total` (`Counters::phases`).
    pub phases: Vec<StageTime>,
    pub max_penetration_m: f32,
    pub state_hash: String,
}

pub fn run(args: &BenchArgs) -> Result<()> {
    if args.steps == 0 || args.steps > MAX_STEPS {
        bail!("--steps: expected 1 to {MAX_STEPS}, found {}", args.steps);
    }
    check_load_state_alone(args.load_state.as_deref(), args.scene.balloons)?;
    let scene = args.scene.load()?;
    let mut built = build_or_restore(&scene, args.load_state.as_deref())?;
    let world = &mut built.world;

    let mut step_ms = Vec::with_capacity(args.steps as usize);
    let mut stage_sums: Vec<(&'static str, f64)> = world.counters().stages();
    stage_sums.iter_mut().for_each(|(_, ms)| *ms = 0.0);
    let mut phase_sums: Vec<(&'static str, f64)> = world.counters().phases();
    phase_sums.iter_mut().for_each(|(_, ms)| *ms = 0.0);
    let mut max_penetration = 0.0f32;
    let progress = progress_bar(args.steps, "steps");
    let started = Instant::now();
    for step in 1..=args.steps {
        let t0 = Instant::now();
        world.step();
        step_ms.push(t0.elapsed().as_secs_f64() * 1000.0);
        for (sum, (_, ms)) in stage_sums.iter_mut().zip(world.counters().stages()) {
            sum.1 += ms;
        }
        for (sum, (_, ms)) in phase_sums.iter_mut().zip(world.counters().phases()) {
            sum.1 += ms;
        }
        max_penetration = max_penetration.max(world.stats().max_penetration);
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

    let n = step_ms.len() as f64;
    let mut sorted = step_ms.clone();
    sorted.sort_by(f64::total_cmp);
    let percentile = |p: f64| sorted[((sorted.len() - 1) as f64 * p).round() as usize];
    let summary = BenchSummary {
        scene: args.scene.name(),
        balloons: world.body_count(),
        threads: rayon::current_num_threads(),
        steps: args.steps,
        sim_seconds: world.time(),
        wall_seconds: wall,
        ms_per_step: step_ms.iter().sum::<f64>() / n,
        median_ms: percentile(0.5),
        p95_ms: percentile(0.95),
        max_ms: sorted[sorted.len() - 1],
        stages: means(&stage_sums, n),
        phases: means(&phase_sums, n),
        max_penetration_m: max_penetration,
        state_hash: format!("{:016x}", world.state_hash()),
    };

    let mut rows = vec![
        ("scene", summary.scene.clone()),
        ("balloons", summary.balloons.to_string()),
        ("threads", summary.threads.to_string()),
        ("steps", summary.steps.to_string()),
        ("simulated", format!("{:.3} s", summary.sim_seconds)),
        ("wall clock", format!("{:.3} s", summary.wall_seconds)),
        ("mean", format!("{:.3} ms/step", summary.ms_per_step)),
        ("median", format!("{:.3} ms/step", summary.median_ms)),
        ("p95", format!("{:.3} ms/step", summary.p95_ms)),
        ("max", format!("{:.3} ms/step", summary.max_ms)),
    ];
    let indented = |times: &[StageTime]| -> Vec<(String, String)> {
        times
            .iter()
            .map(|s| {
                (
                    format!("  {}", s.name),
                    format!("{:.3} ms/step", s.ms_per_step),
                )
            })
            .collect()
    };
    let (stage_rows, phase_rows) = (indented(&summary.stages), indented(&summary.phases));
    rows.push(("stages (mean)", String::new()));
    rows.extend(
        stage_rows
            .iter()
            .map(|(name, value)| (name.as_str(), value.clone())),
    );
    rows.push(("phases (mean)", String::new()));
    rows.extend(
        phase_rows
            .iter()
            .map(|(name, value)| (name.as_str(), value.clone())),
    );
    rows.push((
        "max penetration",
        format!("{:.2} mm", summary.max_penetration_m * 1000.0),
    ));
    rows.push(("state hash", summary.state_hash.clone()));
    print_table("up bench", &rows);
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    }
    Ok(())
}

/// Each sum over `steps` steps as a mean per step.
fn means(sums: &[(&'static str, f64)], steps: f64) -> Vec<StageTime> {
    sums.iter()
        .map(|(name, sum)| StageTime {
            name: name.to_string(),
            ms_per_step: sum / steps,
        })
        .collect()
}
