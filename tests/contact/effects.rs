//! The contact effects (`hcm_core::effect`) against hand computations, the extended
//! law against its base, and a property test that no input panics.
//!
//! Hand values use round parameters so that each expected force can be checked on
//! paper; the extended-law tests use the reference steel ball on concrete.

use hcm_core::effect::{
    Adhesion, AirDrag, ContactEffect, ContactMemory, ExtendedLaw, HysteresisDamping, Plasticity,
    StiffnessExponent, ViscousDamping, MAX_EFFECTS,
};
use hcm_core::law::{
    AnyNormalLaw, Flores, Hertz, HuntCrossley, Impact, Indentation, LankaraniNikravesh, NormalLaw,
    VariableStiffness,
};
use hcm_core::{LawError, Real};
use hcm_tests::reference;
use nalgebra::Vector3;
use proptest::prelude::*;

/// Approach speed δ̇0 (m/s) used for every contact state here.
const APPROACH: f64 = 1.4;

fn at<T: Real>(depth: f64, rate: f64) -> Indentation<T> {
    Indentation {
        depth: T::of(depth),
        rate: T::of(rate),
        approach_speed: T::of(APPROACH),
    }
}

fn memory<T: Real>(max_depth: f64) -> ContactMemory<T> {
    ContactMemory {
        max_depth: T::of(max_depth),
    }
}

/// `base` with `effects` added (panics only if the test lists more than fit).
fn extended<T: Real>(base: AnyNormalLaw<T>, effects: &[ContactEffect<T>]) -> ExtendedLaw<T> {
    let mut law = ExtendedLaw::new(base);
    for effect in effects {
        law.effects
            .push(*effect)
            .expect("test lists too many effects");
    }
    law
}

fn assert_close(value: f64, expected: f64, relative: f64) {
    assert!(
        (value - expected).abs() <= relative * expected.abs(),
        "{value} vs {expected}"
    );
}

// --- Each term against a hand computation ------------------------------------------

#[test]
fn viscous_damping_is_c_times_rate() {
    let effect = ViscousDamping { coefficient: 120.0 };
    // 120 N·s/m × 1.3 m/s = 156 N; × −0.4 m/s = −48 N.
    assert_close(effect.force(&at(2e-5, 1.3)), 156.0, 1e-15);
    assert_close(effect.force(&at(1e-6, -0.4)), -48.0, 1e-15);
}

#[test]
fn hysteresis_damping_is_c_times_depth_power_times_rate() {
    let effect = HysteresisDamping {
        coefficient: 3e8,
        exponent: 1.5,
    };
    // (1e-4)^1.5 = 1e-6: 3e8 × 1e-6 × 0.5 = 150 N.
    assert_close(effect.force(&at(1e-4, 0.5)), 150.0, 1e-12);
    // (4e-6)^1.5 = 8e-9: 3e8 × 8e-9 × (−2) = −4.8 N.
    assert_close(effect.force(&at(4e-6, -2.0)), -4.8, 1e-12);
    // p = 0 is viscous damping.
    let viscous = HysteresisDamping {
        coefficient: 7.0,
        exponent: 0.0,
    };
    assert_eq!(viscous.force(&at(3e-5, 2.0)), 14.0);
}

#[test]
fn stiffness_exponent_scales_the_elastic_force() {
    let effect = StiffnessExponent {
        exponent_change: 0.5,
        reference_depth: 1e-5,
    };
    // δ/δ_ref = 4: √4 − 1 = 1, so the term is f_el itself.
    assert_close(effect.force(4e-5, 10.0), 10.0, 1e-14);
    // δ/δ_ref = 1/4: √(1/4) − 1 = −1/2.
    assert_close(effect.force(2.5e-6, 10.0), -5.0, 1e-14);
}

#[test]
fn adhesion_is_a_constant_pull() {
    let effect = Adhesion {
        pull_off_force: 2.5,
    };
    assert_eq!(effect.force(&at(1e-9, 3.0)), -2.5);
    assert_eq!(effect.force(&at(1e-3, -3.0)), -2.5);
}

