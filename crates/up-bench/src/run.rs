//! A comparison run: build the scene in each engine, step them alternately
//! (UP then Rapier on even steps, Rapier then UP on odd ones, so neither
//! always runs with the other's data in cache), time every step, record the
//! poses at every step (see `measure`), measure overlap and escapes from them
//! once the timed loop is done, and take each engine's peak memory from a
//! child process that runs it alone.
//!
//! With ribbons (`--ribbons`), UP and Rapier both hold them, and a third
//! engine joins the same loop: UP on the same scene without ribbons, for the
//! cost of the ribbons themselves. Every ribbon's stretch is measured after
//! every step (outside the timed step: a pass over the points, too small to
//! record them all instead).

use std::path::PathBuf;
use std::process::Command;
use std::time::Instant;

use anyhow::{bail, Context, Result};
use serde::{Deserialize, Serialize};
use up_geom::Pose;

use crate::core_probe;
use crate::engine::{Engine, EngineKind};
use crate::measure::{measure_every, measure_frames};
use crate::output::EngineResult;
use crate::rapier_engine::{RapierEngine, RapierJoints, RapierShape};
use crate::ribbons::{tie_ribbons, BenchRibbons};
use crate::rss::peak_rss_mb;
use crate::scene_data::SceneData;
use crate::stats::{mean, median, quantile, settled};
use crate::step_times;
use crate::up_engine::UpEngine;
use up_physics::ThreadSums;

/// Most steps a run takes.
pub const MAX_STEPS: u64 = 1_000_000;

/// s: the start of a run with ribbons, reported apart. The scene lays each
/// ribbon straight down from its knot, through the balloons packed below
/// it, and both engines first push the ribbons out of them.
pub const RIBBON_START_S: f32 = 1.0;

#[derive(Clone, Debug)]
pub struct RunOptions {
    pub balloons: u64,
    pub steps: u64,
    pub seed: u64,
    /// Threads for UP (Rapier always runs on one).
    pub threads: usize,
    pub engines: Vec<EngineKind>,
    pub rapier_shape: RapierShape,
    /// Measure peak memory in child processes (doubles the run time).
    pub rss: bool,
    /// Where to write every step's time (`step_times`), if anywhere.
    pub step_times: Option<PathBuf>,
    /// Tie the default ribbon to every balloon (`ribbons`), in every engine.
    pub ribbons: bool,
    /// How Rapier joints a ribbon's balls.
    pub rapier_joints: RapierJoints,
    /// Time each of UP's threads in each stage (`thread_times`).
    pub thread_times: bool,
}

/// What a memory probe child prints.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
pub struct RssProbe {
    /// MB: the child's peak resident set before the scene was built.
    pub baseline_rss_mb: f64,
    /// MB: its peak at the end.
    pub peak_rss_mb: f64,
}

/// Steps the benchmark takes by default for a room whose walls and apex are
/// `wall_height + apex_height` m high: twice the time a balloon takes to rise
/// that far at its terminal speed (≈ 1.7 m/s), plus 2 s, and at least 600.
pub fn default_steps(top_m: f32, dt: f32) -> u64 {
    const TERMINAL_SPEED: f32 = 1.7;
    let seconds = 2.0 * top_m / TERMINAL_SPEED + 2.0;
    ((seconds / dt).ceil() as u64).max(600)
}

/// One engine of a run: which, and whether its balloons have ribbons.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Slot {
    kind: EngineKind,
    ribbons: bool,
}

/// The engines a run steps: those asked for, with ribbons if asked, and then
/// UP without ribbons when UP runs with them.
fn slots(opts: &RunOptions) -> Vec<Slot> {
    let mut slots: Vec<Slot> = opts
        .engines
        .iter()
        .map(|&kind| Slot {
            kind,
            ribbons: opts.ribbons,
        })
        .collect();
    if opts.ribbons && opts.engines.contains(&EngineKind::Up) {
        slots.push(Slot {
            kind: EngineKind::Up,
            ribbons: false,
        });
    }
    slots
}

/// UP's world, taken once, with the ribbons (built once, from it) or without.
struct UpWorlds {
    with_ribbons: Option<up_physics::World>,
    ribbons: Option<BenchRibbons>,
}

fn build_engine(
    slot: Slot,
    data: &SceneData,
    worlds: &mut UpWorlds,
    opts: &RunOptions,
) -> Result<Box<dyn Engine>> {
    Ok(match (slot.kind, slot.ribbons) {
        (EngineKind::Up, true) => {
            let world = worlds
                .with_ribbons
                .take()
                .context("UP may appear only once in --engines")?;
            Box::new(UpEngine::new(world, opts.threads)?)
        }
        (EngineKind::Up, false) if opts.ribbons => {
            let built = up_scene::build::build_world(&data.scene)
                .context("building the benchmark scene again, without ribbons")?;
            Box::new(UpEngine::new(built.world, opts.threads)?)
        }
        (EngineKind::Up, false) => {
            let world = worlds
                .with_ribbons
                .take()
                .context("UP may appear only once in --engines")?;
            Box::new(UpEngine::new(world, opts.threads)?)
        }
        (EngineKind::Rapier, true) => {
            let ribbons = worlds.ribbons.as_ref().context("ribbons not tied")?;
            Box::new(RapierEngine::with_ribbons(
                data,
                opts.rapier_shape,
                ribbons,
                opts.rapier_joints,
            )?)
        }
        (EngineKind::Rapier, false) => Box::new(RapierEngine::new(data, opts.rapier_shape)?),
    })
}

