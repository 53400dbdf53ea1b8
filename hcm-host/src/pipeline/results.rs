//! The results of a reproduction: every table of the report as typed values, the
//! content of `results.json` (keys documented in the README, "results.json").

use super::{Evaluation, Example, Pm2, ReproduceSettings, Setup, Trained};
use crate::evaluate::{ConditionTable, IndicatorErrors};
use crate::export::Blobs;
use serde::Serialize;

/// Every table of the report.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReproduceResults {
    /// Which example.
    pub(crate) example: Example,
    /// Seed of the experiment, the split, the GA and the training.
    pub(crate) seed: u64,
    /// Runs per condition generated.
    pub(crate) runs_per_condition: usize,
    /// The scenario file, as given.
    pub(crate) scenario: String,
    /// Overrides applied to it (`key=value`).
    pub(crate) overrides: Vec<String>,
    /// PM2: the law and its identified parameters.
    pub(crate) pm2: Pm2Summary,
    /// The paper's table on S2: the S2 means, their standard errors, and the rows of
    /// PM2, HCM and HCM int8 (indicators and Eq 20 errors).
    pub(crate) validation: ConditionTable,
    /// The paper's own errors, Tables 5 and 10.
    pub(crate) paper: PaperErrors,
    /// How the residual network trained.
    pub(crate) residual: ResidualSummary,
    /// The exported blobs, f32 then int8.
    pub(crate) blobs: Vec<BlobSummary>,
    /// Wall-clock time per stage, in order.
    pub(crate) timings: Vec<StageTiming>,
    /// The figure files, SVG and PNG.
    pub(crate) figures: Vec<String>,
    /// The experiment in words, for the report (not in results.json).
    #[serde(skip)]
    pub(crate) setup: Setup,
}

/// PM2 as identified.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Pm2Summary {
    /// Catalogue name of the law (`lankarani_nikravesh`).
    pub(crate) law: String,
    /// How it was identified (`lsq`, `ga (curve) + LM`, … as the fit record says).
    pub(crate) method: String,
    /// Its parameters in the catalogue's order and units (SI: k in N/m^n, n –, ce –).
    pub(crate) parameters: Vec<NamedValue>,
}

/// A named number.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct NamedValue {
    /// Its name.
    pub(crate) name: String,
    /// Its value (SI).
    pub(crate) value: f64,
}

/// The paper's errors (–, fractions: 0.0158 = 1.58 %).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PaperErrors {
    /// PM2's.
    pub(crate) pm2: IndicatorErrors,
    /// The HCM's.
    pub(crate) hcm: IndicatorErrors,
}

/// The residual network's training and its int8 twin's fine-tuning.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ResidualSummary {
    /// Training rows (S1's force samples inside the contact).
    pub(crate) training_samples: usize,
    /// Epochs run.
    pub(crate) epochs: usize,
    /// Epoch (1-based) whose weights were kept.
    pub(crate) best_epoch: usize,
    /// RMS error of the network on its validation rows (N).
    pub(crate) validation_rms: f64,
    /// RMS of the plainly rounded int8 network against the f32 one (N).
    pub(crate) int8_rounded_rms: f64,
    /// RMS of the fine-tuned int8 twin against the f32 network (N).
    pub(crate) int8_tuned_rms: f64,
    /// Fine-tuning epochs of the twin.
    pub(crate) int8_epochs: usize,
}

/// One exported blob.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BlobSummary {
    /// Weight storage, `f32` or `int8`.
    pub(crate) weights: String,
    /// Size of the blob (bytes).
    pub(crate) bytes: usize,
    /// Worst relative |core − host| over the envelope grid (–).
    pub(crate) round_trip_error: f64,
}

/// The time one stage took.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StageTiming {
    /// Stage, e.g. `identify PM2`.
    pub(crate) stage: String,
    /// Wall-clock time (s).
    pub(crate) seconds: f64,
}

/// Wall-clock time per stage, in the order the stages ran.
#[derive(Default)]
pub struct StageClock(pub Vec<StageTiming>);

impl StageClock {
    /// Runs `stage`, records how long it took under `name`, and returns its value.
    pub fn time<T>(&mut self, name: &str, stage: impl FnOnce() -> T) -> T {
        let clock = std::time::Instant::now();
        let value = stage();
        self.0.push(StageTiming {
            stage: name.to_owned(),
            seconds: clock.elapsed().as_secs_f64(),
        });
        value
    }
}

impl ReproduceResults {
    /// The results of the stages' values; `setup` describes the experiment.
    pub(crate) fn gather(
        settings: &ReproduceSettings,
        setup: Setup,
        pm2: &Pm2,
        trained: &Trained,
        blobs: &Blobs,
        evaluation: &Evaluation,
        timings: Vec<StageTiming>,
    ) -> Self {
        let found = &pm2.identification;
        let parameters = found
            .law
            .named()
            .map(|(n, v)| NamedValue {
                name: n.to_string(),
                value: v,
            })
            .collect();
        let blobs = [&blobs.f32, &blobs.int8].map(|b| BlobSummary {
            weights: format!("{:?}", b.quantisation).to_lowercase(),
            bytes: b.bytes.len(),
            round_trip_error: b.round_trip_error,
        });
        ReproduceResults {
            example: settings.example,
            seed: settings.seed,
            runs_per_condition: settings.runs,
            scenario: settings.scenario.label().display().to_string(),
            overrides: settings.scenario.overrides.clone(),
            pm2: Pm2Summary {
                law: found.law.name().to_owned(),
                method: found.fit.method.clone(),
                parameters,
            },
            validation: evaluation.table.clone(),
            paper: settings.example.paper(),
            residual: ResidualSummary {
                training_samples: trained.rows,
                epochs: trained.report.epochs,
                best_epoch: trained.report.best_epoch,
                validation_rms: trained.report.validation_loss.sqrt(),
                int8_rounded_rms: trained.int8.rounded_rms,
                int8_tuned_rms: trained.int8.tuned_rms,
                int8_epochs: trained.int8.epochs,
            },
            blobs: blobs.into(),
            timings,
            figures: evaluation
                .figures
                .iter()
                .flat_map(|f| [format!("{}.svg", f.stem), format!("{}.png", f.stem)])
                .collect(),
            setup,
        }
    }

    /// The content of `results.json` (NaN, where a model failed, as `null`).
    pub fn json(&self) -> Result<String, serde_json::Error> {
        serde_json::to_string_pretty(self)
    }
}
