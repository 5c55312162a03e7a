//! Saved states: continued exactly, timed from where they stopped, refused when damaged; interrupted runs leave no file.

use super::*;

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
    // The run must be cut while writing: rows in its temporary file, not done.
    let wrote = temp_has_rows();
    let running = child.try_wait().unwrap().is_none();
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(
        wrote,
        "no rows in a temporary file within 60 s: {:?}",
        dir.files()
    );
    assert!(running, "the run ended before it was interrupted");
    let files = dir.files();
    assert!(!files.contains(&"traj.csv".to_string()), "{files:?}");
    assert!(
        files.len() == 1 && files[0].starts_with(".traj.csv.") && files[0].ends_with(".tmp"),
        "the temporary file, and only it, remains: {files:?}"
    );
}
