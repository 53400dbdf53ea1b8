//! The residual network: a fully connected multilayer perceptron in f64.
//!
//! Layout (the one the core's blob carries): `hidden_layers` hidden layers of equal
//! `width` with activation σ (tanh or relu), then a linear output layer. Layer l maps
//! a⁽ˡ⁾ = σ(W⁽ˡ⁾·a⁽ˡ⁻¹⁾ + b⁽ˡ⁾) with W⁽ˡ⁾ row-major outin; the network reads the
//! normalised input x̂ = (x − mean)/scale and returns y = ŷ·scale + mean.
//!
//! Training works on a flat parameter vector ([`Layout`]) holding, layer by layer from
//! input to output, the weights outin then the biases out — the export order, so
//! [`Layout::layers`] only cuts it up.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;

/// Activation of the hidden layers (the output layer is linear): the core's, so the
/// trained network and the exported one cannot disagree on it.
pub use hcm_core::residual::Activation;

/// A trained network with its normalisation and training envelope, ready to export.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Network {
    /// Number of inputs (3 for the 1D residual: δ, δ̇, δ̇0).
    pub inputs: usize,
    /// Neurons per hidden layer.
    pub width: usize,
    /// Number of outputs (1 for the 1D residual: the normal-force error, N).
    pub outputs: usize,
    /// Number of hidden layers (1–3).
    pub hidden_layers: usize,
    /// Activation of the hidden layers.
    pub activation: Activation,
    /// (weights row-major outin, biases out) per layer, input → output;
    /// `hidden_layers + 1` layers.
    pub layers: Vec<(Vec<f64>, Vec<f64>)>,
    /// Input normalisation x̂ = (x − input_mean)/input_scale (raw input units).
    pub input_mean: Vec<f64>,
    /// See `input_mean` (raw input units, > 0).
    pub input_scale: Vec<f64>,
    /// Output y = ŷ·output_scale + output_mean (raw output units).
    pub output_mean: Vec<f64>,
    /// See `output_mean` (raw output units, > 0).
    pub output_scale: Vec<f64>,
    /// Smallest value of each input in the training data (raw units).
    pub envelope_min: Vec<f64>,
    /// Largest value of each input in the training data (raw units).
    pub envelope_max: Vec<f64>,
    /// How far beyond [min, max] each input still counts as inside (raw units, ≥ 0;
    /// rule: [`envelope_tolerance`](super::envelope_tolerance)). Empty in files written
    /// before it existed: no tolerance.
    #[serde(default)]
    pub envelope_tolerance: Vec<f64>,
}

impl Network {
    /// The network's output for `input` (raw units in and out).
    ///
    /// # Panics
    /// If `input.len() != self.inputs`.
    pub fn evaluate(&self, input: &[f64]) -> Vec<f64> {
        assert_eq!(input.len(), self.inputs, "network input length");
        let mut a: Vec<f64> = input
            .iter()
            .zip(self.input_mean.iter().zip(&self.input_scale))
            .map(|(x, (mean, scale))| (x - mean) / scale)
            .collect();
        let last = self.layers.len() - 1;
        for (l, (weights, biases)) in self.layers.iter().enumerate() {
            let activation = (l < last).then_some(self.activation);
            a = affine(weights, biases, &a, activation);
        }
        a.iter()
            .zip(self.output_mean.iter().zip(&self.output_scale))
            .map(|(y, (mean, scale))| y * scale + mean)
            .collect()
    }

    /// Whether every component of `input` lies within the training data's
    /// [min, max] widened by its tolerance (false for a wrong length or NaN): outside
    /// it the network extrapolates.
    pub fn inside_envelope(&self, input: &[f64]) -> bool {
        let tolerance = |i: usize| self.envelope_tolerance.get(i).copied().unwrap_or(0.0);
        input.len() == self.inputs
            && input
                .iter()
                .zip(self.envelope_min.iter().zip(&self.envelope_max))
                .enumerate()
                .all(|(i, (x, (min, max)))| min - tolerance(i) <= *x && *x <= max + tolerance(i))
    }
}

/// σ(W·a + b), or W·a + b without an activation.
fn affine(weights: &[f64], biases: &[f64], a: &[f64], activation: Option<Activation>) -> Vec<f64> {
    biases
        .iter()
        .zip(weights.chunks_exact(a.len()))
        .map(|(b, row)| {
            let z = b + dot(row, a);
            activation.map_or(z, |s| s.apply(z))
        })
        .collect()
}

