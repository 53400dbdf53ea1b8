//! Rigid-body dynamics (`hcm_core::rigid`, Eq 22) against exact solutions and
//! invariants: the tennis-racket flip of torque-free motion with angular momentum and
//! energy conserved, free fall, and a constant torque about a principal axis.
//!
//! Run with `--nocapture` to see the figures each test measured.

use hcm_core::integrate::{Dopri5, Settings};
use hcm_core::rigid::{step_unit, ConstantLoad, RigidBody, RigidState};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

/// Gravity (m/s², world frame).
const GRAVITY: Vector3<f64> = Vector3::new(0.0, 0.0, -9.81);

fn diagonal_body(inertia: [f64; 3], gravity: Vector3<f64>) -> RigidBody<f64> {
    let inertia = Matrix3::from_diagonal(&Vector3::from(inertia));
    RigidBody::new(0.37, inertia, gravity)
}

fn unloaded(body: RigidBody<f64>) -> ConstantLoad<f64> {
    ConstantLoad {
        body,
        force: Vector3::zeros(),
        torque: Vector3::zeros(),
    }
}

fn tilted() -> UnitQuaternion<f64> {
    UnitQuaternion::from_euler_angles(0.35, -0.26, 0.1)
}

/// Runs `system` from `start` to `until` (s) with `step_unit`, calling `watch` on every
/// accepted state; returns the stepper.
fn run(
    system: &mut ConstantLoad<f64>,
    start: RigidState<f64>,
    until: f64,
    settings: Settings<f64>,
    mut watch: impl FnMut(&RigidState<f64>),
) -> Dopri5<f64, RigidState<f64>> {
    let mut stepper = Dopri5::new(system, 0.0, start, settings);
    while stepper.time() < until {
        step_unit(&mut stepper, system, until).unwrap();
        watch(stepper.state());
    }
    stepper
}

#[test]
fn spin_near_the_intermediate_axis_flips_and_conserves_momentum_and_energy() {
    let body = diagonal_body([1.0, 2.0, 3.0], Vector3::zeros());
    let mut system = unloaded(body);
    // Mostly about the intermediate (y) axis, slightly perturbed (rad/s, body frame).
    let omega = Vector3::new(1e-3, 1.0, 1e-3);
    let start = RigidState::new(Vector3::zeros(), tilted(), Vector3::zeros(), omega);
    let momentum0 = body.angular_momentum(&start);
    let energy0 = body.kinetic_energy(&start);
    let (mut flips, mut sign) = (0, 1.0_f64);
    let (mut worst_momentum, mut worst_energy, mut worst_unit) = (0.0_f64, 0.0_f64, 0.0_f64);
    let mut flip_times = [0.0; 10];
    let mut projections = 0_usize;
    let mut stepper = Dopri5::new(&mut system, 0.0, start, Settings::new(1e-13, 1e-15));
    while flips < 10 && stepper.time() < 1e4 {
        step_unit(&mut stepper, &mut system, 1e4).unwrap();
        let state = stepper.state();
        let momentum = body.angular_momentum(state);
        worst_momentum = worst_momentum.max((momentum - momentum0).norm() / momentum0.norm());
        worst_energy = worst_energy.max((body.kinetic_energy(state) - energy0).abs() / energy0);
        worst_unit = worst_unit.max(state.quaternion_drift());
        // step_unit renormalises before the next step when this exceeds 4 ulps.
        projections += usize::from(state.quaternion_drift() > 4.0 * f64::EPSILON);
        let intermediate = state.body_angular_velocity().y;
        if intermediate * sign < 0.0 {
            flip_times[flips] = stepper.time();
            flips += 1;
            sign = -sign;
        }
    }
    println!(
        "tennis racket: {flips} flips by t = {:.1} s (at {flip_times:.1?}), {} accepted / {} rejected steps, \
         {projections} renormalisations; \
         max relative |ΔL| = {worst_momentum:.2e}, |ΔE| = {worst_energy:.2e}, |‖q‖−1| = {worst_unit:.2e}",
        stepper.time(),
        stepper.accepted_steps(),
        stepper.rejected_steps()
    );
    assert_eq!(
        flips, 10,
        "the intermediate-axis component must flip 10 times"
    );
    assert!(
        worst_momentum < 1e-9,
        "angular momentum drift {worst_momentum:e}"
    );
    assert!(worst_energy < 1e-9, "kinetic energy drift {worst_energy:e}");
    assert!(worst_unit < 1e-12, "quaternion norm drift {worst_unit:e}");
}

