//! `up-bench report --ribbons`: the ribbons' sweep, each size in a fresh
//! child process (`up-bench --ribbons --json`), written into
//! docs/benchmarks.md after the main results, which are kept as they are.

use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::Command;

use anyhow::{bail, Context, Result};

use crate::output::EngineResult;
use crate::report::{
    check_steps, document, main_results, parse_results, steps_of, RIBBONS_BEGIN, RIBBONS_END,
};
use crate::step_times::write_whole;
use crate::system_info::{cpu_model, memory_gb, threads, today_utc};

pub struct RibbonReportOptions {
    /// Sizes both engines run at, Rapier's balls on impulse joints.
    pub sizes: Vec<u64>,
    /// Sizes both engines run at, Rapier's balls on multibody joints.
    pub multibody_sizes: Vec<u64>,
    /// Steps: one for every size, or one per size of `sizes` then `multibody_sizes`.
    pub steps: Vec<u64>,
    /// Threads for UP (Rapier runs on one).
    pub threads: usize,
    pub markdown: PathBuf,
}

/// One child run: its arguments, as run and as shown, and the load average
/// before it started.
struct Run {
    args: Vec<String>,
    shown: String,
    load: Option<f64>,
}

fn run_args(n: u64, joints: &str, steps: Option<u64>, threads: usize) -> Vec<String> {
    let mut args: Vec<String> = [
        "--ribbons",
        "--balloons",
        &n.to_string(),
        "--rapier-joints",
        joints,
        "--threads",
        &threads.to_string(),
        "--no-rss",
        "--json",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    if let Some(k) = steps {
        args.extend(["--steps".to_string(), k.to_string()]);
    }
    args
}

/// The 1-minute load average, from /proc/loadavg.
pub fn load_average() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/loadavg").ok()?;
    text.split_whitespace().next()?.parse().ok()
}

pub fn ribbon_report(opts: &RibbonReportOptions) -> Result<()> {
    check_steps(&opts.steps, opts.sizes.len() + opts.multibody_sizes.len())?;
    let old = std::fs::read_to_string(&opts.markdown)
        .with_context(|| format!("reading {}", opts.markdown.display()))?;
    // The main results must be there before an hour of ribbons is run.
    let main = main_results(&opts.markdown, &old)?;
    let exe = std::env::current_exe().context("finding the up-bench executable")?;
    let sizes = opts
        .sizes
        .iter()
        .map(|&n| (n, "impulse"))
        .chain(opts.multibody_sizes.iter().map(|&n| (n, "multibody")));
    let mut runs: Vec<Run> = sizes
        .enumerate()
        .map(|(i, (n, joints))| {
            let args = run_args(n, joints, steps_of(&opts.steps, i), opts.threads);
            Run {
                shown: format!("target/release/up-bench {}", args.join(" ")),
                args,
                load: None,
            }
        })
        .collect();
    let mut results = Vec::new();
    for run in &mut runs {
        eprintln!("up-bench report: {}", run.shown);
        run.load = load_average();
        let output = Command::new(&exe)
            .args(&run.args)
            .output()
            .with_context(|| format!("running {}", run.shown))?;
        if !output.status.success() {
            bail!(
                "{} failed: {}",
                run.shown,
                String::from_utf8_lossy(&output.stderr).trim()
            );
        }
        results.extend(
            parse_results(&String::from_utf8_lossy(&output.stdout))
                .with_context(|| format!("output of {}", run.shown))?,
        );
    }
    let commands: Vec<(String, Option<f64>)> =
        runs.iter().map(|r| (r.shown.clone(), r.load)).collect();
    let section = ribbon_section(&results, &commands);
    write_whole(&opts.markdown, &document(&main, Some(&section)))
        .with_context(|| format!("writing {}", opts.markdown.display()))?;
    eprintln!("up-bench report: wrote {}", opts.markdown.display());
    Ok(())
}

fn pct(value: Option<f32>) -> String {
    value.map_or("–".into(), |v| format!("{:.3}", v * 100.0))
}

/// What a row's engine is: UP with or without ribbons, Rapier and its joints.
fn label(r: &EngineResult) -> String {
    match (r.engine.as_str(), r.ribbons) {
        ("up", 0) => "UP, no ribbons".into(),
        ("up", _) => "UP".into(),
        (_, _) => format!(
            "Rapier, {} joints",
            r.rapier_joints.as_deref().unwrap_or("impulse")
        ),
    }
}

