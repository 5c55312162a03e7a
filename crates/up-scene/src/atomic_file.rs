//! Output files written whole or not at all: into a temporary file beside
//! the target, renamed over it when complete. A failed or interrupted run
//! leaves no half file under the target's name. Every file UP writes (the
//! CLI's trajectories, snapshots and fits; the OBJ and MTL exports) goes
//! through here.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use thiserror::Error;

/// A file that could not be written; the message names it.
#[derive(Debug, Error)]
pub enum WriteError {
    /// The temporary file could not be made (a missing directory, no permission).
    #[error("cannot create {}", path.display())]
    Create {
        path: PathBuf,
        #[source]
        source: io::Error,
    },
    /// Writing, syncing or the final rename failed.
    #[error("cannot write {}", path.display())]
    Write {
        path: PathBuf,
        #[source]
        source: io::Error,
    },
}

impl WriteError {
    /// The target the error is about.
    pub fn path(&self) -> &Path {
        match self {
            WriteError::Create { path, .. } | WriteError::Write { path, .. } => path,
        }
    }

    /// The I/O error underneath.
    pub fn io_error(&self) -> &io::Error {
        match self {
            WriteError::Create { source, .. } | WriteError::Write { source, .. } => source,
        }
    }

    pub fn into_io_error(self) -> io::Error {
        match self {
            WriteError::Create { source, .. } | WriteError::Write { source, .. } => source,
        }
    }
}

/// A file being written: nothing appears under the target's name until `commit`.
pub struct AtomicFile {
    target: PathBuf,
    temp: PathBuf,
    /// `None` once committed.
    writer: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Creates the temporary file now, so a missing directory fails before any work.
    pub fn create(target: &Path) -> Result<AtomicFile, WriteError> {
        let create_error = |source| WriteError::Create {
            path: target.to_path_buf(),
            source,
        };
        let name = target.file_name().ok_or_else(|| {
            create_error(io::Error::new(
                io::ErrorKind::InvalidInput,
                "expected a file name",
            ))
        })?;
        let temp_name = format!(".{}.{}.tmp", name.to_string_lossy(), std::process::id());
        let temp = target.with_file_name(temp_name);
        let file = File::create(&temp).map_err(create_error)?;
        Ok(AtomicFile {
            target: target.to_path_buf(),
            temp,
            writer: Some(BufWriter::new(file)),
        })
    }

    /// Flushes, syncs, closes and renames the temporary file onto the target.
    pub fn commit(mut self) -> Result<(), WriteError> {
        let writer = self.writer.take();
        let finish = || -> io::Result<()> {
            if let Some(writer) = writer {
                let file = writer.into_inner().map_err(|e| e.into_error())?;
                file.sync_all()?;
            }
            std::fs::rename(&self.temp, &self.target)
        };
        finish().map_err(|source| WriteError::Write {
            path: self.target.clone(),
            source,
        })
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        match &mut self.writer {
            Some(w) => w.write(buf),
            None => Err(io::Error::other("file already committed")),
        }
    }

    fn flush(&mut self) -> io::Result<()> {
        match &mut self.writer {
            Some(w) => w.flush(),
            None => Ok(()),
        }
    }
}

impl Drop for AtomicFile {
    /// Not committed (an error, or a rename that failed): remove the temporary file.
    fn drop(&mut self) {
        self.writer.take();
        if self.temp.exists() {
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

/// Writes `bytes` to `target` atomically.
pub fn write_atomically(target: &Path, bytes: &[u8]) -> Result<(), WriteError> {
    let mut file = AtomicFile::create(target)?;
    file.write_all(bytes).map_err(|source| WriteError::Write {
        path: target.to_path_buf(),
        source,
    })?;
    file.commit()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("up-atomic-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn the_target_appears_only_on_commit() {
        let dir = scratch("commit");
        let target = dir.join("out.csv");
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(b"half a file").unwrap();
        file.flush().unwrap();
        assert!(!target.exists(), "nothing under the name before commit");
        assert_eq!(names(&dir).len(), 1);
        file.commit().unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"half a file");
        assert_eq!(names(&dir), vec!["out.csv"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn an_abandoned_write_leaves_nothing() {
        let dir = scratch("abandon");
        let target = dir.join("out.csv");
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(&[b'x'; 100_000]).unwrap();
        drop(file);
        assert!(names(&dir).is_empty(), "{:?}", names(&dir));
        // An existing target is kept whole when a new write is abandoned.
        std::fs::write(&target, "old").unwrap();
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(b"new, unfinished").unwrap();
        drop(file);
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
        assert_eq!(names(&dir), vec!["out.csv"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failing_rename_leaves_no_target_and_no_temporary() {
        let dir = scratch("rename");
        // A directory in the way: the rename fails after the data is written.
        let target = dir.join("taken");
        std::fs::create_dir_all(target.join("inside")).unwrap();
        let mut file = AtomicFile::create(&target).unwrap();
        file.write_all(b"data").unwrap();
        let e = file.commit().unwrap_err();
        assert!(matches!(e, WriteError::Write { .. }), "{e}");
        assert_eq!(e.to_string(), format!("cannot write {}", target.display()));
        assert_eq!(e.path(), target);
        assert_eq!(names(&dir), vec!["taken"]);
        assert!(target.is_dir());
        let missing = dir.join("no/such/dir/f");
        let e = write_atomically(&missing, b"x").unwrap_err();
        assert!(matches!(e, WriteError::Create { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            format!("cannot create {}", missing.display())
        );
        assert_eq!(e.io_error().kind(), io::ErrorKind::NotFound);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
