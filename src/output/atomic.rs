//! Atomic file output: write a temporary file beside the target, flush and sync it, then
//! rename it over the target. A failed or abandoned write leaves neither a partial target
//! nor the temporary file (on SIGINT/SIGTERM too, see [`super::cleanup`]).
//!
//! A set of files that belong together (a run's `.out`, `.mov`, `.log`, `.m`, `.json`) is
//! put in place by [`commit_set`]: every file is synced first, then a journal
//! `.NAME.romdyn-commit` lists the renames, the renames are done and the journal removed.
//! A process killed during the renames leaves the journal: the set is incomplete while it
//! exists, and [`recover_set`] (run by the next run with the same prefix) completes it.
//! The journal and the renames are done holding an advisory lock on the folder, so two
//! processes writing the same names put whole sets in place, one after the other.
//!
//! A command that writes several files through writers that each commit their own
//! (`rom`, `freq`, `sweep`) runs them inside [`write_set`]: there every commit on the thread
//! is deferred, and the files are put in place together at the end, or none of them.

use std::cell::RefCell;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

thread_local! {
    /// The files whose commit [`write_set`] defers on this thread (`None` outside it).
    static DEFERRED: RefCell<Option<Vec<AtomicFile>>> = const { RefCell::new(None) };
}

/// An output file could not be written.
#[derive(Debug, thiserror::Error)]
pub enum OutputError {
    /// (`cause` is in the message and deliberately not an error `source`: `{:#}` would print it twice.)
    #[error("{path}: cannot {operation}: {cause}")]
    Io { path: PathBuf, operation: &'static str, cause: std::io::Error },
    #[error("{path}: {message}")]
    Invalid { path: PathBuf, message: String },
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_else(|| "out".into());
    let unique = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.subsec_nanos());
    path.with_file_name(format!(".{name}.tmp-{}-{unique}", std::process::id()))
}

/// Bytes a file collects before each write to the system: a run's per-step files (`.mov`,
/// `.out`, a few kB a step) go out in a few hundred kB at a time instead of 8 kB (the
/// default), a tenth of the write calls.
const WRITE_BUFFER: usize = 1 << 18;

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
        let io = |operation, source| OutputError::Io { path: path.to_path_buf(), operation, cause: source };
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir).map_err(|e| io("create its directory", e))?;
        }
        if path.is_dir() {
            return Err(OutputError::Invalid { path: path.to_path_buf(), message: "is a directory: cannot write a file there".into() });
        }
        super::cleanup::remove_stale_temporaries(path.parent().unwrap_or(Path::new("")));
        let tmp = temp_path(path);
        super::cleanup::register(&tmp);
        let file = match File::create(&tmp) {
            Ok(f) => f,
            Err(e) => {
                super::cleanup::unregister(&tmp);
                return Err(io("create a temporary file", e));
            }
        };
        Ok(AtomicFile { path: path.to_path_buf(), tmp, out: Some(BufWriter::with_capacity(WRITE_BUFFER, file)) })
    }

    /// The target path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Runs `write` on the file's stream, naming the file in an error.
    pub fn write_with(&mut self, write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>) -> Result<(), OutputError> {
        let AtomicFile { path, out, .. } = self;
        let out = out.as_mut().ok_or_else(|| OutputError::Invalid { path: path.clone(), message: "written after commit".into() })?;
        write(out).map_err(|source| OutputError::Io { path: path.clone(), operation: "write", cause: source })
    }

    /// Flushes and syncs the temporary file (it stays under its temporary name).
    fn sync(&mut self) -> Result<(), OutputError> {
        let io = |operation, source| OutputError::Io { path: self.path.clone(), operation, cause: source };
        if let Some(out) = self.out.take() {
            let file = out.into_inner().map_err(|e| io("write", e.into_error()))?;
            file.sync_all().map_err(|e| io("sync", e))?;
        }
        Ok(())
    }

    fn rename(&self) -> Result<(), OutputError> {
        std::fs::rename(&self.tmp, &self.path).map_err(|source| OutputError::Io { path: self.path.clone(), operation: "rename the temporary file onto it", cause: source })
    }

    /// Flushes, syncs and renames the file onto its target; inside [`write_set`], keeps it
    /// for the set instead.
    pub fn commit(mut self) -> Result<(), OutputError> {
        let deferred = DEFERRED.with(|d| match d.borrow_mut().as_mut() {
            Some(files) => {
                files.push(std::mem::replace(&mut self, AtomicFile { path: PathBuf::new(), tmp: PathBuf::new(), out: None }));
                true
            }
            None => false,
        });
        if deferred {
            return Ok(());
        }
        self.sync()?;
        let _guard = super::cleanup::commit_guard();
        self.rename()?;
        self.committed();
        Ok(())
    }

    fn committed(&mut self) {
        super::cleanup::unregister(&self.tmp);
        self.tmp = PathBuf::new();
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        if !self.tmp.as_os_str().is_empty() {
            let _ = std::fs::remove_file(&self.tmp);
            super::cleanup::unregister(&self.tmp);
        }
    }
}

