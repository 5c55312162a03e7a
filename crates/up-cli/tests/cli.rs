//! The `up` binary end to end: every subcommand, every error path, the CSV
//! and JSON formats, and that failed runs leave no half-written files.
//! Simulations stay short (a few balloons, at most a simulated second).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::Value;

fn up(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_up"))
        .args(args)
        .output()
        .expect("the up binary runs")
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// Runs `up` and expects success.
fn up_ok(args: &[&str]) -> String {
    let out = up(args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "up {args:?} failed:\n{}",
        stderr(&out)
    );
    assert!(!stderr(&out).contains("panicked"), "{}", stderr(&out));
    stdout(&out)
}

/// Runs `up` and expects exit code 2 with an `error:` message; returns stderr.
fn up_err(args: &[&str]) -> String {
    let out = up(args);
    let err = stderr(&out);
    assert_eq!(
        out.status.code(),
        Some(2),
        "up {args:?}: stdout {}\nstderr {err}",
        stdout(&out)
    );
    assert!(err.starts_with("error:"), "up {args:?}: {err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// The last line of standard output, as JSON.
fn last_json(text: &str) -> Value {
    let line = text.lines().last().expect("some output");
    serde_json::from_str(line).unwrap_or_else(|e| panic!("not JSON: {line}: {e}"))
}

/// A fresh directory per test, removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let dir = std::env::temp_dir().join(format!("up-cli-{name}-{}-{n}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    fn str(&self, name: &str) -> String {
        self.path(name).display().to_string()
    }

    fn files(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(&self.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn asset(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/scenes")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn help_is_available_everywhere() {
    assert!(up_ok(&["--help"]).contains("run"));
    for sub in [
        "run",
        "bench",
        "colliders",
        "validate",
        "export-obj",
        "fit-spheres",
        "soak",
    ] {
        let text = up_ok(&[sub, "--help"]);
        assert!(text.contains("Usage: up"), "{sub}: {text}");
    }
}

#[test]
fn unknown_subcommands_and_flags_exit_2() {
    up_err(&["fly"]);
    up_err(&["run", "--wings", "2"]);
    up_err(&["run", "--every", "0"]);
    up_err(&["run", "--balloons", "many"]);
}

#[test]
fn run_json_reports_every_field() {
    let text = up_ok(&["run", "--balloons", "3", "--seconds", "0.5", "--json"]);
    let j = last_json(&text);
    for key in [
        "balloons",
        "steps",
        "sim_seconds",
        "wall_seconds",
        "ms_per_step",
        "max_penetration_m",
        "escaped",
        "nan_bodies",
        "state_hash",
        "mean_height_m",
        "max_tilt_deg",
        "kinetic_energy_j",
    ] {
        assert!(j.get(key).is_some(), "missing {key} in {j}");
    }
    assert_eq!(j["balloons"], 3);
    assert_eq!(j["steps"], 30);
    assert!(
        (j["sim_seconds"].as_f64().unwrap() - 0.5).abs() < 1e-3,
        "{j}"
    );
    assert_eq!(j["escaped"], 0);
    assert_eq!(j["nan_bodies"], 0);
    let hash = j["state_hash"].as_str().unwrap();
    assert_eq!(hash.len(), 16);
    assert!(hash.chars().all(|c| c.is_ascii_hexdigit()), "{hash}");
    // Helium balloons released from the floor are rising.
    assert!(j["mean_height_m"].as_f64().unwrap() > 0.1, "{j}");
    // The summary table comes before the JSON line.
    assert!(text.contains("max penetration"), "{text}");
}

#[test]
fn runs_are_deterministic_for_a_seed() {
    let hash = |seed: &str| {
        let text = up_ok(&[
            "run",
            "--balloons",
            "4",
            "--seconds",
            "0.25",
            "--seed",
            seed,
            "--json",
        ]);
        last_json(&text)["state_hash"].as_str().unwrap().to_string()
    };
    assert_eq!(hash("5"), hash("5"));
    assert_ne!(hash("5"), hash("6"));
}

#[test]
fn run_writes_the_trajectory_csv_every_k_steps() {
    let dir = TempDir::new("csv");
    let csv = dir.str("traj.csv");
    up_ok(&[
        "run",
        "--balloons",
        "2",
        "--seconds",
        "0.25",
        "--every",
        "5",
        "--out",
        &csv,
    ]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("t,id,x,y,z,qx,qy,qz,qw"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|f| f.parse::<f64>().unwrap()).collect())
        .collect();
    // 15 steps: the start, steps 5, 10, 15; two balloons each.
    assert_eq!(rows.len(), 4 * 2, "{text}");
    assert!(rows.iter().all(|r| r.len() == 9));
    assert_eq!(rows[0][0], 0.0);
    assert!((rows.last().unwrap()[0] - 0.25).abs() < 1e-3);
    for r in &rows {
        let q_len = (r[5] * r[5] + r[6] * r[6] + r[7] * r[7] + r[8] * r[8]).sqrt();
        assert!((q_len - 1.0).abs() < 1e-4, "{r:?}");
    }
    assert_eq!(dir.files(), vec!["traj.csv"], "no temporary file remains");
}

#[test]
fn run_with_an_output_in_a_missing_directory_fails_cleanly() {
    let dir = TempDir::new("missing");
    let csv = dir.path("no/such/dir/out.csv");
    let err = up_err(&[
        "run",
        "--balloons",
        "1",
        "--seconds",
        "0.1",
        "--out",
        &csv.display().to_string(),
    ]);
    assert!(err.contains("out.csv"), "{err}");
    assert!(dir.files().is_empty());
    let state = dir.path("nope/state.bin");
    up_err(&[
        "run",
        "--balloons",
        "1",
        "--seconds",
        "0.1",
        "--save-state",
        &state.display().to_string(),
    ]);
    assert!(dir.files().is_empty());
}

#[test]
fn run_rejects_bad_scenes_with_file_key_and_line() {
    let dir = TempDir::new("bad");
    let missing = dir.str("missing.toml");
    let err = up_err(&["run", &missing]);
    assert!(
        err.contains(&missing) && err.contains("cannot read the scene file"),
        "{err}"
    );

    std::fs::write(dir.path("typo.toml"), "[room]\nwidth = 6\nwidht = 5\n").unwrap();
    let err = up_err(&["run", &dir.str("typo.toml")]);
    assert!(
        err.contains("typo.toml:3: room.widht: unknown field `widht`"),
        "{err}"
    );

    std::fs::write(dir.path("nan.toml"), "[sim]\ndt = nan\n").unwrap();
    let err = up_err(&["run", &dir.str("nan.toml")]);
    assert!(
        err.contains("nan.toml:2: sim.dt: expected a finite number"),
        "{err}"
    );

    std::fs::write(dir.path("scene.yaml"), "room: {}\n").unwrap();
    up_err(&["run", &dir.str("scene.yaml")]);

    let err = up_err(&["run", "--balloons", "1000000000"]);
    assert!(err.contains("balloons[0].count"), "{err}");
    let err = up_err(&["run", "--seconds=-1"]);
    assert!(err.contains("--seconds"), "{err}");
    let err = up_err(&["run", "--seconds", "0"]);
    assert!(err.contains("--seconds"), "{err}");
    up_err(&["run", "--seconds", "NaN"]);
}

#[test]
fn a_wrong_type_names_its_key_and_writes_no_output() {
    let dir = TempDir::new("wrong-type");
    let out = dir.str("out.csv");
    let state = dir.str("end.upsnap");
    std::fs::write(
        dir.path("room.json"),
        r#"{"room": {"width": [1,2], "depth": 6, "wall_height": 3, "ceiling": "flat"}}"#,
    )
    .unwrap();
    let err = up_err(&[
        "run",
        &dir.str("room.json"),
        "--out",
        &out,
        "--save-state",
        &state,
    ]);
    assert!(
        err.contains("room.json:1: room.width: invalid type: sequence, expected f32"),
        "{err}"
    );
    assert!(!err.contains("room.ceiling"), "{err}");

    std::fs::write(
        dir.path("room.toml"),
        "[room]\ndepth = 6\nwidth = [1, 2]\nceiling = \"flat\"\n",
    )
    .unwrap();
    let err = up_err(&["run", &dir.str("room.toml"), "--out", &out]);
    assert!(
        err.contains("room.toml:3: room.width: invalid type: sequence, expected f32"),
        "{err}"
    );
    assert_eq!(
        dir.files(),
        vec!["room.json", "room.toml"],
        "no output written"
    );
}

#[test]
fn empty_scene_files_are_refused_by_every_command() {
    let dir = TempDir::new("empty");
    std::fs::write(dir.path("zero.toml"), "").unwrap();
    std::fs::write(dir.path("zero.json"), "").unwrap();
    std::fs::write(dir.path("blank.toml"), " \n\t\n").unwrap();
    std::fs::write(dir.path("blank.json"), "\n   \n").unwrap();
    let out = dir.str("out.csv");
    let obj = dir.str("obj");
    for name in ["zero.toml", "zero.json", "blank.toml", "blank.json"] {
        let scene = dir.str(name);
        let expected = format!("{scene}: the scene is empty");
        let commands: [&[&str]; 5] = [
            &["run", &scene, "--out", &out, "--seconds", "0.1"],
            &["validate", &scene],
            &["bench", &scene, "--steps", "1"],
            &["soak", &scene, "--balloons", "2", "--seconds", "0.1"],
            &["export-obj", &obj, "--scene", &scene],
        ];
        for args in commands {
            let err = up_err(args);
            assert!(err.contains(&expected), "up {args:?}: {err}");
        }
    }
    assert_eq!(
        dir.files(),
        vec!["blank.json", "blank.toml", "zero.json", "zero.toml"],
        "no output written"
    );
}

/// Runs 3 balloons for 0.5 s, then again for 0.25 s saving the state in
/// `dir`; returns the whole run's output and the state file.
fn run_whole_and_save_half(dir: &TempDir) -> (String, String) {
    let state = dir.str("half.upsnap");
    let common = ["--balloons", "3", "--seed", "9", "--json"];
    let whole = up_ok(&[&["run", "--seconds", "0.5"][..], &common].concat());
    up_ok(
        &[
            &["run", "--seconds", "0.25", "--save-state", &state][..],
            &common,
        ]
        .concat(),
    );
    (whole, state)
}

#[test]
fn saved_state_continues_exactly() {
    let dir = TempDir::new("state");
    let (whole, state) = run_whole_and_save_half(&dir);
    assert_eq!(dir.files(), vec!["half.upsnap"]);
    let resumed = up_ok(&[
        "run",
        "--seconds",
        "0.25",
        "--load-state",
        &state,
        "--seed",
        "9",
        "--json",
    ]);
    assert_eq!(
        last_json(&whole)["state_hash"],
        last_json(&resumed)["state_hash"]
    );
    assert_eq!(last_json(&resumed)["steps"], 15);

    std::fs::write(dir.path("junk.upsnap"), b"not a snapshot").unwrap();
    let err = up_err(&["run", "--load-state", &dir.str("junk.upsnap")]);
    assert!(err.contains("junk.upsnap"), "{err}");
    up_err(&["run", "--load-state", &dir.str("absent.upsnap")]);
    up_err(&["run", "--load-state", &state, "--balloons", "2"]);
}

#[test]
fn bench_reports_timings_and_stages() {
    let text = up_ok(&["bench", "--balloons", "3", "--steps", "20", "--json"]);
    let j = last_json(&text);
    assert_eq!(j["balloons"], 3);
    assert_eq!(j["steps"], 20);
    for key in [
        "ms_per_step",
        "median_ms",
        "p95_ms",
        "max_ms",
        "wall_seconds",
        "state_hash",
    ] {
        assert!(j[key].is_number() || j[key].is_string(), "{key} in {j}");
    }
    let stages = j["stages"].as_array().unwrap();
    assert!(stages.iter().any(|s| s["name"] == "solve"), "{j}");
    up_err(&["bench", "--steps", "0"]);
    up_err(&["bench", "no-such-scene.toml"]);
}

#[test]
fn threads_set_the_pool_and_change_no_result() {
    let bench = |threads: &str| {
        let args = ["bench", "--balloons", "400", "--steps", "60", "--json"];
        last_json(&up_ok(&[&args[..], &["--threads", threads]].concat()))
    };
    let (one, three) = (bench("1"), bench("3"));
    assert_eq!(
        (one["threads"].as_u64(), three["threads"].as_u64()),
        (Some(1), Some(3))
    );
    assert_eq!(one["state_hash"], three["state_hash"]);
    let err = up_err(&["bench", "--threads", "0"]);
    assert!(err.contains("--threads"), "{err}");
}

#[test]
fn bench_times_a_saved_state_from_where_it_stopped() {
    let dir = TempDir::new("bench-state");
    let (whole, state) = run_whole_and_save_half(&dir);
    // 15 steps from the snapshot end where the whole 0.5 s run ends.
    let timed = up_ok(&["bench", "--steps", "15", "--load-state", &state, "--json"]);
    let (timed, whole) = (last_json(&timed), last_json(&whole));
    assert_eq!(timed["state_hash"], whole["state_hash"]);
    assert_eq!(timed["balloons"], 3);
    assert!(
        (timed["sim_seconds"].as_f64().unwrap() - 0.5).abs() < 1e-6,
        "{timed}"
    );

    let err = up_err(&["bench", "--load-state", &dir.str("absent.upsnap")]);
    assert!(err.contains("absent.upsnap"), "{err}");
    let err = up_err(&["bench", "--load-state", &state, "--balloons", "2"]);
    assert!(err.contains("--balloons"), "{err}");
}

#[test]
fn colliders_show_the_default_tree_and_mass() {
    let text = up_ok(&["colliders"]);
    assert!(
        text.contains("node  0") && text.contains("mass properties"),
        "{text}"
    );
    let j = last_json(&up_ok(&["colliders", "--json"]));
    let nodes = j["nodes"].as_array().unwrap();
    assert_eq!(nodes.iter().filter(|n| n["leaf"] == true).count(), 5, "{j}");
    assert_eq!(nodes[0]["leaf"], false);
    let mass = j["mass_kg"].as_f64().unwrap();
    assert!((0.002..0.02).contains(&mass), "{mass}");
    assert!(j["coverage"].as_f64().unwrap() > 0.99, "{j}");
}

#[test]
fn validate_accepts_every_example_and_rejects_bad_files() {
    for name in [
        "default.toml",
        "terminal-velocity.toml",
        "party-hall.toml",
        "thrown.toml",
        "two-gases.json",
    ] {
        let text = up_ok(&["validate", &asset(name)]);
        assert!(text.contains("valid"), "{name}: {text}");
    }
    let dir = TempDir::new("validate");
    std::fs::write(
        dir.path("crowded.toml"),
        "[room]\nwidth = 1\ndepth = 1\nwall_height = 1\n[[balloons]]\ncount = 900\n",
    )
    .unwrap();
    let err = up_err(&["validate", &dir.str("crowded.toml")]);
    assert!(
        err.contains("balloons[0].count") && err.contains("do not fit"),
        "{err}"
    );
    std::fs::write(dir.path("bad.json"), "{\"sim\": {\"substeps\": 100}}").unwrap();
    let err = up_err(&["validate", &dir.str("bad.json")]);
    assert!(err.contains("bad.json:1: sim.substeps"), "{err}");
    up_err(&["validate", &dir.str("absent.toml")]);
    up_err(&["validate"]);
}

#[test]
fn export_obj_writes_meshes_and_fit_spheres_reads_them_back() {
    let dir = TempDir::new("export");
    let out = dir.path("assets");
    let listed = up_ok(&["export-obj", &out.display().to_string()]);
    let balloon = out.join("balloon.obj");
    assert!(balloon.exists(), "{listed}");
    let written: Vec<&str> = listed.lines().collect();
    assert!(written.iter().any(|l| l.ends_with(".mtl")), "{listed}");
    assert!(written.iter().all(|l| Path::new(l).exists()), "{listed}");

    let json = dir.str("fit.json");
    up_ok(&[
        "fit-spheres",
        &balloon.display().to_string(),
        "--leaves",
        "5",
        "--out",
        &json,
    ]);
    let fit: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert!(fit["coverage"].as_f64().unwrap() > 0.99, "{fit}");
    assert!(fit["tree"].is_object(), "{fit}");
    // Without --out the JSON goes to standard output.
    let printed: Value =
        serde_json::from_str(&up_ok(&["fit-spheres", &balloon.display().to_string()])).unwrap();
    assert_eq!(printed["coverage"], fit["coverage"]);

    up_err(&["fit-spheres", &dir.str("absent.obj")]);
    up_err(&[
        "fit-spheres",
        &balloon.display().to_string(),
        "--leaves",
        "0",
    ]);
    std::fs::write(dir.path("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    up_err(&["fit-spheres", &dir.str("open.obj")]);
    let before = dir.files();
    up_err(&[
        "fit-spheres",
        &balloon.display().to_string(),
        "--out",
        &dir.str("no/dir/fit.json"),
    ]);
    assert_eq!(dir.files(), before);
}

#[test]
fn corrupted_or_truncated_state_files_are_rejected_clearly() {
    let dir = TempDir::new("corrupt");
    let state = dir.str("good.upsnap");
    up_ok(&[
        "run",
        "--balloons",
        "3",
        "--seconds",
        "0.1",
        "--save-state",
        &state,
    ]);
    let bytes = std::fs::read(&state).unwrap();
    let load = |name: &str, content: &[u8]| {
        std::fs::write(dir.path(name), content).unwrap();
        up_err(&["run", "--seconds", "0.1", "--load-state", &dir.str(name)])
    };
    let err = load("truncated.upsnap", &bytes[..bytes.len() / 2]);
    assert!(
        err.contains("truncated.upsnap") && err.contains("snapshot truncated"),
        "{err}"
    );
    let err = load("header.upsnap", &bytes[..10]);
    assert!(err.contains("snapshot truncated"), "{err}");
    let mut flipped = bytes.clone();
    let middle = flipped.len() / 2;
    flipped[middle] ^= 0x40;
    let err = load("flipped.upsnap", &flipped);
    assert!(
        err.contains("flipped.upsnap") && err.contains("checksum mismatch"),
        "{err}"
    );
    let mut longer = bytes.clone();
    longer.extend_from_slice(b"tail");
    let err = load("longer.upsnap", &longer);
    assert!(err.contains("snapshot truncated"), "{err}");
    let err = load("empty.upsnap", b"");
    assert!(err.contains("not a UP snapshot"), "{err}");
    let mut version = bytes.clone();
    version[6] = 0xEE;
    let err = load("version.upsnap", &version);
    assert!(err.contains("format version"), "{err}");
    // The good one still loads.
    up_ok(&["run", "--seconds", "0.1", "--load-state", &state]);
}

#[test]
fn an_interrupted_run_leaves_no_file_under_the_requested_name() {
    let dir = TempDir::new("interrupt");
    let csv = dir.str("traj.csv");
    let mut child = Command::new(env!("CARGO_BIN_EXE_up"))
        .args([
            "run",
            "--balloons",
            "200",
            "--seconds",
            "600",
            "--out",
            &csv,
        ])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Wait until the temporary file has rows in it, then kill the run.
    let started = std::time::Instant::now();
    let temp_has_rows = || {
        dir.files().iter().any(|name| {
            name.ends_with(".tmp") && std::fs::metadata(dir.path(name)).is_ok_and(|m| m.len() > 0)
        })
    };
    while !temp_has_rows() && started.elapsed().as_secs() < 60 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let files = dir.files();
    assert!(!files.contains(&"traj.csv".to_string()), "{files:?}");
    assert!(
        files
            .iter()
            .all(|f| f.starts_with(".traj.csv.") && f.ends_with(".tmp")),
        "only the temporary file may remain: {files:?}"
    );
}

#[test]
fn soak_checks_and_reports_its_figures() {
    let text = up_ok(&[
        "soak",
        "--balloons",
        "20",
        "--seconds",
        "2",
        "--check-every",
        "30",
        "--json",
    ]);
    let j = last_json(&text);
    assert_eq!(j["balloons"], 20);
    assert_eq!(j["steps"], 120);
    assert_eq!(j["checks"].as_array().unwrap().len(), 4, "{j}");
    assert_eq!(j["failures"].as_array().unwrap().len(), 0, "{j}");
    assert_eq!(j["max_non_finite"], 0);
    assert_eq!(j["max_escaped"], 0);
    let bound = j["penetration_bound_m"].as_f64().unwrap();
    assert!(
        (bound - 0.0014).abs() < 1e-6,
        "1 % of an 11-inch radius: {j}"
    );
    assert!(j["checks"][0]["rss_bytes"].as_u64().unwrap() > 0, "{j}");
    // The heap holds at least the world: 20 balloons' bodies and the room.
    assert!(
        j["checks"][0]["heap_bytes"].as_u64().unwrap() > 10_000,
        "{j}"
    );
    assert!(j["heap_end_bytes"].as_u64().unwrap() > 0, "{j}");
    // Two seconds are too short to hold the heap flat after a minute: said, not passed over.
    assert_eq!(j["heap_checked"], false, "{j}");
    assert!(
        text.contains("not made: the run is shorter than a minute"),
        "{text}"
    );
    assert!(text.contains("result") && text.contains("passed"), "{text}");
    up_err(&["soak", "--seconds", "0"]);
    up_err(&["soak", "--check-every", "0"]);
    let err = up_err(&["soak", "--balloons", "1000000000"]);
    assert!(err.contains("balloons[0].count"), "{err}");
}

#[test]
fn a_pile_asleep_again_holds_less_than_its_busiest_step_took() {
    // 300 balloons rise, pile up under the ceiling (the busiest steps, about
    // 4 s in) and are asleep well before the first minute. Buffers sized by
    // the contacts give back what the arrival took: without that, the heap at
    // one minute is the arrival's peak (2.4 MB against 1.0 MB).
    let text = up_ok(&[
        "soak",
        "--balloons",
        "300",
        "--seconds",
        "61",
        "--check-every",
        "30",
        "--stir-every",
        "0",
        "--json",
    ]);
    let j = last_json(&text);
    let checks = j["checks"].as_array().unwrap();
    let busiest = checks
        .iter()
        .map(|c| c["heap_bytes"].as_u64().unwrap())
        .max()
        .unwrap();
    let asleep = j["heap_at_1min_bytes"].as_u64().unwrap();
    assert_eq!(checks.last().unwrap()["awake"], 0, "{j}");
    assert!(
        asleep * 10 < busiest * 6,
        "asleep {asleep} B against {busiest} B at the busiest check"
    );
}

#[test]
fn bad_inputs_exit_2_naming_file_key_and_range() {
    let dir = TempDir::new("ranges");
    let cases = [
        (
            "count.toml",
            "[[balloons]]\ncount = 1000000000\n",
            "count.toml:2: balloons[0].count: expected at most 200000",
        ),
        (
            "big.json",
            "{\"balloons\": [{\"diameter_m\": 4.0}], \"room\": {\"wall_height\": 3}}",
            "big.json:1: balloons[0].diameter_m: expected a balloon smaller than the room",
        ),
        (
            "spawn.toml",
            "[[balloons]]\nspawn = { min = [-9, 0, -1], max = [1, 1, 1] }\n",
            "spawn.toml:2: balloons[0].spawn: expected a region inside the room",
        ),
        (
            "type.json",
            "{\"sim\": {\"dt\": \"fast\"}}",
            "type.json:1: sim.dt: invalid type: string \"fast\", expected f32",
        ),
        (
            "leaves.toml",
            "[[balloons]]\nleaves = 64\n",
            "leaves.toml:2: balloons[0].leaves: expected an integer in [1, 32], found 64",
        ),
        (
            "mesh.toml",
            "[room]\nmesh = \"absent.obj\"\n",
            "mesh.toml:2: room.mesh: cannot build the room",
        ),
    ];
    for (name, text, expected) in cases {
        std::fs::write(dir.path(name), text).unwrap();
        let path = dir.str(name);
        for command in ["run", "validate"] {
            let err = up_err(&[command, &path]);
            assert!(
                err.contains(&format!("{}{}", dir.0.display(), "/")),
                "{err}"
            );
            assert!(err.contains(expected), "{command} {name}: {err}");
        }
    }
    // An open room mesh is refused with the file and the edge.
    std::fs::write(dir.path("open.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(dir.path("room.toml"), "[room]\nmesh = \"open.obj\"\n").unwrap();
    let err = up_err(&["validate", &dir.str("room.toml")]);
    assert!(
        err.contains("open.obj") && err.contains("not closed"),
        "{err}"
    );
    // A huge OBJ (a device that never ends) is refused by its size.
    let err = up_err(&["fit-spheres", "/dev/zero"]);
    assert!(err.contains("/dev/zero: too large"), "{err}");
}
