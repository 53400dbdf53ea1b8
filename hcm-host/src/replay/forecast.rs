//! A toss forecast by one ensemble with everything it gives at once: each member's
//! predicted path (what `hcm predict --members` writes), the paths' proper scores
//! ([`super::path_forecast`]) and, for a box, the final faces' ([`super::ensemble`]) —
//! from the same members, drawn once.

use super::ensemble::{each_toss, forecast_face, has_faces, member_replays, Spread};
use super::path_forecast::score_paths;
use super::predict::PreparedToss;
use super::{FaceForecast, PathForecast, TossError, TossPrediction, TossSetup};
use crate::dataset::Dataset;
use crate::scenario::Model;

/// One toss forecast by an ensemble.
#[derive(Clone, Debug)]
pub struct TossForecast {
    /// Each member's prediction, in draw order (member 0 first); None where its replay
    /// failed.
    pub members: Vec<Option<TossPrediction>>,
    /// The paths' scores.
    pub paths: PathForecast,
    /// The final face's forecast, when asked for.
    pub face: Option<FaceForecast>,
}

/// Every toss of `data` forecast by `spread.members` members of `model` (drawn as
/// [`super::forecast_paths`] draws them, the same bits), with the final faces when
/// `faces` (the primary body must then be a box); tosses in parallel, in the data's
/// order, `done` called as each finishes.
pub fn forecast_tosses(
    model: &Model,
    data: &Dataset,
    spread: Spread,
    faces: bool,
    done: impl Fn() + Sync,
) -> Result<Vec<TossForecast>, TossError> {
    let setup = TossSetup::new(model)?;
    if faces {
        has_faces(model, &setup)?;
    }
    let forecast = |toss: &PreparedToss<'_>, stream| {
        let members = member_replays(model, &setup, toss, &spread, stream);
        let paths = score_paths(&setup, toss, &members)?;
        let face = faces
            .then(|| forecast_face(model, &setup, toss, &members))
            .transpose()?;
        Ok(TossForecast {
            members: members.into_iter().map(Result::ok).collect(),
            paths,
            face,
        })
    };
    each_toss(&setup, data, forecast, done)
}

/// The path forecast of one prepared toss by `spread`'s members of `model`, drawn from
/// stream `stream` of its seed: what a diagnosis scores a model that varies by. None
/// when every member's replay failed.
pub(crate) fn forecast_toss_paths(
    model: &Model,
    setup: &TossSetup,
    toss: &PreparedToss<'_>,
    spread: &Spread,
    stream: u64,
) -> Option<PathForecast> {
    let members = member_replays(model, setup, toss, spread, stream);
    let paths = score_paths(setup, toss, &members).ok()?;
    (paths.members > 0).then_some(paths)
}
