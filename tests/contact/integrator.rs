//! The adaptive integrator (`hcm_core::integrate`) against exact solutions: accuracy
//! and its convergence with the tolerance, dense output, event location to 1e-12 s,
//! a microsecond contact inside a long flight, and failures that must end in an error
//! rather than a hang or a panic.
//!
//! Run with `--nocapture` to see the figures each test measured. The last test is a
//! property test: any settings, state, system coefficients and times (NaN and ±∞
//! included) end in `Ok` or an error, never a panic or a step past `until`.

use hcm_core::integrate::{locate_crossing, Dopri5, IntegrationError, OdeSystem, Settings};
use hcm_core::Real;
use proptest::prelude::*;

/// Harmonic oscillator x'' = −x, state [x, v]: x = cos t, v = −sin t from [1, 0].
struct Oscillator;

impl<T: Real> OdeSystem<T, [T; 2]> for Oscillator {
    fn derivative(&mut self, _time: T, y: &[T; 2], dy: &mut [T; 2]) {
        *dy = [y[1], -y[0]];
    }
}

/// Integrates the oscillator from [1, 0] at t = 0 to `until` (s); returns the stepper.
fn oscillate<T: Real>(tolerance: T, until: T) -> Dopri5<T, [T; 2]> {
    let settings = Settings::new(tolerance, tolerance);
    let mut stepper = Dopri5::new(&mut Oscillator, T::zero(), [T::one(), T::zero()], settings);
    while stepper.time() < until {
        stepper.step(&mut Oscillator, until).unwrap();
    }
    stepper
}

/// Largest end-state error (max over x, v) of the oscillator run to t = 10 s.
fn oscillator_error(tolerance: f64) -> (f64, u64) {
    let stepper = oscillate(tolerance, 10.0);
    let [x, v] = *stepper.state();
    let error = (x - 10.0_f64.cos()).abs().max((v + 10.0_f64.sin()).abs());
    (error, stepper.accepted_steps())
}

#[test]
fn harmonic_oscillator_end_state_and_convergence_with_tolerance() {
    let (tight, tight_steps) = oscillator_error(1e-10);
    println!("rtol = atol = 1e-10: end-state error {tight:.3e} in {tight_steps} steps");
    assert!(tight < 1e-8, "end-state error {tight:e}");

    let (loose, loose_steps) = oscillator_error(1e-6);
    let (fine, fine_steps) = oscillator_error(1e-9);
    let ratio = loose / fine;
    println!(
        "1e-6: error {loose:.3e} ({loose_steps} steps); 1e-9: error {fine:.3e} \
         ({fine_steps} steps); ratio {ratio:.0}"
    );
    assert!(ratio > 50.0, "error ratio {ratio}");
}

#[test]
fn dense_output_matches_the_exact_solution_inside_every_step() {
    let tolerance = 1e-8;
    let settings = Settings::new(tolerance, tolerance);
    let mut stepper = Dopri5::new(&mut Oscillator, 0.0, [1.0, 0.0], settings);
    let mut out = [0.0; 2];
    let (mut worst_global, mut worst_local, mut points) = (0.0_f64, 0.0_f64, 0);
    while stepper.time() < 10.0 {
        stepper.step(&mut Oscillator, 10.0).unwrap();
        let (t0, t1) = (stepper.previous_time(), stepper.time());
        let [x0, v0] = *stepper.previous_state();
        for i in 1..=12 {
            let t = t0 + (t1 - t0) * f64::from(i) / 13.0;
            stepper.dense_output(t, &mut out);
            // Against the exact solution of the problem (global error) …
            let global = (out[0] - t.cos()).abs().max((out[1] + t.sin()).abs());
            // … and against the exact solution through the step's start (the
            // interpolation error alone).
            let (c, s) = ((t - t0).cos(), (t - t0).sin());
            let local = (out[0] - (x0 * c + v0 * s))
                .abs()
                .max((out[1] - (v0 * c - x0 * s)).abs());
            worst_global = worst_global.max(global);
            worst_local = worst_local.max(local);
            points += 1;
        }
    }
    println!(
        "tolerance {tolerance:e}: {points} dense points in {} steps; worst error vs exact \
         solution {worst_global:.3e}, vs solution through the step start {worst_local:.3e}",
        stepper.accepted_steps()
    );
    assert!(worst_global < 10.0 * tolerance, "global {worst_global:e}");
    assert!(worst_local < tolerance, "local {worst_local:e}");
}

