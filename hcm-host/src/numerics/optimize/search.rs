//! The bounded outer searches of separable least squares, and the errors of the
//! least-squares solvers.
//!
//! Separable least squares (variable projection, Golub & Pereyra 1973, *The
//! differentiation of pseudo-inverses and nonlinear least squares problems whose
//! variables separate*, SIAM J. Numer. Anal. 10(2)) splits a contact law's parameters
//! into nonlinear ones (an exponent n) and linear ones (k, k·(1−ce²), …): for a fixed
//! n the force is linear in the others, so
//! [`crate::numerics::linear_least_squares()`] solves them exactly and leaves a residual
//! that depends on n alone. [`minimize_scalar`] (one nonlinear parameter) or
//! [`minimize_box2`] (two) then search that reduced residual over a bounded interval
//! or box.
//!
//! Nothing here is specific to contact laws and nothing prints.

use crate::numerics::LinearLeastSquaresError;

/// √ε of `f64`: the relative precision to which the minimiser of a smooth function
/// can be located from its values (Brent 1973, ch. 5).
const SQRT_EPSILON: f64 = 1.490_116_119_384_765_6e-8;

/// (3 − √5)/2, the golden-section fraction.
const GOLDEN_FRACTION: f64 = 0.381_966_011_250_105_1;

/// Cap on Brent iterations; a bracket shrinks by at least the golden ratio every few
/// iterations, so this is only reached with a tolerance below the bracket's ulp.
const MAX_BRENT_ITERATIONS: usize = 500;

/// Cap on the coordinate sweeps of [`minimize_box2`].
const MAX_SWEEPS: usize = 200;

/// Points of the local grid of each coordinate search in [`minimize_box2`].
const LOCAL_GRID: usize = 5;

