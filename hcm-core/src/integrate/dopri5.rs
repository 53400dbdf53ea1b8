//! The Dormand–Prince 5(4) stepper with dense output ("DOPRI5").
//!
//! Method: the embedded Runge–Kutta pair of Dormand & Prince, "A family of embedded
//! Runge–Kutta formulae", J. Comput. Appl. Math. 6 (1980) 19–26: seven stages, the
//! fifth-order solution is propagated (local extrapolation), the fourth-order one only
//! estimates the error, and the last stage is the first stage of the next step
//! (FSAL), so an accepted step costs six evaluations of f.
//!
//! Step-size control, error norm and starting step follow Hairer, Nørsett & Wanner,
//! *Solving Ordinary Differential Equations I* (2nd ed., Springer 1993), Section II.4;
//! the continuous extension is Shampine's fourth-order one ("Some practical
//! Runge–Kutta formulas", Math. Comp. 46 (1986) 135–150) in the form used by the
//! book's DOPRI5 code (Section II.6).

use super::interval::{next_interval, step_cap};
use super::state::copy_states;
use super::vector::{all_finite, combine, error_norm, increment, is_finite, scaled_rms};
use super::{IntegrationError, OdeState, OdeSystem};
use crate::Real;

// Dormand–Prince tableau (Hairer–Nørsett–Wanner, Table II.5.2). Nodes c_i (fraction
// of the step), coefficients a_ij, weights b_i of the 5th-order solution; stage 7 is
// taken at c = 1 with a_7j = b_j (FSAL).
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;

const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;

const B1: f64 = 35.0 / 384.0;
const B3: f64 = 500.0 / 1113.0;
const B4: f64 = 125.0 / 192.0;
const B5: f64 = -2187.0 / 6784.0;
const B6: f64 = 11.0 / 84.0;

// e_i = b_i − b̂_i: 5th-order minus embedded 4th-order weights (b_2 = b̂_2 = 0).
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;

// Shampine's dense-output coefficients, as in the DOPRI5 code (CONTD5) of
// Hairer–Nørsett–Wanner.
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

/// Safety factor of the step-size formula (dimensionless).
const SAFETY: f64 = 0.9;
/// Smallest step-size ratio h_new / h (dimensionless).
const FACTOR_MIN: f64 = 0.2;
/// Largest step-size ratio h_new / h (dimensionless).
const FACTOR_MAX: f64 = 10.0;
/// Step (s) tried when the starting-step heuristic has nothing to go on (Hairer's
/// fallback).
const FALLBACK_STEP: f64 = 1e-6;

/// Tolerances and step bounds of a [`Dopri5`] run.
///
/// A step is accepted when the RMS over components of e_i / sc_i is ≤ 1, with e_i the
/// embedded error estimate and sc_i = `absolute_tolerance` +
/// `relative_tolerance`·max(|y0_i|, |y1_i|) (Hairer–Nørsett–Wanner eq. II.4.11).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings<T> {
    /// Relative tolerance (dimensionless), finite and ≥ 0.
    pub relative_tolerance: T,
    /// Absolute tolerance, in the state's units (the same for every component),
    /// finite and ≥ 0; not both tolerances zero.
    pub absolute_tolerance: T,
    /// First step (s); <= 0 means choose automatically (Hairer's initial-step heuristic).
    pub initial_step: T,
    /// Longest step (s) ever taken, > 0 (`T::MAX` for no bound).
    pub max_step: T,
    /// A step shorter than this (s) is an error (stiff or diverging run).
    pub min_step: T,
    /// Accepted + rejected steps allowed in total before an error (bounds run time).
    pub max_steps: u64,
}

impl<T: Real> Settings<T> {
    /// The given tolerances (relative: dimensionless; absolute: state units) and
    /// defaults for the rest: automatic first step, no longest step, shortest step
    /// 1e-15 s, 10 000 000 attempts.
    pub fn new(relative_tolerance: T, absolute_tolerance: T) -> Self {
        Settings {
            relative_tolerance,
            absolute_tolerance,
            initial_step: T::zero(),
            max_step: T::MAX,
            min_step: T::of(1e-15),
            max_steps: 10_000_000,
        }
    }

