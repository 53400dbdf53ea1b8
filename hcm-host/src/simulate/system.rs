//! The equations of motion of a scenario as an ODE: Newton–Euler for every moving
//! body (Eq 22, [`hcm_core::rigid`]; Eq 17 and Eq 21 are special cases) under gravity,
//! air drag and the contact wrenches, each contact a manifold of points evaluated by
//! the contact's core model (normal law + effects + STEP friction at every point, Eq 1
//! with the arms, plus the residual), and each contact's linear and angular impulse.

use super::jacobian::Linearisation;
use super::joints::{add_constraint_loads, add_law_torques, world_inverse_inertia, BodyMotion};
use super::layout::{RigidLayout, StateVector};
use super::memory::PointMemory;
use crate::residual::{ContactResidual, INPUTS, WRENCH_INPUTS};
use crate::scenario::Model;
use crate::scenario::{pair_contacts, Pose};
use hcm_core::integrate::OdeSystem;
use hcm_core::law::Indentation;
use hcm_core::model::{ContactPoint, Manifold, PairLoad, MAX_POINTS};
use hcm_core::rigid::RigidBody;
use nalgebra::Vector3;

/// A scenario's dynamics with the current point histories. `JOINT_PATH` false compiles
/// the joints' loads out of the derivative (a scene's joints then go unheeded): what
/// `benches/ball_simulation.rs` measures the joint path's cost on a scene without joints
/// against ([`super::simulate_on_path`]); every command runs the default, true.
pub struct RigidSystem<'a, const JOINT_PATH: bool = true> {
    /// The model.
    pub(crate) model: &'a Model,
    /// State layout.
    pub(crate) layout: &'a RigidLayout,
    /// Each contact's point histories.
    pub(crate) memory: Vec<PointMemory>,
    /// Each body's mass properties (fixed bodies: unused).
    bodies: Vec<RigidBody<f64>>,
    /// Each body's inverse inertia, body frame (1/(kg·m²)), for the joints' solve.
    inverse_inertia: Vec<nalgebra::Matrix3<f64>>,
    /// Force and torque on each body (N, N·m), reused per evaluation.
    scratch: Vec<(Vector3<f64>, Vector3<f64>)>,
    /// The Jacobian and factored W of the linearly implicit steps.
    pub(super) linear: Linearisation,
}

impl RigidSystem<'_> {
    /// The system of `model` with no contact history (the joint path in).
    pub fn new<'m>(model: &'m Model, layout: &'m RigidLayout) -> RigidSystem<'m> {
        RigidSystem::on_path(model, layout)
    }
}

/// A contact's touching points with their feature ids and the two bodies' poses.
pub struct PairManifold {
    /// The points, as the contact model reads them.
    pub points: Manifold<f64>,
    /// Each point's feature id (see [`hcm_core::geometry::ContactGeometry`]).
    pub features: heapless::Vec<u32, MAX_POINTS>,
    /// Body 1's pose.
    pub pose_1: Pose,
    /// Body 2's pose.
    pub pose_2: Pose,
}

/// One contact's loads at one instant and the body whose motion it reports.
#[derive(Clone, Copy, Debug)]
pub struct ContactLoad {
    /// The loads on both bodies (torques about their centres of mass).
    pub(crate) load: PairLoad<f64>,
    /// Contact points touching.
    pub(crate) points: usize,
    /// The force (N) and torque (N·m, about its centre of mass) on the contact's
    /// moving body: body 1, or body 2 when body 1 is fixed.
    pub(crate) on_mover: (Vector3<f64>, Vector3<f64>),
    /// The power the contact takes from the two bodies (W): −(**F**1·**v**1 +
    /// **T**1·**ω**1 + **F**2·**v**2 + **T**2·**ω**2), f_n·δ̇ for one point without friction.
    pub(crate) dissipation: f64,
}

