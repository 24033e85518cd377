//! Temporary files that must not outlive the process: every [`AtomicFile`] registers its
//! temporary here; on SIGINT, SIGTERM or SIGHUP (after [`remove_temporaries_on_signal`])
//! they are removed and the process exits with status 128 + the signal number. A set of
//! files being put in place holds [`commit_guard`], so a signal waits for the renames to
//! end: the set is then complete, never half renamed. Temporaries that a killed process
//! (SIGKILL, power loss) left behind are removed by the next process that writes in
//! their folder ([`remove_stale_temporaries`]).
//!
//! [`AtomicFile`]: super::atomic::AtomicFile

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

static TEMPORARIES: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());
static COMMIT: Mutex<()> = Mutex::new(());
static SCANNED: Mutex<Option<HashSet<PathBuf>>> = Mutex::new(None);

fn lock<T>(m: &Mutex<T>) -> MutexGuard<'_, T> {
    m.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

pub(crate) fn register(path: &Path) {
    lock(&TEMPORARIES).push(path.to_path_buf());
}

pub(crate) fn unregister(path: &Path) {
    lock(&TEMPORARIES).retain(|p| p != path);
}

/// Held while a set of files is renamed into place.
pub(crate) fn commit_guard() -> MutexGuard<'static, ()> {
    lock(&COMMIT)
}

/// Starts a thread that removes the registered temporaries on SIGINT, SIGTERM or SIGHUP
/// and exits with status 128 + signal. Call once, early in `main`.
pub fn remove_temporaries_on_signal() -> std::io::Result<()> {
    use signal_hook::consts::{SIGHUP, SIGINT, SIGTERM};
    let mut signals = signal_hook::iterator::Signals::new([SIGINT, SIGTERM, SIGHUP])?;
    std::thread::Builder::new().name("romdyn-signals".into()).spawn(move || {
        if let Some(signal) = signals.forever().next() {
            let _commit = commit_guard();
            for p in lock(&TEMPORARIES).drain(..) {
                let _ = std::fs::remove_file(&p);
            }
            std::process::exit(128 + signal);
        }
    })?;
    Ok(())
}

/// The process id in a temporary's name `.NAME.tmp-PID-NANOS`, if it is one.
pub(crate) fn temporary_pid(name: &str) -> Option<u32> {
    let rest = name.strip_prefix('.')?;
    let (_, tail) = rest.rsplit_once(".tmp-")?;
    let (pid, nanos) = tail.split_once('-')?;
    nanos.bytes().all(|b| b.is_ascii_digit()).then_some(())?;
    pid.parse().ok()
}

/// Removes, once per folder and process, the temporaries of processes that no longer run
/// (known from /proc; elsewhere nothing is removed).
pub(crate) fn remove_stale_temporaries(dir: &Path) {
    let proc = Path::new("/proc/self");
    if !proc.exists() {
        return;
    }
    let key = std::fs::canonicalize(dir).unwrap_or_else(|_| dir.to_path_buf());
    if !lock(&SCANNED).get_or_insert_with(HashSet::new).insert(key) {
        return;
    }
    let Ok(entries) = std::fs::read_dir(if dir.as_os_str().is_empty() { Path::new(".") } else { dir }) else { return };
    for e in entries.flatten() {
        let name = e.file_name();
        let Some(pid) = name.to_str().and_then(temporary_pid) else { continue };
        if pid != std::process::id() && !Path::new(&format!("/proc/{pid}")).exists() {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporary_names_give_their_process() {
        assert_eq!(temporary_pid(".run.out.tmp-1234-99"), Some(1234));
        assert_eq!(temporary_pid(".a.tmp-b.tmp-7-1"), Some(7));
        assert_eq!(temporary_pid("run.out"), None);
        assert_eq!(temporary_pid(".run.out.tmp-x-1"), None);
    }
}
