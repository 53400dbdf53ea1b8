//! The summed-rows trainer (`hcm_host::train::train_summed`, behind the contact-frame
//! residual): a function seen only through weighted sums of its values at several points
//! is learned, the same weights on one thread as on several. (Moved from the library's
//! unit tests: at their opt-level 0 it took 17 s.)

use hcm_host::train::{train_summed, SummedRow, TrainSettings};

/// Rows of one to three points on a line, each point's output y(x) = sin(3x)
/// pushed through a lever that differs per point; the network must recover y from
/// the sums alone.
#[test]
fn a_function_seen_only_through_sums_of_its_values_is_learned() {
    let truth = |x: f64| (3.0 * x).sin();
    let rows: Vec<SummedRow> = (0..600)
        .map(|i| {
            let count = 1 + i % 3;
            let points: Vec<(Vec<f64>, Vec<f64>)> = (0..count)
                .map(|j| {
                    let x = ((i * 7 + j * 13) % 97) as f64 / 48.0 - 1.0;
                    (vec![x], vec![1.0 + j as f64, 0.5 - x])
                })
                .collect();
            let target = (0..2)
                .map(|t| points.iter().map(|(x, l)| l[t] * truth(x[0])).sum())
                .collect();
            SummedRow { points, target }
        })
        .collect();
    let settings = TrainSettings {
        width: 16,
        max_epochs: 400,
        learning_rate: 5e-3,
        seed: 3,
        ..TrainSettings::default()
    };
    let (network, report, unfelt) = train_summed(&rows, 1, &settings, |_, _, _| {}).unwrap();
    assert!(unfelt.is_empty());
    for x in [-0.9, -0.3, 0.2, 0.8] {
        let y = network.evaluate(&[x])[0];
        assert!((y - truth(x)).abs() < 0.05, "y({x}) = {y} vs {}", truth(x));
    }
    assert!(report.validation_loss < 2e-3, "{report:?}");
    // The same seed, the same weights, whatever the thread count.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let (again, _, _) = pool
        .install(|| train_summed(&rows, 1, &settings, |_, _, _| {}))
        .unwrap();
    assert_eq!(again.layers, network.layers);
}
