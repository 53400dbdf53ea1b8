//! The residual function as the iteration sees it: in scaled coordinates
//! u_i = p_i / scale_i, inside a box, with its forward-difference Jacobian; and the
//! checks of the caller's inputs.

use super::{Bound, LeastSquaresError, LmSettings};
use rayon::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};

/// √ε of `f64`, the relative forward-difference step.
const SQRT_EPSILON: f64 = 1.490_116_119_384_765_6e-8;

/// The residual function seen in scaled coordinates u = p / scale.
pub(super) struct Problem<'a, F> {
    residuals: &'a F,
    scales: &'a [f64],
    /// Residuals (m).
    pub(super) m: usize,
    /// The bounds in the caller's units.
    box_p: Vec<(f64, f64)>,
    /// The bounds in scaled coordinates.
    pub(super) lower: Vec<f64>,
    pub(super) upper: Vec<f64>,
    /// Calls of the residual function so far.
    evaluations: AtomicUsize,
}

impl<'a, F: Fn(&[f64], &mut [f64]) + Sync> Problem<'a, F> {
    /// The problem after checking every input (see [`super::levenberg_marquardt`]'s
    /// errors).
    pub(super) fn new(
        residuals: &'a F,
        m: usize,
        initial: &[f64],
        scales: &'a [f64],
        bounds: Option<&[Bound]>,
        settings: &LmSettings,
    ) -> Result<Self, LeastSquaresError> {
        check_sizes(m, initial.len())?;
        check_settings(settings)?;
        check_start(initial, scales)?;
        let box_p = check_bounds(bounds, initial.len())?;
        let lower = box_p.iter().zip(scales).map(|(b, s)| b.0 / s).collect();
        let upper = box_p.iter().zip(scales).map(|(b, s)| b.1 / s).collect();
        Ok(Problem {
            residuals,
            scales,
            m,
            box_p,
            lower,
            upper,
            evaluations: AtomicUsize::new(0),
        })
    }

    /// The start in scaled coordinates, projected onto the box.
    pub(super) fn start(&self, initial: &[f64]) -> Vec<f64> {
        (0..initial.len())
            .map(|i| (initial[i] / self.scales[i]).clamp(self.lower[i], self.upper[i]))
            .collect()
    }

    /// r at scaled point `u`.
    pub(super) fn eval(&self, u: &[f64], out: &mut [f64]) {
        let p = self.unscale(u);
        self.evaluations.fetch_add(1, Ordering::Relaxed);
        (self.residuals)(&p, out);
    }

    /// Calls of the residual function so far.
    pub(super) fn evaluations(&self) -> usize {
        self.evaluations.load(Ordering::Relaxed)
    }

    /// The parameters' scales (their typical magnitudes, > 0).
    pub(super) fn scales(&self) -> &[f64] {
        self.scales
    }

    /// p = u·scale, kept inside the caller's bounds (rounding in p/scale·scale could
    /// otherwise leave them by an ulp, where a law may be undefined).
    pub(super) fn unscale(&self, u: &[f64]) -> Vec<f64> {
        u.iter()
            .zip(self.scales)
            .zip(&self.box_p)
            .map(|((u, s), &(low, high))| (u * s).clamp(low, high))
            .collect()
    }

    /// Forward-difference ∂r/∂u into `jacobian` (column-major, m × n), given r(u),
    /// the columns in parallel (rayon). The step is √ε·max(|u_j|, 1), i.e.
    /// √ε·max(|p_j|, scale_j) in p; it goes backward where the forward point would leave
    /// the box or gives a non-finite residual, and is shortened to the room left in a
    /// box narrower than it.
    pub(super) fn jacobian(
        &self,
        u: &[f64],
        r: &[f64],
        jacobian: &mut [f64],
    ) -> Result<(), LeastSquaresError> {
        let failure = jacobian
            .par_chunks_mut(self.m)
            .enumerate()
            .find_map_any(|(j, column)| self.difference(u, r, j, column).err());
        match failure {
            None => Ok(()),
            Some(parameter) => Err(LeastSquaresError::NonFiniteJacobian {
                parameter,
                value: u[parameter] * self.scales[parameter],
            }),
        }
    }