    /// `Ok` if every field is in its domain, otherwise
    /// [`IntegrationError::InvalidSettings`] naming the first one that is not.
    /// [`Dopri5::step`] checks this before stepping.
    pub fn validate(&self) -> Result<(), IntegrationError> {
        let tolerance_ok = |value: T| value >= T::zero() && value <= T::MAX;
        if !tolerance_ok(self.relative_tolerance) {
            return Err(IntegrationError::InvalidSettings {
                setting: "relative_tolerance",
            });
        }
        if !tolerance_ok(self.absolute_tolerance) {
            return Err(IntegrationError::InvalidSettings {
                setting: "absolute_tolerance",
            });
        }
        if self.relative_tolerance == T::zero() && self.absolute_tolerance == T::zero() {
            return Err(IntegrationError::InvalidSettings {
                setting: "absolute_tolerance",
            });
        }
        if self.min_step.positive().is_none() {
            return Err(IntegrationError::InvalidSettings {
                setting: "min_step",
            });
        }
        // +∞ is allowed and means "no bound"; NaN is not.
        if self.max_step.is_nan() || self.max_step <= T::zero() {
            return Err(IntegrationError::InvalidSettings {
                setting: "max_step",
            });
        }
        Ok(())
    }
}

/// The adaptive Dormand–Prince 5(4) integrator, advanced one accepted step at a time.
///
/// It holds the current point (t, y), the previous accepted point, the stages of the
/// last step and its dense-output coefficients, so that between two calls to
/// [`step`](Dopri5::step) the caller can read the solution anywhere in the step just
/// taken ([`dense_output`](Dopri5::dense_output)), locate events in it
/// ([`locate_crossing`](super::locate_crossing)) and [`restart`](Dopri5::restart) from
/// an event. All working states are clones of the initial state; nothing is
/// allocated.
///
/// Accuracy: 5th order per step (local error O(h⁵) per unit step, controlled by the
/// tolerances), dense output 4th order. It is an explicit method: for a stiff system
/// (a contact spring much stiffer than the tolerance can follow) it takes very small
/// steps, bounded by [`Settings::min_step`] and [`Settings::max_steps`].
#[derive(Debug)]
pub struct Dopri5<T: Real, S: OdeState<T>> {
    settings: Settings<T>,
    /// Current time t (s).
    time: T,
    /// Current state y(t).
    state: S,
    /// Start time (s) of the last accepted step.
    previous_time: T,
    /// State at `previous_time`.
    previous_state: S,
    /// Length h (s) of the last accepted step; 0 after `new` and `restart`.
    last_step: T,
    /// Step (s) to try next: finite and > 0.
    next_step: T,
    /// Stage derivatives k1 … k7 of the last attempt; k1 = f(time, state) (FSAL).
    stages: [S; 7],
    /// Working space: a stage's argument, then the error estimate.
    stage_state: S,
    /// Working space: the candidate y1 of an attempt.
    trial: S,
    /// Dense-output coefficients r2 … r5 of the last accepted step (CONTD5 form).
    dense: [S; 4],
    /// h·ρ of the last attempt and of the last accepted step (–), ρ the stiffness
    /// estimate ‖k₇ − k₆‖ / ‖y₁ − Y₆‖ (see [`Dopri5::stiffness`]).
    attempt_stiffness: T,
    stiffness: T,
    accepted: u64,
    rejected: u64,
}

/// By hand for `clone_from`, which copies into the existing states (a recorder
/// keeps a few steps' copies to sample after the stepper moved on, without
/// allocating per step); the derived one would allocate every state anew.
impl<T: Real, S: OdeState<T>> Clone for Dopri5<T, S> {
    fn clone(&self) -> Self {
        Dopri5 {
            settings: self.settings,
            time: self.time,
            state: self.state.clone(),
            previous_time: self.previous_time,
            previous_state: self.previous_state.clone(),
            last_step: self.last_step,
            next_step: self.next_step,
            stages: self.stages.clone(),
            stage_state: self.stage_state.clone(),
            trial: self.trial.clone(),
            dense: self.dense.clone(),
            attempt_stiffness: self.attempt_stiffness,
            stiffness: self.stiffness,
            accepted: self.accepted,
            rejected: self.rejected,
        }
    }

