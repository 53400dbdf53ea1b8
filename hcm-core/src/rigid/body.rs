//! A rigid body's mass properties and its Newton–Euler derivative (Eq 22).

use super::RigidState;
use crate::Real;
use nalgebra::{Matrix3, Quaternion, Vector3};

/// Mass m (kg), inertia tensor **I** (kg·m², about the centre of mass, body frame) and
/// the gravity **g** (m/s², world frame) a body falls under.
///
/// **I** is inverted once in [`new`](RigidBody::new); a singular or non-finite tensor
/// stores a NaN inverse, so every derivative is NaN (the integrator then reports
/// `NonFinite`) instead of a panic.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RigidBody<T: Real> {
    mass: T,
    inertia: Matrix3<T>,
    inverse_inertia: Matrix3<T>,
    gravity: Vector3<T>,
}

impl<T: Real> RigidBody<T> {
    /// A body of `mass` (kg, > 0), `inertia` (kg·m², symmetric positive definite, about
    /// the centre of mass in the body frame) under `gravity` (m/s², world frame).
    pub fn new(mass: T, inertia: Matrix3<T>, gravity: Vector3<T>) -> Self {
        let inverse_inertia = inertia
            .try_inverse()
            .unwrap_or_else(|| Matrix3::from_element(T::of(f64::NAN)));
        RigidBody {
            mass,
            inertia,
            inverse_inertia,
            gravity,
        }
    }

    /// Mass m (kg).
    pub fn mass(&self) -> T {
        self.mass
    }

    /// Inertia tensor **I** (kg·m², about the centre of mass, body frame).
    pub fn inertia(&self) -> &Matrix3<T> {
        &self.inertia
    }

    /// Gravity **g** (m/s², world frame).
    pub fn gravity(&self) -> &Vector3<T> {
        &self.gravity
    }

    /// The time derivative of `state` under `force` **F** (N, world frame, at the centre
    /// of mass) and `torque` **T** (N·m, world frame, about the centre of mass), written
    /// into `out` — Eq 22 with the misprint corrected (see [`rigid`](super)):
    /// ṗ = v, v̇ = F/m + g, q̇ = ½·q ⊗ (0, ω), ω̇ = I⁻¹·(Rᵀ·T − ω × I·ω).
    ///
    /// q̇ uses the stored q (so ‖q‖ is an invariant of the exact flow); the rotation R
    /// uses q/‖q‖ (so drift in ‖q‖ never scales the torque). NaN propagates.
    pub fn derivative(
        &self,
        state: &RigidState<T>,
        force: &Vector3<T>,
        torque: &Vector3<T>,
        out: &mut RigidState<T>,
    ) {
        let omega = state.body_angular_velocity();
        let acceleration = force / self.mass + self.gravity;
        let velocity = state.velocity();
        let c = &mut out.components;
        c[0..3].copy_from_slice(velocity.as_slice());
        c[7..10].copy_from_slice(acceleration.as_slice());
        // Not turning and no torque (a sphere on its line of centres, every 1D
        // example): q̇ and ω̇ are 0, and the rotation's arithmetic can be skipped.
        let zero = |v: &Vector3<T>| v.iter().all(|x| *x == T::zero());
        if zero(&omega) && zero(torque) {
            c[3..7].fill(T::zero());
            c[10..13].fill(T::zero());
            return;
        }
        let spin = state.quaternion() * Quaternion::from_imag(omega) * T::of(0.5);
        let body_torque = state.orientation().inverse_transform_vector(torque);
        let gyroscopic = omega.cross(&(self.inertia * omega));
        let angular_acceleration = self.inverse_inertia * (body_torque - gyroscopic);
        c[3..7].copy_from_slice(&[spin.w, spin.i, spin.j, spin.k]);
        c[10..13].copy_from_slice(angular_acceleration.as_slice());
    }

    /// Kinetic energy ½·m·v·v + ½·ω·I·ω (J) of `state`.
    pub fn kinetic_energy(&self, state: &RigidState<T>) -> T {
        let v = state.velocity();
        let omega = state.body_angular_velocity();
        let half = T::of(0.5);
        half * self.mass * v.dot(&v) + half * omega.dot(&(self.inertia * omega))
    }

