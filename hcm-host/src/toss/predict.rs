//! The prediction of a toss: the scenario's body started at the window start in the
//! state [`estimate_initial_state`] gives, simulated to the toss's last frame, and
//! sampled at the toss's own frame times — the simulator's recorder samples on a grid
//! of one frame period from the start, and every frame of the window must lie on it
//! (frames may be missing, not shifted).
//!
//! Tosses are independent: [`predict_tosses`] checks every toss's window and initial
//! state first (cheap, so that a bad file fails at once), then simulates them in
//! parallel with rayon and returns them in the data's order — the same numbers whatever
//! the thread count.

use super::{estimate_initial_state, find_window, InitialState, TossError, TossSetup, Window};
use crate::dataset::{BodyTrack, Dataset, Run, Sample};
use crate::scenario::Model;
use crate::simulate::simulate;
use rayon::prelude::*;
use std::time::Instant;

/// How far a frame's time may lie from the grid of frame periods from the window
/// start, as a fraction of the period (–): the data's times are rounded to 1e-12 s.
const CLOCK_TOLERANCE: f64 = 1e-3;

/// One toss predicted.
#[derive(Clone, Debug)]
pub struct TossPrediction {
    /// Run id.
    pub(crate) run: String,
    /// The window, as indices into the run's frames of the body.
    pub window: Window,
    /// The state the replay started from.
    pub initial: InitialState,
    /// The frame period the replay was sampled at (s): the median of the toss's.
    pub frame_period: f64,
    /// The predicted samples, one per frame of the window, at the frames' times.
    pub samples: Vec<Sample>,
    /// Accepted solver steps.
    pub steps: u64,
    /// Wall-clock time of the simulation (s); not part of the prediction proper.
    pub seconds: f64,
}

/// A toss checked and ready to simulate.
#[derive(Clone, Debug)]
pub struct PreparedToss<'a> {
    /// Run id.
    pub(crate) run: &'a str,
    /// The recorded track of the tossed body.
    pub(crate) track: &'a BodyTrack,
    /// Its window.
    pub(crate) window: Window,
    /// The state at the window start.
    pub(crate) initial: InitialState,
    /// Frame period (s).
    pub(crate) frame_period: f64,
    /// Each window frame's index on the grid of frame periods from the window start.
    pub(crate) ticks: Vec<u64>,
}

/// Checks `run` and finds its window, initial state and frame grid.
pub(crate) fn prepare<'a>(setup: &TossSetup, run: &'a Run) -> Result<PreparedToss<'a>, TossError> {
    let track = run
        .body(&setup.name)
        .ok_or_else(|| TossError::MissingBody {
            run: run.id.clone(),
            body: setup.name.clone(),
        })?;
    let window = find_window(setup, &run.id, track)?;
    let initial = estimate_initial_state(setup, &run.id, track, &window)?;
    let frame_period = median_period(track);
    let mut ticks = Vec::with_capacity(window.len());
    for sample in &track.samples[window.start..] {
        let periods = (sample.time - initial.time) / frame_period;
        let tick = periods.round();
        if (periods - tick).abs() > CLOCK_TOLERANCE {
            return Err(TossError::Frame {
                run: run.id.clone(),
                time: sample.time,
                problem: format!(
                    "the frame lies {periods:.4} frame periods ({frame_period} s, the toss's \
                     median) after the window start, not a whole number: a toss's frames \
                     must come on one clock"
                ),
            });
        }
        ticks.push(tick as u64);
    }
    Ok(PreparedToss {
        run: &run.id,
        track,
        window,
        initial,
        frame_period,
        ticks,
    })
}

/// Median time between consecutive frames (s); one frame has none, and then any
/// positive period serves (its only frame is tick 0).
fn median_period(track: &BodyTrack) -> f64 {
    let mut gaps: Vec<f64> = (track.samples.windows(2))
        .map(|pair| pair[1].time - pair[0].time)
        .collect();
    if gaps.is_empty() {
        return 1.0;
    }
    gaps.sort_by(f64::total_cmp);
    gaps[gaps.len() / 2]
}

