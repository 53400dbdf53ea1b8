//! An output directory built as a hidden temporary directory and renamed into place at
//! the end: it appears complete or not at all (`reproduce --out DIR`).

use super::destination::{resolve, Expected};
use super::{registry, OutputError};
use std::ffi::OsString;
use std::fs;
use std::io;
use std::path::{Path, PathBuf};

/// An output directory being filled: write its files into [`StagedDirectory::path`], then
/// [`StagedDirectory::commit`]. Dropped before, it is removed with everything in it.
///
/// An existing directory at the destination is replaced only when it is empty or a
/// previous output of the same kind: it holds the `marker` file (e.g. `results.json`) and
/// nothing but regular files, each of a name the new output also has. Anything else is
/// refused, so that no file of the user's is ever deleted.
pub struct StagedDirectory {
    /// The temporary directory.
    path: PathBuf,
    /// Where it goes: the destination, or a link's final target.
    target: PathBuf,
    /// The destination as given, for messages.
    shown: PathBuf,
    /// The file that marks a previous output.
    marker: &'static str,
    moved: bool,
}

impl StagedDirectory {
    /// Starts the directory at `destination`. Refuses at once what [`commit`] would refuse
    /// for the existing directory there (except the comparison of names, which needs the
    /// new output). Nothing is created at the destination, not even missing parents,
    /// until [`commit`]: the temporary goes into the nearest existing ancestor.
    ///
    /// [`commit`]: StagedDirectory::commit
    pub fn create(destination: &Path, marker: &'static str) -> Result<Self, OutputError> {
        let target = resolve(destination, Expected::Directory)?;
        let shown = destination.to_owned();
        if target.exists() {
            replaceable(&target, marker, None).map_err(|problem| refused(&shown, problem))?;
        }
        let name = target.file_name().map(OsString::from).ok_or_else(|| {
            refused(
                &shown,
                "the path does not end in a directory name".to_owned(),
            )
        })?;
        let mut ancestor = target.parent().unwrap_or(Path::new("."));
        while !ancestor.as_os_str().is_empty() && !ancestor.is_dir() {
            ancestor = ancestor.parent().unwrap_or(Path::new(""));
        }
        if ancestor.as_os_str().is_empty() {
            ancestor = Path::new(".");
        }
        let path = registry::create_directory(ancestor, &name).map_err(|source| OutputError {
            path: shown.clone(),
            action: "create a temporary directory for",
            error: source,
        })?;
        Ok(StagedDirectory {
            path,
            target,
            shown,
            marker,
            moved: false,
        })
    }

    /// Where to write the files.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Moves the directory into place: creates missing parents, sets a replaceable
    /// existing directory aside, renames the new one in and removes the old one, with no
    /// signal handled in between.
    pub fn commit(mut self) -> Result<(), OutputError> {
        let shown = &self.shown;
        let failed = |action| {
            move |source| OutputError {
                path: shown.clone(),
                action,
                error: source,
            }
        };
        if let Some(parent) = self.target.parent().filter(|p| !p.as_os_str().is_empty()) {
            fs::create_dir_all(parent).map_err(failed("create the parent directories of"))?;
        }
        let old = self.target.exists();
        if old {
            let names = names(&self.path).map_err(failed("list"))?;
            replaceable(&self.target, self.marker, Some(&names))
                .map_err(|problem| refused(&self.shown, problem))?;
        }
        let (path, target) = (&self.path, &self.target);
        let aside = registry::while_held(|live| -> Result<Option<PathBuf>, OutputError> {
            if !old {
                fs::rename(path, target).map_err(failed("move the finished directory to"))?;
                live.forget(path);
                return Ok(None);
            }
            // The old output under a temporary name, so that a failure can put it back
            // and a SIGKILL in between leaves a recognisable leftover.
            let aside = registry::temporary_name(
                target.parent().unwrap_or(Path::new(".")),
                target.file_name().unwrap_or_default(),
            );
            fs::rename(target, &aside).map_err(failed("set aside the previous"))?;
            if let Err(source) = fs::rename(path, target) {
                let _ = fs::rename(&aside, target);
                return Err(failed("move the finished directory to")(source));
            }
            live.forget(path);
            live.adopt(&aside);
            Ok(Some(aside))
        })?;
        self.moved = true;
        if let Some(aside) = aside {
            registry::remove(&aside);
        }
        Ok(())
    }
}

impl Drop for StagedDirectory {
    fn drop(&mut self) {
        if !self.moved {
            registry::remove(&self.path);
        }
    }
}

