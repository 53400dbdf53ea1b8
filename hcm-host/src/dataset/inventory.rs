//! What a data set holds, said before a command works on it (issue 28: "`hcm` says
//! which channels it found and what it can do with them"): per body, how many rows
//! fill each channel, and what a rigid contact's commands can do with that.

use super::channel::Channel;
use super::Dataset;
use crate::scenario::Model;
use std::fmt::Write as _;

/// Rows filling each channel, per body, over every run: (body, [rows per channel in
/// [`Channel::ALL`] order], rows).
pub fn channel_counts(data: &Dataset) -> Vec<(String, [usize; 6], usize)> {
    let mut out: Vec<(String, [usize; 6], usize)> = Vec::new();
    for run in &data.runs {
        for track in &run.bodies {
            let at = match out.iter().position(|(b, _, _)| *b == track.body) {
                Some(at) => at,
                None => {
                    out.push((track.body.clone(), [0; 6], 0));
                    out.len() - 1
                }
            };
            for sample in &track.samples {
                for (k, channel) in Channel::ALL.iter().enumerate() {
                    out[at].1[k] += usize::from(sample.has(*channel));
                }
                out[at].2 += 1;
            }
        }
    }
    out
}

/// The summary a rigid command prints: the runs, each body's channels with their row
/// counts, and what contact `c` of `model` can be given from them.
pub fn summary(data: &Dataset, model: &Model, c: usize) -> String {
    let counts = channel_counts(data);
    let mut out = format!("data: {} runs", data.runs.len());
    for (body, filled, rows) in &counts {
        let have: Vec<String> = (Channel::ALL.iter().zip(filled))
            .filter(|(_, n)| **n > 0)
            .map(|(ch, n)| {
                if n == rows {
                    ch.name().to_owned()
                } else {
                    format!("{} ({n})", ch.name())
                }
            })
            .collect();
        let _ = write!(
            out,
            "; `{body}` {rows} rows: {}",
            if have.is_empty() {
                "nothing".to_owned()
            } else {
                have.join(", ")
            }
        );
    }
    let Some(contact) = model.contacts.get(c) else {
        return out;
    };
    let pair = [contact.body_1, contact.body_2];
    let filled = |channel: Channel, moving_only: bool| {
        pair.iter().any(|&b| {
            let body = &model.bodies[b];
            (!moving_only || !body.fixed)
                && counts
                    .iter()
                    .any(|(n, f, _)| *n == body.name && f[channel as usize] > 0)
        })
    };
    let states = [
        Channel::Position,
        Channel::Orientation,
        Channel::Velocity,
        Channel::AngularVelocity,
    ]
    .iter()
    .all(|&ch| filled(ch, true));
    let force = filled(Channel::Force, false);
    let can = match (states, force) {
        (true, true) => "force and motion: identify (lsq, ga), train, evaluate, diagnose",
        (true, false) => "motion only: no force to fit a law to — a tossed body's fit is `hcm identify-motion`, its diagnosis `hcm diagnose-motion`",
        (false, true) => "force without the moving body's poses (position and orientation): nothing a rigid contact can be fitted on",
        (false, false) => "neither force nor the moving body's state",
    };
    let _ = write!(out, "\n  → {can}");
    out
}
