//! `up soak`: a long run that checks the world's health as it goes: every
//! pose finite, no balloon outside the room, the deepest overlap within 1 %
//! of the balloon radius, and the heap flat after the first simulated minute
//! (bytes held, `heap_meter`; resident memory is shown beside it).
//!
//! A scene file keeps its groups' counts unless `--balloons` spreads a
//! total over them. Without one the room is sized for the balloons (10,000
//! unless `--balloons` says; a pyramid-roofed box of at least 6 m × 6 m,
//! about 20 balloons per m² of floor); its balloons have no ribbons (the original room's
//! are left off, so the soak stays the pile it was written for; a scene file
//! with ribbons soaks them). Every `--stir-every` seconds (300 by default) every
//! tenth balloon is thrown, so a long run keeps waking the pile rather than
//! watching it sleep. The checks print as a table, one row per check;
//! the run fails (exit 2) at the end if any check failed.

use std::time::Instant;

use anyhow::{bail, Result};
use clap::Args;
use glam::Vec3;
use serde::Serialize;
use up_geom::SplitMix64;
use up_physics::{BodyId, World};
use up_scene::build::build_world;
use up_scene::room::RoomMesh;
use up_scene::scene::Scene;

use crate::heap_meter::held_bytes;
use crate::scene_arg::SceneArgs;
use crate::summary::print_table;

/// Longest soak `--seconds` accepts, s (one simulated day).
const MAX_SECONDS: f64 = 86_400.0;
/// Allowed overlap, as a fraction of the smallest balloon radius.
const PENETRATION_FRACTION: f32 = 0.01;
/// Simulated time after which memory must stay flat, s.
const SETTLE_SECONDS: f64 = 60.0;
/// Allowed heap growth after the first minute, bytes: a pile asleep again
/// after stirs may keep more contacts' impulses, and buffers keep up to four
/// times their use (up-physics `spare`). A leak of 40 bytes a step is more
/// within an hour at 60 steps a second.
const HEAP_SLACK_BYTES: u64 = 8 << 20;
/// Mixed into the scene's seed for the stirring's own sequence.
const STIR_SEED: u64 = 0x5715_0000;
/// Balloons in the room made for them when neither a scene nor `--balloons` is given.
const DEFAULT_BALLOONS: u64 = 10_000;
/// Balloons per m² of floor in the room made for `--balloons`.
const BALLOONS_PER_M2: f64 = 20.0;

#[derive(Args, Debug)]
#[command(
    mut_arg("scene", |a| a.help("Scene file (.toml or .json); without one, a room sized for --balloons")),
    mut_arg("balloons", |a| a.help("Total number of balloons, spread over the scene's groups (overrides the scene's counts); without a scene file, 10000 if left out")),
)]
pub struct SoakArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Simulated seconds.
    #[arg(long, value_name = "S", default_value_t = 3600.0)]
    pub seconds: f64,
    /// Check every K steps (penetration is tracked at every step regardless).
    #[arg(long, value_name = "K", default_value_t = 600,
          value_parser = clap::value_parser!(u64).range(1..))]
    pub check_every: u64,
    /// Every S simulated seconds, throw every tenth balloon at up to 2 m/s along
    /// each axis, spinning up to 3 rad/s (seeded), so that the run keeps
    /// waking the pile instead of watching it sleep; 0: never.
    #[arg(long, value_name = "S", default_value_t = 300.0)]
    pub stir_every: f64,
    /// Keep every balloon awake (sleep off): the whole pile is simulated at every step.
    #[arg(long)]
    pub no_sleep: bool,
    /// End with one JSON object on the last line of standard output.
    #[arg(long)]
    pub json: bool,
}

/// One row of the soak's table.
#[derive(Clone, Debug, Serialize)]
pub struct SoakCheck {
    pub sim_seconds: f64,
    pub steps: u64,
    /// Deepest overlap over the steps since the previous check, m.
    pub max_penetration_m: f32,
    pub non_finite: usize,
    pub escaped: usize,
    pub awake: u32,
    /// Bytes held on the heap (`heap_meter`).
    pub heap_bytes: u64,
    /// Resident memory of the process, bytes (0 where /proc is missing).
    pub rss_bytes: u64,
    /// Mean wall-clock time per step since the previous check, ms.
    pub ms_per_step: f64,
}

