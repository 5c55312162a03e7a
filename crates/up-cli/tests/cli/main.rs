//! The `up` binary end to end: every subcommand, every error path, the CSV
//! and JSON formats, and that failed runs leave no half-written files.
//! Simulations stay short (a few balloons, at most a simulated second, or
//! a few simulated hours as a time-lapse in a small room).

mod air;
mod body_hashes;
mod export_gltf;
mod forecast;
mod furniture;
mod probe;
mod ribbons;
mod run;
mod saved_state;
mod scene_errors;
mod soak;
mod tools;

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

/// The rows of a CSV file of numbers whose first line is `header`.
fn csv_rows(path: &str, header: &str) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some(header), "{path}");
    lines
        .map(|l| l.split(',').map(|f| f.parse::<f64>().unwrap()).collect())
        .collect()
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
