//! The command line's files checked before any work, for every command at once: an
//! output that is one of the command's inputs (writing it would destroy what is being
//! read) or two outputs that are one file are refused, naming both options. (An output
//! that is a device, a pipe or a socket is refused by `hcm_host::output` itself.) An
//! existing output of the other kind — a file where a directory is written (the
//! options marked `ValueHint::DirPath`), a directory where a file is — is refused too,
//! before a long run finds it at its end. A directory option given a path ending in
//! `.json` writes that one file (`hcm diagnose` from poses writes only its diagnosis).

use clap::ArgMatches;
use hcm_host::output::check_kind;
use std::path::{Path, PathBuf};

/// The argument ids of every command that name a file or directory it writes.
const OUTPUTS: [&str; 6] = [
    "out",
    "figures",
    "scores",
    "faces",
    "held_out",
    "scenario_out",
];

/// An option's name as typed (`scenario_out` → `--scenario-out`).
fn option(id: &str) -> String {
    format!("--{}", id.replace('_', "-"))
}

/// `path` resolved through links and `..`, if it exists.
fn resolved(path: &Path) -> Option<PathBuf> {
    std::fs::canonicalize(path).ok()
}

/// Where `path` is or would be created: resolved if it exists, else its resolved
/// folder joined with its name (else as given).
fn place(path: &Path) -> PathBuf {
    resolved(path)
        .or_else(|| {
            let folder = match path.parent() {
                Some(p) if !p.as_os_str().is_empty() => p,
                _ => Path::new("."),
            };
            Some(resolved(folder)?.join(path.file_name()?))
        })
        .unwrap_or_else(|| path.to_owned())
}

/// Refuses an existing output `path` of option `id` of the other kind than the
/// option writes (`directory`: whether it writes a directory).
fn same_kind(id: &str, path: &Path, directory: bool) -> anyhow::Result<()> {
    check_kind(&option(id), path, directory).map_err(anyhow::Error::msg)
}

/// Checks the subcommand's output arguments (`command` defines them) against their
/// kind, its inputs and each other.
pub fn check(command: &clap::Command, matches: &ArgMatches) -> anyhow::Result<()> {
    let Some((name, sub)) = matches.subcommand() else {
        return Ok(());
    };
    let writes_directory = |id: &str| {
        command
            .find_subcommand(name)
            .and_then(|c| c.get_arguments().find(|a| a.get_id() == id))
            .is_some_and(|a| a.get_value_hint() == clap::ValueHint::DirPath)
    };
    let (mut inputs, mut outputs) = (Vec::new(), Vec::new());
    for id in sub.ids() {
        let id = id.as_str();
        let Ok(Some(values)) = sub.try_get_raw(id) else {
            continue;
        };
        for value in values {
            let path = Path::new(value);
            if OUTPUTS.contains(&id) {
                let json = path.extension().is_some_and(|e| e == "json");
                same_kind(id, path, writes_directory(id) && !json)?;
                outputs.push((id, path));
            } else if path.is_file() {
                inputs.push((id, path));
            }
        }
    }
    for (k, (id, out)) in outputs.iter().enumerate() {
        let target = place(out);
        for (other_id, other) in &outputs[k + 1..] {
            if place(other) == target {
                anyhow::bail!(
                    "{} and {} name the same file {}: give each its own path",
                    option(id),
                    option(other_id),
                    out.display()
                );
            }
        }
        for (input_id, input) in &inputs {
            if resolved(input).as_ref() == Some(&target) {
                anyhow::bail!(
                    "{} {} is the file {} reads: writing it would destroy the input; give \
                     another path",
                    option(id),
                    out.display(),
                    option(input_id)
                );
            }
        }
    }
    Ok(())
}
