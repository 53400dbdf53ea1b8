//! Puts `memory.x` (and an empty `device.x`) where cortex-m-rt's `link.x` finds it (the
//! linker's search path), and writes the peg's two networks as Rust source for the peg
//! images (`OUT_DIR/peg_f32.rs`, `OUT_DIR/peg_int8.rs`).
//!
//! The networks: each shipped blob (`examples/blobs/peg_in_hole.*.hcm`) decoded here,
//! on the build machine, by hcm-core's own decoder (`peg::decode_network`, the function
//! the host test decodes with: its CRC and every check included; a bad blob fails the
//! build), then written out as one constant expression — every `f32` as
//! `f32::from_bits` of its exact bits, the int8 levels as stored — which the image
//! holds in a `static`. The network then sits in flash alone: no decoder in the image,
//! no copy of it in RAM (as MicroFlow compiles its models in). The ball's image still
//! decodes its blobs on the device.

use std::fmt::Write as _;
use std::{env, fs, path::Path, path::PathBuf};

#[allow(dead_code, unused_imports)] // only the blobs, their types and the decoder here
#[path = "src/peg/mod.rs"]
mod peg;

use hcm_core::residual::{
    Activation, Envelope, F32Weights, Int8Layer, Int8Weights, Layer, Normalisation,
};
use peg::{PegResidual, PegWeights};

fn main() {
    let out = PathBuf::from(env::var_os("OUT_DIR").expect("cargo sets OUT_DIR"));
    fs::copy("memory.x", out.join("memory.x")).expect("memory.x beside Cargo.toml");
    // cortex-m-rt's `device` feature includes the device's interrupt handler names;
    // the firmware handles no interrupt, so there are none.
    fs::write(out.join("device.x"), "/* no interrupt handlers */\n").expect("OUT_DIR writable");
    println!("cargo:rustc-link-search={}", out.display());
    write_network::<F32Weights>(&out);
    write_network::<Int8Weights>(&out);
    for input in [
        "memory.x",
        "build.rs",
        "src/peg",
        "../examples/blobs/peg_in_hole.f32.hcm",
        "../examples/blobs/peg_in_hole.int8.hcm",
    ] {
        println!("cargo:rerun-if-changed={input}");
    }
}

/// Decodes the peg's blob of `Q` and writes it to `OUT_DIR/peg_<name>.rs` as an
/// expression of type `PegResidual<Q>`.
fn write_network<Q: PegWeights>(out: &Path)
where
    Q::Square<32>: Source,
{
    let network: PegResidual<Q> = peg::decode_network::<Q>()
        .unwrap_or_else(|error| panic!("the peg's {} blob: {error:?}", Q::NAME));
    let mut text = format!(
        "// The peg's {} network, decoded from its blob by build.rs. Do not edit.\n",
        Q::NAME
    );
    text.push_str("::hcm_core::residual::Mlp {\n    activation: ");
    network.activation.source(&mut text);
    for (field, value) in [
        ("normalisation", &network.normalisation as &dyn Source),
        ("envelope", &network.envelope),
        ("input_layer", &network.input_layer),
        ("hidden_layers", &network.hidden_layers.as_ref()),
        ("output_layer", &network.output_layer),
    ] {
        write!(text, ",\n    {field}: ").expect("a String takes any text");
        value.source(&mut text);
    }
    text.push_str(",\n}\n");
    let path = out.join(format!("peg_{}.rs", Q::NAME));
    fs::write(&path, text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
}

/// A value written as the Rust expression that rebuilds it, bit for bit.
trait Source {
    fn source(&self, text: &mut String);
}

impl Source for f32 {
    fn source(&self, text: &mut String) {
        write!(text, "f32::from_bits({:#010x})", self.to_bits()).expect("a String takes any text");
    }
}

impl Source for i8 {
    fn source(&self, text: &mut String) {
        write!(text, "{self}").expect("a String takes any text");
    }
}

impl<T: Source> Source for [T] {
    fn source(&self, text: &mut String) {
        text.push('[');
        for (i, item) in self.iter().enumerate() {
            if i > 0 {
                text.push_str(", ");
            }
            item.source(text);
        }
        text.push(']');
    }
}

impl<T: Source, const N: usize> Source for [T; N] {
    fn source(&self, text: &mut String) {
        self.as_slice().source(text);
    }
}

impl<T: Source + ?Sized> Source for &T {
    fn source(&self, text: &mut String) {
        (**self).source(text);
    }
}

impl Source for Activation {
    fn source(&self, text: &mut String) {
        write!(text, "::hcm_core::residual::Activation::{self:?}")
            .expect("a String takes any text");
    }
}

/// `::hcm_core::residual::NAME { field: value, … }`.
fn structure(text: &mut String, name: &str, fields: &[(&str, &dyn Source)]) {
    write!(text, "::hcm_core::residual::{name} {{").expect("a String takes any text");
    for (field, value) in fields {
        write!(text, "\n        {field}: ").expect("a String takes any text");
        value.source(text);
        text.push(',');
    }
    text.push_str("\n    }");
}

impl<const N: usize, const M: usize> Source for Normalisation<N, M> {
    fn source(&self, text: &mut String) {
        structure(
            text,
            "Normalisation",
            &[
                ("input_mean", &self.input_mean),
                ("input_scale", &self.input_scale),
                ("output_mean", &self.output_mean),
                ("output_scale", &self.output_scale),
            ],
        );
    }
}

impl<const N: usize> Source for Envelope<N> {
    fn source(&self, text: &mut String) {
        let fields: [(&str, &dyn Source); 3] = [
            ("min", &self.min),
            ("max", &self.max),
            ("tolerance", &self.tolerance),
        ];
        structure(text, "Envelope", &fields);
    }
}

impl<const IN: usize, const OUT: usize> Source for Layer<IN, OUT> {
    fn source(&self, text: &mut String) {
        let fields: [(&str, &dyn Source); 2] = [("weights", &self.weights), ("bias", &self.bias)];
        structure(text, "Layer", &fields);
    }
}

impl<const IN: usize, const OUT: usize> Source for Int8Layer<IN, OUT> {
    fn source(&self, text: &mut String) {
        text.push_str("::hcm_core::residual::Int8Layer::from_stored_levels(");
        for (i, part) in [
            self.stored_levels() as &dyn Source,
            self.scales(),
            self.biases(),
        ]
        .into_iter()
        .enumerate()
        {
            if i > 0 {
                text.push_str(", ");
            }
            part.source(text);
        }
        text.push(')');
    }
}