/// Free fall under gravity g (m/s²), state [z (m), v (m/s)].
struct Fall {
    gravity: f64,
}

impl OdeSystem<f64, [f64; 2]> for Fall {
    fn derivative(&mut self, _time: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        *dy = [y[1], -self.gravity];
    }
}

#[test]
fn event_location_finds_the_landing_of_a_falling_body_to_1e_12_s() {
    let mut fall = Fall { gravity: 9.81 };
    let settings = Settings::new(1e-12, 1e-14);
    let mut stepper = Dopri5::new(&mut fall, 0.0, [0.1, 0.0], settings);
    let mut scratch = [0.0; 2];
    let landing = loop {
        stepper.step(&mut fall, 1.0).unwrap();
        if let Some(t) = locate_crossing(&stepper, |_, y| y[0], 1e-13, &mut scratch) {
            break t;
        }
        assert!(stepper.time() < 1.0, "no landing found");
    };
    let exact = (2.0 * 0.1 / 9.81_f64).sqrt();
    let error = (landing - exact).abs();
    println!(
        "landing at {landing:.15} s, exact {exact:.15} s: error {error:.2e} s after {} steps",
        stepper.accepted_steps()
    );
    assert!(error <= 1e-12, "landing time error {error:e} s");
    // The located time is on the far side: z there is ≤ 0.
    stepper.dense_output(landing, &mut scratch);
    assert!(scratch[0] <= 0.0);
}

/// A 50 g ball on a linear penalty spring k·(−z) acting only for z < 0, under gravity,
/// state [z (m), v (m/s)].
struct PenaltyBall {
    mass: f64,
    stiffness: f64,
    gravity: f64,
}

impl OdeSystem<f64, [f64; 2]> for PenaltyBall {
    fn derivative(&mut self, _time: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        let [z, v] = *y;
        let spring = if z < 0.0 { -self.stiffness * z } else { 0.0 };
        *dy = [v, spring / self.mass - self.gravity];
    }

    /// Time to reach the plane at the current closing speed, floored at 0.1 µs.
    fn step_limit(&self, _time: f64, y: &[f64; 2]) -> f64 {
        let [z, v] = *y;
        if z > 0.0 && v < 0.0 {
            (z / -v).max(1e-7)
        } else {
            f64::MAX
        }
    }
}

#[test]
fn a_stiff_contact_inside_a_long_flight_is_found_and_timed() {
    let (mass, stiffness, gravity, height) = (0.05, 1e7, 9.81, 0.1);
    let mut ball = PenaltyBall {
        mass,
        stiffness,
        gravity,
    };
    let settings = Settings::new(1e-10, 1e-12);
    let mut stepper = Dopri5::new(&mut ball, 0.0, [height, 0.0], settings);
    let mut scratch = [0.0; 2];
    let until = 0.3; // after lift-off (≈ 0.143 s), before the next landing (≈ 0.428 s)
    let mut events = [0.0_f64; 2];
    let mut found = 0;
    while stepper.time() < until {
        stepper.step(&mut ball, until).unwrap();
        if let Some(t) = locate_crossing(&stepper, |_, y| y[0], 1e-13, &mut scratch) {
            assert!(found < 2, "a third crossing at {t} s");
            events[found] = t;
            found += 1;
            let mut at_event = [0.0; 2];
            stepper.dense_output(t, &mut at_event);
            stepper.restart(&mut ball, t, at_event);
        }
    }
    assert_eq!(found, 2, "touch-down and lift-off");
    let [touch_down, lift_off] = events;

    // Exact: the spring acts about the static sag d = m·g/k, so the contact lasts
    // (π + 2·atan(d·ω/v0))/ω, a little more than the half period π/ω.
    let omega = (stiffness / mass).sqrt();
    let impact_speed = (2.0 * gravity * height).sqrt();
    let sag = mass * gravity / stiffness;
    let exact_duration =
        (core::f64::consts::PI + 2.0 * (sag * omega / impact_speed).atan()) / omega;
    let half_period = core::f64::consts::PI * (mass / stiffness).sqrt();
    let exact_touch_down = (2.0 * height / gravity).sqrt();
    let duration = lift_off - touch_down;
    let steps = stepper.accepted_steps() + stepper.rejected_steps();
    println!(
        "touch-down {touch_down:.12} s (error {:.2e} s), contact {duration:.6e} s: \
         error {:.2e} s vs exact {exact_duration:.9e} s (π·sqrt(m/k) = {half_period:.9e} s \
         differs by {:.2e} s because of gravity); {} accepted + {} rejected = {steps} steps",
        (touch_down - exact_touch_down).abs(),
        (duration - exact_duration).abs(),
        exact_duration - half_period,
        stepper.accepted_steps(),
        stepper.rejected_steps(),
    );
    assert!((touch_down - exact_touch_down).abs() < 1e-9);
    assert!(
        (duration - exact_duration).abs() < 1e-9,
        "duration {duration:e} s"
    );
    assert!(steps < 5000, "{steps} steps");
}

