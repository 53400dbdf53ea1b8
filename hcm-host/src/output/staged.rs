//! Output files written to temporaries and moved into place together: a set of files
//! appears whole or not at all.

use super::destination::{resolve, Expected};
use super::{registry, OutputError};
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// An output file being written: a registered temporary beside its destination (or beside
/// the final target of a link there), buffered. Moved into place by [`commit`]; removed if
/// dropped before.
pub struct StagedFile {
    out: BufWriter<File>,
    temporary: Temporary,
}

/// A staged file written, flushed and synced to disk, ready for [`commit`].
pub struct Finished {
    temporary: Temporary,
}

/// A registered temporary and where it goes; removed on drop unless moved there.
struct Temporary {
    /// The temporary file.
    path: PathBuf,
    /// Where it is moved: the destination, or a link's final target.
    target: PathBuf,
    /// The destination as the caller gave it, for messages.
    shown: PathBuf,
    moved: bool,
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if !self.moved {
            registry::remove(&self.path);
        }
    }
}

impl StagedFile {
    /// Starts writing the file at `destination`: refuses a directory or special file there
    /// and follows a symbolic link (see [`super::destination`]), then creates the
    /// temporary, removing the leftovers of killed processes beside it first.
    pub fn create(destination: &Path) -> Result<StagedFile, OutputError> {
        let failed = |action| {
            move |source| OutputError {
                path: destination.to_owned(),
                action,
                error: source,
            }
        };
        let target = resolve(destination, Expected::File)?;
        let name = target.file_name().ok_or_else(|| {
            failed("write")(io::Error::new(
                io::ErrorKind::InvalidInput,
                "the path does not end in a file name",
            ))
        })?;
        let directory = match target.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent,
            _ => Path::new("."),
        };
        if !directory.is_dir() {
            return Err(failed("write")(io::Error::new(
                io::ErrorKind::NotFound,
                format!("the directory `{}` does not exist", directory.display()),
            )));
        }
        let (file, path) = registry::create_file(directory, name)
            .map_err(failed("create a temporary file next to"))?;
        Ok(StagedFile {
            out: BufWriter::new(file),
            temporary: Temporary {
                path,
                target,
                shown: destination.to_owned(),
                moved: false,
            },
        })
    }

    /// The destination as given.
    pub fn destination(&self) -> &Path {
        &self.temporary.shown
    }

    /// Flushes the file and syncs it to disk, ready to be moved into place.
    pub fn finish(self) -> Result<Finished, OutputError> {
        let StagedFile { out, temporary } = self;
        let failed = |source| OutputError {
            path: temporary.shown.clone(),
            action: "write",
            error: source,
        };
        let file = out.into_inner().map_err(|e| failed(e.into_error()))?;
        file.sync_all().map_err(failed)?;
        drop(file);
        Ok(Finished { temporary })
    }
}

impl Write for StagedFile {
    fn write(&mut self, bytes: &[u8]) -> io::Result<usize> {
        self.out.write(bytes)
    }

    fn write_all(&mut self, bytes: &[u8]) -> io::Result<()> {
        self.out.write_all(bytes)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.out.flush()
    }
}

/// Moves every finished file into place (renames, atomic each), with no signal handled in
/// between: after a signal the set is all there or none of it is.
///
/// If a rename fails (e.g. the destination became a directory meanwhile), the files of
/// the set already moved are removed again, so the set is absent rather than half new;
/// the files they replaced are lost then, as with any replacing write that failed late.
pub fn commit(files: Vec<Finished>) -> Result<(), OutputError> {
    let mut files = files;
    registry::while_held(|live| {
        for index in 0..files.len() {
            let t = &files[index].temporary;
            if let Err(source) = fs::rename(&t.path, &t.target) {
                for done in &files[..index] {
                    let _ = fs::remove_file(&done.temporary.target);
                }
                return Err(OutputError {
                    path: t.shown.clone(),
                    action: "move the finished file into place as",
                    error: source,
                });
            }
            live.forget(&t.path);
            files[index].temporary.moved = true;
        }
        Ok(())
    })
}