/// Why a least-squares problem could not be solved.
#[derive(Debug, thiserror::Error)]
pub enum LeastSquaresError {
    /// The problem has no rows (no residuals).
    #[error("the least-squares problem has no rows")]
    NoRows,
    /// The problem has no unknowns.
    #[error("the least-squares problem has no unknowns")]
    NoUnknowns,
    /// Fewer rows (equations, residuals) than unknowns.
    #[error("{rows} rows cannot determine {unknowns} unknowns; at least as many rows as unknowns are needed")]
    TooFewRows {
        /// Rows (residuals) of the problem.
        rows: usize,
        /// Unknowns (parameters) to determine.
        unknowns: usize,
    },
    /// A linear least-squares solve failed.
    #[error(transparent)]
    Linear(#[from] LinearLeastSquaresError),
    /// A per-parameter slice has the wrong length.
    #[error("{what} has {found} entries but there are {expected} parameters")]
    LengthMismatch {
        /// Which slice: `scales` or `bounds`.
        what: &'static str,
        /// Parameters of the problem.
        expected: usize,
        /// Entries of the slice.
        found: usize,
    },
    /// A starting value is NaN or infinite.
    #[error("parameter {index}: the initial value {value} is not finite")]
    NonFiniteInitial {
        /// The parameter's index (from 0).
        index: usize,
        /// The starting value given.
        value: f64,
    },
    /// A parameter scale is not a finite positive number.
    #[error("parameter {index}: the scale {scale} must be finite and positive")]
    InvalidScale {
        /// The parameter's index (from 0).
        index: usize,
        /// The scale given, in the parameter's own unit.
        scale: f64,
    },
    /// A parameter's bounds are NaN or the lower one exceeds the upper one.
    #[error("parameter {index}: the bounds [{lower}, {upper}] are not an interval")]
    InvalidBounds {
        /// The parameter's index (from 0).
        index: usize,
        /// Lower bound, in the parameter's own unit.
        lower: f64,
        /// Upper bound, in the parameter's own unit.
        upper: f64,
    },
    /// A solver setting is outside its domain.
    #[error("setting `{name}` = {value} is out of range: {expected}")]
    InvalidSetting {
        /// The setting's name.
        name: &'static str,
        /// Its value, as given.
        value: f64,
        /// The domain it must lie in, in words.
        expected: &'static str,
    },
    /// The residuals are not all finite at the starting point.
    #[error("residual {index} is not finite at the initial parameters")]
    NonFiniteInitialResidual {
        /// The residual's index (from 0).
        index: usize,
    },
    /// Neither a forward nor a backward difference of the residuals with respect to a
    /// parameter is finite.
    #[error("the residuals' derivative with respect to parameter {parameter} is not finite on either side of {value}")]
    NonFiniteJacobian {
        /// The parameter's index (from 0).
        parameter: usize,
        /// The parameter's value the derivative was taken at.
        value: f64,
    },
}

/// Minimises a scalar function on [lower, upper]: a grid of `grid` points (at least 3),
/// then Brent's method (Brent 1973, *Algorithms for Minimization without Derivatives*,
/// ch. 5: parabolic interpolation safeguarded by golden section) on the two grid cells
/// around the best point, to an x tolerance `tolerance` (absolute, plus √ε·|x|, below
/// which a smooth minimum cannot be located). Returns (x, f(x)) of the best point
/// evaluated, grid included.
///
/// NaN and ±∞ values count as worse than any finite value; if every value is
/// non-finite the returned f(x) is non-finite. The grid makes the search global at its
/// resolution: a function with several minima gives the lowest one the grid resolves.
/// Bounds given in the wrong order are swapped; non-finite bounds return (NaN, NaN)
/// without calling `f`.
pub fn minimize_scalar(
    f: impl FnMut(f64) -> f64,
    lower: f64,
    upper: f64,
    grid: usize,
    tolerance: f64,
) -> (f64, f64) {
    if !lower.is_finite() || !upper.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let (lower, upper) = if lower <= upper {
        (lower, upper)
    } else {
        (upper, lower)
    };
    let mut tracked = Tracked::new(f);
    if lower == upper {
        tracked.eval(lower);
        return tracked.best();
    }
    let points = grid.max(3);
    let at = |i: usize| {
        if i + 1 == points {
            upper
        } else {
            lower + (upper - lower) * i as f64 / (points - 1) as f64
        }
    };
    let mut best_index = 0;
    let mut best_value = f64::INFINITY;
    for i in 0..points {
        let value = tracked.eval(at(i));
        if value < best_value {
            best_value = value;
            best_index = i;
        }
    }
    let a = at(best_index.saturating_sub(1));
    let b = at((best_index + 1).min(points - 1));
    brent(&mut tracked, a, b, tolerance);
    tracked.best()
}

/// The same for two variables on a box: a `grid × grid` grid (at least 3 × 3), then
/// coordinate-wise refinement — alternately [`minimize_scalar`] in x and in y over one
/// grid cell either side of the current point — until a sweep moves the point by less
/// than `tolerance` (absolute, in both variables; at most 200 sweeps). From the second
/// sweep on, a line search through the ends of the last two sweeps follows a valley
/// running diagonally to the axes, along which plain coordinate descent would
/// zig-zag: both ends minimise f in y, so for a quadratic they lie on the line
/// ∂f/∂y = 0 through the minimum, and the search is Powell's (1964) conjugate
/// direction step. Returns ((x, y), f(x, y)) of the best point evaluated.
///
/// NaN and ±∞ values count as worse than any finite value. Bounds in the wrong order
/// are swapped; non-finite bounds return ((NaN, NaN), NaN) without calling `f`.
pub fn minimize_box2(
    mut f: impl FnMut(f64, f64) -> f64,
    (lower_x, upper_x): (f64, f64),
    (lower_y, upper_y): (f64, f64),
    grid: usize,
    tolerance: f64,
) -> ((f64, f64), f64) {
    if ![lower_x, upper_x, lower_y, upper_y]
        .iter()
        .all(|v| v.is_finite())
    {
        return ((f64::NAN, f64::NAN), f64::NAN);
    }
    let search = Box2::new((lower_x, upper_x), (lower_y, upper_y), grid);
    let mut best = search.grid(&mut f);
    // End of the previous sweep's coordinate searches (before its pattern move).
    let mut previous_end: Option<(f64, f64)> = None;
    for _ in 0..MAX_SWEEPS {
        let (x0, y0) = (best.x, best.y);
        search.sweep(&mut f, &mut best, tolerance);
        let end = (best.x, best.y);
        if let Some(previous) = previous_end {
            search.pattern_move(&mut f, &mut best, previous, end, tolerance);
        }
        previous_end = Some(end);

        let moved = (best.x - x0).abs().max((best.y - y0).abs());
        // A NaN tolerance stops after one sweep.
        if moved < tolerance || tolerance.is_nan() {
            break;
        }
    }
    ((best.x, best.y), best.value)
}

/// The best point so far of [`minimize_box2`].
struct Best2 {
    x: f64,
    y: f64,
    /// f(x, y) as returned.
    value: f64,
    /// The value for comparison ([`comparable`]).
    key: f64,
}

impl Best2 {
    /// Keeps (x, y) if its value beats the best so far (or nothing is kept yet).
    fn offer(&mut self, x: f64, y: f64, value: f64) {
        let key = comparable(value);
        if key < self.key || self.x.is_nan() {
            *self = Best2 { x, y, value, key };
        }
    }
}

/// The box of [`minimize_box2`], its ends ordered, and the steps of its grid.
struct Box2 {
    x: (f64, f64),
    y: (f64, f64),
    step_x: f64,
    step_y: f64,
    /// Grid points per variable (≥ 3).
    points: usize,
}

impl Box2 {
    fn new((lower_x, upper_x): (f64, f64), (lower_y, upper_y): (f64, f64), grid: usize) -> Box2 {
        let x = (lower_x.min(upper_x), lower_x.max(upper_x));
        let y = (lower_y.min(upper_y), lower_y.max(upper_y));
        let points = grid.max(3);
        Box2 {
            x,
            y,
            step_x: (x.1 - x.0) / (points - 1) as f64,
            step_y: (y.1 - y.0) / (points - 1) as f64,
            points,
        }
    }

