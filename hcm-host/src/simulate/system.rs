//! The equations of motion of a scenario as an ODE: Newton for every moving body
//! under gravity and contact forces (Eq 17 and Eq 21 are special cases), plus the
//! impulse and work of each contact.

use super::state::{Layout, StateVector};
use crate::scenario::geometry::{pair_kinematics, PairKinematics};
use crate::scenario::Model;
use hcm_core::effect::ContactMemory;
use hcm_core::integrate::OdeSystem;
use hcm_core::law::Indentation;
use hcm_core::model::{ContactPoint, PairLoad};
use nalgebra::Vector3;

/// Per-contact discrete state: whether the pair is in contact and the approach
/// speed latched at touch-down (the δ̇0 of Lankarani–Nikravesh and Flores).
///
/// Contact forces act only in contact mode; mode switches happen at located
/// δ = 0 events, so a solver step never straddles a touch-down or lift-off.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactModes {
    /// In contact, per contact.
    pub touching: Vec<bool>,
    /// Approach speed δ̇0 (m/s) of the current (or last) impact, per contact.
    pub approach_speed: Vec<f64>,
}

/// A scenario's dynamics in the current contact modes.
pub struct ContactSystem<'a> {
    /// The model.
    pub model: &'a Model,
    /// State layout.
    pub layout: &'a Layout,
    /// Contact modes in force.
    pub modes: ContactModes,
    /// Reused by [`OdeSystem::derivative`], so the solver's hot path does not allocate.
    scratch: Loads,
}

/// Forces and torques (N, N·m) on every body, and each contact's normal force (N).
#[derive(Clone, Debug, Default)]
pub struct Loads {
    /// Force on each body (N).
    pub force: Vec<Vector3<f64>>,
    /// Torque on each body about its reference point (N·m).
    pub torque: Vec<Vector3<f64>>,
    /// Normal force f_n of each contact (N), 0 when apart.
    pub normal_force: Vec<f64>,
    /// Kinematics of each contact.
    pub kinematics: Vec<PairKinematics>,
}

