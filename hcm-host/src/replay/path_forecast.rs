//! A toss forecast as a distribution of paths: the members `ensemble.rs` draws (start
//! states from the free-flight fits' covariance, the contact's parameters scattered),
//! kept frame by frame rather than reduced to the final face, and scored against the
//! recorded path by proper scores (`crate::numerics::scores`).
//!
//! Per toss, over the primary body's window frames:
//! - position: the energy score of the members' centres for the recorded centre,
//!   E‖X − y‖ − ½·E‖X − X′‖, in % of the body's width;
//! - rotation: the same form with the rotation angle between two orientations as the
//!   distance, in degrees;
//!
//! each the mean over the frames. With one member they are the toss's position and
//! rotation errors ([`super::TossScore`]), so a single replay and an ensemble are scored
//! by one rule and compare toss by toss. And the coverage: per frame and axis, whether
//! the recorded coordinate lies inside the members' central 50 % and 90 % bands (an
//! ensemble drawn like the outcome holds it the level's share, or (M − 1)/(M + 1) with
//! fewer than 19 members for 90 %: [`crate::numerics::scores::central_band`]).
//!
//! The members are those of [`super::forecast_faces`] for the same spread: the same
//! draws, in the same order, from the toss's own stream of the seed.

use super::ensemble::{each_toss, member_replays, Spread};
use super::initial_state::orientation;
use super::predict::{PreparedToss, TossPrediction};
use super::score::rotation_angle;
use super::{Summary, TossError, TossSetup};
use crate::dataset::{Dataset, Sample};
use crate::numerics::scores::{self, energy_parts_by, euclidean, Coverage};
use crate::scenario::Model;

/// The central bands whose coverage is printed and written per toss (–).
pub const BAND_LEVELS: [f64; 2] = [0.5, 0.9];
/// The central bands whose coverage is counted (–): every tenth and 95 %, the
/// calibration curve's points ([`BAND_LEVELS`] among them).
pub const CALIBRATION_LEVELS: [f64; 10] = [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 0.95];

/// The shares of `coverage`'s outcomes inside the bands of [`BAND_LEVELS`] (–).
pub fn band_shares(coverage: &Coverage) -> [f64; 2] {
    BAND_LEVELS.map(|level| coverage.share_at(level))
}

/// One toss's path forecast and its scores.
#[derive(Clone, Debug, PartialEq)]
pub struct PathForecast {
    /// Run id.
    pub run: String,
    /// Members whose replay ran (–).
    pub members: usize,
    /// Members whose replay failed, left out (–).
    pub failed: usize,
    /// Frames scored (the primary body's window) (–).
    pub frames: usize,
    /// Mean energy score of the centre over the frames, % of the body's width.
    pub position: f64,
    /// Mean energy score of the orientation over the frames (degrees).
    pub rotation: f64,
    /// The energy scores' spread terms ½·E‖X − X′‖ (1/M²), means over the frames:
    /// position (% of the width) and rotation (°); 0 for one member.
    pub spread: [f64; 2],
    /// Mean CRPS of the centre's x, y and z over the frames, % of the body's width
    /// (with one member, the mean absolute error of each coordinate).
    pub crps: [f64; 3],
    /// The recorded coordinates inside the members' bands of [`BAND_LEVELS`], counted
    /// per frame and axis.
    pub coverage: Coverage,
}

impl PathForecast {
    /// The toss's score: position plus rotation (% + °), the sum `hcm predict` ranks
    /// by.
    pub fn score(&self) -> f64 {
        self.position + self.rotation
    }

    /// The same sum with the "fair" spread term, M/(M − 1) on it
    /// ([`crate::numerics::scores::energy_parts_by`]): an unbiased estimate of the
    /// score of the distribution the members come from (% + °); the score itself for
    /// one member. What a search choosing a spread compares.
    pub fn fair_score(&self) -> f64 {
        if self.members < 2 {
            return self.score();
        }
        self.score() - (self.spread[0] + self.spread[1]) / (self.members - 1) as f64
    }
}

