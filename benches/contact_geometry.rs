//! Contact generation time: one box–box manifold (a cube tilted a little on a slab, a
//! face contact clipped to 4 points) and one box–plane manifold (a cube on an edge, 2
//! points), in f64 (host) and f32 (controller).
//!
//! Run: `cargo bench -p hcm-tests --bench contact_geometry`

use criterion::{criterion_group, criterion_main, Criterion};
use hcm_core::geometry::{box_box, box_plane, Cuboid};
use hcm_core::Real;
use nalgebra::{UnitQuaternion, Vector3};
use std::hint::black_box;

/// A 0.1 m cube turned 0.3 rad about z and tilted 5 mrad about x, 0.5 mm into a
/// 0.4 × 0.4 × 0.1 m slab.
fn cube_on_slab<T: Real>() -> (Cuboid<T>, Cuboid<T>) {
    let cube = Cuboid {
        half_extents: Vector3::repeat(T::of(0.05)),
        center: Vector3::new(T::of(0.01), T::of(-0.02), T::of(0.1 - 5e-4)),
        orientation: UnitQuaternion::from_euler_angles(T::of(0.005), T::zero(), T::of(0.3)),
    };
    let slab = Cuboid {
        half_extents: Vector3::new(T::of(0.2), T::of(0.2), T::of(0.05)),
        center: Vector3::zeros(),
        orientation: UnitQuaternion::identity(),
    };
    (cube, slab)
}

/// The same cube on an edge (45° about x), 1 mm into the plane z = 0.
fn cube_on_edge<T: Real>() -> Cuboid<T> {
    Cuboid {
        half_extents: Vector3::repeat(T::of(0.05)),
        center: Vector3::new(
            T::zero(),
            T::zero(),
            T::of(0.05 * core::f64::consts::SQRT_2 - 1e-3),
        ),
        orientation: UnitQuaternion::from_euler_angles(
            T::of(core::f64::consts::FRAC_PI_4),
            T::zero(),
            T::zero(),
        ),
    }
}

fn bench_in<T: Real>(c: &mut Criterion, precision: &str) {
    let mut group = c.benchmark_group(format!("contact_geometry_{precision}"));
    let (cube, slab) = cube_on_slab::<T>();
    assert_eq!(box_box::contacts(&cube, &slab).len(), 4, "a face contact");
    group.bench_function("box_box_face_tilted", |b| {
        b.iter(|| box_box::contacts(black_box(&cube), black_box(&slab)))
    });
    let edge = cube_on_edge::<T>();
    let (origin, up) = (Vector3::zeros(), Vector3::z());
    assert_eq!(
        box_plane::contacts(&edge, &origin, &up).len(),
        2,
        "an edge contact"
    );
    group.bench_function("box_plane_edge", |b| {
        b.iter(|| box_plane::contacts(black_box(&edge), black_box(&origin), black_box(&up)))
    });
    group.finish();
}

fn bench_contact_geometry(c: &mut Criterion) {
    bench_in::<f64>(c, "f64");
    bench_in::<f32>(c, "f32");
}

criterion_group!(benches, bench_contact_geometry);
criterion_main!(benches);
