//! What of a scenario the tosses use: its one moving body (a box), the fixed plane it
//! lands on, and the lengths the window and the scores are measured in.

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

/// The tossed body and its plane, read from a model.
#[derive(Clone, Debug, PartialEq)]
pub struct TossSetup {
    /// Index of the moving body in the model.
    pub(crate) body: usize,
    /// Its name (the data's `body` column).
    pub name: String,
    /// The plane body's reference point (m, world frame): the table as the data's frame
    /// has it. The contact's surface lies `offset` from it along the normal; the windows
    /// are measured from this point, not from the surface, so that fitting the table's
    /// height (the offset) leaves every toss's window, and the frames scored, as they are.
    pub(crate) plane_point: Vector3<f64>,
    /// The plane's unit outward normal (world frame).
    pub(crate) plane_normal: Vector3<f64>,
    /// Circumscribed radius: the largest distance from the centre to a corner (m);
    /// 0.0524·√3 m for the ContactNets cube. Farther from the plane, nothing touches.
    pub radius: f64,
    /// Width the position error is divided by: twice the largest half extent (m); the
    /// cube's side, 0.1048 m.
    pub width: f64,
    /// Gravity (m/s², world frame).
    pub(crate) gravity: Vector3<f64>,
}

impl TossSetup {
    /// The setup of `model`: exactly one moving body, a box, in contact with a fixed
    /// plane.
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
                "a toss has one moving body, and this scenario has {}",
                moving.len()
            )));
        };
        let tossed = &model.bodies[body];
        let Shape::Box { half_extents } = tossed.shape else {
            return Err(fail(format!(
                "body `{}` must be a box (shape = {{ box = {{ half_extents = [a, b, c] }} }}) \
                 to be tossed",
                tossed.name
            )));
        };
        let plane = model
            .contacts
            .iter()
            .filter(|c| c.body_1 == body || c.body_2 == body)
            .map(|c| c.body_1 + c.body_2 - body)
            .find_map(|other| match model.bodies[other].shape {
                Shape::Plane { normal, .. } => {
                    let fixed = &model.bodies[other];
                    Some((fixed.position, fixed.orientation * normal))
                }
                _ => None,
            })
            .ok_or_else(|| {
                fail(format!(
                    "body `{}` has no contact with a fixed plane (the table) to land on",
                    tossed.name
                ))
            })?;
        Ok(TossSetup {
            body,
            name: tossed.name.clone(),
            plane_point: plane.0,
            plane_normal: plane.1,
            radius: half_extents.norm(),
            width: 2.0 * half_extents.max(),
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

    /// Height of a centre at `position` (m) above the plane's reference point, along
    /// its normal (m).
    pub fn height(&self, position: &Vector3<f64>) -> f64 {
        self.plane_normal.dot(&(position - self.plane_point))
    }
}
