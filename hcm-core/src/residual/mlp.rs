//! The residual network: a fixed-size multilayer perceptron evaluated in `f32`.
//!
//! For an input x (raw units) the network computes
//!
//! ```text
//! x̂   = (x − μ_x) / σ_x                       input normalisation
//! h_1 = a(W_1·x̂ + b_1)                         input → first hidden layer
//! h_k = a(W_k·h_(k−1) + b_k),  k = 2..HIDDEN   hidden → hidden
//! ŷ   = W_o·h_HIDDEN + b_o                      linear output
//! y   = ŷ·σ_y + μ_y                            output de-normalisation
//! ```
//!
//! with a = tanh or ReLU ([`Activation`]). Every size is a const generic, so the
//! network lives in a `static` or on the stack with no allocator; the number of hidden
//! layers (1 to 3) picks, through [`HiddenDepth`], an array of exactly HIDDEN − 1
//! width × width layers, so no storage is wasted on unused layers.
//!
//! The hidden → hidden layers' weights (WIDTH × WIDTH each, the bulk of a network) are
//! stored in the blob as `f32` ([`F32Weights`]) or as `i8` with one `f32` scale per
//! output row ([`Int8Weights`], a quarter of the blob). The `f32` ones run in `f32`
//! with the network's activation; the int8 ones run in integers on 16-bit
//! activations with the quantised tanh ([`Int8Layer`], [`super::qtanh`]). The
//! input layer (INPUTS weights per row) and the linear output layer are always `f32`:
//! a per-row scale over only a few input weights rounds the small ones by up to
//! 100 %, and the output layer's rounding reaches the output undamped. Measured on the
//! flat shot's residual (3-16-16-1), RMS of the int8 network against the f32 one after
//! quantisation-aware fine-tuning: 0.26 N with every layer int8 but the output, 0.043 N
//! with this split; the f32 layers cost 4·(3·16 + 16) = 256 bytes more than int8 ones.
//! With one hidden layer there is no hidden → hidden layer, and an int8 network holds
//! no int8 weights.

pub use super::envelope::{Envelope, Excursion};
pub use super::int8::Int8Layer;
pub use super::layer::{F32Weights, Int8Weights, Layer, WeightFormat};

use super::Activation;
use crate::Real;
use core::fmt::Debug;

/// A hidden-layer count, as a type: `Hidden<1>`, `Hidden<2>`, `Hidden<3>` implement
/// [`HiddenDepth`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Hidden<const HIDDEN: usize>;

/// The storage of the HIDDEN − 1 width → width layers between the first hidden layer
/// and the output layer.
///
/// Stable Rust cannot write `[Layer; HIDDEN - 1]`, so this trait names the array for
/// each supported depth; a network with 0 or more than 3 hidden layers does not compile.
pub trait HiddenDepth<const WIDTH: usize, Q: WeightFormat> {
    /// `[Q::Square<WIDTH>; HIDDEN - 1]`.
    type Layers: Copy + Debug + PartialEq + AsRef<[Q::Square<WIDTH>]> + AsMut<[Q::Square<WIDTH>]>;

    /// The layers with every weight and bias zero.
    fn zeroed() -> Self::Layers;
}

macro_rules! hidden_depth {
    ($($hidden:literal => $between:literal),*) => {$(
        impl<const WIDTH: usize, Q: WeightFormat> HiddenDepth<WIDTH, Q> for Hidden<$hidden> {
            type Layers = [Q::Square<WIDTH>; $between];

            fn zeroed() -> Self::Layers {
                core::array::from_fn(|_| Q::zeroed_square())
            }
        }
    )*};
}
hidden_depth!(1 => 0, 2 => 1, 3 => 2);

/// The affine maps between raw units and the network's normalised values.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Normalisation<const INPUTS: usize, const OUTPUTS: usize> {
    /// Mean μ_x of each input over the training data (the input's unit).
    pub input_mean: [f32; INPUTS],
    /// Scale σ_x of each input (the input's unit), finite and > 0.
    pub input_scale: [f32; INPUTS],
    /// Mean μ_y of each output (the output's unit, N for a force correction).
    pub output_mean: [f32; OUTPUTS],
    /// Scale σ_y of each output (the output's unit), finite and > 0.
    pub output_scale: [f32; OUTPUTS],
}