/// y' = y², blowing up at t = 1 from y(0) = 1.
struct BlowUp;

impl OdeSystem<f64, [f64; 1]> for BlowUp {
    fn derivative(&mut self, _time: f64, y: &[f64; 1], dy: &mut [f64; 1]) {
        *dy = [y[0] * y[0]];
    }
}

#[test]
fn a_blow_up_and_a_step_budget_end_in_errors() {
    let mut stepper = Dopri5::new(&mut BlowUp, 0.0, [1.0], Settings::new(1e-8, 1e-8));
    let outcome = loop {
        if let Err(error) = stepper.step(&mut BlowUp, 2.0) {
            break error;
        }
        assert!(stepper.time() < 2.0, "integrated through the blow-up");
    };
    let steps = stepper.accepted_steps() + stepper.rejected_steps();
    println!(
        "blow-up: {outcome} (y = {:e}, {steps} steps)",
        stepper.state()[0]
    );
    match outcome {
        IntegrationError::StepTooSmall { time, step } => {
            assert!((time - 1.0).abs() < 1e-6 && step < 1e-15, "{time} {step}");
        }
        other => panic!("expected StepTooSmall, got {other:?}"),
    }

    let settings = Settings {
        max_steps: 100,
        ..Settings::new(1e-10, 1e-10)
    };
    let mut stepper = Dopri5::new(&mut Oscillator, 0.0, [1.0, 0.0], settings);
    let outcome = loop {
        if let Err(error) = stepper.step(&mut Oscillator, 1e4) {
            break error;
        }
    };
    println!("step budget: {outcome}");
    assert!(
        matches!(outcome, IntegrationError::TooManySteps { steps: 100, .. }),
        "{outcome:?}"
    );
    assert_eq!(stepper.accepted_steps() + stepper.rejected_steps(), 100);
}

/// A derivative that is NaN from `from` (s) on.
struct NanAfter {
    from: f64,
}

impl OdeSystem<f64, [f64; 2]> for NanAfter {
    fn derivative(&mut self, time: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        *dy = if time >= self.from {
            [f64::NAN, y[0]]
        } else {
            [1.0, y[0]]
        };
    }
}

#[test]
fn a_nan_derivative_is_reported_not_propagated() {
    // NaN from the start: the first step fails at once.
    let mut system = NanAfter { from: 0.0 };
    let mut stepper = Dopri5::new(&mut system, 0.0, [0.0, 0.0], Settings::new(1e-8, 1e-8));
    let outcome = stepper.step(&mut system, 1.0);
    println!("NaN at the start: {outcome:?}");
    assert_eq!(outcome, Err(IntegrationError::NonFinite { time: 0.0 }));

    // NaN from t = 0.5 s: steps shrink towards it, then NonFinite (not StepTooSmall).
    let mut system = NanAfter { from: 0.5 };
    let mut stepper = Dopri5::new(&mut system, 0.0, [0.0, 0.0], Settings::new(1e-8, 1e-8));
    let outcome = loop {
        if let Err(error) = stepper.step(&mut system, 1.0) {
            break error;
        }
    };
    println!(
        "NaN from 0.5 s: {outcome} after {} accepted, {} rejected steps",
        stepper.accepted_steps(),
        stepper.rejected_steps()
    );
    match outcome {
        IntegrationError::NonFinite { time } => assert!(time < 0.5 && time > 0.5 - 1e-12),
        other => panic!("expected NonFinite, got {other:?}"),
    }
    assert!(stepper.state().iter().all(|x| x.is_finite()));
}

