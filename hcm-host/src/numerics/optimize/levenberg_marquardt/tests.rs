use super::*;

/// The box of `ranges` (lower, upper), one unnamed parameter each.
fn boxed(ranges: &[(f64, f64)]) -> Vec<Bound> {
    ranges
        .iter()
        .enumerate()
        .map(|(i, &(lower, upper))| Bound::linear(format!("p{i}"), lower, upper))
        .collect()
}
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::Normal;

fn relative(a: f64, b: f64) -> f64 {
    ((a - b) / b).abs()
}

#[test]
fn rosenbrock_from_the_classic_start() {
    let result = levenberg_marquardt(
        |p, r| {
            r[0] = 10.0 * (p[1] - p[0] * p[0]);
            r[1] = 1.0 - p[0];
        },
        2,
        &[-1.2, 1.0],
        &[1.0, 1.0],
        None,
        &LmSettings::default(),
    )
    .unwrap();
    eprintln!(
        "rosenbrock: error ({:.1e}, {:.1e}), cost {:.1e}, {} iterations, {} evaluations",
        result.parameters[0] - 1.0,
        result.parameters[1] - 1.0,
        result.cost,
        result.iterations,
        result.evaluations
    );
    assert!(result.termination.converged(), "{result:?}");
    assert!((result.parameters[0] - 1.0).abs() < 1e-8, "{result:?}");
    assert!((result.parameters[1] - 1.0).abs() < 1e-8, "{result:?}");
    // m = p: no degrees of freedom left for σ².
    assert_eq!(result.covariance, None);
}

/// y = a·exp(−b·t) on 40 points of [0, 3].
fn exponential(p: &[f64], t: f64) -> f64 {
    p[0] * (-p[1] * t).exp()
}
const TIMES: usize = 40;
fn time(i: usize) -> f64 {
    3.0 * i as f64 / (TIMES - 1) as f64
}

#[test]
fn exponential_standard_errors_match_the_spread_of_estimates() {
    let truth = [2.0, 1.3];
    let sigma = 0.05;
    let noise = Normal::new(0.0, sigma).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(20_240_611);
    let realisations = 50;
    let mut estimates = Vec::new();
    let mut reported = [0.0; 2];
    for _ in 0..realisations {
        let data: Vec<f64> = (0..TIMES)
            .map(|i| exponential(&truth, time(i)) + rng.sample(noise))
            .collect();
        let result = levenberg_marquardt(
            |p, r| {
                for (i, r) in r.iter_mut().enumerate() {
                    *r = exponential(p, time(i)) - data[i];
                }
            },
            TIMES,
            &[1.0, 0.5],
            &[1.0, 1.0],
            None,
            &LmSettings::default(),
        )
        .unwrap();
        assert!(result.termination.converged(), "{result:?}");
        let covariance = result.covariance.unwrap();
        for (k, total) in reported.iter_mut().enumerate() {
            *total += covariance[k][k].sqrt() / realisations as f64;
        }
        estimates.push(result.parameters);
    }
    for k in 0..2 {
        let mean = estimates.iter().map(|e| e[k]).sum::<f64>() / realisations as f64;
        let spread = (estimates.iter().map(|e| (e[k] - mean).powi(2)).sum::<f64>()
            / (realisations - 1) as f64)
            .sqrt();
        let ratio = reported[k] / spread;
        eprintln!(
            "exponential parameter {k}: mean {mean:.4} (true {}), spread {spread:.4e}, mean reported standard error {:.4e}, ratio {ratio:.3}",
            truth[k], reported[k]
        );
        assert!((0.5..2.0).contains(&ratio), "parameter {k}: ratio {ratio}");
    }
}

#[test]
fn linear_model_covariance_is_the_analytic_one() {
    // y = c0 + c1·t: covariance σ²(XᵀX)⁻¹ with σ² = RSS/(m − 2), in closed form.
    let data = [
        (0.0, 0.1),
        (1.0, 1.26),
        (2.0, 1.92),
        (3.0, 3.18),
        (4.0, 4.04),
    ];
    let result = levenberg_marquardt(
        |p, r| {
            for (r, (t, y)) in r.iter_mut().zip(data) {
                *r = p[0] + p[1] * t - y;
            }
        },
        data.len(),
        &[0.0, 0.0],
        &[1.0, 1.0],
        None,
        &LmSettings::default(),
    )
    .unwrap();
    // Solution 0.14 + 0.98·t, RSS = 0.064; XᵀX = [[5, 10], [10, 30]], det 50.
    let variance = 0.064 / 3.0;
    let analytic = [
        [variance * 30.0 / 50.0, -variance * 10.0 / 50.0],
        [-variance * 10.0 / 50.0, variance * 5.0 / 50.0],
    ];
    let covariance = result.covariance.clone().unwrap();
    let worst = (0..4)
        .map(|e| relative(covariance[e / 2][e % 2], analytic[e / 2][e % 2]))
        .fold(0.0, f64::max);
    eprintln!("linear covariance: worst relative error {worst:.2e}");
    assert!((result.parameters[0] - 0.14).abs() < 1e-10, "{result:?}");
    assert!((result.parameters[1] - 0.98).abs() < 1e-10, "{result:?}");
    assert!(worst < 1e-6, "{covariance:?} vs {analytic:?}");
}

