//! What a data set holds, said before a command works on it (which channels
//! it found and what can be done with them): per body, how many rows
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
pub fn inventory_summary(data: &Dataset, model: &Model, c: usize) -> String {
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
    let (poses, states, force) = what_is_filled(&counts, model, contact);
    let can = match (states || poses, force) {
        (true, true) if !states => "force and poses without velocities: identify (lsq) reads the state from the frames",
        (true, true) => "force and motion: identify (lsq, ga), train, evaluate, diagnose",
        (true, false) => "motion only: identify, evaluate and diagnose replay the runs from their poses (as `hcm identify-motion`, `hcm predict` and `hcm diagnose-motion`); train learns from them too (a contact's residual, or a mechanism's joint torque)",
        (false, true) => "force without the moving body's poses (position and orientation): nothing a rigid contact can be fitted on",
        (false, false) => "neither force nor the moving body's state",
    };
    let _ = write!(out, "\n  → {can}");
    out
}

/// Whether the moving bodies of `contact` have their poses (position and orientation),
/// their full state (and velocities), and whether either body has force or torque
/// samples.
fn what_is_filled(
    counts: &[(String, [usize; 6], usize)],
    model: &Model,
    contact: &crate::scenario::Contact,
) -> (bool, bool, bool) {
    let pair = [contact.body_1, contact.body_2];
    let filled = |channel: Channel, moving_only: bool| {
        pair.iter().any(|&b| {
            let body = &model.bodies[b];
            (!moving_only || !body.fixed)
                && (counts.iter()).any(|(n, f, _)| *n == body.name && f[channel as usize] > 0)
        })
    };
    let poses = [Channel::Position, Channel::Orientation]
        .iter()
        .all(|&ch| filled(ch, true));
    let states = poses
        && [Channel::Velocity, Channel::AngularVelocity]
            .iter()
            .all(|&ch| filled(ch, true));
    // A torque without its force still marks a sensor's data (missing a channel).
    let wrench = filled(Channel::Force, false) || filled(Channel::Torque, false);
    (poses, states, wrench)
}

/// Whether `data` hold contact `c`'s moving body's poses and no force or torque on
/// either body:
/// what a camera records, which `hcm identify` and `hcm diagnose` answer by replaying
/// the runs from their poses ([`crate::identify::identify_motion`]).
pub fn motion_only(data: &Dataset, model: &Model, c: usize) -> bool {
    let Some(contact) = model.contacts.get(c) else {
        return false;
    };
    let (poses, _, wrench) = what_is_filled(&channel_counts(data), model, contact);
    poses && !wrench
}
