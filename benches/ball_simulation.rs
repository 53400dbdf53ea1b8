//! Whole simulations with the shipped defaults, each including event location, peak
//! search and sampling the trajectory: the 1D bouncing ball (drop, contact, lift-off),
//! and the 3D peg-in-hole (two wall contacts and the bottom, IMPACT + STEP friction
//! at up to 8 points), the cube drop (0.4 s of bouncing, tumbling and sliding) and one
//! cube toss (the shipped scenario's), and the elbow toss (two links on a hinge held by
//! constraint forces, each link's vertices on the table), so that one run gives their
//! ratios. Then what the joints cost a scene without any (group `joint_path`): the cube
//! toss and the peg-in-hole simulated by the derivative that holds the joints' loads
//! (what `simulate` runs) and by its twin with them compiled out (the derivative before
//! joints), both in this one run; the two give the same run, checked first.
//!
//! Run: `cargo bench -p hcm-tests --bench ball_simulation`

use criterion::{criterion_group, criterion_main, Criterion};
use hcm_host::scenario::{Model, Scenario};
use hcm_host::simulate::{simulate, simulate_on_path};
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

/// The joint path's cost on scenes without joints: the same simulation with the joints'
/// loads in the derivative (`with_joint_path`, `simulate`'s) and compiled out
/// (`without_joint_path`).
fn bench_joint_path(c: &mut Criterion) {
    let mut group = c.benchmark_group("joint_path");
    for (label, file) in [
        ("cube_toss", "cube_toss.toml"),
        ("peg_in_hole", "peg_in_hole.toml"),
    ] {
        let model = shipped(file);
        assert!(model.joints.is_empty(), "{file} has no joint");
        let (with, without) = (
            simulate_on_path::<true>(&model).unwrap().run,
            simulate_on_path::<false>(&model).unwrap().run,
        );
        assert_eq!(
            format!("{with:?}"),
            format!("{without:?}"),
            "{file}: the same run"
        );
        group.bench_function(format!("{label}/with_joint_path"), |b| {
            b.iter(|| simulate_on_path::<true>(black_box(&model)).unwrap())
        });
        group.bench_function(format!("{label}/without_joint_path"), |b| {
            b.iter(|| simulate_on_path::<false>(black_box(&model)).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench_simulations, bench_joint_path);
criterion_main!(benches);
