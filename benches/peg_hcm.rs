//! Evaluation cost of the peg-in-hole's HCM, all `f32`, at one peg state in
//! contact with the residual on (`wall_2_peak` of `hcm-firmware/src/peg/states.rs`:
//! the peg against two walls, 4 contact points):
//!
//! - `residual/core_f32`, `residual/core_int8`: the 13-32-32-6 wrench residual alone
//!   (`Mlp::evaluate` of `examples/blobs/peg_in_hole.{f32,int8}.hcm`);
//! - `residual/candle_1_thread`: the same network (the f32 blob's weights and
//!   normalisation) in candle-core on the CPU, `RAYON_NUM_THREADS=1` as in
//!   `residual_evaluation`: one input row, matmul + bias (+ tanh on the two hidden
//!   layers) per layer, the six outputs read back;
//! - `pair_8_points/hcm_f32`, `pair_8_points/hcm_int8`: the contact model given an
//!   8-point manifold (`ContactModel::pair_load`: IMPACT + STEP friction at 8 points
//!   summed by Eq 1, plus the residual's wrench), the firmware's PM2;
//! - `pair_8_points/hcm_candle_1_thread`: the same physics with the residual evaluated
//!   by candle (the physics' `pair_load`, then the wrench added inside the envelope);
//! - `peg_load/hcm_f32`, `peg_load/hcm_int8`: the whole peg HCM as the firmware runs
//!   it (`peg_load`: the peg box against the block's five boxes, the touching points'
//!   rates, then `pair_load`).
//!
//! Before timing, candle is checked against the core on every peg state inside the
//! residual's envelope: the 8-point HCM's force and torque within 1e-5 relative (of the
//! largest component), the residual's six outputs within 1e-4 (measured: up to
//! 1.1e-5; candle's tanh is libm's, the core's a rational one within 1.2e-6 of it per
//! activation, which two hidden layers of 32 carry to the outputs amplified, as
//! `residual_evaluation` explains for the ball's network).
//!
//! The firmware's peg module (`hcm-firmware/src/peg`) is compiled in, as
//! `tests/controller/firmware.rs` does: its states, PM2, blobs, manifold and `peg_load` are the
//! firmware's own. Only the core's public API is used (`decode`, `Mlp::evaluate`,
//! `ContactModel::pair_load`, the f32 network's public weights for candle).
//!
//! Run: `cargo bench -p hcm-tests --features candle --bench peg_hcm`. Without the
//! `candle` feature the candle rows and the check are left out and the core's rows run
//! alone (`cargo test --workspace` runs them so, once each: see docs/tests.md).

#[allow(dead_code)] // the firmware's printing helpers are not used here
#[path = "../hcm-firmware/src/peg/mod.rs"]
mod peg;

#[cfg(feature = "candle")]
#[path = "common/candle_mlp.rs"]
mod candle_mlp;

#[cfg(feature = "candle")]
use candle_mlp::CandleMlp;
use criterion::{criterion_group, criterion_main, Criterion};
#[cfg(feature = "candle")]
use hcm_core::model::PairLoad;
use hcm_core::model::{ContactModel, ContactPoint, Evaluated};
use hcm_core::residual::{F32Weights, Int8Weights};
use hcm_core::rigid::RigidState;
use nalgebra::Vector3;
#[cfg(feature = "candle")]
use peg::STATE_NAMES;
use peg::{PegResidual, PEG_STATES};
use std::hint::black_box;

/// Inputs and outputs of the peg's residual.
const INPUTS: usize = 13;
#[cfg(feature = "candle")]
const OUTPUTS: usize = 6;

/// The benchmarked state: `wall_2_peak`.
const STATE: usize = 3;

/// The peg's residual network in candle-core.
#[cfg(feature = "candle")]
type CandleResidual = CandleMlp<INPUTS, OUTPUTS>;

/// The peg's HCM with `Q` weights, as the firmware's host test builds it.
struct PegFixture<Q: peg::PegWeights> {
    /// PM2 + friction + the residual.
    hcm: ContactModel<f32, PegResidual<Q>>,
}

