//! The residual's training pairs of a rigid contact (Eq 12 for one moving body): at
//! every measured sample where the moving body touches the other, its 13 state
//! components in, the wrench PM2 misses out.
//!
//! **Input**: the moving body's state as the integrator stores it and passes it to
//! the residual (`simulate`'s `contact_load`; `RigidState`'s order):
//! position p (m, world), quaternion q = (w, x, y, z) (–, body → world), velocity v
//! (m/s, world), angular velocity ω (rad/s, **body frame**). The data record ω in the
//! world frame; it is turned into the body frame here, so that the HCM sees in the
//! simulation exactly what it was trained on.
//!
//! **Target**: measured (force, torque) − PM2's (force, torque) on the moving body at
//! the same state, force in N and torque in N·m about its centre of mass, both in the
//! **world frame**. Why world: the data and the integrator's loads are world-frame
//! (the core adds [`Correction::Wrench`](hcm_core::model::Correction) to body 1's
//! world-frame load about its centre of mass), so the target needs no rotation and no
//! rounding is added; orientation effects are still learnable, because the quaternion
//! is an input. PM2's wrench comes from the simulator's own contact code
//! ([`RigidSystem::contact_load`]): the same manifold, laws, friction and arms as in
//! the HCM's simulation.
//!
//! Samples out of contact are not rows: there the core switches the residual off
//! (no touching point, physics only), so it never needs a value there.
//!
//! PM2's wrench is evaluated at one state with no point history (each point's δ̇0 is
//! its current δ̇, its δ_max its current δ): exact for a memory-free law such as
//! IMPACT (Eq 8–9) with STEP friction, PM2's laws on the peg.

pub use crate::dataset::state_input;
use crate::dataset::Dataset;
use crate::identify::RecordedContact;
use crate::scenario::Model;
use crate::simulate::RigidSystem;
use nalgebra::Vector3;

/// Residual inputs of a rigid contact: the moving body's 13 state components.
pub(crate) use crate::dataset::STATE_INPUTS;

/// The training pairs of one contact, one row per touching sample, runs in file
/// order and samples in time order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct WrenchPairs {
    /// The moving body's 13 state components per row (see the module docs).
    pub inputs: Vec<Vec<f64>>,
    /// Measured − PM2 (force (N), torque (N·m)) on the moving body per row, world
    /// frame, torque about its centre of mass.
    pub targets: Vec<Vec<f64>>,
    /// Index in the data's runs of each row's run (to hold out whole runs).
    pub runs: Vec<usize>,
    /// Time of each row's sample (s).
    pub times: Vec<f64>,
}

/// Why the pairs cannot be built.
#[derive(Debug, thiserror::Error)]
pub enum WrenchSampleError {
    /// The model has no such contact.
    #[error("the scenario has no contact number {0}")]
    NoSuchContact(usize),
    /// The contact is not one moving body against a fixed one.
    #[error(
        "contact `{0}`: the body-state residual (Eq 12, `--inputs state`) is trained for one \
         moving body against a fixed one; between two moving bodies use the contact-frame \
         residual (`--inputs contact`)"
    )]
    NotOneMover(String),
    /// The touching samples could not be read (see the message).
    #[error("{0}")]
    Recorded(String),
}

/// The training pairs of contact `c` of `physics` (PM2; its residual, if any, left
/// out) from the measured `data`: the rows of [`RecordedContact`] — every touching
/// sample with the mover's state and a measured force, its own or a force plate's,
/// point histories latched along each run — the measured minus PM2's wrench as the
/// target. A torque not measured has a target of 0 (nothing to learn there).
pub fn wrench_pairs(
    physics: &Model,
    data: &Dataset,
    c: usize,
) -> Result<WrenchPairs, WrenchSampleError> {
    moving_body(physics, c)?;
    let mut model = physics.clone();
    model.contacts[c].model.residual = None;
    let recorded = RecordedContact::from_data(&model, data, c)
        .map_err(|e| WrenchSampleError::Recorded(e.to_string()))?;
    let mut pairs = WrenchPairs::default();
    for sample in &recorded.samples {
        let got = recorded.predicted(&model, sample);
        let target: Vec<f64> = (0..6)
            .map(|k| {
                let d = sample.measured[k] - got[k];
                if d.is_finite() {
                    d
                } else {
                    0.0
                }
            })
            .collect();
        pairs.inputs.push(sample.state.to_vec());
        pairs.targets.push(target);
        pairs.runs.push(sample.run);
        pairs.times.push(sample.time);
    }
    Ok(pairs)
}

/// The (force (N), torque (N·m) about its centre of mass, world frame) that contact
/// `c` of `system`'s model — physics, and its residual if one is attached — exerts on
/// its moving body `mover` in `state` (13 components, see the module docs), or `None`
/// when the body does not touch. `y` is a state vector of `system`'s layout (the
/// other bodies' states), `mover`'s components overwritten in place.
pub fn contact_wrench(
    system: &RigidSystem<'_>,
    y: &mut [f64],
    mover: usize,
    c: usize,
    state: &[f64; STATE_INPUTS],
) -> Option<(Vector3<f64>, Vector3<f64>)> {
    let slot = system.layout.slot(mover)?;
    y[slot..slot + STATE_INPUTS].copy_from_slice(state);
    let load = system.contact_load(y, c);
    (load.points > 0).then_some(load.on_mover)
}

/// Contact `c`'s moving body, body 1; an error unless body 1 moves and body 2 is
/// fixed: the residual's wrench acts on body 1
/// ([`hcm_core::model::ContactModel::pair_load`]).
pub fn moving_body(model: &Model, c: usize) -> Result<usize, WrenchSampleError> {
    let contact = model
        .contacts
        .get(c)
        .ok_or(WrenchSampleError::NoSuchContact(c))?;
    let (one, two) = (&model.bodies[contact.body_1], &model.bodies[contact.body_2]);
    if one.fixed || !two.fixed {
        return Err(WrenchSampleError::NotOneMover(format!(
            "{}–{}",
            one.name, two.name
        )));
    }
    Ok(contact.body_1)
}
