//! The contact model: the one type a controller ships and every host stage —
//! simulation, identification, training, evaluation, diagnosis — evaluates.
//!
//! For one body pair touching at the points p_1 … p_k (a [`Manifold`]):
//!
//! - at each point, the normal force f_n = f_law(δ_eff, δ̇, δ̇0) + Σ effects
//!   ([`ExtendedLaw`]: a law of Eq 2–9 with the catalogued effects), exactly 0 for
//!   δ ≤ 0, and the friction force **f_f** of Eq 10–11 from the slip velocity and f_n;
//! - the pair's wrench by Eq 1, summed over the points: F1 = Σ (f_n·**n** + **f_f**),
//!   T1 = Σ l1 × (f_n·**n** + **f_f**), and the opposite on body 2;
//! - plus the learned residual r(x) (Section 3.2, Eq 12), added only while at least
//!   one point touches and the residual's input lies inside its training envelope
//!   ([`Residual`]); elsewhere the physics alone, and [`Evaluated`] says which. A
//!   contact-frame residual ([`PerPoint`]) instead adds its correction at each
//!   touching point, from that point's own state ([`point_residual`]).
//!
//! Generic over [`Real`]: `f32` in the controller, `f64` in the host's stiff
//! simulation, the same formulas in both.

mod point;
pub mod point_residual;
mod residual;

pub use point::{ContactPoint, Manifold, PointForce, MAX_POINTS};
pub use point_residual::{PerPoint, POINT_INPUTS, POINT_OUTPUTS};
pub use residual::{Correction, NoResidual, Residual};

use crate::effect::{ContactMemory, ExtendedLaw};
use crate::friction::{TangentialEffects, VelocityStepFriction};
use crate::law::{touching, AnyNormalLaw, Indentation};
use crate::residual::Excursion;
use crate::wrench::ContactWrench;
use crate::{vector, LawError, Real};
use nalgebra::Vector3;

/// Which parts of the contact model produced a force.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Evaluated {
    /// In contact, with the residual's input inside its training envelope: physics +
    /// residual.
    PhysicsAndResidual,
    /// Out of contact, no residual, or its input outside the envelope (or NaN): the
    /// physics alone.
    PhysicsOnly,
}

/// Physics (normal law + effects + friction) plus a learned residual `R`.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactModel<T, R = NoResidual> {
    /// The normal law with its effects, identified parameters.
    pub normal: ExtendedLaw<T>,
    /// The tangential law (Eq 10–11); `None`: frictionless.
    pub friction: Option<VelocityStepFriction<T>>,
    /// Tangential effects beside it (viscous friction, torsional and rolling
    /// resistance); none by default.
    pub tangential: TangentialEffects<T>,
    /// The learned correction ([`NoResidual`] for physics alone).
    pub residual: R,
}

/// The loads one body pair's contact applies: what [`ContactModel::pair_load`] returns.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairLoad<T: Real> {
    /// Forces and torques on both bodies about their reference points (N, N·m).
    pub wrench: ContactWrench<T>,
    /// Σ f_n over the points, a normal-force correction included (N).
    pub normal_force: T,
    /// Whether the residual took part (why not: [`ContactModel::excursion`]).
    pub evaluated: Evaluated,
}

impl<T: Real> ContactModel<T, NoResidual> {
    /// The physics alone: `law` (with or without effects), frictionless.
    pub fn physics(law: impl Into<ExtendedLaw<T>>) -> Self {
        ContactModel {
            normal: law.into(),
            friction: None,
            tangential: TangentialEffects::default(),
            residual: NoResidual,
        }
    }
}

impl<T: Real, R> ContactModel<T, R> {
    /// The same physics with `residual` as its learned part.
    pub fn with_residual<S>(self, residual: S) -> ContactModel<T, S> {
        ContactModel {
            normal: self.normal,
            friction: self.friction,
            tangential: self.tangential,
            residual,
        }
    }

    /// The same model with friction law `friction`.
    pub fn with_friction(mut self, friction: VelocityStepFriction<T>) -> Self {
        self.friction = Some(friction);
        self
    }

    /// The base normal law (without effects).
    pub fn law(&self) -> &AnyNormalLaw<T> {
        &self.normal.base
    }

    /// Physics normal force f_n (N, > 0 repulsive) at one point: the law with its
    /// effects; exactly 0 for δ ≤ 0, NaN propagates, saturates at ±[`Real::MAX`].
    #[inline]
    pub fn physics_normal_force(
        &self,
        indentation: &Indentation<T>,
        memory: &ContactMemory<T>,
    ) -> T {
        if !touching(indentation.depth) {
            return T::zero();
        }
        self.normal.normal_force(indentation, memory)
    }

