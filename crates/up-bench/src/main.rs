//! `up-bench`: UP against Rapier on the benchmark scene.
//!
//!   up-bench --balloons 1000 --steps 600 --json        both engines, JSON lines
//!   up-bench --balloons 1000 --print-scene > s.json    the scene for web/bench
//!   up-bench --ribbons --balloons 1000 --steps 300     with ribbons in both, and UP without
//!   up-bench measure --balloons 1000 --poses p.f32     overlap of poses from Node
//!   up-bench report                                    the sweep → docs/benchmarks.md
//!   up-bench report --keep-results                     its method rewritten, results kept
//!   up-bench report --ribbons --steps 600,120          the ribbons' sweep → docs/benchmarks.md

use std::path::PathBuf;

use anyhow::{bail, Context, Result};
use clap::{Args, Parser, Subcommand};
use up_bench::engine::EngineKind;
use up_bench::measure::measure_frames;
use up_bench::output::{self, json_lines, ratio, ribbon_ratio, EngineResult};
use up_bench::rapier_engine::{RapierJoints, RapierShape};
use up_bench::report::{self, ReportOptions};
use up_bench::ribbon_report::{ribbon_report, RibbonReportOptions};
use up_bench::run::{default_steps, rss_probe, run, RunOptions};
use up_bench::scene_data::SceneData;
use up_bench::scene_export::{export, read_poses};
use up_scene::bench_scene::bench_scene;

#[derive(Parser, Debug)]
#[command(
    name = "up-bench",
    version,
    about = "UP against Rapier on the same balloon scene"
)]
#[command(args_conflicts_with_subcommands = true)]
struct Cli {
    #[command(subcommand)]
    command: Option<Cmd>,
    #[command(flatten)]
    run: RunArgs,
    /// Print the scene (and Rapier's matched parameters) as JSON for web/bench, and exit.
    #[arg(long)]
    print_scene: bool,
}

#[derive(Subcommand, Debug)]
enum Cmd {
    /// Run the sweep and write docs/benchmarks.md (the method, then the results) and docs/benchmarks.svg.
    Report(ReportArgs),
    /// Measure overlap and escapes of poses recorded elsewhere (web/bench).
    Measure(MeasureArgs),
    /// (internal) Run one engine alone and print its peak memory.
    #[command(hide = true)]
    RssProbe(ProbeArgs),
}

#[derive(Args, Debug, Clone)]
struct SceneArgs {
    /// Balloons in the benchmark scene (the room scales with them).
    #[arg(long, value_name = "N", default_value_t = 1000)]
    balloons: u64,
    /// Seed of the spawn layout.
    #[arg(long, default_value_t = 1)]
    seed: u64,
}

#[derive(Args, Debug, Clone)]
struct RunArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Steps to time; by default twice the rise to the apex plus 2 s (at least 600).
    #[arg(long, value_name = "K")]
    steps: Option<u64>,
    /// Threads for UP (Rapier runs on one).
    #[arg(long, value_name = "T", default_value_t = 1)]
    threads: usize,
    /// One JSON line per engine, then the ratio.
    #[arg(long)]
    json: bool,
    /// Engines to compare, comma-separated: up, rapier.
    #[arg(long, value_delimiter = ',', default_value = "up,rapier")]
    engines: Vec<String>,
    /// How Rapier holds a balloon's spheres: one compound collider, or one ball collider each.
    #[arg(long, default_value = "compound")]
    rapier_shape: String,
    /// Skip the peak-memory child processes (they take as long as the run).
    #[arg(long)]
    no_rss: bool,
    /// Write every step's wall time, ms, per engine, as CSV (`step,up,rapier`).
    #[arg(long, value_name = "FILE.csv")]
    step_times: Option<PathBuf>,
    /// Tie a ribbon (1.5 m, 16 segments, 0.25 g/m) to every balloon in every
    /// engine, and run UP without ribbons beside them.
    #[arg(long)]
    ribbons: bool,
    /// How Rapier joints a ribbon's balls: impulse or multibody.
    #[arg(long, default_value = "impulse")]
    rapier_joints: String,
    /// Time each of UP's threads in each stage: busy, waiting at barriers,
    /// idle, and the barriers crossed (two clock reads per task).
    #[arg(long)]
    thread_times: bool,
}

#[derive(Args, Debug)]
struct MeasureArgs {
    #[command(flatten)]
    scene: SceneArgs,
    /// Little-endian f32 file: frames of N poses (x, y, z, qx, qy, qz, qw).
    #[arg(long)]
    poses: PathBuf,
}

