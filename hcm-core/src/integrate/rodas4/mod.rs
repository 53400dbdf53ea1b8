//! The Rosenbrock method RODAS (order 4(3), L-stable, stiffly accurate) with dense
//! output, for stiff stretches of a run: a body held by static friction, whose STEP
//! law's steep slope near zero slip (μ_s·f_n/v_s) sets a time constant far below the
//! motion's own, which an explicit method must resolve step by step.
//!
//! Method: Hairer & Wanner, *Solving Ordinary Differential Equations II* (2nd ed.,
//! Springer 1996), Section VI.4, in the transformed variables uᵢ of their code RODAS
//! (coefficients of its ROCOE, method 1; Hairer & Wanner, "RODAS"):
//!
//! (1/(hγ)·I − J)·uᵢ = f(t + cᵢh, y + Σⱼ aᵢⱼuⱼ) + Σⱼ (Cᵢⱼ/h)·uⱼ + h·dᵢ·∂f/∂t,
//!
//! six stages, the fifth and sixth at t + h; y₁ = y + Σ a₅ⱼuⱼ + u₅ + u₆ and u₆ is the
//! error estimate (stiffly accurate). The continuous extension is the code's cubic one.
//! It needs the exact Jacobian for order 4 (a Rosenbrock, not a W-method): the
//! system supplies J at every accepted point ([`LinearlyImplicit`]).

mod tableau;
#[cfg(test)]
mod tests;

use super::dopri5::Settings;
use super::interval::{next_interval, step_cap};
use super::state::copy_states;
use super::vector::{all_finite, error_norm, is_finite};
use super::{DenseOutput, IntegrationError, LinearlyImplicit, OdeState};
use crate::Real;
use tableau::{ARGUMENT, DENSE, GAMMA, MEMORY, NODE, TIME_RATE};

/// Safety factor of the step-size formula (–).
const SAFETY: f64 = 0.9;
/// Smallest and largest step-size ratio h_new / h (–), RODAS's defaults.
const FACTOR_MIN: f64 = 0.2;
const FACTOR_MAX: f64 = 6.0;
/// First step (s) when the settings give none.
const FALLBACK_STEP: f64 = 1e-6;

/// The adaptive RODAS stepper, advanced one accepted step at a time, with the same
/// contract as [`Dopri5`](super::Dopri5): [`step`](Rodas4::step) never goes beyond
/// `until`, [`DenseOutput`] covers the step just taken, nothing is allocated, nothing
/// panics. Six evaluations of f, one Jacobian and one factorisation of W per
/// accepted step (a rejected step refactors W only).
#[derive(Debug)]
pub struct Rodas4<T: Real, S: OdeState<T>> {
    settings: Settings<T>,
    time: T,
    state: S,
    /// f(time, state).
    rate: S,
    previous_time: T,
    previous_state: S,
    last_step: T,
    next_step: T,
    /// Whether the system's Jacobian is that of the current point.
    jacobian_current: bool,
    /// ∂f/∂t at the current point.
    time_rate: S,
    /// The stage increments u₁ … u₆ of the last attempt.
    stages: [S; 6],
    /// Working space: a stage's argument.
    argument: S,
    /// Working space: f at a stage's argument, then its right-hand side.
    stage_rate: S,
    /// The candidate y₁ of an attempt.
    trial: S,
    /// Dense-output terms Σ H2ⱼuⱼ, Σ H3ⱼuⱼ of the last accepted step.
    dense: [S; 2],
    /// Step (s) and error (–) of the last accepted step, for Gustafsson's predictive
    /// step control.
    last_accepted: Option<(T, T)>,
    accepted: u64,
    rejected: u64,
}

