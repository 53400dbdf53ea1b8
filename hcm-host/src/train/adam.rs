//! Adam, the first-order optimiser of Kingma & Ba, "Adam: A Method for Stochastic
//! Optimization", ICLR 2015, Algorithm 1.
//!
//! Per parameter θ with gradient g at step t (t = 1, 2, …):
//!
//! - m ← β1·m + (1 − β1)·g,  v ← β2·v + (1 − β2)·g²  (biased moment estimates),
//! - m̂ = m / (1 − β1ᵗ),  v̂ = v / (1 − β2ᵗ)  (bias correction),
//! - θ ← θ − α·m̂ / (√v̂ + ε).
//!
//! The paper's defaults β1 = 0.9, β2 = 0.999, ε = 1e-8 are used; only the step size α
//! is a setting.

/// Adam's state for one flat parameter vector.
#[derive(Clone, Debug)]
pub struct Adam {
    /// Step size α (units of the parameters).
    pub(crate) learning_rate: f64,
    /// Decay of the first-moment estimate β1.
    pub(crate) beta1: f64,
    /// Decay of the second-moment estimate β2.
    pub(crate) beta2: f64,
    /// ε, keeping the step finite where v̂ ≈ 0.
    pub(crate) epsilon: f64,
    first_moment: Vec<f64>,
    second_moment: Vec<f64>,
    // β1ᵗ and β2ᵗ, kept as running products rather than powers of a step count.
    beta1_power: f64,
    beta2_power: f64,
}

impl Adam {
    /// Fresh state (m = v = 0, t = 0) for `parameters` parameters.
    pub fn new(parameters: usize, learning_rate: f64) -> Self {
        Self {
            learning_rate,
            beta1: 0.9,
            beta2: 0.999,
            epsilon: 1e-8,
            first_moment: vec![0.0; parameters],
            second_moment: vec![0.0; parameters],
            beta1_power: 1.0,
            beta2_power: 1.0,
        }
    }

    /// One step of Algorithm 1: moves `parameters` against `gradient` (same length).
    pub fn step(&mut self, parameters: &mut [f64], gradient: &[f64]) {
        assert_eq!(parameters.len(), self.first_moment.len());
        assert_eq!(gradient.len(), self.first_moment.len());
        self.beta1_power *= self.beta1;
        self.beta2_power *= self.beta2;
        let first_correction = 1.0 - self.beta1_power;
        let second_correction = 1.0 - self.beta2_power;
        let moments = self.first_moment.iter_mut().zip(&mut self.second_moment);
        for ((theta, &g), (m, v)) in parameters.iter_mut().zip(gradient).zip(moments) {
            *m = self.beta1 * *m + (1.0 - self.beta1) * g;
            *v = self.beta2 * *v + (1.0 - self.beta2) * g * g;
            let m_hat = *m / first_correction;
            let v_hat = *v / second_correction;
            *theta -= self.learning_rate * m_hat / (v_hat.sqrt() + self.epsilon);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_step_moves_each_parameter_by_the_learning_rate_against_the_gradient_sign() {
        // With bias correction, m̂ = g and v̂ = g² at t = 1, so the step is α·sign(g).
        let mut adam = Adam::new(3, 0.01);
        let mut theta = vec![1.0, 1.0, 1.0];
        adam.step(&mut theta, &[2.0, -0.5, 0.0]);
        assert!((theta[0] - 0.99).abs() < 1e-9);
        assert!((theta[1] - 1.01).abs() < 1e-9);
        assert_eq!(theta[2], 1.0);
    }

    #[test]
    fn minimises_a_badly_scaled_quadratic() {
        // f = x² + 1000·y²: Adam's per-parameter scaling copes with the conditioning.
        let mut adam = Adam::new(2, 0.05);
        let mut theta = vec![3.0, -2.0];
        for _ in 0..2000 {
            let gradient = [2.0 * theta[0], 2000.0 * theta[1]];
            adam.step(&mut theta, &gradient);
        }
        assert!(theta[0].abs() < 1e-3 && theta[1].abs() < 1e-3, "{theta:?}");
    }
}
