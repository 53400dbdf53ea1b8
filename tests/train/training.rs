//! Residual training: fitting known functions, learning a damping the physics law
//! lacks from noisy samples, determinism, early stopping, bad data, and speed.

use hcm_core::law::{AnyNormalLaw, Indentation, LankaraniNikravesh, NormalLaw};
use hcm_core::model::ContactModel;
use hcm_host::dataset::ForceSample;
use hcm_host::train::{residual_pairs, train, Network, TrainError, TrainReport, TrainSettings};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

type Rows = Vec<Vec<f64>>;

/// A standard normal draw (Box–Muller).
fn gaussian(rng: &mut ChaCha8Rng) -> f64 {
    let u1 = 1.0 - rng.random::<f64>(); // (0, 1]
    let u2 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

fn quiet(
    inputs: &[Vec<f64>],
    targets: &[Vec<f64>],
    settings: &TrainSettings,
) -> Result<(Network, TrainReport), TrainError> {
    train(inputs, targets, settings, |_, _, _| {})
}

/// y = 0.5·sin(3x) + 0.1·x² on `n` evenly spaced x ∈ [−1, 1].
fn sine_rows(n: usize) -> (Rows, Rows) {
    (0..n)
        .map(|i| {
            let x = -1.0 + 2.0 * i as f64 / (n - 1) as f64;
            (vec![x], vec![0.5 * (3.0 * x).sin() + 0.1 * x * x])
        })
        .unzip()
}

#[test]
fn fits_a_smooth_function_of_one_input() {
    let (inputs, targets) = sine_rows(2000);
    let (network, report) = quiet(&inputs, &targets, &TrainSettings::default()).unwrap();
    println!(
        "sine: validation MSE {:.3e}, train MSE {:.3e}, best epoch {} of {}, {:.2} s",
        report.validation_loss, report.train_loss, report.best_epoch, report.epochs, report.seconds
    );
    assert!(report.validation_loss < 1e-3, "{}", report.validation_loss);
    // Between the training points too.
    let worst = (0..997)
        .map(|i| -0.99 + 1.98 * i as f64 / 996.0)
        .map(|x| (network.evaluate(&[x])[0] - (0.5 * (3.0 * x).sin() + 0.1 * x * x)).abs())
        .fold(0.0, f64::max);
    println!("sine: worst error between grid points {worst:.3e}");
    assert!(worst < 0.02, "{worst}");
}

#[test]
fn fits_a_function_with_two_inputs_and_two_outputs() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let function = |a: f64, b: f64| vec![0.5 * (2.0 * a).sin() * b.cos(), a * b + 0.2 * b];
    let (inputs, targets): (Rows, Rows) = (0..2000)
        .map(|_| {
            let (a, b) = (rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0));
            (vec![a, b], function(a, b))
        })
        .unzip();
    let (network, report) = quiet(&inputs, &targets, &TrainSettings::default()).unwrap();
    println!(
        "two outputs: validation MSE {:.3e}, best epoch {} of {}",
        report.validation_loss, report.best_epoch, report.epochs
    );
    assert!(report.validation_loss < 1e-3, "{}", report.validation_loss);
    assert_eq!(network.evaluate(&[0.3, -0.4]).len(), 2);
}

/// The law the synthetic data are built on: the reconstruction's PM2 for the ball.
fn pm2() -> AnyNormalLaw<f64> {
    LankaraniNikravesh {
        stiffness: 7.203e9,
        exponent: 1.494,
        restitution: 0.9276,
    }
    .into()
}

/// Damping the law lacks (N·s/m^2.5): c·δ^1.5·δ̇, up to ≈ 150 N at the fastest impact.
const MISSING_DAMPING: f64 = 1.5e9;

fn correction(depth: f64, rate: f64) -> f64 {
    MISSING_DAMPING * depth.powf(1.5) * rate
}

