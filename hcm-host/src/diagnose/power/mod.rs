//! The diagnosis's power study on a user's scenario: how often `hcm diagnose` names an
//! effect hidden in the scenario's data at a given strength, how often it names one
//! that was not hidden, how often a named parameter's 95 % interval holds the truth,
//! and how often it names anything with nothing hidden (false alarms).
//!
//! Each data set is what `hcm generate` would make of the scenario with one catalogued
//! effect hidden ([`Hiding`]): `runs` runs from its own seed, written as CSV and read
//! back; the diagnosis is `hcm diagnose`'s ([`diagnose`]), against the scenario's
//! own law as given or as `hcm identify --method lsq` fits it on the same runs. The
//! data sets are numbered effect by effect, strength by strength, seed by seed, then
//! the seeds with nothing hidden; data set k depends on (scenario, settings, k) only,
//! so a study splits into shards ([`crate::experiment::Shard`]) whose rows, in order,
//! are the whole study's byte for byte.

mod hiding;
mod rows;
mod summary;

pub use hiding::{Hiding, HIDDEN_HYSTERESIS_EXPONENT};
pub use rows::{read_rows, write_rows, PowerRow};
pub use summary::summary_markdown;

use super::{answer, contact_samples, diagnose, BaseFreedom, Candidate, DiagnoseSettings};
use crate::dataset::Dataset;
use crate::experiment::{conditions, generated, ExperimentError, Generation};
use crate::identify::{identify, IdentifyError, Method};
use crate::indicators::contact_history;
use crate::progress::{in_stage, Progress, Silent, Stage};
use crate::scenario::{Model, Scenario};
use rayon::prelude::*;
use std::ops::Range;
use std::sync::atomic::{AtomicU64, Ordering};

/// Why a power study could not be made.
#[derive(Debug, thiserror::Error)]
pub enum PowerError {
    /// The study's settings or scenario do not make one.
    #[error("{0}")]
    Setup(String),
    /// A data set could not be generated.
    #[error(transparent)]
    Experiment(#[from] ExperimentError),
    /// A data set could not be fitted or diagnosed.
    #[error("data set {data_set} ({what}): {source}")]
    Diagnose {
        /// Its index.
        data_set: usize,
        /// What it hides, and its seed.
        what: String,
        /// What failed.
        source: IdentifyError,
    },
    /// A file of rows does not read as this study's.
    #[error("{file}, line {line}: {what}")]
    Rows {
        /// The file.
        file: String,
        /// Its line (from 1).
        line: usize,
        /// What is wrong there.
        what: String,
    },
}

/// What each data set's diagnosis is judged against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PowerBase {
    /// The scenario's own law as given ([`BaseFreedom::Given`]): were the model right
    /// but for the hidden effect, would the diagnosis find it?
    Scenario,
    /// The scenario's law fitted by least squares on the same runs, every parameter
    /// `hcm identify` fits free ([`BaseFreedom::Fitted`]): a user's workflow.
    Fitted,
}

/// A power study's design.
#[derive(Clone, Debug, PartialEq)]
pub struct PowerSettings {
    /// Runs per data set.
    pub runs: usize,
    /// Data sets per hidden effect and strength, and with nothing hidden.
    pub seeds: u64,
    /// The first data set's seed: seeds `first_seed` to `first_seed + seeds − 1`.
    pub first_seed: u64,
    /// Strengths, as shares of the peak force (–), each in (0, 1].
    pub levels: Vec<f64>,
    /// The effects hidden, one at a time.
    pub effects: Vec<Candidate>,
    /// The base each diagnosis judges the data against.
    pub base: PowerBase,
    /// The diagnosis's own settings (contact, hold-out, seed, chance; its HCM is not
    /// trained: the answer does not depend on it).
    pub diagnose: DiagnoseSettings,
}

/// One data set of a study: what it hides, how strongly, from which seed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DataSetDesign {
    /// The hidden effect (None: nothing).
    pub hiding: Option<Hiding>,
    /// Its strength, a share of the peak force (–); 0 with nothing hidden.
    pub level: f64,
    /// The seed its runs are generated with.
    pub seed: u64,
}

