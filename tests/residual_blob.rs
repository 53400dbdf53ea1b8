//! The weights blob end to end: the host encoder (`hcm_host::export`) writes it, the
//! no_std core (`hcm_core::residual::decode`) reads it, and the core's `f32` network
//! agrees with the host's f64 reference.

use hcm_core::residual::blob::{BlobContents, Shape, VERSION};
use hcm_core::residual::{
    decode, Activation, BlobError, F32Weights, Hidden, HiddenDepth, Int8Weights, Mlp, Quantisation,
    WeightFormat,
};
use hcm_host::export::{encode, seal, ExportError, ExportModel};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Training ranges of the 1D contact examples: δ (m), δ̇ (m/s), δ̇0 (m/s).
const ENVELOPE: [(f64, f64); 3] = [(0.0, 1e-3), (-2.0, 2.0), (0.5, 2.0)];
/// Output normalisation: a force correction of about ±50 N around 3 N.
const OUTPUT_MEAN: f64 = 3.0;
const OUTPUT_SCALE: f64 = 50.0;

/// A random 3-input, 1-output network with Xavier-scaled weights (so that tanh works
/// in its curved range rather than saturated) and the contact examples' envelope.
fn random_model(
    seed: u64,
    width: usize,
    hidden_layers: usize,
    activation: Activation,
) -> ExportModel {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut model = ExportModel {
        inputs: 3,
        width,
        outputs: 1,
        hidden_layers,
        activation,
        layers: Vec::new(),
        input_mean: ENVELOPE.iter().map(|(lo, hi)| 0.5 * (lo + hi)).collect(),
        input_scale: ENVELOPE.iter().map(|(lo, hi)| 0.5 * (hi - lo)).collect(),
        output_mean: vec![OUTPUT_MEAN],
        output_scale: vec![OUTPUT_SCALE],
        envelope_min: ENVELOPE.iter().map(|(lo, _)| *lo).collect(),
        envelope_max: ENVELOPE.iter().map(|(_, hi)| *hi).collect(),
    };
    model.layers = model
        .layer_sizes()
        .into_iter()
        .map(|(inputs, outputs)| {
            let limit = (6.0 / (inputs + outputs) as f64).sqrt();
            let weights = (0..inputs * outputs)
                .map(|_| rng.random_range(-limit..limit))
                .collect();
            let bias = (0..outputs).map(|_| rng.random_range(-0.1..0.1)).collect();
            (weights, bias)
        })
        .collect();
    model
}

/// `count` inputs drawn uniformly inside the envelope.
fn random_inputs(seed: u64, count: usize) -> Vec<[f64; 3]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    (0..count)
        .map(|_| ENVELOPE.map(|(lo, hi)| lo + (hi - lo) * rng.random::<f64>()))
        .collect()
}

/// Over 1000 inputs inside the envelope: the largest |core − host| / max(|host|, σ_y)
/// (relative error, with the output scale σ_y = 50 N as its floor so that outputs
/// crossing zero do not divide by ~0), and, for information, the largest plain
/// |core − host| / |host| over outputs with |host| ≥ 10 N.
fn worst_errors<const HIDDEN: usize, Q: WeightFormat>(
    model: &ExportModel,
    mlp: &Mlp<3, 16, 1, HIDDEN, Q>,
) -> (f64, f64)
where
    Hidden<HIDDEN>: HiddenDepth<16, Q>,
{
    let (mut of_scale, mut relative) = (0.0_f64, 0.0_f64);
    for input in random_inputs(11, 1000) {
        let host = model.evaluate(&input)[0];
        let [core] = mlp.evaluate(&input.map(|x| x as f32));
        assert!(mlp.inside_envelope(&input.map(|x| x as f32)));
        let error = (f64::from(core) - host).abs();
        of_scale = of_scale.max(error / host.abs().max(OUTPUT_SCALE));
        if host.abs() >= 10.0 {
            relative = relative.max(error / host.abs());
        }
    }
    (of_scale, relative)
}