    fn clone_from(&mut self, source: &Self) {
        // Destructured so that a new field cannot be forgotten here.
        let Dopri5 {
            settings,
            time,
            state,
            previous_time,
            previous_state,
            last_step,
            next_step,
            stages,
            stage_state,
            trial,
            dense,
            attempt_stiffness,
            stiffness,
            accepted,
            rejected,
        } = source;
        (self.settings, self.time, self.previous_time) = (*settings, *time, *previous_time);
        (self.last_step, self.next_step) = (*last_step, *next_step);
        (self.attempt_stiffness, self.stiffness) = (*attempt_stiffness, *stiffness);
        (self.accepted, self.rejected) = (*accepted, *rejected);
        self.state.clone_from(state);
        self.previous_state.clone_from(previous_state);
        self.stage_state.clone_from(stage_state);
        self.trial.clone_from(trial);
        copy_states(&mut self.stages, stages);
        copy_states(&mut self.dense, dense);
    }
}

impl<T: Real, S: OdeState<T>> Dopri5<T, S> {
    /// Starts at (`time` (s), `state`) with `settings`.
    ///
    /// Evaluates f once at the start (the FSAL derivative) and, when
    /// `settings.initial_step` is not > 0, once more for Hairer's starting-step
    /// heuristic (Hairer–Nørsett–Wanner, Section II.4, "Starting Step Size"). Never
    /// fails: bad settings are reported by the first [`step`](Dopri5::step).
    pub fn new(
        system: &mut impl OdeSystem<T, S>,
        time: T,
        state: S,
        settings: Settings<T>,
    ) -> Self {
        let mut stepper = Dopri5 {
            settings,
            time,
            previous_time: time,
            previous_state: state.clone(),
            last_step: T::zero(),
            next_step: T::of(FALLBACK_STEP),
            stages: core::array::from_fn(|_| state.clone()),
            stage_state: state.clone(),
            trial: state.clone(),
            dense: core::array::from_fn(|_| state.clone()),
            state,
            attempt_stiffness: T::zero(),
            stiffness: T::zero(),
            accepted: 0,
            rejected: 0,
        };
        let [k1, ..] = &mut stepper.stages;
        system.derivative(time, &stepper.state, k1);
        stepper.next_step = stepper.initial_step(system);
        stepper
    }

    /// Current time t (s): the end of the last accepted step.
    pub fn time(&self) -> T {
        self.time
    }

    /// Current state y(t).
    pub fn state(&self) -> &S {
        &self.state
    }

    /// Start time (s) of the last accepted step (= [`time`](Dopri5::time) after `new`
    /// or `restart`).
    pub fn previous_time(&self) -> T {
        self.previous_time
    }

    /// State at [`previous_time`](Dopri5::previous_time).
    pub fn previous_state(&self) -> &S {
        &self.previous_state
    }

    /// The settings the stepper runs with.
    pub fn settings(&self) -> &Settings<T> {
        &self.settings
    }

    /// Steps accepted since `new`.
    pub fn accepted_steps(&self) -> u64 {
        self.accepted
    }

    /// h·ρ of the last accepted step (–): ρ = ‖k₇ − k₆‖ / ‖y₁ − Y₆‖, the two last
    /// stages being taken at the same time, estimates the largest |λ| of ∂f/∂y
    /// along the step (Hairer–Nørsett–Wanner, Section IV.2 of volume II, as their
    /// DOPRI5 code's stiffness test). Near 3.3, the edge of the method's stability
    /// region, the step is held by stability rather than accuracy: the problem is
    /// stiff there. 0 before the first step and when ‖y₁ − Y₆‖ = 0.
    pub fn stiffness(&self) -> T {
        self.stiffness
    }

    /// Attempts rejected since `new` (error too large, or a NaN/∞ in the attempt).
    pub fn rejected_steps(&self) -> u64 {
        self.rejected
    }

