//! The peg-in-hole's `report.md` (our Table 15 beside the paper's) and
//! `results.json` (the same numbers, unrounded, for programs).

use super::{PegReproduction, PegRow, INDICATORS};
use serde::Serialize;
use std::fmt::Write as _;

/// `results.json`.
#[derive(Serialize)]
struct Results<'a> {
    example: &'static str,
    seed: u64,
    runs: usize,
    s2_runs: usize,
    s2_runs_averaged: usize,
    pm2: Pm2<'a>,
    models: &'a [String],
    table: &'a [PegRow],
    checks: Vec<Check>,
    /// Every S2 run as `hcm evaluate` judges it.
    events: &'a crate::evaluate::RigidEvaluation,
    residual: Residual,
    blobs: Vec<BlobSummary>,
    timings: &'a [super::StageTiming],
    figures: Vec<String>,
}

/// Per row: the two checks of the HCM (at or below the paper's error, within two S2
/// standard errors).
#[derive(Serialize)]
struct Check {
    contact: usize,
    indicator: &'static str,
    hcm_beats_pm2: bool,
    /// `≤ paper`, `≤ 2 SE`, `neither`.
    verdict: &'static str,
}

#[derive(Serialize)]
struct Residual {
    training_rows: usize,
    epochs: usize,
    best_epoch: usize,
    validation_mse: f64,
    int8_rounded_rms: f64,
    int8_tuned_rms: f64,
}

#[derive(Serialize)]
struct BlobSummary {
    weights: &'static str,
    bytes: usize,
    round_trip_error: f64,
}

#[derive(Serialize)]
struct Pm2<'a> {
    law: &'a str,
    exponent: f64,
    parameters: &'a [(String, f64)],
    fitness: f64,
    generations: usize,
    replays: usize,
}

impl PegReproduction {
    /// `results.json`'s text.
    pub fn json(&self, seed: u64, runs: usize) -> Result<String, serde_json::Error> {
        let contact = &self.pm2.model.contacts[super::CONTACT];
        let results = Results {
            example: "peg-in-hole",
            seed,
            runs,
            s2_runs: self.evaluation.runs.0,
            s2_runs_averaged: self.evaluation.runs.1,
            pm2: Pm2 {
                law: contact.law().name(),
                exponent: contact.law().get("exponent").unwrap_or(f64::NAN),
                parameters: &self.pm2.parameters,
                fitness: self.pm2.fitness,
                generations: self.pm2.generations,
                replays: self.pm2.evaluations,
            },
            models: &self.evaluation.models,
            table: &self.evaluation.rows,
            checks: (self.evaluation.rows.iter())
                .map(|r| Check {
                    contact: r.contact,
                    indicator: r.indicator,
                    hcm_beats_pm2: r.beats(1, 0),
                    verdict: r.verdict(1),
                })
                .collect(),
            events: &self.events,
            residual: Residual {
                training_rows: self.trained.rows,
                epochs: self.trained.report.epochs,
                best_epoch: self.trained.report.best_epoch,
                validation_mse: self.trained.report.validation_loss,
                int8_rounded_rms: self.trained.int8.rounded_rms,
                int8_tuned_rms: self.trained.int8.tuned_rms,
            },
            blobs: [("f32", &self.blobs.f32), ("int8", &self.blobs.int8)]
                .into_iter()
                .map(|(weights, b)| BlobSummary {
                    weights,
                    bytes: b.bytes.len(),
                    round_trip_error: b.round_trip_error,
                })
                .collect(),
            timings: &self.timings,
            figures: self.figure_files(),
        };
        serde_json::to_string_pretty(&results)
    }

    /// The figure files written (SVG and PNG of each).
    pub(crate) fn figure_files(&self) -> Vec<String> {
        (self.evaluation.figures.iter())
            .flat_map(|f| [format!("{}.svg", f.stem), format!("{}.png", f.stem)])
            .collect()
    }

