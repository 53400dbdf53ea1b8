//! The residual network as the simulator uses it: the core's fixed-size model,
//! decoded from the exported blob, attached to one contact of a model. Inside its
//! training envelope it adds its correction to the law's; outside it is switched off
//! (the paper's strategy for conditions without data), and out of contact the core
//! does not ask it.
//!
//! The core fixes a network's shape at compile time; the host holds one variant per
//! shipped shape and picks it by the shape the blob's header names:
//!
//! - [`ContactResidual::Force`], 3-16-16-1: the 1D contacts' normal-force error from
//!   [δ (m), δ̇ (m/s), δ̇0 (m/s)];
//! - [`ContactResidual::Wrench`], 13-32-32-6, and [`ContactResidual::WideWrench`],
//!   13-48-48-6: a rigid body's force and torque error (Eq 12, the peg) from its 13
//!   state components (`crate::train::wrench_samples`); the wide one holds the six
//!   per-output networks of width 8 merged block-diagonally
//!   (`crate::train::per_output`), or one joint network of width 48;
//! - [`ContactResidual::Point`], 5-16-16-5: the contact-frame residual, evaluated at
//!   every touching point from that point's δ, δ̇, slip speed, spin and rolling rate
//!   ([`hcm_core::model::point_residual`]; trained by `crate::train::point_residual`);
//! - [`ContactResidual::JointTorque`], 2-16-16-1: a joint's torque error from its own
//!   angle and rate ([`JointResidual`], [`hcm_core::joint::hybrid_torque`]; trained by
//!   `crate::train::joint_residual`), attached to a joint, not a contact.

mod joint;
mod stored;

pub use joint::{JointResidual, JOINT_WIDTH};
pub use stored::Stored;

use hcm_core::joint::JOINT_INPUTS;
use hcm_core::model::{
    ContactModel, ContactPoint, Correction, Residual, POINT_INPUTS, POINT_OUTPUTS,
};
use hcm_core::residual::blob::Shape;
use hcm_core::residual::{BlobError, Excursion};
use nalgebra::Vector3;

/// Inputs of the 1D contact residual: δ (m), δ̇ (m/s), δ̇0 (m/s).
pub const INPUTS: usize = 3;
/// Hidden-layer width of the shipped 1D residual architecture.
pub const WIDTH: usize = 16;
/// Hidden layers of the shipped residual architectures.
pub const HIDDEN: usize = 2;

/// Inputs of the wrench residual: the moving body's 13 state components.
pub(crate) const WRENCH_INPUTS: usize = 13;
/// Outputs of the wrench residual: force x, y, z (N), torque x, y, z (N·m).
pub(crate) const WRENCH_OUTPUTS: usize = 6;
/// Hidden-layer width of the joint wrench network (one network, six outputs).
pub(crate) const WRENCH_WIDTH: usize = 32;
/// Hidden-layer width of each of the six per-output networks.
pub(crate) const PER_OUTPUT_WIDTH: usize = 8;
/// Hidden-layer width of the six per-output networks merged (6 × 8).
pub(crate) const WIDE_WRENCH_WIDTH: usize = WRENCH_OUTPUTS * PER_OUTPUT_WIDTH;

/// Hidden-layer width of the contact-frame residual.
pub(crate) const POINT_WIDTH: usize = 16;

/// A decoded residual network of one of the shipped shapes, either weight storage.
#[derive(Clone, Debug)]
pub enum ContactResidual {
    /// The 1D normal-force residual, 3-16-16-1.
    Force(Stored<INPUTS, WIDTH, 1, HIDDEN>),
    /// The joint wrench residual, 13-32-32-6.
    Wrench(Stored<WRENCH_INPUTS, WRENCH_WIDTH, WRENCH_OUTPUTS, HIDDEN>),
    /// The six per-output wrench networks merged, 13-48-48-6.
    WideWrench(Stored<WRENCH_INPUTS, WIDE_WRENCH_WIDTH, WRENCH_OUTPUTS, HIDDEN>),
    /// The contact-frame residual, 5-16-16-5, one evaluation per touching point.
    Point(Stored<POINT_INPUTS, POINT_WIDTH, POINT_OUTPUTS, HIDDEN>),
    /// A joint's torque residual, 2-16-16-1, from the joint's angle and rate.
    JointTorque(JointResidual),
}

