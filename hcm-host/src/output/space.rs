//! Free disk space at a destination, checked before long work that writes a lot.

use std::path::Path;

/// The output would not fit on the file system of its destination.
#[derive(Debug, thiserror::Error)]
#[error(
    "not enough disk space for `{}`: the output needs about {}, and {} are free there",
    path.display(), bytes(*needed), bytes(*available)
)]
pub struct NoSpace {
    /// The destination.
    pub(crate) path: std::path::PathBuf,
    /// Bytes the output needs (an estimate).
    pub(crate) needed: u64,
    /// Bytes free to an unprivileged user on the destination's file system.
    pub(crate) available: u64,
}

/// Bytes free to an unprivileged user on the file system that holds `path` (or its
/// nearest existing ancestor, for a path not yet created); None where that cannot be
/// told (not Unix, or the file system does not say).
pub fn available_space(path: &Path) -> Option<u64> {
    let mut at = path;
    while !at.exists() {
        at = match at.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent,
            _ => Path::new("."),
        };
    }
    free_bytes(at)
}

#[cfg(unix)]
fn free_bytes(path: &Path) -> Option<u64> {
    let stat = rustix::fs::statvfs(path).ok()?;
    Some(stat.f_bavail.saturating_mul(stat.f_frsize))
}

#[cfg(not(unix))]
fn free_bytes(_: &Path) -> Option<u64> {
    None
}

/// Refuses an output of about `needed` bytes at `path` when its file system has less
/// free (unknown free space is not refused).
pub fn ensure_space(path: &Path, needed: u64) -> Result<(), NoSpace> {
    match available_space(path) {
        Some(available) if available < needed => Err(NoSpace {
            path: path.to_owned(),
            needed,
            available,
        }),
        _ => Ok(()),
    }
}

/// A byte count for people: `812 B`, `70.3 kB`, `14.0 GB`, `70.0 TB` (powers of 1000).
pub fn bytes(count: u64) -> String {
    const UNITS: [&str; 6] = ["kB", "MB", "GB", "TB", "PB", "EB"];
    if count < 1000 {
        return format!("{count} B");
    }
    let mut value = count as f64 / 1000.0;
    let mut unit = 0;
    while value >= 999.95 && unit + 1 < UNITS.len() {
        value /= 1000.0;
        unit += 1;
    }
    format!("{value:.1} {}", UNITS[unit])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_counts_read_in_round_units() {
        assert_eq!(bytes(812), "812 B");
        assert_eq!(bytes(70_300), "70.3 kB");
        assert_eq!(bytes(999_999), "1.0 MB");
        assert_eq!(bytes(14_000_000_000), "14.0 GB");
        assert_eq!(bytes(u64::MAX), "18.4 EB");
    }

    #[cfg(unix)]
    #[test]
    fn the_free_space_of_a_path_not_yet_made_is_its_ancestors() {
        let dir = std::env::temp_dir();
        // Other processes write to the same disk between the two reads: the same file
        // system, so the same free space up to what they wrote meanwhile (≤ 1 GiB here).
        let free = available_space(&dir).unwrap() as i128;
        let through_ancestor = available_space(&dir.join("no/such/dir/data.csv")).unwrap() as i128;
        assert!(
            (through_ancestor - free).abs() <= 1 << 30,
            "{through_ancestor} vs {free}"
        );
        assert!(ensure_space(&dir.join("data.csv"), u64::MAX).is_err());
        let error = ensure_space(&dir.join("data.csv"), u64::MAX).unwrap_err();
        assert!(error.to_string().contains("data.csv") && error.to_string().contains("free"));
    }
}