/// The runs whose results belong together: one child process each, in order.
fn groups(results: &[EngineResult]) -> Vec<&[EngineResult]> {
    let mut out = Vec::new();
    let mut start = 0;
    for i in 1..=results.len() {
        let ends = i == results.len()
            || (results[i].engine == "up" && results[i].ribbons > 0)
            || results[i].balloons != results[start].balloons;
        if ends {
            out.push(&results[start..i]);
            start = i;
        }
    }
    out
}

/// The ribbons' results as markdown, between `RIBBONS_BEGIN` and `RIBBONS_END`.
pub fn ribbon_section(results: &[EngineResult], commands: &[(String, Option<f64>)]) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "{RIBBONS_BEGIN}");
    let _ = writeln!(md, "## Latest results with ribbons\n");
    let memory = memory_gb().map_or(String::new(), |gb| format!(", {gb:.0} GB of memory"));
    let _ = writeln!(
        md,
        "Machine: {}, {} threads (`nproc`){memory}. Date: {} (UTC).\n",
        cpu_model(),
        threads(),
        today_utc(),
    );
    let _ = writeln!(
        md,
        "Commands (each in a fresh process), with the machine's 1-minute load average before each \
         (above the thread count, other work shared the machine):\n\n```sh"
    );
    for (c, load) in commands {
        let load = load.map_or(String::new(), |l| format!("   # load {l:.1}"));
        let _ = writeln!(md, "{c}{load}");
    }
    let _ = writeln!(md, "```\n");
    let _ = writeln!(
        md,
        "| engine | balloons | steps | ribbons | median ms/step | mean ms/step | p95 ms | \
         worst stretch % (step) | worst stretch after 1 s % | max penetration mm | escaped | \
         awake at end |"
    );
    let _ = writeln!(md, "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
    for r in results {
        let step = r
            .max_ribbon_stretch_step
            .map_or(String::new(), |s| format!(" ({s})"));
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.3} | {:.3} | {:.3} | {}{} | {} | {:.3} | {} | {} |",
            label(r),
            r.balloons,
            r.steps,
            r.ribbons,
            r.ms_per_step_median,
            r.ms_per_step_mean,
            r.ms_per_step_p95,
            pct(r.max_ribbon_stretch),
            step,
            pct(r.max_ribbon_stretch_after_start),
            r.max_penetration_m * 1e3,
            r.escaped,
            r.awake_at_end,
        );
    }
    let _ = writeln!(
        md,
        "\nRatios within each run (same process, interleaved): Rapier over UP, both with \
         ribbons, and UP with ribbons over UP without:\n"
    );
    let _ = writeln!(
        md,
        "| balloons | Rapier joints | Rapier / UP, median | Rapier / UP, mean | UP ribbons / none, median | UP ribbons / none, mean |\n|--:|---|--:|--:|--:|--:|"
    );
    let find = |g: &[EngineResult], engine: &str, ribbons: bool| -> Option<EngineResult> {
        g.iter()
            .find(|r| r.engine == engine && (r.ribbons > 0) == ribbons)
            .cloned()
    };
    let ratio = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => format!("{:.2}", a / b),
        _ => "–".into(),
    };
    for g in groups(results) {
        let (up, rapier, bare) = (
            find(g, "up", true),
            find(g, "rapier", true),
            find(g, "up", false),
        );
        let median = |r: &Option<EngineResult>| r.as_ref().map(|r| r.ms_per_step_median);
        let mean = |r: &Option<EngineResult>| r.as_ref().map(|r| r.ms_per_step_mean);
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {} |",
            g[0].balloons,
            rapier
                .as_ref()
                .and_then(|r| r.rapier_joints.clone())
                .unwrap_or("–".into()),
            ratio(median(&rapier), median(&up)),
            ratio(mean(&rapier), mean(&up)),
            ratio(median(&up), median(&bare)),
            ratio(mean(&up), mean(&bare)),
        );
    }
    // A row per stage (the step has a few dozen), a column per run.
    let runs: Vec<(&EngineResult, &Vec<(String, f64)>)> = results
        .iter()
        .filter(|r| r.engine == "up")
        .filter_map(|r| r.stage_ms_mean.as_ref().map(|s| (r, s)))
        .collect();
    if let Some((_, first)) = runs.first() {
        let _ = writeln!(
            md,
            "\nWhere UP's time goes (`World::counters`, ms per step over the run, stage by stage \
             in step order; the ribbons are solved in `solve`, their neighbours found in \
             `prepare_ribbons`):\n"
        );
        let columns: Vec<String> = runs
            .iter()
            .map(|(r, _)| format!("{} balloons, {} ribbons", r.balloons, r.ribbons))
            .collect();
        let _ = writeln!(md, "| stage | {} |", columns.join(" | "));
        let _ = writeln!(md, "|:--|{}", "--:|".repeat(columns.len()));
        for (k, (name, _)) in first.iter().enumerate() {
            let times: Vec<String> = runs
                .iter()
                .map(|(_, s)| s.get(k).map_or("–".into(), |(_, ms)| format!("{ms:.3}")))
                .collect();
            let _ = writeln!(md, "| {name} | {} |", times.join(" | "));
        }
    }
    let _ = writeln!(md, "\n{RIBBONS_END}");
    md
}

