//! What of a scenario the tosses use: its moving bodies (boxes or spheres), the bodies
//! each can touch, and the lengths the window and the scores are measured in.
//!
//! The first moving body is the *primary*: its name is the one a single-body command
//! prints and its frames index the window. Every other moving body is a *companion*:
//! replayed from its own frames beside the primary and scored the same way (several
//! moving bodies from a camera's poses alone).

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

/// One moving body of a toss.
#[derive(Clone, Debug, PartialEq)]
pub struct Mover {
    /// Index of the body in the model.
    pub(crate) body: usize,
    /// Its name (the data's `body` column).
    pub name: String,
    /// Its shape (body frame), for the other movers' clearance from it.
    pub(crate) shape: Shape,
    /// Circumscribed radius: the largest distance from the centre to a point of the
    /// body (m); 0.0524·√3 m for the ContactNets cube, the radius for a sphere.
    pub radius: f64,
    /// Width its position error is divided by: twice the largest half extent, or the
    /// diameter (m); the cube's side, 0.1048 m.
    pub width: f64,
    /// The fixed bodies it has a contact with, as the scenario places them.
    pub(crate) partners: Vec<Partner>,
    /// The other movers (indices into [`TossSetup::movers`]) it has a contact with.
    pub(crate) touches: Vec<usize>,
    /// Its mass (kg), for a mechanism's centre of mass (`assembly.rs`).
    pub(crate) mass: f64,
}

/// The replayed bodies and the bodies they can touch, read from a model.
#[derive(Clone, Debug, PartialEq)]
pub struct TossSetup {
    /// Index of the primary moving body in the model.
    pub(crate) body: usize,
    /// The primary's name (the data's `body` column).
    pub name: String,
    /// The primary's circumscribed radius (m): farther from every partner, nothing
    /// touches.
    pub radius: f64,
    /// The primary's width (m), what its position error is divided by.
    pub width: f64,
    /// Every moving body, the primary first.
    pub movers: Vec<Mover>,
    /// Gravity (m/s², world frame).
    pub(crate) gravity: Vector3<f64>,
    /// The joints between movers, parents before children (none: every mover free).
    pub(crate) joints: Vec<MoverJoint>,
}

/// A joint of the scene between two movers.
#[derive(Clone, Debug, PartialEq)]
pub struct MoverJoint {
    /// The joint.
    pub(crate) joint: crate::scenario::Joint,
    /// Its body 1, as an index into the movers.
    pub(crate) parent: usize,
    /// Its body 2, likewise.
    pub(crate) child: usize,
}

impl TossSetup {
    /// The setup of `model`: its moving bodies, each a box or a sphere, and each in
    /// contact with at least one other body (a fixed plane, box, sphere or compound, or
    /// another moving body).
    pub fn new(model: &Model) -> Result<TossSetup, TossError> {
        let fail = |problem: String| TossError::Setup {
            scenario: model.scenario.name.clone(),
            problem,
        };
        let moving: Vec<usize> = (0..model.bodies.len())
            .filter(|&b| !model.bodies[b].fixed)
            .collect();
        if moving.is_empty() {
            return Err(fail(
                "a replay from motion follows a moving body, and every body of this \
                 scenario is fixed"
                    .into(),
            ));
        }
        let movers = (moving.iter())
            .map(|&body| mover(model, body, &moving).map_err(&fail))
            .collect::<Result<Vec<Mover>, TossError>>()?;
        let joints = mover_joints(model, &movers).map_err(fail)?;
        let primary = &movers[0];
        Ok(TossSetup {
            body: primary.body,
            name: primary.name.clone(),
            radius: primary.radius,
            width: primary.width,
            movers,
            gravity: model.gravity,
            joints,
        })
    }

    /// Checks that `data` (read from `file`) holds every moving body's pose in every
    /// frame.
    pub fn check_data(&self, file: &str, model: &Model, data: &Dataset) -> Result<(), TossError> {
        let moving: Vec<usize> = self.movers.iter().map(|m| m.body).collect();
        let contacts: Vec<usize> = (0..model.contacts.len())
            .filter(|&c| {
                let contact = &model.contacts[c];
                moving.contains(&contact.body_1) || moving.contains(&contact.body_2)
            })
            .collect();
        Ok(data.require(file, model, &contacts, &TOSSES)?)
    }