/// The last line of `up soak --json`.
#[derive(Debug, Serialize)]
pub struct SoakSummary {
    pub scene: String,
    pub balloons: usize,
    pub steps: u64,
    /// Times every tenth balloon was thrown (`--stir-every`).
    pub stirs: u64,
    pub sim_seconds: f64,
    pub wall_seconds: f64,
    pub ms_per_step: f64,
    /// Deepest overlap over the whole run, m, and the bound it is held to.
    pub max_penetration_m: f32,
    pub penetration_bound_m: f32,
    pub max_non_finite: usize,
    pub max_escaped: usize,
    /// Whether the run reached a minute, so that the heap was held to staying
    /// flat after it; a shorter run says so rather than pass the check unmade.
    pub heap_checked: bool,
    /// Heap held at the first check at or after one simulated minute, and at the end, bytes.
    pub heap_at_1min_bytes: u64,
    pub heap_end_bytes: u64,
    /// Resident memory at the same two checks, bytes (0 where /proc is missing).
    pub rss_at_1min_bytes: u64,
    pub rss_end_bytes: u64,
    pub state_hash: String,
    /// What failed; empty when the soak passed.
    pub failures: Vec<String>,
    pub checks: Vec<SoakCheck>,
}

/// Resident set size of this process, bytes, from `/proc/self/statm`.
pub fn resident_bytes() -> u64 {
    let Ok(text) = std::fs::read_to_string("/proc/self/statm") else {
        return 0;
    };
    let pages: u64 = text
        .split_whitespace()
        .nth(1)
        .and_then(|w| w.parse().ok())
        .unwrap_or(0);
    pages * 4096
}

/// The default scene with a room wide enough for `balloons` on the floor.
fn room_for(balloons: u64) -> Scene {
    let mut scene = Scene::default();
    for group in &mut scene.balloons {
        group.ribbon = None;
    }
    // Capped at the largest room: an absurd count is then refused by its own key.
    let side = (balloons as f64 / BALLOONS_PER_M2)
        .sqrt()
        .ceil()
        .clamp(6.0, 1000.0) as f32;
    scene.room.width = side;
    scene.room.depth = side;
    scene
}