    /// `report.md`.
    pub fn markdown(&self) -> String {
        let mut md = String::new();
        self.introduction(&mut md);
        self.pm2_section(&mut md);
        self.table_15(&mut md);
        self.every_run(&mut md);
        self.error_model(&mut md);
        self.figures_and_timings(&mut md);
        md
    }

    /// Every S2 run judged as `hcm evaluate` judges a user's rig.
    fn every_run(&self, md: &mut String) {
        let _ = writeln!(
            md,
            "## Every S2 run, event by event (`hcm evaluate`)\n\nThe same models as `hcm \
             evaluate --physics pm2.toml --residual residual.bin --data s2.csv` judges them: \
             each of the {} runs' contact events replayed from the recorded state before it, \
             the path from the run's pre-contact state, and the HCM − PM2 difference run by \
             run.\n",
            self.events.runs
        );
        let _ = writeln!(md, "{}", crate::evaluate::rigid_markdown(&self.events));
    }

    /// The title and what was run: the scenario and S2's runs (all, averaged).
    fn introduction(&self, md: &mut String) {
        let e = &self.evaluation;
        let _ = writeln!(
            md,
            "# hcm reproduce peg-in-hole: the paper's Section 5.3 (Table 15)\n"
        );
        let _ = writeln!(
            md,
            "A steel peg falls tilted into a hole with 2 mm clearance (`{}`): two wall contacts, \
             then the bottom. PM1 (IMPACT + STEP friction, parameters scattered per run, noise on \
             the recorded force and torque) made the runs; S2 holds {} of them ({} averaged: the \
             others make a different number of contacts). PM2 is IMPACT with its exponent fixed \
             and the rest identified on S1's wall contacts by the genetic algorithm.\n",
            self.scenario.source.path.display(),
            e.runs.0,
            e.runs.1
        );
    }

    /// PM2's identified parameters and the genetic algorithm's effort and fitness.
    fn pm2_section(&self, md: &mut String) {
        let _ = writeln!(md, "## PM2\n");
        for (name, value) in &self.pm2.parameters {
            let _ = writeln!(md, "- {name} = {value:.6e}");
        }
        let _ = writeln!(
            md,
            "\nGA: {} generations, {} replays, fitness {:.3e} (mean squared relative error of the wall contacts' indicators).\n",
            self.pm2.generations, self.pm2.evaluations, self.pm2.fitness
        );
    }

    /// Table 15: each wall contact's indicators on S2 beside every model's and the
    /// paper's errors, and how the errors are read.
    fn table_15(&self, md: &mut String) {
        let e = &self.evaluation;
        let _ = writeln!(md, "## Table 15: the wall contacts on S2\n");
        let mut header = "| contact | indicator | S2 mean | std. error |".to_owned();
        let mut rule = "|---|---|---|---|".to_owned();
        for m in &e.models {
            let _ = write!(header, " {m} | error of {m} |");
            rule.push_str("---|---|");
        }
        header.push_str(" paper PM2 | paper HCM | HCM < PM2 | HCM vs paper / S2 |");
        rule.push_str("---|---|---|---|");
        let _ = writeln!(md, "{header}\n{rule}");
        for row in &e.rows {
            table_15_row(md, row);
        }
        let _ = writeln!(md, "\nError: the paper's Eq 20, |S2 mean − model| / S2 mean. Std. error: s/√n of the S2 mean, as a share of it. \
             Last column: the HCM's error at or below the paper's HCM error (`≤ paper`), else within two standard errors of the S2 mean (`≤ 2 SE`: \
             as close as the S2 runs can tell), else `neither`. \
             PM1 nominal: the scenario's own laws at their nominal (unscattered) parameters, replayed like the models — the true physics of a mean run. \
             What it misses is what no single deterministic replay can make: the S2 mean of each run's peak is not the peak of a mean run.\n");
    }