/// Puts a set of files in place together (see the module doc); `journal` names the set's
/// journal. On an error no file of the set is left in place.
pub fn commit_set(mut files: Vec<AtomicFile>, journal: &Path) -> Result<(), OutputError> {
    for f in files.iter_mut() {
        f.sync()?;
    }
    let io = |operation, source| OutputError::Io { path: journal.to_path_buf(), operation, cause: source };
    let mut text = String::new();
    for f in &files {
        let (Some(tmp), Some(target)) = (f.tmp.to_str(), f.path.to_str()) else {
            return Err(OutputError::Invalid { path: f.path.clone(), message: "an output path must be UTF-8".into() });
        };
        if tmp.contains('\n') || target.contains('\n') || tmp.contains('\t') {
            return Err(OutputError::Invalid { path: f.path.clone(), message: "an output path must not contain a tab or a newline".into() });
        }
        text.push_str(&format!("{tmp}\t{target}\n"));
    }
    let _guard = super::cleanup::commit_guard();
    let _folder = lock_folder(journal);
    write_journal(journal, &text).map_err(|e| io("write the commit journal", e))?;
    for k in 0..files.len() {
        if let Err(e) = files[k].rename() {
            // Take the set back out: complete or absent.
            for f in &files[..k] {
                let _ = std::fs::remove_file(&f.path);
            }
            let _ = std::fs::remove_file(journal);
            return Err(e);
        }
    }
    for f in files.iter_mut() {
        f.committed();
    }
    std::fs::remove_file(journal).map_err(|e| io("remove the commit journal", e))
}

/// An exclusive advisory lock on the folder of `journal` (released when dropped), so that
/// two processes' sets in one folder are put in place one after the other; `None` where the
/// folder cannot be locked (the set is then put in place without it).
fn lock_folder(journal: &Path) -> Option<File> {
    let dir = journal.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let folder = File::open(dir).ok()?;
    folder.lock().ok()?;
    Some(folder)
}

/// Runs `write` with every [`AtomicFile::commit`] on this thread deferred, then puts the
/// files it wrote in place together ([`commit_set`], journal `journal`): after an error of
/// `write` or of the commit, none of them is (their temporaries are removed). Returns
/// `write`'s value and the paths put in place.
pub fn write_set<T, E: From<OutputError>>(journal: &Path, write: impl FnOnce() -> Result<T, E>) -> Result<(T, Vec<PathBuf>), E> {
    let outer = DEFERRED.with(|d| d.borrow_mut().replace(Vec::new()));
    let result = write();
    let files = DEFERRED.with(|d| std::mem::replace(&mut *d.borrow_mut(), outer)).unwrap_or_default();
    let value = result?;
    let paths: Vec<PathBuf> = files.iter().map(|f| f.path.clone()).collect();
    if let Some(k) = (1..paths.len()).find(|&k| paths[..k].contains(&paths[k])) {
        return Err(OutputError::Invalid { path: paths[k].clone(), message: "two outputs of this command would be this one file: name them apart".into() }.into());
    }
    if !files.is_empty() {
        commit_set(files, journal)?;
    }
    Ok((value, paths))
}

/// Checks, before any computation, the files a command will write, each with the option
/// that names it: none is a directory or a special file (a device, FIFO or socket: `-o
/// /dev/null` would have made `/dev/null.csv`), none is named by an empty or hidden-only
/// name (`-o dir/` would have made `dir/.csv`), and no two are the same file.
pub fn check_output_paths(outputs: &[(&str, PathBuf)]) -> Result<(), OutputError> {
    let invalid = |path: &Path, message: String| Err(OutputError::Invalid { path: path.to_path_buf(), message });
    for (k, (option, path)) in outputs.iter().enumerate() {
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        if name.is_empty() || name.starts_with('.') && !name[1..].contains('.') || path.to_string_lossy().ends_with('/') {
            return invalid(path, format!("{option}: names no file (a prefix such as DIR/NAME is needed)"));
        }
        if let Ok(meta) = std::fs::metadata(path) {
            if meta.is_dir() {
                return invalid(path, format!("{option}: is a directory: cannot write a file there"));
            }
            if !meta.is_file() {
                return invalid(path, format!("{option}: is a special file (a device, FIFO or socket): romdyn writes regular files only"));
            }
        }
        let same = |a: &Path, b: &Path| a == b || match (a.parent().map(absolute_dir), b.parent().map(absolute_dir)) {
            (Some(Some(x)), Some(Some(y))) => x == y && a.file_name() == b.file_name(),
            _ => false,
        };
        if let Some((other, _)) = outputs[..k].iter().find(|(_, p)| same(p, path)) {
            return invalid(path, format!("{other} and {option} would both write this file: name them apart"));
        }
    }
    Ok(())
}

