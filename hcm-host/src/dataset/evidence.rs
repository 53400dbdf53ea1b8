//! What measured data can show about one contact of a model, decided once from the
//! model and the data's channels: every stage that fits, trains on, judges or diagnoses
//! a model against data takes its path from this value, and the command line only
//! reads it.

use super::inventory::motion_only;
use super::needs::Requirement;
use super::{DataError, Dataset};
use crate::scenario::Model;

/// The kind of evidence a data file holds about one contact of a model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evidence {
    /// A 1D contact: the contact force sampled along the line of centres, the motion
    /// reconstructed at the force samples from camera frames (a one-point manifold).
    LineForce,
    /// A rigid (3D) contact with a force channel: the contact wrench (N, N·m) at
    /// measured poses of the moving body.
    Wrench,
    /// A rigid (3D) contact seen by a camera alone: poses, no force or torque on
    /// either body; a model is judged by replaying the runs from their poses.
    Poses,
}

/// What a command does with the data, for the channels it needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DataUse {
    /// Fit a law to the force along the motion (least squares on the samples).
    Identify,
    /// Fit a law to whole contact events by replaying them (the genetic algorithm on
    /// a rigid contact's event indicators).
    IdentifyEvents,
    /// Train the residual network on the force the model gets wrong.
    Train,
    /// Name what the model misses.
    Diagnose,
    /// Judge the model's indicators (and the HCM's) against the data.
    Evaluate,
    /// Compute the indicators of each contact event in the data.
    Indicators,
}

impl Evidence {
    /// The evidence `data` hold about contact `c` of `model`: [`Evidence::LineForce`]
    /// for a 1D scene, and for a rigid one [`Evidence::Poses`] when the moving body's
    /// poses are recorded with no force or torque on either body, [`Evidence::Wrench`]
    /// otherwise (a missing channel is then reported by [`Evidence::requirement`]'s
    /// check, naming it).
    pub fn of(model: &Model, data: &Dataset, c: usize) -> Self {
        if !model.is_rigid() {
            Evidence::LineForce
        } else if motion_only(data, model, c) {
            Evidence::Poses
        } else {
            Evidence::Wrench
        }
    }

    /// The evidence a simulation of `model` records (`hcm simulate`, `hcm generate`):
    /// force along the line of centres for a 1D scene, full states and the contact
    /// wrench on every row for a rigid one.
    pub fn simulated(model: &Model) -> Self {
        if model.is_rigid() {
            Evidence::Wrench
        } else {
            Evidence::LineForce
        }
    }

    /// The channels `what` needs of data holding this evidence, for
    /// [`Dataset::require`]; `None` where the path checks the data itself (the replay
    /// of poses reads every toss and names the one it cannot use).
    pub fn requirement(self, what: DataUse) -> Option<&'static Requirement> {
        use DataUse as U;
        Some(match (self, what) {
            (Evidence::LineForce, U::Identify | U::IdentifyEvents) => &Requirement::IDENTIFY,
            (Evidence::LineForce, U::Train) => &Requirement::TRAIN,
            (Evidence::LineForce, U::Diagnose) => &Requirement::DIAGNOSE,
            (Evidence::LineForce, U::Evaluate) => &Requirement::EVALUATE,
            (Evidence::LineForce, U::Indicators) => &Requirement::INDICATORS,
            (Evidence::Poses, U::Identify | U::Diagnose | U::Evaluate | U::Train) => return None,
            (_, U::Identify | U::Diagnose) => &Requirement::IDENTIFY_RIGID_SAMPLES,
            (_, U::IdentifyEvents) => &Requirement::IDENTIFY_RIGID,
            (_, U::Train) => &Requirement::TRAIN_RIGID,
            (_, U::Evaluate | U::Indicators) => &Requirement::INDICATORS_RIGID,
        })
    }
}

impl Dataset {
    /// Checks that these data (read from `file`) hold what `what` needs of `evidence` on
    /// contact `c` of `model` ([`Evidence::requirement`]); nothing to check where the
    /// path checks the data itself.
    pub fn require_for(
        &self,
        file: &str,
        model: &Model,
        c: usize,
        evidence: Evidence,
        what: DataUse,
    ) -> Result<(), DataError> {
        match evidence.requirement(what) {
            Some(needs) => self.require(file, model, &[c], needs),
            None => Ok(()),
        }
    }
}
