//! One whole bouncing-ball simulation (drop, contact, lift-off) with the shipped
//! defaults, including event location, peak search and sampling the trajectory.
//!
//! Run: `cargo bench -p hcm-tests --bench ball_simulation`

use criterion::{criterion_group, criterion_main, Criterion};
use hcm_host::scenario::Scenario;
use hcm_host::simulate::simulate;
use std::hint::black_box;
use std::path::Path;

fn bench_ball(c: &mut Criterion) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/bouncing_ball.toml");
    let model = Scenario::load(&path, &[]).unwrap().resolve(&path).unwrap();
    c.bench_function("bouncing_ball_simulation", |b| {
        b.iter(|| simulate(black_box(&model)).unwrap())
    });
}

criterion_group!(benches, bench_ball);
criterion_main!(benches);
