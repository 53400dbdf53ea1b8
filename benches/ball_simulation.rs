//! Whole simulations with the shipped defaults, each including event location, peak
//! search and sampling the trajectory: the 1D bouncing ball (drop, contact, lift-off),
//! and the 3D peg-in-hole (two wall contacts and the bottom, IMPACT + STEP friction
//! at up to 8 points), the cube drop (0.4 s of bouncing, tumbling and sliding) and one
//! cube toss (the shipped scenario's), and the elbow toss (two links on a hinge held by
//! constraint forces, each link's vertices on the table), so that one run gives their
//! ratios.
//!
//! Run: `cargo bench -p hcm-tests --bench ball_simulation`

use criterion::{criterion_group, criterion_main, Criterion};
use hcm_host::scenario::{Model, Scenario};
use hcm_host::simulate::simulate;
use std::hint::black_box;
use std::path::Path;

fn shipped(name: &str) -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(name);
    Scenario::load(&path, &[]).unwrap().resolve(&path).unwrap()
}

fn bench_simulations(c: &mut Criterion) {
    for (label, file) in [
        ("bouncing_ball_simulation", "bouncing_ball.toml"),
        ("peg_in_hole_simulation", "peg_in_hole.toml"),
        ("cube_drop_simulation", "cube_drop.toml"),
        ("cube_toss_simulation", "cube_toss.toml"),
        ("elbow_toss_simulation", "elbow_toss.toml"),
    ] {
        let model = shipped(file);
        c.bench_function(label, |b| b.iter(|| simulate(black_box(&model)).unwrap()));
    }
}

criterion_group!(benches, bench_simulations);
criterion_main!(benches);
