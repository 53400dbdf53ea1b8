//! The joint laws against their definitions, in `f64` and `f32`.

extern crate std;

use super::*;
use crate::{LawError, Real};
use std::format;

fn of<T: Real>(x: f64) -> T {
    T::of(x)
}

/// Rates (rad/s) from −4 to 4 across the smoothing band of ω_s = 0.05, denser near 0.
fn rates() -> impl Iterator<Item = f64> {
    (-400..=400).map(|k| {
        let x = f64::from(k) / 100.0;
        x * x * x.signum() / 4.0
    })
}

fn full() -> JointLaw<f64> {
    JointLaw {
        spring: Some(JointSpring {
            stiffness: 3.0,
            rest_angle: 0.4,
        }),
        viscous: Some(JointViscous { damping: 0.25 }),
        coulomb: Some(JointCoulomb {
            torque: 0.7,
            smoothing_rate: 0.05,
        }),
        limit: None,
    }
}

/// The stops push back past either end, never pull into them, and give nothing
/// between; NaN in gives NaN out.
fn limit_pushes_back_only_past_its_ends<T: Real + core::fmt::Debug>() {
    let limit = JointLimit {
        lower: of::<T>(-0.5),
        upper: of(1.0),
        stiffness: of(100.0),
        damping: of(2.0),
    };
    for k in -50..=100 {
        let angle = of::<T>(f64::from(k) / 100.0);
        assert_eq!(limit.torque(angle, of(3.0)), T::zero());
    }
    // Past the upper stop, moving on: spring and damper push back.
    assert_eq!(limit.torque(of(1.25), of(1.0)), of(-27.0));
    // Leaving it fast: the damper would pull; the stop gives nothing.
    assert_eq!(limit.torque(of(1.01), of(-5.0)), T::zero());
    // Past the lower stop, moving on: pushed up.
    assert_eq!(limit.torque(of(-0.75), of(-1.0)), of(27.0));
    assert!(limit.torque(of(f64::NAN), T::zero()).is_nan());
    assert!(limit.torque(of(2.0), of(f64::NAN)).is_nan());
    assert!(limit.validate().is_ok());
    let crossed = JointLimit {
        lower: of::<T>(1.0),
        upper: of(0.0),
        ..limit
    };
    assert!(crossed.validate().is_err());
    let negative = JointLimit {
        damping: of::<T>(-1.0),
        ..limit
    };
    assert!(negative.validate().is_err());
}

#[test]
fn limit_pushes_back_only_past_its_ends_f64_and_f32() {
    limit_pushes_back_only_past_its_ends::<f64>();
    limit_pushes_back_only_past_its_ends::<f32>();
}

fn viscous_is_linear_and_odd<T: Real + core::fmt::Debug>() {
    let law = JointViscous {
        damping: of::<T>(0.25),
    };
    assert_eq!(law.torque(of(2.0)), of(-0.5));
    assert_eq!(law.torque(T::zero()), T::zero());
    for r in rates() {
        let r = of::<T>(r);
        assert_eq!(law.torque(-r), -law.torque(r));
        assert_eq!(law.torque(r + r), law.torque(r) + law.torque(r));
    }
}

fn coulomb_is_a_smoothed_sign<T: Real + core::fmt::Debug>() {
    let tau_c = of::<T>(0.7);
    let law = JointCoulomb {
        torque: tau_c,
        smoothing_rate: of(0.05),
    };
    assert_eq!(law.torque(T::zero()), T::zero());
    assert_eq!(law.torque(of(0.05)), -tau_c);
    assert_eq!(law.torque(of(-3.0)), tau_c);
    // Midway through the STEP, half the torque.
    assert_eq!(law.torque(of(0.025)), -tau_c / of(2.0));
    let mut previous = T::zero();
    for k in 0..=20_000 {
        let r = of::<T>(f64::from(k) * 1e-5); // 0 to 0.2 rad/s
        let tau = law.torque(r);
        assert_eq!(law.torque(-r), -tau);
        assert!(tau.abs() <= tau_c, "{r:?}: {tau:?}");
        assert!(tau.abs() >= previous, "{r:?}: {tau:?} < {previous:?}");
        assert!(r == T::zero() || tau < T::zero());
        if r >= of(0.05) {
            assert_eq!(tau, -tau_c);
        }
        previous = tau.abs();
    }
}

