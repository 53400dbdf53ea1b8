//! The independent reference solver for the cube drop (`scenarios/cube_drop.toml`,
//! `hcm_tests::rigid_reference`) checked on its own: it converges when its step is
//! halved, flies the exact parabola with constant angular momentum until touch-down,
//! never gains energy, and brings the cube to rest on a face at the static indentation
//! (by 1.2 s: at the scenario's 0.4 s it is still tumbling). Convergence and energy are
//! also checked on a second body with a full inertia tensor and other parameters. Also
//! unit tests of `compare`, the helper that measures hcm's output against the reference.
//!
//! Run with `--nocapture` to see the figures each test measured.

use hcm_tests::rigid_reference::{
    angular_momentum, compare, cube_drop, energy, simulate, tossed_plate, vertices, Case, Sample,
    Trajectory,
};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
use std::sync::OnceLock;
use std::time::Instant;

/// The reference step (s). RK4's error shrinks as h⁴, but the contact and friction
/// forces have kinks (the max(0, ·) clip, touch-down and lift-off of each vertex) where
/// it falls back to a lower order. Measured on the cube drop against a run at 2.5e-7 s,
/// the final orientation is off by 0.11° at 4e-5 s, 0.038° at 2e-5 s, 0.0069° at 1e-5 s
/// and 6e-5° at this step, which halving moves by 5e-6° (asserted below). 0.4 s takes
/// 160 000 steps, about 45 ms in the test profile (opt-level 1).
const STEP: f64 = 2.5e-6;

/// When the dropped cube rests (s), found by running on past the scenario's 0.4 s.
const SETTLED: f64 = 1.2;

/// Largest energy rise between samples that rounding may cause, relative to the
/// initial energy (–); measured rises stay below 1e-13 J on 0.8–2.7 J.
const ENERGY_ROUNDING: f64 = 1e-12;

fn run(case: &Case, step: f64) -> Trajectory {
    let start = Instant::now();
    let trajectory = simulate(case, step);
    println!(
        "{} steps of {step:e} s in {:.0} ms",
        trajectory.steps,
        start.elapsed().as_secs_f64() * 1e3
    );
    trajectory
}

/// The cube drop at the reference step, run once for all the tests.
fn reference() -> &'static Trajectory {
    static TRAJECTORY: OnceLock<Trajectory> = OnceLock::new();
    TRAJECTORY.get_or_init(|| run(&cube_drop(), STEP))
}

fn final_sample(trajectory: &Trajectory) -> &Sample {
    trajectory.samples.last().unwrap()
}

/// The poses of `trajectory` in `compare`'s input form: times, positions, quaternions.
fn poses(trajectory: &[Sample]) -> (Vec<f64>, Vec<[f64; 3]>, Vec<[f64; 4]>) {
    let times = trajectory.iter().map(|s| s.time).collect();
    let positions = trajectory.iter().map(|s| s.position.into()).collect();
    let quaternions = trajectory
        .iter()
        .map(|s| {
            let q = s.quaternion();
            [q.w, q.i, q.j, q.k]
        })
        .collect();
    (times, positions, quaternions)
}

/// The final pose's and the run's worst change (m, rad) when the step is halved.
fn halving(case: &Case, coarse: &Trajectory) -> [(f64, f64); 2] {
    let fine = run(case, STEP / 2.0);
    let (times, positions, quaternions) = poses(&fine.samples);
    let last = times.len() - 1;
    let whole = compare(&coarse.samples, &times, &positions, &quaternions);
    let at_end = compare(
        &coarse.samples,
        &times[last..],
        &positions[last..],
        &quaternions[last..],
    );
    println!(
        "step {STEP:e} s vs {:e} s: the final pose moves {:.2e} m, {:.2e}°; \
         the worst over the run {:.2e} m, {:.2e}°",
        STEP / 2.0,
        at_end.0,
        at_end.1.to_degrees(),
        whole.0,
        whole.1.to_degrees()
    );
    [at_end, whole]
}