/// A power study, its strengths scaled on the scenario's data with nothing hidden.
#[derive(Clone, Debug)]
pub struct PowerStudy {
    scenario: Scenario,
    base: Model,
    conditions: Vec<(String, Model)>,
    settings: PowerSettings,
    hidings: Vec<Hiding>,
    key: String,
}

impl PowerStudy {
    /// The study `settings` describe on `scenario` (a 1D scene: the line-force
    /// diagnosis). Generates the first seed's data set with nothing hidden to scale
    /// the strengths.
    pub fn new(scenario: &Scenario, settings: PowerSettings) -> Result<PowerStudy, PowerError> {
        check(&settings)?;
        let base = scenario
            .model()
            .map_err(|e| PowerError::Setup(e.to_string()))?;
        base.check_contact(settings.diagnose.contact)
            .map_err(PowerError::Setup)?;
        if base.is_rigid() {
            return Err(PowerError::Setup(format!(
                "scenario `{}` is a rigid (3D) scene: the power study runs the line-force \
                 (1D) diagnosis only; give a 1D scenario (a 3D study is not built yet)",
                scenario.name
            )));
        }
        let c = settings.diagnose.contact;
        let conditions = conditions(scenario)?;
        let plain = measured(&conditions, settings.runs, settings.first_seed)?;
        let samples = contact_samples(&base, &plain, c).map_err(|source| PowerError::Diagnose {
            data_set: 0,
            what: format!(
                "nothing hidden, seed {}, scaling the strengths",
                settings.first_seed
            ),
            source,
        })?;
        let direction = force_direction(&base, &plain, c)?;
        let law = &base.contacts[c].model.normal;
        let hidings = (settings.effects.iter())
            .map(|&e| Hiding::of(e, &samples, law, direction))
            .collect::<Result<Vec<_>, _>>()?;
        let key = key(scenario, &settings);
        Ok(PowerStudy {
            scenario: scenario.clone(),
            base,
            conditions,
            settings,
            hidings,
            key,
        })
    }

    /// The study's design.
    pub fn settings(&self) -> &PowerSettings {
        &self.settings
    }

    /// The scenario's name.
    pub fn scenario_name(&self) -> &str {
        &self.scenario.name
    }

    /// Each hidden effect's strength scale, in the order of the settings' effects.
    pub fn hidings(&self) -> &[Hiding] {
        &self.hidings
    }

    /// The line that names the study in its files: its scenario (name and a digest of
    /// its text) and every setting a row depends on.
    pub fn key(&self) -> &str {
        &self.key
    }

    /// Data sets in the study.
    pub fn len(&self) -> usize {
        let seeds = self.settings.seeds as usize;
        (self.hidings.len() * self.settings.levels.len() + 1) * seeds
    }

    /// Whether the study has no data set (never: a study has at least one seed).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Data set `k`'s design: effect by effect, strength by strength, seed by seed,
    /// then the seeds with nothing hidden.
    pub fn design(&self, k: usize) -> DataSetDesign {
        let seeds = self.settings.seeds as usize;
        let levels = self.settings.levels.len();
        let seed = self.settings.first_seed + (k % seeds) as u64;
        let cell = k / seeds;
        match self.hidings.get(cell / levels.max(1)) {
            Some(&hiding) => DataSetDesign {
                hiding: Some(hiding),
                level: self.settings.levels[cell % levels],
                seed,
            },
            None => DataSetDesign {
                hiding: None,
                level: 0.0,
                seed,
            },
        }
    }