    /// The error model (Eq 12): its training, the variance it explains per output, the
    /// outputs fixed at zero, and its blobs' sizes (bytes) and round trips.
    fn error_model(&self, md: &mut String) {
        let t = &self.trained;
        let _ = writeln!(md, "## The error model (Eq 12)\n");
        let _ = writeln!(
            md,
            "One network, 13 inputs (the peg's position, orientation quaternion, velocity — world frame — and angular velocity in its body frame) → 32 → 32 → 6 \
             outputs (force and torque error on the peg, world frame, torque about its centre of mass), trained on {} samples of S1's wall contacts: \
             {} epochs (best {}), validation MSE {:.4} (N², N²·m² averaged over the outputs), {:.1} s. \
             int8 twin: RMS {:.4} against the f32 network after fine-tuning ({:.4} plainly rounded).\n",
            t.rows, t.report.epochs, t.report.best_epoch, t.report.validation_loss, t.report.seconds, t.int8.tuned_rms, t.int8.rounded_rms
        );
        const OUTPUTS: [&str; 6] = ["F_x", "F_y", "F_z", "T_x", "T_y", "T_z"];
        let explained: Vec<String> = (OUTPUTS.iter().zip(&t.explained))
            .map(|(name, r2)| format!("{name} {r2:.3}"))
            .collect();
        let silenced: Vec<&str> = (t.silenced.iter())
            .filter_map(|&k| OUTPUTS.get(k).copied())
            .collect();
        let silenced = if silenced.is_empty() {
            "none".to_owned()
        } else {
            silenced.join(", ")
        };
        let _ = writeln!(
            md,
            "Share of each target's variance the network explains on its training rows (R²): {}. \
             Fixed at zero (R² < 0.1: no signal beyond the sensor noise): {silenced}.\n",
            explained.join(", ")
        );
        let _ = writeln!(
            md,
            "| blob | bytes | round trip (core vs host, relative) |\n|---|---|---|"
        );
        for (name, blob) in [("f32", &self.blobs.f32), ("int8", &self.blobs.int8)] {
            let _ = writeln!(
                md,
                "| {name} | {} | {:.2e} |",
                blob.bytes.len(),
                blob.round_trip_error
            );
        }
        md.push('\n');
    }

    /// The figures, and the time each stage took (s).
    fn figures_and_timings(&self, md: &mut String) {
        let _ = writeln!(md, "## Figures\n");
        for f in &self.evaluation.figures {
            let _ = writeln!(md, "![{}]({}.png)\n", f.stem, f.stem);
        }
        let _ = writeln!(md, "## Time per stage\n\n| stage | s |\n|---|---|");
        for t in &self.timings {
            let _ = writeln!(md, "| {} | {:.2} |", t.stage, t.seconds);
        }
    }
}

/// One row of Table 15: contact, indicator, the S2 mean with its unit and standard
/// error (% of the mean), each model's value and error (%), the paper's errors (%), and
/// the HCM's two checks.
fn table_15_row(md: &mut String, row: &PegRow) {
    let label = INDICATORS
        .iter()
        .find(|i| i.0 == row.indicator)
        .map_or(row.indicator, |i| i.1);
    let _ = write!(
        md,
        "| {} | {label} | {:.6} {} | {:.2} % |",
        row.contact,
        row.mean,
        row.unit,
        100.0 * row.standard_error / row.mean.abs()
    );
    for (value, error) in row.values.iter().zip(&row.errors) {
        match (value, error) {
            (Some(v), Some(err)) => {
                let _ = write!(md, " {v:.6} | {:.2} % |", 100.0 * err);
            }
            _ => md.push_str(" no contact | – |"),
        }
    }
    match row.paper {
        Some((pm2, hcm)) => {
            let _ = write!(md, " {:.2} % | {:.2} % |", 100.0 * pm2, 100.0 * hcm);
        }
        None => md.push_str(" – | – |"),
    }
    let beats = if row.beats(1, 0) { "yes" } else { "**no**" };
    let _ = writeln!(md, " {beats} | {} |", row.verdict(1));
}