impl<const INPUTS: usize, const OUTPUTS: usize> Normalisation<INPUTS, OUTPUTS> {
    /// Means 0 and scales 1: the network sees raw values.
    pub const fn identity() -> Self {
        Normalisation {
            input_mean: [0.0; INPUTS],
            input_scale: [1.0; INPUTS],
            output_mean: [0.0; OUTPUTS],
            output_scale: [1.0; OUTPUTS],
        }
    }
}

/// A multilayer perceptron with `INPUTS` inputs, `HIDDEN` hidden layers of `WIDTH`
/// neurons, and `OUTPUTS` linear outputs, weights stored as `Q`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mlp<
    const INPUTS: usize,
    const WIDTH: usize,
    const OUTPUTS: usize,
    const HIDDEN: usize,
    Q: WeightFormat = F32Weights,
> where
    Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    /// Nonlinearity after every hidden layer.
    pub activation: Activation,
    /// Input normalisation and output de-normalisation.
    pub normalisation: Normalisation<INPUTS, OUTPUTS>,
    /// Training envelope, raw units.
    pub envelope: Envelope<INPUTS>,
    /// Normalised input → first hidden layer; always f32 (see the module docs).
    pub input_layer: Layer<INPUTS, WIDTH>,
    /// Hidden → hidden, HIDDEN − 1 of them, in order.
    pub hidden_layers: <Hidden<HIDDEN> as HiddenDepth<WIDTH, Q>>::Layers,
    /// Last hidden layer → normalised output; always f32 (see the module docs).
    pub output_layer: Layer<WIDTH, OUTPUTS>,
}

impl<const INPUTS: usize, const WIDTH: usize, const OUTPUTS: usize, const HIDDEN: usize, Q>
    Mlp<INPUTS, WIDTH, OUTPUTS, HIDDEN, Q>
