//! Replaying recorded motion: a body filmed while it is tossed onto (or slid over) fixed
//! bodies (a table, a ramp, a bin) — position and orientation per camera frame, no
//! force — replayed in the 3D simulator from each recording's *window* start, and the
//! prediction scored against the recorded poses. A recording is called a toss here,
//! whatever the motion.
//!
//! - [`window`]: where a toss's window starts — [`LEAD_FRAMES`] frames before the
//!   body's centre first comes within its circumscribed radius of a partner (below
//!   that a corner can touch; 0.0524·√3 m for the ContactNets cube).
//! - [`initial_state`]: the state the replay starts from, re-estimated from the
//!   free-flight frames up to the window start (a parabola under gravity for the
//!   position, constant angular velocity for the orientation).
//! - [`predict`]: the replay of one toss, sampled at the toss's frame times, and of
//!   every toss of a data file in parallel.
//! - [`score`]: position error (% of the body's width) and rotation error (degrees),
//!   per toss and over tosses; [`baseline`]: the frozen-pose baseline scored the same
//!   way; [`evaluation`]: every toss of a file predicted and scored.
//! - [`setup`]: what of a scenario the tosses need (its moving bodies, the bodies each
//!   touches; several moving bodies are replayed together, each from its own frames,
//!   and scored each on its own width); [`partner`]: a fixed body's clearance and the shift and tilt a
//!   tracker's calibration error makes to it.

mod assembly;
mod baseline;
mod ensemble;
mod evaluation;
mod face;
mod forecast;
mod initial_state;
mod partner;
mod path_forecast;
mod predict;
mod score;
mod scores_file;
mod setup;
mod window;
pub use crate::scenario::{shift_surface, tilt_surface};
pub(crate) use assembly::assemble;
pub use initial_state::orientation;
pub use path_forecast::{band_shares, forecast_paths, summarize_paths, PathForecast, PathSummary};
pub use path_forecast::{BAND_LEVELS, CALIBRATION_LEVELS};
pub(crate) use predict::prepare;
pub(crate) use predict::simulate_toss;
pub use predict::{replay_model, PreparedToss};
pub use score::rotation_angle;

pub use baseline::frozen_pose;
pub use ensemble::{
    calibrate_scatter, forecast_faces, scatter_all, scatter_contact, summarize_faces, FaceForecast,
    FaceSummary, Spread, SCATTERS,
};
pub use evaluation::{
    evaluate_tosses, predicted_dataset, summarize, summarize_bodies, EvaluationSummary,
    TossEvaluation,
};
pub use face::{Face, FACES};
pub(crate) use forecast::forecast_toss_paths;
pub use forecast::{forecast_tosses, TossForecast};
pub use initial_state::{estimate_initial_state, InitialState, StateSource};
pub use predict::{predict_toss, predict_tosses, BodyPrediction, TossPrediction};
pub use score::{score_movers, score_toss, BodyScore, Summary, TossScore};
pub use scores_file::write_scores;
pub use setup::{Mover, TossSetup};
pub use window::{find_window, find_windows, Window, LEAD_FRAMES};

use crate::dataset::DataError;
use crate::scenario::ScenarioError;
use crate::simulate::SimulationError;

/// Why a toss could not be predicted or scored. Every variant names the run, and the
/// data's or the scenario's terms.
#[derive(Debug, thiserror::Error)]
pub enum TossError {
    /// The scenario does not describe bodies tossed onto others.
    #[error("scenario `{scenario}`: {problem}")]
    Setup {
        /// The scenario's name.
        scenario: String,
        /// What it lacks for a toss, in words.
        problem: String,
    },
    /// The data lack what the prediction needs.
    #[error(transparent)]
    Data(#[from] DataError),
    /// The scenario (with a physics file or candidate parameters) is invalid.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// A run has no track of the tossed body.
    #[error("run `{run}` has no samples of body `{body}` (the scenario's moving body); the data's `body` column must name it")]
    MissingBody {
        /// The run's id.
        run: String,
        /// The tossed body's name.
        body: String,
    },
    /// The body's centre never comes near enough to a fixed body to touch it.
    #[error(
        "run `{run}`: the centre of `{body}` never comes within {threshold} m of a fixed body \
         (its lowest is {lowest} m at t = {lowest_time} s), so no contact and no window; \
         leave the run out or check the fixed bodies' positions (the table height)"
    )]
    NoContact {
        /// The run's id.
        run: String,
        /// The tossed body's name.
        body: String,
        /// Its circumscribed radius (m): nearer than this, the centre may touch.
        threshold: f64,
        /// The centre's least distance to a fixed body over the run (m).
        lowest: f64,
        /// When it was that near (s).
        lowest_time: f64,
    },
    /// A frame's pose cannot be used.
    #[error("run `{run}`, t = {time} s: {problem}")]
    Frame {
        /// The run's id.
        run: String,
        /// The frame's time (s).
        time: f64,
        /// What is wrong with its pose, in words.
        problem: String,
    },
    /// The replay failed. (The simulator's error is part of the message, not a
    /// `source`, so that a chain printed with `{:#}` does not repeat it.)
    #[error("run `{run}`: the replay from the window start failed: {error}")]
    Simulation {
        /// The run's id.
        run: String,
        /// Why the simulation of the replay failed.
        error: SimulationError,
    },
}
