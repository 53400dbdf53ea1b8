//! The training envelope's tolerance: how far beyond the range seen in training each
//! input may lie and the residual still run.
//!
//! Rule: an input constant in training (normalised spread (max − min)/σ below 1e-6; the
//! ball's δ̇0: min and max 7e-13 m/s apart) may leave its [min, max] by ρ = 1 % of S in
//! its *normalised* units, where S is the mean normalised spread of the inputs that
//! vary. In raw units, tolerance_i = ρ·S·σ_i, and σ_i is 1 in the input's unit for a
//! constant input (`normalisation` in `train`): ρ·S in its unit, 0.03 m/s for the ball
//! (S ≈ 3). An input that varies keeps tolerance 0: its training range already is
//! where the network was fitted, and widening it (tried: 1 % of each range) let the
//! residual extrapolate at touch-down and lift-off and moved the ball's HCM indicator
//! errors up by 0.02–0.04 points.
//!
//! Why this measure: the first layer sees x̂ = (x − μ)/σ. A constant input's x̂ was 0
//! throughout training, so its weights kept their initial (Glorot) values, of the
//! same size as the trained inputs' weights: an x̂ of ρ·S moves the first layer's
//! pre-activations by about ρ of what the inputs that the network was trained over do.
//! A controller's δ̇0 that differs in the 7th digit stays far inside; one 10 % away is
//! outside. The data give S and σ; ρ is the one chosen number.

/// ρ: the tolerance as a fraction of the varying inputs' mean normalised spread.
pub(crate) const TOLERANCE_FRACTION: f64 = 0.01;

/// A normalised spread below this counts as constant and does not enter S.
const CONSTANT_SPREAD: f64 = 1e-6;

/// tolerance_i = ρ·S·σ_i for a constant input, 0 for one that varies (raw units, ≥ 0),
/// for inputs with training range [min, max] and normalisation scale σ (one value per
/// input each); every component of each of `vectors` — varying or not — gets ρ·S·σ_v,
/// σ_v the largest scale in its vector (its unit).
///
/// Why vectors differ: a state vector's components move together, and a replay that
/// differs from every training run by a hair (the HCM's own prediction error) takes
/// them past their training range at once — the peg tilting 5e-6 beyond the largest
/// q_y seen, at the end of its second wall contact, switched the residual off for the
/// rest of that contact (145 of 348 samples; measured). A tolerance of ρ·S·σ_v is
/// about 1–3 % of the vector's range (peg: 0.28 mm, 6e-4 of a quaternion, 3.6 mm/s,
/// 0.14 rad/s) and the same rule as a constant component's. Inputs outside any vector
/// (the 1D residual's δ, δ̇, δ̇0) keep the rule for single inputs.
pub fn envelope_tolerance(
    min: &[f64],
    max: &[f64],
    scale: &[f64],
    vectors: &[std::ops::Range<usize>],
) -> Vec<f64> {
    let spread: Vec<f64> = min
        .iter()
        .zip(max)
        .zip(scale)
        .map(|((min, max), scale)| (max - min) / scale)
        .collect();
    let varies = |spread: f64| spread.is_finite() && spread > CONSTANT_SPREAD;
    let spreads: Vec<f64> = spread.iter().copied().filter(|s| varies(*s)).collect();
    let mean_spread = if spreads.is_empty() {
        0.0
    } else {
        spreads.iter().sum::<f64>() / spreads.len() as f64
    };
    let mut tolerance: Vec<f64> = scale
        .iter()
        .zip(&spread)
        .map(|(scale, spread)| match varies(*spread) {
            true => 0.0,
            false => TOLERANCE_FRACTION * mean_spread * scale,
        })
        .collect();
    for vector in vectors {
        let (Some(scales), Some(slots)) =
            (scale.get(vector.clone()), tolerance.get_mut(vector.clone()))
        else {
            continue;
        };
        let largest = scales.iter().copied().fold(0.0, f64::max);
        slots.fill(TOLERANCE_FRACTION * mean_spread * largest);
    }
    tolerance
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_constant_input_gets_a_fraction_of_the_others_normalised_spread() {
        // δ on [0, 60 µm] (σ 17 µm), δ̇ on ±1.4 m/s (σ 0.8 m/s), δ̇0 constant (σ 1).
        let min = [0.0, -1.4, 1.4];
        let max = [60e-6, 1.4, 1.4 + 7e-13];
        let scale = [17e-6, 0.8, 1.0];
        let spread = (60.0 / 17.0 + 2.8 / 0.8) / 2.0;
        let tolerance = envelope_tolerance(&min, &max, &scale, &[]);
        assert!(
            (tolerance[2] - 0.01 * spread).abs() < 1e-12,
            "{tolerance:?}"
        );
        // The varying inputs keep their training range.
        assert_eq!(&tolerance[..2], &[0.0, 0.0]);
        // Nothing varies: no tolerance at all.
        assert_eq!(envelope_tolerance(&[1.0], &[1.0], &[1.0], &[]), vec![0.0]);
        // Inputs 1..3 as one vector: both get ρ·S·(largest scale of the two); input 0
        // keeps its rule.
        let vectors = [std::ops::Range { start: 1, end: 3 }];
        let tolerance = envelope_tolerance(&min, &max, &scale, &vectors);
        assert_eq!(tolerance[0], 0.0);
        assert!(
            (tolerance[1] - 0.01 * spread * 1.0).abs() < 1e-12,
            "{tolerance:?}"
        );
        assert_eq!(tolerance[1], tolerance[2]);
    }
}