fn round_trip<const HIDDEN: usize>(activation: Activation)
where
    Hidden<HIDDEN>: HiddenDepth<16, F32Weights> + HiddenDepth<16, Int8Weights>,
{
    let model = random_model(HIDDEN as u64, 16, HIDDEN, activation);

    let blob = encode(&model, Quantisation::F32).unwrap();
    let mlp: Mlp<3, 16, 1, HIDDEN> = decode(&blob).unwrap();
    let (of_scale, relative) = worst_errors(&model, &mlp);
    println!(
        "{activation:?}, {HIDDEN} hidden: f32 blob {} bytes, worst relative error {of_scale:.2e} (floor σ_y), {relative:.2e} where |y| ≥ 10 N",
        blob.len()
    );
    assert!(of_scale < 1e-6, "{of_scale:e}");

    let blob = encode(&model, Quantisation::Int8).unwrap();
    let mlp: Mlp<3, 16, 1, HIDDEN, Int8Weights> = decode(&blob).unwrap();
    let (of_scale, relative) = worst_errors(&model, &mlp);
    println!(
        "{activation:?}, {HIDDEN} hidden: int8 blob {} bytes, worst relative error {of_scale:.2e} (floor σ_y), {relative:.2e} where |y| ≥ 10 N",
        blob.len()
    );
    // Int8 rounds each weight by up to half its row scale (0.4 % of the row's
    // largest weight): 1 % of the output scale is the stated tolerance.
    assert!(of_scale < 1e-2, "{of_scale:e}");
}

#[test]
fn f32_and_int8_round_trips_match_the_host_for_one_to_three_hidden_layers() {
    round_trip::<1>(Activation::Tanh);
    round_trip::<2>(Activation::Tanh);
    round_trip::<3>(Activation::Tanh);
    round_trip::<1>(Activation::Relu);
    round_trip::<2>(Activation::Relu);
    round_trip::<3>(Activation::Relu);
}

/// A valid 3-16-1, two-hidden-layer f32 blob.
fn valid_blob() -> Vec<u8> {
    encode(&random_model(2, 16, 2, Activation::Tanh), Quantisation::F32).unwrap()
}

fn decode_3_16_1_2(bytes: &[u8]) -> Result<Mlp<3, 16, 1, 2>, BlobError> {
    decode(bytes)
}

