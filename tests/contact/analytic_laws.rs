//! The contact laws against analytic results, by integrating them in a one-body
//! impact: a ball of mass m meets a fixed plane at speed v, no gravity, m·δ̈ = −f_n.

use hcm_core::friction::VelocityStepFriction;
use hcm_core::integrate::hermite_zero;
use hcm_core::law::{step, AnyNormalLaw, Indentation, LankaraniNikravesh, NormalLaw};
use hcm_core::wrench::ContactWrench;
use hcm_tests::reference::{self, BALL_MASS, IMPACT_SPEED};
use nalgebra::Vector3;

/// What one integrated impact produced.
struct Impact {
    max_depth: f64,
    max_force: f64,
    duration: f64,
    restitution: f64,
}

/// Integrates one impact with classical RK4 at `steps_per_contact` steps over the
/// Hertz contact time, locating lift-off (δ = 0) by cubic Hermite interpolation.
fn integrate_impact(law: &impl NormalLaw<f64>, mass: f64, speed: f64) -> Impact {
    let force = |depth: f64, rate: f64| {
        law.normal_force(&Indentation {
            depth,
            rate,
            approach_speed: speed,
        })
    };
    let acceleration = |y: [f64; 2]| [y[1], -force(y[0], y[1]) / mass];
    let k = reference::hertz_stiffness::<f64>();
    let hertz_time = 2.94 * (5.0 * mass * speed * speed / (4.0 * k)).powf(0.4) / speed;
    let h = hertz_time / 40_000.0;
    let (mut y, mut t) = ([0.0, speed], 0.0);
    let (mut max_depth, mut max_force) = (0.0_f64, 0.0_f64);
    for _ in 0..400_000 {
        let k1 = acceleration(y);
        let k2 = acceleration([y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]]);
        let k3 = acceleration([y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]]);
        let k4 = acceleration([y[0] + h * k3[0], y[1] + h * k3[1]]);
        let next = [
            y[0] + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
            y[1] + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
        ];
        if next[0] <= 0.0 && t > 0.0 {
            let (d0, d1, r0, r1) = (y[0], next[0], y[1], next[1]);
            let s = hermite_zero(h, (d0, r0), (d1, r1));
            let exit_speed = -(r0 + s * (r1 - r0));
            return Impact {
                max_depth,
                max_force,
                duration: t + s * h,
                restitution: exit_speed / speed,
            };
        }
        y = next;
        t += h;
        max_depth = max_depth.max(y[0]);
        max_force = max_force.max(force(y[0], y[1]));
    }
    panic!("the contact never ended");
}

fn relative_error(value: f64, expected: f64) -> f64 {
    ((value - expected) / expected).abs()
}

#[test]
fn hertz_impact_matches_the_closed_forms() {
    let law = reference::hertz::<f64>();
    let k = law.stiffness;
    let (m, v) = (BALL_MASS, IMPACT_SPEED);
    let max_depth = (5.0 * m * v * v / (4.0 * k)).powf(0.4);
    let max_force = k * max_depth.powf(1.5);
    let duration = 2.9433 * max_depth / v;
    let impact = integrate_impact(&law, m, v);
    assert!(
        relative_error(impact.max_depth, max_depth) < 1e-3,
        "δmax {}",
        impact.max_depth
    );
    assert!(
        relative_error(impact.max_force, max_force) < 1e-3,
        "Fmax {}",
        impact.max_force
    );
    assert!(
        relative_error(impact.duration, duration) < 1e-3,
        "T {}",
        impact.duration
    );
}

#[test]
fn hertz_restitution_is_one() {
    for speed in [0.1, 1.4007, 5.0] {
        let impact = integrate_impact(&reference::hertz::<f64>(), BALL_MASS, speed);
        assert!(
            (impact.restitution - 1.0).abs() < 1e-4,
            "v {speed}: e {}",
            impact.restitution
        );
    }
}

#[test]
fn lankarani_nikravesh_restitution_follows_ce_near_one() {
    for restitution in [0.9, 0.95, 0.99] {
        for speed in [0.2, 1.4007] {
            let law = LankaraniNikravesh {
                restitution,
                ..reference::lankarani_nikravesh::<f64>()
            };
            let impact = integrate_impact(&law, BALL_MASS, speed);
            assert!(
                relative_error(impact.restitution, restitution) < 0.02,
                "ce {restitution} v {speed}: e {}",
                impact.restitution
            );
        }
    }
}

#[test]
fn dissipative_laws_lose_energy_and_elastic_hertz_does_not() {
    for law in reference::all_laws::<f64>() {
        let e = integrate_impact(&law, BALL_MASS, IMPACT_SPEED).restitution;
        match law {
            AnyNormalLaw::Hertz(_) => assert!((e - 1.0).abs() < 1e-4),
            _ => assert!(e < 0.999 && e > 0.5, "{}: e {e}", law.name()),
        }
    }
}