/// `impacts` × `per_impact` samples along half-sine impacts: δ̇0 ∈ [0.2, 1.4] m/s,
/// δ_max = 30 µm·(δ̇0/1.4)^0.8, δ = δ_max·sin θ, δ̇ = δ̇0·cos θ; measured force = PM2 +
/// the missing damping + `noise`·ζ (N).
fn impact_samples(
    rng: &mut ChaCha8Rng,
    impacts: usize,
    per_impact: usize,
    noise: f64,
) -> Vec<ForceSample> {
    let law = pm2();
    let mut samples = Vec::with_capacity(impacts * per_impact);
    for _ in 0..impacts {
        let approach_speed = rng.random_range(0.2..1.4);
        let max_depth = 3e-5 * (approach_speed / 1.4_f64).powf(0.8);
        for _ in 0..per_impact {
            let phase = rng.random_range(0.0..std::f64::consts::PI);
            let state = Indentation {
                depth: max_depth * phase.sin(),
                rate: approach_speed * phase.cos(),
                approach_speed,
            };
            let force = law.normal_force(&state)
                + correction(state.depth, state.rate)
                + noise * gaussian(rng);
            samples.push(ForceSample {
                depth: state.depth,
                rate: state.rate,
                approach_speed,
                max_depth,
                force,
            });
        }
    }
    samples
}

#[test]
fn learns_a_damping_the_law_lacks_well_below_the_noise() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let samples = impact_samples(&mut rng, 1000, 20, 15.0);
    let (inputs, targets) = residual_pairs(&samples, &ContactModel::physics(pm2()));
    let (network, report) = quiet(&inputs, &targets, &TrainSettings::default()).unwrap();

    let held_out = impact_samples(&mut rng, 200, 20, 0.0);
    let (mut sum, mut largest) = (0.0, 0.0_f64);
    for s in &held_out {
        let truth = correction(s.depth, s.rate);
        let error = network.evaluate(&[s.depth, s.rate, s.approach_speed])[0] - truth;
        sum += error * error;
        largest = largest.max(truth.abs());
    }
    let rms = (sum / held_out.len() as f64).sqrt();
    println!(
        "residual: RMS error against the true correction {rms:.2} N (noise σ 15 N, largest correction {largest:.0} N); \
         validation MSE {:.1} N², best epoch {} of {}, {:.2} s",
        report.validation_loss, report.best_epoch, report.epochs, report.seconds
    );
    assert!(
        largest > 100.0,
        "the test's correction is too small: {largest}"
    );
    assert!(rms < 5.0, "RMS error {rms} N");
}

/// Every weight and bias as bits.
fn bits(network: &Network) -> Vec<u64> {
    network
        .layers
        .iter()
        .flat_map(|(w, b)| w.iter().chain(b).map(|v| v.to_bits()))
        .collect()
}

#[test]
fn same_seed_gives_bit_identical_weights_whatever_the_thread_count() {
    let (inputs, targets) = sine_rows(1000);
    let settings = TrainSettings {
        max_epochs: 15,
        batch_size: 100, // > CHUNK_ROWS: exercises the parallel reduction
        seed: 3,
        ..TrainSettings::default()
    };
    let on_threads = |threads: usize, settings: &TrainSettings| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| quiet(&inputs, &targets, settings).unwrap())
    };
    let (one, one_report) = on_threads(1, &settings);
    let (two, two_report) = on_threads(2, &settings);
    assert_eq!(bits(&one), bits(&two));
    assert_eq!(one_report.history, two_report.history);
    let (again, _) = quiet(&inputs, &targets, &settings).unwrap();
    assert_eq!(bits(&one), bits(&again));

    let other = TrainSettings {
        seed: 4,
        ..settings
    };
    let (different, _) = quiet(&inputs, &targets, &other).unwrap();
    assert_ne!(bits(&one), bits(&different));
}