/// The refusal of the destination `shown` for `problem`.
fn refused(shown: &Path, problem: String) -> OutputError {
    OutputError {
        path: shown.to_owned(),
        action: "write the directory",
        error: io::Error::new(io::ErrorKind::AlreadyExists, problem),
    }
}

/// The names in `directory`.
fn names(directory: &Path) -> io::Result<Vec<OsString>> {
    fs::read_dir(directory)?
        .map(|entry| entry.map(|e| e.file_name()))
        .collect()
}

/// Why the existing directory `target` may not be replaced, if it may not: it is neither
/// empty nor a previous output (the `marker` file and regular files only, each among
/// `new_names` when those are known).
fn replaceable(target: &Path, marker: &str, new_names: Option<&[OsString]>) -> Result<(), String> {
    let entries = fs::read_dir(target).map_err(|e| format!("cannot list it: {e}"))?;
    let mut has_marker = false;
    let mut empty = true;
    for entry in entries {
        let entry = entry.map_err(|e| format!("cannot list it: {e}"))?;
        empty = false;
        let name = entry.file_name();
        let regular = entry.file_type().is_ok_and(|t| t.is_file());
        let known = new_names.is_none_or(|names| names.contains(&name));
        if !regular || !known {
            return Err(format!(
                "it exists and holds `{}`, which this output would not replace; hcm \
                 replaces only an empty directory or a previous output of the same command \
                 (remove it or choose another --out)",
                name.to_string_lossy()
            ));
        }
        has_marker |= name == marker;
    }
    if empty || has_marker {
        Ok(())
    } else {
        Err(format!(
            "it exists, is not empty and holds no `{marker}`, so it is no previous output \
             of this command; hcm replaces only an empty directory or a previous output \
             (remove it or choose another --out)"
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::tests::entries;

    #[test]
    fn a_directory_appears_whole_at_commit_and_not_before() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("results").join("ball");
        let staged = StagedDirectory::create(&out, "results.json").unwrap();
        fs::write(staged.path().join("results.json"), "{}").unwrap();
        assert!(
            !dir.path().join("results").exists(),
            "no parent before commit"
        );
        staged.commit().unwrap();
        assert_eq!(entries(&out), ["results.json"]);
        assert_eq!(entries(dir.path()), ["results"]);
        // Dropped before commit: nothing is left.
        let staged = StagedDirectory::create(&dir.path().join("other"), "results.json").unwrap();
        fs::write(staged.path().join("a"), "x").unwrap();
        drop(staged);
        assert_eq!(entries(dir.path()), ["results"]);
    }

    #[test]
    fn a_previous_output_is_replaced_and_anything_else_refused() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("ball");
        fs::create_dir(&out).unwrap();
        fs::write(out.join("results.json"), "old").unwrap();
        fs::write(out.join("report.md"), "old").unwrap();
        let staged = StagedDirectory::create(&out, "results.json").unwrap();
        for name in ["results.json", "report.md", "s1.csv"] {
            fs::write(staged.path().join(name), "new").unwrap();
        }
        staged.commit().unwrap();
        assert_eq!(entries(&out), ["report.md", "results.json", "s1.csv"]);
        assert_eq!(fs::read_to_string(out.join("report.md")).unwrap(), "new");
        assert_eq!(entries(dir.path()), ["ball"], "the old one removed");

        // A file the new output lacks: refused at commit, the old output untouched.
        fs::write(out.join("notes.txt"), "mine").unwrap();
        let staged = StagedDirectory::create(&out, "results.json").unwrap();
        for name in ["results.json", "report.md", "s1.csv"] {
            fs::write(staged.path().join(name), "newer").unwrap();
        }
        let error = staged.commit().unwrap_err().to_string();
        assert!(
            error.contains("ball") && error.contains("notes.txt"),
            "{error}"
        );
        assert_eq!(fs::read_to_string(out.join("notes.txt")).unwrap(), "mine");
        assert_eq!(entries(dir.path()), ["ball"]);

        // No marker: refused before any work.
        let other = dir.path().join("home");
        fs::create_dir(&other).unwrap();
        fs::write(other.join("thesis.tex"), "mine").unwrap();
        let error = StagedDirectory::create(&other, "results.json")
            .err()
            .unwrap()
            .to_string();
        assert!(
            error.contains("home") && error.contains("results.json"),
            "{error}"
        );
        assert_eq!(entries(dir.path()), ["ball", "home"]);
    }
}
