//! Writing output files so that a failed or interrupted run leaves nothing half-written:
//! every output (CSV, TOML, JSON, PNG) goes through [`write_atomically`].

use std::ffi::OsString;
use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// A file-system step of [`write_atomically`] failed.
#[derive(Debug, thiserror::Error)]
#[error("cannot {action} `{}`: {source}", path.display())]
pub struct OutputError {
    /// The destination file.
    pub path: PathBuf,
    /// What was being done, phrased to follow "cannot" and precede the path, e.g.
    /// "create a temporary file next to".
    pub action: &'static str,
    /// The operating system's error.
    #[source]
    pub source: io::Error,
}

/// Writes the file at `path` by calling `write` with a buffered writer to a new temporary
/// file in the same directory, then flushing it to disk and renaming it over `path`.
///
/// Only a complete file ever appears at `path`: if `write` returns an error (or panics),
/// or any file-system step fails, the temporary file is removed, `path` is untouched (it
/// keeps its old content, or stays absent) and the error is returned. `write`'s own error
/// type `E` is passed through; the file-system steps' [`OutputError`]s are converted into
/// it, so `E` can be e.g. `anyhow::Error` or a crate error with `From<OutputError>`.
///
/// The temporary file is named `.<file name>.<process id>-<counter>.tmp`, so that
/// concurrent writers never share one; the replaced file's permissions are not kept.
pub fn write_atomically<E>(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E>
where
    E: From<OutputError>,
{
    let failed = |action: &'static str| {
        move |source: io::Error| OutputError {
            path: path.to_owned(),
            action,
            source,
        }
    };
    let file_name = path.file_name().ok_or_else(|| {
        failed("write")(io::Error::new(
            io::ErrorKind::InvalidInput,
            "the path does not end in a file name",
        ))
    })?;
    let directory = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let (file, temporary) = create_temporary(directory, file_name)
        .map_err(failed("create a temporary file next to"))?;
    // Declared before `out`, so dropped after it: the file is closed before removal.
    let mut temporary = Temporary {
        path: temporary,
        keep: false,
    };
    let mut out = BufWriter::new(file);
    write(&mut out)?;
    let file = out
        .into_inner()
        .map_err(|error| failed("write")(error.into_error()))?;
    file.sync_all().map_err(failed("write"))?;
    drop(file);
    fs::rename(&temporary.path, path).map_err(failed("move the finished file into place as"))?;
    temporary.keep = true;
    Ok(())
}

/// Creates a new, uniquely named temporary file in `directory`.
fn create_temporary(directory: &Path, file_name: &std::ffi::OsStr) -> io::Result<(File, PathBuf)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let mut attempts = 0;
    loop {
        let mut name = OsString::from(".");
        name.push(file_name);
        name.push(format!(
            ".{}-{}.tmp",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let path = directory.join(name);
        match OpenOptions::new().write(true).create_new(true).open(&path) {
            Ok(file) => return Ok((file, path)),
            // A leftover of a crashed process that had the same id: try the next name.
            Err(error) if error.kind() == io::ErrorKind::AlreadyExists && attempts < 100 => {
                attempts += 1;
            }
            Err(error) => return Err(error),
        }
    }
}

/// Removes the temporary file when dropped, unless it has become the destination.
struct Temporary {
    path: PathBuf,
    keep: bool,
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if !self.keep {
            // Best effort: the error being returned (or the panic) matters more.
            let _ = fs::remove_file(&self.path);
        }
    }
}

/// Writes `bytes` as the whole content of the file at `path`, atomically (see
/// [`write_atomically`]).
pub fn write_bytes(path: &Path, bytes: &[u8]) -> Result<(), OutputError> {
    write_atomically(path, |w: &mut dyn Write| {
        w.write_all(bytes).map_err(|source| OutputError {
            path: path.to_owned(),
            action: "write",
            source,
        })
    })
}
