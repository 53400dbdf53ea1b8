//! Which outputs a trained network actually predicts: its share of each target's
//! variance (R² = 1 − MSE/variance over rows), and silencing the outputs it does not.
//!
//! Why: an output whose training targets hold no signal — the peg's out-of-plane force
//! F_y and torques T_x, T_z, zero by the setup's symmetry, so their targets are the
//! sensor noise alone — is still fitted, to that noise, and a network's small bias
//! there is not harmless: 1e-3 N·m about z spins the peg (I_zz = 1.7e-5 kg·m²) by
//! 0.2 rad/s within one 3 ms wall contact, out of the training envelope, where the
//! residual switches off mid-contact. Measured on the peg's wall contacts
//! (tests/train/peg_hcm.rs, 20 runs): R² 0.001, 0.002, 0.001 for F_y, T_x, T_z against 0.979,
//! 0.939, 0.977 for F_x, F_z, T_y.

use super::Network;

/// Below this share of its target's variance an output counts as unpredicted.
pub const EXPLAINED_MIN: f64 = 0.1;

/// R² of each output of `network` over the rows (inputs, targets); 0 for a target
/// without variance.
pub fn explained_variance(
    network: &Network,
    inputs: &[Vec<f64>],
    targets: &[Vec<f64>],
) -> Vec<f64> {
    let n = targets.len().max(1) as f64;
    let outputs = network.outputs;
    let mut mean = vec![0.0; outputs];
    for t in targets {
        for (m, v) in mean.iter_mut().zip(t) {
            *m += v / n;
        }
    }
    let (mut variance, mut error) = (vec![0.0; outputs], vec![0.0; outputs]);
    for (x, t) in inputs.iter().zip(targets) {
        let y = network.evaluate(x);
        for k in 0..outputs {
            variance[k] += (t[k] - mean[k]).powi(2);
            error[k] += (t[k] - y[k]).powi(2);
        }
    }
    variance
        .iter()
        .zip(&error)
        .map(|(v, e)| if *v > 0.0 { 1.0 - e / v } else { 0.0 })
        .collect()
}

/// `network` with outputs `which` fixed at 0: their output-layer rows, biases and
/// de-normalisation means zeroed, so the exported blob carries the zero too.
pub fn silence_outputs(network: &Network, which: &[usize]) -> Network {
    let mut out = network.clone();
    let inputs = out.width;
    if let Some((weights, biases)) = out.layers.last_mut() {
        for &k in which {
            if let Some(row) = weights.get_mut(k * inputs..(k + 1) * inputs) {
                row.fill(0.0);
            }
            if let Some(b) = biases.get_mut(k) {
                *b = 0.0;
            }
        }
    }
    for &k in which {
        if let Some(m) = out.output_mean.get_mut(k) {
            *m = 0.0;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_silenced_output_is_zero_and_the_others_unchanged() {
        let network = Network {
            inputs: 1,
            width: 2,
            outputs: 2,
            hidden_layers: 1,
            activation: super::super::Activation::Tanh,
            layers: vec![
                (vec![1.0, -1.0], vec![0.0, 0.5]),
                (vec![2.0, 0.5, -1.0, 3.0], vec![0.1, 0.2]),
            ],
            input_mean: vec![0.0],
            input_scale: vec![1.0],
            output_mean: vec![1.0, -2.0],
            output_scale: vec![1.0, 2.0],
            envelope_min: vec![-1.0],
            envelope_max: vec![1.0],
            envelope_tolerance: vec![0.0],
        };
        let silenced = silence_outputs(&network, &[1]);
        for x in [-0.7, 0.0, 0.4] {
            let (a, b) = (network.evaluate(&[x]), silenced.evaluate(&[x]));
            assert_eq!(a[0], b[0]);
            assert_eq!(b[1], 0.0);
            assert_ne!(a[1], 0.0);
        }
        // R²: the network's own outputs as targets are explained fully; a target
        // independent of the input (constant plus alternating noise) not at all.
        let inputs: Vec<Vec<f64>> = (0..50).map(|i| vec![f64::from(i) / 25.0 - 1.0]).collect();
        let targets: Vec<Vec<f64>> = (inputs.iter().enumerate())
            .map(|(i, x)| vec![network.evaluate(x)[0], if i % 2 == 0 { 1.0 } else { -1.0 }])
            .collect();
        let r2 = explained_variance(&silenced, &inputs, &targets);
        assert!((r2[0] - 1.0).abs() < 1e-12, "{r2:?}");
        assert!(r2[1] < 0.05, "{r2:?}");
    }
}
