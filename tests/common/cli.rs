//! The `hcm` binary for end-to-end tests: a fixture that runs it in a temporary
//! directory, asserts how it ended and hands back what it printed.
//!
//! Cargo tells only the integration tests of the package that owns a binary where it is
//! (`CARGO_BIN_EXE_<name>`), and builds it only for them. These tests live in the root
//! package, so the first call of a test process asks Cargo to build `hcm` (a no-op when it
//! is fresh) and takes the path from Cargo's own report: the binary is never stale and is
//! found under any target directory and profile.

use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;
use tempfile::TempDir;

/// The `hcm` executable of this build, built once per test process.
pub fn hcm_exe() -> &'static Path {
    static EXE: OnceLock<PathBuf> = OnceLock::new();
    EXE.get_or_init(build_hcm)
}

/// Builds `hcm` with the profile these tests were built with, and returns the executable
/// Cargo reports. For the whole workspace, so that the features match the test build's
/// and its artifacts serve (a build of hcm-host alone would build its dependencies anew).
fn build_hcm() -> PathBuf {
    // Cargo sets CARGO for the processes it runs; the fallback serves a test run by hand.
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let mut build = Command::new(cargo);
    // From the workspace root, so that Cargo reads the same configuration as the build
    // that made this test.
    build.current_dir(env!("CARGO_MANIFEST_DIR")).args([
        "build",
        "--workspace",
        "--bin",
        "hcm",
        "--message-format=json-render-diagnostics",
        "--profile",
        test_profile(),
    ]);
    let output = build.output().expect("cargo runs");
    assert!(
        output.status.success(),
        "building hcm failed:\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    String::from_utf8_lossy(&output.stdout)
        .lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .filter(|message| message["reason"] == "compiler-artifact")
        .filter(|message| message["target"]["name"] == "hcm")
        .find_map(|message| message["executable"].as_str().map(PathBuf::from))
        .expect("cargo reports the hcm executable")
}

/// The Cargo profile of this test executable, from the folder it was built in
/// (`<target>/<profile folder>/deps/<test>`): `debug` holds the dev and test profiles,
/// `release` the release and bench profiles, any other folder its own profile.
fn test_profile() -> &'static str {
    static PROFILE: OnceLock<String> = OnceLock::new();
    PROFILE.get_or_init(|| {
        let exe = std::env::current_exe().expect("the test executable's path");
        let folder = exe
            .parent()
            .and_then(Path::parent)
            .and_then(Path::file_name)
            .and_then(OsStr::to_str)
            .expect("the test executable lies in <target>/<profile>/deps");
        match folder {
            "debug" => "dev".to_owned(),
            other => other.to_owned(),
        }
    })
}

/// A temporary working directory for `hcm` runs, removed when dropped.
pub struct Hcm {
    dir: TempDir,
}

impl Default for Hcm {
    fn default() -> Self {
        Self::new()
    }
}

impl Hcm {
    /// A fresh, empty temporary directory to run `hcm` in.
    pub fn new() -> Self {
        Hcm {
            dir: tempfile::tempdir().expect("a temporary directory"),
        }
    }

    /// The temporary directory.
    pub fn dir(&self) -> &Path {
        self.dir.path()
    }

    /// The path of `name` in the temporary directory.
    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// `hcm simulate` of `scenario` with each of `sets` as a `--set`, which must fail:
    /// its error message, nothing written to its `--out`.
    pub fn simulate_refused(&self, scenario: &Path, sets: &[&str]) -> String {
        let mut call = (self.run("simulate"))
            .opt("--scenario", scenario)
            .opt("--out", self.path("out.csv"));
        for set in sets {
            call = call.opt("--set", set);
        }
        let message = call.fails();
        assert!(
            !self.path("out.csv").exists(),
            "nothing written on an error"
        );
        message
    }

    /// An `hcm subcommand` call, to be given arguments and run.
    pub fn run(&self, subcommand: &str) -> Call {
        let mut command = Command::new(hcm_exe());
        command.current_dir(self.dir.path()).arg(subcommand);
        Call { command }
    }
}

/// One `hcm` call being assembled.
pub struct Call {
    command: Command,
}

impl Call {
    /// A positional argument or a flag without value (`--json`).
    pub fn arg(mut self, arg: impl AsRef<OsStr>) -> Self {
        self.command.arg(arg);
        self
    }

    /// An environment variable of the call (`RAYON_NUM_THREADS`, `1`).
    pub fn env(mut self, key: &str, value: &str) -> Self {
        self.command.env(key, value);
        self
    }

    /// An option and its value (`--out`, path).
    pub fn opt(mut self, option: &str, value: impl AsRef<OsStr>) -> Self {
        self.command.arg(option).arg(value);
        self
    }

    /// Runs the call, asserts that it succeeded (showing its standard error otherwise),
    /// and returns its standard output.
    pub fn ok(self) -> String {
        let (line, output) = self.output();
        assert!(
            output.status.success(),
            "{line} failed:\n{}",
            String::from_utf8_lossy(&output.stderr)
        );
        String::from_utf8_lossy(&output.stdout).into_owned()
    }

    /// Runs the call, asserts that it failed (showing its output otherwise), and returns
    /// its standard error.
    pub fn fails(self) -> String {
        let (line, output) = self.output();
        assert!(
            !output.status.success(),
            "{line} succeeded:\n{}",
            String::from_utf8_lossy(&output.stdout)
        );
        String::from_utf8_lossy(&output.stderr).into_owned()
    }

    /// The command line, for messages, and what the run printed.
    fn output(mut self) -> (String, Output) {
        let line = std::iter::once(self.command.get_program())
            .chain(self.command.get_args())
            .map(|part| part.to_string_lossy())
            .collect::<Vec<_>>()
            .join(" ");
        let output = self.command.output().expect("hcm runs");
        (line, output)
    }
}