/// The path forecasts over tosses.
#[derive(Clone, Debug, PartialEq)]
pub struct PathSummary {
    /// Tosses (–).
    pub tosses: usize,
    /// The per-toss position scores (% of the width).
    pub position: Summary,
    /// The per-toss rotation scores (°).
    pub rotation: Summary,
    /// The per-toss CRPS of x, y and z, means over tosses (% of the width).
    pub crps: [f64; 3],
    /// Every toss's coverage counts pooled.
    pub coverage: Coverage,
}

/// The path forecast of every toss of `data` under `model`, `spread.members` replays
/// each (see the module documentation), in the data's order; tosses run in parallel,
/// `done` called as each finishes. The same seed gives the same bits on any number of
/// threads.
pub fn forecast_paths(
    model: &Model,
    data: &Dataset,
    spread: Spread,
    done: impl Fn() + Sync,
) -> Result<Vec<PathForecast>, TossError> {
    let setup = TossSetup::new(model)?;
    let forecast = |toss: &PreparedToss<'_>, stream| {
        let members: Vec<_> = member_replays(model, &setup, toss, &spread, stream);
        score_paths(&setup, toss, &members)
    };
    each_toss(&setup, data, forecast, done)
}

/// The scores of `forecasts` over tosses.
pub fn summarize_paths(forecasts: &[PathForecast]) -> PathSummary {
    let of =
        |f: fn(&PathForecast) -> f64| Summary::of(&forecasts.iter().map(f).collect::<Vec<_>>());
    let mut coverage = Coverage::new(&CALIBRATION_LEVELS);
    for f in forecasts {
        coverage.merge(&f.coverage);
    }
    let n = forecasts.len().max(1) as f64;
    let crps = std::array::from_fn(|k| forecasts.iter().map(|f| f.crps[k]).sum::<f64>() / n);
    PathSummary {
        tosses: forecasts.len(),
        position: of(|f| f.position),
        rotation: of(|f| f.rotation),
        crps,
        coverage,
    }
}

/// The scores of the primary body's paths of `members` (each one sample per window
/// frame; a failed member left out and counted) against its recorded frames.
pub(super) fn score_paths(
    setup: &TossSetup,
    toss: &PreparedToss<'_>,
    members: &[Result<TossPrediction, TossError>],
) -> Result<PathForecast, TossError> {
    let paths: Vec<&[Sample]> = (members.iter().flatten())
        .map(|m| m.samples.as_slice())
        .collect();
    let mover = &setup.movers[0];
    let recorded = toss.primary().measured();
    let turn = |s: &Sample| orientation(&mover.name, toss.run, s);
    let mut coverage = Coverage::new(&CALIBRATION_LEVELS);
    let (mut position, mut rotation, mut crps) = (0.0, 0.0, [0.0; 3]);
    let mut spread = [0.0; 2];
    for (i, frame) in recorded.iter().enumerate() {
        let centres: Vec<[f64; 3]> = paths.iter().map(|p| p[i].position).collect();
        let points: Vec<&[f64]> = centres.iter().map(|c| &c[..]).collect();
        let (error, half) = energy_parts_by(&points, &frame.position[..], euclidean);
        (position, spread[0]) = (position + (error - half), spread[0] + half);
        let turns = (paths.iter().map(|p| turn(&p[i]))).collect::<Result<Vec<_>, _>>()?;
        let (error, half) = energy_parts_by(&turns, &turn(frame)?, rotation_angle);
        (rotation, spread[1]) = (rotation + (error - half), spread[1] + half);
        for axis in 0..3 {
            let coordinate: Vec<f64> = centres.iter().map(|c| c[axis]).collect();
            crps[axis] += scores::crps(&coordinate, frame.position[axis]);
            coverage.add(&coordinate, frame.position[axis]);
        }
    }
    let n = recorded.len().max(1) as f64;
    let percent = |sum: f64| 100.0 * sum / n / mover.width;
    Ok(PathForecast {
        run: toss.run.to_owned(),
        members: paths.len(),
        failed: members.len() - paths.len(),
        frames: recorded.len(),
        position: percent(position),
        rotation: rotation.to_degrees() / n,
        spread: [percent(spread[0]), spread[1].to_degrees() / n],
        crps: crps.map(percent),
        coverage,
    })
}