#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The shape behind a flat parameter vector, and forward and backward passes on it
/// (in normalised units).
#[derive(Clone, Debug)]
pub struct Layout {
    /// Neurons per layer, input first: [inputs, width, …, width, outputs].
    pub(crate) sizes: Vec<usize>,
    /// Activation of the hidden layers.
    pub(crate) activation: Activation,
    /// (offset of the weights in the flat vector, inputs, outputs) of each layer.
    shapes: Vec<(usize, usize, usize)>,
}

/// Per-sample work space of [`Layout::forward`] and `Layout::accumulate_gradient`.
#[derive(Clone, Debug)]
pub struct Scratch {
    /// Each layer's output a⁽¹⁾, a⁽²⁾, …; the last is the network output ŷ. The input
    /// a⁽⁰⁾ = x̂ is read where it is, not copied here: the backward pass takes it as an
    /// argument.
    activations: Vec<Vec<f64>>,
    delta: Vec<f64>,
    delta_previous: Vec<f64>,
}

impl Scratch {
    /// Sets ∂L/∂ŷ for [`Layout::backpropagate`].
    pub(crate) fn set_output_gradient(&mut self, gradient: impl Iterator<Item = f64>) {
        self.delta.clear();
        self.delta.extend(gradient);
    }

    /// The output ŷ of the last forward pass.
    pub fn output(&self) -> &[f64] {
        self.activations.last().map_or(&[], Vec::as_slice)
    }
}

impl Layout {
    /// `hidden_layers` layers of `width` between `inputs` and `outputs`.
    pub fn new(
        inputs: usize,
        width: usize,
        hidden_layers: usize,
        outputs: usize,
        activation: Activation,
    ) -> Self {
        let mut sizes = vec![inputs];
        sizes.extend(std::iter::repeat_n(width, hidden_layers));
        sizes.push(outputs);
        let mut offset = 0;
        let shapes = sizes
            .windows(2)
            .map(|pair| {
                let start = offset;
                offset += pair[0] * pair[1] + pair[1];
                (start, pair[0], pair[1])
            })
            .collect();
        Self {
            sizes,
            activation,
            shapes,
        }
    }