    /// Takes one accepted step (retrying rejected ones internally), never beyond `until` (s)
    /// and never longer than min(settings.max_step, system.step_limit(t, y)).
    /// After it, [previous_time, time] is the step just taken and dense_output covers it.
    /// If time() >= until already, returns Ok without stepping.
    ///
    /// A step that would end within 1 % of a step length before `until` is stretched
    /// to end exactly at `until` (the time is then `until` itself, bit for bit), and so
    /// is a step to an `until` closer than `min_step`. A NaN `until` never steps.
    ///
    /// After a rejection the step shrinks by 0.9·err^(−1/5) (≥ 0.2×) and the next
    /// accepted step does not grow; after an acceptance it changes by that factor within
    /// [0.2, 10]. A NaN or ∞ in an attempt's state or error estimate counts as a
    /// rejection shrinking the step 5×.
    ///
    /// # Errors
    ///
    /// - [`IntegrationError::InvalidSettings`] if [`Settings::validate`] fails;
    /// - [`IntegrationError::NonFinite`] if the current state or its derivative is not
    ///   finite, or attempts kept being non-finite down to `min_step`;
    /// - [`IntegrationError::StepTooSmall`] if the error test needs a step below
    ///   `min_step` (or below the time's float resolution);
    /// - [`IntegrationError::TooManySteps`] once accepted + rejected attempts reach
    ///   `max_steps`.
    ///
    /// On error the stepper stays at its last accepted point.
    pub fn step(
        &mut self,
        system: &mut impl OdeSystem<T, S>,
        until: T,
    ) -> Result<(), IntegrationError> {
        if until.is_nan() || self.time >= until {
            return Ok(());
        }
        self.settings.validate()?;
        let [k1, ..] = &self.stages;
        if !is_finite(self.time) || !all_finite(&self.state) || !all_finite(k1) {
            return Err(IntegrationError::NonFinite {
                time: self.time.to_f64(),
            });
        }
        let Settings {
            relative_tolerance,
            absolute_tolerance,
            min_step,
            max_steps,
            ..
        } = self.settings;
        // (t, y) stay put until an attempt is accepted, and so does the cap.
        let cap = step_cap(&self.settings, system.step_limit(self.time, &self.state));
        // Whether the last rejection was caused by a NaN/∞ (decides the error kind).
        let mut non_finite = false;
        // Whether this call rejected an attempt (then the step may not grow).
        let mut rejected_here = false;
        loop {
            let attempts = self.accepted.saturating_add(self.rejected);
            if attempts >= max_steps {
                return Err(IntegrationError::TooManySteps {
                    time: self.time.to_f64(),
                    steps: attempts,
                });
            }
            let guess = self.next_step;
            let (h, end) =
                next_interval(&self.settings, self.time, guess, (cap, until), non_finite)?;
            let clamped = h < guess;

            self.attempt(system, h, end);
            let error = error_norm(
                &self.stage_state,
                &self.state,
                &self.trial,
                relative_tolerance,
                absolute_tolerance,
            );
            match error {
                None => {
                    self.rejected = self.rejected.saturating_add(1);
                    non_finite = true;
                    rejected_here = true;
                    self.next_step = h * T::of(FACTOR_MIN);
                }
                Some(error) if error > T::one() => {
                    self.rejected = self.rejected.saturating_add(1);
                    non_finite = false;
                    rejected_here = true;
                    let factor = step_factor(error);
                    self.next_step = h * if factor < T::one() { factor } else { T::one() };
                }
                Some(error) => {
                    let mut factor = step_factor(error);
                    if rejected_here && factor > T::one() {
                        factor = T::one();
                    }
                    let mut next = h * factor;
                    // A step cut short by `until` or the step cap says little about the
                    // step the tolerance allows: keep the earlier guess if this one only
                    // grew by the maximum factor.
                    if clamped && factor >= T::of(FACTOR_MAX) && next < guess {
                        next = guess;
                    }
                    if next < min_step {
                        next = min_step;
                    }
                    if !is_finite(next) {
                        next = T::MAX;
                    }
                    self.next_step = next;
                    self.accept(h, end);
                    return Ok(());
                }
            }
        }
    }

    /// 4th-order continuous extension at `time` in [previous_time, time] (clamped to that interval), written into `out`.
    ///
    /// `time` in s. `out` becomes a clone of the previous state with its components
    /// replaced, so any non-component data comes from the previous state. At (or
    /// beyond) either end it is the stored state exactly; after `new` or `restart`
    /// (an empty interval) and for a NaN `time` it is the previous state.
    pub fn dense_output(&self, time: T, out: &mut S) {
        let h = self.last_step;
        let theta = (time - self.previous_time) / h;
        if h.is_nan() || theta.is_nan() || h <= T::zero() || theta <= T::zero() {
            out.clone_from(&self.previous_state);
            return;
        }
        if theta >= T::one() {
            out.clone_from(&self.state);
            return;
        }
        let theta1 = T::one() - theta;
        out.clone_from(&self.previous_state);
        let [r2, r3, r4, r5] = &self.dense;
        let coefficients = self
            .previous_state
            .components()
            .iter()
            .zip(r2.components())
            .zip(r3.components())
            .zip(r4.components())
            .zip(r5.components());
        for (o, ((((y0, r2), r3), r4), r5)) in out.components_mut().iter_mut().zip(coefficients) {
            *o = *y0 + theta * (*r2 + theta1 * (*r3 + theta * (*r4 + theta1 * *r5)));
        }
    }