fn spring_is_zero_at_rest_and_linear<T: Real + core::fmt::Debug>() {
    let law = JointSpring {
        stiffness: of::<T>(3.0),
        rest_angle: of(0.5),
    };
    assert_eq!(law.torque(of(0.5)), T::zero());
    assert_eq!(law.torque(of(1.5)), of(-3.0));
    assert_eq!(law.torque(of(-0.5)), of(3.0));
    for k in -50..=50 {
        let d = of::<T>(f64::from(k) / 8.0); // exact offsets from θ₀
        let tau = law.torque(of::<T>(0.5) + d);
        assert!((tau + of::<T>(3.0) * d).abs() <= of(1e-6), "{d:?}: {tau:?}");
    }
}

fn dissipation_is_never_positive<T: Real + core::fmt::Debug>() {
    let law = JointLaw {
        spring: None,
        ..full()
    }
    .map(of::<T>);
    for r in rates() {
        for angle in [-2.0, 0.0, 0.4, 7.0] {
            let p = law.power(of(angle), of(r));
            assert!(p <= T::zero(), "θ̇ = {r}: {p:?}");
        }
    }
}

fn never_panics<T: Real + core::fmt::Debug>() {
    let law = full().map(of::<T>);
    let (nan, inf) = (T::zero() / T::zero(), T::MAX * of(2.0));
    assert!(law.torque(nan, T::zero()).is_nan());
    assert!(law.torque(T::zero(), nan).is_nan());
    assert!(JointLaw::<T>::ZERO.torque(nan, T::zero()).is_nan());
    assert!(law.power(T::zero(), nan).is_nan());
    for (angle, rate) in [
        (inf, T::zero()),
        (-inf, of(1.0)),
        (T::zero(), inf),
        (inf, -inf),
    ] {
        let tau = law.torque(angle, rate);
        assert!(
            tau.is_nan() || tau.abs() <= T::MAX,
            "{angle:?}, {rate:?}: {tau:?}"
        );
        let p = law.power(angle, rate);
        assert!(
            p.is_nan() || p.abs() <= T::MAX,
            "{angle:?}, {rate:?}: {p:?}"
        );
    }
    let coulomb = law.coulomb.unwrap();
    assert_eq!(coulomb.torque(inf), -coulomb.torque);
    assert_eq!(coulomb.torque(-inf), coulomb.torque);
    assert!(coulomb.torque(nan).is_nan());
    // Out-of-domain parameters are evaluated literally, still without a panic.
    let odd = JointCoulomb {
        torque: inf,
        smoothing_rate: nan,
    };
    assert!(odd.torque(of(1.0)).is_nan());
    let jump = JointCoulomb {
        torque: of(1.0),
        smoothing_rate: T::zero(),
    };
    assert_eq!(jump.torque(of(1e-20)), of(-1.0));
    assert_eq!(jump.torque(T::zero()), T::zero());
}

#[test]
fn viscous_torque_is_linear_and_odd() {
    viscous_is_linear_and_odd::<f64>();
    viscous_is_linear_and_odd::<f32>();
}

#[test]
fn coulomb_torque_saturates_is_odd_monotone_and_bounded() {
    coulomb_is_a_smoothed_sign::<f64>();
    coulomb_is_a_smoothed_sign::<f32>();
}

