//! `variation.tails`: the run-to-run draws Student-t with ν degrees of freedom, one
//! scale per run — the same variance as the normal draws, heavier tails — and without
//! it the very draws a model always made.

use hcm_host::scenario::{drawn_run, Draw, Model, Scenario};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::path::Path;

fn ball(sets: &[&str]) -> Model {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/bouncing_ball.toml");
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    Scenario::load(&path, &sets).unwrap().model().unwrap()
}

/// The drawn ζ of the surface loading (its `noise` b = 0.02) over `runs` exact draws.
fn zetas(model: &Model, runs: usize) -> Vec<f64> {
    let a = model.contacts[0]
        .model
        .normal
        .base
        .get("surface_loading")
        .unwrap();
    let noise = &model.contacts[0].noise;
    let b = noise
        .iter()
        .find(|(n, _)| n == "surface_loading")
        .unwrap()
        .1;
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    (0..runs)
        .map(|_| {
            let run = drawn_run(model, &mut rng, Draw::Exact).unwrap();
            let drawn = run.contacts[0]
                .model
                .normal
                .base
                .get("surface_loading")
                .unwrap();
            (drawn - a) / (a * b)
        })
        .collect()
}

/// Sample variance and kurtosis (E z⁴ / (E z²)², 3 for a normal law).
fn moments(z: &[f64]) -> (f64, f64) {
    let n = z.len() as f64;
    let m2 = z.iter().map(|x| x * x).sum::<f64>() / n;
    let m4 = z.iter().map(|x| x.powi(4)).sum::<f64>() / n;
    (m2, m4 / (m2 * m2))
}

#[test]
fn student_t_draws_keep_the_variance_and_fatten_the_tails() {
    let runs = 40_000;
    let (normal_var, normal_kurt) = moments(&zetas(&ball(&[]), runs));
    let (t_var, t_kurt) = moments(&zetas(&ball(&["variation.tails=6"]), runs));
    // Unit variance both ways (σ of the variance estimate ≈ √(2/n) for the normal law,
    // larger for the t: 6 % is over 4 of them for ν = 6).
    assert!(
        (normal_var - 1.0).abs() < 0.03,
        "normal variance {normal_var}"
    );
    assert!((t_var - 1.0).abs() < 0.06, "t variance {t_var}");
    // The normal law's kurtosis is 3; Student's t with ν = 6 has 3 + 6/(ν − 4) = 6.
    assert!(
        (normal_kurt - 3.0).abs() < 0.15,
        "normal kurtosis {normal_kurt}"
    );
    assert!(t_kurt > 4.5, "t kurtosis {t_kurt}");
    // A share of draws beyond 3σ: 0.27 % for the normal law, 1.4 % for unit-variance t6.
    let beyond = |z: &[f64]| z.iter().filter(|x| x.abs() > 3.0).count() as f64 / z.len() as f64;
    assert!(beyond(&zetas(&ball(&["variation.tails=6"]), runs)) > 0.008);
}

#[test]
fn without_tails_the_draws_are_the_normal_laws_as_before() {
    // tails = 0 draws no scale: the same numbers as a model that never had the field.
    let z0 = zetas(&ball(&[]), 200);
    let z1 = zetas(&ball(&["variation.tails=0"]), 200);
    assert_eq!(z0, z1);
}

#[test]
fn tails_of_two_or_less_are_refused_naming_the_field() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenarios/bouncing_ball.toml");
    for bad in [
        "variation.tails=2",
        "variation.tails=1.5",
        "variation.tails=-3",
    ] {
        let error = Scenario::load(&path, &[bad.to_string()])
            .and_then(|s| s.model())
            .unwrap_err()
            .to_string();
        assert!(
            error.contains("variation.tails") && error.contains("> 2"),
            "{error}"
        );
    }
}
