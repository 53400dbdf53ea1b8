//! Per-contact evaluation cost, physics vs hybrid contact model vs a general-purpose
//! framework, all `f32`, at one state inside the residual's envelope (δ = 10 µm,
//! δ̇ = 1 m/s, δ̇0 = 1.4 m/s, the state of `law_evaluation`):
//!
//! - `physics_only`: the Lankarani–Nikravesh law at the reference parameters;
//! - `hcm_f32`: `ContactModel` = that law + the shipped 3-16-16-1 tanh residual
//!   (`hcm_core::residual::Mlp`, f32 weights), envelope check included;
//! - `hcm_int8`: the same with the int8 weights of the same network;
//! - `hcm_candle`: the same law and envelope check, the residual (same f32 weights, same
//!   normalisation) evaluated with candle-core on the CPU: one input row, matmul + bias
//!   (+ tanh on the two hidden layers) per layer, the result read back as an `f32`;
//!   with candle's default thread count (`RAYON_NUM_THREADS`, else the CPU count);
//! - `hcm_candle_1_thread`: the same with `RAYON_NUM_THREADS=1`, which candle reads at
//!   every matmul: gemm then gets single-threaded work (with 2, each 1-row product is
//!   passed to gemm as multi-threaded work, which costs 20–30× more here).
//!
//! The group `residual_only` times the residual evaluations alone (no law, no
//! envelope check). Before timing, the candle path is checked against `hcm_f32` on a few
//! inputs (the same function within 1e-5 relative) and the comparison is printed.
//!
//! Run: `cargo bench -p hcm-tests --features candle --bench residual_evaluation`.
//! Without the `candle` feature the candle rows and the check are left out and the
//! core's rows run alone (`cargo test --workspace` runs them so, once each: see
//! docs/tests.md).

#[cfg(feature = "candle")]
#[path = "common/candle_mlp.rs"]
mod candle_mlp;

#[cfg(feature = "candle")]
use candle_mlp::CandleMlp;
use criterion::{criterion_group, criterion_main, Criterion};
use hcm_core::effect::ContactMemory;
use hcm_core::law::{AnyNormalLaw, Indentation, NormalLaw};
use hcm_core::model::{ContactModel, Evaluated};
use hcm_core::residual::{decode, F32Weights, Int8Weights, Mlp, Quantisation};
use hcm_host::export::encode;
use hcm_host::residual::{HIDDEN, INPUTS, WIDTH};
use hcm_host::train::{quantisation_aware, train, TrainSettings};
use hcm_tests::reference;
use std::hint::black_box;

type CoreMlp<Q> = Mlp<INPUTS, WIDTH, 1, HIDDEN, Q>;
type Hybrid<Q> = ContactModel<f32, CoreMlp<Q>>;

/// δ̇0 of every synthetic row (m/s): the ball's impact speed.
const APPROACH_SPEED: f64 = 1.4;

/// A network of the shipped architecture, trained for a few epochs on a smooth
/// synthetic force error over the ball's ranges (δ 0–60 µm, δ̇ ±1.4 m/s, δ̇0 1.4 m/s),
/// and its int8 twin as `hcm train` makes it (quantisation-aware, with the quantised
/// tanh the core's integer kernel runs: an int8 blob of the plain tanh is refused).
/// The timings do not depend on the weight values (no branch or sparsity in the
/// forward pass depends on them); training only gives realistic weights and
/// normalisation, and an envelope that contains the benchmarked state.
fn trained_blobs() -> (Vec<u8>, Vec<u8>) {
    let (depths, rates) = (40, 50);
    let mut inputs = Vec::with_capacity(depths * rates);
    let mut targets = Vec::with_capacity(depths * rates);
    for i in 0..depths {
        let depth = 60e-6 * i as f64 / (depths - 1) as f64;
        for j in 0..rates {
            let rate = -1.4 + 2.8 * j as f64 / (rates - 1) as f64;
            let s = depth / 60e-6;
            // N: a rate-proportional damping error plus a depth-only stiffness error.
            let error = 40.0 * s.powf(1.5) * rate - 15.0 * (std::f64::consts::PI * s).sin();
            inputs.push(vec![depth, rate, APPROACH_SPEED]);
            targets.push(vec![error]);
        }
    }
    let settings = TrainSettings {
        hidden_layers: HIDDEN,
        width: WIDTH,
        max_epochs: 5,
        patience: 0,
        seed: 0,
        ..TrainSettings::default()
    };
    let (network, _) = train(&inputs, &targets, &settings, |_, _, _| {}).unwrap();
    let (twin, _) = quantisation_aware(&network, &inputs, 2, 0, |_, _| {}).unwrap();
    (
        encode(&network, Quantisation::F32).unwrap(),
        encode(&twin, Quantisation::Int8).unwrap(),
    )
}