/// UP's world from the scene builder, with ribbons tied if the run has them.
fn up_worlds(
    data: &SceneData,
    mut world: up_physics::World,
    opts: &RunOptions,
) -> Result<UpWorlds> {
    let ribbons = if opts.ribbons {
        Some(tie_ribbons(&mut world, data.knot)?)
    } else {
        None
    };
    Ok(UpWorlds {
        with_ribbons: Some(world),
        ribbons,
    })
}

fn check(opts: &RunOptions) -> Result<()> {
    if opts.steps == 0 || opts.steps > MAX_STEPS {
        bail!("--steps: expected 1 to {MAX_STEPS}, found {}", opts.steps);
    }
    if opts.threads == 0 || opts.threads > 1024 {
        bail!("--threads: expected 1 to 1024, found {}", opts.threads);
    }
    if opts.engines.is_empty() {
        bail!("--engines: expected up, rapier or both");
    }
    if let Some(path) = &opts.step_times {
        step_times::check_target(path)?;
    }
    Ok(())
}

/// Runs the comparison; one result per engine, in the order of `opts.engines`.
pub fn run(opts: &RunOptions) -> Result<Vec<EngineResult>> {
    check(opts)?;
    let (data, built) = SceneData::build(opts.balloons, opts.seed)?;
    let mut worlds = up_worlds(&data, built.world, opts)?;
    let slots = slots(opts);
    let mut engines = slots
        .iter()
        .map(|&slot| build_engine(slot, &data, &mut worlds, opts))
        .collect::<Result<Vec<_>>>()?;
    drop(worlds);

    let steps = opts.steps as usize;
    let every = measure_every(opts.balloons, opts.steps);
    let mut times: Vec<Vec<f64>> = vec![Vec::with_capacity(steps); engines.len()];
    let mut frames: Vec<Vec<Vec<Pose>>> = vec![Vec::new(); engines.len()];
    let mut poses: Vec<Pose> = Vec::new();
    let mut stretch: Vec<Option<f32>> = vec![None; engines.len()];
    let mut stretch_late: Vec<Option<f32>> = vec![None; engines.len()];
    let mut stretch_step: Vec<u64> = vec![0; engines.len()];
    let late_from = (RIBBON_START_S / data.def.dt).round() as u64;
    let mut stages: Vec<Vec<(&'static str, f64)>> = vec![Vec::new(); engines.len()];
    let mut threads: Vec<ThreadSums> = vec![ThreadSums::default(); engines.len()];
    up_physics::set_thread_timing(opts.thread_times);
    let probe_cores = opts.thread_times && opts.threads > 1;
    let round_trip_before = probe_cores.then(core_probe::round_trip_ns).flatten();
    let mut scratch = Vec::new();
    let order: Vec<usize> = (0..engines.len()).collect();
    for step in 1..=opts.steps {
        // Alternate who goes first.
        let forward = step % 2 == 1;
        for k in 0..engines.len() {
            let i = if forward {
                order[k]
            } else {
                order[engines.len() - 1 - k]
            };
            let started = Instant::now();
            engines[i].step();
            times[i].push(started.elapsed().as_secs_f64() * 1e3);
        }
        for (i, engine) in engines.iter().enumerate() {
            if let Some(now) = engine.max_ribbon_stretch(&mut scratch) {
                let worst = worse(stretch[i], now);
                if Some(worst) != stretch[i] {
                    stretch_step[i] = step;
                }
                stretch[i] = Some(worst);
                if step > late_from {
                    stretch_late[i] = Some(worse(stretch_late[i], now));
                }
            }
            if let Some(counters) = engine.counters() {
                add_stages(&mut stages[i], &counters.stages());
                threads[i].add(&counters);
            }
        }
        if step % every == 0 || step == opts.steps {
            for (i, engine) in engines.iter().enumerate() {
                engine.poses(&mut poses);
                frames[i].push(poses.clone());
            }
        }
    }

    let round_trip_after = probe_cores.then(core_probe::round_trip_ns).flatten();
    let round_trips = round_trip_before.zip(round_trip_after).map(|(a, b)| [a, b]);

    if let Some(path) = &opts.step_times {
        let names: Vec<&str> = engines.iter().map(|e| e.name()).collect();
        step_times::write(path, &names, &times)?;
    }

    let mut results = Vec::with_capacity(engines.len());
    for (i, engine) in engines.iter().enumerate() {
        let measured = measure_frames(&data, &std::mem::take(&mut frames[i]))?;
        let Slot { kind, ribbons } = slots[i];
        // Memory is probed for the engines asked for, not UP's bare reference.
        let rss = if opts.rss && ribbons == opts.ribbons {
            Some(probe_in_child(kind, opts)?)
        } else {
            None
        };
        let t = &times[i];
        results.push(EngineResult {
            engine: engine.name().to_string(),
            runtime: "native".to_string(),
            balloons: opts.balloons,
            steps: opts.steps,
            threads: if kind == EngineKind::Up {
                opts.threads
            } else {
                1
            },
            ms_per_step_median: median(t),
            ms_per_step_p95: quantile(t, 0.95),
            ms_per_step_mean: mean(t),
            settled_ms_per_step_median: median(settled(t)),
            max_penetration_m: measured.max_penetration_m,
            final_penetration_m: measured.final_penetration_m,
            escaped: measured.escaped,
            awake_at_end: engine.awake_count(),
            peak_rss_mb: rss.map(|r| r.peak_rss_mb),
            rss_bytes_per_balloon: rss
                .map(|r| (r.peak_rss_mb - r.baseline_rss_mb) * 1e6 / opts.balloons as f64),
            room_width_m: data.layout.room_width_m,
            rapier_shape: (kind == EngineKind::Rapier).then(|| opts.rapier_shape.name().into()),
            ribbons: engine.ribbon_count(),
            max_ribbon_stretch: stretch[i],
            max_ribbon_stretch_step: stretch[i].map(|_| stretch_step[i]),
            max_ribbon_stretch_after_start: stretch_late[i],
            rapier_joints: (kind == EngineKind::Rapier && ribbons)
                .then(|| opts.rapier_joints.name().into()),
            stage_ms_mean: (!stages[i].is_empty()).then(|| {
                stages[i]
                    .iter()
                    .map(|&(name, total)| (name.to_string(), total / opts.steps as f64))
                    .collect()
            }),
            stage_threads_mean: Some(threads[i].means()).filter(|rows| !rows.is_empty()),
            core_round_trip_ns: round_trips.filter(|_| kind == EngineKind::Up),
        });
    }
    Ok(results)
}

/// The larger stretch, NaN (a ribbon gone non-finite) the largest.
fn worse(so_far: Option<f32>, now: f32) -> f32 {
    match so_far {
        Some(s) if s.is_nan() || s >= now => s,
        _ => now,
    }
}

/// Adds a step's stage times to the run's totals.
fn add_stages(totals: &mut Vec<(&'static str, f64)>, step: &[(&'static str, f64)]) {
    if totals.is_empty() {
        totals.extend(step.iter().map(|&(name, _)| (name, 0.0)));
    }
    for (total, &(_, ms)) in totals.iter_mut().zip(step) {
        total.1 += ms;
    }
}