    /// (offset of the weights in the flat vector, inputs, outputs) of each layer.
    fn shapes(&self) -> std::iter::Copied<std::slice::Iter<'_, (usize, usize, usize)>> {
        self.shapes.iter().copied()
    }

    /// Length of the flat parameter vector.
    pub fn parameter_count(&self) -> usize {
        self.shapes().map(|(_, i, o)| i * o + o).sum()
    }

    /// Random weights, zero biases: Glorot & Bengio (2010) uniform U(±√(6/(in+out)))
    /// for tanh, He et al. (2015) uniform U(±√(6/in)) for relu (keeping the variance
    /// of the activations from layer to layer). The linear output layer follows Glorot.
    pub(crate) fn initial_parameters(&self, rng: &mut ChaCha8Rng) -> Vec<f64> {
        let mut parameters = vec![0.0; self.parameter_count()];
        let hidden = self.sizes.len() - 2;
        for (l, (offset, n_in, n_out)) in self.shapes().enumerate() {
            let limit = match self.activation {
                Activation::Relu if l < hidden => (6.0 / n_in as f64).sqrt(),
                _ => (6.0 / (n_in + n_out) as f64).sqrt(),
            };
            for w in &mut parameters[offset..offset + n_in * n_out] {
                *w = limit * (2.0 * rng.random::<f64>() - 1.0);
            }
        }
        parameters
    }

    /// The flat vector of per-layer (weights, biases), the inverse of [`Layout::layers`].
    pub fn flatten(&self, layers: &[(Vec<f64>, Vec<f64>)]) -> Vec<f64> {
        layers
            .iter()
            .flat_map(|(weights, biases)| weights.iter().chain(biases))
            .copied()
            .collect()
    }

    /// Cuts the flat vector into (weights, biases) per layer.
    pub fn layers(&self, parameters: &[f64]) -> Vec<(Vec<f64>, Vec<f64>)> {
        self.shapes()
            .map(|(offset, n_in, n_out)| {
                let split = offset + n_in * n_out;
                (
                    parameters[offset..split].to_vec(),
                    parameters[split..split + n_out].to_vec(),
                )
            })
            .collect()
    }

    /// Empty work space for this layout.
    pub fn scratch(&self) -> Scratch {
        Scratch {
            activations: self.sizes[1..].iter().map(|&n| vec![0.0; n]).collect(),
            delta: Vec::with_capacity(self.sizes.iter().copied().max().unwrap_or(0)),
            delta_previous: Vec::new(),
        }
    }

    /// ŷ for the normalised input `x`; the output stays in `scratch` for a backward pass.
    /// Panics if `x` is not one input wide (a caller's bug, not a data error).
    pub fn forward<'a>(
        &self,
        parameters: &[f64],
        x: &[f64],
        scratch: &'a mut Scratch,
    ) -> &'a [f64] {
        assert_eq!(x.len(), self.sizes[0], "network input length");
        let last = self.sizes.len() - 2;
        for (l, (offset, n_in, n_out)) in self.shapes().enumerate() {
            let (before, after) = scratch.activations.split_at_mut(l);
            let a = if l == 0 { x } else { &before[l - 1] };
            let out = &mut after[0];
            let weights = &parameters[offset..offset + n_in * n_out];
            let biases = &parameters[offset + n_in * n_out..offset + n_in * n_out + n_out];
            for ((z, b), row) in out.iter_mut().zip(biases).zip(weights.chunks_exact(n_in)) {
                let sum = b + dot(row, a);
                *z = if l < last {
                    self.activation.apply(sum)
                } else {
                    sum
                };
            }
        }
        scratch.output()
    }

    /// Adds ∂/∂θ Σ_o (ŷ_o − t_o)² for one sample (x, t) to `gradient` (backpropagation:
    /// δ at the output is 2(ŷ − t); each layer adds δ·aᵀ to its weights' gradient and δ
    /// to its biases', and passes (Wᵀ·δ)⊙σ'(a) down). The output ŷ stays in `scratch`.
    pub(crate) fn accumulate_gradient(
        &self,
        parameters: &[f64],
        x: &[f64],
        target: &[f64],
        scratch: &mut Scratch,
        gradient: &mut [f64],
    ) {
        self.forward(parameters, x, scratch);
        let output = &scratch.activations[scratch.activations.len() - 1];
        let mut delta = std::mem::take(&mut scratch.delta);
        delta.clear();
        delta.extend(output.iter().zip(target).map(|(y, t)| 2.0 * (y - t)));
        scratch.delta = delta;
        self.backpropagate(parameters, x, scratch, gradient);
    }

    /// Adds ∂L/∂θ to `gradient` for the sample `x` of the last [`Layout::forward`] into
    /// `scratch`, given ∂L/∂ŷ in `scratch`'s output gradient (set by
    /// [`Scratch::set_output_gradient`]).
    pub(crate) fn backpropagate(
        &self,
        parameters: &[f64],
        x: &[f64],
        scratch: &mut Scratch,
        gradient: &mut [f64],
    ) {
        let Scratch {
            activations,
            delta,
            delta_previous,
        } = scratch;
        for (l, (offset, n_in, n_out)) in self.shapes().enumerate().rev() {
            let a = if l == 0 { x } else { &activations[l - 1] };
            let split = offset + n_in * n_out;
            let (weight_gradient, bias_gradient) =
                gradient[offset..split + n_out].split_at_mut(n_in * n_out);
            for ((d, gb), row) in delta
                .iter()
                .zip(bias_gradient)
                .zip(weight_gradient.chunks_exact_mut(n_in))
            {
                *gb += d;
                for (g, x) in row.iter_mut().zip(a) {
                    *g += d * x;
                }
            }
            if l == 0 {
                break;
            }
            delta_previous.clear();
            delta_previous.resize(n_in, 0.0);
            for (d, row) in delta
                .iter()
                .zip(parameters[offset..split].chunks_exact(n_in))
            {
                for (p, w) in delta_previous.iter_mut().zip(row) {
                    *p += w * d;
                }
            }
            for (p, a) in delta_previous.iter_mut().zip(a) {
                *p *= self.activation.slope(*a);
            }
            std::mem::swap(delta, delta_previous);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    /// Σ over samples and outputs of (ŷ − t)².
    fn loss(layout: &Layout, parameters: &[f64], samples: &[(Vec<f64>, Vec<f64>)]) -> f64 {
        let mut scratch = layout.scratch();
        samples
            .iter()
            .map(|(x, t)| {
                let y = layout.forward(parameters, x, &mut scratch);
                y.iter().zip(t).map(|(y, t)| (y - t).powi(2)).sum::<f64>()
            })
            .sum()
    }

    /// ‖analytic − central difference‖ / (‖analytic‖ + ‖central difference‖).
    fn gradient_check(activation: Activation) -> f64 {
        let layout = Layout::new(3, 5, 2, 2, activation);
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut parameters = layout.initial_parameters(&mut rng);
        for p in &mut parameters {
            *p += 0.1 * (2.0 * rng.random::<f64>() - 1.0); // non-zero biases too
        }
        let samples: Vec<(Vec<f64>, Vec<f64>)> = (0..4)
            .map(|_| {
                let x = (0..3).map(|_| 2.0 * rng.random::<f64>() - 1.0).collect();
                let t = (0..2).map(|_| rng.random::<f64>()).collect();
                (x, t)
            })
            .collect();
        let mut analytic = vec![0.0; parameters.len()];
        let mut scratch = layout.scratch();
        for (x, t) in &samples {
            layout.accumulate_gradient(&parameters, x, t, &mut scratch, &mut analytic);
        }
        let h = 1e-6;
        let numeric: Vec<f64> = (0..parameters.len())
            .map(|i| {
                let mut plus = parameters.clone();
                let mut minus = parameters.clone();
                plus[i] += h;
                minus[i] -= h;
                (loss(&layout, &plus, &samples) - loss(&layout, &minus, &samples)) / (2.0 * h)
            })
            .collect();
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let difference: Vec<f64> = analytic.iter().zip(&numeric).map(|(a, n)| a - n).collect();
        norm(&difference) / (norm(&analytic) + norm(&numeric))
    }

    #[test]
    fn backpropagation_matches_central_differences_for_tanh() {
        let error = gradient_check(Activation::Tanh);
        println!("tanh: relative gradient error {error:.1e}");
        // Back-propagation uses tanh's own slope 1 − a², the forward pass the rational
        // approximation, whose slope differs by up to 1.3e-5 (hcm_core tanh.rs): measured
        // 1.4e-6 here (ReLU, exact, stays under 1e-6). A wrong gradient is off by ≫ 1e-3.
        assert!(error < 3e-6, "relative gradient error {error:e}");
    }

    #[test]
    fn backpropagation_matches_central_differences_for_relu() {
        let error = gradient_check(Activation::Relu);
        println!("relu: relative gradient error {error:.1e}");
        assert!(error < 1e-6, "relative gradient error {error:e}");
    }

    #[test]
    fn network_evaluate_matches_the_flat_forward_pass_with_normalisation() {
        let layout = Layout::new(2, 4, 3, 1, Activation::Tanh);
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let parameters = layout.initial_parameters(&mut rng);
        let network = Network {
            inputs: 2,
            width: 4,
            outputs: 1,
            hidden_layers: 3,
            activation: Activation::Tanh,
            layers: layout.layers(&parameters),
            input_mean: vec![1.0, -2.0],
            input_scale: vec![0.5, 4.0],
            output_mean: vec![10.0],
            output_scale: vec![3.0],
            envelope_min: vec![0.0, -5.0],
            envelope_max: vec![2.0, 1.0],
            envelope_tolerance: vec![0.1, 0.0],
        };
        let x = [1.5, 0.0];
        let mut scratch = layout.scratch();
        let y_hat = layout.forward(&parameters, &[(1.5 - 1.0) / 0.5, 2.0 / 4.0], &mut scratch)[0];
        assert_eq!(network.evaluate(&x), vec![y_hat * 3.0 + 10.0]);
        assert!(network.inside_envelope(&x));
        assert!(!network.inside_envelope(&[2.5, 0.0]));
        // Within the tolerance of 0.1 beyond δ's maximum 2, not beyond it.
        assert!(network.inside_envelope(&[2.09, 0.0]));
        assert!(!network.inside_envelope(&[2.11, 0.0]));
        assert!(!network.inside_envelope(&[f64::NAN, 0.0]));
        assert!(!network.inside_envelope(&[1.0]));
    }
}
