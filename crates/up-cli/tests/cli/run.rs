//! The `run` command and its outputs, help and flags.

use super::*;

#[test]
fn help_is_available_everywhere() {
    assert!(up_ok(&["--help"]).contains("run"));
    for sub in [
        "run",
        "forecast",
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
    let rows = csv_rows(&csv, "t,id,x,y,z,qx,qy,qz,qw");
    // 15 steps: the start, steps 5, 10, 15; two balloons each.
    assert_eq!(rows.len(), 4 * 2, "{rows:?}");
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