pub fn run(args: &SoakArgs) -> Result<()> {
    if !(args.seconds.is_finite() && args.seconds > 0.0 && args.seconds <= MAX_SECONDS) {
        bail!(
            "--seconds: expected a number in (0, {MAX_SECONDS}], found {}",
            args.seconds
        );
    }
    if !(args.stir_every.is_finite() && args.stir_every >= 0.0) {
        bail!(
            "--stir-every: expected a number of seconds ≥ 0, found {}",
            args.stir_every
        );
    }
    let scene = match &args.scene.scene {
        // The scene's own counts unless `--balloons` is given.
        Some(_) => args.scene.load()?,
        None => {
            let balloons = args.scene.balloons.unwrap_or(DEFAULT_BALLOONS);
            let mut scene = room_for(balloons);
            if let Some(seed) = args.scene.seed {
                scene.sim.seed = seed;
            }
            scene.with_total_balloons(balloons)?
        }
    };
    let mut scene = scene;
    if args.no_sleep {
        scene.sim.sleep = false;
    }
    let radius = scene
        .balloons
        .iter()
        .filter(|g| g.count > 0)
        .map(|g| g.diameter() / 2.0)
        .fold(f32::INFINITY, f32::min);
    let bound = PENETRATION_FRACTION * radius;
    let mut built = build_world(&scene)?;
    let world = &mut built.world;
    let steps = (args.seconds / f64::from(world.def().dt)).round().max(1.0) as u64;
    let stir_steps = (args.stir_every / f64::from(world.def().dt)).round() as u64;
    let mut stir_rng = SplitMix64::new(scene.sim.seed ^ STIR_SEED);
    let mut stirs = 0u64;
    eprintln!(
        "up soak: {} balloons, {steps} steps, room {} m × {} m; checks every {} steps",
        world.body_count(),
        scene.room.width,
        scene.room.depth,
        args.check_every
    );

    // Reserved whole now: records growing later would count as a leak.
    let mut checks = Vec::with_capacity((steps / args.check_every + 1) as usize);
    let mut window_penetration = 0.0f32;
    let mut window_start = Instant::now();
    let mut window_steps = 0u64;
    let started = Instant::now();
    let mut at_1min = None;
    for step in 1..=steps {
        world.step();
        window_penetration = window_penetration.max(world.stats().max_penetration);
        window_steps += 1;
        if stir_steps > 0 && step % stir_steps == 0 && step < steps {
            stir(world, &mut stir_rng)?;
            stirs += 1;
        }
        if step % args.check_every == 0 || step == steps {
            let ms = window_start.elapsed().as_secs_f64() * 1000.0 / window_steps as f64;
            let check = check(world, &built.room, step, window_penetration, ms);
            if at_1min.is_none() && check.sim_seconds >= SETTLE_SECONDS {
                at_1min = Some((check.heap_bytes, check.rss_bytes));
            }
            eprintln!(
                "  t {:>8.1} s  max pen {:>6.3} mm  non-finite {}  escaped {}  awake {:>6}  \
                 heap {:>7.1} MiB  rss {:>7.1} MiB  {:>8.3} ms/step",
                check.sim_seconds,
                check.max_penetration_m * 1000.0,
                check.non_finite,
                check.escaped,
                check.awake,
                mib(check.heap_bytes),
                mib(check.rss_bytes),
                check.ms_per_step
            );
            checks.push(check);
            window_penetration = 0.0;
            window_steps = 0;
            window_start = Instant::now();
        }
    }
    let wall = started.elapsed().as_secs_f64();
    let last = checks.last().cloned();
    let heap_checked = at_1min.is_some();
    let (heap_at_1min, rss_at_1min) = at_1min.unwrap_or((0, 0));
    let (heap_end, rss_end) = last
        .as_ref()
        .map_or((0, 0), |c| (c.heap_bytes, c.rss_bytes));
    let summary = SoakSummary {
        scene: match &args.scene.scene {
            Some(_) => args.scene.name(),
            None => "a room sized for the balloons".into(),
        },
        balloons: world.body_count(),
        steps,
        stirs,
        sim_seconds: world.time(),
        wall_seconds: wall,
        ms_per_step: wall * 1000.0 / steps as f64,
        max_penetration_m: checks
            .iter()
            .map(|c| c.max_penetration_m)
            .fold(0.0, f32::max),
        penetration_bound_m: bound,
        max_non_finite: checks.iter().map(|c| c.non_finite).max().unwrap_or(0),
        max_escaped: checks.iter().map(|c| c.escaped).max().unwrap_or(0),
        heap_checked,
        heap_at_1min_bytes: heap_at_1min,
        heap_end_bytes: heap_end,
        rss_at_1min_bytes: rss_at_1min,
        rss_end_bytes: rss_end,
        state_hash: format!("{:016x}", world.state_hash()),
        failures: Vec::new(),
        checks,
    };
    let summary = SoakSummary {
        failures: failures(&summary),
        ..summary
    };
    print_table("up soak", &rows(&summary));
    if args.json {
        println!("{}", serde_json::to_string(&summary)?);
    }
    if !summary.failures.is_empty() {
        bail!("soak failed: {}", summary.failures.join("; "));
    }
    Ok(())
}

/// Throws every tenth balloon (see `--stir-every`).
fn stir(world: &mut World, rng: &mut SplitMix64) -> Result<()> {
    let ids: Vec<BodyId> = world.body_ids().iter().copied().step_by(10).collect();
    let mut axis = |scale: f32| {
        let mut c = || rng.range(-scale, scale);
        Vec3::new(c(), c(), c())
    };
    for id in ids {
        let (v, w) = (axis(2.0), axis(3.0));
        world.set_velocity(id, v, w)?;
    }
    Ok(())
}

fn check(world: &World, room: &RoomMesh, steps: u64, penetration: f32, ms: f64) -> SoakCheck {
    let mut non_finite = 0;
    let mut escaped = 0;
    for (_, pose) in world.poses() {
        if !(pose.position.is_finite() && pose.rotation.is_finite()) {
            non_finite += 1;
        } else if !room.contains_point(pose.position) {
            escaped += 1;
        }
    }
    SoakCheck {
        sim_seconds: world.time(),
        steps,
        max_penetration_m: penetration,
        non_finite,
        escaped,
        awake: world.stats().awake_count,
        heap_bytes: held_bytes(),
        rss_bytes: resident_bytes(),
        ms_per_step: ms,
    }
}

