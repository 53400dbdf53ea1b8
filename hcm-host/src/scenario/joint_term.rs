//! The terms of a joint's own law a fit or a diagnosis frees, each by its one
//! coefficient: viscous damping c (N·m·s/rad), Coulomb friction τ_c (N·m), a spring's
//! stiffness k (N·m/rad). Their boxes come from the joint's [`JointScales`]: how much
//! of each a link swinging about its joint under its own weight could show.

use super::{Joint, JointScales};
use hcm_core::joint::{JointCoulomb, JointLaw, JointSpring, JointViscous};

/// One term of a joint's law.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointTerm {
    /// −c·θ̇.
    Viscous,
    /// −sign(θ̇)·τ_c, STEP-smoothed.
    Coulomb,
    /// −k·(θ − θ₀).
    Stiffness,
}

/// The smoothing rate a Coulomb term created by a fit is given, as a fraction of the
/// joint's pendulum rate (–): narrow beside the rates a swinging link reaches, wide
/// enough that sticking is not an ODE's stiffest part.
pub const SMOOTHING_FRACTION: f64 = 0.05;

impl JointTerm {
    /// Every term, in the order a fit lists them.
    pub const ALL: [JointTerm; 3] = [JointTerm::Viscous, JointTerm::Coulomb, JointTerm::Stiffness];

    /// Its keys under a joint's `law`: the term and its coefficient
    /// (`viscous.damping`, `coulomb.torque`, `spring.stiffness`).
    pub fn key(self) -> [&'static str; 2] {
        match self {
            JointTerm::Viscous => ["viscous", "damping"],
            JointTerm::Coulomb => ["coulomb", "torque"],
            JointTerm::Stiffness => ["spring", "stiffness"],
        }
    }

    /// Its coefficient in `law`, where the law has the term.
    pub fn get(self, law: &JointLaw<f64>) -> Option<f64> {
        match self {
            JointTerm::Viscous => law.viscous.map(|t| t.damping),
            JointTerm::Coulomb => law.coulomb.map(|t| t.torque),
            JointTerm::Stiffness => law.spring.map(|t| t.stiffness),
        }
    }

    /// `law` with the coefficient `value` (clamped at 0), the term created where absent
    /// (a Coulomb term smoothed over [`SMOOTHING_FRACTION`] of `scales.rate`, a spring
    /// at rest where the frames align).
    pub fn set(self, law: &mut JointLaw<f64>, value: f64, scales: &JointScales) {
        let value = value.max(0.0);
        match self {
            JointTerm::Viscous => law.viscous = Some(JointViscous { damping: value }),
            JointTerm::Coulomb => {
                let smoothing_rate = (law.coulomb.map(|t| t.smoothing_rate))
                    .unwrap_or(SMOOTHING_FRACTION * scales.rate);
                law.coulomb = Some(JointCoulomb {
                    torque: value,
                    smoothing_rate,
                });
            }
            JointTerm::Stiffness => {
                let rest_angle = law.spring.map_or(0.0, |t| t.rest_angle);
                law.spring = Some(JointSpring {
                    stiffness: value,
                    rest_angle,
                });
            }
        }
    }

    /// The largest coefficient searched (the box is [0, this]): a damping ratio of 2
    /// on the link's pendulum, 4·I·ω̂ (N·m·s/rad); twice its weight's torque, 2·τ̂
    /// (N·m); a spring four times as stiff as its weight's pull, 4·τ̂ per radian
    /// (N·m/rad) — I, τ̂ and ω̂ the joint's [`JointScales`].
    pub fn upper(self, scales: &JointScales) -> f64 {
        match self {
            JointTerm::Viscous => 4.0 * scales.inertia * scales.rate,
            JointTerm::Coulomb => 2.0 * scales.torque,
            JointTerm::Stiffness => 4.0 * scales.torque,
        }
    }

    /// Its unit.
    pub fn unit(self) -> &'static str {
        match self {
            JointTerm::Viscous => "N·m·s/rad",
            JointTerm::Coulomb => "N·m",
            JointTerm::Stiffness => "N·m/rad",
        }
    }
}

impl Joint {
    /// The terms its law declares (a fit frees those).
    pub fn declared_terms(&self) -> impl Iterator<Item = JointTerm> + '_ {
        JointTerm::ALL
            .into_iter()
            .filter(|t| t.get(&self.law).is_some())
    }
}