impl ContactSystem<'_> {
    /// Kinematics of contact `c` in state `y`.
    #[inline]
    pub fn kinematics(&self, y: &[f64], c: usize) -> PairKinematics {
        let contact = &self.model.contacts[c];
        let motion = |b| self.layout.motion(self.model, y, b);
        pair_kinematics(
            self.model,
            contact,
            motion(contact.body_1),
            motion(contact.body_2),
        )
    }

    /// A system for `model` in the given contact `modes`.
    pub fn new<'m>(model: &'m Model, layout: &'m Layout, modes: ContactModes) -> ContactSystem<'m> {
        ContactSystem {
            model,
            layout,
            modes,
            scratch: Loads::default(),
        }
    }

    /// Contact loads in state `y` under the current modes.
    pub fn loads(&self, y: &[f64]) -> Loads {
        let mut loads = Loads::default();
        self.fill_loads(y, &mut loads);
        loads
    }

    /// [`ContactSystem::loads`] into existing buffers.
    fn fill_loads(&self, y: &[f64], loads: &mut Loads) {
        let (n_bodies, n_contacts) = (self.model.bodies.len(), self.model.contacts.len());
        loads.force.clear();
        loads.force.resize(n_bodies, Vector3::zeros());
        loads.torque.clear();
        loads.torque.resize(n_bodies, Vector3::zeros());
        loads.normal_force.clear();
        loads.normal_force.resize(n_contacts, 0.0);
        loads.kinematics.clear();
        for (c, contact) in self.model.contacts.iter().enumerate() {
            let k = self.kinematics(y, c);
            loads.kinematics.push(k);
            if !self.modes.touching[c] {
                continue;
            }
            let load = self.contact_load(y, c, &k);
            loads.normal_force[c] = load.normal_force;
            let w = load.wrench;
            loads.force[contact.body_1] += w.force_1;
            loads.torque[contact.body_1] += w.torque_1;
            loads.force[contact.body_2] += w.force_2;
            loads.torque[contact.body_2] += w.torque_2;
        }
    }

    /// The loads of contact `c` (kinematics `k`) in state `y`, in contact mode:
    /// evaluated by the contact's core model (law + effects + residual, Eq 1) at its
    /// one point.
    pub fn contact_load(&self, y: &[f64], c: usize, k: &PairKinematics) -> PairLoad<f64> {
        let contact = &self.model.contacts[c];
        let (point, input) = self.contact_point(y, c, k);
        let origin = |b| self.layout.motion(self.model, y, b).0;
        contact.model.pair_load(
            &[point],
            &origin(contact.body_1),
            &origin(contact.body_2),
            &input,
        )
    }

    /// The normal force f_n (N) of contact `c` in state `y`, in contact mode: the
    /// same model as [`ContactSystem::contact_load`] without the point's geometry and
    /// the wrench (the peak search evaluates it often).
    pub fn contact_normal_force(&self, y: &[f64], c: usize, k: &PairKinematics) -> f64 {
        let (indentation, memory) = self.indentation(y, c, k);
        let input = [k.depth, k.rate, indentation.approach_speed];
        let model = &self.model.contacts[c].model;
        model.normal_force(&indentation, &memory, &input).0
    }

    /// Contact `c`'s one point and the residual's input [δ (m), δ̇ (m/s), δ̇0 (m/s)].
    fn contact_point(
        &self,
        y: &[f64],
        c: usize,
        k: &PairKinematics,
    ) -> (ContactPoint<f64>, [f64; 3]) {
        let (indentation, memory) = self.indentation(y, c, k);
        let point = ContactPoint {
            indentation,
            memory,
            normal: k.normal,
            position: k.point,
            relative_velocity: self.relative_velocity(y, c),
            // Bodies of a 1D scenario do not rotate.
            relative_angular_velocity: Vector3::zeros(),
        };
        (point, [k.depth, k.rate, indentation.approach_speed])
    }

    /// Velocity of contact `c`'s body 1 relative to its body 2 (m/s): what friction
    /// reads as slip. Bodies do not rotate yet, so it is the same at every point; read
    /// only when the contact has friction (it costs two body lookups per evaluation).
    fn relative_velocity(&self, y: &[f64], c: usize) -> Vector3<f64> {
        let contact = &self.model.contacts[c];
        if contact.model.friction.is_none() {
            return Vector3::zeros();
        }
        let velocity = |b| self.layout.motion(self.model, y, b).1;
        velocity(contact.body_1) - velocity(contact.body_2)
    }

    /// Contact `c`'s (δ, δ̇, δ̇0) and δ_max in state `y`.
    #[inline]
    fn indentation(
        &self,
        y: &[f64],
        c: usize,
        k: &PairKinematics,
    ) -> (Indentation<f64>, ContactMemory<f64>) {
        let indentation = Indentation {
            depth: k.depth,
            rate: k.rate,
            approach_speed: self.modes.approach_speed[c],
        };
        let memory = ContactMemory {
            max_depth: y[self.layout.deepest_index(c)].max(k.depth),
        };
        (indentation, memory)
    }
}

impl OdeSystem<f64, StateVector> for ContactSystem<'_> {
    fn derivative(&mut self, _time: f64, state: &StateVector, derivative: &mut StateVector) {
        let (y, dy) = (&state.0, &mut derivative.0);
        let mut loads = std::mem::take(&mut self.scratch);
        self.fill_loads(y, &mut loads);
        for (b, body) in self.model.bodies.iter().enumerate() {
            if let Some(s) = self.layout.slot(b) {
                let mut acceleration = self.model.gravity + loads.force[b] / body.mass;
                if let Some(drag) = &body.air_drag {
                    let velocity = Vector3::new(y[s + 3], y[s + 4], y[s + 5]);
                    acceleration += drag.force(&velocity) / body.mass;
                }
                dy[s..s + 3].copy_from_slice(&y[s + 3..s + 6]);
                dy[s + 3..s + 6].copy_from_slice(acceleration.as_slice());
            }
        }
        for (c, k) in loads.kinematics.iter().enumerate() {
            let i = self.layout.impulse_index(c);
            dy[i] = loads.normal_force[c];
            dy[i + 1] = loads.normal_force[c] * k.rate;
            // δ_max follows δ while it grows at its maximum (a relative slack of 1e-9
            // absorbs the rounding between the two integrals), and holds otherwise.
            let deepest = y[self.layout.deepest_index(c)];
            let growing =
                self.modes.touching[c] && k.rate > 0.0 && k.depth >= deepest - 1e-9 * deepest.abs();
            dy[self.layout.deepest_index(c)] = if growing { k.rate } else { 0.0 };
        }
        self.scratch = loads;
    }
}
