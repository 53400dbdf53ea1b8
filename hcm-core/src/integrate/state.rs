//! What is integrated: the state vector y and the system y' = f(t, y).

use crate::Real;

/// The state y of an ordinary differential equation: a fixed list of numbers the
/// integrator advances.
///
/// The integrator only reads and writes [`components`](OdeState::components); the
/// units of each component are the caller's (e.g. m and m/s for a position and a
/// velocity). Any other data in the type is carried along by `Clone` and never
/// changed by the integrator.
///
/// All states an integrator handles are clones of the one it was started with, so
/// they have the same number of components. If an implementation ever returned
/// slices of different lengths, the integrator works on the common prefix and does
/// not panic.
pub trait OdeState<T: Real>: Clone {
    /// The components y₁ … yₙ, in the caller's units.
    fn components(&self) -> &[T];

    /// The components y₁ … yₙ, writable.
    fn components_mut(&mut self) -> &mut [T];
}

impl<T: Real, const N: usize> OdeState<T> for [T; N] {
    #[inline]
    fn components(&self) -> &[T] {
        self
    }

    #[inline]
    fn components_mut(&mut self) -> &mut [T] {
        self
    }
}

/// Copies each of `from`'s states into the one at the same place in `into`, reusing
/// its storage (`clone_from`).
pub(crate) fn copy_states<T: Real, S: OdeState<T>>(into: &mut [S], from: &[S]) {
    for (to, from) in into.iter_mut().zip(from) {
        to.clone_from(from);
    }
}

/// An ordinary differential equation y' = f(t, y), with t the time (s).
pub trait OdeSystem<T: Real, S: OdeState<T>> {
    /// dy/dt at (time, state), written into `derivative` (same length as state).
    ///
    /// `time` is in s; each derivative component is in the state component's unit
    /// per second. `derivative` holds a clone of some earlier state or derivative on
    /// entry: write every component. NaN or ±∞ in the result is not a panic: the
    /// integrator shrinks the step and finally reports
    /// [`IntegrationError::NonFinite`](super::IntegrationError::NonFinite).
    ///
    /// Takes `&mut self` so that a system can count evaluations or cache; the
    /// integrator calls it at stage points inside a step that may be rejected, so it
    /// must not latch anything (latch at events, then
    /// [`restart`](super::Dopri5::restart)).
    fn derivative(&mut self, time: T, state: &S, derivative: &mut S);

    /// Largest step (s) the system allows from (time, state); default T::MAX.
    /// Used so that a step cannot jump over an event (e.g. gap / closing speed).
    ///
    /// A value below [`Settings::min_step`](super::Settings::min_step) (zero and
    /// negative included) counts as `min_step`, so the run always advances; NaN
    /// counts as no limit.
    fn step_limit(&self, _time: T, _state: &S) -> T {
        T::MAX
    }
}

/// A system that also supplies its Jacobian, for linearly implicit (Rosenbrock)
/// steps such as [`Rodas4`](super::Rodas4): the stepper solves with
/// W = d·I − J, J ≈ ∂f/∂y, and never forms or stores W itself, so the system chooses
/// the storage (a fixed array on a controller, a heap matrix on a host) and may use
/// its structure.
pub trait LinearlyImplicit<T: Real, S: OdeState<T>>: OdeSystem<T, S> {
    /// Evaluates and keeps J ≈ ∂f/∂y at (`time` (s), `state`), where `derivative` =
    /// f(time, state) is already known (a finite-difference Jacobian reuses it), and
    /// writes ∂f/∂t into `time_rate` (zeros for an autonomous system). Called once per
    /// step point, before any [`factor`](LinearlyImplicit::factor).
    fn jacobian(&mut self, time: T, state: &S, derivative: &S, time_rate: &mut S);

    /// Factors W = `diagonal`·I − J with the kept J (`diagonal` = 1/(h·γ), 1/s).
    /// Returns false when W is singular or not finite: the stepper then shrinks h.
    fn factor(&mut self, diagonal: T) -> bool;

    /// `rhs` ← W⁻¹·`rhs` with the last factored W.
    fn solve(&self, rhs: &mut S);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_array_is_its_own_component_list() {
        let mut state = [1.0_f64, 2.0, 3.0];
        assert_eq!(state.components(), &[1.0, 2.0, 3.0]);
        for component in state.components_mut() {
            *component *= 2.0;
        }
        assert_eq!(state, [2.0, 4.0, 6.0]);
        let empty: [f32; 0] = [];
        assert!(empty.components().is_empty());
    }
}