#[cfg(test)]
mod tests {
    use super::*;

    fn result(engine: &str, ribbons: usize, median: f64, mean: f64) -> EngineResult {
        EngineResult {
            engine: engine.into(),
            runtime: "native".into(),
            balloons: 1000,
            steps: 300,
            threads: 1,
            ms_per_step_median: median,
            ms_per_step_p95: median * 2.0,
            ms_per_step_mean: mean,
            settled_ms_per_step_median: median,
            max_penetration_m: 0.002,
            final_penetration_m: 0.001,
            escaped: 0,
            awake_at_end: 7,
            peak_rss_mb: None,
            rss_bytes_per_balloon: None,
            room_width_m: 5.55,
            rapier_shape: (engine == "rapier").then(|| "compound".into()),
            ribbons,
            max_ribbon_stretch: (ribbons > 0).then_some(0.0125),
            max_ribbon_stretch_step: (ribbons > 0).then_some(2),
            max_ribbon_stretch_after_start: (ribbons > 0).then_some(0.0005),
            rapier_joints: (engine == "rapier").then(|| "impulse".into()),
            stage_ms_mean: (engine == "up").then(|| vec![("solve".into(), 1.5)]),
            stage_threads_mean: None,
            core_round_trip_ns: None,
        }
    }

    #[test]
    fn the_section_has_a_row_per_engine_and_the_ratios_of_each_run() {
        let results = [
            result("up", 1000, 4.0, 5.0),
            result("rapier", 1000, 40.0, 60.0),
            result("up", 0, 2.0, 4.0),
        ];
        let md = ribbon_section(&results, &[("up-bench --ribbons".into(), Some(1.5))]);
        assert!(md.starts_with(RIBBONS_BEGIN) && md.trim_end().ends_with(RIBBONS_END));
        assert!(md.contains("up-bench --ribbons   # load 1.5"), "{md}");
        assert!(
            md.contains("| UP | 1000 | 300 | 1000 | 4.000 | 5.000 | 8.000 | 1.250 (2) | 0.050 |"),
            "{md}"
        );
        assert!(md.contains("| Rapier, impulse joints | 1000 |"), "{md}");
        assert!(md.contains("| UP, no ribbons | 1000 | 300 | 0 |"), "{md}");
        assert!(
            md.contains("| 1000 | impulse | 10.00 | 12.00 | 2.00 | 1.25 |"),
            "{md}"
        );
        assert!(
            md.contains("| stage | 1000 balloons, 1000 ribbons | 1000 balloons, 0 ribbons |"),
            "{md}"
        );
        assert!(md.contains("| solve | 1.500 | 1.500 |"), "{md}");
    }

    #[test]
    fn each_child_runs_results_are_a_group() {
        let mut second = [
            result("up", 1000, 4.0, 5.0),
            result("rapier", 1000, 40.0, 60.0),
            result("up", 0, 2.0, 4.0),
        ];
        for r in &mut second {
            r.rapier_joints = (r.engine == "rapier").then(|| "multibody".into());
        }
        let mut all = vec![
            result("up", 1000, 4.0, 5.0),
            result("rapier", 1000, 40.0, 60.0),
            result("up", 0, 2.0, 4.0),
        ];
        all.extend(second);
        let g = groups(&all);
        assert_eq!(g.len(), 2);
        assert_eq!(g[0].len(), 3);
        assert_eq!(g[1][1].rapier_joints.as_deref(), Some("multibody"));
    }
}