/// By hand for `clone_from`, which copies into the existing states (see
/// [`Dopri5`](super::Dopri5)'s).
impl<T: Real, S: OdeState<T>> Clone for Rodas4<T, S> {
    fn clone(&self) -> Self {
        Rodas4 {
            settings: self.settings,
            time: self.time,
            state: self.state.clone(),
            rate: self.rate.clone(),
            previous_time: self.previous_time,
            previous_state: self.previous_state.clone(),
            last_step: self.last_step,
            next_step: self.next_step,
            jacobian_current: self.jacobian_current,
            time_rate: self.time_rate.clone(),
            stages: self.stages.clone(),
            argument: self.argument.clone(),
            stage_rate: self.stage_rate.clone(),
            trial: self.trial.clone(),
            dense: self.dense.clone(),
            last_accepted: self.last_accepted,
            accepted: self.accepted,
            rejected: self.rejected,
        }
    }

    fn clone_from(&mut self, source: &Self) {
        // Destructured so that a new field cannot be forgotten here.
        let Rodas4 {
            settings,
            time,
            state,
            rate,
            previous_time,
            previous_state,
            last_step,
            next_step,
            jacobian_current,
            time_rate,
            stages,
            argument,
            stage_rate,
            trial,
            dense,
            last_accepted,
            accepted,
            rejected,
        } = source;
        (self.settings, self.time, self.previous_time) = (*settings, *time, *previous_time);
        (self.last_step, self.next_step) = (*last_step, *next_step);
        (self.jacobian_current, self.last_accepted) = (*jacobian_current, *last_accepted);
        (self.accepted, self.rejected) = (*accepted, *rejected);
        self.state.clone_from(state);
        self.rate.clone_from(rate);
        self.previous_state.clone_from(previous_state);
        self.time_rate.clone_from(time_rate);
        self.argument.clone_from(argument);
        self.stage_rate.clone_from(stage_rate);
        self.trial.clone_from(trial);
        copy_states(&mut self.stages, stages);
        copy_states(&mut self.dense, dense);
    }
}

impl<T: Real, S: OdeState<T>> Rodas4<T, S> {
    /// Starts at (`time` (s), `state`) with `settings` (first step:
    /// `settings.initial_step` if > 0, else 1 µs); evaluates f once.
    pub fn new(
        system: &mut impl LinearlyImplicit<T, S>,
        time: T,
        state: S,
        settings: Settings<T>,
    ) -> Self {
        let mut stepper = Rodas4 {
            settings,
            time,
            rate: state.clone(),
            previous_time: time,
            previous_state: state.clone(),
            last_step: T::zero(),
            next_step: T::of(FALLBACK_STEP),
            jacobian_current: false,
            time_rate: state.clone(),
            stages: core::array::from_fn(|_| state.clone()),
            argument: state.clone(),
            stage_rate: state.clone(),
            trial: state.clone(),
            dense: core::array::from_fn(|_| state.clone()),
            state,
            last_accepted: None,
            accepted: 0,
            rejected: 0,
        };
        system.derivative(time, &stepper.state, &mut stepper.rate);
        if settings.initial_step > T::zero() {
            stepper.next_step = settings.initial_step;
        }
        stepper
    }

    /// Steps accepted since `new`.
    pub fn accepted_steps(&self) -> u64 {
        self.accepted
    }

    /// Attempts rejected since `new`.
    pub fn rejected_steps(&self) -> u64 {
        self.rejected
    }

    /// The step (s) the next attempt will try.
    pub fn next_step(&self) -> T {
        self.next_step
    }

