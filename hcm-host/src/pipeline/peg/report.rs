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
    timings: &'a [super::StageTiming],
    figures: Vec<String>,
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
            timings: &self.timings,
            figures: self.figure_files(),
        };
        serde_json::to_string_pretty(&results)
    }

    /// The figure files written (SVG and PNG of each).
    pub fn figure_files(&self) -> Vec<String> {
        (self.evaluation.figures.iter())
            .flat_map(|f| [format!("{}.svg", f.stem), format!("{}.png", f.stem)])
            .collect()
    }

    /// `report.md`.
    pub fn markdown(&self) -> String {
        let e = &self.evaluation;
        let mut md = String::new();
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
        let _ = writeln!(md, "## PM2\n");
        for (name, value) in &self.pm2.parameters {
            let _ = writeln!(md, "- {name} = {value:.6e}");
        }
        let _ = writeln!(
            md,
            "\nGA: {} generations, {} replays, fitness {:.3e} (mean squared relative error of the wall contacts' indicators).\n",
            self.pm2.generations, self.pm2.evaluations, self.pm2.fitness
        );
        let _ = writeln!(md, "## Table 15: the wall contacts on S2\n");
        let mut header = "| contact | indicator | S2 mean | std. error |".to_owned();
        let mut rule = "|---|---|---|---|".to_owned();
        for m in &e.models {
            let _ = write!(header, " {m} | error of {m} |");
            rule.push_str("---|---|");
        }
        header.push_str(" paper PM2 | paper HCM |");
        rule.push_str("---|---|");
        let _ = writeln!(md, "{header}\n{rule}");
        for row in &e.rows {
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
                    let _ = writeln!(md, " {:.2} % | {:.2} % |", 100.0 * pm2, 100.0 * hcm);
                }
                None => md.push_str(" – | – |\n"),
            }
        }
        let _ = writeln!(md, "\nError: the paper's Eq 20, |S2 mean − model| / S2 mean. Std. error: s/√n of the S2 mean, as a share of it.\n");
        let _ = writeln!(md, "## Figures\n");
        for f in &e.figures {
            let _ = writeln!(md, "![{}]({}.png)\n", f.stem, f.stem);
        }
        let _ = writeln!(md, "## Time per stage\n\n| stage | s |\n|---|---|");
        for t in &self.timings {
            let _ = writeln!(md, "| {} | {:.2} |", t.stage, t.seconds);
        }
        md
    }
}
