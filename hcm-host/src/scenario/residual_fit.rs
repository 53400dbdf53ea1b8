//! Which residual network a scenario's contact can take: the 1D normal-force network
//! (3 inputs: δ, δ̇, δ̇0) on a 1D scenario, the body-state wrench networks (13 inputs: a
//! rigid body's state) on a 3D one, the contact-frame network (5 inputs, evaluated at
//! each touching point) on either. A blob of another kind would be evaluated without a
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
