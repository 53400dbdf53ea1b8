//! `lsq` vs `ga` on the same data: time per identification (criterion) and the fit
//! each reaches (printed once: force RMS over the samples, curve RMS of the replay).
//!
//! Data: 20 noisy runs of the shipped bouncing ball (seed 1), PM2 = Lankarani–Nikravesh,
//! GA with the CLI defaults (population 60, 150 generations, curve fitness).
//! Run: `cargo bench -p hcm-tests --bench identification`

use criterion::{criterion_group, criterion_main, Criterion};
use hcm_host::experiment::generate;
use hcm_host::identify::Fitness;
use hcm_host::identify::{identify, Method};
use hcm_host::numerics::optimize::GeneticSettings;
use hcm_host::scenario::Scenario;
use std::path::Path;
use std::time::Duration;

fn bench_identification(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/bouncing_ball.toml");
    let scenario = Scenario::load(&path, &[]).unwrap();
    let model = scenario.model().unwrap();
    let data = generate(&scenario, 20, 1, &hcm_host::progress::Silent).unwrap();
    let ga = Method::Ga(
        Fitness::Curve,
        GeneticSettings {
            population: 60,
            generations: 150,
            seed: 1,
            ..GeneticSettings::default()
        },
    );
    let methods = [("lsq", Method::Lsq), ("ga", ga)];
    // `cargo bench` passes `--bench`; `cargo test` runs each benchmark once without it,
    // and that one run already checks the fits: the printed fits (one more
    // identification each) only under `cargo bench`.
    let benchmarking = std::env::args().any(|a| a == "--bench");
    for (name, method) in methods.iter().filter(|_| benchmarking) {
        let fit = identify(
            &scenario,
            &model,
            &data,
            0,
            "lankarani_nikravesh",
            method.clone(),
            &hcm_host::progress::Silent,
        )
        .unwrap()
        .fit;
        eprintln!(
            "{name}: force RMS {:.4} N, curve RMS {:.4} N, {:.3} s",
            fit.force_rms, fit.curve_rms, fit.seconds
        );
    }
    let mut group = c.benchmark_group("identify_lankarani_nikravesh_ball_20_runs");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(30));
    for (name, method) in methods {
        group.bench_function(name, |b| {
            b.iter(|| {
                identify(
                    &scenario,
                    &model,
                    &data,
                    0,
                    "lankarani_nikravesh",
                    method.clone(),
                    &hcm_host::progress::Silent,
                )
                .unwrap()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_identification);
criterion_main!(benches);