#[test]
fn a_spin_about_the_major_axis_does_not_flip() {
    // The counter-case: the same perturbation about the stable z axis stays bounded.
    let body = diagonal_body([1.0, 2.0, 3.0], Vector3::zeros());
    let mut system = unloaded(body);
    let omega = Vector3::new(1e-3, 1e-3, 1.0);
    let start = RigidState::new(Vector3::zeros(), tilted(), Vector3::zeros(), omega);
    let mut smallest = f64::MAX;
    run(
        &mut system,
        start,
        200.0,
        Settings::new(1e-12, 1e-14),
        |s| {
            smallest = smallest.min(s.body_angular_velocity().z);
        },
    );
    assert!(smallest > 0.99, "major-axis spin dropped to {smallest}");
}

#[test]
fn free_fall_is_the_exact_parabola() {
    let body = diagonal_body([1.0, 2.0, 3.0], GRAVITY);
    let mut system = unloaded(body);
    let (p0, v0) = (Vector3::new(0.0, 0.0, 0.15), Vector3::new(0.5, 0.0, -1.0));
    let omega = Vector3::new(2.0, -3.0, 1.0);
    let start = RigidState::new(p0, tilted(), v0, omega);
    let mut worst = 0.0_f64;
    let mut time = 0.0;
    let mut stepper = Dopri5::new(&mut system, 0.0, start, Settings::new(1e-12, 1e-14));
    while time < 2.0 {
        time = (time + 0.1_f64).min(2.0);
        while stepper.time() < time {
            step_unit(&mut stepper, &mut system, time).unwrap();
        }
        let exact = p0 + v0 * time + GRAVITY * (0.5 * time * time);
        worst = worst.max((stepper.state().position() - exact).norm());
        let exact_velocity = v0 + GRAVITY * time;
        assert!((stepper.state().velocity() - exact_velocity).norm() < 1e-12);
    }
    println!(
        "free fall: max |p − (p0 + v0·t − ½g·t²)| = {worst:.2e} m over 2 s, {} steps",
        stepper.accepted_steps()
    );
    assert!(worst < 1e-12, "free-fall position error {worst:e} m");
}

#[test]
fn a_constant_torque_about_a_principal_axis_gives_a_linear_spin_up() {
    let inertia = [1.0, 2.0, 3.0];
    let body = diagonal_body(inertia, Vector3::zeros());
    let start = RigidState::new(
        Vector3::zeros(),
        tilted(),
        Vector3::zeros(),
        Vector3::zeros(),
    );
    let torque = 0.6; // N·m about the body's z axis, given in the world frame
    let mut system = ConstantLoad {
        body,
        force: Vector3::zeros(),
        torque: tilted() * Vector3::new(0.0, 0.0, torque),
    };
    let stepper = run(&mut system, start, 5.0, Settings::new(1e-12, 1e-14), |_| {});
    let t = stepper.time();
    let expected = Vector3::new(0.0, 0.0, torque / inertia[2] * t);
    let worst = (stepper.state().body_angular_velocity() - expected).norm();
    // The axis stays fixed in the world while the body turns θ = ½·(T/I)·t² about it.
    let turned =
        tilted() * UnitQuaternion::from_euler_angles(0.0, 0.0, 0.5 * torque / inertia[2] * t * t);
    let angle = stepper.state().orientation().angle_to(&turned);
    println!(
        "constant torque: |ω − T/I·t| = {worst:.2e} rad/s at t = {t} s, orientation error {angle:.2e} rad, {} steps",
        stepper.accepted_steps()
    );
    assert!(worst < 1e-12, "spin-up error {worst:e} rad/s");
    assert!(angle < 1e-9, "orientation error {angle:e} rad");
}
