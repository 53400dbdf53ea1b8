//! Which residual network a scenario's contact can take: the 1D normal-force network
//! (3 inputs: δ, δ̇, δ̇0) on a 1D scenario, the body-state wrench networks (13 inputs: a
//! rigid body's state) on a 3D one, the contact-frame network (5 inputs, evaluated at
//! each touching point) on either; and which joint takes a joint's torque network (2
//! inputs: θ, θ̇) — a mechanism's one joint. A blob of another kind would be evaluated without a
//! word — its envelope shutting it off, the HCM silently equal to PM2 — so it is
//! refused where it is attached.

use super::Model;
use crate::residual::ContactResidual;

impl Model {
    /// `self` with `residual` on contact `contact`, or why that network does not fit
    /// this scenario's contact (`source` names the blob in the message).
    pub fn with_residual(
        &self,
        contact: usize,
        residual: ContactResidual,
        source: &str,
    ) -> Result<Model, String> {
        if let ContactResidual::JointTorque(joint) = residual {
            return self.with_joint_residual(joint, source);
        }
        if contact >= self.contacts.len() {
            return Err(format!(
                "{source}: scenario `{}` has no contact {contact} (it has {})",
                self.scenario.name,
                self.contacts.len()
            ));
        }
        let shape = residual.shape();
        let fits = match residual {
            ContactResidual::Force(_) => !self.is_rigid(),
            ContactResidual::Wrench(_) | ContactResidual::WideWrench(_) => self.is_rigid(),
            ContactResidual::Point(_) => true,
            // Attached to its joint above.
            ContactResidual::JointTorque(_) => false,
        };
        if !fits {
            let (kind, needs) = if self.is_rigid() {
                (
                    "3D",
                    "a rigid body's wrench network (13 inputs) or the contact-frame network \
                     (5 inputs)",
                )
            } else {
                (
                    "1D",
                    "the normal-force network (3 inputs: δ, δ̇, δ̇0) or the contact-frame \
                     network (5 inputs)",
                )
            };
            return Err(format!(
                "{source}: a {}-input, {}-output network does not fit scenario `{}`, a {kind} \
                 scenario, which takes {needs}; train it on this scenario's data (`hcm \
                 train`) and export that",
                shape.inputs, shape.outputs, self.scenario.name
            ));
        }
        let mut out = self.clone();
        out.contacts[contact].model.residual = Some(residual);
        Ok(out)
    }
}

impl Model {
    /// `self` with a joint's torque network on its joint: a scenario of one joint
    /// (a mechanism of several would need the joint named; not yet).
    fn with_joint_residual(
        &self,
        residual: crate::residual::JointResidual,
        source: &str,
    ) -> Result<Model, String> {
        match self.joints.len() {
            1 => {
                let mut out = self.clone();
                out.joints[0].residual = Some(residual);
                Ok(out)
            }
            0 => Err(format!(
                "{source}: a joint's torque network (2 inputs: θ, θ̇) does not fit scenario                  `{}`, which has no joint; give the mechanism's scenario it was trained on",
                self.scenario.name
            )),
            n => Err(format!(
                "{source}: scenario `{}` has {n} joints, and a joint's torque network is                  attached only to a scenario of one joint so far",
                self.scenario.name
            )),
        }
    }
}
