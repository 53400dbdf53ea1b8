//! What an output path names: a regular file (or nothing yet) is written; a symbolic link
//! is followed; a directory, device, FIFO or socket is refused.
//!
//! Why follow links rather than refuse them: a link at the output path is the user's own
//! choice of where the data go (e.g. `data.csv -> /big-disk/data.csv`), and replacing it by
//! a regular file would silently undo that choice. hcm writes the link's final target
//! atomically (its temporary beside the target, so the rename stays on one file system)
//! and leaves the link as it was. hcm runs with the user's rights and never as a
//! privileged writer into shared directories, where following links would be a hazard.

use super::OutputError;
use std::fs::{self, FileType};
use std::io;
use std::path::{Path, PathBuf};

/// What the caller means to put at the path.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Expected {
    /// A file (CSV, TOML, JSON, PNG, …).
    File,
    /// A directory of files (`reproduce --out`).
    Directory,
}

/// Links followed before giving up (the kernel's own limit is 40).
const MAX_LINKS: usize = 40;

/// The path the output at `path` is written to: `path` itself, or the final target of
/// the chain of symbolic links at `path`, which exists as what `expected` says or not at
/// all. Anything else is refused with an error naming `path`.
pub fn resolve(path: &Path, expected: Expected) -> Result<PathBuf, OutputError> {
    let refuse = |problem: String| OutputError {
        path: path.to_owned(),
        action: "write to",
        error: io::Error::new(io::ErrorKind::InvalidInput, problem),
    };
    let mut target = path.to_owned();
    for _ in 0..=MAX_LINKS {
        let kind = match fs::symlink_metadata(&target) {
            Ok(meta) => meta.file_type(),
            Err(error) if error.kind() == io::ErrorKind::NotFound => return Ok(target),
            Err(source) => {
                return Err(OutputError {
                    path: path.to_owned(),
                    action: "inspect",
                    error: source,
                })
            }
        };
        if kind.is_symlink() {
            let link = fs::read_link(&target).map_err(|source| OutputError {
                path: path.to_owned(),
                action: "follow the link",
                error: source,
            })?;
            target = match target.parent() {
                Some(parent) if link.is_relative() => parent.join(link),
                _ => link,
            };
            continue;
        }
        let what = if target == path {
            "it is".to_owned()
        } else {
            format!("it links to `{}`, which is", target.display())
        };
        return match (expected, kind.is_file(), kind.is_dir()) {
            (Expected::File, true, _) | (Expected::Directory, _, true) => Ok(target),
            (Expected::File, _, true) => Err(refuse(format!(
                "{what} a directory; expected the path of a file to create or replace"
            ))),
            (Expected::Directory, true, _) => Err(refuse(format!(
                "{what} a file; expected the path of a directory to create"
            ))),
            _ => Err(refuse(format!(
                "{what} {}, not a regular file; hcm writes only regular files, \
                 which it creates or replaces whole (give the path of a file)",
                special(kind)
            ))),
        };
    }
    Err(refuse(format!(
        "more than {MAX_LINKS} symbolic links in a chain (a loop?)"
    )))
}

/// What a file that is neither regular file, directory nor link is.
#[cfg(unix)]
fn special(kind: FileType) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    if kind.is_fifo() {
        "a FIFO (named pipe)"
    } else if kind.is_char_device() {
        "a character device"
    } else if kind.is_block_device() {
        "a block device"
    } else if kind.is_socket() {
        "a socket"
    } else {
        "a special file"
    }
}

#[cfg(not(unix))]
fn special(_: FileType) -> &'static str {
    "a special file"
}

/// Refuses an existing output `path` of the other kind than the option `option` (as
/// typed, `--out`) writes (`directory`: whether it writes a directory), naming both, before
/// any work: the CLI checks every output option so, and the Python API its `out`.
pub fn check_kind(option: &str, path: &Path, directory: bool) -> Result<(), String> {
    let Ok(metadata) = fs::metadata(path) else {
        return Ok(());
    };
    match (directory, metadata.is_dir()) {
        (true, false) => Err(format!(
            "{option} {}: is a file; {option} names a directory (created if missing): give \
             a directory's path",
            path.display()
        )),
        (false, true) => Err(format!(
            "{option} {}: is a directory; {option} names a file: give a file's path, e.g. {}",
            path.display(),
            path.join("out").display()
        )),
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_and_absent_paths_are_written_where_they_are() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("a.csv");
        fs::write(&file, "x").unwrap();
        assert_eq!(resolve(&file, Expected::File).unwrap(), file);
        let absent = dir.path().join("b.csv");
        assert_eq!(resolve(&absent, Expected::File).unwrap(), absent);
        assert_eq!(
            resolve(dir.path(), Expected::Directory).unwrap(),
            dir.path()
        );
    }

    #[cfg(unix)]
    #[test]
    fn links_are_followed_to_their_final_target_and_special_files_refused() {
        use std::os::unix::fs::symlink;
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("real").join("data.csv");
        fs::create_dir(dir.path().join("real")).unwrap();
        // A relative link to a relative link to a file not yet there.
        symlink("real/data.csv", dir.path().join("first.csv")).unwrap();
        symlink("first.csv", dir.path().join("second.csv")).unwrap();
        let resolved = resolve(&dir.path().join("second.csv"), Expected::File).unwrap();
        assert_eq!(resolved, dir.path().join("real/data.csv"));
        fs::write(&target, "x").unwrap();
        assert_eq!(
            resolve(&dir.path().join("second.csv"), Expected::File).unwrap(),
            dir.path().join("real/data.csv")
        );

        let null = dir.path().join("null.csv");
        symlink("/dev/null", &null).unwrap();
        let error = resolve(&null, Expected::File).unwrap_err().to_string();
        assert!(
            error.contains("null.csv") && error.contains("/dev/null"),
            "{error}"
        );
        assert!(error.contains("character device") && error.contains("regular file"));

        let error = resolve(dir.path(), Expected::File).unwrap_err().to_string();
        assert!(
            error.contains("a directory; expected the path of a file"),
            "{error}"
        );

        let looped = dir.path().join("loop.csv");
        symlink("loop.csv", &looped).unwrap();
        let error = resolve(&looped, Expected::File).unwrap_err().to_string();
        assert!(
            error.contains("loop.csv") && error.contains("symbolic links"),
            "{error}"
        );
    }
}