    /// Grid point `i` of [lower, upper] with spacing `step` (the last one exactly
    /// `upper`).
    fn along(&self, (lower, upper): (f64, f64), step: f64, i: usize) -> f64 {
        if i + 1 == self.points {
            upper
        } else {
            lower + step * i as f64
        }
    }

    /// The best point of the `points × points` grid.
    fn grid(&self, f: &mut impl FnMut(f64, f64) -> f64) -> Best2 {
        let mut best = Best2 {
            x: f64::NAN,
            y: f64::NAN,
            value: f64::NAN,
            key: f64::INFINITY,
        };
        for i in 0..self.points {
            for j in 0..self.points {
                let (x, y) = (
                    self.along(self.x, self.step_x, i),
                    self.along(self.y, self.step_y, j),
                );
                best.offer(x, y, f(x, y));
            }
        }
        best
    }

    /// One coordinate sweep: x, then y, each over one grid cell either side of the
    /// best point.
    fn sweep(&self, f: &mut impl FnMut(f64, f64) -> f64, best: &mut Best2, tolerance: f64) {
        let y = best.y;
        let (x, value) = minimize_scalar(
            |x| f(x, y),
            (best.x - self.step_x).max(self.x.0),
            (best.x + self.step_x).min(self.x.1),
            LOCAL_GRID,
            tolerance,
        );
        best.offer(x, y, value);
        let x = best.x;
        let (y, value) = minimize_scalar(
            |y| f(x, y),
            (best.y - self.step_y).max(self.y.0),
            (best.y + self.step_y).min(self.y.1),
            LOCAL_GRID,
            tolerance,
        );
        best.offer(x, y, value);
    }

    /// Powell's conjugate-direction step: both sweep ends minimise f in y, so (for a
    /// quadratic) both lie on the line ∂f/∂y = 0, which passes through the minimum:
    /// search along the line from `previous` through `end`, inside the box.
    fn pattern_move(
        &self,
        f: &mut impl FnMut(f64, f64) -> f64,
        best: &mut Best2,
        (x1, y1): (f64, f64),
        end: (f64, f64),
        tolerance: f64,
    ) {
        let (dx, dy) = (end.0 - x1, end.1 - y1);
        if dx == 0.0 && dy == 0.0 {
            return;
        }
        // Points end + t·(dx, dy) inside the box; t = −1 is the previous end.
        // In a valley the optimum along the line can be many sweeps ahead.
        let (mut t_low, mut t_high) = (-1.0_f64, f64::INFINITY);
        for (origin, delta, (lower, upper)) in [(end.0, dx, self.x), (end.1, dy, self.y)] {
            if delta != 0.0 {
                let (to_lower, to_upper) = ((lower - origin) / delta, (upper - origin) / delta);
                t_low = t_low.max(to_lower.min(to_upper));
                t_high = t_high.min(to_lower.max(to_upper));
            }
        }
        if t_high > t_low {
            let t_tolerance = tolerance / dx.abs().max(dy.abs());
            let (t, value) = minimize_scalar(
                |t| f(end.0 + t * dx, end.1 + t * dy),
                t_low,
                t_high,
                LOCAL_GRID,
                t_tolerance,
            );
            best.offer(end.0 + t * dx, end.1 + t * dy, value);
        }
    }
}

/// The value used to compare function values: non-finite ones are worst.
fn comparable(value: f64) -> f64 {
    if value.is_finite() {
        value
    } else {
        f64::INFINITY
    }
}

/// A function wrapper that remembers the best point it has been evaluated at.
struct Tracked<F> {
    f: F,
    x: f64,
    value: f64,
    key: f64,
}

impl<F: FnMut(f64) -> f64> Tracked<F> {
    fn new(f: F) -> Self {
        Self {
            f,
            x: f64::NAN,
            value: f64::NAN,
            key: f64::INFINITY,
        }
    }

