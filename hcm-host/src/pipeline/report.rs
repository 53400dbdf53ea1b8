//! The results as the report's markdown (`report.md`), written to be read without the
//! paper: the setup in a sentence, every term glossed once, every column explained, a
//! takeaway per table computed from its numbers, plain numbers with units, and the
//! figures embedded with captions.

use super::quantity::{number, percent, Scale};
use super::setup::law_phrase;
use super::{Example, ReproduceResults};
use crate::evaluate::{ConditionTable, IndicatorErrors, ModelRow};
use std::fmt::Write as _;

/// The indicators' names in the paper's words, in [`crate::indicators::Indicators::NAMES`] order.
const INDICATORS: [&str; 4] = [
    "maximum contact force",
    "contact impulse",
    "contact energy loss",
    "contact duration",
];

/// The indicators as they qualify an error ("energy-loss error").
const ERROR_OF: [&str; 4] = ["max-force", "impulse", "energy-loss", "duration"];

/// Significant digits of the indicator values.
const DIGITS: usize = 6;

impl ReproduceResults {
    /// The report: setup, terms, the paper's table on S2, our errors beside the
    /// paper's, the figures, the residual network and the stage timings.
    pub fn markdown(&self) -> String {
        [
            self.heading(),
            self.terms(),
            self.validation_section(),
            self.paper_section(),
            self.figures_section(),
            self.network_section(),
            self.timings_section(),
        ]
        .join("\n")
    }

    /// Title, the setup in one sentence, the outcome in one line, and how it was run.
    fn heading(&self) -> String {
        let example = self.example;
        let mut md = format!(
            "# hcm reproduce {}: the paper's {} example ({})\n\n",
            example.name(),
            example.name().replace('-', " "),
            example.section()
        );
        if !self.setup.sentence.is_empty() {
            let _ = writeln!(md, "**Setup.** {}\n", self.setup.sentence);
        }
        let _ = writeln!(md, "**Outcome.** {}\n", self.outcome());
        let conditions = &self.setup.conditions;
        let runs = if conditions.is_empty() {
            format!("{} runs", self.runs_per_condition)
        } else {
            format!(
                "{} runs at each of {} conditions ({})",
                self.runs_per_condition,
                conditions.len(),
                conditions.join(", ")
            )
        };
        let overrides: String = (self.overrides.iter())
            .map(|o| format!(" `--set {o}`"))
            .collect();
        let _ = writeln!(md, "Run: {runs} (the paper: {}), seed {}, scenario `{}`{overrides}. The scenario's parameters are a reconstruction of the paper's lost ones (`docs/reconstruction.md` in the hcm repository).",
            example.runs(), self.seed, self.scenario);
        md
    }

    /// Every term of the report, glossed once.
    fn terms(&self) -> String {
        let s = &self.setup;
        let scatter = if s.parameter_noise.is_empty() {
            String::new()
        } else {
            format!(
                ", each run with its parameters scattered ({}, standard deviations; the paper's Eq 18)",
                s.parameter_noise
            )
        };
        let noise = Scale::plain("N").brief(s.force_noise, 4);
        let pm2 = law_phrase(
            &self.pm2.law,
            (self.pm2.parameters.iter()).map(|p| (p.name.as_str(), p.value)),
        );
        let mut md = String::from("## What the words mean\n\n");
        let _ = writeln!(md, "- **PM1** (physics model 1) stands in for measurements: the contact simulated with {}{scatter}, and random noise of {noise} (standard deviation) added to every force sample (Eq 19).", s.pm1);
        let _ = writeln!(md, "- **S1** and **S2**: the runs split into a training set S1 ({} runs), the only data the models below learn from, and a validation set S2 ({} runs: {}), used only to judge them.", s.training_runs, s.validation_runs, s.holdout);
        let _ = writeln!(
            md,
            "- **PM2** (physics model 2): a physics law fitted to S1 — {pm2}, found by {}.",
            method_words(&self.pm2.method)
        );
        md.push_str("- **HCM** (hybrid contact model): PM2 plus a small neural network, the *residual*, trained on S1 to predict the force PM2 gets wrong from the indentation δ (how far the surfaces overlap), its rate δ̇ and the impact speed δ̇0. Outside the range of inputs seen in training (its *envelope*) the HCM is PM2 alone. **HCM int8**: the same network with its weights stored as 8-bit integers, as a microcontroller would hold it.\n");
        md.push_str("- **Indicators** of one contact: the *maximum contact force*; the *contact impulse* ∫f dt, the force integrated over the contact; the *contact energy loss*, the kinetic energy of the relative motion that the contact takes away; the *contact duration*, from touch-down to lift-off.\n");
        md.push_str("- **Error** (the paper's Eq 20): |S2 mean − model| / S2 mean, each model simulated from the S2 runs' mean state just before touch-down.\n");
        md
    }