#[test]
fn plasticity_maps_unloading_depths() {
    let effect = Plasticity {
        permanent_ratio: 0.2,
    };
    let memory = memory(1e-4);
    assert_close(effect.permanent_depth(&memory), 2e-5, 1e-15);
    // δ_max·(δ − δ_p)/(δ_max − δ_p) = 1e-4 × 4e-5 / 8e-5 = 5e-5.
    assert_close(
        effect.effective_depth(&at(6e-5, -0.3), &memory),
        5e-5,
        1e-14,
    );
    // 1e-4 × 7e-5 / 8e-5 = 8.75e-5.
    assert_close(
        effect.effective_depth(&at(9e-5, -1.0), &memory),
        8.75e-5,
        1e-14,
    );
    // Loading, or at the deepest point, changes nothing.
    assert_eq!(effect.effective_depth(&at(6e-5, 0.3), &memory), 6e-5);
    assert_eq!(effect.effective_depth(&at(6e-5, 0.0), &memory), 6e-5);
    assert_eq!(effect.effective_depth(&at(1e-4, -0.3), &memory), 1e-4);
    // Deeper than the memory (not yet recorded): a new maximum, unchanged.
    assert_eq!(effect.effective_depth(&at(2e-4, -0.3), &memory), 2e-4);
}

#[test]
fn air_drag_is_quadratic_and_opposes_velocity() {
    let drag = AirDrag {
        coefficient: 0.01_f64,
    };
    // |v| = 5: −0.01 × 5 × (3, 0, 4).
    let f = drag.force(&Vector3::new(3.0, 0.0, 4.0));
    for (value, expected) in f.iter().zip([-0.15, 0.0, -0.2]) {
        assert!((value - expected).abs() < 1e-15, "{f:?}");
    }
    // |v| = 3: −0.01 × 3 × (−1, 2, −2).
    let f = drag.force(&Vector3::new(-1.0, 2.0, -2.0));
    for (value, expected) in f.iter().zip([0.03, -0.06, 0.06]) {
        assert!((value - expected).abs() < 1e-15, "{f:?}");
    }
    assert_eq!(drag.force(&Vector3::zeros()), Vector3::zeros());
}

// --- Out of contact ------------------------------------------------------------------

/// One of each contact effect at plausible parameters for the reference ball.
fn every_effect<T: Real>() -> [ContactEffect<T>; 5] {
    [
        ViscousDamping {
            coefficient: T::of(40.0),
        }
        .into(),
        HysteresisDamping {
            coefficient: T::of(2e8),
            exponent: T::of(1.5),
        }
        .into(),
        StiffnessExponent {
            exponent_change: T::of(0.1),
            reference_depth: T::of(2e-5),
        }
        .into(),
        Adhesion {
            pull_off_force: T::of(0.5),
        }
        .into(),
        Plasticity {
            permanent_ratio: T::of(0.3),
        }
        .into(),
    ]
}

#[test]
fn every_term_is_exactly_zero_out_of_contact() {
    let base: AnyNormalLaw<f64> = reference::hertz().into();
    let effects = every_effect::<f64>();
    let (first, last) = effects.split_at(MAX_EFFECTS);
    let laws = [extended(base, first), extended(base, last)];
    for depth in [0.0, -0.0, -1e-9, -1e-3, -1.0, f64::NEG_INFINITY] {
        for rate in [-5.0, -0.1, 0.0, 0.1, 5.0] {
            let contact = at::<f64>(depth, rate);
            for effect in every_effect::<f64>() {
                let term = effect.additive_force(&base, &contact);
                assert_eq!(term, 0.0, "{} at δ {depth}", effect.name());
            }
            let plasticity = Plasticity {
                permanent_ratio: 0.3,
            };
            assert_eq!(plasticity.effective_depth(&contact, &memory(1e-4)), depth);
            for law in &laws {
                assert_eq!(law.normal_force(&contact, &memory(1e-4)), 0.0);
            }
        }
    }
    // The same effects do act in contact (so the zeros above have teeth).
    for effect in &every_effect::<f64>()[..4] {
        assert_ne!(effect.additive_force(&base, &at(1e-5, 0.5)), 0.0);
    }
}

// --- The extended law ----------------------------------------------------------------

#[test]
fn extended_law_without_effects_is_the_base_law() {
    fn check<T: Real>() {
        for base in reference::all_laws::<T>() {
            let law = ExtendedLaw::from(base);
            for depth in [-1e-5, 0.0, 1e-7, 3e-6, 2e-5, 1e-4] {
                for rate in [-2.0, -0.1, 0.0, 0.7, 1.4] {
                    let contact = at::<T>(depth, rate);
                    for max_depth in [0.0, 1e-5, 1e-3] {
                        let force = law.normal_force(&contact, &memory(max_depth));
                        assert_eq!(force, base.normal_force(&contact), "{}", base.name());
                    }
                }
            }
        }
    }
    check::<f64>();
    check::<f32>();
}

