//! The Python package's build reuses the tests' build: Cargo resolves the features of
//! hcm-py's dependencies alone when maturin builds it, and of the whole workspace when
//! `cargo test --workspace` does; every package both builds share must get the same
//! features, or CI compiles it (and hcm-host after it) twice (hcm-py/Cargo.toml's
//! "workspace hack" lines keep them alike).

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

/// `package version` → its enabled features, as `cargo tree -e features` lists them
/// for `selection` (`-p hcm-py` or `--workspace`).
fn features(selection: &[&str]) -> BTreeMap<String, Vec<String>> {
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let output = Command::new(cargo)
        .args([
            "tree",
            "--offline",
            "-e",
            "no-dev",
            "--prefix",
            "none",
            "-f",
            "{p} {f}",
        ])
        .args(selection)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")))
        .output()
        .expect("cargo tree runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let mut found = BTreeMap::new();
    for line in String::from_utf8_lossy(&output.stdout).lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.len() < 2 || words[1].starts_with('(') {
            continue;
        }
        let key = format!("{} {}", words[0], words[1]);
        // `name version [(path)] [features]`; a repeated package ends in `(*)`.
        let enabled = match words[2..].iter().rfind(|w| !w.starts_with('(')) {
            Some(list) => list.split(',').map(str::to_owned).collect(),
            None => Vec::new(),
        };
        found.entry(key).or_insert(enabled);
    }
    found
}

#[test]
fn the_python_build_resolves_the_features_the_tests_build_does() {
    let python = features(&["-p", "hcm-py"]);
    let workspace = features(&["--workspace"]);
    assert!(python.len() > 50, "{} packages under hcm-py", python.len());
    let differing: Vec<String> = python
        .iter()
        .filter(|(package, _)| !package.starts_with("hcm-py "))
        .filter_map(|(package, enabled)| {
            let other = workspace.get(package)?;
            (other != enabled)
                .then(|| format!("{package}: hcm-py {enabled:?}, workspace {other:?}"))
        })
        .collect();
    assert!(
        differing.is_empty(),
        "enable the workspace's features in hcm-py/Cargo.toml:\n{}",
        differing.join("\n")
    );
}
