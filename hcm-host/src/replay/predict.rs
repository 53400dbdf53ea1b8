//! The prediction of a toss: the scenario's moving bodies started at the window start
//! in the states [`super::estimate_initial_state`] gives (from each body's own frames), simulated to the toss's last frame, and
//! sampled at the toss's own frame times — the simulator's recorder samples on a grid
//! of one frame period from the start, and every frame of the window must lie on it
//! (frames may be missing, not shifted).
//!
//! Tosses are independent: [`predict_tosses`] checks every toss's window and initial
//! state first (cheap, so that a bad file fails at once), then simulates them in
//! parallel with rayon and returns them in the data's order — the same numbers whatever
//! the thread count.

use super::initial_state::estimate_state;
use super::window::windows;
use super::{InitialState, TossError, TossSetup, Window};
use crate::dataset::{BodyTrack, Dataset, Run, Sample};
use crate::scenario::Model;
use crate::simulate::{simulate_observing, Observed};
use nalgebra::Vector3;
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
    /// The primary body's window, as indices into the run's frames of the body.
    pub window: Window,
    /// The state the primary's replay started from.
    pub initial: InitialState,
    /// The frame period the replay was sampled at (s): the median of the toss's.
    pub frame_period: f64,
    /// The primary's predicted samples, one per frame of the window, at the frames'
    /// times.
    pub samples: Vec<Sample>,
    /// Every other moving body's, in the setup's order.
    pub companions: Vec<BodyPrediction>,
    /// Accepted solver steps.
    pub steps: u64,
    /// Wall-clock time of the simulation (s); not part of the prediction proper.
    pub seconds: f64,
}

impl TossPrediction {
    /// The predicted samples of every moving body, the primary first.
    pub fn tracks(&self) -> Vec<&[Sample]> {
        let companions = self.companions.iter().map(|c| c.samples.as_slice());
        std::iter::once(self.samples.as_slice())
            .chain(companions)
            .collect()
    }

    /// The prediction as a run of the measured-data format: the toss's id, the primary
    /// body (called `primary`) and then every other moving body, each the window's
    /// frames at their recorded times.
    pub fn to_run(&self, primary: &str) -> Run {
        let primary = BodyTrack {
            body: primary.to_owned(),
            samples: self.samples.clone(),
        };
        let companions = self.companions.iter().map(|c| BodyTrack {
            body: c.name.clone(),
            samples: c.samples.clone(),
        });
        Run {
            id: self.run.clone(),
            bodies: std::iter::once(primary).chain(companions).collect(),
        }
    }

    /// Every moving body's window, the primary's first.
    pub fn windows(&self) -> Vec<Window> {
        let companions = self.companions.iter().map(|c| c.window);
        std::iter::once(self.window).chain(companions).collect()
    }
}

/// One companion body's prediction.
#[derive(Clone, Debug)]
pub struct BodyPrediction {
    /// The body's name.
    pub name: String,
    /// Its window, as indices into the run's frames of the body.
    pub window: Window,
    /// The predicted samples, one per frame of the window, at the frames' times.
    pub samples: Vec<Sample>,
    /// The state it started from (assembled onto the scene's joints).
    pub initial: InitialState,
}

/// One moving body of a toss checked and ready to simulate.
#[derive(Clone, Debug)]
pub struct PreparedBody<'a> {
    /// Its recorded track.
    pub(crate) track: &'a BodyTrack,
    /// Its window.
    pub(crate) window: Window,
    /// Its state at the window start.
    pub(crate) initial: InitialState,
    /// Each window frame's index on the grid of frame periods from the window start.
    pub(crate) ticks: Vec<u64>,
}

impl PreparedBody<'_> {
    /// The window's recorded frames.
    pub(crate) fn measured(&self) -> &[Sample] {
        &self.track.samples[self.window.start..]
    }
}

/// A toss checked and ready to simulate.
#[derive(Clone, Debug)]
pub struct PreparedToss<'a> {
    /// Run id.
    pub(crate) run: &'a str,
    /// Every moving body (the setup's movers, in order; the primary first).
    pub(crate) bodies: Vec<PreparedBody<'a>>,
    /// Frame period (s).
    pub(crate) frame_period: f64,
}

impl<'a> PreparedToss<'a> {
    /// The primary body.
    pub(crate) fn primary(&self) -> &PreparedBody<'a> {
        &self.bodies[0]
    }

    /// Every body's recorded window frames, the primary's first.
    pub(crate) fn measured(&self) -> Vec<&[Sample]> {
        self.bodies.iter().map(PreparedBody::measured).collect()
    }

    /// The scores of `prediction` of this toss ([`super::score::score_movers`]).
    pub(crate) fn score(
        &self,
        setup: &TossSetup,
        prediction: &TossPrediction,
    ) -> Result<super::TossScore, TossError> {
        super::score::score_movers(setup, self.run, &self.measured(), &prediction.tracks())
    }
}

