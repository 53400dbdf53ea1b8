//! The residual's training pairs: what PM2 misses at each measured contact sample.

use crate::dataset::ForceSample;
use hcm_core::model::ContactModel;

/// Residual training pairs of the 1D normal contact: inputs [δ (m), δ̇ (m/s), δ̇0 (m/s)],
/// target [f_measured − f_physics (N)] (the contact model's law and effects, its own
/// residual left out), one row per sample, in the samples' order.
pub fn residual_pairs<R>(
    samples: &[ForceSample],
    physics: &ContactModel<f64, R>,
) -> (Vec<Vec<f64>>, Vec<Vec<f64>>) {
    samples
        .iter()
        .map(|s| {
            let (state, memory) = s.state();
            let error = s.force - physics.physics_normal_force(&state, &memory);
            (vec![s.depth, s.rate, s.approach_speed], vec![error])
        })
        .unzip()
}

#[cfg(test)]
mod tests {
    use super::*;
    use hcm_core::law::{AnyNormalLaw, Hertz};

    #[test]
    fn target_is_measured_minus_law_force() {
        let law: AnyNormalLaw<f64> = Hertz {
            stiffness: 1e9,
            exponent: 1.5,
        }
        .into();
        let sample = ForceSample {
            depth: 1e-5,
            rate: 0.5,
            approach_speed: 1.0,
            max_depth: 1e-5,
            force: 40.0,
        };
        let (inputs, targets) = residual_pairs(&[sample], &ContactModel::physics(law));
        assert_eq!(inputs, vec![vec![1e-5, 0.5, 1.0]]);
        let hertz = 1e9 * 1e-5_f64.powf(1.5);
        assert!((targets[0][0] - (40.0 - hertz)).abs() < 1e-9);
    }
}
