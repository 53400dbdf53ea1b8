//! Markdown tables shared by the subcommands.

use hcm_host::indicators::{
    ContactStatistics, Estimate, EventSummary, Indicators, WrenchIndicators,
};
use std::fmt::Write;

/// One row per contact event: label, touch-down time and the indicators.
pub fn event_table(rows: &[(String, f64, Option<Indicators>)]) -> String {
    let mut out = String::from(
        "| contact | touch-down (s) | max force (N) | impulse (N·s) | energy loss (N·m) | duration (s) |\n|---|---|---|---|---|---|\n",
    );
    for (label, touch_down, indicators) in rows {
        match indicators {
            Some(i) => writeln!(
                out,
                "| {label} | {touch_down:.9} | {:.6e} | {:.6e} | {:.6e} | {:.6e} |",
                i.max_force, i.impulse, i.energy_loss, i.duration
            ),
            None => writeln!(
                out,
                "| {label} | {touch_down:.9} | (still in contact at the end) | | | |"
            ),
        }
        .expect("writing to a String cannot fail");
    }
    out
}

/// One row per 3D contact event: label, touch-down (s), indicators, and whether the
/// event was still open when the run ended.
pub fn pair_event_table(rows: &[(String, f64, WrenchIndicators, bool)]) -> String {
    let mut out = String::from(
        "| contact | touch-down (s) | max force (N) | max torque (N·m) | linear impulse (N·s) | angular impulse (N·m·s) | duration (s) |\n|---|---|---|---|---|---|---|\n",
    );
    for (label, touch_down, i, open) in rows {
        let duration = if *open {
            format!("≥ {:.6e} (still in contact at the end)", i.duration)
        } else {
            format!("{:.6e}", i.duration)
        };
        writeln!(
            out,
            "| {label} | {touch_down:.9} | {:.6e} | {:.6e} | {:.6e} | {:.6e} | {duration} |",
            i.max_force, i.max_torque, i.linear_impulse, i.angular_impulse
        )
        .expect("writing to a String cannot fail");
    }
    out
}

/// Mean ± standard deviation over runs, one row per contact event.
pub fn summary_table(summaries: &[EventSummary]) -> String {
    let mut out = String::from(
        "| contact | event | runs | max force (N) | impulse (N·s) | energy loss (N·m) | duration (s) |\n|---|---|---|---|---|---|---|\n",
    );
    for s in summaries {
        let cell =
            |st: hcm_host::indicators::Statistic| format!("{:.6e} ± {:.2e}", st.mean, st.std);
        writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} |",
            s.contact,
            s.event,
            s.runs,
            cell(s.max_force),
            cell(s.impulse),
            cell(s.energy_loss),
            cell(s.duration)
        )
        .expect("writing to a String cannot fail");
    }
    out
}

/// Per 3D contact event: the mean over the matched runs ± its standard error (and the
/// standard error as a percentage of the mean).
pub fn wrench_statistics_table(contacts: &[ContactStatistics]) -> String {
    let mut out = String::from(
        "| contact | event | runs | max force (N) | max torque (N·m) | linear impulse (N·s) | angular impulse (N·m·s) | duration (s) |\n|---|---|---|---|---|---|---|---|\n",
    );
    let cell = |e: Estimate| {
        if e.standard_error.is_nan() {
            format!("{:.6e} (1 run)", e.mean)
        } else {
            let percent = 100.0 * e.relative_error();
            format!("{:.6e} ± {:.2e} ({percent:.2} %)", e.mean, e.standard_error)
        }
    };
    for contact in contacts {
        for event in &contact.events {
            let cells: Vec<String> = event.estimates().map(cell).to_vec();
            writeln!(
                out,
                "| {} | {} | {} | {} |",
                contact.contact,
                event.event,
                event.runs,
                cells.join(" | ")
            )
            .expect("writing to a String cannot fail");
        }
    }
    out
}