/// The blob's contents, copied out so that a test can change them and `seal` again.
fn reseal(blob: &[u8], change: impl FnOnce(&mut BlobContents<'_>, &mut Vec<u8>)) -> Vec<u8> {
    let mut contents: BlobContents<'_> = postcard::from_bytes(&blob[..blob.len() - 4]).unwrap();
    let mut layers = contents.layers.to_vec();
    change(&mut contents, &mut layers);
    seal(&BlobContents {
        layers: &layers,
        ..contents
    })
    .unwrap()
}

#[test]
fn every_prefix_of_a_valid_blob_is_truncated() {
    let blob = valid_blob();
    assert!(decode_3_16_1_2(&blob).is_ok());
    for length in 0..blob.len() {
        // Past its header (magic, version, four shape varints, two tags), a prefix
        // is measured against the length the header announces: the whole blob's.
        let header = 11;
        let announced = (length >= header).then_some(blob.len());
        assert_eq!(
            decode_3_16_1_2(&blob[..length]).unwrap_err(),
            BlobError::Truncated { length, announced },
            "prefix of {length} bytes"
        );
    }
    let mut longer = blob.clone();
    longer.push(0);
    assert_eq!(
        decode_3_16_1_2(&longer).unwrap_err(),
        BlobError::TrailingBytes {
            count: 1,
            announced: blob.len()
        }
    );
}

#[test]
fn a_blob_without_the_magic_is_refused() {
    let mut blob = valid_blob();
    blob[0] = b'X';
    assert_eq!(decode_3_16_1_2(&blob).unwrap_err(), BlobError::BadMagic);
    assert_eq!(
        decode_3_16_1_2(b"PK\x03\x04").unwrap_err(),
        BlobError::BadMagic
    );
}

#[test]
fn another_format_version_is_refused() {
    // Version 1 stored the output layer of an int8 blob as int8 too; a later version
    // is unknown. Both are refused by name.
    for found in [VERSION - 1, VERSION + 1] {
        let blob = reseal(&valid_blob(), |contents, _| contents.version = found);
        assert_eq!(
            decode_3_16_1_2(&blob).unwrap_err(),
            BlobError::UnsupportedVersion { found }
        );
    }
}

#[test]
fn a_blob_of_another_shape_is_refused() {
    let blob = valid_blob();
    let error = decode::<2, 16, 1, 2, F32Weights>(&blob).unwrap_err();
    let shape = |inputs| Shape {
        inputs,
        width: 16,
        outputs: 1,
        hidden_layers: 2,
    };
    assert_eq!(
        error,
        BlobError::WrongShape {
            expected: shape(2),
            found: shape(3)
        }
    );
    println!("{error}");
    assert!(matches!(
        decode::<3, 16, 1, 3, F32Weights>(&blob),
        Err(BlobError::WrongShape { .. })
    ));
    assert_eq!(
        decode::<3, 16, 1, 2, Int8Weights>(&blob).unwrap_err(),
        BlobError::WrongQuantisation {
            expected: Quantisation::Int8,
            found: Quantisation::F32
        }
    );
    let deep = reseal(&blob, |contents, _| contents.shape.hidden_layers = 4);
    assert_eq!(
        decode_3_16_1_2(&deep).unwrap_err(),
        BlobError::UnsupportedDepth { found: 4 }
    );
    let odd = reseal(&blob, |contents, _| contents.activation = 7);
    assert_eq!(
        decode_3_16_1_2(&odd).unwrap_err(),
        BlobError::BadActivation { found: 7 }
    );
}

#[test]
fn a_corrupted_byte_fails_the_crc() {
    let blob = valid_blob();
    let stored = u32::from_le_bytes(blob[blob.len() - 4..].try_into().unwrap());
    // A byte of the last bias: the structure stays intact, only the CRC can tell.
    let mut corrupted = blob.clone();
    let at = blob.len() - 6;
    corrupted[at] ^= 0x10;
    match decode_3_16_1_2(&corrupted).unwrap_err() {
        BlobError::BadCrc { expected, found } => {
            assert_eq!(expected, stored);
            assert_ne!(found, stored);
        }
        other => panic!("{other:?}"),
    }
    // Every single-bit flip anywhere is refused (CRC-32 catches all of them).
    let mut bad_crc = 0;
    for at in 0..blob.len() {
        for bit in 0..8 {
            let mut flipped = blob.clone();
            flipped[at] ^= 1 << bit;
            let error = decode_3_16_1_2(&flipped).unwrap_err();
            bad_crc += usize::from(matches!(error, BlobError::BadCrc { .. }));
        }
    }
    println!(
        "{bad_crc} of {} single-bit flips reported as BadCrc, the rest by an earlier check",
        blob.len() * 8
    );
}

#[test]
fn a_nan_weight_is_refused_by_the_encoder_and_the_decoder() {
    let mut model = random_model(2, 16, 2, Activation::Tanh);
    model.layers[1].0[5] = f64::NAN;
    assert!(matches!(
        encode(&model, Quantisation::F32),
        Err(ExportError::NonFinite { .. })
    ));
    assert!(matches!(
        encode(&model, Quantisation::Int8),
        Err(ExportError::NonFinite { .. })
    ));
    model.layers[1].0[5] = 1e300; // finite in f64, infinite in f32
    assert!(matches!(
        encode(&model, Quantisation::F32),
        Err(ExportError::NonFinite { .. })
    ));

    // The first weight of the first layer, overwritten by hand, CRC recomputed.
    let blob = reseal(&valid_blob(), |_, layers| {
        layers[..4].copy_from_slice(&f32::NAN.to_le_bytes());
    });
    assert_eq!(
        decode_3_16_1_2(&blob).unwrap_err(),
        BlobError::NonFiniteWeight
    );
}

#[test]
fn random_damage_never_panics_and_is_always_refused() {
    let blob = valid_blob();
    let mut rng = ChaCha8Rng::seed_from_u64(99);
    for _ in 0..20_000 {
        let mut damaged = blob.clone();
        for _ in 0..rng.random_range(1..4) {
            let at = rng.random_range(0..damaged.len());
            match rng.random_range(0..3) {
                0 => damaged[at] = rng.random(),
                1 => {
                    damaged.remove(at);
                }
                _ => damaged.insert(at, rng.random()),
            }
        }
        if damaged != blob {
            assert!(decode_3_16_1_2(&damaged).is_err());
        }
    }
}

#[test]
fn blob_sizes_of_the_reference_network() {
    // 3 inputs, 2 hidden layers of 16, 1 output: 353 weights and biases.
    let model = random_model(5, 16, 2, Activation::Tanh);
    let f32_blob = encode(&model, Quantisation::F32).unwrap();
    let int8_blob = encode(&model, Quantisation::Int8).unwrap();
    println!(
        "3-16-16-1: f32 blob {} bytes, int8 blob {} bytes",
        f32_blob.len(),
        int8_blob.len()
    );
    // 353 f32 parameters take 1412 bytes. Int8 stores the 16×16 hidden → hidden
    // weights in one byte each instead of four (−768 bytes) and adds a 4-byte scale
    // per row of that layer (+64); the input and output layers stay f32. (The postcard
    // length prefix of the layers section may shrink by a byte.)
    assert!(f32_blob.len() > 1412 && f32_blob.len() < 1412 + 100);
    let saved = f32_blob.len() - int8_blob.len();
    assert!((703..=705).contains(&saved), "saved {saved} bytes");
}
