//! The temporary files and directories this process has made and not yet moved into
//! place: a signal handler removes them all before the process exits, and the next run
//! writing beside them removes those a killed process left.
//!
//! Every temporary is named `.hcm-tmp-<process id>-<counter>-<destination name>`: hidden,
//! recognisable as hcm's, and telling which process made it, so that a later run removes
//! only the leftovers of processes that no longer exist.

use std::ffi::OsStr;
use std::fs::{self, File, OpenOptions};
use std::io;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};

/// The start of every temporary's name.
pub const PREFIX: &str = ".hcm-tmp-";

/// The live temporaries. Held while temporaries are created, moved into place or removed:
/// a signal handler that takes it next sees a consistent set, and the renames of one
/// [`super::commit`] happen all before it or all after it.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

/// The registry, even if a thread panicked while holding it (the list stays usable).
fn live() -> MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// A new temporary name in `directory` for the destination called `name`.
pub(crate) fn temporary_name(directory: &Path, name: &OsStr) -> PathBuf {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let mut file_name = std::ffi::OsString::from(format!(
        "{PREFIX}{}-{}-",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    file_name.push(name);
    directory.join(file_name)
}

/// Makes a new temporary in `directory` for the destination called `name` with `make`
/// (which must fail if the path exists), registered until [`forget`] or [`remove`].
fn create<T>(
    directory: &Path,
    name: &OsStr,
    make: impl Fn(&Path) -> io::Result<T>,
) -> io::Result<(T, PathBuf)> {
    remove_leftovers(directory);
    let mut live = live();
    let mut attempts = 0;
    loop {
        let path = temporary_name(directory, name);
        match make(&path) {
            Ok(made) => {
                live.push(path.clone());
                return Ok((made, path));
            }
            // A leftover of a process that had our id and could not be removed: next name.
            Err(error) if error.kind() == io::ErrorKind::AlreadyExists && attempts < 100 => {
                attempts += 1;
            }
            Err(error) => return Err(error),
        }
    }
}

/// A new, registered temporary file in `directory` for the destination called `name`.
pub(crate) fn create_file(directory: &Path, name: &OsStr) -> io::Result<(File, PathBuf)> {
    create(directory, name, |path| {
        OpenOptions::new().write(true).create_new(true).open(path)
    })
}

/// A new, registered, empty temporary directory in `directory` for the destination
/// called `name`.
pub(crate) fn create_directory(directory: &Path, name: &OsStr) -> io::Result<PathBuf> {
    create(directory, name, |path| fs::create_dir(path)).map(|((), path)| path)
}

/// Removes the temporary file or directory at `path` and forgets it. Best effort: a
/// temporary that cannot be removed is left for [`remove_leftovers`].
pub fn remove(path: &Path) {
    let mut live = live();
    remove_path(path);
    live.retain(|p| p != path);
}

/// The live temporaries, as [`while_held`] hands them to its closure.
pub struct Held<'a>(&'a mut Vec<PathBuf>);

impl Held<'_> {
    /// Forgets `path`: it was moved into place (or removed).
    pub fn forget(&mut self, path: &Path) {
        self.0.retain(|p| p != path);
    }

    /// Registers `path` (an existing directory moved aside, to be removed).
    pub(crate) fn adopt(&mut self, path: &Path) {
        self.0.push(path.to_owned());
    }
}

/// Runs `moves` (renames of registered temporaries into place) with the registry held, so
/// that no signal handler acts in between; `moves` forgets what it moved.
pub(crate) fn while_held<T>(moves: impl FnOnce(&mut Held) -> T) -> T {
    let mut live = live();
    moves(&mut Held(&mut live))
}

/// Removes every live temporary and exits with `code`, holding the registry so that no
/// thread makes or moves another in between.
pub(crate) fn remove_all_and_exit(code: i32) -> ! {
    let live = live();
    for path in live.iter() {
        remove_path(path);
    }
    std::process::exit(code)
}

fn remove_path(path: &Path) {
    // A temporary directory is ours whole; `remove_dir_all` does not follow links out.
    let _ = match fs::symlink_metadata(path) {
        Ok(meta) if meta.is_dir() => fs::remove_dir_all(path),
        Ok(_) => fs::remove_file(path),
        Err(_) => Ok(()),
    };
}

/// Removes the temporaries in `directory` that processes which no longer exist left
/// behind (killed by SIGKILL, or the machine stopped). Best effort.
pub(crate) fn remove_leftovers(directory: &Path) {
    let Ok(entries) = fs::read_dir(directory) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = name.to_str().and_then(leftover_process) else {
            continue;
        };
        if pid != std::process::id() && !process_exists(pid) {
            remove_path(&entry.path());
        }
    }
}

/// The process id in a temporary's name (`.hcm-tmp-<pid>-<counter>-…`), if it is one.
fn leftover_process(name: &str) -> Option<u32> {
    let rest = name.strip_prefix(PREFIX)?;
    let (pid, rest) = rest.split_once('-')?;
    let (counter, _) = rest.split_once('-')?;
    counter.parse::<u64>().ok()?;
    pid.parse().ok()
}

/// Whether a process with id `pid` exists (`kill(pid, 0)`); where that cannot be told,
/// true, so that nothing is removed.
#[cfg(unix)]
fn process_exists(pid: u32) -> bool {
    let Some(pid) = i32::try_from(pid)
        .ok()
        .and_then(rustix::process::Pid::from_raw)
    else {
        return true;
    };
    rustix::process::test_kill_process(pid) != Err(rustix::io::Errno::SRCH)
}

#[cfg(not(unix))]
fn process_exists(_: u32) -> bool {
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_temporary_name_tells_its_process() {
        let path = temporary_name(Path::new("d"), OsStr::new("data-1.csv"));
        let name = path.file_name().unwrap().to_str().unwrap();
        assert!(
            name.starts_with(PREFIX) && name.ends_with("-data-1.csv"),
            "{name}"
        );
        assert_eq!(leftover_process(name), Some(std::process::id()));
        assert_eq!(leftover_process(".hcm-tmp-x-1-a"), None);
        assert_eq!(leftover_process(".data.csv.12-3.tmp"), None);
    }

    #[test]
    fn leftovers_of_dead_processes_are_removed_and_live_ones_kept() {
        let dir = tempfile::tempdir().unwrap();
        // Process ids above Linux's largest (2^22) never exist.
        let dead = dir.path().join(format!("{PREFIX}2147483000-0-data.csv"));
        let dead_directory = dir.path().join(format!("{PREFIX}2147483001-0-ball"));
        let ours = dir
            .path()
            .join(format!("{PREFIX}{}-0-data.csv", std::process::id()));
        let user = dir.path().join(".hcm-tmp-notes");
        fs::write(&dead, "x").unwrap();
        fs::create_dir(&dead_directory).unwrap();
        fs::write(dead_directory.join("s1.csv"), "x").unwrap();
        fs::write(&ours, "x").unwrap();
        fs::write(&user, "x").unwrap();
        remove_leftovers(dir.path());
        assert!(!dead.exists() && !dead_directory.exists());
        assert!(ours.exists() && user.exists());
    }
}