#[test]
fn early_stopping_keeps_the_best_epoch() {
    // Pure noise: nothing to learn, so the validation loss soon stops improving.
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let (inputs, targets): (Rows, Rows) = (0..60)
        .map(|_| (vec![rng.random_range(-1.0..1.0)], vec![gaussian(&mut rng)]))
        .unzip();
    let settings = TrainSettings {
        patience: 3,
        max_epochs: 1000,
        batch_size: 8,
        learning_rate: 1e-2,
        validation_fraction: 0.25,
        seed: 1,
        ..TrainSettings::default()
    };
    let (network, report) = quiet(&inputs, &targets, &settings).unwrap();
    println!(
        "early stopping: stopped after {} epochs, best {}",
        report.epochs, report.best_epoch
    );
    assert!(report.epochs < settings.max_epochs);
    assert_eq!(report.epochs, report.best_epoch + settings.patience);
    let lowest = report
        .history
        .iter()
        .map(|h| h.1)
        .fold(f64::INFINITY, f64::min);
    assert_eq!(report.validation_loss, lowest);
    assert_eq!(
        report.validation_loss,
        report.history[report.best_epoch - 1].1
    );

    // The returned weights are those after the best epoch: training exactly that long
    // (same seed, same draws) ends on the same bits.
    let up_to_best = TrainSettings {
        max_epochs: report.best_epoch,
        patience: 0,
        ..settings
    };
    let (replayed, _) = quiet(&inputs, &targets, &up_to_best).unwrap();
    assert_eq!(bits(&network), bits(&replayed));
}

#[test]
fn bad_data_and_settings_are_errors() {
    let settings = TrainSettings::default();
    let (inputs, targets) = sine_rows(50);
    assert!(matches!(
        quiet(&[], &[], &settings),
        Err(TrainError::NoData)
    ));

    let mut ragged = inputs.clone();
    ragged[7].push(1.0);
    let error = quiet(&ragged, &targets, &settings).unwrap_err();
    assert!(
        matches!(error, TrainError::RaggedRow { row: 7, .. }),
        "{error}"
    );

    let mut with_nan = targets.clone();
    with_nan[12][0] = f64::NAN;
    let error = quiet(&inputs, &with_nan, &settings).unwrap_err();
    assert!(error.to_string().contains("target row 12"), "{error}");

    let error = quiet(&inputs, &targets[..49], &settings).unwrap_err();
    assert!(
        matches!(error, TrainError::RowCountMismatch { .. }),
        "{error}"
    );

    let zero_batch = TrainSettings {
        batch_size: 0,
        ..TrainSettings::default()
    };
    let error = quiet(&inputs, &targets, &zero_batch).unwrap_err();
    assert!(error.to_string().contains("batch_size"), "{error}");

    let four_layers = TrainSettings {
        hidden_layers: 4,
        ..TrainSettings::default()
    };
    let error = quiet(&inputs, &targets, &four_layers).unwrap_err();
    assert!(error.to_string().contains("hidden_layers"), "{error}");

    let error = quiet(&inputs[..1], &targets[..1], &settings).unwrap_err();
    assert!(matches!(error, TrainError::TooFewRows { .. }), "{error}");
}

#[test]
fn speed_of_100_000_residual_pairs_with_the_defaults() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let samples = impact_samples(&mut rng, 5000, 20, 15.0);
    let (inputs, targets) = residual_pairs(&samples, &ContactModel::physics(pm2()));
    let (_, report) = quiet(&inputs, &targets, &TrainSettings::default()).unwrap();
    println!(
        "speed: {} pairs, {} epochs (best {}), {:.2} s, {:.2} ms per epoch, validation RMS {:.2} N",
        inputs.len(),
        report.epochs,
        report.best_epoch,
        report.seconds,
        1e3 * report.seconds / report.epochs as f64,
        report.validation_loss.sqrt()
    );
}