#[test]
fn bounds_hold_the_solution_on_the_boundary() {
    // Noise-free decay with b = 1.3, but b is bounded to [0, 1]: the constrained
    // optimum has b = 1 and a = Σy·e^{−t}/Σe^{−2t}.
    let data: Vec<f64> = (0..TIMES)
        .map(|i| exponential(&[2.0, 1.3], time(i)))
        .collect();
    let result = levenberg_marquardt(
        |p, r| {
            for (i, r) in r.iter_mut().enumerate() {
                *r = exponential(p, time(i)) - data[i];
            }
        },
        TIMES,
        &[1.0, 0.5],
        &[1.0, 1.0],
        Some(&boxed(&[(0.0, 10.0), (0.0, 1.0)])),
        &LmSettings::default(),
    )
    .unwrap();
    let numerator: f64 = (0..TIMES).map(|i| data[i] * (-time(i)).exp()).sum();
    let denominator: f64 = (0..TIMES).map(|i| (-2.0 * time(i)).exp()).sum();
    let a = numerator / denominator;
    eprintln!(
        "bounded: b = {}, a error {:.1e}, {} iterations",
        result.parameters[1],
        result.parameters[0] - a,
        result.iterations
    );
    assert!(result.termination.converged(), "{result:?}");
    assert_eq!(result.parameters[1], 1.0, "{result:?}");
    assert!(
        relative(result.parameters[0], a) < 1e-9,
        "{result:?} vs a = {a}"
    );

    // Starting outside the box: projected in, and the lower bound holds.
    let result = levenberg_marquardt(
        |p, r| {
            r[0] = p[0] - 3.0;
            r[1] = p[1] + 2.0;
            r[2] = p[0] + p[1] - 1.0;
        },
        3,
        &[10.0, 0.5],
        &[1.0, 1.0],
        Some(&boxed(&[(-1.0, 2.0), (-0.5, f64::INFINITY)])),
        &LmSettings::default(),
    )
    .unwrap();
    assert!(result.termination.converged(), "{result:?}");
    assert_eq!(result.parameters[1], -0.5, "{result:?}");
    // With p1 = −0.5: minimise (p0 − 3)² + (p0 − 1.5)² → p0 = 2.25, above 2.
    assert_eq!(result.parameters[0], 2.0, "{result:?}");

    // A law undefined beyond its bound, with a scale that does not divide the bound
    // exactly (0.7/0.3·0.3 rounds above 0.7): the bound is still met exactly.
    let result = levenberg_marquardt(
        |p, r| r[0] = if p[0] > 0.7 { f64::NAN } else { p[0] - 5.0 },
        1,
        &[0.5],
        &[0.3],
        Some(&boxed(&[(0.0, 0.7)])),
        &LmSettings::default(),
    )
    .unwrap();
    assert!(result.termination.converged(), "{result:?}");
    assert_eq!(result.parameters[0], 0.7, "{result:?}");
}

#[test]
fn parameters_ten_orders_apart_converge_from_30_percent_off() {
    // A Hertz law f = k·δ^n, k = 7e9 N/m^n, n = 1.45, δ ∈ (0, 30 µm].
    let (k, n) = (7e9, 1.45);
    let m = 500;
    let depth = |i: usize| 3e-5 * (i + 1) as f64 / m as f64;
    let force: Vec<f64> = (0..m).map(|i| k * depth(i).powf(n)).collect();
    for start in [[1.3 * k, 0.7 * n], [0.7 * k, 1.3 * n]] {
        let result = levenberg_marquardt(
            |p, r| {
                for (i, r) in r.iter_mut().enumerate() {
                    *r = p[0] * depth(i).powf(p[1]) - force[i];
                }
            },
            m,
            &start,
            &[1e9, 1.0],
            None,
            &LmSettings::default(),
        )
        .unwrap();
        eprintln!(
            "hertz from {start:?}: k rel {:.1e}, n error {:.1e}, {} iterations, {} evaluations",
            relative(result.parameters[0], k),
            result.parameters[1] - n,
            result.iterations,
            result.evaluations
        );
        assert!(result.termination.converged(), "{result:?}");
        assert!(relative(result.parameters[0], k) < 1e-8, "{result:?}");
        assert!((result.parameters[1] - n).abs() < 1e-9, "{result:?}");
    }
}

