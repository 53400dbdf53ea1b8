//! Paired comparisons of two models' scores on the same held-out units — the runs of a
//! force diagnosis ([`super::held_out`]), the tosses of a motion diagnosis
//! ([`super::motion`]): the mean difference, its standard error over the units, its t
//! and Student's t interval. The one yardstick both diagnoses judge a cause by.

use serde::Serialize;

/// Student's t 97.5 % quantiles for 1 to 30 degrees of freedom (two-sided 95 %).
const T_975: [f64; 30] = [
    12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179, 2.160,
    2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064, 2.060, 2.056,
    2.052, 2.048, 2.045, 2.042,
];

/// Student's t 97.5 % quantile for `dof` degrees of freedom (–; 1.96 beyond 30, and
/// for 0, where no interval is finite anyway).
pub(crate) fn t_975(dof: usize) -> f64 {
    dof.checked_sub(1)
        .and_then(|k| T_975.get(k))
        .copied()
        .unwrap_or(1.96)
}

/// Mean of `a − b` over paired units (runs or tosses), with its uncertainty.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Paired {
    /// Units compared (tosses, runs).
    #[serde(rename = "tosses")]
    pub(crate) units: usize,
    /// Mean difference (the scores' unit: % + ° for tosses, N² for runs' RSS).
    pub mean: f64,
    /// Its standard error (same unit); +∞ with fewer than two units.
    pub standard_error: f64,
    /// 95 % interval of the mean difference (Student's t).
    pub(crate) interval: [f64; 2],
}

impl Paired {
    /// `a[i] − b[i]` over the units both hold (the shorter length).
    pub fn of(a: &[f64], b: &[f64]) -> Paired {
        let d: Vec<f64> = a.iter().zip(b).map(|(a, b)| a - b).collect();
        let n = d.len();
        let mean = d.iter().sum::<f64>() / n.max(1) as f64;
        let standard_error = if n < 2 {
            f64::INFINITY
        } else {
            let variance = d.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
            (variance / n as f64).sqrt()
        };
        let half = t_975(n.saturating_sub(1)) * standard_error;
        Paired {
            units: n,
            mean,
            standard_error,
            interval: [mean - half, mean + half],
        }
    }

    /// Mean over its standard error (0 when both are 0: no difference at all).
    pub fn t(&self) -> f64 {
        if self.mean == 0.0 {
            0.0
        } else {
            self.mean / self.standard_error
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_difference_is_certain_and_noise_is_not() {
        let p = Paired::of(&[3.0, 4.0, 5.0], &[2.0, 3.0, 4.0]);
        assert_eq!((p.mean, p.standard_error), (1.0, 0.0));
        assert_eq!(p.t(), f64::INFINITY);
        // Differences 1, −1, 1, −1: mean 0, se 1/√4·√(4/3).
        let q = Paired::of(&[1.0, 0.0, 1.0, 0.0], &[0.0, 1.0, 0.0, 1.0]);
        assert_eq!(q.mean, 0.0);
        assert!((q.standard_error - (4.0_f64 / 3.0).sqrt() / 2.0).abs() < 1e-15);
        assert_eq!(q.t(), 0.0);
        let half = 3.182 * q.standard_error;
        assert!((q.interval[1] - half).abs() < 1e-12);
    }
}