/// The core residual's forward pass in candle-core (one output: the force correction).
#[cfg(feature = "candle")]
type CandleResidual = CandleMlp<INPUTS, 1>;

/// `ContactModel::normal_force` with the residual evaluated by candle.
#[cfg(feature = "candle")]
fn hybrid_candle(
    law: &AnyNormalLaw<f32>,
    residual: &CandleResidual,
    contact: &Indentation<f32>,
    input: &[f32; INPUTS],
) -> (f32, Evaluated) {
    if !(contact.depth > 0.0 || contact.depth.is_nan()) {
        return (0.0, Evaluated::PhysicsOnly);
    }
    let physics = law.normal_force(contact);
    if !residual.envelope.contains(input) {
        return (physics, Evaluated::PhysicsOnly);
    }
    let [correction] = residual.evaluate(input).unwrap();
    (physics + correction, Evaluated::PhysicsAndResidual)
}

fn state(depth: f32, rate: f32) -> (Indentation<f32>, [f32; INPUTS]) {
    let approach_speed = APPROACH_SPEED as f32;
    (
        Indentation {
            depth,
            rate,
            approach_speed,
        },
        [depth, rate, approach_speed],
    )
}

/// Fails unless candle computes the same function as the core f32 model: hybrid force
/// within 1e-5 relative, residual correction within 1e-4 (against max(|r|, 1 N), its
/// scale being tens of N; candle's libm tanh differs from the core's by ≤ 1.2e-6).
#[cfg(feature = "candle")]
fn check_same_function(
    law: &AnyNormalLaw<f32>,
    core: &Hybrid<F32Weights>,
    candle: &CandleResidual,
) {
    println!("candle vs hcm_f32 (same weights and normalisation):");
    println!("  δ (µm)  δ̇ (m/s)   force hcm_f32 (N)   force candle (N)   rel. diff   residual hcm_f32 (N)  residual candle (N)");
    for (depth, rate) in [
        (10e-6, 1.0),
        (5e-6, -1.2),
        (30e-6, -0.5),
        (45e-6, 0.3),
        (58e-6, 1.35),
    ] {
        let (contact, input) = state(depth, rate);
        let (force, evaluated) = core.normal_force(&contact, &ContactMemory::touch_down(), &input);
        let (force_candle, evaluated_candle) = hybrid_candle(law, candle, &contact, &input);
        assert_eq!(evaluated, Evaluated::PhysicsAndResidual);
        assert_eq!(evaluated_candle, Evaluated::PhysicsAndResidual);
        let [residual] = core.residual.evaluate(&input);
        let [residual_candle] = candle.evaluate(&input).unwrap();
        let relative = (force_candle - force).abs() / force.abs();
        println!(
            "  {:6.1}  {rate:8.2}  {force:18.6}  {force_candle:17.6}  {relative:10.2e}  {residual:20.6}  {residual_candle:19.6}",
            depth * 1e6
        );
        assert!(relative <= 1e-5, "force {force} vs candle {force_candle}");
        // candle's tanh is libm's; the core's rational one is within 1.2e-6 of it per
        // activation, which the layers carry to the output amplified by their row sums
        // (tests/contact/residual_blob.rs asserts that carried bound exactly): 1e-4 here.
        assert!(
            (residual_candle - residual).abs() <= 1e-4 * residual.abs().max(1.0),
            "residual {residual} vs candle {residual_candle}"
        );
    }
}

