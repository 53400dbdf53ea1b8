//! `hcm reproduce cube-toss`: the library's cube pipeline
//! ([`hcm_host::pipeline::cube`]) with progress bars, its physics file, data, report,
//! `results.json` and figures written to the output directory as one unit.

use super::progress_bar;
use super::reproduce::write_figures;
use hcm_host::identify::motion::fitted_physics;
use hcm_host::output::{write_bytes, StagedDirectory};
use hcm_host::pipeline::cube::{reproduce_cube, CubeProgress, CubeReproduction, CubeSettings};
use hcm_host::pipeline::StageTiming;
use hcm_host::toss::{predicted_dataset, TossSetup};
use indicatif::ProgressBar;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};
use std::time::Instant;

/// The options `hcm reproduce` passes on for the cube toss.
pub struct CubeArgs {
    pub out: PathBuf,
    pub data: Option<PathBuf>,
    pub first: Option<usize>,
    pub seed: u64,
    pub scenario: Option<PathBuf>,
    pub overrides: Vec<String>,
    pub generations: Option<usize>,
    pub population: Option<usize>,
    pub polish: Option<usize>,
    pub no_diagnosis: bool,
}

pub fn run(args: CubeArgs) -> anyhow::Result<()> {
    let data = args.data.ok_or_else(|| {
        anyhow::anyhow!(
            "`hcm reproduce cube-toss` needs --data: the filmed tosses, e.g. \
             data/contactnets-cube/tosses.csv of the source"
        )
    })?;
    if let Some(first) = args.first {
        anyhow::ensure!(
            first >= 6,
            "--first {first}: give at least 6 runs (3 per part)"
        );
    }
    let shipped = CubeSettings::shipped(&data);
    let settings = CubeSettings {
        first: args.first,
        scenario: args.scenario,
        overrides: args.overrides,
        seed: args.seed,
        population: args.population.unwrap_or(shipped.population),
        generations: args.generations.unwrap_or(shipped.generations),
        polish: args.polish.unwrap_or(shipped.polish),
        diagnose: !args.no_diagnosis,
        ..shipped
    };
    let staged = StagedDirectory::create(&args.out, "results.json")?;
    let out = staged.path();
    let mut reproduction = reproduce_cube(&settings, &Bars::default())?;
    let clock = Instant::now();
    write_files(&reproduction, &settings, out)?;
    let results = &mut reproduction.results;
    results.timings.push(StageTiming {
        stage: "write files".into(),
        seconds: clock.elapsed().as_secs_f64(),
    });
    let json = serde_json::to_string_pretty(results)?;
    write_bytes(&out.join("results.json"), json.as_bytes())?;
    let report = results.markdown();
    write_bytes(&out.join("report.md"), report.as_bytes())?;
    staged.commit()?;
    print!("{report}");
    Ok(())
}

/// physics.toml, the two parts of the split, the fitted model's held-out predictions
/// and the figures.
fn write_files(r: &CubeReproduction, settings: &CubeSettings, out: &Path) -> anyhow::Result<()> {
    let method = "ga + Nelder–Mead on toss replays (motion only), hcm reproduce cube-toss";
    let data = settings.data.display().to_string();
    let runs = r.training.runs.len();
    fitted_physics(&r.fit, r.contact, &r.sets, method, &data, runs).write(
        &out.join("physics.toml"),
        &format!(
            "contact of scenario `{}` fitted to tosses by hcm reproduce cube-toss",
            r.scenario.name
        ),
    )?;
    r.training.write(&out.join("training.csv"))?;
    r.held_out.write(&out.join("held_out.csv"))?;
    let body = TossSetup::new(&r.fit.model)?.name;
    predicted_dataset(&r.predicted.held_out_fitted, &body)
        .write(&out.join("predicted_held_out.csv"))?;
    write_figures(&r.figures, out)
}

/// One progress bar per stage on standard error (hidden when it is not a terminal).
#[derive(Default)]
struct Bars(Mutex<Option<ProgressBar>>);

impl Bars {
    fn bar(&self) -> MutexGuard<'_, Option<ProgressBar>> {
        // A panic while drawing leaves the bar usable.
        self.0
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner())
    }
}

impl CubeProgress for Bars {
    fn begin(&self, stage: &'static str, steps: u64) {
        *self.bar() = Some(progress_bar(steps, stage));
    }

    fn advance(&self, done: u64, steps: u64) {
        if let Some(bar) = self.bar().as_ref() {
            bar.set_length(steps);
            bar.set_position(done);
        }
    }

    fn end(&self) {
        if let Some(bar) = self.bar().take() {
            bar.finish_and_clear();
        }
    }
}
