//! Per-contact evaluation time: one f32 evaluation of each law at the reference
//! parameters, mid-contact (δ = 10 µm, δ̇ = 1 m/s, δ̇0 = 1.4 m/s).
//!
//! Run: `cargo bench -p hcm-tests --bench law_evaluation`

use criterion::{criterion_group, criterion_main, Criterion};
use hcm_core::friction::VelocityStepFriction;
use hcm_core::law::{Indentation, NormalLaw};
use hcm_core::wrench::ContactWrench;
use hcm_tests::reference;
use nalgebra::Vector3;
use std::hint::black_box;

fn bench_normal_laws(c: &mut Criterion) {
    let mut group = c.benchmark_group("normal_force_f32");
    let state = Indentation {
        depth: 10e-6_f32,
        rate: 1.0,
        approach_speed: 1.4,
    };
    for law in reference::all_laws::<f32>() {
        group.bench_function(law.name(), |b| {
            b.iter(|| black_box(law).normal_force(black_box(&state)))
        });
    }
    group.finish();
}

fn bench_friction_and_wrench(c: &mut Criterion) {
    let friction = VelocityStepFriction {
        static_coefficient: 0.3_f32,
        dynamic_coefficient: 0.1,
        stiction_speed: 1e-4,
        dynamic_speed: 1e-2,
    };
    let (velocity, normal) = (Vector3::new(0.02_f32, -0.01, 0.3), Vector3::z());
    let mut group = c.benchmark_group("tangential_f32");
    group.bench_function("velocity_step_friction", |b| {
        b.iter(|| black_box(friction).force(black_box(&velocity), black_box(&normal), 250.0))
    });
    let (friction_force, arm) = (
        Vector3::new(-20.0_f32, 5.0, 0.0),
        Vector3::new(0.0, 0.0, -0.0127),
    );
    group.bench_function("contact_wrench", |b| {
        b.iter(|| {
            ContactWrench::assemble(
                black_box(250.0_f32),
                black_box(&normal),
                black_box(&friction_force),
                &arm,
                &Vector3::zeros(),
            )
        })
    });
    group.finish();
}

criterion_group!(benches, bench_normal_laws, bench_friction_and_wrench);
criterion_main!(benches);