#[derive(Args, Debug)]
struct ProbeArgs {
    #[command(flatten)]
    run: RunArgs,
    #[arg(long)]
    engine: String,
}

#[derive(Args, Debug)]
struct ReportArgs {
    /// Sizes both engines run at.
    #[arg(long, value_delimiter = ',', default_value = "1000,10000")]
    sizes: Vec<u64>,
    /// Sizes UP runs at alone (`--up-only-sizes` with no value: none).
    #[arg(long, value_delimiter = ',', num_args = 0.., default_value = "100000")]
    up_only_sizes: Vec<u64>,
    /// Steps at every size, or one count per size (`--sizes`, then
    /// `--up-only-sizes` or `--multibody-sizes`); default: each size's own,
    /// see `--steps` of a run.
    #[arg(long, value_delimiter = ',')]
    steps: Vec<u64>,
    /// Run the ribbons' sweep instead (`--ribbons` at `--sizes`, Rapier on
    /// impulse joints, and at `--multibody-sizes` on multibody joints), and
    /// write its results after the main ones, which are kept.
    #[arg(long)]
    ribbons: bool,
    /// With `--ribbons`: sizes where Rapier's ribbons are multibody chains.
    #[arg(long, value_delimiter = ',', num_args = 0..)]
    multibody_sizes: Vec<u64>,
    /// Threads for UP where both engines run.
    #[arg(long, default_value_t = 1)]
    threads: usize,
    /// Threads for UP where it runs alone; 0: all the machine has.
    #[arg(long, default_value_t = 0)]
    up_only_threads: usize,
    /// Also run web/bench (node) at the sizes both engines run at.
    #[arg(long)]
    node: bool,
    /// web/bench/bench.mjs.
    #[arg(long, default_value = "web/bench/bench.mjs")]
    node_script: PathBuf,
    /// Run nothing: write the method (crates/up-bench/src/method.md) again
    /// around the results already in the markdown.
    #[arg(long)]
    keep_results: bool,
    #[arg(long, default_value = "docs/benchmarks.md")]
    markdown: PathBuf,
    #[arg(long, default_value = "docs/benchmarks.svg")]
    svg: PathBuf,
}

fn run_options(args: &RunArgs) -> Result<RunOptions> {
    let engines = args
        .engines
        .iter()
        .map(|name| {
            EngineKind::parse(name)
                .with_context(|| format!("--engines: expected up or rapier, found {name:?}"))
        })
        .collect::<Result<Vec<_>>>()?;
    let rapier_shape = RapierShape::parse(&args.rapier_shape).with_context(|| {
        format!(
            "--rapier-shape: expected compound or balls, found {:?}",
            args.rapier_shape
        )
    })?;
    let rapier_joints = RapierJoints::parse(&args.rapier_joints).with_context(|| {
        format!(
            "--rapier-joints: expected impulse or multibody, found {:?}",
            args.rapier_joints
        )
    })?;
    let steps = match args.steps {
        Some(steps) => steps,
        None => {
            let (scene, layout) = bench_scene(args.scene.balloons, args.scene.seed)?;
            default_steps(layout.wall_height_m + layout.apex_height_m, scene.sim.dt)
        }
    };
    Ok(RunOptions {
        balloons: args.scene.balloons,
        steps,
        seed: args.scene.seed,
        threads: args.threads,
        engines,
        rapier_shape,
        rss: !args.no_rss,
        step_times: args.step_times.clone(),
        ribbons: args.ribbons,
        rapier_joints,
        thread_times: args.thread_times,
    })
}