#[test]
fn step_reaches_both_end_values_with_zero_slope() {
    let (x0, h0, x1, h1) = (0.2_f64, -1.0, 1.7, 3.0);
    assert_eq!(step(x0, x0, h0, x1, h1), h0);
    assert_eq!(step(x1, x0, h0, x1, h1), h1);
    for eps in [1e-3, 1e-4, 1e-5] {
        // A zero end slope makes the one-sided difference quotient shrink like ε.
        let left = (step(x0 + eps, x0, h0, x1, h1) - h0) / eps;
        let right = (h1 - step(x1 - eps, x0, h0, x1, h1)) / eps;
        let scale = (h1 - h0) / (x1 - x0);
        assert!(
            left.abs() < 4.0 * scale * eps / (x1 - x0),
            "left slope {left}"
        );
        assert!(
            right.abs() < 4.0 * scale * eps / (x1 - x0),
            "right slope {right}"
        );
    }
    let mut previous = h0;
    for i in 0..=1000 {
        let value = step(x0 + (x1 - x0) * i as f64 / 1000.0, x0, h0, x1, h1);
        assert!(value >= previous, "not monotone at {i}");
        previous = value;
    }
}

#[test]
fn impact_never_pulls() {
    let law = reference::impact::<f64>();
    for i in 0..200 {
        for rate in [-1e3, -10.0, -1.4, -0.1, 0.0, 0.1, 1.4] {
            let depth = 1e-7 * 1.05_f64.powi(i);
            let force = law.normal_force(&Indentation {
                depth,
                rate,
                approach_speed: 1.4,
            });
            assert!(force >= 0.0, "δ {depth} δ̇ {rate}: {force}");
        }
    }
    // The same state does pull under an undamped-clamp law (so the check has teeth).
    let ln = reference::lankarani_nikravesh::<f64>();
    assert!(
        ln.normal_force(&Indentation {
            depth: 1e-6,
            rate: -100.0,
            approach_speed: 1.4
        }) < 0.0
    );
}

#[test]
fn friction_opposes_slip_and_never_exceeds_static_bound() {
    let law = VelocityStepFriction {
        static_coefficient: 0.3,
        dynamic_coefficient: 0.1,
        stiction_speed: 1e-4,
        dynamic_speed: 1e-2,
    };
    let normal = Vector3::new(1.0, 2.0, 2.0) / 3.0;
    for i in 0..400 {
        let angle = i as f64 * 0.37;
        let speed = 1e-6 * 1.05_f64.powi(i);
        let velocity = Vector3::new(angle.cos(), angle.sin(), (2.0 * angle).cos()) * speed;
        let normal_force = if i % 2 == 0 { 250.0 } else { -250.0 };
        let f = law.force(&velocity, &normal, normal_force);
        let slip = velocity - normal * velocity.dot(&normal);
        assert!(f.dot(&slip) <= 0.0, "friction helps slip at {i}");
        assert!(
            f.norm() <= 0.3 * 250.0 * (1.0 + 1e-12),
            "|f| {} at {i}",
            f.norm()
        );
        assert!(
            f.dot(&normal).abs() < 1e-9 * 250.0,
            "friction has a normal part at {i}"
        );
        if slip.norm() > 1e-4 {
            assert!(f.norm() > 0.09 * 250.0, "no friction while sliding at {i}");
        }
    }
}

#[test]
fn wrench_torques_are_arm_cross_force_and_balance() {
    let contact_point = Vector3::new(0.3, -0.1, 0.05);
    let (origin_1, origin_2) = (Vector3::new(0.3, 0.0, 0.1), Vector3::new(-1.0, 0.5, 0.0));
    let normal = Vector3::new(0.0, 0.6, 0.8);
    let friction = Vector3::new(4.0, 0.8, -0.6);
    let (arm_1, arm_2) = (contact_point - origin_1, contact_point - origin_2);
    let w = ContactWrench::assemble(120.0, &normal, &friction, &arm_1, &arm_2);
    let total = normal * 120.0 + friction;
    assert_eq!(w.force_1, total);
    assert_eq!(w.force_2, -total);
    assert!((w.torque_1 - arm_1.cross(&total)).norm() < 1e-12);
    assert!((w.torque_2 + arm_2.cross(&total)).norm() < 1e-12);
    // Newton's third law for moments: about the world origin, the two bodies'
    // wrenches cancel exactly because both forces act at the same point.
    let moment = origin_1.cross(&w.force_1) + w.torque_1 + origin_2.cross(&w.force_2) + w.torque_2;
    assert!(moment.norm() < 1e-12, "net moment {moment}");
}

#[test]
fn f32_and_f64_agree_at_the_reference_parameters() {
    let (laws_32, laws_64) = (reference::all_laws::<f32>(), reference::all_laws::<f64>());
    for (law_32, law_64) in laws_32.iter().zip(laws_64.iter()) {
        for i in 0..60 {
            let depth = 1e-7 * 1.1_f64.powi(i); // 0.1 µm … 28 µm
            for rate in [1.4, 0.5, -0.3, -1.3] {
                let state = Indentation {
                    depth,
                    rate,
                    approach_speed: IMPACT_SPEED,
                };
                let state_32 = Indentation {
                    depth: depth as f32,
                    rate: rate as f32,
                    approach_speed: IMPACT_SPEED as f32,
                };
                let f64_force = law_64.normal_force(&state);
                let f32_force = law_32.normal_force(&state_32) as f64;
                let scale = f64_force.abs().max(1e-3);
                assert!(
                    (f32_force - f64_force).abs() / scale < 1e-5,
                    "{}: δ {depth} δ̇ {rate}: f32 {f32_force} vs f64 {f64_force}",
                    law_64.name()
                );
            }
        }
    }
}