#[test]
fn stiffness_exponent_vanishes_at_reference_and_tilts_hertz() {
    let hertz = reference::hertz::<f64>();
    let (k, n) = (hertz.stiffness, hertz.exponent);
    let base: AnyNormalLaw<f64> = hertz.into();
    for exponent_change in [-0.3, 0.1, 0.5] {
        let reference_depth = 2e-5;
        let effect: ContactEffect<f64> = StiffnessExponent {
            exponent_change,
            reference_depth,
        }
        .into();
        let law = extended(base, &[effect]);
        let touching = at(reference_depth, 0.9);
        assert_eq!(effect.additive_force(&base, &touching), 0.0);
        assert_eq!(
            law.normal_force(&touching, &memory(0.0)),
            base.normal_force(&touching)
        );
        for depth in [1e-6_f64, 5e-6, 4e-5, 1e-4] {
            let elastic = k * depth.powf(n);
            let expected =
                k * depth.powf(n + exponent_change) * reference_depth.powf(-exponent_change)
                    - elastic;
            let term = effect.additive_force(&base, &at(depth, 0.9));
            assert!(
                (term - expected).abs() <= 1e-12 * elastic,
                "Δ {exponent_change} δ {depth}: {term} vs {expected}"
            );
            assert_ne!(term, 0.0);
        }
    }
}

#[test]
fn plasticity_unloading_meets_loading_at_max_depth() {
    let plasticity: ContactEffect<f64> = Plasticity {
        permanent_ratio: 0.4,
    }
    .into();
    let max_depth = 3e-5;
    let memory = memory(max_depth);
    // Hertz: rate-independent, so loading and unloading forces at δ_max agree.
    let hertz: AnyNormalLaw<f64> = reference::hertz().into();
    let law = extended(hertz, &[plasticity]);
    let loading = law.normal_force(&at(max_depth, 1.0), &memory);
    assert_eq!(law.normal_force(&at(max_depth, -1.0), &memory), loading);
    assert!(loading > 100.0);
    // Just below δ_max while unloading the curve is continuous with it …
    let below = law.normal_force(&at(max_depth * (1.0 - 1e-9), -1.0), &memory);
    assert_close(below, loading, 1e-8);
    // … but steeper: at the same depth further down it gives less than loading.
    let depth = 0.7 * max_depth;
    assert!(
        law.normal_force(&at(depth, -1.0), &memory) < law.normal_force(&at(depth, 1.0), &memory)
    );
    // A damped base at δ_max while unloading is the base law at the same state.
    for base in reference::all_laws::<f64>() {
        let law = extended(base, &[plasticity]);
        let contact = at(max_depth, -0.8);
        assert_eq!(
            law.normal_force(&contact, &memory),
            base.normal_force(&contact)
        );
    }
}

#[test]
fn plasticity_force_is_zero_at_and_below_permanent_depth() {
    let ratio = 0.3;
    let max_depth = 5e-5;
    let permanent = ratio * max_depth;
    let memory = memory(max_depth);
    for base in reference::all_laws::<f64>() {
        let mut effects = every_effect::<f64>();
        effects.swap(2, 4); // plasticity among the first MAX_EFFECTS, with the terms
        let law = extended(base, &effects[..MAX_EFFECTS]);
        assert!(law.effects.iter().any(|e| e.name() == "plasticity"));
        for depth in [permanent, 0.5 * permanent, 1e-3 * permanent] {
            assert_eq!(
                law.normal_force(&at(depth, -0.5), &memory),
                0.0,
                "{}",
                base.name()
            );
            // Loading through the same depth still pushes.
            assert!(law.normal_force(&at(depth, 0.5), &memory) > 0.0);
        }
        // Above δ_p the contact is still on while unloading.
        let above = law.normal_force(&at(1.5 * permanent, -0.01), &memory);
        assert!(above > 0.0, "{}: {above}", base.name());
    }
}

