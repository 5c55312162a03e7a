//! `up-bench report`: runs the sweep, each size in a fresh child process
//! (`up-bench --json`, and `node web/bench/bench.mjs --json` with `--node`),
//! then writes docs/benchmarks.md and the plot.
//!
//! The markdown is written whole: the method (`method.md`, fixed text kept
//! beside this generator so that it is edited in one place), then the run's
//! results between `BEGIN` and `END`. `--keep-results` writes the method
//! again around the results already in the file, so that a change to the
//! method needs no new run of the sweep.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{bail, Context, Result};

use crate::output::EngineResult;
use crate::plot::{plot_svg, Series};
use crate::step_times::write_whole;
use crate::system_info::{cpu_model, memory_gb, threads, today_utc};

/// The first line of the markdown: where it comes from, for whoever opens it to edit it.
pub const HEADER: &str = "<!-- Written by `up-bench report`: the method from \
    crates/up-bench/src/method.md, then the results of the run named below. Edit method.md and \
    run `up-bench report --keep-results`; edits here are overwritten. -->\n";

/// How the benchmark is run and read: the fixed text before the results.
pub const METHOD: &str = include_str!("method.md");

pub const BEGIN: &str = "<!-- up-bench report: results begin -->";
pub const END: &str = "<!-- up-bench report: results end -->";
/// The ribbons' results (`report --ribbons`), after the main results.
pub const RIBBONS_BEGIN: &str = "<!-- up-bench report: ribbon results begin -->";
pub const RIBBONS_END: &str = "<!-- up-bench report: ribbon results end -->";

pub struct ReportOptions {
    pub sizes: Vec<u64>,
    pub up_only_sizes: Vec<u64>,
    /// Steps: one for every size, or one per size of `sizes` then `up_only_sizes`.
    pub steps: Vec<u64>,
    /// Threads for UP where both engines run (Rapier runs on one).
    pub threads: usize,
    /// Threads for UP where it runs alone.
    pub up_only_threads: usize,
    /// web/bench/bench.mjs, when Node runs too.
    pub node: Option<PathBuf>,
    pub markdown: PathBuf,
    pub svg: PathBuf,
}

/// A command as run, and as the report shows it.
struct Step {
    program: String,
    shown: String,
    args: Vec<String>,
}

fn run_child(step: &Step) -> Result<Vec<EngineResult>> {
    eprintln!("up-bench report: {}", step.shown);
    let output = Command::new(&step.program)
        .args(&step.args)
        .output()
        .with_context(|| format!("running {}", step.shown))?;
    if !output.status.success() {
        bail!(
            "{} failed: {}",
            step.shown,
            String::from_utf8_lossy(&output.stderr).trim()
        );
    }
    parse_results(&String::from_utf8_lossy(&output.stdout))
        .with_context(|| format!("output of {}", step.shown))
}

/// The engine lines of `--json` output (the ratio line and other lines are skipped).
pub fn parse_results(text: &str) -> Result<Vec<EngineResult>> {
    let mut results = Vec::new();
    for line in text.lines().filter(|l| l.contains("\"engine\"")) {
        results.push(serde_json::from_str(line).with_context(|| format!("line {line:?}"))?);
    }
    if results.is_empty() {
        bail!("no result line in {text:?}");
    }
    Ok(results)
}

/// The steps of the `i`-th size: `--steps` K for all, or its own of a list.
pub fn steps_of(steps: &[u64], i: usize) -> Option<u64> {
    match steps {
        [] => None,
        [all] => Some(*all),
        each => each.get(i).copied(),
    }
}

/// `--steps` must give one count, or one per size.
pub fn check_steps(steps: &[u64], sizes: usize) -> Result<()> {
    if steps.len() > 1 && steps.len() != sizes {
        bail!(
            "--steps: expected one count, or one per size ({sizes}), found {}",
            steps.len()
        );
    }
    Ok(())
}

fn bench_step(exe: &str, n: u64, engines: &str, threads: usize, steps: Option<u64>) -> Step {
    let mut args = vec![
        "--balloons".to_string(),
        n.to_string(),
        "--engines".into(),
        engines.into(),
        "--threads".into(),
        threads.to_string(),
        "--json".into(),
    ];
    if let Some(steps) = steps {
        args.extend(["--steps".to_string(), steps.to_string()]);
    }
    Step {
        program: exe.to_string(),
        shown: format!("target/release/up-bench {}", args.join(" ")),
        args,
    }
}