    /// Takes one accepted step, never beyond `until` (s) nor longer than
    /// min(settings.max_step, system.step_limit(t, y)); the step-length rules, the
    /// end-of-interval stretch and the errors are those of
    /// [`Dopri5::step`](super::Dopri5::step). A singular W counts as a non-finite
    /// attempt (the step shrinks 5×). After an acceptance the step changes by
    /// 0.9·err^(−1/4) within [0.2, 6], or by Gustafsson's predictive factor when that
    /// is smaller (Hairer–Wanner IV.8, as RODAS does).
    ///
    /// # Errors
    /// As [`Dopri5::step`](super::Dopri5::step).
    pub fn step(
        &mut self,
        system: &mut impl LinearlyImplicit<T, S>,
        until: T,
    ) -> Result<(), IntegrationError> {
        if until.is_nan() || self.time >= until {
            return Ok(());
        }
        self.settings.validate()?;
        if !is_finite(self.time) || !all_finite(&self.state) || !all_finite(&self.rate) {
            return Err(IntegrationError::NonFinite {
                time: self.time.to_f64(),
            });
        }
        if !self.jacobian_current {
            system.jacobian(self.time, &self.state, &self.rate, &mut self.time_rate);
            self.jacobian_current = true;
        }
        let limit = system.step_limit(self.time, &self.state);
        let cap = step_cap(&self.settings, limit);
        let (mut non_finite, mut rejected_here) = (false, false);
        loop {
            let attempts = self.accepted.saturating_add(self.rejected);
            if attempts >= self.settings.max_steps {
                return Err(IntegrationError::TooManySteps {
                    time: self.time.to_f64(),
                    steps: attempts,
                });
            }
            let (h, end) = next_interval(
                &self.settings,
                self.time,
                self.next_step,
                (cap, until),
                non_finite,
            )?;
            let error = if system.factor(T::one() / (h * T::of(GAMMA))) {
                self.attempt(system, h, end);
                let settings = &self.settings;
                let (rtol, atol) = (settings.relative_tolerance, settings.absolute_tolerance);
                error_norm(&self.stages[5], &self.state, &self.trial, rtol, atol)
            } else {
                None
            };
            match error {
                Some(error) if error <= T::one() => {
                    self.next_step = self.grown(h, error, rejected_here);
                    self.accept(system, h, end, error);
                    return Ok(());
                }
                Some(error) => {
                    non_finite = false;
                    let factor = step_factor(error);
                    self.next_step = h * if factor < T::one() { factor } else { T::one() };
                }
                None => {
                    non_finite = true;
                    self.next_step = h * T::of(FACTOR_MIN);
                }
            }
            self.rejected = self.rejected.saturating_add(1);
            rejected_here = true;
        }
    }

    /// The step (s) after an accepted one of `h` (s) with `error` (–).
    fn grown(&self, h: T, error: T, rejected_here: bool) -> T {
        let mut factor = step_factor(error);
        if let Some((last_h, last_error)) = self.last_accepted {
            // Gustafsson: h_new = h·(h/h_acc)·(err_acc/err²)^(1/4)·0.9 (as a factor).
            let predicted =
                T::of(SAFETY) * (h / last_h) * (last_error / (error * error)).pow(T::of(0.25));
            let predicted = clamp_factor(predicted);
            if predicted < factor {
                factor = predicted;
            }
        }
        if rejected_here && factor > T::one() {
            factor = T::one();
        }
        let next = h * factor;
        if next < self.settings.min_step {
            self.settings.min_step
        } else if !is_finite(next) {
            T::MAX
        } else {
            next
        }
    }

    /// Restarts from (`time` (s), `state`): f and the Jacobian are re-evaluated, the
    /// step guess kept; the dense output becomes the point itself.
    pub fn restart(&mut self, system: &mut impl LinearlyImplicit<T, S>, time: T, state: S) {
        self.previous_state.clone_from(&state);
        self.state = state;
        self.time = time;
        self.previous_time = time;
        self.last_step = T::zero();
        self.jacobian_current = false;
        self.last_accepted = None;
        system.derivative(time, &self.state, &mut self.rate);
    }
}

impl<T: Real, S: OdeState<T>> Rodas4<T, S> {
    /// One attempt of length `h` (s) ending at `end` (s) with W factored: fills
    /// u₁ … u₆ and the candidate y₁ (`trial`).
    fn attempt(&mut self, system: &mut impl LinearlyImplicit<T, S>, h: T, end: T) {
        for i in 0..6 {
            let (done, rest) = self.stages.split_at_mut(i);
            let Some((stage, _)) = rest.split_first_mut() else {
                return;
            };
            if i == 0 {
                self.stage_rate.clone_from(&self.rate);
            } else {
                let at = if i >= 4 {
                    end
                } else {
                    self.time + T::of(NODE[i]) * h
                };
                affine(&mut self.argument, &self.state, done, &ARGUMENT[i]);
                system.derivative(at, &self.argument, &mut self.stage_rate);
            }
            for (u, c) in done.iter().zip(MEMORY[i]) {
                add_scaled(&mut self.stage_rate, T::of(c) / h, u);
            }
            if TIME_RATE[i] != 0.0 {
                add_scaled(
                    &mut self.stage_rate,
                    T::of(TIME_RATE[i]) * h,
                    &self.time_rate,
                );
            }
            system.solve(&mut self.stage_rate);
            core::mem::swap(stage, &mut self.stage_rate);
        }
        affine(&mut self.trial, &self.state, &self.stages, &ARGUMENT[6]);
    }