    /// Column j of the Jacobian: the first of the two difference steps that gives a
    /// finite column, zeros for a parameter fixed by its bounds, `Err(j)` otherwise.
    fn difference(&self, u: &[f64], r: &[f64], j: usize, column: &mut [f64]) -> Result<(), usize> {
        let (room_up, room_down) = (self.upper[j] - u[j], u[j] - self.lower[j]);
        let mut shifted = u.to_vec();
        for step in difference_steps(u[j], room_up, room_down) {
            if step == 0.0 {
                continue;
            }
            shifted[j] = u[j] + step;
            // The step actually taken, exactly representable.
            let h = shifted[j] - u[j];
            if h == 0.0 {
                continue;
            }
            self.eval(&shifted, column);
            column
                .iter_mut()
                .zip(r)
                .for_each(|(c, r0)| *c = (*c - r0) / h);
            if column.iter().all(|v| v.is_finite()) {
                return Ok(());
            }
        }
        if room_up == 0.0 && room_down == 0.0 {
            // Fixed by its bounds: no derivative, no movement.
            column.fill(0.0);
            return Ok(());
        }
        Err(j)
    }
}

/// The two steps to try for a difference at u with the given room to the bounds:
/// forward √ε·max(|u|, 1) if it fits, else backward; the other direction (as far as
/// the room allows) second.
fn difference_steps(u: f64, room_up: f64, room_down: f64) -> [f64; 2] {
    let nominal = SQRT_EPSILON * u.abs().max(1.0);
    if room_up >= nominal {
        [nominal, -nominal.min(room_down)]
    } else if room_down >= nominal {
        [-nominal, room_up]
    } else if room_up >= room_down {
        [room_up, -room_down]
    } else {
        [-room_down, room_up]
    }
}

/// At least one parameter and one residual, and no fewer residuals than parameters.
fn check_sizes(m: usize, n: usize) -> Result<(), LeastSquaresError> {
    if n == 0 {
        return Err(LeastSquaresError::NoUnknowns);
    }
    if m == 0 {
        return Err(LeastSquaresError::NoRows);
    }
    if m < n {
        return Err(LeastSquaresError::TooFewRows {
            rows: m,
            unknowns: n,
        });
    }
    Ok(())
}

/// Rejects settings outside their domain.
fn check_settings(settings: &LmSettings) -> Result<(), LeastSquaresError> {
    let checks = [
        ("gradient_tolerance", settings.gradient_tolerance),
        ("step_tolerance", settings.step_tolerance),
        ("cost_tolerance", settings.cost_tolerance),
    ];
    for (name, value) in checks {
        if !(value.is_finite() && value >= 0.0) {
            return Err(LeastSquaresError::InvalidSetting {
                name,
                value,
                expected: "finite and ≥ 0",
            });
        }
    }
    let value = settings.initial_damping;
    if !(value.is_finite() && value > 0.0) {
        return Err(LeastSquaresError::InvalidSetting {
            name: "initial_damping",
            value,
            expected: "finite and > 0",
        });
    }
    Ok(())
}

/// One finite positive scale per parameter and a finite start.
fn check_start(initial: &[f64], scales: &[f64]) -> Result<(), LeastSquaresError> {
    let n = initial.len();
    if scales.len() != n {
        return Err(LeastSquaresError::LengthMismatch {
            what: "scales",
            expected: n,
            found: scales.len(),
        });
    }
    for (index, &scale) in scales.iter().enumerate() {
        if !(scale.is_finite() && scale > 0.0) {
            return Err(LeastSquaresError::InvalidScale { index, scale });
        }
    }
    for (index, &value) in initial.iter().enumerate() {
        if !value.is_finite() {
            return Err(LeastSquaresError::NonFiniteInitial { index, value });
        }
    }
    Ok(())
}

/// The box in the caller's units, (−∞, ∞) where no bounds are given; each bound pair
/// an interval (either end may be infinite, not both on the same side).
fn check_bounds(bounds: Option<&[Bound]>, n: usize) -> Result<Vec<(f64, f64)>, LeastSquaresError> {
    let Some(bounds) = bounds else {
        return Ok(vec![(f64::NEG_INFINITY, f64::INFINITY); n]);
    };
    if bounds.len() != n {
        return Err(LeastSquaresError::LengthMismatch {
            what: "bounds",
            expected: n,
            found: bounds.len(),
        });
    }
    for (
        index,
        &Bound {
            lower: low,
            upper: high,
            ..
        },
    ) in bounds.iter().enumerate()
    {
        if low.is_nan()
            || high.is_nan()
            || low > high
            || low == f64::INFINITY
            || high == f64::NEG_INFINITY
        {
            return Err(LeastSquaresError::InvalidBounds {
                index,
                lower: low,
                upper: high,
            });
        }
    }
    Ok(bounds.iter().map(Bound::range).collect())
}