    /// f(x) for comparison (non-finite → +∞).
    fn eval(&mut self, x: f64) -> f64 {
        let value = (self.f)(x);
        let key = comparable(value);
        if key < self.key || self.x.is_nan() {
            (self.x, self.value, self.key) = (x, value, key);
        }
        key
    }

    fn best(&self) -> (f64, f64) {
        (self.x, self.value)
    }
}

/// Brent's localmin on [a, b] (Brent 1973, ch. 5): keeps the best point x, the second
/// best w and the previous w, v; tries the minimum of the parabola through them when it
/// lies inside the bracket and the step is less than half the step before last, and
/// falls back to golden section otherwise. Stops when x is within 2·tol of every point
/// of the bracket, tol = √ε·|x| + tolerance/3.
fn brent<F: FnMut(f64) -> f64>(tracked: &mut Tracked<F>, mut a: f64, mut b: f64, tolerance: f64) {
    let absolute = if tolerance.is_finite() && tolerance > 0.0 {
        tolerance / 3.0
    } else {
        0.0
    };
    let mut x = a + GOLDEN_FRACTION * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = tracked.eval(x);
    let (mut fw, mut fv) = (fx, fx);
    // d: the last step; e: the step before it.
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    for _ in 0..MAX_BRENT_ITERATIONS {
        let middle = 0.5 * (a + b);
        let tol = SQRT_EPSILON * x.abs() + absolute;
        let tol2 = 2.0 * tol;
        if (x - middle).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut parabolic = false;
        if e.abs() > tol && fx.is_finite() && fw.is_finite() && fv.is_finite() {
            // Minimum of the parabola through (x, fx), (w, fw), (v, fv) at x + p/q.
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut p = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                p = -p;
            } else {
                q = -q;
            }
            let before_last = e;
            e = d;
            if p.abs() < (0.5 * q * before_last).abs() && p > q * (a - x) && p < q * (b - x) {
                d = p / q;
                let u = x + d;
                // Do not evaluate within tol of the bracket's ends.
                if u - a < tol2 || b - u < tol2 {
                    d = if x < middle { tol } else { -tol };
                }
                parabolic = true;
            }
        }
        if !parabolic {
            e = if x < middle { b - x } else { a - x };
            d = GOLDEN_FRACTION * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else if d > 0.0 {
            x + tol
        } else {
            x - tol
        };
        let fu = tracked.eval(u);
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv) = (w, fw);
            (w, fw) = (x, fx);
            (x, fx) = (u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv) = (w, fw);
                (w, fw) = (u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::numerics::linear_least_squares;

    fn relative(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    /// A deterministic well-spread sequence in [0, 1) (golden-ratio additive recurrence).
    fn spread(i: usize) -> f64 {
        (i as f64 * 0.618_033_988_749_894_9).fract()
    }

    #[test]
    fn separable_fit_recovers_a_hunt_crossley_law() {
        // f = k·δ^n + c·δ^n·δ̇: for fixed n linear in (k, c).
        let (k, n, c) = (7e9, 1.45, 5e8);
        let samples = 2000;
        let depth = |i: usize| 3e-5 * (i + 1) as f64 / samples as f64;
        let rate = |i: usize| -1.4 + 2.8 * spread(i);
        let force = |i: usize| {
            let power = depth(i).powf(n);
            k * power + c * power * rate(i)
        };
        let inner = |exponent: f64| {
            linear_least_squares(samples, 2, |i, out| {
                let power = depth(i).powf(exponent);
                out[0] = power;
                out[1] = power * rate(i);
                force(i)
            })
        };
        let mut calls = 0;
        let (n_found, rss) = minimize_scalar(
            |exponent| {
                calls += 1;
                inner(exponent).map_or(f64::NAN, |fit| fit.residual_sum_of_squares)
            },
            1.0,
            2.0,
            16, // spacing 1/15: no grid point falls on n
            1e-10,
        );
        let fit = inner(n_found).unwrap();
        let (k_found, c_found) = (fit.coefficients[0], fit.coefficients[1]);
        eprintln!(
            "separable: n error {:.2e}, k rel {:.2e}, c rel {:.2e}, rss {rss:.2e}, {calls} evaluations",
            (n_found - n).abs(),
            relative(k_found, k),
            relative(c_found, c)
        );
        assert!((n_found - n).abs() < 1e-6, "n = {n_found}");
        assert!(relative(k_found, k) < 1e-5, "k = {k_found}");
        assert!(relative(c_found, c) < 1e-5, "c = {c_found}");
    }

    #[test]
    fn scalar_minimum_of_a_smooth_function() {
        let mut calls = 0;
        let (x, value) = minimize_scalar(
            |x| {
                calls += 1;
                (x - 0.3).powi(2) + 1.0
            },
            -2.0,
            3.0,
            11,
            1e-10,
        );
        eprintln!(
            "parabola: x error {:.2e}, {calls} evaluations",
            (x - 0.3).abs()
        );
        assert!((x - 0.3).abs() < 1e-8, "x = {x}");
        assert!((value - 1.0).abs() < 1e-15);
    }

    #[test]
    fn scalar_grid_finds_the_global_minimum_and_skips_nan() {
        // Local minima near ±π/5, 3π/5 …; the global one is the one near π/5.
        let f = |x: f64| (5.0 * x).cos() + 0.1 * (x - 1.0).powi(2);
        let derivative = |x: f64| -5.0 * (5.0 * x).sin() + 0.2 * (x - 1.0);
        let (x, value) = minimize_scalar(f, -3.0, 3.0, 40, 1e-12);
        let scan = (0..=600_000)
            .map(|i| f(-3.0 + 6.0 * i as f64 / 600_000.0))
            .fold(f64::INFINITY, f64::min);
        eprintln!(
            "multimodal: x {x}, f'(x) {:.2e}, f - scan {:.2e}",
            derivative(x),
            value - scan
        );
        assert!((x - 0.6).abs() < 0.1, "x = {x}");
        assert!(derivative(x).abs() < 1e-6, "f'({x}) = {}", derivative(x));
        assert!(value <= scan + 1e-12);

        // Undefined below 0.5 (NaN) and +∞ above 2.5: both count as worst.
        let (x, value) = minimize_scalar(
            |x| {
                if x < 0.5 {
                    f64::NAN
                } else if x > 2.5 {
                    f64::INFINITY
                } else {
                    (x - 0.7).powi(2)
                }
            },
            0.0,
            3.0,
            7,
            1e-10,
        );
        assert!((x - 0.7).abs() < 1e-8, "x = {x}");
        assert!(value < 1e-15);

        // Minimum at a bound.
        let (x, _) = minimize_scalar(|x| x, 1.0, 2.0, 5, 1e-9);
        assert!((x - 1.0).abs() <= 1e-9, "x = {x}");
    }

    #[test]
    fn box_minimum_in_a_diagonal_valley() {
        // A narrow valley along y = 0.6 + 0.9·(x − 0.3), minimum at (0.3, 0.6).
        let mut calls = 0;
        let ((x, y), value) = minimize_box2(
            |x, y| {
                calls += 1;
                (x - 0.3).powi(2) + 100.0 * (y - 0.6 - 0.9 * (x - 0.3)).powi(2)
            },
            (-1.0, 1.0),
            (-1.0, 2.0),
            11,
            1e-9,
        );
        eprintln!(
            "valley: error ({:.2e}, {:.2e}), f {value:.2e}, {calls} evaluations",
            x - 0.3,
            y - 0.6
        );
        assert!(
            (x - 0.3).abs() < 1e-6 && (y - 0.6).abs() < 1e-6,
            "({x}, {y})"
        );
        assert!(value < 1e-12);

        // Rosenbrock's curved valley, minimum at (1, 1).
        let mut calls = 0;
        let ((x, y), value) = minimize_box2(
            |x, y| {
                calls += 1;
                (1.0 - x).powi(2) + 100.0 * (y - x * x).powi(2)
            },
            (-2.0, 2.0),
            (-1.0, 3.0),
            21,
            1e-10,
        );
        eprintln!(
            "rosenbrock box: error ({:.2e}, {:.2e}), f {value:.2e}, {calls} evaluations",
            x - 1.0,
            y - 1.0
        );
        assert!(
            (x - 1.0).abs() < 1e-6 && (y - 1.0).abs() < 1e-6,
            "({x}, {y})"
        );

        // Minimum outside the box in x: ends on the x bound; NaN region ignored.
        let ((x, y), _) = minimize_box2(
            |x, y| {
                if y > 1.5 {
                    f64::NAN
                } else {
                    (x - 5.0).powi(2) + (y - 0.25).powi(2)
                }
            },
            (0.0, 2.0),
            (0.0, 2.0),
            9,
            1e-10,
        );
        assert!((x - 2.0).abs() < 1e-9, "x = {x}");
        assert!((y - 0.25).abs() < 1e-7, "y = {y}");
    }
}