    /// The paper's table on S2, what its columns mean, and its takeaway.
    fn validation_section(&self) -> String {
        let table = &self.validation;
        let condition = if table.condition.is_empty() {
            String::new()
        } else {
            format!(", condition {}", table.condition)
        };
        let mut md = format!(
            "## 1. The models against the validation runs (S2: {} runs{condition})\n\n",
            table.runs
        );
        let _ = writeln!(md, "**Takeaway:** {}\n", self.validation_takeaway());
        md.push_str(&indicator_table(table));
        let _ = writeln!(
            md,
            "\n- *S2 mean*: the indicator measured on each of the {} S2 runs, averaged.",
            table.runs
        );
        md.push_str("- *S2 standard error*: the uncertainty of that mean (s/√n), as a share of it; a model's error below about twice it cannot be told apart from the runs' own scatter.\n");
        md.push_str("- *PM2*, *HCM*, *HCM int8*: the indicator of each model.\n");
        md.push_str("- *error of …*: that model's Eq 20 error against the S2 mean.\n");
        md
    }

    /// The report in one line: PM2's worst error against the HCM's, and on how many
    /// indicators the HCM is closer.
    fn outcome(&self) -> String {
        let table = &self.validation;
        let (Some(pm2), Some(hcm)) = (errors(table, "PM2"), errors(table, "HCM")) else {
            return "A model's simulation failed: see the table.".to_owned();
        };
        let worst = largest(&pm2);
        let better = (0..4).filter(|&i| hcm[i] < pm2[i]).count();
        format!(
            "{} error {} → {} from PM2 to the HCM (PM2's largest error); the HCM is closer to the measurements than PM2 on {better} of the 4 indicators.",
            capitalised(ERROR_OF[worst]), percent(pm2[worst]), percent(hcm[worst])
        )
    }

    /// One line: the outcome, how many of the HCM's errors are within the S2 noise,
    /// and what int8 weights cost.
    fn validation_takeaway(&self) -> String {
        let table = &self.validation;
        let mut line = self.outcome();
        let Some(hcm) = errors(table, "HCM") else {
            return line;
        };
        // Undefined (None) for a single S2 run: NaN, so nothing counts as resolved.
        let noise = table.standard_error.map_or([f64::NAN; 4], |s| s.values());
        let measured = table.measured.values();
        let resolved = (0..4)
            .filter(|&i| hcm[i] <= 2.0 * (noise[i] / measured[i]).abs())
            .count();
        let _ = write!(
            line,
            " {resolved} of the HCM's 4 errors are within twice the S2 standard error, as close as {} runs can tell.",
            table.runs
        );
        if let Some(int8) = errors(table, "HCM int8") {
            let moved = (0..4).map(|i| (int8[i] - hcm[i]).abs()).fold(0.0, f64::max);
            let amount = if moved < 5e-5 {
                "less than 0.01 points".to_owned()
            } else {
                format!("at most {:.2} points", 100.0 * moved)
            };
            let _ = write!(
                line,
                " Storing the network in 8-bit integers moves the HCM's errors by {amount}."
            );
        }
        line
    }