#[test]
fn halving_the_step_moves_the_pose_by_less_than_a_hundredth_of_a_millimetre() {
    let trajectory = reference();
    let last = final_sample(trajectory);
    let (roll, pitch, yaw) = last.quaternion().euler_angles();
    println!(
        "cube drop: touch-down {:?} s; at {} s position {:.6?} m, \
         orientation Rz({yaw:.6})·Ry({pitch:.6})·Rx({roll:.6}), velocity {:.6?} m/s, \
         angular velocity {:.6?} rad/s",
        trajectory.touch_down,
        last.time,
        last.position.as_slice(),
        last.velocity.as_slice(),
        last.angular_velocity.as_slice()
    );
    let plate = tossed_plate();
    let cases = [
        (cube_drop(), trajectory.clone()),
        (plate, run(&plate, STEP)),
    ];
    for (case, coarse) in &cases {
        for (position, angle) in halving(case, coarse) {
            assert!(position < 1e-5, "the position moved {position} m");
            assert!(
                angle.to_degrees() < 0.01,
                "the orientation moved {angle} rad"
            );
        }
    }
}

/// The exact free flight from the case's initial state: the parabola, and for an
/// isotropic inertia a constant ω, so R(t) = exp(t·[ω]×)·R(0).
fn free_flight(case: &Case, time: f64) -> (Vector3<f64>, Matrix3<f64>) {
    let position = case.position + case.velocity * time + case.gravity * (0.5 * time * time);
    let turn = Rotation3::new(case.angular_velocity * time);
    (position, turn.matrix() * case.rotation)
}

#[test]
fn before_touch_down_the_cube_flies_the_exact_parabola_with_constant_momentum() {
    let case = cube_drop();
    let trajectory = reference();
    let touch_down = trajectory.touch_down.expect("the cube touches down");
    let momentum0 = angular_momentum(&case, &case.rotation, &case.angular_velocity);
    let (mut position_error, mut velocity_error) = (0.0_f64, 0.0_f64);
    let (mut rotation_error, mut momentum_error) = (0.0_f64, 0.0_f64);
    let flight = trajectory
        .samples
        .iter()
        .take_while(|s| s.time < touch_down);
    for sample in flight {
        let (position, rotation) = free_flight(&case, sample.time);
        let velocity = case.velocity + case.gravity * sample.time;
        let momentum = angular_momentum(&case, &sample.rotation, &sample.angular_velocity);
        position_error = position_error.max((sample.position - position).norm());
        velocity_error = velocity_error.max((sample.velocity - velocity).norm());
        rotation_error = rotation_error.max((sample.rotation - rotation).norm());
        momentum_error = momentum_error.max((momentum - momentum0).norm() / momentum0.norm());
    }
    // The exact touch-down: the lowest vertex of the exact flight reaches z = 0.
    let lowest = |time: f64| {
        let (position, rotation) = free_flight(&case, time);
        let corners = vertices(&case.half_extents, &position, &rotation);
        corners.iter().map(|v| v.z).fold(f64::INFINITY, f64::min)
    };
    let (mut before, mut after) = (0.0, touch_down);
    for _ in 0..60 {
        let middle = 0.5 * (before + after);
        if lowest(middle) > 0.0 {
            before = middle;
        } else {
            after = middle;
        }
    }
    println!(
        "free flight until {touch_down} s (exact touch-down {after:.9} s): errors position \
         {position_error:.1e} m, velocity {velocity_error:.1e} m/s, rotation \
         {rotation_error:.1e}, angular momentum {momentum_error:.1e} relative"
    );
    // Exact up to the rounding of some 21 600 steps.
    assert!(position_error < 1e-12 && velocity_error < 1e-11);
    assert!(rotation_error < 1e-12 && momentum_error < 1e-13);
    assert!(
        after <= touch_down && touch_down - after < STEP,
        "touch-down reported at {touch_down} s, exact {after} s"
    );
}

/// The largest rise of the energy between samples (J), and the first and last energy (J).
fn energy_rise(case: &Case, samples: &[Sample]) -> (f64, f64, f64) {
    let energies: Vec<f64> = samples.iter().map(|s| energy(case, s)).collect();
    let rise = energies
        .windows(2)
        .map(|pair| pair[1] - pair[0])
        .fold(f64::NEG_INFINITY, f64::max);
    (rise, energies[0], *energies.last().unwrap())
}

#[test]
fn the_energy_never_increases() {
    let plate = tossed_plate();
    let cases = [
        (cube_drop(), reference().clone()),
        (plate, run(&plate, STEP)),
    ];
    for (case, trajectory) in &cases {
        let (rise, first, last) = energy_rise(case, &trajectory.samples);
        println!(
            "energy {first:.6} J → {last:.6} J at {} s; largest rise between samples {rise:.1e} J",
            case.end_time
        );
        assert!(
            rise < ENERGY_ROUNDING * first,
            "the energy rose by {rise} J"
        );
        assert!(
            last < 0.8 * first,
            "the contacts dissipated too little: {last} J"
        );
    }
}