fn node_step(script: &Path, n: u64, steps: Option<u64>) -> Step {
    let mut args = vec![
        script.display().to_string(),
        "--balloons".to_string(),
        n.to_string(),
        "--json".into(),
        // The report compares UP with Rapier; the other peers are in their own section.
        "--engines".into(),
        "up,rapier".into(),
    ];
    if let Some(steps) = steps {
        args.extend(["--steps".to_string(), steps.to_string()]);
    }
    Step {
        program: "node".into(),
        shown: format!("node {}", args.join(" ")),
        args,
    }
}

fn node_version() -> Option<String> {
    let out = Command::new("node").arg("--version").output().ok()?;
    Some(String::from_utf8_lossy(&out.stdout).trim().to_string())
}

pub fn report(opts: &ReportOptions) -> Result<()> {
    check_steps(&opts.steps, opts.sizes.len() + opts.up_only_sizes.len())?;
    let exe = std::env::current_exe().context("finding the up-bench executable")?;
    let exe = exe.display().to_string();
    let mut steps: Vec<Step> = opts
        .sizes
        .iter()
        .enumerate()
        .map(|(i, &n)| bench_step(&exe, n, "up,rapier", opts.threads, steps_of(&opts.steps, i)))
        .collect();
    let first = opts.sizes.len();
    steps.extend(opts.up_only_sizes.iter().enumerate().map(|(i, &n)| {
        let k = steps_of(&opts.steps, first + i);
        bench_step(&exe, n, "up", opts.up_only_threads, k)
    }));
    if let Some(script) = &opts.node {
        steps.extend(
            opts.sizes
                .iter()
                .enumerate()
                .map(|(i, &n)| node_step(script, n, steps_of(&opts.steps, i))),
        );
    }
    // The ribbons' results of an earlier `report --ribbons` stay.
    let kept = std::fs::read_to_string(&opts.markdown).ok();
    let ribbons = kept
        .as_deref()
        .and_then(|md| section_of(md, RIBBONS_BEGIN, RIBBONS_END));
    let mut results = Vec::new();
    for step in &steps {
        results.extend(run_child(step)?);
    }
    let commands: Vec<String> = steps.iter().map(|s| s.shown.clone()).collect();
    let node = opts.node.as_ref().and_then(|_| node_version());
    let section = results_section(&results, &commands, node.as_deref(), &opts.svg);
    write_whole(&opts.markdown, &document(&section, ribbons))
        .with_context(|| format!("writing {}", opts.markdown.display()))?;
    plot_svg(&opts.svg, &series(&results))?;
    eprintln!(
        "up-bench report: wrote {} and {}",
        opts.markdown.display(),
        opts.svg.display()
    );
    Ok(())
}

/// One line per engine and runtime: (balloons, median ms per step).
pub fn series(results: &[EngineResult]) -> Vec<Series> {
    let mut keys: Vec<(String, String)> = Vec::new();
    for r in results {
        let key = (r.engine.clone(), r.runtime.clone());
        if !keys.contains(&key) {
            keys.push(key);
        }
    }
    keys.into_iter()
        .map(|(engine, runtime)| {
            let mut points: Vec<(f64, f64)> = results
                .iter()
                .filter(|r| r.engine == engine && r.runtime == runtime)
                .map(|r| (r.balloons as f64, r.ms_per_step_median))
                .collect();
            points.sort_by(|a, b| a.0.total_cmp(&b.0));
            let name = if engine == "up" { "UP" } else { "Rapier" };
            Series {
                label: format!("{name} ({runtime})"),
                points,
            }
        })
        .collect()
}

fn opt(value: Option<f64>, digits: usize) -> String {
    value.map_or("–".to_string(), |v| format!("{v:.digits$}"))
}

