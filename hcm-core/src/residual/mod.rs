//! The data-driven residual of the hybrid contact model: a small fixed-size network
//! that learns what the physics law gets wrong (paper Section 3.2).
//!
//! The host trains the network and writes it as a weights blob (`hcm export`); the
//! controller embeds the blob with `include_bytes!` and [`decode`]s it into an [`Mlp`]
//! whose shape it fixes at compile time. Nothing here allocates, and nothing panics:
//! a blob that is short, corrupted, of another version or of another shape is a
//! [`BlobError`], and any input (NaN included) gives an output.
//!
//! - [`mlp`]: the network and its input/output normalisation;
//! - [`layer`]: one `f32` layer and the two weight formats;
//! - [`int8`]: the int8 layer, run in integers (`smlad` on a Cortex-M4);
//! - [`qtanh`]: the quantised tanh, the int8 network's activation (a table);
//! - [`envelope`]: the training envelope, its tolerance and the excursion report;
//! - [`blob`]: the weights blob format and its decoder;
//! - [`crc`]: the CRC-32 that guards the blob;
//! - [`tanh`]: the rational tanh both inference and training use.
//!
//! ## Example
//!
//! A controller holding a 3-input, width-16, two-hidden-layer, one-output residual
//! (inputs [δ (m), δ̇ (m/s), δ̇0 (m/s)], output the normal-force correction (N)):
//!
//! ```no_run
//! use hcm_core::residual::{decode, Mlp};
//!
//! # let blob: &[u8] = &[];
//! // let blob: &[u8] = include_bytes!("residual.hcm");
//! let residual: Mlp<3, 16, 1, 2> = decode(blob)?;
//! let input = [10e-6, 1.2, 1.4];
//! if residual.inside_envelope(&input) {
//!     let [correction] = residual.evaluate(&input);
//!     # let _ = correction;
//! }
//! # Ok::<(), hcm_core::residual::BlobError>(())
//! ```

pub mod blob;
pub mod crc;
pub mod envelope;
pub mod int8;
pub mod layer;
pub mod mlp;
pub mod qtanh;
pub mod tanh;

pub use blob::{decode, BlobError};
pub use crc::crc32;
pub use int8::{Int8Layer, Q15Value};
pub use mlp::WeightFormat;
pub use mlp::{
    Envelope, Excursion, F32Weights, Hidden, HiddenDepth, Int8Weights, Layer, Mlp, Normalisation,
};

use crate::Real;
use core::fmt;

/// The nonlinearity applied after every hidden layer; the output layer is linear.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Activation {
    /// tanh(z).
    Tanh,
    /// max(z, 0), with NaN passed through.
    Relu,
    /// tanh by a table and integer interpolation, in Q15 ([`qtanh`]): the activation
    /// an int8 network is trained with, so that its integer kernel computes the
    /// function training fitted (within 1.2e-4 of tanh).
    QuantisedTanh,
}

impl Activation {
    /// The tag that stands for this activation in a weights blob.
    pub const fn tag(self) -> u8 {
        match self {
            Activation::Tanh => 0,
            Activation::Relu => 1,
            Activation::QuantisedTanh => 2,
        }
    }

    /// The activation a blob tag stands for, if any.
    pub const fn from_tag(tag: u8) -> Option<Self> {
        match tag {
            0 => Some(Activation::Tanh),
            1 => Some(Activation::Relu),
            2 => Some(Activation::QuantisedTanh),
            _ => None,
        }
    }

