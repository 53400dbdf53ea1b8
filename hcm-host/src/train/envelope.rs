//! The training envelope's tolerance: how far beyond the range seen in training each
//! input may lie and the residual still run.
//!
//! Rule: every input may leave its [min, max] by ρ = 1 % of S in its *normalised*
//! units, where S is the mean normalised spread (max − min)/σ of the inputs that vary
//! in training. In raw units, tolerance_i = ρ·S·σ_i:
//!
//! - for a varying input, about 1 % of its own range (S·σ_i ≈ its range; uniform
//!   data: S ≈ 3.5);
//! - for an input constant in training (the ball's δ̇0: min and max 7e-13 m/s apart),
//!   whose normalisation scale is 1 in its unit (`normalisation` in `train`), ρ·S in
//!   its unit: 0.035 m/s for S = 3.5.
//!
//! Why this measure: the first layer sees x̂ = (x − μ)/σ. A constant input's x̂ was 0
//! throughout training, so its weights kept their initial (Glorot) values, of the
//! same size as the trained inputs' weights: an x̂ of ρ·S moves the first layer's
//! pre-activations by about ρ of what the inputs that the network was trained over do.
//! A controller's δ̇0 that differs in the 7th digit stays far inside; one 10 % away is
//! outside. The data give S and σ; ρ is the one chosen number.

/// ρ: the tolerance as a fraction of the varying inputs' mean normalised spread.
pub const TOLERANCE_FRACTION: f64 = 0.01;

/// A normalised spread below this counts as constant and does not enter S.
const CONSTANT_SPREAD: f64 = 1e-6;

/// tolerance_i = ρ·S·σ_i (raw units, ≥ 0) for inputs with training range [min, max]
/// and normalisation scale σ (all three one value per input).
pub fn envelope_tolerance(min: &[f64], max: &[f64], scale: &[f64]) -> Vec<f64> {
    let spreads: Vec<f64> = min
        .iter()
        .zip(max)
        .zip(scale)
        .map(|((min, max), scale)| (max - min) / scale)
        .filter(|spread| spread.is_finite() && *spread > CONSTANT_SPREAD)
        .collect();
    let mean_spread = if spreads.is_empty() {
        0.0
    } else {
        spreads.iter().sum::<f64>() / spreads.len() as f64
    };
    scale
        .iter()
        .map(|scale| TOLERANCE_FRACTION * mean_spread * scale)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_constant_input_gets_a_fraction_of_the_others_normalised_spread() {
        // δ on [0, 60 µm] (σ 17 µm), δ̇ on ±1.4 m/s (σ 0.8 m/s), δ̇0 constant (σ 1).
        let min = [0.0, -1.4, 1.4];
        let max = [60e-6, 1.4, 1.4 + 7e-13];
        let scale = [17e-6, 0.8, 1.0];
        let spread = (60.0 / 17.0 + 2.8 / 0.8) / 2.0;
        let tolerance = envelope_tolerance(&min, &max, &scale);
        assert!(
            (tolerance[2] - 0.01 * spread).abs() < 1e-12,
            "{tolerance:?}"
        );
        assert!((tolerance[0] - 0.01 * spread * 17e-6).abs() < 1e-15);
        assert!((tolerance[1] - 0.01 * spread * 0.8).abs() < 1e-12);
        // Nothing varies: no tolerance at all.
        assert_eq!(envelope_tolerance(&[1.0], &[1.0], &[1.0]), vec![0.0]);
    }
}