impl<const JOINT_PATH: bool> RigidSystem<'_, JOINT_PATH> {
    /// The system of `model` with no contact history, its derivative on `JOINT_PATH`.
    pub fn on_path<'m>(model: &'m Model, layout: &'m RigidLayout) -> RigidSystem<'m, JOINT_PATH> {
        let bodies = model
            .bodies
            .iter()
            .map(|b| RigidBody::new(b.mass, b.inertia, model.gravity))
            .collect();
        let inverse_inertia = (model.bodies.iter())
            .map(|b| {
                b.inertia
                    .try_inverse()
                    .unwrap_or_else(nalgebra::Matrix3::zeros)
            })
            .collect();
        RigidSystem {
            model,
            layout,
            memory: vec![PointMemory::default(); model.contacts.len()],
            bodies,
            inverse_inertia,
            scratch: Vec::new(),
            linear: Linearisation::default(),
        }
    }

    /// The manifold of contact `c` in state `y`: every touching point with its
    /// indentation, history, normal, position and slip velocity.
    pub fn manifold(&self, y: &[f64], c: usize) -> PairManifold {
        let (pose_1, pose_2) = self.poses(y, c);
        let mut pair = PairManifold {
            points: Manifold::new(),
            features: heapless::Vec::new(),
            pose_1,
            pose_2,
        };
        self.each_point(c, &pose_1, &pose_2, |point, feature| {
            // Both hold at most MAX_POINTS: the pushes cannot fail.
            let _ = pair.points.push(point);
            let _ = pair.features.push(feature);
        });
        pair
    }

    /// The poses of contact `c`'s two bodies in state `y`.
    fn poses(&self, y: &[f64], c: usize) -> (Pose, Pose) {
        let contact = &self.model.contacts[c];
        let pose = |b| self.layout.pose(self.model, y, b);
        (pose(contact.body_1), pose(contact.body_2))
    }

    /// Hands `each` every touching point of contact `c` with its bodies at `pose_1`,
    /// `pose_2`, and its feature id (a callback: the solver's hot path then moves no
    /// manifold).
    fn each_point(
        &self,
        c: usize,
        pose_1: &Pose,
        pose_2: &Pose,
        mut each: impl FnMut(ContactPoint<f64>, u32),
    ) {
        let contact = &self.model.contacts[c];
        for g in pair_contacts(self.model, contact, pose_1, pose_2) {
            let relative_velocity =
                pose_1.point_velocity(&g.point) - pose_2.point_velocity(&g.point);
            let rate = -relative_velocity.dot(&g.normal);
            let (approach_speed, memory) = self.memory[c].recall(g.feature, g.depth, rate);
            let point = ContactPoint {
                indentation: Indentation {
                    depth: g.depth,
                    rate,
                    approach_speed,
                },
                memory,
                normal: g.normal,
                position: g.point,
                relative_velocity,
                relative_angular_velocity: pose_1.angular_velocity - pose_2.angular_velocity,
            };
            each(point, g.feature);
        }
    }

    /// The loads of contact `c` in state `y` (zero when apart).
    pub fn contact_load(&self, y: &[f64], c: usize) -> ContactLoad {
        let contact = &self.model.contacts[c];
        let (pose_1, pose_2) = self.poses(y, c);
        let mut points = Manifold::new();
        self.each_point(c, &pose_1, &pose_2, |point, _| {
            let _ = points.push(point);
        });
        // The residual's input (Eq 12): the moving body's 13 state components.
        let mover = if self.model.bodies[contact.body_1].fixed {
            contact.body_2
        } else {
            contact.body_1
        };
        let mut input = [f64::NAN; WRENCH_INPUTS];
        // The 1D force residual reads [δ (m), δ̇ (m/s), δ̇0 (m/s)] of the first point;
        // without a residual the input is not read.
        let inputs = match (&contact.model.residual, points.first()) {
            // A contact-frame residual reads each point itself.
            (None | Some(ContactResidual::Point(_) | ContactResidual::JointTorque(_)), _) => 0,
            (Some(ContactResidual::Force(_)), Some(p)) => {
                let i = p.indentation;
                input[..INPUTS].copy_from_slice(&[i.depth, i.rate, i.approach_speed]);
                INPUTS
            }
            _ => {
                if let Some(state) = self.layout.rigid_state(y, mover) {
                    input = state.components;
                }
                WRENCH_INPUTS
            }
        };
        let load = contact.model.pair_load(
            &points,
            &pose_1.position,
            &pose_2.position,
            &input[..inputs],
        );
        let w = &load.wrench;
        let on_mover = if mover == contact.body_1 {
            (w.force_1, w.torque_1)
        } else {
            (w.force_2, w.torque_2)
        };
        let power = |f: &Vector3<f64>, t: &Vector3<f64>, pose: &Pose| {
            f.dot(&pose.velocity) + t.dot(&pose.angular_velocity)
        };
        ContactLoad {
            load,
            points: points.len(),
            on_mover,
            dissipation: -(power(&w.force_1, &w.torque_1, &pose_1)
                + power(&w.force_2, &w.torque_2, &pose_2)),
        }
    }

    /// Kinetic energy ½·m·v² + ½·ω·I·ω (J) of body `b` in state `y`; 0 for a fixed body.
    pub fn kinetic_energy(&self, y: &[f64], b: usize) -> f64 {
        let Some(state) = self.layout.rigid_state(y, b) else {
            return 0.0;
        };
        if self.turns(b) {
            self.bodies[b].kinetic_energy(&state)
        } else {
            0.5 * self.bodies[b].mass() * state.velocity().norm_squared()
        }
    }

    /// Whether body `b` may turn: every body but a moving plane given no inertia tensor
    /// (a 1D scenario's plate, held from turning as in Eq 21).
    fn turns(&self, b: usize) -> bool {
        !self.model.bodies[b].inertia[(0, 0)].is_nan()
    }

    /// Latches the point histories at the accepted state `y` (see `PointMemory`).
    pub fn latch(&mut self, y: &[f64]) {
        for c in 0..self.model.contacts.len() {
            let (pose_1, pose_2) = self.poses(y, c);
            let mut touching = heapless::Vec::<_, { MAX_POINTS }>::new();
            self.each_point(c, &pose_1, &pose_2, |p, feature| {
                let _ = touching.push((feature, p.indentation.depth, p.indentation.rate));
            });
            self.memory[c].latch(touching.into_iter());
        }
    }

    /// Contact force and torque (N, N·m) on every body in state `y`.
    pub fn body_loads(&self, y: &[f64], out: &mut Vec<(Vector3<f64>, Vector3<f64>)>) {
        self.sum_loads(y, out, |_, _| {});
    }

    /// Sums every contact's wrench in state `y` into `out`, one (force, torque) per
    /// body, and hands each contact's load to `each` (the derivative's impulse rates).
    fn sum_loads(
        &self,
        y: &[f64],
        out: &mut Vec<(Vector3<f64>, Vector3<f64>)>,
        mut each: impl FnMut(usize, &ContactLoad),
    ) {
        out.clear();
        out.resize(
            self.model.bodies.len(),
            (Vector3::zeros(), Vector3::zeros()),
        );
        for (c, contact) in self.model.contacts.iter().enumerate() {
            let load = self.contact_load(y, c);
            let w = &load.load.wrench;
            out[contact.body_1].0 += w.force_1;
            out[contact.body_1].1 += w.torque_1;
            out[contact.body_2].0 += w.force_2;
            out[contact.body_2].1 += w.torque_2;
            each(c, &load);
        }
    }
}