/// `ContactModel::pair_load` with the residual evaluated by candle: the physics' loads,
/// plus the residual's wrench on body 1 while a point touches and the input lies
/// inside the envelope (what the core does for a six-output residual).
#[cfg(feature = "candle")]
fn pair_load_candle(
    physics: &ContactModel<f32>,
    residual: &CandleResidual,
    points: &[ContactPoint<f32>],
    reference: &Vector3<f32>,
    input: &[f32; INPUTS],
) -> PairLoad<f32> {
    let mut load = physics.pair_load(points, reference, &Vector3::zeros(), &[]);
    let touching = points
        .iter()
        .any(|p| p.indentation.depth > 0.0 || p.indentation.depth.is_nan());
    if touching && residual.envelope.contains(input) {
        let y = residual.evaluate(input).unwrap();
        let (force, torque) = (
            Vector3::new(y[0], y[1], y[2]),
            Vector3::new(y[3], y[4], y[5]),
        );
        let w = &mut load.wrench;
        w.force_1 += force;
        w.torque_1 += torque;
        w.force_2 -= force;
        w.torque_2 -= torque + reference.cross(&force);
        load.evaluated = Evaluated::PhysicsAndResidual;
    }
    load
}

/// max |a − b| over max |b|: the distance of `a` from `b` relative to `b`'s scale.
#[cfg(feature = "candle")]
fn relative(a: &[f32], b: &[f32]) -> f32 {
    let scale = b.iter().fold(0.0_f32, |m, x| m.max(x.abs()));
    let error = a
        .iter()
        .zip(b)
        .fold(0.0_f32, |m, (x, y)| m.max((x - y).abs()));
    error / scale
}

/// Fails unless the HCM with candle's residual gives the same loads as `pair_load`
/// within 1e-5 relative, and candle's residual the core f32 network's outputs within
/// 1e-4 (the two tanh differ; see the module docs), at every peg state inside the
/// residual's envelope. Prints the comparison.
#[cfg(feature = "candle")]
fn check_same_function(fixture: &PegFixture<F32Weights>, candle: &CandleResidual) {
    println!("candle vs hcm_f32 (peg residual 13-32-32-6, same weights and normalisation):");
    println!("  state            residual rel. diff   HCM 8 points rel. diff");
    let physics = ContactModel::physics(fixture.hcm.normal.clone())
        .with_friction(fixture.hcm.friction.expect("the peg's PM2 has friction"));
    let mut checked = 0;
    for (components, name) in PEG_STATES.iter().zip(STATE_NAMES) {
        if !candle.envelope.contains(components) {
            continue;
        }
        let core = fixture.hcm.residual.evaluate(components);
        let other = candle.evaluate(components).unwrap();
        let residual = relative(&other, &core);
        let state = RigidState {
            components: *components,
        };
        let points = peg::eight_points(&state);
        let reference = state.position();
        let hcm = fixture
            .hcm
            .pair_load(&points, &reference, &Vector3::zeros(), components);
        let with_candle = pair_load_candle(&physics, candle, &points, &reference, components);
        assert_eq!(hcm.evaluated, Evaluated::PhysicsAndResidual, "{name}");
        assert_eq!(with_candle.evaluated, hcm.evaluated, "{name}");
        let wrench = |l: &PairLoad<f32>| {
            let w = &l.wrench;
            [w.force_1.as_slice(), w.torque_1.as_slice()].concat()
        };
        let load = relative(&wrench(&with_candle), &wrench(&hcm));
        println!("  {name:<16} {residual:19.2e}   {load:22.2e}");
        assert!(
            residual <= 1e-4,
            "{name}: residual {core:?} vs candle {other:?}"
        );
        assert!(load <= 1e-5, "{name}: HCM loads differ by {load:e}");
        checked += 1;
    }
    assert!(checked >= 4, "the wall states lie inside the envelope");
}

/// The peg's HCM (PM2 + the residual of `Q`), as the firmware decodes it.
fn fixture<Q: peg::PegWeights>() -> PegFixture<Q> {
    let network = peg::decode_network::<Q>().expect("the peg's blob decodes");
    PegFixture {
        hcm: peg::peg_hcm(network),
    }
}

