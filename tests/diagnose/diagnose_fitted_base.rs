//! A diagnosis never names the bias of the user's own base fit as an effect:
//! when the base law was fitted with its exponent free (as `hcm identify`
//! fits it), the fit absorbs part of a missing effect in its exponent, and holding that
//! exponent while judging effects named `stiffness_exponent` for a "change" that only
//! undid the bias. With the base's freedom re-tuned ([`BaseFreedom::Fitted`]) the
//! exponent change is not a candidate, on several base laws, with an effect hidden
//! and with nothing hidden.

use hcm_host::diagnose::BaseFreedom;
use hcm_host::diagnose::{contact_samples, diagnose, noise_floor, DiagnoseSettings};
use hcm_host::identify::{identify, Method};
use hcm_host::progress::Silent;
use hcm_tests::hidden::{decided, hidden};

/// The names a diagnosis gives on 12 runs with `effect` hidden, against a base of
/// `law` fitted by least squares on the same runs (its exponent free), judged with
/// `freedom`.
fn named_against_fitted(effect: &str, law: &str, freedom: BaseFreedom) -> Vec<&'static str> {
    let (names, _) = diagnosed_against_fitted(effect, law, freedom);
    names
}

/// A re-fit's cause: its name, its first parameter's value and 95 % interval.
type Named = (&'static str, f64, (f64, f64));

/// [`named_against_fitted`], with the re-fit's causes as (name, value, 95 % interval)
/// of their first parameter.
fn diagnosed_against_fitted(
    effect: &str,
    law: &str,
    freedom: BaseFreedom,
) -> (Vec<&'static str>, Vec<Named>) {
    let (model, data) = hidden(effect, 12, 5);
    let fit = identify(&model.scenario, &model, &data, 0, law, Method::Lsq, &Silent).unwrap();
    let mut base = model.clone();
    base.contacts[0].model.normal.base = fit.law;
    let samples = contact_samples(&base, &data, 0).unwrap();
    let sigma = noise_floor(&samples).sigma;
    let naming = decided(&base, &samples, freedom, sigma);
    let names: Vec<&'static str> = naming.chosen.iter().map(|(c, _)| c.name()).collect();
    println!(
        "{law}, {effect:?}, {freedom:?}: fitted {:?} → {names:?}",
        fit.law
    );
    let values = naming
        .fit
        .causes
        .iter()
        .map(|c| (c.effect, c.parameters[0].value, c.parameters[0].ci))
        .collect();
    (names, values)
}

/// Measured with this test (seed 5, 12 runs, σ = 15 N): with the fitted exponent held
/// (the old rule), 6 of the 12 cases named `stiffness_exponent` — beside a wrong
/// `adhesion` or `sensor_delay` — and on the damped bases nothing hidden was answered
/// `hysteresis_damping`; with the exponent re-tuned, none, and a hidden plasticity is
/// named alone.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_fitted_base_never_has_its_exponent_named() {
    let mut held = Vec::new();
    for law in ["hertz", "lankarani_nikravesh", "hunt_crossley", "impact"] {
        for effect in [
            "",
            "{ plasticity = { permanent_ratio = 0.03 } }",
            "{ adhesion = { pull_off_force = 40.0 } }",
        ] {
            let names = named_against_fitted(effect, law, BaseFreedom::Fitted);
            assert!(
                !names.contains(&"stiffness_exponent"),
                "{law}, {effect:?}: {names:?}"
            );
            // A base with damping of its own (all but Hertz, which lacks the
            // truth's damping): nothing hidden is nothing named, a plasticity
            // is the plasticity alone.
            if law != "hertz" && effect.is_empty() {
                assert!(names.is_empty(), "{law}, nothing hidden: {names:?}");
            }
            if law != "hertz" && effect.contains("plasticity") {
                assert_eq!(names, ["plasticity"], "{law}");
            }
            if named_against_fitted(effect, law, BaseFreedom::Given).contains(&"stiffness_exponent")
            {
                held.push((law, effect));
            }
        }
    }
    // The failure this guards against is real on these cases.
    assert!(!held.is_empty(), "the held exponent named nothing wrong");
    println!("named stiffness_exponent with the fitted exponent held: {held:?}");
}