    /// The activation applied to one pre-activation z; NaN stays NaN.
    ///
    /// The one implementation: the core's inference (`f32`) and the host's training
    /// (`f64`) both call it, so the trained and the exported network cannot disagree.
    /// tanh is the rational approximation of [`tanh::tanh`] (within 9.4e-7 of libm's
    /// in `f64`, 1.2e-6 in `f32`) in both: training fits the function the controller
    /// evaluates, and the round trip host → blob → core differs by `f32` rounding only.
    #[inline]
    pub fn apply<T: Real>(self, z: T) -> T {
        match self {
            Activation::Tanh => tanh::tanh(z),
            // The integer function on z rounded to f32: what the int8 kernel computes
            // from its own f32 pre-activation (NaN gives 0, like tanh's clamp).
            Activation::QuantisedTanh => {
                T::of_f32(f32::from(qtanh::quantised_tanh(z.to_f32())) * int8::Q15_UNIT)
            }
            // `max(0, NaN)` would be 0: test explicitly so that NaN propagates.
            Activation::Relu => {
                if z < T::zero() {
                    T::zero()
                } else {
                    z
                }
            }
        }
    }

    /// The slope σ'(z), written through the activation's output a = σ(z), which is
    /// what backpropagation has at hand: tanh' = 1 − a², relu' = 1 for a > 0 else 0
    /// (NaN for a NaN a).
    #[inline]
    pub fn slope<T: Real>(self, a: T) -> T {
        match self {
            // The table's slope is tanh's within its error: training takes tanh's
            // (a straight-through estimate across the interpolation's kinks).
            Activation::Tanh | Activation::QuantisedTanh => T::one() - a * a,
            Activation::Relu => {
                if a > T::zero() {
                    T::one()
                } else if a.is_nan() {
                    a
                } else {
                    T::zero()
                }
            }
        }
    }
}

/// How the weights are stored: full `f32`, or `i8` with one `f32` scale per output row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantisation {
    /// Every weight an `f32` (4 bytes).
    F32,
    /// The hidden → hidden weights `i8` q ∈ [−127, 127], w ≈ q·scale_row, one `f32`
    /// scale per output row, run in integers on 16-bit activations
    /// ([`int8::Int8Layer`]).
    Int8,
}

impl Quantisation {
    /// The tag that stands for this storage in a weights blob.
    pub const fn tag(self) -> u8 {
        match self {
            Quantisation::F32 => 0,
            Quantisation::Int8 => 1,
        }
    }

    /// The storage a blob tag stands for, if any.
    pub const fn from_tag(tag: u8) -> Option<Self> {
        match tag {
            0 => Some(Quantisation::F32),
            1 => Some(Quantisation::Int8),
            _ => None,
        }
    }
}

impl fmt::Display for Quantisation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Quantisation::F32 => "f32",
            Quantisation::Int8 => "int8",
        })
    }
}

#[cfg(test)]
mod tests {
    extern crate std;

    use super::Activation;

    #[test]
    fn one_activation_for_f32_inference_and_f64_training() {
        for activation in [Activation::Tanh, Activation::Relu] {
            for z in [-3.0_f64, -0.5, 0.25, 2.0] {
                let wide = activation.apply(z);
                let narrow = activation.apply(z as f32);
                assert!((wide - narrow as f64).abs() < 1e-6, "{activation:?}({z})");
                // The slope through the output matches a central difference.
                let h = 1e-6;
                let numeric = (activation.apply(z + h) - activation.apply(z - h)) / (2.0 * h);
                // Training's slope is tanh's own, 1 − a²; the approximation's differs
                // from it by its own slope error (at most 1.3e-5, tanh.rs).
                let bound = if activation == Activation::Tanh {
                    1.3e-5
                } else {
                    1e-6
                };
                assert!(
                    (activation.slope(wide) - numeric).abs() < bound,
                    "{activation:?}'({z}): {} vs {numeric}",
                    activation.slope(wide)
                );
            }
            assert!(activation.slope(f64::NAN).is_nan());
        }
        // NaN stays NaN through ReLU (written as max(z, 0) it would make 0); tanh makes
        // it 0 (its clamp; see tanh.rs), and the network returns NaN for NaN itself.
        assert!(Activation::Relu.apply(f64::NAN).is_nan());
        assert!(Activation::Relu.apply(f32::NAN).is_nan());
        for nan in [
            Activation::Tanh.apply(f64::NAN),
            f64::from(Activation::Tanh.apply(f32::NAN)),
        ] {
            assert_eq!(nan, 0.0);
        }
    }
}