impl<const JOINT_PATH: bool> RigidSystem<'_, JOINT_PATH> {
    /// Adds the joints' own torques, then their constraint forces and torques, to
    /// `loads` (the contacts' so far), from every body's motion without the constraints
    /// (`joints.rs`).
    fn add_joint_loads(&self, y: &[f64], loads: &mut [(Vector3<f64>, Vector3<f64>)]) {
        let poses: Vec<_> = (0..self.model.bodies.len())
            .map(|b| self.layout.pose(self.model, y, b))
            .collect();
        add_law_torques(self.model, &poses, loads);
        let motion: Vec<BodyMotion> = (poses.into_iter().enumerate())
            .map(|(b, pose)| {
                let Some(rigid) = self.layout.rigid_state(y, b) else {
                    let zero = Vector3::zeros();
                    let inverse = (0.0, nalgebra::Matrix3::zeros());
                    return BodyMotion {
                        pose,
                        free: (zero, zero),
                        inverse,
                    };
                };
                let (mut force, torque) = loads[b];
                if let Some(drag) = &self.model.bodies[b].air_drag {
                    force += drag.force(&rigid.velocity());
                }
                let mut out = rigid;
                self.bodies[b].derivative(&rigid, &force, &torque, &mut out);
                let c = &out.components;
                let linear = Vector3::new(c[7], c[8], c[9]);
                let (angular, inertia) = match self.turns(b) {
                    true => (
                        pose.orientation * Vector3::new(c[10], c[11], c[12]),
                        world_inverse_inertia(&self.inverse_inertia[b], &pose.orientation),
                    ),
                    false => (Vector3::zeros(), nalgebra::Matrix3::zeros()),
                };
                let inverse = (1.0 / self.model.bodies[b].mass, inertia);
                BodyMotion {
                    pose,
                    free: (linear, angular),
                    inverse,
                }
            })
            .collect();
        add_constraint_loads(self.model, &motion, loads);
    }
}

impl<const JOINT_PATH: bool> OdeSystem<f64, StateVector> for RigidSystem<'_, JOINT_PATH> {
    fn derivative(&mut self, _time: f64, state: &StateVector, derivative: &mut StateVector) {
        let (y, dy) = (&state.0, &mut derivative.0);
        let mut loads = std::mem::take(&mut self.scratch);
        let layout = self.layout;
        self.sum_loads(y, &mut loads, |c, load| {
            let i = layout.impulse_index(c);
            dy[i..i + 3].copy_from_slice(load.on_mover.0.as_slice());
            dy[i + 3..i + 6].copy_from_slice(load.on_mover.1.as_slice());
        });
        if JOINT_PATH && !self.model.joints.is_empty() {
            self.add_joint_loads(y, &mut loads);
        }
        for (b, body) in self.model.bodies.iter().enumerate() {
            let (Some(s), Some(rigid)) = (self.layout.slot(b), self.layout.rigid_state(y, b))
            else {
                continue;
            };
            let (mut force, torque) = loads[b];
            if let Some(drag) = &body.air_drag {
                force += drag.force(&rigid.velocity());
            }
            let mut out = rigid;
            self.bodies[b].derivative(&rigid, &force, &torque, &mut out);
            if !self.turns(b) {
                out.components[10..13].fill(0.0);
            }
            dy[s..s + 13].copy_from_slice(&out.components);
        }
        self.scratch = loads;
    }
}