/// The run's results as markdown, between `BEGIN` and `END`: the machine and
/// date, the commands, the tables and the plot.
pub fn results_section(
    results: &[EngineResult],
    commands: &[String],
    node: Option<&str>,
    svg: &Path,
) -> String {
    let mut md = String::new();
    let _ = writeln!(md, "{BEGIN}");
    let _ = writeln!(md, "## Latest results\n");
    let memory = memory_gb().map_or(String::new(), |gb| format!(", {gb:.0} GB of memory"));
    let _ = writeln!(
        md,
        "Machine: {}, {} threads (`nproc`){memory}. Date: {} (UTC).{}\n",
        cpu_model(),
        threads(),
        today_utc(),
        node.map_or(String::new(), |v| format!(" Node {v}."))
    );
    let _ = writeln!(md, "Commands (each in a fresh process):\n\n```sh");
    for c in commands {
        let _ = writeln!(md, "{c}");
    }
    let _ = writeln!(md, "```\n");
    let _ = writeln!(
        md,
        "| runtime | engine | balloons | steps | threads | median ms/step | p95 ms | settled median ms | \
         max penetration mm | escaped | awake at end | peak RSS MB | bytes/balloon |"
    );
    let _ = writeln!(md, "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|");
    for r in results {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {} | {:.3} | {:.3} | {:.3} | {:.3} | {} | {} | {} | {} |",
            r.runtime,
            r.engine,
            r.balloons,
            r.steps,
            r.threads,
            r.ms_per_step_median,
            r.ms_per_step_p95,
            r.settled_ms_per_step_median,
            r.max_penetration_m * 1e3,
            r.escaped,
            r.awake_at_end,
            opt(r.peak_rss_mb, 1),
            opt(r.rss_bytes_per_balloon, 0),
        );
    }
    let _ = writeln!(
        md,
        "\nRapier over UP, whole-run ms per step (same process, interleaved): the \
         median, and the mean (total time):\n"
    );
    let _ = writeln!(
        md,
        "| runtime | balloons | Rapier / UP, median | Rapier / UP, mean |\n|---|--:|--:|--:|"
    );
    for up in results.iter().filter(|r| r.engine == "up") {
        if let Some(rapier) = results
            .iter()
            .find(|r| r.engine == "rapier" && r.runtime == up.runtime && r.balloons == up.balloons)
        {
            let _ = writeln!(
                md,
                "| {} | {} | {:.2} | {:.2} |",
                up.runtime,
                up.balloons,
                rapier.ms_per_step_median / up.ms_per_step_median,
                rapier.ms_per_step_mean / up.ms_per_step_mean
            );
        }
    }
    let _ = writeln!(md, "\nUP's cost per balloon-step (linearity):\n");
    let _ = writeln!(
        md,
        "| runtime | balloons | µs per balloon-step |\n|---|--:|--:|"
    );
    for up in results.iter().filter(|r| r.engine == "up") {
        let _ = writeln!(
            md,
            "| {} | {} | {:.3} |",
            up.runtime,
            up.balloons,
            up.ms_per_step_median * 1e3 / up.balloons as f64
        );
    }
    let name = svg
        .file_name()
        .map_or("benchmarks.svg".into(), |n| n.to_string_lossy());
    let _ = writeln!(
        md,
        "\n![median ms per step against balloons, log-log]({name})\n"
    );
    let _ = writeln!(md, "{END}");
    md
}

/// The whole markdown: the header, the method, then `section`
/// (`results_section`) and the ribbons' results if there are any
/// (`ribbon_report::ribbon_section`).
pub fn document(section: &str, ribbons: Option<&str>) -> String {
    let ribbons = ribbons.map_or(String::new(), |r| format!("\n{}\n", r.trim_end()));
    format!("{HEADER}{METHOD}{}\n{ribbons}", section.trim_end())
}

/// The part of `markdown` from `begin` to `end`, markers included.
pub fn section_of<'a>(markdown: &'a str, begin: &str, end: &str) -> Option<&'a str> {
    let from = markdown.find(begin)?;
    let to = markdown[from..].find(end)? + from + end.len();
    Some(&markdown[from..to])
}

/// The results section of a document `document` wrote, markers included.
pub fn results_of(markdown: &str) -> Option<&str> {
    section_of(markdown, BEGIN, END)
}

/// The main results of the document at `path`, which must have them.
pub fn main_results(path: &Path, markdown: &str) -> Result<String> {
    match results_of(markdown) {
        Some(section) => Ok(section.to_string()),
        None => bail!(
            "{}: no results to keep (expected a section from {BEGIN} to {END}); run `up-bench report`",
            path.display()
        ),
    }
}