    /// Data set `k` made and diagnosed.
    pub fn row(&self, k: usize) -> Result<PowerRow, PowerError> {
        let design = self.design(k);
        let c = self.settings.diagnose.contact;
        let name = design.hiding.map_or("none", |h| h.candidate.name());
        let fail = |source| PowerError::Diagnose {
            data_set: k,
            what: format!("{name} at {}, seed {}", design.level, design.seed),
            source,
        };
        let mut truth = self.conditions.clone();
        if let Some(hiding) = design.hiding {
            for (_, model) in &mut truth {
                hiding.hide(model, c, design.level)?;
            }
        }
        let data = measured(&truth, self.settings.runs, design.seed)?;
        let mut base = self.base.clone();
        // The HCM is the gain table's comparison; the answer does not depend on it.
        let mut settings = DiagnoseSettings {
            hcm_epochs: 0,
            ..self.settings.diagnose.clone()
        };
        if self.settings.base == PowerBase::Fitted {
            let law = base.contacts[c].law().name();
            let fit = identify(&self.scenario, &base, &data, c, law, Method::Lsq, &Silent)
                .map_err(fail)?;
            base.contacts[c].model.normal.base = fit.law;
            settings.base_freedom = BaseFreedom::Fitted;
        } else {
            settings.base_freedom = BaseFreedom::Given;
        }
        let diagnosis = diagnose(&base, &data, &settings).map_err(fail)?;
        let named: Vec<&str> = diagnosis.causes.iter().map(|c| c.effect).collect();
        let answer = answer(&diagnosis);
        let found = diagnosis.causes.iter().find(|c| c.effect == name);
        let first = found.and_then(|c| c.parameters.first());
        let (value, (low, high)) =
            first.map_or((f64::NAN, (f64::NAN, f64::NAN)), |p| (p.value, p.ci));
        let exact = match design.hiding {
            Some(_) => answer == name,
            None => answer == "none",
        };
        Ok(PowerRow {
            data_set: k,
            effect: name.to_owned(),
            level: design.level,
            seed: design.seed,
            parameter: design
                .hiding
                .map_or("", |h| h.candidate.strength().0)
                .to_owned(),
            truth: design.hiding.map_or(f64::NAN, |h| h.value(design.level)),
            wrong: named.iter().any(|n| *n != name),
            named: named.join("+"),
            answer,
            exact,
            value,
            low,
            high,
        })
    }

    /// The study's rows from `parts` (each a name for messages — a shard's file — and its
    /// rows, as [`read_rows`] reads them), in order: refused unless they hold every data
    /// set once, from 0, in order. What `hcm power --merge` and the Python API's join do.
    pub fn join(&self, parts: Vec<(String, Vec<PowerRow>)>) -> Result<Vec<PowerRow>, PowerError> {
        let mut rows: Vec<PowerRow> = Vec::with_capacity(self.len());
        for (name, part) in parts {
            let next = rows.len();
            if let Some((k, row)) = (part.iter().enumerate()).find(|(k, r)| r.data_set != next + k)
            {
                return Err(PowerError::Setup(format!(
                    "{name}: data set {} where {} comes next (give the parts in order, the \
                     first first, none missing)",
                    row.data_set,
                    next + k
                )));
            }
            rows.extend(part);
        }
        if rows.len() != self.len() {
            return Err(PowerError::Setup(format!(
                "the parts hold data sets 0..{} of {}: a part is missing",
                rows.len(),
                self.len()
            )));
        }
        Ok(rows)
    }

    /// The rows of data sets `range` (in order; made in parallel), reporting
    /// [`Stage::Power`] to `progress`, a step per data set.
    pub fn rows(
        &self,
        range: Range<usize>,
        progress: &dyn Progress,
    ) -> Result<Vec<PowerRow>, PowerError> {
        let steps = range.len() as u64;
        let done = AtomicU64::new(0);
        in_stage(progress, Stage::Power, steps, || {
            range
                .into_par_iter()
                .map(|k| {
                    let row = self.row(k);
                    progress.advance(done.fetch_add(1, Ordering::Relaxed) + 1, steps);
                    row
                })
                .collect()
        })
    }
}