/// The memory probe, run in a child: builds the scene and `kind` alone, takes
/// the steps, and reports the peak resident set.
pub fn rss_probe(kind: EngineKind, opts: &RunOptions) -> Result<RssProbe> {
    check(opts)?;
    let baseline_rss_mb = peak_rss_mb().context("reading /proc/self/status")?;
    let (data, built) = SceneData::build(opts.balloons, opts.seed)?;
    let mut worlds = up_worlds(&data, built.world, opts)?;
    if kind == EngineKind::Rapier {
        // UP's world is not kept while Rapier runs.
        worlds.with_ribbons = None;
    }
    let slot = Slot {
        kind,
        ribbons: opts.ribbons,
    };
    let mut engine = build_engine(slot, &data, &mut worlds, opts)?;
    drop(worlds);
    for _ in 0..opts.steps {
        engine.step();
    }
    Ok(RssProbe {
        baseline_rss_mb,
        peak_rss_mb: peak_rss_mb().context("reading /proc/self/status")?,
    })
}

fn probe_in_child(kind: EngineKind, opts: &RunOptions) -> Result<RssProbe> {
    let exe = std::env::current_exe().context("finding the up-bench executable")?;
    let output = Command::new(&exe)
        .arg("rss-probe")
        .args(["--engine", kind.name()])
        .args(["--balloons", &opts.balloons.to_string()])
        .args(["--steps", &opts.steps.to_string()])
        .args(["--seed", &opts.seed.to_string()])
        .args(["--threads", &opts.threads.to_string()])
        .args(["--rapier-shape", opts.rapier_shape.name()])
        .args(["--rapier-joints", opts.rapier_joints.name()])
        .args(opts.ribbons.then_some("--ribbons"))
        .output()
        .with_context(|| format!("running {}", exe.display()))?;
    if !output.status.success() {
        bail!(
            "memory probe for {} failed: {}",
            kind.name(),
            String::from_utf8_lossy(&output.stderr).trim()
        );
    }
    let text = String::from_utf8_lossy(&output.stdout);
    let line = text.lines().last().unwrap_or_default();
    serde_json::from_str(line).with_context(|| {
        format!(
            "memory probe for {}: unexpected output {line:?}",
            kind.name()
        )
    })
}
