//! Property tests: every law, in f32 and f64, over wide parameter and state ranges.
//!
//! Two properties: (1) for parameters that pass `validate` and a finite state, the
//! force is finite and exactly zero out of contact; (2) for any bit pattern at all
//! (NaN, ±∞, negative or zero parameters) nothing panics.

use hcm_core::friction::VelocityStepFriction;
use hcm_core::law::{
    step, AnyNormalLaw, Flores, Hertz, HuntCrossley, Impact, Indentation, LankaraniNikravesh,
    NormalLaw, VariableStiffness,
};
use hcm_core::wrench::ContactWrench;
use hcm_core::Real;
use nalgebra::Vector3;
use proptest::prelude::*;

/// Log-uniform over [10^lo, 10^hi].
fn decades(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo..hi).prop_map(|e| 10f64.powf(e))
}

/// A law of any kind with parameters in its physical domain (as f64; cast later).
fn valid_law() -> impl Strategy<Value = AnyNormalLaw<f64>> {
    let k = || decades(3.0, 12.0);
    let n = 1.0..2.5;
    let ce = 0.05..=1.0;
    prop_oneof![
        (k(), n.clone()).prop_map(|(stiffness, exponent)| Hertz {
            stiffness,
            exponent
        }
        .into()),
        (k(), n.clone(), ce.clone()).prop_map(|(stiffness, exponent, restitution)| {
            LankaraniNikravesh {
                stiffness,
                exponent,
                restitution,
            }
            .into()
        }),
        (
            4.0 / 3.0..std::f64::consts::TAU,
            decades(6.0, 12.0),
            decades(-4.0, 0.0),
            0.0..5e3,
            decades(-3.0, 3.0)
        )
            .prop_map(
                |(surface_loading, effective_modulus, radius, damping, effective_mass)| {
                    VariableStiffness {
                        surface_loading,
                        effective_modulus,
                        radius,
                        damping,
                        effective_mass,
                    }
                    .into()
                }
            ),
        (k(), n.clone(), 0.0..1e5, decades(-7.0, -2.0)).prop_map(
            |(stiffness, exponent, max_damping, full_damping_depth)| {
                Impact {
                    stiffness,
                    exponent,
                    max_damping,
                    full_damping_depth,
                }
                .into()
            }
        ),
        (k(), n.clone(), 0.0..10.0).prop_map(|(stiffness, exponent, damping)| {
            HuntCrossley {
                stiffness,
                exponent,
                damping,
            }
            .into()
        }),
        (k(), n, ce).prop_map(|(stiffness, exponent, restitution)| {
            Flores {
                stiffness,
                exponent,
                restitution,
            }
            .into()
        }),
    ]
}

fn finite_state() -> impl Strategy<Value = Indentation<f64>> {
    (
        -1e-2..1e-2,
        -100.0..100.0,
        prop_oneof![Just(0.0), 0.0..100.0],
    )
        .prop_map(|(depth, rate, approach_speed)| Indentation {
            depth,
            rate,
            approach_speed,
        })
}

fn check_finite<T: Real>(
    law: &AnyNormalLaw<f64>,
    state: &Indentation<f64>,
) -> Result<(), TestCaseError> {
    let law = law.cast::<T>();
    prop_assert_eq!(law.validate(), Ok(()));
    let state = Indentation {
        depth: T::of(state.depth),
        rate: T::of(state.rate),
        approach_speed: T::of(state.approach_speed),
    };
    let force = law.normal_force(&state);
    prop_assert!(
        force.is_finite(),
        "{} gave {:?} at {:?}",
        law.name(),
        force,
        state
    );
    if state.depth <= T::zero() {
        prop_assert!(force == T::zero(), "force {:?} out of contact", force);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn valid_laws_give_finite_forces(law in valid_law(), state in finite_state()) {
        check_finite::<f64>(&law, &state)?;
        check_finite::<f32>(&law, &state)?;
    }

    #[test]
    fn no_input_panics(params in prop::array::uniform5(any::<f64>()), state in prop::array::uniform3(any::<f64>())) {
        let [a, b, c, d, e] = params;
        let laws: [AnyNormalLaw<f64>; 6] = [
            Hertz { stiffness: a, exponent: b }.into(),
            LankaraniNikravesh { stiffness: a, exponent: b, restitution: c }.into(),
            VariableStiffness { surface_loading: a, effective_modulus: b, radius: c, damping: d, effective_mass: e }.into(),
            Impact { stiffness: a, exponent: b, max_damping: c, full_damping_depth: d }.into(),
            HuntCrossley { stiffness: a, exponent: b, damping: c }.into(),
            Flores { stiffness: a, exponent: b, restitution: c }.into(),
        ];
        let state = Indentation { depth: state[0], rate: state[1], approach_speed: state[2] };
        for law in laws {
            let force = law.normal_force(&state);
            let _ = law.validate();
            let force_32 = law.cast::<f32>().normal_force(&Indentation {
                depth: state.depth as f32, rate: state.rate as f32, approach_speed: state.approach_speed as f32,
            });
            // NaN in the state must not be turned into a plausible force.
            if state.depth.is_nan() {
                prop_assert!(force.is_nan() && force_32.is_nan());
            }
        }
        let friction = VelocityStepFriction { static_coefficient: a, dynamic_coefficient: b, stiction_speed: c, dynamic_speed: d };
        let v = Vector3::new(state.depth, state.rate, state.approach_speed);
        let _ = friction.force(&v, &Vector3::new(e, a, b), c);
        let _ = friction.validate();
        let _ = step(a, b, c, d, e);
        let _ = ContactWrench::assemble(a, &v, &v, &v, &v);
    }

    #[test]
    fn step_stays_between_its_end_values(x in -10.0..10.0, x0 in -5.0..5.0, width in 0.0..5.0, h0 in -1e3..1e3, h1 in -1e3..1e3) {
        let value: f64 = step(x, x0, h0, x0 + width, h1);
        prop_assert!(value >= h0.min(h1) && value <= h0.max(h1), "{}", value);
        let value_32: f32 = step(x as f32, x0 as f32, h0 as f32, (x0 + width) as f32, h1 as f32);
        prop_assert!(value_32.is_finite());
    }

    #[test]
    fn friction_is_finite_tangential_and_bounded(
        v in prop::array::uniform3(-10.0..10.0),
        n in prop::array::uniform3(-1.0..1.0),
        normal_force in -1e4..1e4,
        mu_s in 0.0..1.5, mu_d_share in 0.0..=1.0, vs in decades(-6.0, -1.0), vd_factor in 1.0..1e3,
    ) {
        let normal = Vector3::from(n);
        prop_assume!(normal.norm() > 1e-3);
        let normal = normal.normalize();
        let law = VelocityStepFriction {
            static_coefficient: mu_s, dynamic_coefficient: mu_s * mu_d_share,
            stiction_speed: vs, dynamic_speed: vs * vd_factor,
        };
        prop_assert_eq!(law.validate(), Ok(()));
        let f = law.force(&Vector3::from(v), &normal, normal_force);
        prop_assert!(f.iter().all(|x| x.is_finite()));
        prop_assert!(f.norm() <= mu_s * normal_force.abs() * (1.0 + 1e-12) + 1e-300);
        prop_assert!(f.dot(&normal).abs() <= 1e-9 * (1.0 + f.norm()));
    }
}