where
    Q: WeightFormat,
    Hidden<HIDDEN>: HiddenDepth<WIDTH, Q>,
{
    /// A network whose weights and biases are all zero (it outputs μ_y), with identity
    /// normalisation and an unbounded envelope; fill its fields to build one by hand.
    pub fn zeroed(activation: Activation) -> Self {
        Mlp {
            activation,
            normalisation: Normalisation::identity(),
            envelope: Envelope::unbounded(),
            input_layer: Layer::zeroed(),
            hidden_layers: <Hidden<HIDDEN> as HiddenDepth<WIDTH, Q>>::zeroed(),
            output_layer: Layer::zeroed(),
        }
    }

    /// The network's outputs for `input` (raw units in, raw units out).
    ///
    /// NaN in any input gives NaN outputs; outputs saturate at ±`f32::MAX`. The
    /// envelope is not consulted: see [`Mlp::inside_envelope`].
    pub fn evaluate(&self, input: &[f32; INPUTS]) -> [f32; OUTPUTS] {
        self.evaluate_normalised(&self.normalise(input))
    }

    /// x̂ = (x − μ_x)/σ_x, computed in the input's own type `T` and then rounded to
    /// `f32`: a host passing `f64` inputs keeps their precision through the
    /// normalisation (an input whose spread is small beside its value — a unit
    /// quaternion's w near 1 — would otherwise lose it to the rounding of the raw
    /// value). In `f32` it is exactly [`Mlp::evaluate`]'s first step.
    #[inline(never)]
    pub fn normalise<T: Real>(&self, input: &[T; INPUTS]) -> [f32; INPUTS] {
        let scaling = &self.normalisation;
        let mut x = [0.0_f32; INPUTS];
        for ((x, value), (mean, scale)) in x
            .iter_mut()
            .zip(input)
            .zip(scaling.input_mean.iter().zip(&scaling.input_scale))
        {
            *x = ((*value - T::of_f32(*mean)) / T::of_f32(*scale)).to_f32();
        }
        x
    }

    /// The network's outputs (raw units) for already normalised inputs x̂
    /// ([`Mlp::normalise`]); NaN in any gives NaN outputs.
    pub fn evaluate_normalised(&self, x: &[f32; INPUTS]) -> [f32; OUTPUTS] {
        // Said here, not left to the arithmetic: the tanh activation turns NaN into 0.
        if x.iter().any(|x| x.is_nan()) {
            return [f32::NAN; OUTPUTS];
        }
        let scaling = &self.normalisation;
        let hidden = Q::hidden_pass(
            self.activation,
            &self.input_layer,
            self.hidden_layers.as_ref(),
            x,
        );
        let mut output = self.output_layer.forward(&hidden);
        for (y, (mean, scale)) in output
            .iter_mut()
            .zip(scaling.output_mean.iter().zip(&scaling.output_scale))
        {
            *y = (*y * scale + mean).saturate();
        }
        output
    }

    /// True if every input lies inside the training envelope, its tolerance included
    /// (NaN is outside).
    pub fn inside_envelope(&self, input: &[f32; INPUTS]) -> bool {
        self.envelope.contains(input)
    }

    /// Which input left the training envelope and by how much, or `None` inside it.
    pub fn excursion(&self, input: &[f32; INPUTS]) -> Option<Excursion> {
        self.envelope.excursion(input)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// 2 inputs, 3 tanh/relu neurons, 1 output, with weights small enough to compute
    /// by hand. Normalisation: x̂ = (x − [1, −1]) / [2, 4]; y = ŷ·10 + 5.
    pub(crate) fn hand_built(activation: Activation) -> Mlp<2, 3, 1, 1> {
        let mut mlp = Mlp::zeroed(activation);
        mlp.normalisation = Normalisation {
            input_mean: [1.0, -1.0],
            input_scale: [2.0, 4.0],
            output_mean: [5.0],
            output_scale: [10.0],
        };
        mlp.envelope = Envelope {
            min: [-3.0, -5.0],
            max: [5.0, 3.0],
            tolerance: [0.0; 2],
        };
        mlp.input_layer =
            Layer::from_rows([[0.5, -1.0], [1.0, 1.0], [-2.0, 0.25]], [0.1, -0.2, 0.0]);
        mlp.output_layer = Layer::from_rows([[1.0, -0.5, 2.0]], [0.3]);
        mlp
    }

    /// The same network by hand in f64: x = [3, 1] → x̂ = [1, 0.5];
    /// z = [0.5 − 0.5 + 0.1, 1 + 0.5 − 0.2, −2 + 0.125] = [0.1, 1.3, −1.875].
    fn by_hand(activation: Activation) -> f64 {
        let z: [f64; 3] = [0.1, 1.3, -1.875];
        let h = z.map(|z| match activation {
            Activation::Tanh => z.tanh(),
            Activation::Relu => z.max(0.0),
            Activation::QuantisedTanh => Activation::QuantisedTanh.apply(z),
        });
        let y_hat = h[0] - 0.5 * h[1] + 2.0 * h[2] + 0.3;
        y_hat * 10.0 + 5.0
    }

    #[test]
    fn hand_built_tanh_network_gives_the_hand_computed_output() {
        let [y] = hand_built(Activation::Tanh).evaluate(&[3.0, 1.0]);
        let expected = by_hand(Activation::Tanh);
        // tanh: 0.09967 − 0.43086 − 1.90809 + 0.3 = −1.93928 → −14.3928
        assert!((expected - -14.3928).abs() < 1e-4, "{expected}");
        assert!((f64::from(y) - expected).abs() < 1e-5, "{y} vs {expected}");
    }

    #[test]
    fn hand_built_relu_network_gives_the_hand_computed_output() {
        let [y] = hand_built(Activation::Relu).evaluate(&[3.0, 1.0]);
        // relu: h = [0.1, 1.3, 0]; ŷ = 0.1 − 0.65 + 0 + 0.3 = −0.25; y = 2.5
        assert!((by_hand(Activation::Relu) - 2.5).abs() < 1e-12);
        assert!((y - 2.5).abs() < 1e-6, "{y}");
    }

    #[test]
    fn int8_weights_are_scaled_per_row() {
        // A 2-3-3-1 network: only its hidden → hidden layer is int8.
        // Both with the quantised tanh, the one activation int8 runs.
        let base = hand_built(Activation::QuantisedTanh);
        let mut float: Mlp<2, 3, 1, 2> = Mlp::zeroed(Activation::QuantisedTanh);
        let mut int8: Mlp<2, 3, 1, 2, Int8Weights> = Mlp::zeroed(Activation::QuantisedTanh);
        float.normalisation = base.normalisation;
        int8.normalisation = base.normalisation;
        float.input_layer = base.input_layer;
        int8.input_layer = base.input_layer;
        float.output_layer = base.output_layer;
        int8.output_layer = base.output_layer;
        // Every hidden weight is a multiple of its row's scale: exact in int8.
        let bias = [0.1, -0.2, 0.05];
        float.hidden_layers[0] = Layer::from_rows(
            [[0.5, -1.0, 0.25], [1.0, 1.0, -3.0], [-2.0, 0.25, 0.75]],
            bias,
        );
        int8.hidden_layers[0] = Int8Layer::from_levels(
            [[2, -4, 1], [1, 1, -3], [-8, 1, 3]],
            [0.25, 1.0, 0.25],
            bias,
        );
        // The int8 network carries its activations in Q15 (a rounding of at most
        // 2⁻¹⁶ each), which reaches the output through weights of a few units and the
        // output scale 10: within 1e-3 here.
        for x in [[3.0, 1.0], [-1.0, 0.5], [0.0, 0.0]] {
            let ([y8], [y32]) = (int8.evaluate(&x), float.evaluate(&x));
            assert!((y8 - y32).abs() < 1e-3, "{y8} vs {y32} at {x:?}");
        }
        // And a wrong level is seen: the int8 storage is really used (row 1, column 2).
        int8.hidden_layers[0].set_level(1, 2, -2);
        let ([y8], [y32]) = (int8.evaluate(&[3.0, 1.0]), float.evaluate(&[3.0, 1.0]));
        assert!((y8 - y32).abs() > 1e-2, "{y8} vs {y32}");
    }

    #[test]
    fn nan_input_gives_nan_output_for_both_activations() {
        for activation in [Activation::Tanh, Activation::Relu] {
            let mlp = hand_built(activation);
            assert!(mlp.evaluate(&[f32::NAN, 0.0])[0].is_nan(), "{activation:?}");
            assert!(mlp.evaluate(&[0.0, f32::NAN])[0].is_nan(), "{activation:?}");
            assert!(!mlp.inside_envelope(&[f32::NAN, 0.0]));
        }
    }

    #[test]
    fn infinite_input_saturates_instead_of_overflowing() {
        let mlp = hand_built(Activation::Relu);
        let [y] = mlp.evaluate(&[f32::INFINITY, 1.0]);
        // Relu passes +∞ through, and +∞ − ∞ = NaN in the next row: either way no panic
        // and no infinity.
        assert!(y.is_nan() || y.is_finite(), "{y}");
    }

    #[test]
    fn envelope_is_closed_and_checks_every_input() {
        let mlp = hand_built(Activation::Tanh);
        assert!(mlp.inside_envelope(&[3.0, 1.0]));
        assert!(mlp.inside_envelope(&[-3.0, 3.0])); // both on the boundary
        assert!(!mlp.inside_envelope(&[5.001, 0.0]));
        assert!(!mlp.inside_envelope(&[0.0, -5.001]));
        assert!(!mlp.inside_envelope(&[f32::INFINITY, 0.0]));
    }

    #[test]
    fn deeper_networks_apply_every_hidden_layer() {
        // Width 1, relu, every weight 2, 3 hidden layers: four layers in all, so
        // y = 2⁴·x for x > 0 and 0 for x < 0.
        let mut mlp: Mlp<1, 1, 1, 3> = Mlp::zeroed(Activation::Relu);
        mlp.input_layer.weights = [[2.0]];
        for layer in mlp.hidden_layers.as_mut() {
            layer.weights = [[2.0]];
        }
        mlp.output_layer.weights = [[2.0]];
        assert_eq!(mlp.hidden_layers.len(), 2);
        assert_eq!(mlp.evaluate(&[1.5]), [24.0]);
        assert_eq!(mlp.evaluate(&[-1.5]), [0.0]);
    }
}