/// Checks `run` and finds its window, initial states and frame grid.
pub(crate) fn prepare<'a>(setup: &TossSetup, run: &'a Run) -> Result<PreparedToss<'a>, TossError> {
    let tracks = (setup.movers.iter())
        .map(|mover| {
            run.body(&mover.name).ok_or_else(|| TossError::MissingBody {
                run: run.id.clone(),
                body: mover.name.clone(),
            })
        })
        .collect::<Result<Vec<&BodyTrack>, TossError>>()?;
    let windows = windows(setup, &run.id, &tracks)?;
    let frame_period = median_period(tracks[0]);
    let mut bodies: Vec<PreparedBody<'a>> = Vec::with_capacity(tracks.len());
    for ((track, (window, supported)), mover) in tracks.iter().zip(windows).zip(&setup.movers) {
        // A body resting or sliding on another at the window start is not in free
        // flight: its frames are fitted without gravity.
        let gravity = if supported {
            Vector3::zeros()
        } else {
            setup.gravity
        };
        let initial = estimate_state(&mover.name, gravity, &run.id, track, &window)?;
        let clock = bodies.first().map_or(initial.time, |b| b.initial.time);
        let ticks = ticks(&run.id, &track.samples[window.start..], clock, frame_period)?;
        bodies.push(PreparedBody {
            track,
            window,
            initial,
            ticks,
        });
    }
    assemble_bodies(setup, &mut bodies);
    Ok(PreparedToss {
        run: &run.id,
        bodies,
        frame_period,
    })
}

/// The bodies' start states assembled onto the setup's joints (`assembly.rs`); no
/// change without joints.
pub(crate) fn assemble_bodies(setup: &TossSetup, bodies: &mut [PreparedBody<'_>]) {
    if setup.joints.is_empty() {
        return;
    }
    let mut states: Vec<_> = bodies.iter().map(|b| b.initial.clone()).collect();
    super::assembly::assemble(setup, &mut states);
    for (body, state) in bodies.iter_mut().zip(states) {
        body.initial = state;
    }
}

/// Each frame's index on the grid of `frame_period` (s) from `clock` (s, the window
/// start), refused where a frame lies off the grid.
fn ticks(
    run: &str,
    frames: &[Sample],
    clock: f64,
    frame_period: f64,
) -> Result<Vec<u64>, TossError> {
    frames
        .iter()
        .map(|sample| {
            let periods = (sample.time - clock) / frame_period;
            let tick = periods.round();
            if (periods - tick).abs() > CLOCK_TOLERANCE || tick < 0.0 {
                return Err(TossError::Frame {
                    run: run.to_owned(),
                    time: sample.time,
                    problem: format!(
                        "the frame lies {periods:.4} frame periods ({frame_period} s, the \
                         toss's median) after the window start, not a whole number: a toss's \
                         frames, of every moving body, must come on one clock"
                    ),
                });
            }
            Ok(tick as u64)
        })
        .collect::<Result<Vec<u64>, TossError>>()
        .and_then(|ticks| match (ticks.first(), frames.first()) {
            // A body whose first window frame comes later than the window start would
            // be started there from a state of another instant.
            (Some(&first), Some(frame)) if first > 0 => Err(TossError::Frame {
                run: run.to_owned(),
                time: frame.time,
                problem: format!(
                    "the body's first frame in the window comes {first} frame period(s) \
                     after the window start; every moving body needs a frame there"
                ),
            }),
            _ => Ok(ticks),
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

/// `model` with every moving body started at `toss`'s initial state, ending half a
/// period after the last frame and recording only the moving bodies, once per frame
/// period.
pub fn replay_model(model: &Model, setup: &TossSetup, toss: &PreparedToss<'_>) -> Model {
    let mut replay = model.clone();
    for (mover, prepared) in setup.movers.iter().zip(&toss.bodies) {
        let body = &mut replay.bodies[mover.body];
        let initial = &prepared.initial;
        body.position = initial.position;
        body.orientation = initial.orientation;
        body.velocity = initial.velocity;
        body.angular_velocity = initial.angular_velocity;
    }
    let last = (toss.bodies.iter())
        .filter_map(|b| b.ticks.last().copied())
        .max()
        .unwrap_or(0) as f64;
    let scenario = &mut replay.scenario;
    scenario.simulation.end_time = (last + 0.5) * toss.frame_period;
    scenario.simulation.stop_after_contacts = 0;
    scenario.record.contact_sample_period = toss.frame_period;
    scenario.record.flight_sample_period = toss.frame_period;
    scenario.record.contact_margin = 0.0;
    scenario.record.bodies = setup.movers.iter().map(|m| m.name.clone()).collect();
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
    let simulation = simulate_observing(&replay, Observed::Trajectory).map_err(|error| {
        TossError::Simulation {
            run: toss.run.to_owned(),
            error,
        }
    })?;
    let seconds = started.elapsed().as_secs_f64();
    let mut predicted = Vec::with_capacity(toss.bodies.len());
    for (mover, prepared) in setup.movers.iter().zip(&toss.bodies) {
        let simulated = (simulation.run.body(&mover.name)).map_or(&[][..], |t| &t.samples[..]);
        predicted.push(BodyPrediction {
            name: mover.name.clone(),
            window: prepared.window,
            samples: on_frames(toss, prepared, simulated)?,
            initial: prepared.initial.clone(),
        });
    }
    let mut bodies = predicted.into_iter();
    let primary = bodies.next().map(|b| b.samples).unwrap_or_default();
    Ok(TossPrediction {
        run: toss.run.to_owned(),
        window: toss.primary().window,
        initial: toss.primary().initial.clone(),
        frame_period: toss.frame_period,
        samples: primary,
        companions: bodies.collect(),
        steps: simulation.steps.0,
        seconds,
    })
}

/// The `simulated` samples of one body at `prepared`'s window frames (their times).
fn on_frames(
    toss: &PreparedToss<'_>,
    prepared: &PreparedBody<'_>,
    simulated: &[Sample],
) -> Result<Vec<Sample>, TossError> {
    let frames = prepared.measured();
    let mut samples = Vec::with_capacity(frames.len());
    let mut next = simulated.iter().peekable();
    for (frame, &tick) in frames.iter().zip(&prepared.ticks) {
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
    Ok(samples)
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
