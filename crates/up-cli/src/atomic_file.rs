//! Output files written whole or not at all: into a temporary file beside
//! the target, renamed over it when complete. A failed or interrupted run
//! leaves no half file under the target's name.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

pub struct AtomicFile {
    target: PathBuf,
    temp: PathBuf,
    /// `None` once committed.
    writer: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Creates the temporary file now, so a missing directory fails before any work.
    pub fn create(target: &Path) -> Result<AtomicFile> {
        let name = target
            .file_name()
            .with_context(|| format!("{}: expected a file name", target.display()))?;
        let temp_name = format!(".{}.{}.tmp", name.to_string_lossy(), std::process::id());
        let temp = target.with_file_name(temp_name);
        let file =
            File::create(&temp).with_context(|| format!("cannot create {}", target.display()))?;
        Ok(AtomicFile {
            target: target.to_path_buf(),
            temp,
            writer: Some(BufWriter::new(file)),
        })
    }

    /// Flushes, syncs, closes and renames the temporary file onto the target.
    pub fn commit(mut self) -> Result<()> {
        let writer = self.writer.take();
        let finish = || -> io::Result<()> {
            if let Some(writer) = writer {
                let file = writer.into_inner().map_err(|e| e.into_error())?;
                file.sync_all()?;
            }
            std::fs::rename(&self.temp, &self.target)
        };
        finish().with_context(|| format!("cannot write {}", self.target.display()))
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
pub fn write_atomically(target: &Path, bytes: &[u8]) -> Result<()> {
    let mut file = AtomicFile::create(target)?;
    file.write_all(bytes)
        .with_context(|| format!("cannot write {}", target.display()))?;
    file.commit()
}