/// `model` started at `toss`'s initial state, ending half a period after its last
/// frame and recording only the tossed body, once per frame period.
pub fn replay_model(model: &Model, setup: &TossSetup, toss: &PreparedToss<'_>) -> Model {
    let mut replay = model.clone();
    let body = &mut replay.bodies[setup.body];
    body.position = toss.initial.position;
    body.orientation = toss.initial.orientation;
    body.velocity = toss.initial.velocity;
    body.angular_velocity = toss.initial.angular_velocity;
    let last = toss.ticks.last().copied().unwrap_or(0) as f64;
    let scenario = &mut replay.scenario;
    scenario.simulation.end_time = (last + 0.5) * toss.frame_period;
    scenario.simulation.stop_after_contacts = 0;
    scenario.record.contact_sample_period = toss.frame_period;
    scenario.record.flight_sample_period = toss.frame_period;
    scenario.record.contact_margin = 0.0;
    scenario.record.bodies = vec![setup.name.clone()];
    replay
}

/// Simulates a prepared toss with `model`'s physics.
pub(crate) fn simulate_toss(
    model: &Model,
    setup: &TossSetup,
    toss: &PreparedToss<'_>,
) -> Result<TossPrediction, TossError> {
    let started = Instant::now();
    let replay = replay_model(model, setup, toss);
    let simulation = simulate(&replay).map_err(|error| TossError::Simulation {
        run: toss.run.to_owned(),
        error,
    })?;
    let seconds = started.elapsed().as_secs_f64();
    let simulated = &simulation.run.bodies[0].samples;
    let frames = &toss.track.samples[toss.window.start..];
    let mut samples = Vec::with_capacity(frames.len());
    let mut next = simulated.iter().peekable();
    for (frame, &tick) in frames.iter().zip(&toss.ticks) {
        let wanted = tick as f64 * toss.frame_period;
        while next
            .next_if(|s| s.time < wanted - 0.5 * toss.frame_period)
            .is_some()
        {}
        let sample = (next.next())
            .filter(|s| (s.time - wanted).abs() < 0.5 * toss.frame_period)
            .ok_or_else(|| TossError::Frame {
                run: toss.run.to_owned(),
                time: frame.time,
                problem: "the replay has no sample at this frame".into(),
            })?;
        samples.push(Sample {
            time: frame.time,
            ..sample.clone()
        });
    }
    Ok(TossPrediction {
        run: toss.run.to_owned(),
        window: toss.window,
        initial: toss.initial.clone(),
        frame_period: toss.frame_period,
        samples,
        steps: simulation.steps.0,
        seconds,
    })
}

/// Predicts one run.
pub fn predict_toss(
    model: &Model,
    setup: &TossSetup,
    run: &Run,
) -> Result<TossPrediction, TossError> {
    simulate_toss(model, setup, &prepare(setup, run)?)
}

/// Predicts every run of `data` in parallel, in the data's order; `done` is called
/// (from worker threads) as each toss finishes. The first failure in the data's order
/// is returned, a data error before any simulation.
pub fn predict_tosses(
    model: &Model,
    data: &Dataset,
    done: impl Fn() + Sync,
) -> Result<Vec<TossPrediction>, TossError> {
    let setup = TossSetup::new(model)?;
    let tosses = (data.runs.iter())
        .map(|run| prepare(&setup, run))
        .collect::<Result<Vec<_>, _>>()?;
    let predictions: Vec<Result<TossPrediction, TossError>> = tosses
        .par_iter()
        .map(|toss| {
            let prediction = simulate_toss(model, &setup, toss);
            done();
            prediction
        })
        .collect();
    // Sequentially, so that the error returned is the first in the data's order.
    predictions.into_iter().collect()
}
