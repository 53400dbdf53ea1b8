//! The simulator's integrator: explicit Dormand–Prince ([`Dopri5`]) where its steps
//! are set by accuracy, the linearly implicit RODAS ([`Rodas4`]) where they would be
//! set by stability.
//!
//! Why two: in flight and in most contacts the motion is smooth, and Dopri5's six
//! evaluations per step at 5th order are the least work; at stiction STEP friction's
//! slope makes the equations stiff (see [`super::jacobian`]) and an explicit
//! step must stay below the slip's decay time — the shipped peg's landing took 10 000
//! Dopri5 steps of 10–50 ns each — while RODAS steps over it at the cost of a Jacobian per
//! step. The switch happens between steps, from the current point, so the run stays
//! deterministic and each step's dense output is its own method's.

use super::layout::StateVector;
use super::system::RigidSystem;
use hcm_core::integrate::{DenseOutput, Dopri5, IntegrationError, Rodas4, Settings};

/// One of the two steppers, with the counts of the ones it replaced.
#[derive(Debug)]
pub struct RigidStepper {
    method: Method,
    settings: Settings<f64>,
    /// Accepted and rejected steps of the steppers switched away from.
    earlier: (u64, u64),
    /// Consecutive Dopri5 steps at the edge of its stability region.
    stiff_steps: u32,
    /// Whether the next step is RODAS's.
    stiff: bool,
}

/// h·ρ (–) from which a Dopri5 step counts as held by stability: its stability
/// region reaches |hλ| ≈ 3.3 on the negative real axis, and the step-size control
/// hovers just below it on a stiff stretch.
const STIFF_EDGE: f64 = 3.0;
/// Consecutive such steps before switching to RODAS (one may be a transient).
const STIFF_STEPS: u32 = 3;
/// h·ρ(J) (–) of RODAS's next step below which Dopri5 takes it again.
const NONSTIFF_EDGE: f64 = 2.0;

#[derive(Clone, Debug)]
#[allow(clippy::large_enum_variant)]
enum Method {
    Explicit(Dopri5<f64, StateVector>),
    Implicit(Rodas4<f64, StateVector>),
}

/// By hand for `clone_from`, which reuses the copy's states when both run the same
/// method (the recorder keeps copies of the last few steps).
impl Clone for RigidStepper {
    fn clone(&self) -> Self {
        RigidStepper {
            method: self.method.clone(),
            settings: self.settings,
            earlier: self.earlier,
            stiff_steps: self.stiff_steps,
            stiff: self.stiff,
        }
    }

    fn clone_from(&mut self, source: &Self) {
        match (&mut self.method, &source.method) {
            (Method::Explicit(to), Method::Explicit(from)) => to.clone_from(from),
            (Method::Implicit(to), Method::Implicit(from)) => to.clone_from(from),
            (to, from) => *to = from.clone(),
        }
        (self.settings, self.earlier) = (source.settings, source.earlier);
        (self.stiff_steps, self.stiff) = (source.stiff_steps, source.stiff);
    }
}

impl RigidStepper {
    /// An explicit stepper at (`time` (s), `state`).
    pub fn new<const JOINT_PATH: bool>(
        system: &mut RigidSystem<'_, JOINT_PATH>,
        time: f64,
        state: StateVector,
        settings: Settings<f64>,
    ) -> Self {
        RigidStepper {
            method: Method::Explicit(Dopri5::new(system, time, state, settings)),
            settings,
            earlier: (0, 0),
            stiff_steps: 0,
            stiff: false,
        }
    }

    /// One accepted step towards `until` (s) by the method chosen after the last
    /// one: RODAS after 3 Dopri5 steps held at the edge of its stability region
    /// (h·ρ ≥ 3); Dopri5 again once RODAS's next step is inside that region
    /// (h·ρ(J) < 2). The switch happens before the step,
    /// so the dense output always covers the step just taken.
    pub fn step<const JOINT_PATH: bool>(
        &mut self,
        system: &mut RigidSystem<'_, JOINT_PATH>,
        until: f64,
    ) -> Result<(), IntegrationError> {
        if self.stiff != matches!(self.method, Method::Implicit(_)) {
            self.switch(system, self.stiff);
        }
        self.stiff = match &mut self.method {
            Method::Explicit(s) => {
                s.step(system, until)?;
                self.stiff_steps = if s.stiffness() >= STIFF_EDGE {
                    self.stiff_steps + 1
                } else {
                    0
                };
                self.stiff_steps >= STIFF_STEPS
            }
            Method::Implicit(s) => {
                s.step(system, until)?;
                s.next_step() * system.spectral_radius() >= NONSTIFF_EDGE
            }
        };
        Ok(())
    }

    fn switch<const JOINT_PATH: bool>(
        &mut self,
        system: &mut RigidSystem<'_, JOINT_PATH>,
        stiff: bool,
    ) {
        let (time, state) = (self.time(), self.state().clone());
        let (accepted, rejected) = self.steps();
        self.earlier = (accepted, rejected);
        self.stiff_steps = 0;
        let last = time - self.previous_time();
        let settings = Settings {
            initial_step: if last > 0.0 { last } else { 0.0 },
            ..self.settings
        };
        self.method = if stiff {
            Method::Implicit(Rodas4::new(system, time, state, settings))
        } else {
            Method::Explicit(Dopri5::new(system, time, state, settings))
        };
    }

    /// Restarts the current method from (`time` (s), `state`).
    pub fn restart<const JOINT_PATH: bool>(
        &mut self,
        system: &mut RigidSystem<'_, JOINT_PATH>,
        time: f64,
        state: StateVector,
    ) {
        match &mut self.method {
            Method::Explicit(s) => s.restart(system, time, state),
            Method::Implicit(s) => s.restart(system, time, state),
        }
    }

    /// (accepted, rejected) steps since the start, both methods together.
    pub fn steps(&self) -> (u64, u64) {
        let (a, r) = match &self.method {
            Method::Explicit(s) => (s.accepted_steps(), s.rejected_steps()),
            Method::Implicit(s) => (s.accepted_steps(), s.rejected_steps()),
        };
        (self.earlier.0 + a, self.earlier.1 + r)
    }

    fn dense(&self) -> &dyn DenseOutput<f64, StateVector> {
        match &self.method {
            Method::Explicit(s) => s,
            Method::Implicit(s) => s,
        }
    }
}

impl DenseOutput<f64, StateVector> for RigidStepper {
    fn previous_time(&self) -> f64 {
        self.dense().previous_time()
    }

    fn previous_state(&self) -> &StateVector {
        self.dense().previous_state()
    }

    fn time(&self) -> f64 {
        self.dense().time()
    }

    fn state(&self) -> &StateVector {
        self.dense().state()
    }

    fn dense_output(&self, time: f64, out: &mut StateVector) {
        self.dense().dense_output(time, out);
    }
}
