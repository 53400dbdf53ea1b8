//! What of a scenario the tosses use: its one moving body (a box or a sphere), the
//! fixed bodies it can touch, and the lengths the window and the scores are measured
//! in.

use super::partner::Partner;
use super::TossError;
use crate::dataset::{Channel, Dataset, Need, Requirement};
use crate::scenario::{Model, Shape};
use nalgebra::Vector3;

/// What `hcm predict` (and the identification from motion) needs of a toss's data: the
/// camera's pose in every frame. Velocities are re-estimated from the poses; force is
/// never read.
pub const TOSSES: Requirement = Requirement {
    command: "hcm predict",
    channels: &[
        (Channel::Position, Need::EveryRow),
        (Channel::Orientation, Need::EveryRow),
    ],
    because: "each toss's window, initial state and scores are read from the recorded \
              poses, frame by frame",
};

/// The replayed body and the fixed bodies it can touch, read from a model.
#[derive(Clone, Debug, PartialEq)]
pub struct TossSetup {
    /// Index of the moving body in the model.
    pub(crate) body: usize,
    /// Its name (the data's `body` column).
    pub name: String,
    /// The fixed bodies it has a contact with, as the scenario places them (the window
    /// is measured from these, whatever a fit later moves).
    pub(crate) partners: Vec<Partner>,
    /// Circumscribed radius: the largest distance from the centre to a point of the
    /// body (m); 0.0524·√3 m for the ContactNets cube, the radius for a sphere. Farther
    /// from every partner, nothing touches.
    pub radius: f64,
    /// Width the position error is divided by: twice the largest half extent, or the
    /// diameter (m); the cube's side, 0.1048 m.
    pub width: f64,
    /// Gravity (m/s², world frame).
    pub(crate) gravity: Vector3<f64>,
}

impl TossSetup {
    /// The setup of `model`: exactly one moving body, a box or a sphere, in contact
    /// with at least one fixed body (a plane, a box, a sphere or a compound).
    pub fn new(model: &Model) -> Result<TossSetup, TossError> {
        let fail = |problem: String| TossError::Setup {
            scenario: model.scenario.name.clone(),
            problem,
        };
        let moving: Vec<usize> = (0..model.bodies.len())
            .filter(|&b| !model.bodies[b].fixed)
            .collect();
        let [body] = moving[..] else {
            return Err(fail(format!(
                "a replay from motion follows one moving body, and this scenario has {}; \
                 with force data (fx, fy, fz of a body), `hcm identify` fits a contact \
                 between moving bodies at their recorded poses instead",
                moving.len()
            )));
        };
        let tossed = &model.bodies[body];
        let (radius, width) = match tossed.shape {
            Shape::Box { half_extents } => (half_extents.norm(), 2.0 * half_extents.max()),
            Shape::Sphere { radius } => (radius, 2.0 * radius),
            _ => {
                return Err(fail(format!(
                    "body `{}` must be a box or a sphere to be replayed from its poses",
                    tossed.name
                )))
            }
        };
        let partners: Vec<Partner> = (model.contacts.iter())
            .filter(|c| c.body_1 == body || c.body_2 == body)
            .map(|c| c.body_1 + c.body_2 - body)
            .map(|other| Partner::of(model, other))
            .collect();
        if partners.is_empty() {
            return Err(fail(format!(
                "body `{}` has no contact with a fixed body to land on; add a \
                 [[contact]] with its bodies",
                tossed.name
            )));
        }
        Ok(TossSetup {
            body,
            name: tossed.name.clone(),
            partners,
            radius,
            width,
            gravity: model.gravity,
        })
    }

    /// Checks that `data` (read from `file`) holds the tossed body's pose in every frame.
    pub fn check_data(&self, file: &str, model: &Model, data: &Dataset) -> Result<(), TossError> {
        let contacts: Vec<usize> = (0..model.contacts.len())
            .filter(|&c| [model.contacts[c].body_1, model.contacts[c].body_2].contains(&self.body))
            .collect();
        Ok(data.require(file, model, &contacts, &TOSSES)?)
    }

    /// Clearance of a centre at `position` (m) from the nearest partner (m): a plane's
    /// height above its reference point along its normal, another shape's distance
    /// to its surface ([`Partner::clearance`]).
    pub fn clearance(&self, position: &Vector3<f64>) -> f64 {
        (self.partners.iter())
            .map(|p| p.clearance(position))
            .fold(f64::INFINITY, f64::min)
    }
}
