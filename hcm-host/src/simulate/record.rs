//! Sampling a simulated run into the measured-data format: the contact rate
//! inside contacts (and a margin around them), the flight rate elsewhere.

use super::state::{Layout, StateVector};
use super::system::ContactSystem;
use super::{ContactEvent, Segment};
use crate::dataset::{BodyTrack, Run, Sample};
use crate::scenario::Model;
use hcm_core::integrate::OdeState;

/// Sample times as integer ticks of the contact sample period, so that the two
/// rates share one grid and no two samples nearly coincide.
fn sample_ticks(model: &Model, events: &[ContactEvent], end_time: f64) -> Vec<u64> {
    let record = &model.scenario.record;
    let tick = record.contact_sample_period;
    let stride = (record.flight_sample_period / tick).round().max(1.0) as u64;
    let last = (end_time / tick).floor() as u64;
    let mut ticks: Vec<u64> = (0..=last).step_by(stride as usize).collect();
    for event in events {
        let from = ((event.touch_down - record.contact_margin) / tick)
            .ceil()
            .max(0.0) as u64;
        let until = event.lift_off.unwrap_or(end_time) + record.contact_margin;
        let to = ((until / tick).floor() as u64).min(last);
        ticks.extend(from..=to);
    }
    ticks.sort_unstable();
    ticks.dedup();
    ticks
}

/// Samples every body at the recording grid.
pub fn sample(
    model: &Model,
    layout: &Layout,
    segments: &[Segment],
    events: &[ContactEvent],
    end_time: f64,
) -> Run {
    let tick = model.scenario.record.contact_sample_period;
    let wanted = &model.scenario.record.bodies;
    let recorded: Vec<usize> = (0..model.bodies.len())
        .filter(|&b| wanted.is_empty() || wanted.contains(&model.bodies[b].name))
        .collect();
    let mut tracks: Vec<BodyTrack> = recorded
        .iter()
        .map(|&b| BodyTrack {
            body: model.bodies[b].name.clone(),
            samples: Vec::new(),
        })
        .collect();
    let Some(first) = segments.first() else {
        return Run {
            id: "0".into(),
            bodies: tracks,
        };
    };
    let mut y: StateVector = first.stepper.state().clone();
    let mut index = 0;
    for t in sample_ticks(model, events, end_time)
        .into_iter()
        .map(|k| k as f64 * tick)
    {
        // Segments are contiguous and in time order; a sample on a boundary takes
        // the later segment (the modes after the event).
        while index + 1 < segments.len() && segments[index].end <= t {
            index += 1;
        }
        let segment = &segments[index];
        segment.stepper.dense_output(t, &mut y);
        let system = ContactSystem::new(model, layout, segment.modes.clone());
        let loads = system.loads(y.components());
        for (&b, track) in recorded.iter().zip(tracks.iter_mut()) {
            let (position, velocity) = layout.motion(model, y.components(), b);
            track.samples.push(Sample {
                time: t,
                position: position.into(),
                velocity: velocity.into(),
                force: loads.force[b].into(),
                torque: loads.torque[b].into(),
                ..Sample::at_rest(t)
            });
        }
    }
    Run {
        id: "0".into(),
        bodies: tracks,
    }
}