    /// Restarts from (time, state): used after an event changed the system (e.g. a contact
    /// began and a law parameter was latched). Re-evaluates the FSAL derivative; keeps the current step size guess.
    /// previous_time/previous_state become (time, state) so dense output is the point itself.
    ///
    /// `time` in s. The step counters keep counting. Working states are re-cloned from
    /// `state`.
    pub fn restart(&mut self, system: &mut impl OdeSystem<T, S>, time: T, state: S) {
        for working in self.stages.iter_mut().chain(self.dense.iter_mut()).chain([
            &mut self.stage_state,
            &mut self.trial,
            &mut self.previous_state,
        ]) {
            working.clone_from(&state);
        }
        self.state = state;
        self.time = time;
        self.previous_time = time;
        self.last_step = T::zero();
        let [k1, ..] = &mut self.stages;
        system.derivative(time, &self.state, k1);
    }

    /// One attempt of length `h` (s) ending at `end` (s): fills k2 … k7, the candidate
    /// y1 (`trial`) and the error estimate (`stage_state`).
    fn attempt(&mut self, system: &mut impl OdeSystem<T, S>, h: T, end: T) {
        let t = self.time;
        let y = &self.state;
        let arg = &mut self.stage_state;
        let [k1, k2, k3, k4, k5, k6, k7] = &mut self.stages;
        let at = |c: f64| t + T::of(c) * h;

        combine(arg, y, h, &[(T::of(A21), &*k1)]);
        system.derivative(at(C2), arg, k2);
        combine(arg, y, h, &[(T::of(A31), &*k1), (T::of(A32), &*k2)]);
        system.derivative(at(C3), arg, k3);
        combine(
            arg,
            y,
            h,
            &[(T::of(A41), &*k1), (T::of(A42), &*k2), (T::of(A43), &*k3)],
        );
        system.derivative(at(C4), arg, k4);
        combine(
            arg,
            y,
            h,
            &[
                (T::of(A51), &*k1),
                (T::of(A52), &*k2),
                (T::of(A53), &*k3),
                (T::of(A54), &*k4),
            ],
        );
        system.derivative(at(C5), arg, k5);
        combine(
            arg,
            y,
            h,
            &[
                (T::of(A61), &*k1),
                (T::of(A62), &*k2),
                (T::of(A63), &*k3),
                (T::of(A64), &*k4),
                (T::of(A65), &*k5),
            ],
        );
        system.derivative(end, arg, k6);
        combine(
            &mut self.trial,
            y,
            h,
            &[
                (T::of(B1), &*k1),
                (T::of(B3), &*k3),
                (T::of(B4), &*k4),
                (T::of(B5), &*k5),
                (T::of(B6), &*k6),
            ],
        );
        system.derivative(end, &self.trial, k7);
        self.attempt_stiffness = h * stiffness_ratio(k7, k6, &self.trial, arg);
        increment(
            arg,
            h,
            &[
                (T::of(E1), &*k1),
                (T::of(E3), &*k3),
                (T::of(E4), &*k4),
                (T::of(E5), &*k5),
                (T::of(E6), &*k6),
                (T::of(E7), &*k7),
            ],
        );
    }