/// Writes the method again around the results already in `path`.
pub fn keep_results(path: &Path) -> Result<()> {
    let old =
        std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    let section = main_results(path, &old)?;
    let ribbons = section_of(&old, RIBBONS_BEGIN, RIBBONS_END);
    write_whole(path, &document(&section, ribbons))
        .with_context(|| format!("writing {}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_document_is_the_method_then_the_results() {
        let section = format!("{BEGIN}\n## Latest results\n\nnew table\n{END}\n");
        let doc = document(&section, None);
        assert!(doc.starts_with(HEADER));
        assert_eq!(doc[HEADER.len()..].find(METHOD), Some(0));
        assert!(doc.ends_with(&format!("{END}\n")));
        assert_eq!(results_of(&doc), Some(section.trim_end()));
        // Written again around its own results, it is the same text.
        assert_eq!(document(results_of(&doc).unwrap(), None), doc);
        assert_eq!(results_of("# no results\n"), None);
        assert_eq!(results_of(&format!("{END}\n{BEGIN}\n")), None);
        // The ribbons' results come after the main ones, and are read back apart.
        let ribbons = format!("{RIBBONS_BEGIN}\n## Ribbons\n{RIBBONS_END}");
        let doc = document(&section, Some(&ribbons));
        assert!(doc.ends_with(&format!("{END}\n\n{ribbons}\n")), "{doc}");
        assert_eq!(results_of(&doc), Some(section.trim_end()));
        assert_eq!(
            section_of(&doc, RIBBONS_BEGIN, RIBBONS_END),
            Some(ribbons.as_str())
        );
    }

    /// docs/benchmarks.md is what the generator writes: the method as in
    /// method.md and nothing by hand around the results.
    #[test]
    fn the_committed_benchmarks_are_the_generators_text() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/benchmarks.md");
        let committed = std::fs::read_to_string(&path).unwrap();
        let section = results_of(&committed).expect("docs/benchmarks.md has its results");
        let ribbons = section_of(&committed, RIBBONS_BEGIN, RIBBONS_END);
        assert!(
            committed == document(section, ribbons),
            "docs/benchmarks.md differs from crates/up-bench/src/method.md and its results: \
             run `up-bench report --keep-results`"
        );
    }

    #[test]
    fn keep_results_rewrites_the_method_and_keeps_the_results() {
        let dir = std::env::temp_dir().join(format!("up-bench-report-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("b.md");
        let section = format!("{BEGIN}\n## Latest results\n\n| a | 1 |\n{END}");
        std::fs::write(
            &path,
            format!("# an old method\n\n{section}\n\n## a diary\n"),
        )
        .unwrap();
        keep_results(&path).unwrap();
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            document(&section, None)
        );
        // The ribbons' results are kept too.
        let ribbons = format!("{RIBBONS_BEGIN}\n| r | 2 |\n{RIBBONS_END}");
        std::fs::write(&path, format!("# old\n{section}\n{ribbons}\n## more\n")).unwrap();
        keep_results(&path).unwrap();
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            document(&section, Some(&ribbons))
        );
        assert!(!dir.join("b.md.partial").exists());
        // A file without results is refused by name and left as it was.
        std::fs::write(&path, "# no results\n").unwrap();
        let err = format!("{:#}", keep_results(&path).unwrap_err());
        assert!(err.contains("b.md") && err.contains("no results"), "{err}");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "# no results\n");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn result_lines_are_read_and_the_ratio_line_skipped() {
        let text = "{\"engine\":\"up\",\"runtime\":\"native\",\"balloons\":10,\"steps\":5,\
            \"threads\":1,\"ms_per_step_median\":1.0,\"ms_per_step_p95\":2.0,\
            \"ms_per_step_mean\":1.2,\"settled_ms_per_step_median\":0.5,\
            \"max_penetration_m\":0.001,\"final_penetration_m\":0.0,\"escaped\":0,\
            \"awake_at_end\":3,\"peak_rss_mb\":null,\"rss_bytes_per_balloon\":null,\
            \"room_width_m\":1.5}\n{\"ratio_rapier_over_up\":3.0}\n";
        let results = parse_results(text).unwrap();
        assert_eq!(results.len(), 1);
        assert_eq!(results[0].balloons, 10);
        assert!(parse_results("{\"ratio_rapier_over_up\":3.0}").is_err());
        let md = results_section(&results, &["up-bench".into()], None, Path::new("b.svg"));
        assert!(md.starts_with(BEGIN) && md.trim_end().ends_with(END));
        assert!(md.contains("| native | up | 10 | 5 | 1 | 1.000 |"), "{md}");
    }

    #[test]
    fn the_ratios_are_by_median_and_by_mean() {
        let line = |engine: &str, median: f64, mean: f64| {
            format!(
                "{{\"engine\":\"{engine}\",\"runtime\":\"native\",\"balloons\":10,\"steps\":5,\
                 \"threads\":1,\"ms_per_step_median\":{median},\"ms_per_step_p95\":2.0,\
                 \"ms_per_step_mean\":{mean},\"settled_ms_per_step_median\":0.5,\
                 \"max_penetration_m\":0.001,\"final_penetration_m\":0.0,\"escaped\":0,\
                 \"awake_at_end\":3,\"peak_rss_mb\":null,\"rss_bytes_per_balloon\":null,\
                 \"room_width_m\":1.5}}\n"
            )
        };
        let text = line("up", 2.0, 4.0) + &line("rapier", 5.0, 14.0);
        let results = parse_results(&text).unwrap();
        let md = results_section(&results, &["up-bench".into()], None, Path::new("b.svg"));
        assert!(md.contains("| native | 10 | 2.50 | 3.50 |"), "{md}");
    }
}