#[test]
fn plasticity_with_zero_ratio_is_the_base_law() {
    let plasticity: ContactEffect<f64> = Plasticity {
        permanent_ratio: 0.0,
    }
    .into();
    for base in reference::all_laws::<f64>() {
        let law = extended(base, &[plasticity]);
        for depth in [-1e-6, 1e-7, 4e-6, 2e-5] {
            for rate in [-1.4, -0.2, 0.0, 0.9] {
                let contact = at(depth, rate);
                let force = law.normal_force(&contact, &memory(3e-5));
                assert_eq!(force, base.normal_force(&contact), "{}", base.name());
            }
        }
    }
}

#[test]
fn elastic_force_is_the_force_at_zero_rate() {
    // Every law's damping is a multiple of δ̇, so all six qualify.
    for law in reference::all_laws::<f64>() {
        for depth in [-1e-4, 0.0, 1e-8, 1e-6, 2e-5, 1e-4] {
            let elastic = law.elastic_force(depth);
            assert_eq!(elastic, law.normal_force(&at(depth, 0.0)), "{}", law.name());
            if depth > 0.0 {
                assert!(elastic > 0.0);
            }
        }
        // … and it is the non-dissipative part: the damped laws differ once δ̇ ≠ 0.
        if !matches!(law, AnyNormalLaw::Hertz(_)) {
            assert!(law.normal_force(&at(2e-5, 1.0)) > law.elastic_force(2e-5));
        }
    }
    // Spot values: k·δ^n for the Hertz family, k(δ)·δ for variable stiffness.
    let hc = reference::hunt_crossley::<f64>();
    assert_close(hc.elastic_force(1e-4), 6.86e9 * 1e-6, 1e-12);
    let vs = reference::variable_stiffness::<f64>();
    let k = vs.surface_loading * vs.effective_modulus * (2.0 * vs.radius * 1e-5 - 1e-10).sqrt();
    assert_close(vs.elastic_force(1e-5), k * 1e-5, 1e-12);
    // Beyond δ = 2r the sphere has no contact area.
    assert_eq!(vs.elastic_force(3.0 * vs.radius), 0.0);
}

// --- Validation ----------------------------------------------------------------------

#[test]
fn validate_names_the_bad_parameter() {
    let negative = |parameter| Err(LawError::Negative { parameter });
    assert_eq!(
        ViscousDamping { coefficient: -1.0 }.validate(),
        negative("viscous_damping.coefficient")
    );
    let hysteresis = HysteresisDamping {
        coefficient: 1e8,
        exponent: 1.5,
    };
    assert_eq!(
        HysteresisDamping {
            coefficient: -1e8,
            ..hysteresis
        }
        .validate(),
        negative("hysteresis_damping.coefficient")
    );
    assert_eq!(
        HysteresisDamping {
            exponent: -0.5,
            ..hysteresis
        }
        .validate(),
        negative("hysteresis_damping.exponent")
    );
    assert_eq!(
        Adhesion {
            pull_off_force: -0.1
        }
        .validate(),
        negative("adhesion.pull_off_force")
    );
    assert_eq!(
        AirDrag {
            coefficient: f64::NAN
        }
        .validate(),
        negative("air_drag.coefficient")
    );
    for exponent_change in [f64::INFINITY, f64::NAN] {
        assert_eq!(
            StiffnessExponent {
                exponent_change,
                reference_depth: 1e-5
            }
            .validate(),
            Err(LawError::OutOfRange {
                parameter: "stiffness_exponent.exponent_change",
                allowed: "(−∞, ∞)"
            })
        );
    }
    assert_eq!(
        StiffnessExponent {
            exponent_change: -0.2,
            reference_depth: 0.0
        }
        .validate(),
        Err(LawError::NotPositive {
            parameter: "stiffness_exponent.reference_depth"
        })
    );
    for permanent_ratio in [1.0, 1.5, -0.1, f64::NAN] {
        assert_eq!(
            Plasticity { permanent_ratio }.validate(),
            Err(LawError::OutOfRange {
                parameter: "plasticity.permanent_ratio",
                allowed: "[0, 1)"
            })
        );
    }
    // Every effect of the catalogue at plausible values passes.
    for effect in every_effect::<f64>() {
        assert_eq!(effect.validate(), Ok(()), "{}", effect.name());
    }
    assert_eq!(AirDrag { coefficient: 0.0 }.validate(), Ok(()));
}