#[test]
fn nan_at_a_trial_point_is_a_rejected_step() {
    // r = ln p − ln 2 from p = 10: the Gauss–Newton step goes to p ≈ −6 (NaN).
    let result = levenberg_marquardt(
        |p, r| r[0] = p[0].ln() - 2.0_f64.ln(),
        1,
        &[10.0],
        &[1.0],
        None,
        &LmSettings {
            initial_damping: 1e-9,
            ..LmSettings::default()
        },
    )
    .unwrap();
    assert!(result.termination.converged(), "{result:?}");
    assert!((result.parameters[0] - 2.0).abs() < 1e-10, "{result:?}");
}

#[test]
fn invalid_inputs_are_errors() {
    let residuals = |p: &[f64], r: &mut [f64]| r[0] = p[0];
    let settings = LmSettings::default();
    assert!(matches!(
        levenberg_marquardt(residuals, 1, &[1.0], &[0.0], None, &settings),
        Err(LeastSquaresError::InvalidScale { index: 0, .. })
    ));
    assert!(matches!(
        levenberg_marquardt(
            residuals,
            1,
            &[1.0],
            &[1.0],
            Some(&boxed(&[(2.0, 1.0)])),
            &settings
        ),
        Err(LeastSquaresError::InvalidBounds { index: 0, .. })
    ));
    assert!(matches!(
        levenberg_marquardt(residuals, 1, &[1.0, 2.0], &[1.0, 1.0], None, &settings),
        Err(LeastSquaresError::TooFewRows {
            rows: 1,
            unknowns: 2
        })
    ));
    assert!(matches!(
        levenberg_marquardt(|_, r| r[0] = f64::NAN, 1, &[1.0], &[1.0], None, &settings),
        Err(LeastSquaresError::NonFiniteInitialResidual { index: 0 })
    ));
}

#[test]
fn the_termination_says_why_it_stopped() {
    let rosenbrock = |p: &[f64], r: &mut [f64]| {
        r[0] = 10.0 * (p[1] - p[0] * p[0]);
        r[1] = 1.0 - p[0];
    };
    let run = |start: [f64; 2], settings: &LmSettings| {
        levenberg_marquardt(rosenbrock, 2, &start, &[1.0, 1.0], None, settings).unwrap()
    };
    // Started on the minimum, where the residuals are zero.
    let exact = run([1.0, 1.0], &LmSettings::default());
    assert_eq!(exact.termination, Termination::ExactFit);
    assert_eq!(exact.iterations, 0);
    // Three iterations are far too few from the classic start.
    let short = run(
        [-1.2, 1.0],
        &LmSettings {
            max_iterations: 3,
            ..LmSettings::default()
        },
    )
    .termination;
    assert_eq!(short, Termination::MaxIterations);
    assert!(!short.converged());
    assert_eq!(short.to_string(), "the iteration limit was reached");

    // Both parameters pushed against a bound (the unconstrained minimum is (3, −2)).
    let held = levenberg_marquardt(
        |p, r| {
            r[0] = p[0] - 3.0;
            r[1] = p[1] + 2.0;
        },
        2,
        &[0.0, 0.0],
        &[1.0, 1.0],
        Some(&boxed(&[(-1.0, 2.0), (-0.5, 1.0)])),
        &LmSettings::default(),
    )
    .unwrap();
    assert_eq!(held.termination, Termination::HeldByBounds, "{held:?}");
    assert_eq!(held.parameters, vec![2.0, -0.5]);

    // A straight line through noisy points: the minimum is met by a gradient, step or
    // reduction test, whichever comes first, but a tolerance is met.
    let noisy = levenberg_marquardt(
        |p, r| {
            for (i, r) in r.iter_mut().enumerate() {
                let t = i as f64;
                *r = p[0] + p[1] * t - (0.5 + 2.0 * t + 0.1 * (1.7 * t).sin());
            }
        },
        20,
        &[0.0, 0.0],
        &[1.0, 1.0],
        None,
        &LmSettings::default(),
    )
    .unwrap();
    eprintln!("noisy line: {}", noisy.termination);
    assert!(noisy.termination.converged(), "{noisy:?}");
    assert!(matches!(
        noisy.termination,
        Termination::SmallGradient | Termination::SmallStep | Termination::SmallReduction
    ));
}