    /// Our errors beside the paper's, what the columns mean, and the takeaway.
    fn paper_section(&self) -> String {
        let (paper_pm2, paper_hcm) = (self.paper.pm2.values(), self.paper.hcm.values());
        let ours = |model: &str| errors(&self.validation, model).unwrap_or([f64::NAN; 4]);
        let (pm2, hcm) = (ours("PM2"), ours("HCM"));
        let worst = largest(&paper_pm2);
        let count =
            |mine: &[f64; 4], theirs: &[f64; 4]| (0..4).filter(|&i| mine[i] < theirs[i]).count();
        let (noise, measured) = (
            self.validation
                .standard_error
                .map_or([f64::NAN; 4], |s| s.values()),
            self.validation.measured.values(),
        );
        let unresolvable = (0..4)
            .filter(|&i| paper_hcm[i] < 2.0 * (noise[i] / measured[i]).abs())
            .count();
        let mut md = String::from("## 2. Beside the paper's errors\n\n");
        let _ = writeln!(md, "**Takeaway:** the paper's {} error went {} → {} from PM2 to the HCM, this run's {} → {}. This run's PM2 error is below the paper's on {} of the 4 indicators, its HCM error on {} of 4; {unresolvable} of the paper's 4 HCM errors are smaller than twice this run's S2 standard error, too small for its {} S2 runs to confirm.\n",
            ERROR_OF[worst], percent(paper_pm2[worst]), percent(paper_hcm[worst]),
            percent(pm2[worst]), percent(hcm[worst]), count(&pm2, &paper_pm2), count(&hcm, &paper_hcm), self.validation.runs);
        md.push_str("| indicator | PM2 error (hcm) | PM2 error (paper) | HCM error (hcm) | HCM error (paper) |\n|---|---|---|---|---|\n");
        for (i, name) in INDICATORS.iter().enumerate() {
            let _ = writeln!(
                md,
                "| {name} | {} | {} | {} | {} |",
                percent(pm2[i]),
                percent(paper_pm2[i]),
                percent(hcm[i]),
                percent(paper_hcm[i])
            );
        }
        let _ = writeln!(md, "\n- *(hcm)*: this run, from the table above; *(paper)*: the paper's {}, on its own runs.", self.example.section().split(", ").nth(1).unwrap_or("table"));
        md
    }

    /// The figures, embedded, each with a caption saying what to look at.
    fn figures_section(&self) -> String {
        let (force, error) = match self.example {
            Example::BouncingBall => ("Fig 9", "Fig 10"),
            Example::FlatShot => ("Fig 12", "Fig 13"),
        };
        let mut md = String::from("## 3. Figures\n\n");
        let pngs = (self.figures.iter()).filter(|f| f.ends_with(".png"));
        for png in pngs {
            let (title, caption) = match png.trim_end_matches(".png") {
                "contact_force" => (
                    "Contact force over the contact: S2 mean, PM2 and HCM".to_owned(),
                    format!("The contact force against the time since touch-down: measured (averaged over the S2 runs) and simulated by PM2 and the HCM (the paper's {force}). Look at where PM2's curve leaves the measured one, and whether the HCM's stays on it."),
                ),
                "force_error" => (
                    "Force error over the contact: S2 mean minus each model".to_owned(),
                    format!("The measured mean force minus each model's, over the contact (the paper's {error}). The closer a curve stays to zero, the better the model; PM2's shows the shape of what its law misses."),
                ),
                other => (other.replace('_', " "), String::new()),
            };
            let _ = writeln!(md, "![{title}]({png})\n\n*{caption}*\n");
        }
        let svgs: Vec<&str> = (self.figures.iter())
            .filter(|f| f.ends_with(".svg"))
            .map(String::as_str)
            .collect();
        let _ = writeln!(md, "The same figures as SVG: {}.", svgs.join(", "));
        md
    }

    /// The residual network's training, its int8 twin and the blobs, in words.
    fn network_section(&self) -> String {
        let r = &self.residual;
        let newton = Scale::plain("N");
        let noise = newton.brief(self.setup.force_noise, 4);
        let mut md = String::from("## 4. The residual network\n\n");
        let _ = writeln!(md, "The network learned from {} force samples of S1 for {} epochs (passes over the data), keeping the weights of epoch {}: on samples held back from its training its force error is {} root-mean-square (RMS), where the data's own noise is {noise}.",
            r.training_samples, r.epochs, r.best_epoch, newton.brief(r.validation_rms, 4));
        let _ = writeln!(md, "With its weights stored as 8-bit integers its output moves by {} RMS when they are plainly rounded, and by {} after {} epochs of quantisation-aware fine-tuning (training the integer copy to match the original).",
            newton.brief(r.int8_rounded_rms, 4), newton.brief(r.int8_tuned_rms, 4), r.int8_epochs);
        let blobs: Vec<String> = (self.blobs.iter())
            .map(|b| {
                format!(
                    "{} bytes with {} weights (worst relative difference {})",
                    b.bytes,
                    match b.weights.as_str() {
                        "f32" => "32-bit floating-point (f32)",
                        "int8" => "8-bit integer (int8)",
                        other => other,
                    },
                    number(b.round_trip_error, 2)
                )
            })
            .collect();
        let _ = writeln!(md, "It is exported for the core (hcm's library that runs on a controller) as a blob — {} — each decoded by the core and compared with the host's network over the envelope.", blobs.join(", or "));
        md
    }