/// The f32 network in candle, checked against the core first; candle reads
/// `RAYON_NUM_THREADS` at every matmul: single-threaded gemm throughout.
#[cfg(feature = "candle")]
fn candle_twin(hcm_f32: &PegFixture<F32Weights>) -> CandleResidual {
    std::env::set_var("RAYON_NUM_THREADS", "1");
    assert_eq!(candle_core::utils::get_num_threads(), 1);
    let candle = CandleResidual::from_core(&hcm_f32.hcm.residual).unwrap();
    check_same_function(hcm_f32, &candle);
    candle
}

fn bench_peg(c: &mut Criterion) {
    let hcm_f32 = fixture::<F32Weights>();
    let hcm_int8 = fixture::<Int8Weights>();
    #[cfg(feature = "candle")]
    let candle = candle_twin(&hcm_f32);

    let state = RigidState {
        components: PEG_STATES[STATE],
    };
    let input = state.components;
    let reference = state.position();
    let points = peg::eight_points(&state);
    #[cfg(feature = "candle")]
    let physics = ContactModel::physics(hcm_f32.hcm.normal.clone())
        .with_friction(hcm_f32.hcm.friction.unwrap());
    assert_eq!(peg::manifold(&state).len(), 4);
    let residual_runs = "the benchmarked state must run the residual";
    for evaluated in [
        peg::peg_load(&hcm_f32.hcm, &state).evaluated,
        peg::peg_load(&hcm_int8.hcm, &state).evaluated,
    ] {
        assert_eq!(evaluated, Evaluated::PhysicsAndResidual, "{residual_runs}");
    }
    #[cfg(feature = "candle")]
    assert_eq!(
        pair_load_candle(&physics, &candle, &points, &reference, &input).evaluated,
        Evaluated::PhysicsAndResidual,
        "{residual_runs}"
    );

    let mut group = c.benchmark_group("residual");
    group.bench_function("core_f32", |b| {
        b.iter(|| black_box(&hcm_f32.hcm.residual).evaluate(black_box(&input)))
    });
    group.bench_function("core_int8", |b| {
        b.iter(|| black_box(&hcm_int8.hcm.residual).evaluate(black_box(&input)))
    });
    #[cfg(feature = "candle")]
    group.bench_function("candle_1_thread", |b| {
        b.iter(|| black_box(&candle).evaluate(black_box(&input)).unwrap())
    });
    group.finish();

    let mut group = c.benchmark_group("pair_8_points");
    bench_pair_load(&mut group, "hcm_f32", &hcm_f32, &points, &reference, &input);
    bench_pair_load(
        &mut group, "hcm_int8", &hcm_int8, &points, &reference, &input,
    );
    #[cfg(feature = "candle")]
    group.bench_function("hcm_candle_1_thread", |b| {
        b.iter(|| {
            pair_load_candle(
                black_box(&physics),
                black_box(&candle),
                black_box(&points),
                black_box(&reference),
                black_box(&input),
            )
        })
    });
    group.finish();

    let mut group = c.benchmark_group("peg_load");
    group.bench_function("hcm_f32", |b| {
        b.iter(|| peg::peg_load(black_box(&hcm_f32.hcm), black_box(&state)))
    });
    group.bench_function("hcm_int8", |b| {
        b.iter(|| peg::peg_load(black_box(&hcm_int8.hcm), black_box(&state)))
    });
    group.finish();
}

/// `ContactModel::pair_load` of `fixture`'s HCM on `points`, timed as `name`.
fn bench_pair_load<Q: peg::PegWeights>(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    fixture: &PegFixture<Q>,
    points: &[ContactPoint<f32>],
    reference: &Vector3<f32>,
    input: &[f32; INPUTS],
) {
    group.bench_function(name, |b| {
        b.iter(|| {
            black_box(&fixture.hcm).pair_load(
                black_box(points),
                black_box(reference),
                &Vector3::zeros(),
                black_box(input),
            )
        })
    });
}

criterion_group!(benches, bench_peg);
criterion_main!(benches);