    /// Angular momentum about the centre of mass, R·I·ω (kg·m²/s, world frame).
    pub fn angular_momentum(&self, state: &RigidState<T>) -> Vector3<T> {
        state.orientation() * (self.inertia * state.body_angular_velocity())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;

    fn body() -> RigidBody<f64> {
        let inertia = Matrix3::from_diagonal(&Vector3::new(1.0, 2.0, 3.0));
        RigidBody::new(2.0, inertia, Vector3::new(0.0, 0.0, -9.81))
    }

    fn tilted(omega: Vector3<f64>) -> RigidState<f64> {
        let q = UnitQuaternion::from_euler_angles(0.35, -0.26, 0.1);
        RigidState::new(Vector3::zeros(), q, Vector3::new(1.0, 2.0, 3.0), omega)
    }

    #[test]
    fn force_is_divided_by_mass_and_gravity_added_in_the_world_frame() {
        let state = tilted(Vector3::zeros());
        let mut out = state;
        body().derivative(
            &state,
            &Vector3::new(4.0, 0.0, 0.0),
            &Vector3::zeros(),
            &mut out,
        );
        assert_eq!(out.position(), Vector3::new(1.0, 2.0, 3.0));
        assert_eq!(out.velocity(), Vector3::new(2.0, 0.0, -9.81));
        assert_eq!(out.body_angular_velocity(), Vector3::zeros());
        assert_eq!(out.quaternion(), Quaternion::new(0.0, 0.0, 0.0, 0.0));
    }

    #[test]
    fn a_world_torque_is_rotated_into_the_body_frame() {
        let state = tilted(Vector3::zeros());
        let body_axis = Vector3::new(0.0, 0.0, 1.0);
        let torque = state.orientation() * body_axis * 6.0;
        let mut out = state;
        body().derivative(&state, &Vector3::zeros(), &torque, &mut out);
        let expected = Vector3::new(0.0, 0.0, 2.0); // 6 N·m / 3 kg·m²
        assert!((out.body_angular_velocity() - expected).norm() < 1e-14);
    }

    #[test]
    fn the_gyroscopic_term_and_the_quaternion_rate_follow_euler_and_the_product_rule() {
        let omega = Vector3::new(0.5, -1.0, 2.0);
        let state = tilted(omega);
        let mut out = state;
        body().derivative(&state, &Vector3::zeros(), &Vector3::zeros(), &mut out);
        // Euler, torque-free, diag(1, 2, 3): ω̇1 = (I2 − I3)ω2ω3/I1, and cyclic.
        let (w1, w2, w3) = (omega.x, omega.y, omega.z);
        let expected = Vector3::new(
            (2.0 - 3.0) * w2 * w3 / 1.0,
            (3.0 - 1.0) * w3 * w1 / 2.0,
            (1.0 - 2.0) * w1 * w2 / 3.0,
        );
        assert!((out.body_angular_velocity() - expected).norm() < 1e-14);
        // q̇ is orthogonal to q, so ‖q‖ is invariant.
        let dot = state.quaternion().coords.dot(&out.quaternion().coords);
        assert!(dot.abs() < 1e-15);
        assert!((out.quaternion().norm() - 0.5 * omega.norm()).abs() < 1e-15);
    }

    #[test]
    fn a_singular_inertia_gives_nan_not_a_panic() {
        let singular = RigidBody::new(1.0, Matrix3::zeros(), Vector3::zeros());
        let state = tilted(Vector3::new(1.0, 0.0, 0.0));
        let mut out = state;
        singular.derivative(&state, &Vector3::zeros(), &Vector3::zeros(), &mut out);
        assert!(out.components[10].is_nan());
        let nan = Vector3::new(f64::NAN, 0.0, 0.0);
        body().derivative(&state, &nan, &nan, &mut out);
        assert!(out.components[7].is_nan());
    }
}