    /// Accepts the attempt of length `h` (s) ending at `end` (s): stores the dense
    /// coefficients, moves (t, y) to (end, y1) and k7 into k1.
    fn accept(&mut self, h: T, end: T) {
        let [k1, _, k3, k4, k5, k6, k7] = &mut self.stages;
        let [r2, r3, r4, r5] = &mut self.dense;
        let (y0, y1) = (self.state.components(), self.trial.components());
        for ((r2, y0), y1) in r2.components_mut().iter_mut().zip(y0).zip(y1) {
            *r2 = *y1 - *y0;
        }
        let r2 = r2.components();
        for ((r3, r2), f0) in r3.components_mut().iter_mut().zip(r2).zip(k1.components()) {
            *r3 = h * *f0 - *r2;
        }
        let r3 = r3.components();
        let next = r2.iter().zip(r3).zip(k7.components());
        for (r4, ((r2, r3), f1)) in r4.components_mut().iter_mut().zip(next) {
            *r4 = *r2 - h * *f1 - *r3;
        }
        increment(
            r5,
            h,
            &[
                (T::of(D1), &*k1),
                (T::of(D3), &*k3),
                (T::of(D4), &*k4),
                (T::of(D5), &*k5),
                (T::of(D6), &*k6),
                (T::of(D7), &*k7),
            ],
        );
        core::mem::swap(k1, k7);
        core::mem::swap(&mut self.previous_state, &mut self.state);
        core::mem::swap(&mut self.state, &mut self.trial);
        self.previous_time = self.time;
        self.time = end;
        self.last_step = h;
        self.stiffness = self.attempt_stiffness;
        self.accepted = self.accepted.saturating_add(1);
    }

    /// First step (s): `settings.initial_step` if > 0, else Hairer's heuristic
    /// (Hairer–Nørsett–Wanner II.4, steps a–f, with the RMS norm); bounded by the step
    /// cap, floored at min_step, and finite and > 0 whatever the inputs.
    fn initial_step(&mut self, system: &mut impl OdeSystem<T, S>) -> T {
        let cap = step_cap(&self.settings, system.step_limit(self.time, &self.state));
        let min = |a: T, b: T| if a < b { a } else { b };
        let chosen = if self.settings.initial_step > T::zero() {
            min(self.settings.initial_step, cap)
        } else {
            self.starting_step_heuristic(system, cap)
        };
        let floored = if chosen < self.settings.min_step {
            self.settings.min_step
        } else {
            chosen
        };
        if floored > T::zero() && floored <= T::MAX {
            floored
        } else {
            min(T::of(FALLBACK_STEP), cap)
                .positive()
                .unwrap_or(T::of(FALLBACK_STEP))
        }
    }

    /// Hairer's starting-step heuristic, bounded by `cap` (s); the caller floors and
    /// sanitises the result.
    fn starting_step_heuristic(&mut self, system: &mut impl OdeSystem<T, S>, cap: T) -> T {
        let (rtol, atol) = (
            self.settings.relative_tolerance,
            self.settings.absolute_tolerance,
        );
        let fallback = T::of(FALLBACK_STEP);
        let min = |a: T, b: T| if a < b { a } else { b };
        let y0 = &self.state;
        let [f0, f1, ..] = &mut self.stages;
        if !all_finite(y0) || !all_finite(f0) {
            return fallback;
        }
        // (a) d0 = ‖y0‖, d1 = ‖f(t0, y0)‖ with sc_i = atol + rtol·|y0_i|.
        let d0 = scaled_rms(y0, y0, y0, rtol, atol);
        let d1 = scaled_rms(f0, y0, y0, rtol, atol);
        // (b) h0 = 0.01·d0/d1, or 1e-6 s if either is tiny.
        let tiny = T::of(1e-5);
        let h0 = if d0.is_nan() || d1.is_nan() || d0 < tiny || d1 < tiny {
            fallback
        } else {
            T::of(0.01) * (d0 / d1)
        };
        let h0 = min(h0, cap);
        if h0.positive().is_none() {
            return fallback;
        }
        // (c) one explicit Euler step; (d) d2 = ‖f(t0 + h0, y1) − f(t0, y0)‖ / h0.
        combine(&mut self.stage_state, y0, h0, &[(T::of(1.0), &*f0)]);
        system.derivative(self.time + h0, &self.stage_state, f1);
        combine(&mut self.trial, &*f1, T::one(), &[(T::of(-1.0), &*f0)]);
        let d2 = scaled_rms(&self.trial, y0, y0, rtol, atol) / h0;
        if d2.is_nan() {
            return h0;
        }
        // (e) h1 from max(d1, d2)·h1⁵ = 0.01 (order p = 4, so exponent 1/(p+1)).
        let d = if d1 > d2 { d1 } else { d2 };
        let h1 = if d <= T::of(1e-15) {
            let small = h0 * T::of(1e-3);
            if small > fallback {
                small
            } else {
                fallback
            }
        } else {
            (T::of(0.01) / d).pow(T::of(0.2))
        };
        if h1.is_nan() {
            return h0;
        }
        // (f) h = min(100·h0, h1), and the cap.
        min(min(T::of(100.0) * h0, h1), cap)
    }
}