fn bench_per_contact(c: &mut Criterion) {
    let (f32_blob, int8_blob) = trained_blobs();
    let residual_f32: CoreMlp<F32Weights> = decode(&f32_blob).unwrap();
    let residual_int8: CoreMlp<Int8Weights> = decode(&int8_blob).unwrap();
    let law: AnyNormalLaw<f32> = reference::lankarani_nikravesh::<f32>().into();
    let hcm_f32: Hybrid<F32Weights> = ContactModel::physics(law).with_residual(residual_f32);
    let hcm_int8: Hybrid<Int8Weights> = ContactModel::physics(law).with_residual(residual_int8);
    #[cfg(feature = "candle")]
    let candle = candle_twin(&law, &hcm_f32, &residual_f32);

    let (contact, input) = state(10e-6, 1.0);
    let memory = ContactMemory::touch_down();
    let residual_runs = "the benchmarked state must run the residual";
    for evaluated in [
        hcm_f32.normal_force(&contact, &memory, &input).1,
        hcm_int8.normal_force(&contact, &memory, &input).1,
    ] {
        assert_eq!(evaluated, Evaluated::PhysicsAndResidual, "{residual_runs}");
    }
    #[cfg(feature = "candle")]
    assert_eq!(
        hybrid_candle(&law, &candle, &contact, &input).1,
        Evaluated::PhysicsAndResidual,
        "{residual_runs}"
    );

    let mut group = c.benchmark_group("per_contact_f32");
    group.bench_function("physics_only", |b| {
        b.iter(|| black_box(&law).normal_force(black_box(&contact)))
    });
    group.bench_function("hcm_f32", |b| {
        b.iter(|| black_box(&hcm_f32).normal_force(black_box(&contact), &memory, black_box(&input)))
    });
    group.bench_function("hcm_int8", |b| {
        b.iter(|| {
            black_box(&hcm_int8).normal_force(black_box(&contact), &memory, black_box(&input))
        })
    });
    #[cfg(feature = "candle")]
    {
        let candle_hcm = |b: &mut criterion::Bencher| {
            b.iter(|| {
                hybrid_candle(
                    black_box(&law),
                    black_box(&candle),
                    black_box(&contact),
                    black_box(&input),
                )
            })
        };
        group.bench_function("hcm_candle", candle_hcm);
        single_threaded_candle(|| group.bench_function("hcm_candle_1_thread", candle_hcm));
    }
    group.finish();

    let mut group = c.benchmark_group("residual_only");
    group.bench_function("core_f32", |b| {
        b.iter(|| black_box(&hcm_f32.residual).evaluate(black_box(&input)))
    });
    group.bench_function("core_int8", |b| {
        b.iter(|| black_box(&hcm_int8.residual).evaluate(black_box(&input)))
    });
    #[cfg(feature = "candle")]
    {
        let candle_residual = |b: &mut criterion::Bencher| {
            b.iter(|| black_box(&candle).evaluate(black_box(&input)).unwrap())
        };
        group.bench_function("candle", candle_residual);
        single_threaded_candle(|| group.bench_function("candle_1_thread", candle_residual));
    }
    group.finish();
}

/// The f32 network in candle, checked against the core first.
#[cfg(feature = "candle")]
fn candle_twin(
    law: &AnyNormalLaw<f32>,
    hcm_f32: &Hybrid<F32Weights>,
    residual_f32: &CoreMlp<F32Weights>,
) -> CandleResidual {
    let candle = CandleResidual::from_core(residual_f32).unwrap();
    check_same_function(law, hcm_f32, &candle);
    println!(
        "candle threads (default): {}",
        candle_core::utils::get_num_threads()
    );
    candle
}

/// Runs `bench` with `RAYON_NUM_THREADS=1`, then restores the variable. candle reads it
/// at every matmul (`candle_core::utils::get_num_threads`). Set while no other thread
/// runs: the trainer's rayon workers are idle and the benchmarks are single-threaded.
#[cfg(feature = "candle")]
fn single_threaded_candle<R>(bench: impl FnOnce() -> R) {
    let previous = std::env::var_os("RAYON_NUM_THREADS");
    std::env::set_var("RAYON_NUM_THREADS", "1");
    assert_eq!(candle_core::utils::get_num_threads(), 1);
    bench();
    match previous {
        Some(value) => std::env::set_var("RAYON_NUM_THREADS", value),
        None => std::env::remove_var("RAYON_NUM_THREADS"),
    }
}

criterion_group!(benches, bench_per_contact);
criterion_main!(benches);