#[test]
fn the_oscillator_integrates_in_f32() {
    let stepper = oscillate(1e-5_f32, 10.0);
    let [x, v] = *stepper.state();
    let error = (x - 10.0_f32.cos()).abs().max((v + 10.0_f32.sin()).abs());
    println!(
        "f32, rtol = atol = 1e-5: end-state error {error:.2e} in {} steps",
        stepper.accepted_steps()
    );
    assert!(error < 1e-3, "{error}");
}

#[test]
fn until_is_reached_exactly_and_not_passed() {
    let until = 1.2345;
    let mut stepper = Dopri5::new(&mut Oscillator, 0.0, [1.0, 0.0], Settings::new(1e-6, 1e-6));
    while stepper.time() < until {
        stepper.step(&mut Oscillator, until).unwrap();
        assert!(stepper.time() <= until);
    }
    assert_eq!(stepper.time(), until);
    let steps = stepper.accepted_steps();
    stepper.step(&mut Oscillator, until).unwrap();
    stepper.step(&mut Oscillator, 1.0).unwrap();
    assert_eq!((stepper.time(), stepper.accepted_steps()), (until, steps));
    println!("ended at exactly {} s after {steps} steps", stepper.time());
}

/// y' = [a·y₀ + b, −a·y₁] with a step limit, all arbitrary.
struct Linear {
    a: f64,
    b: f64,
    limit: f64,
}

impl OdeSystem<f64, [f64; 2]> for Linear {
    fn derivative(&mut self, _time: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        *dy = [self.a * y[0] + self.b, -self.a * y[1]];
    }

    fn step_limit(&self, _time: f64, _y: &[f64; 2]) -> f64 {
        self.limit
    }
}

/// Any float, biased towards the awkward ones and towards usable magnitudes.
fn awkward() -> impl Strategy<Value = f64> {
    prop_oneof![
        any::<f64>(),
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(f64::MAX),
        -10.0..10.0,
        1e-12..1e-3,
    ]
}

/// Mostly a usable value from `range`, sometimes an awkward one.
fn mostly(range: core::ops::Range<f64>) -> impl Strategy<Value = f64> {
    prop_oneof![4 => range, 1 => awkward()]
}

proptest! {
    // The test file lives outside the crate's directory, where proptest cannot place a
    // regressions file; a failure prints its minimal input instead.
    #![proptest_config(ProptestConfig {
        cases: 512,
        failure_persistence: None,
        ..ProptestConfig::default()
    })]

    #[test]
    fn nothing_panics_and_until_is_never_passed(
        (rtol, atol, initial, max_step, min_step) in
            (mostly(1e-12..1e-2), mostly(1e-12..1e-2), awkward(), mostly(1e-6..1e3), mostly(1e-18..1e-9)),
        max_steps in 0_u64..3000,
        (a, b, limit) in (mostly(-50.0..50.0), mostly(-10.0..10.0), awkward()),
        (t0, y0, y1) in (mostly(-10.0..10.0), mostly(-10.0..10.0), mostly(-10.0..10.0)),
        (until, probe, tolerance) in (mostly(-10.0..20.0), awkward(), mostly(1e-15..1e-3)),
    ) {
        let settings = Settings {
            relative_tolerance: rtol,
            absolute_tolerance: atol,
            initial_step: initial,
            max_step,
            min_step,
            max_steps,
        };
        let mut system = Linear { a, b, limit };
        let mut stepper = Dopri5::new(&mut system, t0, [y0, y1], settings);
        let mut scratch = [0.0; 2];
        for _ in 0..20 {
            let before = stepper.time();
            let outcome = stepper.step(&mut system, until);
            let _ = format!("{outcome:?}");
            if let Err(error) = outcome {
                let _ = format!("{error}");
                prop_assert_eq!(stepper.time().to_bits(), before.to_bits());
                break;
            }
            if before < until {
                prop_assert!(stepper.time() > before && stepper.time() <= until);
                prop_assert_eq!(stepper.previous_time(), before);
            } else {
                prop_assert_eq!(stepper.time().to_bits(), before.to_bits());
            }
            stepper.dense_output(probe, &mut scratch);
            let g = |t: f64, y: &[f64; 2]| y[0] - probe * t;
            if let Some(t) = locate_crossing(&stepper, g, tolerance, &mut scratch) {
                prop_assert!(t >= stepper.previous_time() && t <= stepper.time());
            }
        }
    }
}