/// The static indentation of a box resting on a face, each of its 4 lower vertices
/// carrying m·g/4: δ = (m·g/(4·k))^(1/e) (m).
fn resting_indentation(case: &Case) -> f64 {
    let load = case.mass * case.gravity.norm() / 4.0;
    (load / case.impact.stiffness).powf(1.0 / case.impact.exponent)
}

#[test]
fn the_cube_comes_to_rest_on_a_face_at_the_static_indentation() {
    // At the scenario's 0.4 s the cube is still tumbling (it bounces on its corners: the
    // IMPACT damping of 50 N·s/m returns most of the energy); it rests from about 0.85 s.
    let mut case = cube_drop();
    case.end_time = SETTLED;
    case.sample_period = 1e-2;
    let trajectory = run(&case, STEP);
    let last = final_sample(&trajectory);
    let mut depths: Vec<f64> = vertices(&case.half_extents, &last.position, &last.rotation)
        .iter()
        .map(|vertex| -vertex.z)
        .collect();
    depths.sort_by(f64::total_cmp);
    let expected = resting_indentation(&case);
    let speed = last.velocity.norm();
    let spin = last.angular_velocity.norm();
    println!(
        "at {SETTLED} s: indentations of the lowest four vertices {} m (static {expected:.4e} m), \
         speed {speed:.1e} m/s, angular speed {spin:.1e} rad/s",
        depths[4..]
            .iter()
            .map(|d| format!("{d:.4e}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    assert!(
        depths[..4].iter().all(|&d| d < -0.09),
        "not on a face: {depths:?}"
    );
    for depth in &depths[4..] {
        assert!(
            (depth / expected - 1.0).abs() < 1e-3,
            "indentation {depth} m"
        );
    }
    assert!(
        speed < 1e-5 && spin < 1e-4,
        "still moving: {speed} m/s, {spin} rad/s"
    );
}

#[test]
fn compare_measures_the_largest_position_and_angle_errors() {
    let samples = &reference().samples;
    let (times, positions, quaternions) = poses(samples);
    let (position, angle) = compare(samples, &times, &positions, &quaternions);
    assert!(
        position == 0.0 && angle < 1e-12,
        "{position} m, {angle} rad against itself"
    );

    // Shifted by 0.5 mm at one sample, turned by 0.7° at another, with the quaternion's
    // sign flipped at every other sample (q and −q are the same orientation).
    let (mut shifted, mut turned) = (positions.clone(), quaternions.clone());
    shifted[100][0] += 3e-4;
    shifted[100][1] -= 4e-4;
    let turn = UnitQuaternion::from_axis_angle(&Vector3::y_axis(), 0.7_f64.to_radians());
    let q = turn * samples[250].quaternion();
    turned[250] = [q.w, q.i, q.j, q.k];
    for quaternion in turned.iter_mut().step_by(2) {
        *quaternion = quaternion.map(|component| -component);
    }
    let (position, angle) = compare(samples, &times, &shifted, &turned);
    println!(
        "shifted 0.5 mm, turned 0.7°: measured {position:.6e} m, {:.9}°",
        angle.to_degrees()
    );
    assert!((position - 5e-4).abs() < 1e-12);
    assert!((angle.to_degrees() - 0.7).abs() < 1e-9);
}

#[test]
fn compare_interpolates_between_the_reference_samples() {
    // Off the 1 ms grid in free flight, the cubic Hermite position and the geodesic
    // orientation are exact: the flight is a parabola at a constant ω.
    let case = cube_drop();
    let samples = &reference().samples;
    let times: Vec<f64> = (0..50).map(|k| 1e-3 * k as f64 + 3.7e-4).collect();
    let (positions, quaternions): (Vec<[f64; 3]>, Vec<[f64; 4]>) = times
        .iter()
        .map(|&time| {
            let (position, rotation) = free_flight(&case, time);
            let q = UnitQuaternion::from_matrix(&rotation);
            let position: [f64; 3] = position.into();
            (position, [q.w, q.i, q.j, q.k])
        })
        .unzip();
    let (position, angle) = compare(samples, &times, &positions, &quaternions);
    println!("between samples in free flight: {position:.1e} m, {angle:.1e} rad");
    assert!(position < 1e-12 && angle < 1e-10);
}

#[test]
#[should_panic(expected = "outside the reference's span")]
fn compare_refuses_a_time_past_the_reference() {
    let samples = &reference().samples;
    compare(samples, &[0.401], &[[0.0; 3]], &[[1.0, 0.0, 0.0, 0.0]]);
}