impl ContactResidual {
    /// The shapes this build decodes, in [`ContactResidual`]'s order.
    pub fn shapes() -> [Shape; 5] {
        [
            Shape::of::<INPUTS, WIDTH, 1, HIDDEN>(),
            Shape::of::<WRENCH_INPUTS, WRENCH_WIDTH, WRENCH_OUTPUTS, HIDDEN>(),
            Shape::of::<WRENCH_INPUTS, WIDE_WRENCH_WIDTH, WRENCH_OUTPUTS, HIDDEN>(),
            Shape::of::<POINT_INPUTS, POINT_WIDTH, POINT_OUTPUTS, HIDDEN>(),
            Shape::of::<JOINT_INPUTS, JOINT_WIDTH, 1, HIDDEN>(),
        ]
    }

    /// Decodes a blob (f32 or int8) of any shipped shape, the one its header names.
    /// A blob of another shape is [`BlobError::WrongShape`], naming as expected the
    /// shipped shape with its inputs and outputs (else the first).
    pub fn decode(bytes: &[u8]) -> Result<ContactResidual, BlobError> {
        let found = match Stored::decode(bytes) {
            Ok(force) => return Ok(ContactResidual::Force(force)),
            Err(BlobError::WrongShape { found, .. }) => found,
            Err(e) => return Err(e),
        };
        let [force, wrench, wide, point, joint] = Self::shapes();
        if found == joint {
            return Stored::decode(bytes).map(|s| ContactResidual::JointTorque(JointResidual(s)));
        }
        if found == wrench {
            return Stored::decode(bytes).map(ContactResidual::Wrench);
        }
        if found == point {
            return Stored::decode(bytes).map(ContactResidual::Point);
        }
        if found == wide {
            return Stored::decode(bytes).map(ContactResidual::WideWrench);
        }
        let expected = [wrench, wide, point, joint]
            .into_iter()
            .find(|s| (s.inputs, s.outputs) == (found.inputs, found.outputs))
            .unwrap_or(force);
        Err(BlobError::WrongShape { expected, found })
    }

    /// The network's shape.
    pub fn shape(&self) -> Shape {
        let [force, wrench, wide, point, joint] = Self::shapes();
        match self {
            ContactResidual::Force(_) => force,
            ContactResidual::Wrench(_) => wrench,
            ContactResidual::WideWrench(_) => wide,
            ContactResidual::Point(_) => point,
            ContactResidual::JointTorque(_) => joint,
        }
    }

    /// The 1D force correction (N) at (δ, δ̇, δ̇0), or None outside the envelope (and
    /// for a wrench residual).
    pub fn correction(&self, depth: f64, rate: f64, approach_speed: f64) -> Option<f64> {
        match Residual::<f64>::correction(self, &[depth, rate, approach_speed]) {
            Some(Correction::NormalForce(force)) => Some(force),
            _ => None,
        }
    }

    /// The wrench correction (force (N), torque (N·m) about the centre of mass, world
    /// frame) at a body's 13 state components, or None outside the envelope (and for
    /// the 1D residual).
    pub fn wrench(&self, state: &[f64; WRENCH_INPUTS]) -> Option<(Vector3<f64>, Vector3<f64>)> {
        match Residual::<f64>::correction(self, state) {
            Some(Correction::Wrench { force, torque }) => Some((force, torque)),
            _ => None,
        }
    }
}

/// The core evaluates the decoded network as the contact model's learned part, the
/// same code path as in a controller.
impl Residual<f64> for ContactResidual {
    fn correction(&self, input: &[f64]) -> Option<Correction<f64>> {
        match self {
            ContactResidual::Force(m) => m.correction(input),
            ContactResidual::Wrench(m) => m.correction(input),
            ContactResidual::WideWrench(m) => m.correction(input),
            // A joint's network is evaluated by its joint, never as a contact's.
            ContactResidual::Point(_) | ContactResidual::JointTorque(_) => None,
        }
    }

    fn point_correction(&self, point: &ContactPoint<f64>) -> Option<[f64; POINT_OUTPUTS]> {
        match self {
            ContactResidual::Point(m) => m.point_correction(point),
            _ => None,
        }
    }

    fn excursion(&self, input: &[f64]) -> Option<Excursion> {
        match self {
            ContactResidual::Force(m) => m.excursion(input),
            ContactResidual::Wrench(m) => m.excursion(input),
            ContactResidual::WideWrench(m) => m.excursion(input),
            ContactResidual::Point(_) | ContactResidual::JointTorque(_) => None,
        }
    }
}

/// A scenario's contact model on the host: physics (f64) with, once attached, the
/// decoded residual network.
pub type HostContactModel = ContactModel<f64, Option<ContactResidual>>;