#[test]
fn extended_law_validates_base_effects_and_duplicates() {
    let base: AnyNormalLaw<f64> = reference::lankarani_nikravesh().into();
    let viscous: ContactEffect<f64> = ViscousDamping { coefficient: 10.0 }.into();
    let adhesion: ContactEffect<f64> = Adhesion {
        pull_off_force: 1.0,
    }
    .into();
    assert_eq!(extended(base, &[viscous, adhesion]).validate(), Ok(()));
    assert_eq!(
        extended(base, &[viscous, adhesion, viscous]).validate(),
        Err(LawError::OutOfRange {
            parameter: "viscous_damping",
            allowed: "at most one entry of `effects`"
        })
    );
    let bad_effect = ContactEffect::Plasticity(Plasticity {
        permanent_ratio: 1.0,
    });
    assert_eq!(
        extended(base, &[adhesion, bad_effect]).validate(),
        Err(LawError::OutOfRange {
            parameter: "plasticity.permanent_ratio",
            allowed: "[0, 1)"
        })
    );
    let bad_base: AnyNormalLaw<f64> = Hertz {
        stiffness: -1.0,
        exponent: 1.5,
    }
    .into();
    assert_eq!(
        extended(bad_base, &[viscous]).validate(),
        Err(LawError::NotPositive {
            parameter: "stiffness"
        })
    );
}

#[test]
fn catalogue_names() {
    let names = every_effect::<f64>().map(|effect| effect.name());
    assert_eq!(
        names,
        [
            "viscous_damping",
            "hysteresis_damping",
            "stiffness_exponent",
            "adhesion",
            "plasticity"
        ]
    );
    assert_eq!(AirDrag { coefficient: 1.0 }.name(), "air_drag");
}

// --- Float types, memory, serialisation ----------------------------------------------

#[test]
fn f32_matches_f64() {
    let effects = every_effect::<f64>();
    let sets: [&[ContactEffect<f64>]; 2] = [&effects[..4], &effects[1..]];
    let states = [(3e-6, 1.2), (1.2e-5, 0.4), (2e-5, -0.6), (2.8e-5, -1.3)];
    for base in reference::all_laws::<f64>() {
        for set in sets {
            let law = extended(base, set);
            let law_32 = law.cast::<f32>();
            for (depth, rate) in states {
                let force = law.normal_force(&at(depth, rate), &memory(3e-5));
                let force_32 = law_32.normal_force(&at(depth, rate), &memory(3e-5));
                let error = (f64::from(force_32) - force).abs() / force.abs();
                assert!(
                    error < 1e-5,
                    "{} δ {depth} δ̇ {rate}: {force_32} vs {force}",
                    base.name()
                );
            }
        }
    }
    let drag = AirDrag { coefficient: 0.013 };
    let v = Vector3::new(2.5, -1.0, 0.3);
    let f = drag.force(&v);
    let f_32 = AirDrag {
        coefficient: 0.013_f32,
    }
    .force(&v.cast::<f32>());
    assert!((f_32.cast::<f64>() - f).norm() < 1e-5 * f.norm());
}

#[test]
fn memory_keeps_the_deepest_indentation() {
    let mut memory = ContactMemory::<f64>::touch_down();
    assert_eq!(memory.max_depth, 0.0);
    for (depth, expected) in [(1e-6, 1e-6), (4e-6, 4e-6), (2e-6, 4e-6), (-1e-6, 4e-6)] {
        memory.record(depth);
        assert_eq!(memory.max_depth, expected);
    }
    memory.record(f64::NAN);
    memory.record(1e-3);
    assert!(
        memory.max_depth.is_nan(),
        "a NaN depth must not be forgotten"
    );
}

#[test]
fn extended_law_round_trips_and_decodes_at_most_max_effects() {
    let base: AnyNormalLaw<f64> = reference::flores().into();
    let effects = every_effect::<f64>();
    let law = extended(base, &effects[..MAX_EFFECTS]);
    let mut buffer = [0u8; 512];
    let bytes = postcard::to_slice(&law, &mut buffer).unwrap();
    let decoded: ExtendedLaw<f64> = postcard::from_bytes(bytes).unwrap();
    assert_eq!(decoded, law);
    // The same layout with one effect too many (a struct is a tuple in postcard, the
    // effects a length-prefixed sequence) is refused rather than truncated.
    let mut buffer = [0u8; 512];
    let bytes = postcard::to_slice(&(base, &effects[..]), &mut buffer).unwrap();
    assert!(postcard::from_bytes::<ExtendedLaw<f64>>(bytes).is_err());
    let bytes = postcard::to_slice(&(base, &effects[..3]), &mut buffer).unwrap();
    assert_eq!(
        postcard::from_bytes::<ExtendedLaw<f64>>(bytes).unwrap(),
        extended(base, &effects[..3])
    );
}