    /// Accepts the attempt of length `h` (s) ending at `end` (s) with `error` (–):
    /// keeps the dense terms, moves to (end, y₁) and evaluates f there.
    fn accept(&mut self, system: &mut impl LinearlyImplicit<T, S>, h: T, end: T, error: T) {
        for (dense, weights) in self.dense.iter_mut().zip(DENSE) {
            for o in dense.components_mut() {
                *o = T::zero();
            }
            for (u, w) in self.stages.iter().zip(weights) {
                add_scaled(dense, T::of(w), u);
            }
        }
        core::mem::swap(&mut self.previous_state, &mut self.state);
        core::mem::swap(&mut self.state, &mut self.trial);
        self.previous_time = self.time;
        self.time = end;
        self.last_step = h;
        let floor = T::of(1e-2);
        self.last_accepted = Some((h, if error > floor { error } else { floor }));
        self.jacobian_current = false;
        self.accepted = self.accepted.saturating_add(1);
        system.derivative(end, &self.state, &mut self.rate);
    }
}

impl<T: Real, S: OdeState<T>> DenseOutput<T, S> for Rodas4<T, S> {
    fn previous_time(&self) -> T {
        self.previous_time
    }

    fn previous_state(&self) -> &S {
        &self.previous_state
    }

    fn time(&self) -> T {
        self.time
    }

    fn state(&self) -> &S {
        &self.state
    }

    /// y(θ) = (1 − θ)·y₀ + θ·(y₁ + (1 − θ)·(H₂ + θ·H₃)), θ = (t − t₀)/h: 3rd order,
    /// the stored states at the ends; the previous state for an empty step or NaN.
    fn dense_output(&self, time: T, out: &mut S) {
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
        let [h2, h3] = &self.dense;
        let terms = self
            .state
            .components()
            .iter()
            .zip(h2.components())
            .zip(h3.components());
        for (o, ((y1, h2), h3)) in out.components_mut().iter_mut().zip(terms) {
            *o = theta1 * *o + theta * (*y1 + theta1 * (*h2 + theta * *h3));
        }
    }
}

/// `out` ← `base` + Σⱼ weights[j]·stages[j] (over the stages given).
fn affine<T: Real, S: OdeState<T>>(out: &mut S, base: &S, stages: &[S], weights: &[f64]) {
    out.clone_from(base);
    for (u, w) in stages.iter().zip(weights) {
        if *w != 0.0 {
            add_scaled(out, T::of(*w), u);
        }
    }
}

/// `out` ← `out` + c·v.
fn add_scaled<T: Real, S: OdeState<T>>(out: &mut S, c: T, v: &S) {
    for (o, v) in out.components_mut().iter_mut().zip(v.components()) {
        *o += c * *v;
    }
}

/// h_new / h = 0.9·err^(−1/4) within [0.2, 6] (–).
fn step_factor<T: Real>(error: T) -> T {
    if error.is_nan() {
        return T::of(FACTOR_MIN);
    }
    if error <= T::zero() {
        return T::of(FACTOR_MAX);
    }
    clamp_factor(T::of(SAFETY) * error.pow(T::of(-0.25)))
}

/// `factor` within [0.2, 6]; NaN gives 0.2.
fn clamp_factor<T: Real>(factor: T) -> T {
    if factor > T::of(FACTOR_MAX) {
        T::of(FACTOR_MAX)
    } else if factor < T::of(FACTOR_MIN) || factor.is_nan() {
        T::of(FACTOR_MIN)
    } else {
        factor
    }
}
