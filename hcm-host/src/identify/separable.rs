//! Least-squares identification by variable projection (Golub & Pereyra 1973):
//! every law of the core is linear in some parameters once the others are fixed,
//! so those are solved exactly by QR for each value of the rest, an outer search
//! picks the rest, and Levenberg–Marquardt then refines all of them on the law
//! itself (with its clamps and guards).
//!
//! | law | nonlinear part | linear part (regressors) |
//! |---|---|---|
//! | hertz | n | k (δ^n) |
//! | lankarani_nikravesh | n | k (δ^n), k(1−ce²) (¾·δ^n·δ̇/δ̇0) |
//! | hunt_crossley | n | k (δ^n), k·χ (δ^n·δ̇) |
//! | flores | n | k (δ^n), k·8(1−ce)/(5ce) (δ^n·δ̇/δ̇0) |
//! | variable_stiffness | — | c·E* (a(δ)·δ), λ·√(c·E*) (2√(a(δ)·m_e)·δ·δ̇) |
//! | impact | e, δ_max | k (δ^e), d_max (step(δ, 0, 0, δ_max, 1)·δ̇) |

use super::bounds::Bounds;
use super::IdentifyError;
use crate::dataset::ForceSample;
use crate::numerics::linear_least_squares;
use crate::numerics::optimize::levenberg_marquardt::{levenberg_marquardt, LmSettings};
use crate::numerics::optimize::{minimize_box2, minimize_scalar, LeastSquaresError, Parameters};
use hcm_core::law::{step, AnyNormalLaw, Impact, VariableStiffness};
use hcm_core::model::ContactModel;

/// The result of a least-squares fit.
#[derive(Clone, Debug)]
pub struct LsqFit {
    /// The identified law.
    pub(crate) law: AnyNormalLaw<f64>,
    /// What the data fix and what they do not.
    pub(crate) notes: Vec<String>,
    /// One-sigma standard errors of the free parameters, by name (from LM's covariance).
    pub(crate) standard_errors: Vec<(String, f64)>,
}

/// Fits `template`'s law (its fixed parameters, e.g. geometry, are kept) to `samples`.
pub fn fit(
    template: &AnyNormalLaw<f64>,
    samples: &[ForceSample],
    bounds: &Bounds,
) -> Result<LsqFit, IdentifyError> {
    let mut notes = Vec::new();
    let initial = linear_stage(template, samples, bounds, &mut notes)?;
    refine(initial, samples, bounds, notes)
}

/// Inner linear solve for fixed nonlinear parameters: returns the coefficients and
/// the residual sum of squares.
fn solve(
    samples: &[ForceSample],
    regressors: impl Fn(&ForceSample, &mut [f64]),
    columns: usize,
) -> Result<(Vec<f64>, f64), IdentifyError> {
    let fit = linear_least_squares(samples.len(), columns, |i, row| {
        regressors(&samples[i], row);
        samples[i].force
    })
    .map_err(LeastSquaresError::from)?;
    Ok((fit.coefficients, fit.residual_sum_of_squares))
}

/// δ̇/δ̇0, 0 when the approach speed is not positive (the laws drop damping then).
fn relative_rate(s: &ForceSample) -> f64 {
    if s.approach_speed > 0.0 {
        s.rate / s.approach_speed
    } else {
        0.0
    }
}

const GRID: usize = 41;
const TOLERANCE: f64 = 1e-10;

/// Variable projection: the law with the best linear parameters at the best nonlinear ones.
fn linear_stage(
    template: &AnyNormalLaw<f64>,
    samples: &[ForceSample],
    bounds: &Bounds,
    notes: &mut Vec<String>,
) -> Result<AnyNormalLaw<f64>, IdentifyError> {
    let exponents = bounds.range("exponent");
    let law = match *template {
        AnyNormalLaw::Hertz(mut law) => {
            (law.exponent, law.stiffness) = power_law(samples, exponents)?;
            law.into()
        }
        AnyNormalLaw::LankaraniNikravesh(mut law) => {
            let damping = |s: &ForceSample| 0.75 * relative_rate(s);
            let (exponent, theta) = damped_power_law(samples, exponents, damping)?;
            law.exponent = exponent;
            law.stiffness = theta[0];
            law.restitution = (1.0 - theta[1] / theta[0]).max(0.0).sqrt();
            law.into()
        }
        AnyNormalLaw::HuntCrossley(mut law) => {
            let (exponent, theta) = damped_power_law(samples, exponents, |s| s.rate)?;
            law.exponent = exponent;
            law.stiffness = theta[0];
            law.damping = theta[1] / theta[0];
            law.into()
        }
        AnyNormalLaw::Flores(mut law) => {
            let (exponent, theta) = damped_power_law(samples, exponents, relative_rate)?;
            law.exponent = exponent;
            law.stiffness = theta[0];
            law.restitution = 8.0 / (5.0 * theta[1] / theta[0] + 8.0);
            law.into()
        }
        AnyNormalLaw::VariableStiffness(law) => variable_stiffness(law, samples, notes)?.into(),
        AnyNormalLaw::Impact(law) => impact(law, samples, bounds)?.into(),
    };
    Ok(bounds.clamp(&law))
}