#[test]
fn coulomb_f32_is_bounded_and_monotone_to_rounding_at_every_float_near_the_band_end() {
    // Every f32 rate in [0.6·ω_s, ω_s]: the cubic rounds up to an ulp above τ_c there
    // (3.3000002 for τ_c = 3.3, ω_s = 0.2) unless clamped, and dips up to 2 ulps below
    // its running maximum (it is monotone in exact arithmetic only).
    for (tau_c, omega_s) in [(0.7_f32, 0.05_f32), (3.3, 0.2)] {
        let law = JointCoulomb {
            torque: tau_c,
            smoothing_rate: omega_s,
        };
        let (mut rate, mut highest) = (0.6 * omega_s, 0.0_f32);
        while rate <= omega_s {
            let magnitude = -law.torque(rate);
            assert!(magnitude <= tau_c, "{rate}: {magnitude}");
            assert!(magnitude >= highest - 4.0 * f32::EPSILON * tau_c, "{rate}");
            highest = highest.max(magnitude);
            rate = f32::from_bits(rate.to_bits() + 1);
        }
    }
}

#[test]
fn spring_torque_is_zero_at_the_rest_angle_and_linear() {
    spring_is_zero_at_rest_and_linear::<f64>();
    spring_is_zero_at_rest_and_linear::<f32>();
}

#[test]
fn viscous_and_coulomb_dissipate() {
    dissipation_is_never_positive::<f64>();
    dissipation_is_never_positive::<f32>();
}

#[test]
fn nan_and_infinity_do_not_panic() {
    never_panics::<f64>();
    never_panics::<f32>();
}

#[test]
fn the_law_is_the_sum_of_its_terms() {
    let law = full();
    let (angle, rate) = (1.1, -0.02);
    let sum = -3.0 * (1.1 - 0.4) - 0.25 * rate + law.coulomb.unwrap().torque(rate);
    assert!((law.torque(angle, rate) - sum).abs() < 1e-15);
    assert_eq!(law.power(angle, rate), law.torque(angle, rate) * rate);
    assert!(JointLaw::<f64>::ZERO.is_zero() && JointLaw::<f32>::default().is_zero());
    assert!(!law.is_zero());
    assert_eq!(JointLaw::<f64>::ZERO.torque(2.0, 3.0), 0.0);
}

#[test]
fn f32_agrees_with_f64_to_f32_precision() {
    let law = full();
    let law32 = law.map(|v| v as f32);
    for r in rates() {
        for angle in [-3.0_f64, -0.1, 0.4, 0.41, 2.5] {
            let (a32, r32) = (angle as f32, r as f32);
            let expected = law.torque(f64::from(a32), f64::from(r32));
            let got = f64::from(law32.torque(a32, r32));
            // Each term within a few f32 ulps of its own scale.
            let scale = 3.0 * (angle.abs() + 0.4) + 0.25 * r.abs() + 0.7;
            let bound = 8.0 * f64::from(f32::EPSILON) * scale;
            assert!(
                (got - expected).abs() <= bound,
                "{angle}, {r}: {got} vs {expected}"
            );
        }
    }
}