/// An effect the 1D diagnosis names, by its catalogue name (`--effects`).
pub fn line_effect(name: &str) -> Result<Candidate, String> {
    let known: Vec<Candidate> = super::line_candidates().collect();
    known
        .iter()
        .copied()
        .find(|c| c.name() == name.trim())
        .ok_or_else(|| {
            let names: Vec<&str> = known.iter().map(|c| c.name()).collect();
            format!(
                "`{name}` is not an effect the 1D diagnosis names; one of: {}",
                names.join(", ")
            )
        })
}

/// Refuses settings that make no study.
fn check(settings: &PowerSettings) -> Result<(), PowerError> {
    let bad = |what: String| Err(PowerError::Setup(what));
    if settings.seeds == 0 {
        return bad("--seeds must be at least 1".into());
    }
    if settings.first_seed.checked_add(settings.seeds).is_none() {
        return bad(format!(
            "--seed {} with --seeds {} runs past the largest seed",
            settings.first_seed, settings.seeds
        ));
    }
    if settings.runs < 2 {
        return bad(format!(
            "--runs {}: the diagnosis fits on some runs and judges on others: give at least 2",
            settings.runs
        ));
    }
    if settings.levels.is_empty() {
        return bad(
            "--levels needs at least one strength (e.g. 0.01 for 1 % of the peak force)".into(),
        );
    }
    if let Some(x) = settings.levels.iter().find(|x| !(**x > 0.0 && **x <= 1.0)) {
        return bad(format!(
            "--levels: {x} is not a share of the peak force in (0, 1] (e.g. 0.01 for 1 %)"
        ));
    }
    Ok(())
}

/// `runs` runs of `conditions` from `seed` as `hcm generate` makes them, written as
/// CSV and read back, as `hcm diagnose` reads a user's file.
fn measured(conditions: &[(String, Model)], runs: usize, seed: u64) -> Result<Dataset, PowerError> {
    let generation = Generation::of_conditions(conditions.to_vec(), runs, seed)?;
    let data = generated(generation, &Silent)?;
    let mut text = Vec::new();
    let as_csv = |e: crate::dataset::DataError| PowerError::Setup(e.to_string());
    data.to_writer(&mut text).map_err(as_csv)?;
    Dataset::from_reader("generated", text.as_slice()).map_err(as_csv)
}

/// The unit vector along which contact `c`'s recorded force vector reads its normal
/// force: the normal at the first run's largest force, turned to the measured body.
fn force_direction(model: &Model, data: &Dataset, c: usize) -> Result<[f64; 3], PowerError> {
    let history =
        contact_history(model, &data.runs[0], c).map_err(|e| PowerError::Setup(e.to_string()))?;
    let peak = (0..history.force.len())
        .max_by(|&a, &b| history.force[a].total_cmp(&history.force[b]))
        .ok_or_else(|| PowerError::Setup("the first run recorded no force".into()))?;
    let sign = match history.force_body {
        Some(body) if body == model.contacts[c].body_2 => -1.0,
        _ => 1.0,
    };
    let n = history.normal[peak] * sign;
    Ok([n.x, n.y, n.z])
}

/// The study's key: what a shard's rows depend on, in one line.
fn key(scenario: &Scenario, s: &PowerSettings) -> String {
    let effects: Vec<&str> = s.effects.iter().map(|e| e.name()).collect();
    let levels: Vec<String> = s.levels.iter().map(|x| format!("{x:e}")).collect();
    let d = &s.diagnose;
    format!(
        "hcm {} scenario {} text {:016x} contact {} runs {} seeds {}+{} levels {} effects {} \
         base {} holdout {:e} seed {} chance {}",
        env!("CARGO_PKG_VERSION"),
        scenario.name,
        fnv1a(scenario.to_toml().as_bytes()),
        d.contact,
        s.runs,
        s.first_seed,
        s.seeds,
        levels.join(","),
        effects.join(","),
        match s.base {
            PowerBase::Scenario => "scenario",
            PowerBase::Fitted => "fitted",
        },
        d.holdout_fraction,
        d.seed,
        d.chance
    )
}

/// FNV-1a 64 of `bytes`: a digest stable across Rust versions and platforms, which
/// std's hasher does not promise (a shard made on one machine is merged on another).
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3)
    })
}
