//! Atomic file output: write a temporary file beside the target, flush and sync it, then
//! rename it over the target. A failed or abandoned write leaves neither a partial target
//! nor the temporary file.

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// An output file could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    #[error("{path}: cannot {operation}: {source}")]
    Io { path: PathBuf, operation: &'static str, source: std::io::Error },
    #[error("{path}: {message}")]
    Invalid { path: PathBuf, message: String },
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "out".into());
    let unique = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.subsec_nanos());
    path.with_file_name(format!(".{name}.tmp-{}-{unique}", std::process::id()))
}

/// A file being written under a temporary name; [`AtomicFile::commit`] puts it in place.
/// Dropped without a commit (an error, a failed run), it removes its temporary file.
pub struct AtomicFile {
    path: PathBuf,
    tmp: PathBuf,
    out: Option<BufWriter<File>>,
}

impl AtomicFile {
    /// Creates the temporary file (and the target's directory).
    pub fn create(path: &Path) -> Result<Self, OutputError> {
        let io = |operation, source| OutputError::Io { path: path.to_path_buf(), operation, source };
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| io("create its directory", e))?;
        }
        let tmp = temp_path(path);
        let file = File::create(&tmp).map_err(|e| io("create a temporary file", e))?;
        Ok(AtomicFile { path: path.to_path_buf(), tmp, out: Some(BufWriter::new(file)) })
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Runs `write` on the file's stream, naming the file in an error.
    pub fn write_with(&mut self, write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<(), OutputError> {
        let path = self.path.clone();
        let out = self.out.as_mut().ok_or_else(|| OutputError::Invalid { path: path.clone(), message: "written after commit".into() })?;
        write(out).map_err(|source| OutputError::Io { path, operation: "write", source })
    }

    /// Flushes, syncs and renames the file onto its target.
    pub fn commit(mut self) -> Result<(), OutputError> {
        let io = |operation, source| OutputError::Io { path: self.path.clone(), operation, source };
        if let Some(out) = self.out.take() {
            let result = (|| {
                let file = out.into_inner().map_err(|e| io("write", e.into_error()))?;
                file.sync_all().map_err(|e| io("sync", e))?;
                std::fs::rename(&self.tmp, &self.path).map_err(|e| io("rename the temporary file onto it", e))
            })();
            if result.is_err() {
                let _ = std::fs::remove_file(&self.tmp);
            }
            result?;
        }
        Ok(())
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if self.out.take().is_some() {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}

/// Writes `path` atomically with the bytes produced by `write`.
pub fn write_atomic(path: &Path, write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<(), OutputError> {
    let mut file = AtomicFile::create(path)?;
    file.write_with(write)?;
    file.commit()
}

/// Writes `bytes` to `path` atomically.
pub fn write_atomic_bytes(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    write_atomic(path, |w| w.write_all(bytes))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failed_write_leaves_no_target_and_no_temporary() {
        let dir = std::env::temp_dir().join(format!("romdyn-atomic-{}", std::process::id()));
        let target = dir.join("out.bin");
        let r = write_atomic(&target, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("disk full"))
        });
        assert!(r.unwrap_err().to_string().contains("disk full"));
        assert!(!target.exists());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        write_atomic_bytes(&target, b"whole").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"whole");
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn an_abandoned_file_is_never_put_in_place() {
        let dir = std::env::temp_dir().join(format!("romdyn-atomic-drop-{}", std::process::id()));
        let target = dir.join("run.out");
        let mut f = AtomicFile::create(&target).unwrap();
        f.write_with(|w| w.write_all(b"Step 1\n")).unwrap();
        drop(f);
        assert!(!target.exists());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        std::fs::remove_dir_all(&dir).ok();
    }
}
