//! What a reproduction writes, and the one writer of it: every example's run lists its
//! files ([`Artifact`]) and its report, and [`write_reproduction`] writes them into an
//! output directory the same way for every example — the files, then `results.json`
//! (with the writing's own time) and `report.md`.

use super::StageTiming;
use crate::dataset::Dataset;
use crate::figure::NamedFigure;
use crate::identify::Physics;
use crate::output::write_bytes;
use crate::replay::{write_scores, TossEvaluation};
use crate::train::TrainedResidual;
use anyhow::Context;
use std::borrow::Cow;
use std::path::Path;
use std::time::Instant;

/// One file (or, for figures, a set of files) of a reproduction's output directory.
pub enum Artifact<'a> {
    /// A data set as CSV, under its file name.
    Data(&'static str, Cow<'a, Dataset>),
    /// A physics file, under its file name, with its comment line.
    Physics(&'static str, Physics, String),
    /// A trained residual network as JSON, under its file name.
    Residual(&'static str, &'a TrainedResidual),
    /// Bytes as they are (a weights blob), under their file name.
    Bytes(&'static str, &'a [u8]),
    /// Each figure as `STEM.svg` and `STEM.png`.
    Figures(&'a [NamedFigure]),
    /// Each toss's scores and initial state as CSV (`hcm predict --scores`'s file),
    /// under its file name.
    Scores(&'static str, Vec<TossEvaluation>),
}

impl Artifact<'_> {
    /// Writes the file(s) into `dir`, each atomically.
    pub fn write(&self, dir: &Path) -> anyhow::Result<()> {
        match self {
            Artifact::Data(name, data) => data.write(&dir.join(name))?,
            Artifact::Physics(name, physics, comment) => physics.write(&dir.join(name), comment)?,
            Artifact::Residual(name, residual) => residual.write(&dir.join(name))?,
            Artifact::Bytes(name, bytes) => write_bytes(&dir.join(name), bytes)?,
            Artifact::Figures(figures) => write_figures(figures, dir)?,
            Artifact::Scores(name, evaluations) => {
                write_scores(&dir.join(name), evaluations, None)?
            }
        }
        Ok(())
    }
}

/// Each figure as `STEM.svg` and `STEM.png` in `dir`.
pub fn write_figures(figures: &[NamedFigure], dir: &Path) -> anyhow::Result<()> {
    for named in figures {
        let (svg, png) = (format!("{}.svg", named.stem), format!("{}.png", named.stem));
        write_bytes(&dir.join(&svg), named.figure.svg().as_bytes())?;
        let bytes = named
            .figure
            .png()
            .with_context(|| format!("drawing {png}"))?;
        write_bytes(&dir.join(&png), &bytes)?;
    }
    Ok(())
}

/// A finished reproduction: its files, its results and its report.
pub trait Reproduced {
    /// The files it writes beside `results.json` and `report.md`.
    fn artifacts(&self) -> anyhow::Result<Vec<Artifact<'_>>>;
    /// Adds a stage's wall-clock time to its results.
    fn record(&mut self, timing: StageTiming);
    /// `results.json`'s text.
    fn results_json(&self) -> anyhow::Result<String>;
    /// `report.md`'s text.
    fn report(&self) -> String;
}

/// Writes `reproduction` into `dir`: its artifacts, then `results.json` (timing the
/// writing as the stage "write files") and `report.md`. Returns the report.
pub fn write_reproduction(reproduction: &mut dyn Reproduced, dir: &Path) -> anyhow::Result<String> {
    let clock = Instant::now();
    for artifact in reproduction.artifacts()? {
        artifact.write(dir)?;
    }
    reproduction.record(StageTiming {
        stage: "write files".into(),
        seconds: clock.elapsed().as_secs_f64(),
    });
    write_bytes(
        &dir.join("results.json"),
        reproduction.results_json()?.as_bytes(),
    )?;
    let report = reproduction.report();
    write_bytes(&dir.join("report.md"), report.as_bytes())?;
    Ok(report)
}