#[test]
fn the_int8_twin_beats_plain_rounding_and_exports_exactly() {
    use hcm_core::residual::{decode, Int8Weights, Mlp, Quantisation};
    use hcm_host::export::encode;
    use hcm_host::train::quantisation_aware;
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let samples = impact_samples(&mut rng, 300, 20, 0.0);
    let (inputs, targets) = residual_pairs(&samples, &ContactModel::physics(pm2()));
    let settings = TrainSettings {
        max_epochs: 60,
        ..TrainSettings::default()
    };
    let (teacher, _) = quiet(&inputs, &targets, &settings).unwrap();
    let (twin, report) = quantisation_aware(&teacher, &inputs, 5, 1, |_, _| {}).unwrap();
    println!(
        "int8 twin: RMS to the teacher {:.3} N plainly rounded, {:.3} N tuned (worst {:.3} N)",
        report.rounded_rms, report.tuned_rms, report.tuned_max
    );
    assert!(
        report.tuned_rms < 0.5 * report.rounded_rms,
        "fine-tuning gained too little: {report:?}"
    );
    // Same shape, normalisation and envelope; only the weights moved.
    assert_eq!(
        (&twin.input_mean, &twin.envelope_max),
        (&teacher.input_mean, &teacher.envelope_max)
    );
    // Its hidden weights sit on their int8 levels, so the int8 blob stores it
    // exactly: the core reproduces the host twin to f32 rounding.
    let blob = encode(&twin, Quantisation::Int8).unwrap();
    let core: Mlp<3, 16, 1, 2, Int8Weights> = decode(&blob).unwrap();
    let scale = targets.iter().map(|t| t[0].abs()).fold(0.0, f64::max);
    for x in inputs.iter().step_by(97) {
        let host = twin.evaluate(x)[0];
        let [y] = core.evaluate(&[x[0] as f32, x[1] as f32, x[2] as f32]);
        assert!(
            (f64::from(y) - host).abs() < 1e-5 * scale,
            "core {y} vs host {host} at {x:?}"
        );
    }
}

/// Two outputs with one cause: the force error and the moment error it makes about
/// a point 5 mm off the contact normal, plus a rate term of its own (N·m).
fn force_and_moment(s: &ForceSample) -> [f64; 2] {
    let force = correction(s.depth, s.rate);
    [force, 0.005 * force + 0.05 * s.rate]
}

#[test]
fn output_nets_joint_and_per_output() {
    use hcm_host::train::OutputNets;
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let samples = impact_samples(&mut rng, 400, 20, 0.0);
    let inputs: Vec<Vec<f64>> = samples
        .iter()
        .map(|s| vec![s.depth, s.rate, s.approach_speed])
        .collect();
    // Measured = truth + noise: σ 15 N on the force, 0.05 N·m on the moment.
    let targets: Vec<Vec<f64>> = samples
        .iter()
        .map(|s| {
            let [f, m] = force_and_moment(s);
            vec![f + 15.0 * gaussian(&mut rng), m + 0.05 * gaussian(&mut rng)]
        })
        .collect();
    let held_out = impact_samples(&mut rng, 100, 20, 0.0);
    let mut rms = Vec::new();
    for output_nets in [OutputNets::Joint, OutputNets::PerOutput] {
        let settings = TrainSettings {
            output_nets,
            ..TrainSettings::default()
        };
        let (network, report) = quiet(&inputs, &targets, &settings).unwrap();
        let mut sums = [0.0; 2];
        for s in &held_out {
            let y = network.evaluate(&[s.depth, s.rate, s.approach_speed]);
            let truth = force_and_moment(s);
            for o in 0..2 {
                sums[o] += (y[o] - truth[o]).powi(2);
            }
        }
        let r = sums.map(|v| (v / held_out.len() as f64).sqrt());
        let parameters: usize = network.layers.iter().map(|(w, b)| w.len() + b.len()).sum();
        println!(
            "{output_nets:?}: held-out RMS against the truth {:.2} N, {:.4} N·m; {parameters} parameters, {} epochs, {:.2} s",
            r[0], r[1], report.epochs, report.seconds
        );
        rms.push(r);
        if output_nets == OutputNets::PerOutput {
            // The merged network's output o is exactly the network trained on column o.
            let column: Vec<Vec<f64>> = targets.iter().map(|t| vec![t[1]]).collect();
            let (alone, _) = quiet(&inputs, &column, &TrainSettings::default()).unwrap();
            for x in inputs.iter().step_by(211) {
                let (merged, part) = (network.evaluate(x)[1], alone.evaluate(x)[0]);
                assert!(
                    (merged - part).abs() <= 1e-12 * part.abs().max(1.0),
                    "{merged} vs {part}"
                );
            }
        }
    }
    // Both strategies learn both outputs well below their noise.
    for r in &rms {
        assert!(r[0] < 5.0 && r[1] < 0.02, "{rms:?}");
    }
}
