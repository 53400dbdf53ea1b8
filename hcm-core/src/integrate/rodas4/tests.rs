use super::*;
use crate::integrate::{locate_crossing, Dopri5, OdeSystem};

/// A two-component system with its exact Jacobian; W⁻¹ kept as an explicit 2×2
/// inverse.
trait Exact {
    fn f(&self, t: f64, y: &[f64; 2]) -> [f64; 2];
    fn jacobian(&self, t: f64, y: &[f64; 2]) -> [[f64; 2]; 2];
    fn time_rate(&self, _t: f64, _y: &[f64; 2]) -> [f64; 2] {
        [0.0; 2]
    }
}

struct Solver<E> {
    exact: E,
    jacobian: [[f64; 2]; 2],
    inverse: [[f64; 2]; 2],
    evaluations: usize,
}

impl<E: Exact> Solver<E> {
    fn new(exact: E) -> Self {
        Solver {
            exact,
            jacobian: [[0.0; 2]; 2],
            inverse: [[0.0; 2]; 2],
            evaluations: 0,
        }
    }
}

impl<E: Exact> OdeSystem<f64, [f64; 2]> for Solver<E> {
    fn derivative(&mut self, t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        self.evaluations += 1;
        *dy = self.exact.f(t, y);
    }
}

impl<E: Exact> LinearlyImplicit<f64, [f64; 2]> for Solver<E> {
    fn jacobian(&mut self, t: f64, y: &[f64; 2], _: &[f64; 2], time_rate: &mut [f64; 2]) {
        self.jacobian = self.exact.jacobian(t, y);
        *time_rate = self.exact.time_rate(t, y);
    }

    fn factor(&mut self, d: f64) -> bool {
        let j = self.jacobian;
        let (a, b, c, e) = (d - j[0][0], -j[0][1], -j[1][0], d - j[1][1]);
        let det = a * e - b * c;
        self.inverse = [[e / det, -b / det], [-c / det, a / det]];
        det != 0.0 && det.is_finite()
    }

    fn solve(&self, rhs: &mut [f64; 2]) {
        let m = self.inverse;
        *rhs = [
            m[0][0] * rhs[0] + m[0][1] * rhs[1],
            m[1][0] * rhs[0] + m[1][1] * rhs[1],
        ];
    }
}

/// The pendulum θ'' = −sin θ (nonlinear, not stiff).
struct Pendulum;
impl Exact for Pendulum {
    fn f(&self, _: f64, y: &[f64; 2]) -> [f64; 2] {
        [y[1], -y[0].sin()]
    }
    fn jacobian(&self, _: f64, y: &[f64; 2]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-y[0].cos(), 0.0]]
    }
}

/// Prothero–Robinson y' = λ(y − sin t) + cos t, λ = −1e6 (stiff; y = sin t), and a
/// second, non-stiff component z' = cos t · z (z = e^{sin t}): explicit t-dependence.
struct ProtheroRobinson;
const LAMBDA: f64 = -1e6;
impl Exact for ProtheroRobinson {
    fn f(&self, t: f64, y: &[f64; 2]) -> [f64; 2] {
        [LAMBDA * (y[0] - t.sin()) + t.cos(), t.cos() * y[1]]
    }
    fn jacobian(&self, t: f64, _: &[f64; 2]) -> [[f64; 2]; 2] {
        [[LAMBDA, 0.0], [0.0, t.cos()]]
    }
    fn time_rate(&self, t: f64, y: &[f64; 2]) -> [f64; 2] {
        [-LAMBDA * t.cos() - t.sin(), -t.sin() * y[1]]
    }
}

/// Fixed steps of `h` (s) up to `end` (s): tolerances so loose that every step is
/// accepted at the cap.
fn fixed_steps<E: Exact>(exact: E, y0: [f64; 2], h: f64, end: f64) -> [f64; 2] {
    let mut system = Solver::new(exact);
    let settings = Settings {
        max_step: h,
        initial_step: h,
        ..Settings::new(1e6, 1e6)
    };
    let mut stepper = Rodas4::new(&mut system, 0.0, y0, settings);
    while stepper.time() < end {
        stepper.step(&mut system, end).unwrap();
    }
    *stepper.state()
}

