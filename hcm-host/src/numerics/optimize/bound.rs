//! One parameter's search interval, the one bounds type of every optimiser here: the
//! genetic algorithm and Nelder–Mead walk it normalised to [0, 1] (through log(value)
//! where it is log-scaled), Levenberg–Marquardt projects onto it, the scalar searches
//! take its ends.

use serde::{Deserialize, Serialize};

/// One parameter's search interval; `log_scale` searches log(value) (for quantities
/// spanning decades, e.g. stiffness).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Bound {
    /// Parameter name, used in error messages.
    pub(crate) name: String,
    /// Smallest value searched (the parameter's units).
    pub lower: f64,
    /// Largest value searched (the parameter's units).
    pub upper: f64,
    /// Search uniformly in log(value) instead of value; needs `lower > 0`.
    #[serde(default)]
    pub log_scale: bool,
}

impl Bound {
    /// The bound of a parameter table's row `(name, lower, upper, log_scale)`.
    pub(crate) fn of_row(&(name, lower, upper, log_scale): &(&str, f64, f64, bool)) -> Bound {
        Bound {
            name: name.to_owned(),
            lower,
            upper,
            log_scale,
        }
    }

    /// The value at fraction `at` of the interval, clamped into [0, 1] (through
    /// log(value) on a log scale): how a local search walks the box on the scale the
    /// genetic algorithm searches.
    pub(crate) fn value_at(&self, at: f64) -> f64 {
        let at = at.clamp(0.0, 1.0);
        if self.log_scale {
            (self.lower.ln() + at * (self.upper.ln() - self.lower.ln())).exp()
        } else {
            self.lower + at * (self.upper - self.lower)
        }
    }

    /// The fraction of the interval `value` lies at, clamped into [0, 1]: the inverse
    /// of [`Bound::value_at`].
    pub(crate) fn fraction_of(&self, value: f64) -> f64 {
        let (lower, upper, value) = if self.log_scale {
            (self.lower.ln(), self.upper.ln(), value.ln())
        } else {
            (self.lower, self.upper, value)
        };
        ((value - lower) / (upper - lower)).clamp(0.0, 1.0)
    }
}

impl Bound {
    /// A linear interval named `name`, [lower, upper] in the parameter's units; either
    /// end may be infinite where the optimiser allows it (Levenberg–Marquardt does).
    pub fn linear(name: impl Into<String>, lower: f64, upper: f64) -> Bound {
        Bound {
            name: name.into(),
            lower,
            upper,
            log_scale: false,
        }
    }

    /// (lower, upper), the parameter's units.
    pub fn range(&self) -> (f64, f64) {
        (self.lower, self.upper)
    }
}