/// The canonical form of an output's folder (`None` while it does not exist).
fn absolute_dir(dir: &Path) -> Option<PathBuf> {
    std::fs::canonicalize(if dir.as_os_str().is_empty() { Path::new(".") } else { dir }).ok()
}

/// Refuses a prefix that is a special file (`-o /dev/null`), whose files would land beside
/// it (`/dev/null.out`): the user meant to throw the output away, which a regular file does
/// not do either.
pub fn check_prefix(option: &str, prefix: &Path) -> Result<(), OutputError> {
    match std::fs::metadata(prefix) {
        Ok(meta) if !meta.is_file() && !meta.is_dir() => Err(OutputError::Invalid { path: prefix.to_path_buf(), message: format!("{option}: is a special file (a device, FIFO or socket): romdyn writes regular files named after a prefix, not into it") }),
        _ => Ok(()),
    }
}

fn write_journal(journal: &Path, text: &str) -> std::io::Result<()> {
    let tmp = temp_path(journal);
    let mut f = File::create(&tmp)?;
    f.write_all(text.as_bytes())?;
    f.sync_all()?;
    std::fs::rename(&tmp, journal)
}

/// Completes a set whose commit was interrupted (its journal exists): renames what is
/// still under a temporary name and removes the journal. Returns whether there was one.
pub fn recover_set(journal: &Path) -> Result<bool, OutputError> {
    let text = match std::fs::read_to_string(journal) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(false),
        Err(source) => return Err(OutputError::Io { path: journal.to_path_buf(), operation: "read the commit journal", cause: source }),
    };
    for line in text.lines() {
        if let Some((tmp, target)) = line.split_once('\t') {
            if Path::new(tmp).exists() {
                std::fs::rename(tmp, target).map_err(|source| OutputError::Io { path: target.into(), operation: "complete an interrupted commit", cause: source })?;
            }
        }
    }
    std::fs::remove_file(journal).map_err(|source| OutputError::Io { path: journal.to_path_buf(), operation: "remove the commit journal", cause: source })?;
    Ok(true)
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
    fn a_set_whose_rename_fails_is_taken_back_out() {
        let dir = std::env::temp_dir().join(format!("romdyn-atomic-set-{}", std::process::id()));
        let (a, b) = (dir.join("run.out"), dir.join("run.mov"));
        let journal = dir.join(".run.romdyn-commit");
        let mut fa = AtomicFile::create(&a).unwrap();
        fa.write_with(|w| w.write_all(b"out")).unwrap();
        let mut fb = AtomicFile::create(&b).unwrap();
        fb.write_with(|w| w.write_all(b"mov")).unwrap();
        // A non-empty directory appears where the second file goes: its rename fails.
        std::fs::create_dir_all(b.join("x")).unwrap();
        assert!(commit_set(vec![fa, fb], &journal).is_err());
        assert!(!a.exists() && !journal.exists());
        std::fs::remove_dir_all(&b).unwrap();
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        // The same set without the obstacle is put in place, journal removed.
        let mut fa = AtomicFile::create(&a).unwrap();
        fa.write_with(|w| w.write_all(b"out")).unwrap();
        let fb = AtomicFile::create(&b).unwrap();
        commit_set(vec![fa, fb], &journal).unwrap();
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2);
        // An interrupted commit (journal written, renames not done) is completed.
        let mut fc = AtomicFile::create(&dir.join("run.log")).unwrap();
        fc.write_with(|w| w.write_all(b"log")).unwrap();
        fc.sync().unwrap();
        std::fs::write(&journal, format!("{}\t{}\n", fc.tmp.display(), dir.join("run.log").display())).unwrap();
        std::mem::forget(fc);
        assert!(recover_set(&journal).unwrap());
        assert_eq!(std::fs::read(dir.join("run.log")).unwrap(), b"log");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 3);
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