#[test]
fn global_error_falls_as_h_to_the_fourth() {
    let y0 = [1.0, 0.0];
    let mut reference = Dopri5::new(&mut Pend, 0.0, y0, Settings::new(1e-14, 1e-15));
    reference.step(&mut Pend, 2.0).unwrap();
    while reference.time() < 2.0 {
        reference.step(&mut Pend, 2.0).unwrap();
    }
    let exact = *reference.state();
    let error = |h: f64| {
        let y = fixed_steps(Pendulum, y0, h, 2.0);
        (y[0] - exact[0]).hypot(y[1] - exact[1])
    };
    let (coarse, fine) = (error(0.04), error(0.02));
    let order = (coarse / fine).log2();
    assert!(
        (3.7..4.6).contains(&order),
        "{coarse:e} {fine:e}: order {order}"
    );
}

/// The pendulum for Dopri5 (the reference).
struct Pend;
impl OdeSystem<f64, [f64; 2]> for Pend {
    fn derivative(&mut self, t: f64, y: &[f64; 2], dy: &mut [f64; 2]) {
        *dy = Pendulum.f(t, y);
    }
}

#[test]
fn explicit_time_dependence_keeps_the_order() {
    let error = |h: f64| {
        let y = fixed_steps(ProtheroRobinson, [0.0, 1.0], h, 1.0);
        (y[1] - 1.0_f64.sin().exp()).abs()
    };
    let order = (error(0.05) / error(0.025)).log2();
    assert!((3.6..4.8).contains(&order), "order {order}");
}

#[test]
fn a_stiff_problem_takes_steps_of_its_smooth_solution() {
    let mut system = Solver::new(ProtheroRobinson);
    let mut stepper = Rodas4::new(&mut system, 0.0, [0.0, 1.0], Settings::new(1e-8, 1e-10));
    let mut worst: f64 = 0.0;
    while stepper.time() < 1.0 {
        stepper.step(&mut system, 1.0).unwrap();
        worst = worst.max((stepper.state()[0] - stepper.time().sin()).abs());
    }
    // An explicit method would need |λ|·1 s / 3.3 ≈ 300 000 steps.
    let steps = stepper.accepted_steps() + stepper.rejected_steps();
    assert!(steps < 300, "{steps} steps");
    assert!(worst < 1e-8, "{worst:e}");
    assert!((stepper.state()[1] - 1.0_f64.sin().exp()).abs() < 1e-7);
    assert!(system.evaluations <= 6 * steps as usize + 1);
}

#[test]
fn dense_output_is_third_order_and_exact_at_the_ends() {
    let worst = |h: f64| {
        let mut system = Solver::new(Pendulum);
        let settings = Settings {
            max_step: h,
            initial_step: h,
            ..Settings::new(1e6, 1e6)
        };
        let mut stepper = Rodas4::new(&mut system, 0.0, [1.0, 0.0], settings);
        stepper.step(&mut system, 1.0).unwrap();
        let mut out = [0.0; 2];
        stepper.dense_output(0.0, &mut out);
        assert_eq!(out, [1.0, 0.0]);
        stepper.dense_output(h, &mut out);
        assert_eq!(&out, stepper.state());
        // The local error of the interpolant at mid-step against a one-step
        // reference there (the step's own error is O(h⁵), the interpolant's O(h⁴)).
        let mut reference = Dopri5::new(&mut Pend, 0.0, [1.0, 0.0], Settings::new(1e-14, 1e-15));
        while reference.time() < h / 2.0 {
            reference.step(&mut Pend, h / 2.0).unwrap();
        }
        stepper.dense_output(h / 2.0, &mut out);
        (out[0] - reference.state()[0]).hypot(out[1] - reference.state()[1])
    };
    let order = (worst(0.2) / worst(0.1)).log2();
    assert!(order > 3.6, "local interpolation order {order}");
}

#[test]
fn events_are_located_in_its_steps() {
    // The pendulum from rest at 1 rad first crosses θ = 0 at a quarter period.
    let mut system = Solver::new(Pendulum);
    let mut stepper = Rodas4::new(&mut system, 0.0, [1.0, 0.0], Settings::new(1e-10, 1e-12));
    let mut scratch = [0.0; 2];
    let crossing = loop {
        stepper.step(&mut system, 5.0).unwrap();
        if let Some(t) = locate_crossing(&stepper, |_, y| y[0], 1e-12, &mut scratch) {
            break t;
        }
    };
    // Quarter period of a pendulum of amplitude 1 rad: K(m = sin² 0.5) by the AGM.
    assert!(
        (crossing - 1.674_993_916_092_613_3).abs() < 1e-8,
        "{crossing}"
    );
}

