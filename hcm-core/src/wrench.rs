//! Contact wrench assembly: forces and torques on both bodies, Eq 1.

use crate::{vector, Real};
use nalgebra::Vector3;
use serde::{Deserialize, Serialize};

/// Force and torque that one contact applies to each of its two bodies.
///
/// All vectors are in the frame the inputs were given in; torques are about each
/// body's reference point (the origin of its arm vector).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactWrench<T: Real> {
    /// Force on body 1, F1 = f_n·**n** + **f_f** (N).
    pub force_1: Vector3<T>,
    /// Torque on body 1, T1 = **l1** × F1 (N·m).
    pub torque_1: Vector3<T>,
    /// Force on body 2, F2 = −F1 (N).
    pub force_2: Vector3<T>,
    /// Torque on body 2, T2 = **l2** × F2 (N·m).
    pub torque_2: Vector3<T>,
}

impl<T: Real> ContactWrench<T> {
    /// Assembles Eq 1, F_i = (−1)^(i−1)·(f_n + f_f), T_i = (−1)^(i−1)·l_i × (f_n + f_f)
    /// (the printed "I_i ×" is a misprint for the arm l_i).
    ///
    /// `normal_force` f_n (N, > 0 repulsive) acts along `normal` (unit, from body 2 to
    /// body 1); `friction` **f_f** (N) is the friction force on body 1; `arm_1`, `arm_2`
    /// (m) run from each body's reference point to the contact point. The normal is
    /// used as given (not re-normalised); NaN anywhere propagates.
    pub fn assemble(
        normal_force: T,
        normal: &Vector3<T>,
        friction: &Vector3<T>,
        arm_1: &Vector3<T>,
        arm_2: &Vector3<T>,
    ) -> Self {
        // Written out component by component (`crate::vector`, nalgebra's operation
        // order, the same bits): nalgebra's generic loops cost the controller several
        // times the arithmetic.
        let force_1 = vector::add(&vector::scale(normal, normal_force), friction);
        let force_2 = vector::neg(&force_1);
        ContactWrench {
            force_1,
            torque_1: vector::cross(arm_1, &force_1),
            force_2,
            torque_2: vector::cross(arm_2, &force_2),
        }
    }

    /// A force `force` (N) and torque `torque` (N·m) on body 1 about its reference
    /// point, and their reaction on body 2 about its own, `arm` (m) from body 2's
    /// reference point to body 1's: −F and −(τ + arm × F).
    pub(crate) fn on_body_1(force: &Vector3<T>, torque: &Vector3<T>, arm: &Vector3<T>) -> Self {
        let couple = vector::add(torque, &vector::cross(arm, force));
        ContactWrench {
            force_1: *force,
            torque_1: *torque,
            force_2: vector::neg(force),
            torque_2: vector::neg(&couple),
        }
    }

    /// Adds `other`'s forces and torques to these, each component once (N, N·m).
    #[inline]
    pub(crate) fn accumulate(&mut self, other: &Self) {
        self.force_1 = vector::add(&self.force_1, &other.force_1);
        self.torque_1 = vector::add(&self.torque_1, &other.torque_1);
        self.force_2 = vector::add(&self.force_2, &other.force_2);
        self.torque_2 = vector::add(&self.torque_2, &other.torque_2);
    }
}