/// Every check the soak holds the run to, as messages of what failed.
fn failures(s: &SoakSummary) -> Vec<String> {
    let mut failed = Vec::new();
    if s.max_non_finite > 0 {
        failed.push(format!("{} bodies became non-finite", s.max_non_finite));
    }
    if s.max_escaped > 0 {
        failed.push(format!("{} bodies left the room", s.max_escaped));
    }
    if s.max_penetration_m > s.penetration_bound_m {
        failed.push(format!(
            "penetration {:.3} mm over the bound {:.3} mm",
            s.max_penetration_m * 1000.0,
            s.penetration_bound_m * 1000.0
        ));
    }
    if s.heap_checked && s.heap_end_bytes > s.heap_at_1min_bytes + HEAP_SLACK_BYTES {
        failed.push(format!(
            "the heap grew from {} to {} bytes after the first minute (allowed: {} more)",
            s.heap_at_1min_bytes, s.heap_end_bytes, HEAP_SLACK_BYTES
        ));
    }
    failed
}

/// Bytes as MiB.
fn mib(bytes: u64) -> f64 {
    bytes as f64 / (1 << 20) as f64
}

fn rows(s: &SoakSummary) -> Vec<(&'static str, String)> {
    let shown = |b: u64| {
        if b == 0 {
            "n/a".to_string()
        } else {
            format!("{:.1} MiB", mib(b))
        }
    };
    vec![
        ("scene", s.scene.clone()),
        ("balloons", s.balloons.to_string()),
        ("steps", s.steps.to_string()),
        ("stirs", s.stirs.to_string()),
        ("simulated", format!("{:.1} s", s.sim_seconds)),
        ("wall clock", format!("{:.1} s", s.wall_seconds)),
        ("per step", format!("{:.3} ms", s.ms_per_step)),
        (
            "max penetration",
            format!(
                "{:.3} mm (bound {:.3} mm)",
                s.max_penetration_m * 1000.0,
                s.penetration_bound_m * 1000.0
            ),
        ),
        ("non-finite bodies", s.max_non_finite.to_string()),
        ("escaped", s.max_escaped.to_string()),
        (
            "heap check",
            if s.heap_checked {
                format!(
                    "after the first minute, within {:.0} MiB",
                    mib(HEAP_SLACK_BYTES)
                )
            } else {
                "not made: the run is shorter than a minute".to_string()
            },
        ),
        ("heap at 1 min", shown(s.heap_at_1min_bytes)),
        ("heap at the end", shown(s.heap_end_bytes)),
        ("resident at 1 min", shown(s.rss_at_1min_bytes)),
        ("resident at the end", shown(s.rss_end_bytes)),
        ("state hash", s.state_hash.clone()),
        (
            "result",
            if s.failures.is_empty() {
                "passed".to_string()
            } else {
                format!("FAILED: {}", s.failures.join("; "))
            },
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn summary(heap: (u64, u64), rss: (u64, u64)) -> SoakSummary {
        SoakSummary {
            scene: "test".into(),
            balloons: 1,
            steps: 1,
            stirs: 0,
            sim_seconds: 1.0,
            wall_seconds: 1.0,
            ms_per_step: 1.0,
            max_penetration_m: 0.0,
            penetration_bound_m: 0.0014,
            max_non_finite: 0,
            max_escaped: 0,
            heap_checked: heap.0 > 0,
            heap_at_1min_bytes: heap.0,
            heap_end_bytes: heap.1,
            rss_at_1min_bytes: rss.0,
            rss_end_bytes: rss.1,
            state_hash: String::new(),
            failures: Vec::new(),
            checks: Vec::new(),
        }
    }

    #[test]
    fn the_heap_decides_a_leak_not_resident_memory() {
        const MIB: u64 = 1 << 20;
        // Spare capacity first written after the first minute: RSS creeps, the heap is flat.
        assert!(failures(&summary((60 * MIB, 61 * MIB), (50 * MIB, 65 * MIB))).is_empty());
        let leak = failures(&summary((60 * MIB, 69 * MIB), (50 * MIB, 51 * MIB)));
        assert_eq!(leak.len(), 1, "{leak:?}");
        assert!(leak[0].contains("heap grew"), "{leak:?}");
        // Within the slack is not a leak.
        assert!(failures(&summary((60 * MIB, 60 * MIB + HEAP_SLACK_BYTES), (0, 0))).is_empty());
        // A run shorter than a minute makes no heap check, and the table says so.
        let short = SoakSummary {
            heap_checked: false,
            ..summary((0, 90 * MIB), (0, 0))
        };
        assert!(failures(&short).is_empty());
        let table = rows(&short);
        let row = table
            .iter()
            .find(|(name, _)| *name == "heap check")
            .unwrap();
        assert!(row.1.contains("not made"), "{row:?}");
    }
}