#[test]
fn validation_names_the_field() {
    assert!(full().validate().is_ok());
    assert!(JointLaw::<f32>::ZERO.validate().is_ok());
    let cases: [(JointLaw<f64>, &str); 8] = [
        (
            JointLaw {
                viscous: Some(JointViscous { damping: -0.1 }),
                ..full()
            },
            "viscous.damping",
        ),
        (
            JointLaw {
                viscous: Some(JointViscous { damping: f64::NAN }),
                ..full()
            },
            "viscous.damping",
        ),
        (
            JointLaw {
                coulomb: Some(JointCoulomb {
                    torque: -1.0,
                    smoothing_rate: 0.1,
                }),
                ..full()
            },
            "coulomb.torque",
        ),
        (
            JointLaw {
                coulomb: Some(JointCoulomb {
                    torque: 1.0,
                    smoothing_rate: 0.0,
                }),
                ..full()
            },
            "coulomb.smoothing_rate",
        ),
        (
            JointLaw {
                coulomb: Some(JointCoulomb {
                    torque: 1.0,
                    smoothing_rate: -0.1,
                }),
                ..full()
            },
            "coulomb.smoothing_rate",
        ),
        (
            JointLaw {
                coulomb: Some(JointCoulomb {
                    torque: 1.0,
                    smoothing_rate: f64::NAN,
                }),
                ..full()
            },
            "coulomb.smoothing_rate",
        ),
        (
            JointLaw {
                spring: Some(JointSpring {
                    stiffness: -2.0,
                    rest_angle: 0.0,
                }),
                ..full()
            },
            "spring.stiffness",
        ),
        (
            JointLaw {
                spring: Some(JointSpring {
                    stiffness: 2.0,
                    rest_angle: f64::NAN,
                }),
                ..full()
            },
            "spring.rest_angle",
        ),
    ];
    for (law, field) in cases {
        let error = law.validate().unwrap_err();
        let message = format!("{error}");
        assert!(message.contains(field), "{field}: {message}");
        // f32 rejects the same parameters.
        assert_eq!(law.map(|v| v as f32).validate(), Err(error));
    }
    let negative = JointLaw::<f64> {
        viscous: Some(JointViscous { damping: -1.0 }),
        ..JointLaw::ZERO
    };
    assert_eq!(
        negative.validate(),
        Err(LawError::Negative {
            parameter: "viscous.damping"
        })
    );
}

/// A 2-4-4-1 network that outputs `offset` (N·m) wherever θ̇ lies in [−1, 1] rad/s (its
/// envelope), zero weights: the output mean alone.
fn constant_network(offset: f32) -> crate::residual::Mlp<2, 4, 1, 2> {
    let mut network = crate::residual::Mlp::zeroed(crate::residual::Activation::Tanh);
    network.normalisation.output_mean = [offset];
    network.envelope.min = [-4.0, -1.0];
    network.envelope.max = [4.0, 1.0];
    network
}

/// The hybrid torque is the law's plus the network's inside its envelope, the law's
/// alone outside it, NaN in NaN out; a network of other than one output adds nothing.
fn hybrid_torque_adds_the_network_inside_its_envelope<T: Real + core::fmt::Debug>() {
    let law = JointLaw {
        viscous: Some(JointViscous {
            damping: of::<T>(0.25),
        }),
        ..JointLaw::ZERO
    };
    let network = constant_network(-0.125);
    let inside = hybrid_torque(&law, &network, of::<T>(0.3), of::<T>(0.5));
    let expected = law.torque(of::<T>(0.3), of::<T>(0.5)) + of::<T>(-0.125);
    assert!((inside - expected).abs() <= of::<T>(1e-6), "{inside:?}");
    assert_eq!(
        residual_torque(&network, of::<T>(0.3), of::<T>(0.5)),
        Some(of::<T>(-0.125))
    );
    // θ̇ = 2 rad/s lies outside: the law alone.
    let outside = hybrid_torque(&law, &network, of::<T>(0.3), of::<T>(2.0));
    assert_eq!(outside, law.torque(of::<T>(0.3), of::<T>(2.0)));
    assert!(hybrid_torque(&law, &network, of::<T>(f64::NAN), of::<T>(0.5)).is_nan());
    assert_eq!(
        residual_torque(&network, of::<T>(0.3), of::<T>(f64::NAN)),
        None
    );
    let wrench = crate::residual::Mlp::<2, 4, 6, 2>::zeroed(crate::residual::Activation::Tanh);
    assert_eq!(residual_torque(&wrench, of::<T>(0.3), of::<T>(0.5)), None);
}

#[test]
fn hybrid_torque_f64() {
    hybrid_torque_adds_the_network_inside_its_envelope::<f64>();
}

#[test]
fn hybrid_torque_f32() {
    hybrid_torque_adds_the_network_inside_its_envelope::<f32>();
}
