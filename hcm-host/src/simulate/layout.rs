//! The simulator's state vector: where each rigid body's state and each contact's
//! running integrals sit in it, and the pose of a body read back from it.

use crate::scenario::Model;
use crate::scenario::Pose;
use hcm_core::integrate::OdeState;
use hcm_core::rigid::RigidState;
use nalgebra::Vector3;

/// A heap-backed state for the core's integrator: the host simulates as many
/// bodies and contacts as the scenario has.
#[derive(Debug, PartialEq)]
pub struct StateVector(pub Vec<f64>);

/// By hand for `clone_from`, which the integrator calls in every stage and dense
/// output: it copies into the existing buffer instead of allocating one (the derived
/// `clone_from` allocates).
impl Clone for StateVector {
    fn clone(&self) -> Self {
        StateVector(self.0.clone())
    }

    fn clone_from(&mut self, source: &Self) {
        self.0.clone_from(&source.0);
    }
}

impl OdeState<f64> for StateVector {
    fn components(&self) -> &[f64] {
        &self.0
    }
    fn components_mut(&mut self) -> &mut [f64] {
        &mut self.0
    }
}

/// Components of one moving body: p (3), q (4), v (3), ω in the body frame (3), as
/// [`RigidState`] orders them.
const BODY_LEN: usize = 13;
/// Components of one contact: the linear impulse ∫**F** dt (N·s, 3) and the angular
/// impulse ∫**T** dt (N·m·s, 3) on its moving body, torque about that body's centre of
/// mass.
const CONTACT_LEN: usize = 6;

/// Where each body's and contact's quantities sit in a [`StateVector`].
#[derive(Clone, Debug)]
pub struct RigidLayout {
    /// First component of each body (None for fixed bodies).
    body_slot: Vec<Option<usize>>,
    /// First component of the contacts' integrals.
    contact_base: usize,
    /// Total length.
    len: usize,
}

impl RigidLayout {
    /// The layout of `model`: its moving bodies in file order, then its contacts.
    pub fn new(model: &Model) -> RigidLayout {
        let mut next = 0;
        let body_slot = model
            .bodies
            .iter()
            .map(|b| {
                (!b.fixed).then(|| {
                    next += BODY_LEN;
                    next - BODY_LEN
                })
            })
            .collect();
        RigidLayout {
            body_slot,
            contact_base: next,
            len: next + CONTACT_LEN * model.contacts.len(),
        }
    }

    /// The initial state: each moving body as the scenario places it, integrals 0.
    pub fn initial_state(&self, model: &Model) -> StateVector {
        let mut y = vec![0.0; self.len];
        for (body, slot) in model.bodies.iter().zip(&self.body_slot) {
            if let Some(s) = *slot {
                let body_omega = body
                    .orientation
                    .inverse_transform_vector(&body.angular_velocity);
                let state =
                    RigidState::new(body.position, body.orientation, body.velocity, body_omega);
                y[s..s + BODY_LEN].copy_from_slice(&state.components);
            }
        }
        StateVector(y)
    }

    /// First component of body `b`, if it moves.
    pub fn slot(&self, body: usize) -> Option<usize> {
        self.body_slot[body]
    }

    /// The rigid state of moving body `b` in `y`, if it moves.
    #[inline]
    pub fn rigid_state(&self, y: &[f64], body: usize) -> Option<RigidState<f64>> {
        let s = self.body_slot[body]?;
        let mut state = RigidState {
            components: [0.0; BODY_LEN],
        };
        state.components.copy_from_slice(&y[s..s + BODY_LEN]);
        Some(state)
    }

    /// Pose and velocities of body `b` in `y`; a fixed body rests where the scenario
    /// put it.
    #[inline]
    pub fn pose(&self, model: &Model, y: &[f64], body: usize) -> Pose {
        match self.rigid_state(y, body) {
            Some(state) => {
                // `world_angular_velocity` would normalise q a second time.
                let orientation = state.orientation();
                let omega = state.body_angular_velocity();
                // A body that does not turn (every 1D example) skips the rotation:
                // it gives +0 exactly for a +0 ω.
                let angular_velocity = if omega.iter().all(|w| w.to_bits() == 0) {
                    omega
                } else {
                    orientation * omega
                };
                Pose {
                    position: state.position(),
                    orientation,
                    velocity: state.velocity(),
                    angular_velocity,
                }
            }
            None => {
                let b = &model.bodies[body];
                Pose {
                    position: b.position,
                    orientation: b.orientation,
                    velocity: Vector3::zeros(),
                    angular_velocity: Vector3::zeros(),
                }
            }
        }
    }

    /// Components of the moving bodies (13 each), which come first (–).
    pub fn body_components(&self) -> usize {
        self.contact_base
    }

    /// First component of contact `c`'s impulses (linear 3, then angular 3).
    pub fn impulse_index(&self, contact: usize) -> usize {
        self.contact_base + CONTACT_LEN * contact
    }

    /// The largest |‖q‖ − 1| over the moving bodies of `y` (–).
    pub fn quaternion_drift(&self, y: &[f64]) -> f64 {
        (0..self.body_slot.len())
            .filter_map(|b| self.rigid_state(y, b))
            .map(|s| s.quaternion_drift())
            .fold(0.0, f64::max)
    }

    /// Scales every moving body's quaternion in `y` to unit norm.
    pub fn normalise(&self, y: &mut [f64]) {
        for b in 0..self.body_slot.len() {
            if let (Some(s), Some(mut state)) = (self.body_slot[b], self.rigid_state(y, b)) {
                state.normalise();
                y[s + 3..s + 7].copy_from_slice(&state.components[3..7]);
            }
        }
    }
}