    /// Wall-clock time per stage, with the total and the slowest stage.
    fn timings_section(&self) -> String {
        let total: f64 = self.timings.iter().map(|t| t.seconds).sum();
        let slowest = (self.timings.iter()).max_by(|a, b| a.seconds.total_cmp(&b.seconds));
        let mut md = String::from("## 5. Time taken\n\n");
        if let Some(slowest) = slowest {
            let _ = writeln!(
                md,
                "**Takeaway:** {total:.1} s in all; the longest stage is {} ({:.1} s).\n",
                slowest.stage, slowest.seconds
            );
        }
        md.push_str("| stage | time |\n|---|---|\n");
        for timing in &self.timings {
            let _ = writeln!(md, "| {} | {:.2} s |", timing.stage, timing.seconds);
        }
        md
    }
}

/// "the paper's genetic algorithm …" for the fit record's method label.
fn method_words(method: &str) -> String {
    if method.starts_with("ga") {
        format!("the paper's genetic algorithm, comparing simulated with measured contacts, then polished by Levenberg–Marquardt least squares (`{method}`)")
    } else if method == "lsq" {
        "least squares on S1's force samples (`lsq`)".to_owned()
    } else {
        format!("`{method}`")
    }
}

/// The four errors of the row labelled `model`, if it simulated.
fn errors(table: &ConditionTable, model: &str) -> Option<[f64; 4]> {
    let row: &ModelRow = table.models.iter().find(|m| m.model == model)?;
    row.errors.as_ref().map(IndicatorErrors::values)
}

/// `text` with its first letter in upper case.
fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or(String::new(), |first| {
        first.to_uppercase().chain(chars).collect()
    })
}

/// Index of the largest of `values` (NaN never wins).
fn largest(values: &[f64; 4]) -> usize {
    (0..4).fold(0, |best, i| if values[i] > values[best] { i } else { best })
}

/// The S2 table with one unit per indicator: the S2 mean, its standard error, each
/// model's value and each model's error.
fn indicator_table(table: &ConditionTable) -> String {
    let mut md = String::from("| indicator | S2 mean | S2 standard error |");
    for m in &table.models {
        let _ = write!(md, " {} |", m.model);
    }
    for m in &table.models {
        let _ = write!(md, " error of {} |", m.model);
    }
    md.push_str(&format!(
        "\n|---|---|---|{}\n",
        "---|".repeat(2 * table.models.len())
    ));
    let measured = table.measured.values();
    let noise = table.standard_error.map(|s| s.values());
    for (i, name) in INDICATORS.iter().enumerate() {
        let scale = match i {
            0 => Scale::plain("N"),
            1 => Scale::plain("N·s"),
            2 => Scale::prefixed(measured[i], "J"),
            _ => Scale::prefixed(measured[i], "s"),
        };
        let _ = write!(
            md,
            "| {name} | {} | {} |",
            scale.show(measured[i], DIGITS),
            match noise {
                Some(noise) => percent((noise[i] / measured[i]).abs()),
                None => format!("n/a ({} run)", table.runs),
            }
        );
        for m in &table.models {
            let value = m.indicators.map(|v| scale.show(v.values()[i], DIGITS));
            let _ = write!(md, " {} |", value.as_deref().unwrap_or("(failed)"));
        }
        for m in &table.models {
            let error = m.errors.map(|e| percent(e.values()[i]));
            let _ = write!(md, " {} |", error.as_deref().unwrap_or("–"));
        }
        md.push('\n');
    }
    md
}