/// ‖f₁ − f₂‖ / ‖y₁ − y₂‖ (1/s), 0 when the states are equal or the ratio is NaN.
fn stiffness_ratio<T: Real, S: OdeState<T>>(f1: &S, f2: &S, y1: &S, y2: &S) -> T {
    let squared_distance = |a: &S, b: &S| {
        a.components()
            .iter()
            .zip(b.components())
            .fold(T::zero(), |sum, (a, b)| sum + (*a - *b) * (*a - *b))
    };
    let (rates, states) = (squared_distance(f1, f2), squared_distance(y1, y2));
    let ratio = (rates / states).square_root();
    if states > T::zero() && ratio.is_finite() {
        ratio
    } else {
        T::zero()
    }
}

/// h_new / h = 0.9·err^(−1/5) within [0.2, 10] (dimensionless).
fn step_factor<T: Real>(error: T) -> T {
    if error.is_nan() {
        return T::of(FACTOR_MIN);
    }
    if error <= T::zero() {
        return T::of(FACTOR_MAX);
    }
    let factor = T::of(SAFETY) * error.pow(T::of(-0.2));
    if factor > T::of(FACTOR_MAX) {
        T::of(FACTOR_MAX)
    } else if factor < T::of(FACTOR_MIN) || factor.is_nan() {
        T::of(FACTOR_MIN)
    } else {
        factor
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const A: [[f64; 6]; 6] = [
        [A21, 0.0, 0.0, 0.0, 0.0, 0.0],
        [A31, A32, 0.0, 0.0, 0.0, 0.0],
        [A41, A42, A43, 0.0, 0.0, 0.0],
        [A51, A52, A53, A54, 0.0, 0.0],
        [A61, A62, A63, A64, A65, 0.0],
        [B1, 0.0, B3, B4, B5, B6],
    ];
    const C: [f64; 7] = [0.0, C2, C3, C4, C5, 1.0, 1.0];
    const B: [f64; 7] = [B1, 0.0, B3, B4, B5, B6, 0.0];

    #[test]
    fn tableau_rows_sum_to_their_nodes() {
        for (row, c) in A.iter().zip(&C[1..]) {
            let sum: f64 = row.iter().sum();
            assert!((sum - c).abs() < 1e-14, "row sum {sum} vs c {c}");
        }
    }

    #[test]
    fn weights_meet_the_quadrature_conditions_to_fifth_order() {
        // Σ b_i c_i^(q−1) = 1/q for q = 1 … 5.
        for q in 1..=5 {
            let sum: f64 = B.iter().zip(&C).map(|(b, c)| b * c.powi(q - 1)).sum();
            assert!((sum - 1.0 / q as f64).abs() < 1e-14, "q = {q}: {sum}");
        }
        // The embedded 4th-order weights b̂ = b − e meet them to 4th order only.
        let e = [E1, 0.0, E3, E4, E5, E6, E7];
        for q in 1..=4 {
            let sum: f64 = e.iter().zip(&C).map(|(e, c)| e * c.powi(q - 1)).sum();
            assert!(sum.abs() < 1e-14, "q = {q}: {sum}");
        }
        let fifth: f64 = e.iter().zip(&C).map(|(e, c)| e * c.powi(4)).sum();
        assert!(fifth.abs() > 1e-6);
        // Dense output is exact for y' = const: Σ d_i = 0.
        let d_sum: f64 = [D1, D3, D4, D5, D6, D7].iter().sum();
        assert!(d_sum.abs() < 1e-13, "{d_sum}");
    }

    /// y' = y.
    struct Growth;
    impl OdeSystem<f64, [f64; 1]> for Growth {
        fn derivative(&mut self, _: f64, y: &[f64; 1], dy: &mut [f64; 1]) {
            *dy = *y;
        }
    }

    /// Error after one step of length h from y(0) = 1, at the end and at mid-step.
    fn one_step_errors(h: f64) -> (f64, f64) {
        let mut settings = Settings::new(1.0, 1.0);
        settings.initial_step = h;
        let mut stepper = Dopri5::new(&mut Growth, 0.0, [1.0], settings);
        stepper.step(&mut Growth, h).unwrap();
        assert_eq!(stepper.time(), h);
        let mut mid = [0.0];
        stepper.dense_output(0.5 * h, &mut mid);
        let [end] = *stepper.state();
        ((end - h.exp()).abs(), (mid[0] - (0.5 * h).exp()).abs())
    }

    #[test]
    fn local_error_is_fifth_order_and_dense_output_fourth() {
        let (end_1, mid_1) = one_step_errors(0.2);
        let (end_2, mid_2) = one_step_errors(0.1);
        // Local errors O(h⁶) at the end and O(h⁵) inside: ratios near 64 and 32.
        assert!(end_1 / end_2 > 50.0, "{end_1} / {end_2}");
        assert!(
            mid_1 / mid_2 > 25.0 && mid_1 / mid_2 < 45.0,
            "{mid_1} / {mid_2}"
        );
    }

    #[test]
    fn invalid_settings_are_reported_not_stepped() {
        let bad = [
            (
                Settings {
                    relative_tolerance: f64::NAN,
                    ..Settings::new(1e-6, 1e-6)
                },
                "relative_tolerance",
            ),
            (Settings::new(1e-6, -1.0), "absolute_tolerance"),
            (Settings::new(0.0, 0.0), "absolute_tolerance"),
            (
                Settings {
                    min_step: 0.0,
                    ..Settings::new(1e-6, 1e-6)
                },
                "min_step",
            ),
            (
                Settings {
                    max_step: f64::NAN,
                    ..Settings::new(1e-6, 1e-6)
                },
                "max_step",
            ),
        ];
        for (settings, name) in bad {
            let mut stepper = Dopri5::new(&mut Growth, 0.0, [1.0], settings);
            assert_eq!(
                stepper.step(&mut Growth, 1.0),
                Err(IntegrationError::InvalidSettings { setting: name })
            );
            assert_eq!(stepper.time(), 0.0);
        }
        let infinite_max = Settings {
            max_step: f64::INFINITY,
            ..Settings::new(1e-6, 1e-6)
        };
        assert_eq!(infinite_max.validate(), Ok(()));
    }

    #[test]
    fn dense_output_is_the_point_itself_before_any_step_and_after_restart() {
        let mut stepper = Dopri5::new(&mut Growth, 1.0, [2.0], Settings::new(1e-8, 1e-8));
        let mut out = [f64::NAN];
        stepper.dense_output(1.5, &mut out);
        assert_eq!(out, [2.0]);
        stepper.step(&mut Growth, 2.0).unwrap();
        stepper.restart(&mut Growth, 3.0, [5.0]);
        for t in [f64::NAN, 0.0, 3.0, 4.0] {
            stepper.dense_output(t, &mut out);
            assert_eq!(out, [5.0]);
        }
        assert_eq!((stepper.previous_time(), stepper.time()), (3.0, 3.0));
    }

    #[test]
    fn dense_output_clamps_to_the_step_and_hits_its_ends_exactly() {
        let mut stepper = Dopri5::new(&mut Growth, 0.0, [1.0], Settings::new(1e-8, 1e-8));
        stepper.step(&mut Growth, 1.0).unwrap();
        let mut out = [0.0];
        stepper.dense_output(-1.0, &mut out);
        assert_eq!(out, *stepper.previous_state());
        stepper.dense_output(stepper.time() + 1.0, &mut out);
        assert_eq!(out, *stepper.state());
        stepper.dense_output(f64::NAN, &mut out);
        assert_eq!(out, *stepper.previous_state());
    }

    #[test]
    fn the_initial_step_guess_is_finite_and_positive_for_any_start() {
        for y in [0.0, 1e-300, 1.0, 1e300, f64::NAN, f64::INFINITY] {
            let stepper = Dopri5::new(&mut Growth, 0.0, [y], Settings::new(1e-6, 1e-9));
            let h = stepper.next_step;
            assert!(h > 0.0 && h.is_finite(), "y0 = {y}: h = {h}");
        }
    }
}
