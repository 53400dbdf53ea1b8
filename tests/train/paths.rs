//! The toss forecast as a distribution of paths (`hcm_host::replay::forecast_paths`),
//! judged by the energy score frame by frame: one member without spread is the single
//! replay, its scores the toss errors `hcm predict` prints, bit for bit; on simulated
//! tosses whose contact scatters by 30 % from toss to toss, ensembles that scatter the
//! contact as much score better than the single replay, toss by toss, and their bands
//! are calibrated: they hold the recorded coordinates as often as bands of M members
//! hold an outcome drawn like them (the level, or their range's (M − 1)/(M + 1)); the draws do not
//! depend on the thread count.

use hcm_host::replay::{band_shares, evaluate_tosses, forecast_paths, summarize_paths, Spread};

#[test]
fn an_ensemble_of_a_scattered_contact_scores_better_than_the_replay_it_reduces_to() {
    let model = hcm_tests::cube_toss_scattered(0.3);
    let data = hcm_tests::scattered_tosses(&model, 30, 7);
    let replay = Spread::replay();
    let single = forecast_paths(&model, &data, replay, || {}).unwrap();
    let evaluations = evaluate_tosses(&model, &data, || {}).unwrap();
    for (forecast, evaluation) in single.iter().zip(&evaluations) {
        let score = &evaluation.score;
        assert_eq!(forecast.frames, score.frames);
        assert_eq!(forecast.position.to_bits(), score.position_error.to_bits());
        assert_eq!(forecast.rotation.to_bits(), score.rotation_error.to_bits());
    }
    let spread = Spread {
        members: 16,
        inflation: Some(1.0),
        scatter: Some(0.3),
        seed: 1,
    };
    let ensemble = forecast_paths(&model, &data, spread, || {}).unwrap();
    let gains: Vec<f64> = (single.iter().zip(&ensemble))
        .map(|(one, many)| one.score() - many.score())
        .collect();
    let gain = hcm_host::replay::Summary::of(&gains);
    let standard_error = gain.std / (gain.count as f64).sqrt();
    let (one, many) = (summarize_paths(&single), summarize_paths(&ensemble));
    println!(
        "replay {:.2} % + {:.2}°, ensemble {:.2} % + {:.2}°; gain {:.2} ± {:.2} per toss; \
         coverage of the 50 % and 90 % bands: replay {:?}, ensemble {:?}",
        one.position.mean,
        one.rotation.mean,
        many.position.mean,
        many.rotation.mean,
        gain.mean,
        standard_error,
        band_shares(&one.coverage),
        band_shares(&many.coverage)
    );
    assert!(ensemble.iter().all(|f| f.members + f.failed == 16));
    assert!(
        gain.mean > 2.0 * standard_error,
        "the ensemble gains {} ± {standard_error} per toss",
        gain.mean
    );
    // 16 members: 0.5 and 0.882 (their range) for a calibrated ensemble.
    for (share, level) in band_shares(&many.coverage).into_iter().zip([0.5, 0.9]) {
        let calibrated = hcm_host::numerics::scores::calibrated_coverage(16, level);
        assert!((share - calibrated).abs() < 0.08, "{share} vs {calibrated}");
    }
    // The same draws on one thread as on two.
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let again = pool.install(|| forecast_paths(&model, &data, spread, || {}).unwrap());
    assert_eq!(again, ensemble);
}
