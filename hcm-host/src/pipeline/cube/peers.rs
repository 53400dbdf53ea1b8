//! The tosses' comparison with their peers (`hcm reproduce cube-toss --peers`,
//! `hcm reproduce elbow-toss --peers`): MuJoCo and PyBullet fitted and scored beside hcm
//! on the same tosses, by the repository's `benches/peers/peers.py` (the cube) or
//! `benches/peers/elbow.py` (the elbow: both links, the same URDF) in their own virtual
//! environment (pinned versions; `bash benches/peers/run.sh OUT --quick` installs them).
//! Its table joins the report; hcm itself never needs Python. The script's own progress
//! goes to stderr.

use super::{CubeReproduction, CubeSettings};
use anyhow::Context;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The cube's script, relative to the repository's root (the working directory).
const SCRIPT: &str = "benches/peers/peers.py";

/// The elbow's script (a mechanism: both links on the URDF's hinge).
const ELBOW_SCRIPT: &str = "benches/peers/elbow.py";

/// Its environment's interpreter, relative to the same root.
const VENV_PYTHON: &str = "benches/peers/.venv/bin/python";

/// The peers' interpreter and script, found before any work.
pub struct Peers {
    python: PathBuf,
    script: PathBuf,
}

/// The peers' script of the example `name` (`cube-toss`, `elbow-toss`).
fn script_of(name: &str) -> &'static str {
    match name {
        "elbow-toss" => ELBOW_SCRIPT,
        _ => SCRIPT,
    }
}

impl Peers {
    /// The interpreter (`HCM_PEERS_PYTHON`, else `benches/peers/.venv/bin/python`) and
    /// example `name`'s script, or what to do to have them.
    pub fn locate(name: &str) -> anyhow::Result<Peers> {
        let script = script_of(name);
        anyhow::ensure!(
            Path::new(script).is_file(),
            "--peers runs {script}, which is not here: run hcm from the repository's root"
        );
        let script = PathBuf::from(script);
        let python = std::env::var_os("HCM_PEERS_PYTHON")
            .map_or_else(|| PathBuf::from(VENV_PYTHON), PathBuf::from);
        anyhow::ensure!(
            python.is_file(),
            "--peers needs MuJoCo and PyBullet in {VENV_PYTHON}, which does not exist: install \
             them once with `bash benches/peers/run.sh peers-out --quick` (or set \
             HCM_PEERS_PYTHON to a Python with benches/peers/requirements.txt's pins)"
        );
        Ok(Peers { python, script })
    }

    /// What runs: the interpreter and the script, for a status line.
    pub fn command_line(&self) -> String {
        format!("{} {}", self.python.display(), self.script.display())
    }

    /// Writes the peers' inputs into `dir/peers/`, runs the script there (its progress
    /// on stderr) and returns its table, a section of the report.
    pub fn run(
        &self,
        dir: &Path,
        reproduction: &CubeReproduction,
        settings: &CubeSettings,
    ) -> anyhow::Result<String> {
        let out = dir.join("peers");
        std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
        for artifact in reproduction.peer_inputs()? {
            artifact.write(&out)?;
        }
        let mut command = Command::new(&self.python);
        command
            .arg(&self.script)
            .arg("--data")
            .arg(&settings.data)
            .arg("--scenario-scores")
            .arg(out.join("scores_scenario.csv"))
            .arg("--scenario-predicted")
            .arg(out.join("predicted_scenario.csv"))
            .arg("--fitted-scores")
            .arg(out.join("scores_fitted.csv"))
            .arg("--out")
            .arg(&out)
            .stdout(Stdio::from(std::io::stderr()));
        if let Some(first) = settings.first {
            command.arg("--first").arg(first.to_string());
        }
        if self.script == Path::new(ELBOW_SCRIPT) {
            // The peers fit the very tosses hcm's fit saw.
            command
                .arg("--fit-stride")
                .arg(settings.fit_stride.to_string());
        }
        let script = self.script.display();
        let status = (command.status())
            .with_context(|| format!("starting {} {script}", self.python.display()))?;
        anyhow::ensure!(
            status.success(),
            "{script} failed ({status}); its messages are above"
        );
        let table = std::fs::read_to_string(out.join("peers.md"))
            .with_context(|| format!("reading {}", out.join("peers.md").display()))?;
        // One level down: a section of the report, not a document of its own.
        Ok(table.replacen("# ", "## Peers: ", 1))
    }
}