/// A sensor delay the user's base fit absorbed: least squares on
/// delayed data bends the base's damping — onto its bound 0 for the variable-stiffness
/// law — and the re-fit, starting there, used to stop near 0.9 µs of a 2.5 µs delay
/// with a singular covariance (the damping, started at 0, had a step scale of ~0 and
/// could not move). Now the damping moves off its bound and the delay starts from the
/// best of a grid over its plausible range: named alone on every base. On the data's
/// own law (variable stiffness) within 10 %, its interval holding it; on the
/// Lankarani–Nikravesh and Hunt–Crossley bases, whose damping has another shape than
/// the data's, the delay takes up part of that mismatch — measured 2.15 µs of 2.5 µs
/// and 7.66 µs of 8 µs, intervals ±0.04 µs that miss the truth: the covariance knows
/// the noise, not the wrong law — so only within 20 %.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_delay_a_fitted_base_absorbed_is_named_with_its_value() {
    for law in ["variable_stiffness", "lankarani_nikravesh", "hunt_crossley"] {
        for delay in [2.5e-6, 8e-6] {
            let effect = format!("experiment.sensor_delay={delay}");
            let (names, causes) = diagnosed_against_fitted(&effect, law, BaseFreedom::Fitted);
            println!("{law}, {delay:e} s: {causes:?}");
            assert_eq!(names, ["sensor_delay"], "{law}, {delay:e} s");
            let (_, value, (lo, hi)) = causes[0];
            if law == "variable_stiffness" {
                assert!((value - delay).abs() < 0.1 * delay, "{law}: {value:e} s");
                assert!(lo <= delay && delay <= hi, "{law}: [{lo:e}, {hi:e}] s");
            } else {
                assert!((value - delay).abs() < 0.2 * delay, "{law}: {value:e} s");
            }
        }
    }
}

/// A sensor reading 3 % high, on 16 runs, against a base fitted
/// by least squares to the same readings: the fit took the gain into its stiffness
/// (and bent the rest of the law to it), and the diagnosis named `stiffness_exponent`.
/// The momentum balance gives the gain first, within 0.3 %; the physics is judged on
/// the corrected readings with the base's freedom re-tuned, and on the data's own law
/// (variable stiffness) nothing else is named. Lankarani–Nikravesh and Hertz bases
/// lack part of the data's damping whatever the sensor: on these runs without the gain
/// the Lankarani–Nikravesh base leaves `hysteresis_damping` and a −0.3 µs
/// `sensor_delay` as rivals (information criteria 9.0 apart, ambiguous) and the Hertz
/// base names `hysteresis_damping`; so beside the gain only that damping may be named.
#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_gain_a_fitted_base_absorbed_is_named_as_the_sensors() {
    let (model, data) = hidden("experiment.force_gain=1.03", 16, 6);
    for law in ["variable_stiffness", "lankarani_nikravesh", "hertz"] {
        let fit = identify(&model.scenario, &model, &data, 0, law, Method::Lsq, &Silent).unwrap();
        let mut base = model.clone();
        base.contacts[0].model.normal.base = fit.law;
        let settings = DiagnoseSettings {
            hcm_epochs: 2,
            base_freedom: BaseFreedom::Fitted,
            ..DiagnoseSettings::default()
        };
        let d = diagnose(&base, &data, &settings).unwrap();
        let names: Vec<&str> = d.causes.iter().map(|c| c.effect).collect();
        println!("{law}: {names:?} {:?}", d.sensor_gain);
        assert_eq!(names.first(), Some(&"sensor_gain"), "{law}: {names:?}");
        let gain = &d.causes[0].parameters[0];
        assert!((gain.value - 1.03).abs() < 0.003, "{law}: {gain:?}");
        assert!(gain.ci.0 <= 1.03 && 1.03 <= gain.ci.1, "{law}: {gain:?}");
        if law == "variable_stiffness" {
            assert_eq!(names, ["sensor_gain"]);
        } else {
            assert!(
                names[1..].iter().all(|n| *n == "hysteresis_damping"),
                "{law}: {names:?}"
            );
        }
    }
}