fn print_table(results: &[EngineResult]) {
    println!(
        "{:<8} {:>9} {:>6} {:>10} {:>10} {:>10} {:>12} {:>8} {:>7} {:>9}",
        "engine",
        "balloons",
        "steps",
        "median ms",
        "p95 ms",
        "settled",
        "max pen. mm",
        "escaped",
        "awake",
        "peak MB"
    );
    let ribbons = results.iter().any(|r| r.ribbons > 0);
    for r in results {
        let rss = r
            .peak_rss_mb
            .map_or("-".to_string(), |mb| format!("{mb:.1}"));
        let stretch = match (r.max_ribbon_stretch, r.max_ribbon_stretch_after_start) {
            (Some(all), late) => format!(
                " {:>9.3} % (step {}), after 1 s {}",
                all * 100.0,
                r.max_ribbon_stretch_step.unwrap_or(0),
                late.map_or("-".into(), |s| format!("{:.3} %", s * 100.0))
            ),
            _ => String::new(),
        };
        let engine = match (ribbons, r.ribbons) {
            (true, 0) => format!("{} bare", r.engine),
            _ => r.engine.clone(),
        };
        println!(
            "{:<8} {:>9} {:>6} {:>10.3} {:>10.3} {:>10.3} {:>12.3} {:>8} {:>7} {:>9}{stretch}",
            engine,
            r.balloons,
            r.steps,
            r.ms_per_step_median,
            r.ms_per_step_p95,
            r.settled_ms_per_step_median,
            r.max_penetration_m * 1e3,
            r.escaped,
            r.awake_at_end,
            rss
        );
    }
    if ribbons {
        println!("(bare: UP without ribbons; the last column: worst ribbon stretch)");
        for r in results.iter().filter(|r| r.engine == "up") {
            if let Some(stages) = &r.stage_ms_mean {
                let stages: Vec<String> = stages
                    .iter()
                    .map(|(name, ms)| format!("{name} {ms:.3}"))
                    .collect();
                let which = if r.ribbons > 0 { "with" } else { "without" };
                println!("UP {which} ribbons, ms per step: {}", stages.join(", "));
            }
        }
    }
    for r in results {
        println!("{} mean ms per step: {:.3}", r.engine, r.ms_per_step_mean);
        if let Some(stages) = &r.stage_threads_mean {
            print!("{}", up_bench::thread_times::table(stages));
        }
        if let Some([before, after]) = r.core_round_trip_ns {
            println!("a cache line's round trip between two cores: {before:.0} ns before the run, {after:.0} ns after");
        }
    }
    if let (Some(by_median), Some(by_mean)) =
        (ratio(results, output::median), ratio(results, output::mean))
    {
        println!(
            "Rapier / UP (median ms per step): {by_median:.2}; mean (total time): {by_mean:.2}"
        );
    }
    if let (Some(by_median), Some(by_mean)) = (
        ribbon_ratio(results, output::median),
        ribbon_ratio(results, output::mean),
    ) {
        println!("UP with ribbons / without (median): {by_median:.2}; mean: {by_mean:.2}");
    }
}

fn main() -> Result<()> {
    let cli = Cli::parse();
    match cli.command {
        Some(Cmd::Report(args)) if args.keep_results => report::keep_results(&args.markdown),
        Some(Cmd::Report(args)) if args.ribbons => ribbon_report(&RibbonReportOptions {
            sizes: args.sizes,
            multibody_sizes: args.multibody_sizes,
            steps: args.steps,
            threads: args.threads,
            markdown: args.markdown,
        }),
        Some(Cmd::Report(args)) => report::report(&ReportOptions {
            sizes: args.sizes,
            up_only_sizes: args.up_only_sizes,
            steps: args.steps,
            threads: args.threads,
            up_only_threads: match args.up_only_threads {
                0 => up_bench::system_info::threads(),
                n => n,
            },
            node: args.node.then_some(args.node_script),
            markdown: args.markdown,
            svg: args.svg,
        }),
        Some(Cmd::Measure(args)) => {
            let (data, _) = SceneData::build(args.scene.balloons, args.scene.seed)?;
            let frames = read_poses(&args.poses, data.start_poses.len())?;
            println!(
                "{}",
                serde_json::to_string(&measure_frames(&data, &frames)?)?
            );
            Ok(())
        }
        Some(Cmd::RssProbe(args)) => {
            let Some(kind) = EngineKind::parse(&args.engine) else {
                bail!("--engine: expected up or rapier, found {:?}", args.engine);
            };
            let probe = rss_probe(kind, &run_options(&args.run)?)?;
            println!("{}", serde_json::to_string(&probe)?);
            Ok(())
        }
        None if cli.print_scene => {
            let (data, _) = SceneData::build(cli.run.scene.balloons, cli.run.scene.seed)?;
            let exported = export(&data, cli.run.scene.balloons, cli.run.scene.seed)?;
            println!("{}", serde_json::to_string(&exported)?);
            Ok(())
        }
        None => {
            let results = run(&run_options(&cli.run)?)?;
            if cli.run.json {
                for line in json_lines(&results)? {
                    println!("{line}");
                }
            } else {
                print_table(&results);
            }
            Ok(())
        }
    }
}
