//! Which residual a model learns — one choice, made from the evidence and, for a wrench,
//! the inputs asked for — and its one training call. Every kind yields a [`Trained`]: the
//! network, its int8 twin, its envelope, the rows it learned from and what it explains.

use super::{
    train_force_residual, train_joint_residual, train_motion_residual, train_point_residual,
    train_wrench_residual, ResidualError, ResidualSettings, Trained, HORIZON,
};
use crate::dataset::{Dataset, Evidence};
use crate::progress::Progress;
use crate::scenario::Model;

/// A residual of the contact model (Eq 12) and what it reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResidualKind {
    /// A 1D contact's normal force from δ, δ̇ and δ̇0 (N), on the line force.
    Force,
    /// The moving body's wrench (N, N·m) from its 13 state components.
    Wrench,
    /// Each touching point's force and couple from its contact-frame features (δ, δ̇,
    /// slip speed, spin and rolling rate), on the wrench at the recorded poses.
    Point,
    /// The same per-point residual learned from poses alone (the replayed frames'
    /// missing momentum, over [`HORIZON`] frames).
    Motion,
    /// A mechanism's joint torque (N·m) from the joint's angle and rate, learned from
    /// poses alone (the joint angle the replayed frames miss, over [`HORIZON`] frames).
    Joint,
}

impl ResidualKind {
    /// The kind for `evidence`: the line force's, the per-point one on a wrench (or the
    /// state one where `state` asks for it), the one from motion on poses — the joint's
    /// torque on a mechanism's poses (`joints`: the model has joints).
    pub fn of(evidence: Evidence, state: bool, joints: bool) -> ResidualKind {
        match evidence {
            Evidence::LineForce => ResidualKind::Force,
            Evidence::Wrench if state => ResidualKind::Wrench,
            Evidence::Wrench => ResidualKind::Point,
            Evidence::Poses if joints => ResidualKind::Joint,
            Evidence::Poses => ResidualKind::Motion,
        }
    }

    /// This residual of contact `c` of `pm2` (a joint's: of joint `c`) trained on
    /// `training` (for a wrench, on the samples before contact event `events`),
    /// reporting to `progress`.
    pub fn train(
        self,
        (pm2, training, c): (&Model, &Dataset, usize),
        events: usize,
        settings: &ResidualSettings,
        progress: &dyn Progress,
    ) -> Result<Trained, ResidualError> {
        match self {
            ResidualKind::Force => train_force_residual(pm2, training, c, settings, progress),
            ResidualKind::Wrench => {
                train_wrench_residual(pm2, training, c, events, settings, progress)
            }
            ResidualKind::Point => {
                train_point_residual(pm2, training, c, events, settings, progress)
            }
            ResidualKind::Motion => {
                train_motion_residual(pm2, training, c, HORIZON, settings, progress)
            }
            ResidualKind::Joint => {
                train_joint_residual(pm2, training, c, HORIZON, settings, progress)
            }
        }
    }

    /// What the network maps, for a report.
    pub fn describe(self) -> &'static str {
        match self {
            ResidualKind::Force => "the force residual (δ, δ̇, δ̇0 → normal force)",
            ResidualKind::Wrench => {
                "the wrench residual (13 state inputs → force and torque on the moving body)"
            }
            ResidualKind::Point => {
                "the contact-frame residual (5 inputs per touching point → its force and couple)"
            }
            ResidualKind::Motion => {
                "the contact-frame residual from motion (5 inputs per touching point → its force and couple)"
            }
            ResidualKind::Joint => {
                "the joint's torque residual from motion (its angle and rate → the torque on the child)"
            }
        }
    }
}