    /// Physics force at one point: f_n, the friction from the point's slip, and the
    /// couple of the tangential effects.
    #[inline]
    pub fn point_force(&self, point: &ContactPoint<T>) -> PointForce<T> {
        let normal_force = self.physics_normal_force(&point.indentation, &point.memory);
        self.point_force_with(point, normal_force)
    }

    /// The force at one point under normal force `normal_force` (N): the friction law
    /// and the tangential effects read it (none for 0).
    #[inline]
    pub fn point_force_with(&self, point: &ContactPoint<T>, normal_force: T) -> PointForce<T> {
        let mut friction = match &self.friction {
            Some(law) if normal_force != T::zero() => {
                law.force(&point.relative_velocity, &point.normal, normal_force)
            }
            _ => Vector3::zeros(),
        };
        let mut couple = Vector3::zeros();
        if normal_force != T::zero() && !self.tangential.is_empty() {
            let (extra, c) = self.tangential.point_loads(
                &point.relative_velocity,
                &point.relative_angular_velocity,
                &point.normal,
                normal_force,
            );
            friction += extra;
            couple = c;
        }
        PointForce {
            normal_force,
            friction,
            couple,
        }
    }

    /// `Ok` if the normal law, its effects and the friction law are in their
    /// physical domains; otherwise the first problem.
    pub fn validate(&self) -> Result<(), LawError> {
        self.normal.validate()?;
        self.friction.as_ref().map_or(Ok(()), |f| f.validate())?;
        self.tangential.validate()
    }

    /// The same model in another float type (f64 → f32 rounds each parameter); the
    /// residual is kept as it is.
    pub fn cast<U: Real>(&self) -> ContactModel<U, R>
    where
        R: Clone,
    {
        ContactModel {
            normal: self.normal.cast(),
            friction: self.friction.map(|f| f.map(Real::cast)),
            tangential: self.tangential.map(Real::cast),
            residual: self.residual.clone(),
        }
    }
}

impl<T: Real, R: Residual<T>> ContactModel<T, R> {
    /// Normal force magnitude f_n (N, > 0 repulsive) of a single-point, frictionless
    /// contact (the 1D examples), and what produced it.
    ///
    /// Exactly (0, `PhysicsOnly`) for δ ≤ 0. In contact, the physics plus the
    /// residual's [`Correction::NormalForce`], saturated at ±[`Real::MAX`] (not
    /// clamped at zero: a correction may leave the force slightly tensile, as the data
    /// said). A residual switched off, or one that returns a wrench (which needs the
    /// geometry of [`ContactModel::pair_load`]), leaves the physics alone.
    pub fn normal_force(
        &self,
        indentation: &Indentation<T>,
        memory: &ContactMemory<T>,
        residual_input: &[T],
    ) -> (T, Evaluated) {
        if !touching(indentation.depth) {
            return (T::zero(), Evaluated::PhysicsOnly);
        }
        let physics = self.normal.normal_force(indentation, memory);
        match self.residual.correction(residual_input) {
            Some(Correction::NormalForce(correction)) => (
                (physics + correction).saturate(),
                Evaluated::PhysicsAndResidual,
            ),
            _ => (physics, Evaluated::PhysicsOnly),
        }
    }

    /// Which input of `residual_input` lies outside the residual's training envelope
    /// and by how much (its unit), or `None` inside it: why a contact that
    /// [`ContactModel::normal_force`] or [`ContactModel::pair_load`] reports as
    /// [`Evaluated::PhysicsOnly`] got no correction. A separate call rather than a field
    /// of every result: the check costs as much again as the envelope test, and only a
    /// controller that logs the switch-off needs it.
    pub fn excursion(&self, residual_input: &[T]) -> Option<Excursion> {
        self.residual.excursion(residual_input)
    }

