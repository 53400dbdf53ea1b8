//! The contact-frame residual learned from motion alone: the rows of
//! [`super::motion_samples`] — the pose the physics misses a few frames after each
//! recorded state, against its touching points' levers along its own path — trained by
//! the contact-frame residual's stages ([`super::point_residual::train_point_rows`]).
//! `hcm train` runs it on a camera's data (poses, no force).

use super::motion_samples::motion_rows;
use super::point_residual::train_point_rows;
use super::ResidualError;
use super::ResidualSettings;
use super::Trained;
use crate::dataset::Dataset;
use crate::progress::Progress;
use crate::scenario::Model;

/// The units of the motion rows' targets: the wrench-impulse moments that move the free
/// body to the recorded pose.
pub const MOTION_UNITS: &str = "N·s², N·m·s²";

/// Frames over which the physics' miss is measured, by default (–): two frames hold a
/// whole contact at the ContactNets tracker's 148 Hz.
pub const HORIZON: usize = 2;

/// The contact-frame residual of contact `c` of `physics` (the fitted physics, its
/// residual left out) learned from the recorded poses of `training` over `horizon`
/// frames, then its int8 twin, seeded with `settings.seed`.
pub fn train_motion_residual(
    physics: &Model,
    training: &Dataset,
    c: usize,
    horizon: usize,
    settings: &ResidualSettings,
    progress: &dyn Progress,
) -> Result<Trained, ResidualError> {
    let (rows, _) = motion_rows(physics, training, c, horizon)?;
    train_point_rows(&rows, c, settings, MOTION_UNITS, progress)
}