// --- No input panics -----------------------------------------------------------------

/// Evaluates and validates everything built from `p` (parameters), `s` (state,
/// memory, velocity); checks the out-of-contact and NaN rules of every term.
fn exercise<T: Real>(p: [T; 13], s: [T; 7]) -> Result<(), TestCaseError> {
    let bases: [AnyNormalLaw<T>; 6] = [
        Hertz {
            stiffness: p[0],
            exponent: p[1],
        }
        .into(),
        LankaraniNikravesh {
            stiffness: p[0],
            exponent: p[1],
            restitution: p[2],
        }
        .into(),
        VariableStiffness {
            surface_loading: p[0],
            effective_modulus: p[1],
            radius: p[2],
            damping: p[3],
            effective_mass: p[4],
        }
        .into(),
        Impact {
            stiffness: p[0],
            exponent: p[1],
            max_damping: p[2],
            full_damping_depth: p[3],
        }
        .into(),
        HuntCrossley {
            stiffness: p[0],
            exponent: p[1],
            damping: p[2],
        }
        .into(),
        Flores {
            stiffness: p[0],
            exponent: p[1],
            restitution: p[2],
        }
        .into(),
    ];
    let effects: [ContactEffect<T>; 5] = [
        ViscousDamping { coefficient: p[5] }.into(),
        HysteresisDamping {
            coefficient: p[6],
            exponent: p[7],
        }
        .into(),
        StiffnessExponent {
            exponent_change: p[8],
            reference_depth: p[9],
        }
        .into(),
        Adhesion {
            pull_off_force: p[10],
        }
        .into(),
        Plasticity {
            permanent_ratio: p[11],
        }
        .into(),
    ];
    let contact = Indentation {
        depth: s[0],
        rate: s[1],
        approach_speed: s[2],
    };
    let mut memory = ContactMemory { max_depth: s[3] };
    for base in bases {
        let _ = base.elastic_force(contact.depth);
        for set in [
            &effects[..4],
            &effects[1..],
            &effects[4..],
            &[effects[0], effects[0]],
        ] {
            let law = extended(base, set);
            let _ = law.normal_force(&contact, &memory);
            let _ = law.validate();
            let _ = law.cast::<f32>().validate();
        }
        for effect in effects {
            let _ = effect.validate();
            let term = effect.additive_force(&base, &contact);
            if contact.depth.is_nan() && !matches!(effect, ContactEffect::Plasticity(_)) {
                prop_assert!(term.is_nan(), "{} gave {:?} at NaN δ", effect.name(), term);
            } else if contact.depth <= T::zero() {
                prop_assert!(term == T::zero(), "{} gave {:?} apart", effect.name(), term);
            }
        }
    }
    let plasticity = Plasticity {
        permanent_ratio: p[11],
    };
    let depth = plasticity.effective_depth(&contact, &memory);
    if contact.depth.is_nan() {
        prop_assert!(depth.is_nan());
    } else if contact.depth <= T::zero() {
        prop_assert!(depth == contact.depth);
    }
    memory.record(contact.depth);
    let drag = AirDrag { coefficient: p[12] };
    let velocity = Vector3::new(s[4], s[5], s[6]);
    let force = drag.force(&velocity);
    let _ = drag.validate();
    if velocity.iter().any(|v| v.is_nan()) {
        prop_assert!(force.iter().all(|f| f.is_nan()));
    }
    Ok(())
}

/// Any f64: raw bit patterns, and proptest's mix of specials (NaN, ±∞, ±0, subnormal).
fn any_f64() -> impl Strategy<Value = f64> {
    prop_oneof![any::<u64>().prop_map(f64::from_bits), any::<f64>()]
}

fn any_f32() -> impl Strategy<Value = f32> {
    prop_oneof![any::<u32>().prop_map(f32::from_bits), any::<f32>()]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn no_input_panics_f64(p in prop::array::uniform13(any_f64()), s in prop::array::uniform7(any_f64())) {
        exercise(p, s)?;
    }

    #[test]
    fn no_input_panics_f32(p in prop::array::uniform13(any_f32()), s in prop::array::uniform7(any_f32())) {
        exercise(p, s)?;
    }
}