    /// The loads of a body pair touching at `points`: Eq 1 at every point, summed,
    /// plus the residual's correction while any point touches.
    ///
    /// `reference_1`, `reference_2` (m) are the bodies' reference points (centres of
    /// mass), about which torques are taken; every vector in one frame. A
    /// [`Correction::NormalForce`] acts along the first point's normal at that
    /// point; a [`Correction::Wrench`] on body 1 about `reference_1`, with the
    /// opposite force on body 2 (its torque taken about `reference_2`). No points,
    /// or none touching: zero loads, physics only.
    pub fn pair_load(
        &self,
        points: &[ContactPoint<T>],
        reference_1: &Vector3<T>,
        reference_2: &Vector3<T>,
        residual_input: &[T],
    ) -> PairLoad<T> {
        let touches = |p: &&ContactPoint<T>| touching(p.indentation.depth);
        let Some((at, first)) = points.iter().enumerate().find(|(_, p)| touches(p)) else {
            return PairLoad {
                wrench: zero_wrench(),
                normal_force: T::zero(),
                evaluated: Evaluated::PhysicsOnly,
            };
        };
        // The residual was trained on (measured − physics): it adds to the physics'
        // result and does not feed back into the friction law.
        let correction = self.residual.correction(residual_input);
        let mut corrected_points = false;
        let mut force = self.corrected_point_force(first, &mut corrected_points);
        if let Some(Correction::NormalForce(extra)) = correction {
            force.normal_force = (force.normal_force + extra).saturate();
        }
        // The first point's wrench is assembled directly (the common single-point
        // contact pays for no summation); the others add to it.
        let mut load = PairLoad {
            wrench: point_wrench(first, &force, reference_1, reference_2),
            normal_force: force.normal_force,
            evaluated: Evaluated::PhysicsOnly,
        };
        let rest = points.get(at + 1..).unwrap_or(&[]);
        for point in rest.iter().filter(touches) {
            let force = self.corrected_point_force(point, &mut corrected_points);
            load.normal_force = (load.normal_force + force.normal_force).saturate();
            let w = point_wrench(point, &force, reference_1, reference_2);
            load.wrench.accumulate(&w);
        }
        if correction.is_some() || corrected_points {
            load.evaluated = Evaluated::PhysicsAndResidual;
        }
        let Some(correction) = correction else {
            return load;
        };
        // Added as the points' wrenches are (`ContactWrench::accumulate`, written out
        // per component: nalgebra's operators took 204 instructions more per peg
        // HCM). Subtracting the reaction is adding its negation, bit for bit.
        let extra = match correction {
            Correction::Wrench { force, torque } => {
                let arm = vector::sub(reference_1, reference_2);
                ContactWrench::on_body_1(&force, &torque, &arm)
            }
            Correction::PairWrench {
                force_1,
                torque_1,
                force_2,
                torque_2,
            } => ContactWrench {
                force_1,
                torque_1,
                force_2,
                torque_2,
            },
            Correction::NormalForce(_) => return load,
        };
        load.wrench.accumulate(&extra);
        load
    }
}

impl<T: Real, R: Residual<T>> ContactModel<T, R> {
    /// The physics force at a touching `point` plus a contact-frame residual's
    /// correction there, if it gives one (then `corrected` is set): the normal
    /// correction added before friction reads the normal force (a tensile total gives
    /// no friction), the friction law's force at the law's own normal force scaled by
    /// r_f, and the motion's terms beside them.
    #[inline]
    fn corrected_point_force(
        &self,
        point: &ContactPoint<T>,
        corrected: &mut bool,
    ) -> PointForce<T> {
        let Some(outputs) = self.residual.point_correction(point) else {
            return self.point_force(point);
        };
        *corrected = true;
        let physics = self.physics_normal_force(&point.indentation, &point.memory);
        let normal = (physics + point_residual::normal_correction(point, &outputs)).saturate();
        let pressing = if normal < T::zero() {
            T::zero()
        } else {
            normal
        };
        let mut force = self.point_force_with(point, pressing);
        force.normal_force = normal;
        if let Some(law) = &self.friction {
            let scale = point_residual::friction_scale(&outputs);
            force.friction += law.force(&point.relative_velocity, &point.normal, physics) * scale;
        }
        let (friction, couple) = point_residual::tangential_correction(point, &outputs);
        force.friction += friction;
        force.couple += couple;
        force
    }
}

fn zero_wrench<T: Real>() -> ContactWrench<T> {
    ContactWrench {
        force_1: Vector3::zeros(),
        torque_1: Vector3::zeros(),
        force_2: Vector3::zeros(),
        torque_2: Vector3::zeros(),
    }
}

/// One point's force on both bodies by Eq 1: `force` at `point`, torques about
/// `reference_1` and `reference_2` (m). Linear in `force`: the host weighs a
/// contact-frame residual's outputs by the wrench each makes alone.
#[inline]
pub fn point_wrench<T: Real>(
    point: &ContactPoint<T>,
    force: &PointForce<T>,
    reference_1: &Vector3<T>,
    reference_2: &Vector3<T>,
) -> ContactWrench<T> {
    let mut wrench = ContactWrench::assemble(
        force.normal_force,
        &point.normal,
        &force.friction,
        &vector::sub(&point.position, reference_1),
        &vector::sub(&point.position, reference_2),
    );
    wrench.torque_1 = vector::add(&wrench.torque_1, &force.couple);
    wrench.torque_2 = vector::sub(&wrench.torque_2, &force.couple);
    wrench
}

#[cfg(test)]
mod tests;
