//! `hcm indicators`: the paper's contact indicators from a data file.

use super::report;
use hcm_host::dataset::{complete, DataUse, Dataset, Evidence};
use hcm_host::indicators::{
    events_of_runs, from_run, pair_events_from_run, summarize, wrench_statistics,
    ContactStatistics, RecordedEvent,
};
use hcm_host::scenario::Model;
use std::path::PathBuf;

/// Contact indicators per contact and run, with mean and standard deviation over runs
/// (3D scenarios: mean and its standard error per contact event).
///
/// The scenario supplies what the data cannot: the bodies' shapes (to recompute the
/// indentation δ from the recorded positions and find where it crosses zero) and
/// masses (for the energy loss ½·m_e·(δ̇_in² − δ̇_out²)).
///
/// Terms:
///   indicators  of one contact: maximum force (N), impulse ∫f dt (N·s), energy lost
///               (N·m = J) and duration (s), between touch-down and lift-off (δ = 0)
///   δ, δ̇        indentation (m, > 0 in contact) and its rate (m/s, > 0 approaching)
///   m_e         effective mass m1·m2/(m1 + m2) of the two bodies (kg)
#[derive(clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    /// Data file in the measured-data format (CSV).
    #[arg(long)]
    data: PathBuf,
    #[command(flatten)]
    scenario: super::ScenarioArgs,
    /// Print JSON (per-event indicators, summary, runs without contact) instead of markdown.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> anyhow::Result<()> {
    let model = args.scenario.load()?.model()?;
    let dataset = Dataset::read(&args.data)?;
    let contacts: Vec<usize> = (0..model.contacts.len()).collect();
    // Every contact at once: the scene decides, whichever contact the data show.
    let evidence = Evidence::of(&model, &dataset, 0);
    if let Some(needs) = evidence.requirement(DataUse::Indicators) {
        dataset.require(&args.data.display().to_string(), &model, &contacts, needs)?;
    }
    if evidence != Evidence::LineForce {
        return run_rigid(&model, &dataset, args.json);
    }
    // Camera frames and force rows on their own clocks: the motion at the force samples.
    let completed = complete(&model, &dataset)?;
    let dataset = completed.data.as_ref();
    let (events, without_contact) = events_of_runs(&dataset.runs, |run| from_run(&model, run))?;
    let summary = summarize(&events);
    if args.json {
        return print_json(&events, RecordedEvent::line, &summary, &without_contact);
    }
    if events.is_empty() {
        println!(
            "no completed contact in the data ({} read)",
            count(dataset.runs.len(), "run")
        );
    } else {
        if dataset.runs.len() <= 10 {
            let rows: Vec<_> = events
                .iter()
                .map(|e| {
                    let label = format!("run `{}` {}", e.run, e.label);
                    (label, e.touch_down(), Some(e.line()))
                })
                .collect();
            print!("{}", report::event_table(&rows));
            println!();
        }
        print!("{}", report::summary_table(&summary));
    }
    if !without_contact.is_empty() {
        let gap = if events.is_empty() { "" } else { "\n" };
        println!("{gap}{}", without_contact_line(&without_contact));
    }
    Ok(())
}

/// The 3D indicators (max force, max torque, linear and angular impulse, duration)
/// per contact event and run (up to 10 runs), then per (contact, event) the mean over
/// the runs with its standard error; runs whose event count differs from the expected
/// are listed, not averaged (see `hcm_host::indicators::wrench_statistics`).
fn run_rigid(model: &Model, dataset: &Dataset, json: bool) -> anyhow::Result<()> {
    let (events, without_contact) =
        events_of_runs(&dataset.runs, |run| pair_events_from_run(model, run))?;
    let ids: Vec<String> = dataset.runs.iter().map(|r| r.id.clone()).collect();
    let summary = wrench_statistics(&ids, &events);
    if json {
        return print_json(&events, RecordedEvent::wrench, &summary, &without_contact);
    }
    if events.is_empty() {
        println!(
            "no completed contact in the data ({} read)",
            count(dataset.runs.len(), "run")
        );
    } else {
        if dataset.runs.len() <= 10 {
            let rows: Vec<_> = events
                .iter()
                .map(|e| {
                    let label = format!("run `{}` {} #{}", e.run, e.label, e.number + 1);
                    (label, e.touch_down(), e.wrench(), false)
                })
                .collect();
            print!("{}", report::pair_event_table(&rows));
        }
        if dataset.runs.len() > 1 {
            println!();
            print!("{}", report::wrench_statistics_table(&summary));
            for contact in &summary {
                if let Some(line) = mismatch_line(contact) {
                    println!("{line}");
                }
            }
        }
    }
    if !without_contact.is_empty() {
        println!("{}", without_contact_line(&without_contact));
    }
    Ok(())
}

/// `--json`: every event with its indicators (the `view` of it the data support), the
/// summary and the runs without contact.
fn print_json<I: serde::Serialize, S: serde::Serialize>(
    events: &[RecordedEvent],
    view: impl Fn(&RecordedEvent) -> I,
    summary: &S,
    without_contact: &[String],
) -> anyhow::Result<()> {
    let events: Vec<serde_json::Value> = (events.iter())
        .map(|e| {
            serde_json::json!({
                "run": e.run, "contact": e.label, "event": e.number,
                "touch_down": e.event.touch_down, "lift_off": e.event.lift_off,
                "indicators": view(e),
            })
        })
        .collect();
    let json = serde_json::json!({
        "events": events, "summary": summary, "runs_without_contact": without_contact,
    });
    println!("{}", serde_json::to_string_pretty(&json)?);
    Ok(())
}

/// The runs a contact's statistics leave out, with their event counts; None if none.
fn mismatch_line(contact: &ContactStatistics) -> Option<String> {
    if contact.mismatched_runs.is_empty() {
        return None;
    }
    let listed: Vec<String> = (contact.mismatched_runs.iter())
        .map(|m| format!("`{}` ({})", m.run, count(m.events, "event")))
        .collect();
    Some(format!(
        "{}: {} of {} have {} (the most common count) and are averaged; left out, their \
         event count differing: {}",
        contact.contact,
        contact.matched_runs,
        count(contact.runs, "run"),
        count(contact.expected_events, "event"),
        listed.join(", ")
    ))
}

/// `1 run without a completed contact: `0``: run ids in backquotes, as every other
/// message names runs, so that a run called `0` is not read as a count.
fn without_contact_line(ids: &[String]) -> String {
    let quoted: Vec<String> = ids.iter().map(|id| format!("`{id}`")).collect();
    format!(
        "{} without a completed contact: {}",
        count(ids.len(), "run"),
        quoted.join(", ")
    )
}

/// `1 run`, `2 runs`.
fn count(n: usize, noun: &str) -> String {
    if n == 1 {
        format!("1 {noun}")
    } else {
        format!("{n} {noun}s")
    }
}

#[cfg(test)]
mod tests {
    use super::without_contact_line;

    #[test]
    fn runs_are_named_apart_from_their_count() {
        assert_eq!(
            without_contact_line(&["0".into()]),
            "1 run without a completed contact: `0`"
        );
        assert_eq!(
            without_contact_line(&["v0.1/000".into(), "2".into()]),
            "2 runs without a completed contact: `v0.1/000`, `2`"
        );
    }
}
