//! The simulator's state vector and where each quantity lives in it.

use crate::scenario::Model;
use hcm_core::integrate::OdeState;
use nalgebra::Vector3;

/// A heap-backed state for the core's integrator: the host simulates as many
/// bodies and contacts as the scenario has.
#[derive(Clone, Debug, PartialEq)]
pub struct StateVector(pub Vec<f64>);

impl OdeState<f64> for StateVector {
    fn components(&self) -> &[f64] {
        &self.0
    }
    fn components_mut(&mut self) -> &mut [f64] {
        &mut self.0
    }
}

/// Where each body's and contact's quantities sit in a [`StateVector`].
///
/// Per moving body: position (m, 3) then velocity (m/s, 3). Then per contact: the
/// normal impulse ∫f_n dt (N·s), the contact work ∫f_n·δ̇ dt (J), and the deepest
/// indentation of the current contact δ_max (m; its rate is δ̇ while δ̇ > 0 at
/// δ = δ_max, else 0; reset to 0 at touch-down), integrated alongside the motion. Bodies do not rotate yet (no friction in the 1D examples):
/// orientation and angular velocity join the layout with the rigid-body examples.
#[derive(Clone, Debug)]
pub struct Layout {
    /// Slot of each body (None for fixed bodies).
    body_slot: Vec<Option<usize>>,
    /// Index of the first contact quantity.
    contact_base: usize,
    /// Total length.
    len: usize,
}

/// The first component of each moving body when each takes `per_body` components in
/// file order (None for fixed bodies), and the first component after them.
pub(crate) fn body_slots(model: &Model, per_body: usize) -> (Vec<Option<usize>>, usize) {
    let mut next = 0;
    let slots = model
        .bodies
        .iter()
        .map(|b| {
            (!b.fixed).then(|| {
                next += per_body;
                next - per_body
            })
        })
        .collect();
    (slots, next)
}

impl Layout {
    /// The layout for `model`.
    pub fn new(model: &Model) -> Layout {
        let (body_slot, contact_base) = body_slots(model, 6);
        Layout {
            body_slot,
            contact_base,
            len: contact_base + 3 * model.contacts.len(),
        }
    }

    /// Number of components.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether the state is empty (never, for a valid model).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The initial state of `model`.
    pub fn initial_state(&self, model: &Model) -> StateVector {
        let mut y = vec![0.0; self.len];
        for (body, slot) in model.bodies.iter().zip(&self.body_slot) {
            if let Some(s) = *slot {
                y[s..s + 3].copy_from_slice(body.position.as_slice());
                y[s + 3..s + 6].copy_from_slice(body.velocity.as_slice());
            }
        }
        StateVector(y)
    }

    /// Slot of body `b`, if it moves.
    pub fn slot(&self, body: usize) -> Option<usize> {
        self.body_slot[body]
    }

    /// Position (m) and velocity (m/s) of body `b`; a fixed body stays at its
    /// initial position with zero velocity.
    pub fn motion(&self, model: &Model, y: &[f64], body: usize) -> (Vector3<f64>, Vector3<f64>) {
        match self.body_slot[body] {
            Some(s) => (
                Vector3::new(y[s], y[s + 1], y[s + 2]),
                Vector3::new(y[s + 3], y[s + 4], y[s + 5]),
            ),
            None => (model.bodies[body].position, Vector3::zeros()),
        }
    }

    /// Index of contact `c`'s impulse (its work follows it).
    pub fn impulse_index(&self, contact: usize) -> usize {
        self.contact_base + 3 * contact
    }

    /// Index of contact `c`'s deepest indentation δ_max (m).
    pub fn deepest_index(&self, contact: usize) -> usize {
        self.contact_base + 3 * contact + 2
    }
}
