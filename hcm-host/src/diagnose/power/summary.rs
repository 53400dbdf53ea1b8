//! A power study's table: per hidden effect and strength, how many data sets named it
//! exactly; the wrong names; how often a named parameter's 95 % interval held the
//! truth; and the false alarms with nothing hidden.

use super::{PowerRow, PowerStudy};
use std::fmt::Write;

/// The study's table in Markdown, from its rows (all of them, in order).
pub fn summary_markdown(study: &PowerStudy, rows: &[PowerRow]) -> String {
    let mut out = String::new();
    introduction(&mut out, study);
    effect_rows(&mut out, study, rows);
    false_alarms(&mut out, rows);
    out
}

/// The title and what a data set is.
fn introduction(out: &mut String, study: &PowerStudy) {
    let settings = study.settings();
    let _ = writeln!(
        out,
        "# Power of `hcm diagnose` on `{}`, contact {}\n",
        study.scenario_name(),
        settings.diagnose.contact
    );
    let _ = writeln!(
        out,
        "Each data set: {} runs as `hcm generate` makes them (the scenario's own noise), \
         one effect hidden at a strength x — the largest change of the force it makes, to \
         first order, as a share of the peak force — then `hcm diagnose` against {}. \
         {} seeds ({} to {}) per cell; {} data sets in all.\n",
        settings.runs,
        match settings.base {
            super::PowerBase::Scenario => "the scenario's own law (as given)",
            super::PowerBase::Fitted => "the scenario's law fitted by least squares on the same runs (`hcm identify --method lsq`)",
        },
        settings.seeds,
        settings.first_seed,
        settings.first_seed + settings.seeds - 1,
        study.len()
    );
}

/// The table: per hidden effect, named exactly at each strength, the wrong names and
/// the intervals that hold the truth.
fn effect_rows(out: &mut String, study: &PowerStudy, rows: &[PowerRow]) {
    let levels = &study.settings().levels;
    let heads: Vec<String> = levels.iter().map(|x| format!("{} %", 100.0 * x)).collect();
    let _ = writeln!(
        out,
        "| effect (parameter at 1 %) | {} | wrong names | 95 % interval holds the truth |",
        heads.join(" | ")
    );
    let _ = writeln!(out, "|---|{}---|---|", "---|".repeat(levels.len()));
    for hiding in study.hidings() {
        let name = hiding.candidate.name();
        let (parameter, unit) = hiding.candidate.strength();
        let of = |l: usize| {
            rows.iter()
                .filter(move |r| r.effect == name && r.level == levels[l])
        };
        let counts: Vec<String> = (0..levels.len())
            .map(|l| format!("{}/{}", of(l).filter(|r| r.exact).count(), of(l).count()))
            .collect();
        let all = || rows.iter().filter(|r| r.effect == name);
        let wrong = all().filter(|r| r.wrong).count();
        let named = all().filter(|r| r.value.is_finite()).count();
        let covered = all().filter(|r| r.covered()).count();
        let _ = writeln!(
            out,
            "| `{name}` ({parameter} = {:.3e} {unit}) | {} | {wrong} | {covered}/{named} |",
            hiding.value(0.01),
            counts.join(" | ")
        );
    }
}

/// What the data sets with nothing hidden named.
fn false_alarms(out: &mut String, rows: &[PowerRow]) {
    let none: Vec<&PowerRow> = rows.iter().filter(|r| r.effect == "none").collect();
    let alarms: Vec<&str> = none
        .iter()
        .filter(|r| !r.named.is_empty())
        .map(|r| r.named.as_str())
        .collect();
    let _ = writeln!(
        out,
        "\nNothing hidden: {} of {} data sets named a cause (false alarms){}.",
        alarms.len(),
        none.len(),
        match alarms.is_empty() {
            true => String::new(),
            false => format!(": {}", alarms.join(", ")),
        }
    );
    let other: usize = none.iter().filter(|r| !r.exact).count() - alarms.len();
    if other > 0 {
        let _ = writeln!(
            out,
            "{other} more answered without naming a cause (ambiguous, unexplained or \
             insufficient data)."
        );
    }
}