/// f is NaN beyond t = 0.5 s.
struct Broken;
impl Exact for Broken {
    fn f(&self, t: f64, y: &[f64; 2]) -> [f64; 2] {
        if t > 0.5 {
            [f64::NAN; 2]
        } else {
            [y[1], -y[0]]
        }
    }
    fn jacobian(&self, _: f64, _: &[f64; 2]) -> [[f64; 2]; 2] {
        [[0.0, 1.0], [-1.0, 0.0]]
    }
}

/// J makes W singular for every step.
struct Singular;
impl Exact for Singular {
    fn f(&self, _: f64, y: &[f64; 2]) -> [f64; 2] {
        [y[1], y[0]]
    }
    fn jacobian(&self, _: f64, _: &[f64; 2]) -> [[f64; 2]; 2] {
        [[f64::NAN, 0.0], [0.0, 0.0]]
    }
}

#[test]
fn nan_and_singular_systems_are_errors_not_panics() {
    let mut broken = Solver::new(Broken);
    let mut stepper = Rodas4::new(&mut broken, 0.0, [1.0, 0.0], Settings::new(1e-8, 1e-10));
    let result = loop {
        match stepper.step(&mut broken, 1.0) {
            Ok(()) if stepper.time() < 1.0 => {}
            other => break other,
        }
    };
    assert!(
        matches!(result, Err(IntegrationError::NonFinite { .. })),
        "{result:?}"
    );
    assert!(stepper.time() <= 0.5);

    let mut singular = Solver::new(Singular);
    let mut stepper = Rodas4::new(&mut singular, 0.0, [1.0, 0.0], Settings::new(1e-8, 1e-10));
    let result = stepper.step(&mut singular, 1.0);
    assert!(
        matches!(result, Err(IntegrationError::NonFinite { .. })),
        "{result:?}"
    );
    assert_eq!(stepper.time(), 0.0);
}

/// A copy made by `clone_from` into a stepper at another point answers dense output
/// and steps on exactly as the original does, for both steppers.
#[test]
fn a_copy_by_clone_from_is_the_same_stepper() {
    let mut system = Solver::new(Pendulum);
    let settings = Settings::new(1e-8, 1e-10);
    let mut implicit = Rodas4::new(&mut system, 0.0, [1.0, 0.0], settings);
    let mut explicit = Dopri5::new(&mut system, 0.0, [1.0, 0.0], settings);
    implicit.step(&mut system, 1.0).unwrap();
    explicit.step(&mut system, 1.0).unwrap();
    let mut implicit_copy = Rodas4::new(&mut system, 5.0, [0.3, 0.2], settings);
    let mut explicit_copy = Dopri5::new(&mut system, 5.0, [0.3, 0.2], settings);
    implicit_copy.clone_from(&implicit);
    explicit_copy.clone_from(&explicit);
    let (mut a, mut b) = ([0.0; 2], [0.0; 2]);
    for s in [0.0, 0.25, 0.5, 1.0] {
        let t = implicit.previous_time() + s * (implicit.time() - implicit.previous_time());
        implicit.dense_output(t, &mut a);
        implicit_copy.dense_output(t, &mut b);
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "RODAS at {t}");
        let t = explicit.previous_time() + s * (explicit.time() - explicit.previous_time());
        explicit.dense_output(t, &mut a);
        explicit_copy.dense_output(t, &mut b);
        assert_eq!(a.map(f64::to_bits), b.map(f64::to_bits), "Dopri5 at {t}");
    }
    for _ in 0..3 {
        implicit.step(&mut system, 2.0).unwrap();
        implicit_copy.step(&mut system, 2.0).unwrap();
        explicit.step(&mut system, 2.0).unwrap();
        explicit_copy.step(&mut system, 2.0).unwrap();
    }
    assert_eq!(implicit.state(), implicit_copy.state());
    assert_eq!(explicit.state(), explicit_copy.state());
    assert_eq!(implicit.accepted_steps(), implicit_copy.accepted_steps());
    assert_eq!(explicit.rejected_steps(), explicit_copy.rejected_steps());
}