    /// Clearance of the primary's centre at `position` (m) from its nearest fixed
    /// partner (m): a plane's height above its reference point along its normal,
    /// another shape's distance to its surface ([`Partner::clearance`]).
    pub fn clearance(&self, position: &Vector3<f64>) -> f64 {
        self.movers[0].fixed_clearance(position)
    }
}

impl Mover {
    /// Clearance of this body's centre at `position` (m) from its nearest fixed partner
    /// (m); +∞ without one.
    pub fn fixed_clearance(&self, position: &Vector3<f64>) -> f64 {
        (self.partners.iter())
            .map(|p| p.clearance(position))
            .fold(f64::INFINITY, f64::min)
    }
}

/// Moving body `body` of `model` as a [`Mover`]; `moving` lists every moving body.
fn mover(model: &Model, body: usize, moving: &[usize]) -> Result<Mover, String> {
    let tossed = &model.bodies[body];
    let (radius, width) = match tossed.shape {
        Shape::Box { half_extents, .. } => (half_extents.norm(), 2.0 * half_extents.max()),
        Shape::Sphere { radius } => (radius, 2.0 * radius),
        _ => {
            return Err(format!(
                "body `{}` must be a box or a sphere to be replayed from its poses",
                tossed.name
            ))
        }
    };
    let others: Vec<usize> = (model.contacts.iter())
        .filter(|c| c.body_1 == body || c.body_2 == body)
        .map(|c| c.body_1 + c.body_2 - body)
        .collect();
    if others.is_empty() {
        return Err(format!(
            "body `{}` has no contact with another body to land on; add a [[contact]] with \
             its bodies",
            tossed.name
        ));
    }
    Ok(Mover {
        body,
        name: tossed.name.clone(),
        shape: tossed.shape.clone(),
        radius,
        width,
        partners: (others.iter())
            .filter(|&&o| model.bodies[o].fixed)
            .map(|&o| Partner::of(model, o))
            .collect(),
        touches: (others.iter())
            .filter_map(|o| moving.iter().position(|m| m == o))
            .collect(),
        mass: tossed.mass,
    })
}

/// The joints of `model` between its `movers`, parents before children: every joint
/// one whose bodies both move (a joint to a fixed body is not replayed from poses yet),
/// and a mover the child of one joint at most, in a tree.
fn mover_joints(model: &Model, movers: &[Mover]) -> Result<Vec<MoverJoint>, String> {
    let index = |body: usize| movers.iter().position(|m| m.body == body);
    let mut joints = Vec::new();
    for joint in &model.joints {
        let (Some(parent), Some(child)) = (index(joint.bodies[0]), index(joint.bodies[1])) else {
            return Err(format!(
                "joint `{}` holds a fixed body: a mechanism pinned to the world is not \
                 replayed from poses yet",
                joint.name
            ));
        };
        if joints.iter().any(|j: &MoverJoint| j.child == child) {
            return Err(format!(
                "body `{}` is the second body of two joints: a replay assembles a tree of \
                 joints, each body the child of one at most",
                movers[child].name
            ));
        }
        joints.push(MoverJoint {
            joint: joint.clone(),
            parent,
            child,
        });
    }
    // Parents before children: a child placed before its parent would be moved again.
    let mut ordered: Vec<MoverJoint> = Vec::new();
    let mut placed: Vec<bool> = (0..movers.len())
        .map(|m| !joints.iter().any(|j| j.child == m))
        .collect();
    while !joints.is_empty() {
        let Some(k) = joints.iter().position(|j| placed[j.parent]) else {
            return Err("the joints close a loop: a replay assembles a tree of joints".into());
        };
        let next = joints.remove(k);
        placed[next.child] = true;
        ordered.push(next);
    }
    Ok(ordered)
}
