//! Writing outputs so that a failed or interrupted run leaves nothing half-written. Every
//! file hcm writes (CSV, TOML, JSON, PNG, SVG, blobs) goes through here:
//!
//! - [`write_atomically`] (one file) and [`StagedFile`] + [`commit`] (a set of files that
//!   belong together, like `generate`'s OUT, OUT.s1.csv and OUT.s2.csv) write to hidden
//!   temporaries beside the destination and rename them into place at the end, all of a
//!   set at once: the outputs appear complete or not at all.
//! - [`StagedDirectory`] does the same for a directory of outputs (`reproduce --out`).
//! - [`destination`]: a directory, device, FIFO or socket at an output path is refused; a
//!   symbolic link is followed (its target written, the link kept; why, in that module).
//! - [`remove_temporaries_on_signals`]: SIGINT, SIGTERM and SIGHUP remove every live
//!   temporary before the process exits; leftovers of a SIGKILL are removed by the next
//!   run writing to the same directory (see [`signals`](remove_temporaries_on_signals)).
//! - [`ensure_space`]: refuses long work whose output will not fit on the disk.

mod destination;
mod directory;
mod registry;
mod signals;
mod space;
mod staged;

pub use destination::check_kind;
pub use directory::StagedDirectory;
pub use registry::PREFIX as TEMPORARY_PREFIX;
pub use signals::remove_temporaries_on_signals;
pub use space::{available_space, bytes, ensure_space, NoSpace};
pub use staged::{commit, Finished, StagedFile};

use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// A file-system step of writing an output failed, or the output path names something
/// hcm does not write to.
#[derive(Debug, thiserror::Error)]
///
/// The operating system's error is part of the message, not a separate source: the
/// message reads whole wherever it is shown.
#[error("cannot {action} `{}`: {error}", path.display())]
pub struct OutputError {
    /// The destination, as given.
    pub path: PathBuf,
    /// What was being done, phrased to follow "cannot" and precede the path, e.g.
    /// "create a temporary file next to".
    pub(crate) action: &'static str,
    /// The operating system's error, or what is wrong with the destination.
    pub(crate) error: io::Error,
}

/// Writes the file at `path` by calling `write` with a buffered writer to a new temporary
/// file beside it, then flushing it to disk and renaming it over `path`.
///
/// Only a complete file ever appears at `path`: if `write` returns an error (or panics),
/// or any file-system step fails, the temporary file is removed, `path` is untouched (it
/// keeps its old content, or stays absent) and the error is returned. `write`'s own error
/// type `E` is passed through; the file-system steps' [`OutputError`]s are converted into
/// it, so `E` can be e.g. `anyhow::Error` or a crate error with `From<OutputError>`.
///
/// The temporary is named `.hcm-tmp-<process id>-<counter>-<file name>`, so that
/// concurrent writers never share one; the replaced file's permissions are not kept. A
/// link at `path` is followed and a special file refused (see [`destination`]).
pub fn write_atomically<E>(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E>
where
    E: From<OutputError>,
{
    let mut file = StagedFile::create(path)?;
    write(&mut file)?;
    commit(vec![file.finish()?])?;
    Ok(())
}

/// Writes `bytes` as the whole content of the file at `path`, atomically (see
/// [`write_atomically`]).
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    write_atomically(path, |w: &mut dyn Write| {
        w.write_all(bytes).map_err(|source| OutputError {
            path: path.to_owned(),
            action: "write",
            error: source,
        })
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use std::fs;

    /// The names in `dir`, sorted (what a test expects to find at a destination).
    pub(crate) fn entries(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_set_of_files_appears_together_or_not_at_all() {
        let dir = tempfile::tempdir().unwrap();
        let paths = ["data.csv", "data.s1.csv", "data.s2.csv"].map(|n| dir.path().join(n));
        let mut files: Vec<StagedFile> = paths
            .iter()
            .map(|p| StagedFile::create(p).unwrap())
            .collect();
        for file in &mut files {
            file.write_all(b"rows").unwrap();
        }
        assert!(paths.iter().all(|p| !p.exists()), "nothing before commit");
        assert_eq!(entries(dir.path()).len(), 3, "three temporaries");
        let finished = files.into_iter().map(|f| f.finish().unwrap()).collect();
        commit(finished).unwrap();
        assert_eq!(
            entries(dir.path()),
            ["data.csv", "data.s1.csv", "data.s2.csv"]
        );

        // Abandoned half-way: the temporaries go, the old files stay.
        let mut first = StagedFile::create(&paths[0]).unwrap();
        first.write_all(b"new").unwrap();
        let second = StagedFile::create(&paths[1]).unwrap();
        drop((first, second));
        assert_eq!(
            entries(dir.path()),
            ["data.csv", "data.s1.csv", "data.s2.csv"]
        );
        assert_eq!(fs::read_to_string(&paths[0]).unwrap(), "rows");
    }

    #[test]
    fn a_failed_move_leaves_none_of_the_set() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.csv"), dir.path().join("b.csv"));
        let files = [&a, &b].map(|p| StagedFile::create(p).unwrap().finish().unwrap());
        // `b.csv` becomes a non-empty directory after staging: its rename fails.
        fs::create_dir(&b).unwrap();
        fs::write(b.join("keep"), "x").unwrap();
        let error = commit(files.into()).unwrap_err();
        assert_eq!(error.path, b);
        assert_eq!(
            entries(dir.path()),
            ["b.csv"],
            "a.csv taken back, temporaries gone"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_link_keeps_pointing_at_the_file_written() {
        let dir = tempfile::tempdir().unwrap();
        fs::create_dir(dir.path().join("disk")).unwrap();
        let link = dir.path().join("data.csv");
        std::os::unix::fs::symlink("disk/real.csv", &link).unwrap();
        write_bytes(&link, b"first").unwrap();
        write_bytes(&link, b"second").unwrap();
        assert!(fs::symlink_metadata(&link).unwrap().is_symlink());
        assert_eq!(
            fs::read_to_string(dir.path().join("disk/real.csv")).unwrap(),
            "second"
        );
        assert_eq!(entries(&dir.path().join("disk")), ["real.csv"]);
    }
}