/// Hertz's f = k·δ^n: the exponent n (–) searched on `exponents`, then the stiffness k
/// (N/m^n) solved at it.
fn power_law(
    samples: &[ForceSample],
    (n_lo, n_hi): (f64, f64),
) -> Result<(f64, f64), IdentifyError> {
    let rss = |n: f64| {
        solve(samples, |s, row| row[0] = s.depth.powf(n), 1).map_or(f64::INFINITY, |(_, r)| r)
    };
    let exponent = minimize_scalar(rss, n_lo, n_hi, GRID, TOLERANCE).0;
    let stiffness = solve(samples, |s, row| row[0] = s.depth.powf(exponent), 1)?.0[0];
    Ok((exponent, stiffness))
}

/// f = θ₀·δ^n + θ₁·δ^n·`damping`(sample): the exponent n (–) searched on `exponents`,
/// then (θ₀, θ₁) solved at it; the caller turns θ into its law's parameters.
fn damped_power_law(
    samples: &[ForceSample],
    (n_lo, n_hi): (f64, f64),
    damping: fn(&ForceSample) -> f64,
) -> Result<(f64, Vec<f64>), IdentifyError> {
    let two_term = |n: f64| {
        solve(
            samples,
            |s, row| {
                let elastic = s.depth.powf(n);
                row[0] = elastic;
                row[1] = elastic * damping(s);
            },
            2,
        )
    };
    let rss = |n: f64| two_term(n).map_or(f64::INFINITY, |(_, rss)| rss);
    let exponent = minimize_scalar(rss, n_lo, n_hi, GRID, TOLERANCE).0;
    let (theta, _) = two_term(exponent)?;
    Ok((exponent, theta))
}

/// The variable-stiffness law's c (–) and damping, linear in the force once E*, R and
/// m_e come from the scenario; `notes` says that the force fixes only c·E*.
fn variable_stiffness(
    mut law: VariableStiffness<f64>,
    samples: &[ForceSample],
    notes: &mut Vec<String>,
) -> Result<VariableStiffness<f64>, IdentifyError> {
    let (r, m) = (law.radius, law.effective_mass);
    let (theta, _) = solve(
        samples,
        |s, row| {
            let area = (2.0 * r * s.depth - s.depth * s.depth).max(0.0).sqrt();
            row[0] = area * s.depth;
            row[1] = 2.0 * (area * m).sqrt() * s.depth * s.rate;
        },
        2,
    )?;
    law.surface_loading = theta[0] / law.effective_modulus;
    law.damping = theta[1] / theta[0].max(f64::MIN_POSITIVE).sqrt();
    notes.push(format!(
        "variable_stiffness: the force fixes only c·E* = {:.6e} Pa; c is reported for E* = {:.6e} Pa from the scenario's materials",
        theta[0], law.effective_modulus
    ));
    Ok(law)
}

/// IMPACT's f = k·δ^e + c_max·STEP(δ; 0, d)·δ̇: the exponent e (–) and the full-damping
/// depth d (m) searched on their box, then k (N/m^e) and c_max (N·s/m) solved there.
fn impact(
    mut law: Impact<f64>,
    samples: &[ForceSample],
    bounds: &Bounds,
) -> Result<Impact<f64>, IdentifyError> {
    let regressors = |e: f64, depth: f64| {
        move |s: &ForceSample, row: &mut [f64]| {
            row[0] = s.depth.powf(e);
            row[1] = step(s.depth, 0.0, 0.0, depth, 1.0) * s.rate;
        }
    };
    let rss = |e: f64, depth: f64| {
        solve(samples, regressors(e, depth), 2).map_or(f64::INFINITY, |(_, r)| r)
    };
    let (exponents, depths) = (bounds.range("exponent"), bounds.range("full_damping_depth"));
    let ((e, depth), _) = minimize_box2(rss, exponents, depths, 11, TOLERANCE);
    let (theta, _) = solve(samples, regressors(e, depth), 2)?;
    (
        law.exponent,
        law.full_damping_depth,
        law.stiffness,
        law.max_damping,
    ) = (e, depth, theta[0], theta[1]);
    Ok(law)
}

/// Levenberg–Marquardt on the free parameters of `law`, residual = model − measured force.
fn refine(
    law: AnyNormalLaw<f64>,
    samples: &[ForceSample],
    bounds: &Bounds,
    mut notes: Vec<String>,
) -> Result<LsqFit, IdentifyError> {
    let free = bounds.free();
    let start = bounds.checked_values(&law)?;
    let scales: Vec<f64> = start.iter().map(|v| v.abs().max(1e-12)).collect();
    let box_bounds = bounds.bounds();
    let with = |p: &[f64]| bounds.with(&law, p);
    let residuals = |p: &[f64], out: &mut [f64]| {
        let candidate = ContactModel::physics(with(p));
        for (r, s) in out.iter_mut().zip(samples) {
            let (state, memory) = s.state();
            *r = candidate.physics_normal_force(&state, &memory) - s.force;
        }
    };
    let result = levenberg_marquardt(
        residuals,
        samples.len(),
        &start,
        &scales,
        Some(&box_bounds),
        &LmSettings::default(),
    )?;
    let fitted = with(&result.parameters);
    let standard_errors = match &result.covariance {
        Some(cov) => free
            .iter()
            .enumerate()
            .map(|(i, name)| (name.to_string(), cov[i][i].max(0.0).sqrt()))
            .collect(),
        None => Vec::new(),
    };
    if !result.termination.converged() {
        notes.push(format!(
            "Levenberg–Marquardt stopped before meeting a tolerance: {}",
            result.termination
        ));
    }
    Ok(LsqFit {
        law: fitted,
        notes,
        standard_errors,
    })
}
