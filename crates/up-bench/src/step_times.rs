//! `--step-times FILE.csv`: every step's wall time for each engine, so the
//! distribution behind the median can be looked at (`step,<engine>,...` in
//! ms). The file is written whole or not at all, by up-scene's atomic writer.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{bail, Context, Result};

/// Fails early, before a long run, when `path` cannot be written: its folder
/// is missing, or it names a folder.
pub fn check_target(path: &Path) -> Result<()> {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    if !folder.is_dir() {
        bail!(
            "--step-times {}: folder {} does not exist",
            path.display(),
            folder.display()
        );
    }
    if path.is_dir() {
        bail!(
            "--step-times {}: is a folder, expected a file",
            path.display()
        );
    }
    Ok(())
}

/// The CSV text: a header of engine names, then one row per step.
pub fn to_csv(engines: &[&str], times: &[Vec<f64>]) -> String {
    let mut out = String::from("step");
    for name in engines {
        out.push(',');
        out.push_str(name);
    }
    out.push('\n');
    let steps = times.iter().map(Vec::len).max().unwrap_or(0);
    for step in 0..steps {
        let _ = write!(out, "{}", step + 1);
        for t in times {
            match t.get(step) {
                Some(ms) => {
                    let _ = write!(out, ",{ms:.4}");
                }
                None => out.push(','),
            }
        }
        out.push('\n');
    }
    out
}

/// Writes `to_csv` to `path`, replacing it only once the whole text is down.
pub fn write(path: &Path, engines: &[&str], times: &[Vec<f64>]) -> Result<()> {
    write_whole(path, &to_csv(engines, times))
        .with_context(|| format!("--step-times: writing {}", path.display()))
}

/// Writes `text` to `path` whole or not at all (`up_scene::atomic_file`):
/// a reader finds the old file or the new one, never a part.
pub fn write_whole(path: &Path, text: &str) -> std::io::Result<()> {
    up_scene::atomic_file::write_atomically(path, text.as_bytes())
        .map_err(up_scene::atomic_file::WriteError::into_io_error)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fs;

    #[test]
    fn a_header_then_a_row_per_step() {
        let csv = to_csv(&["up", "rapier"], &[vec![1.5, 2.0], vec![7.25, 8.0]]);
        assert_eq!(csv, "step,up,rapier\n1,1.5000,7.2500\n2,2.0000,8.0000\n");
    }

    #[test]
    fn written_whole_and_read_back() {
        let dir = std::env::temp_dir().join(format!("up-bench-step-times-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.csv");
        check_target(&path).unwrap();
        write(&path, &["up"], &[vec![3.0]]).unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "step,up\n1,3.0000\n");
        let names: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, ["t.csv"], "nothing but the file is left beside it");
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_missing_folder_or_a_folder_is_refused_by_name() {
        let missing = Path::new("/nonexistent-up-bench-folder/t.csv");
        let err = check_target(missing).unwrap_err().to_string();
        assert!(err.contains("/nonexistent-up-bench-folder"), "{err}");
        let dir = std::env::temp_dir();
        let err = check_target(&dir).unwrap_err().to_string();
        assert!(err.contains("is a folder"), "{err}");
    }
}
