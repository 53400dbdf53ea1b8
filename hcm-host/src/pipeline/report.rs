//! The results as the report's markdown (`report.md`).

use super::ReproduceResults;
use crate::evaluate::markdown;
use std::fmt::Write as _;

/// The indicators' names in the paper's words, in [`crate::indicators::Indicators::NAMES`] order.
const INDICATORS: [&str; 4] = [
    "maximum contact force",
    "contact impulse",
    "contact energy loss",
    "contact duration",
];

impl ReproduceResults {
    /// The report: the paper's table on S2, our errors beside the paper's, the
    /// residual's training and blobs, the stage timings and the figures.
    pub fn markdown(&self) -> String {
        let mut md = String::new();
        let _ = writeln!(
            md,
            "# hcm reproduce {:?} (seed {}, {} runs per condition)\n",
            self.example, self.seed, self.runs_per_condition
        );
        let parameters: Vec<String> = (self.pm2.parameters.iter())
            .map(|p| format!("{} = {:.6e}", p.name, p.value))
            .collect();
        let overrides: String = (self.overrides.iter())
            .map(|o| format!(" `--set {o}`"))
            .collect();
        let _ = writeln!(md, "Scenario `{}`{overrides} (a reconstruction of the paper's lost parameters). PM2 = Lankarani–Nikravesh by {}: {}.\n",
            self.scenario, self.pm2.method, parameters.join(", "));
        let table = &self.validation;
        let condition = if table.condition.is_empty() {
            String::new()
        } else {
            format!(", condition {}", table.condition)
        };
        let _ = writeln!(md, "## Table (S2 = {} runs{condition})\n", table.runs);
        md.push_str(&markdown(table));
        md.push_str(&self.paper_comparison());
        md.push_str(&self.residual_paragraph());
        let _ = writeln!(md, "## Stage timings (s)\n\n| stage | s |\n|---|---|");
        for timing in &self.timings {
            let _ = writeln!(md, "| {} | {:.2} |", timing.stage, timing.seconds);
        }
        let _ = writeln!(md, "\nFigures: {}", self.figures.join(", "));
        md
    }

    /// Our PM2 and HCM errors beside the paper's (Tables 5 and 10).
    fn paper_comparison(&self) -> String {
        let mut out = String::from("\n| indicator | PM2 error (hcm) | PM2 error (paper) | HCM error (hcm) | HCM error (paper) |\n|---|---|---|---|---|\n");
        let ours = |i: usize, k: usize| {
            (self.validation.models.get(k))
                .and_then(|m| m.errors)
                .map_or("–".to_owned(), |e| {
                    format!("{:.2} %", 100.0 * e.values()[i])
                })
        };
        let (pm2, hcm) = (self.paper.pm2.values(), self.paper.hcm.values());
        for (i, name) in INDICATORS.iter().enumerate() {
            let _ = writeln!(
                out,
                "| {name} | {} | {:.2} % | {} | {:.2} % |",
                ours(i, 0),
                100.0 * pm2[i],
                ours(i, 1),
                100.0 * hcm[i]
            );
        }
        out
    }

    /// The residual's training, its int8 twin and the blobs, in one paragraph.
    fn residual_paragraph(&self) -> String {
        let r = &self.residual;
        let blobs: Vec<String> = (self.blobs.iter())
            .map(|b| {
                // The storage as the report always named it: `F32`, `Int8`.
                let mut name = b.weights.clone();
                if let Some(first) = name.get_mut(..1) {
                    first.make_ascii_uppercase();
                }
                format!("{name} {} bytes ({:.1e})", b.bytes, b.round_trip_error)
            })
            .collect();
        format!("\nResidual: {} training samples, {} epochs (best {}), validation RMS {:.2} N. int8 twin: RMS to the f32 network {:.3} N after plain rounding, {:.3} N after {} epochs of quantisation-aware fine-tuning. Blobs (core vs host, worst relative error over the envelope): {}.\n\n",
            r.training_samples, r.epochs, r.best_epoch, r.validation_rms,
            r.int8_rounded_rms, r.int8_tuned_rms, r.int8_epochs, blobs.join(", "))
    }
}
