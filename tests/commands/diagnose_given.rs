//! `hcm diagnose` of a model given as it is — a physics file written by hand, without a
//! fit record — on 3D force data: with nothing of the model's own to fit, each
//! candidate is judged against the model where it stands. (This path once failed with
//! "no start of the least-squares fit gave a finite wrench": a fit of zero unknowns.)

use hcm_tests::cli::Hcm;

/// The cube drop's own contact, written by hand.
const GIVEN: &str = r#"[[contact]]
bodies = ["cube", "ground"]
law = "impact"

[contact.parameters]
stiffness = 1e7
exponent = 1.5
max_damping = 50.0
full_damping_depth = 1e-4

[contact.friction]
mu_static = 0.3
mu_dynamic = 0.2
v_static = 1e-3
v_dynamic = 1e-2
"#;

#[test]
fn a_hand_written_model_is_judged_where_it_stands_and_nothing_is_named_on_its_own_data() {
    let hcm = Hcm::new();
    let scenario = hcm_tests::scenario("cube_drop.toml");
    hcm.run("generate")
        .opt("--scenario", &scenario)
        .opt("--runs", "8")
        .opt("--out", hcm.path("gen"))
        .ok();
    std::fs::write(hcm.path("given.toml"), GIVEN).unwrap();
    hcm.run("diagnose")
        .opt("--scenario", &scenario)
        .opt("--data", hcm.path("gen"))
        .opt("--physics", hcm.path("given.toml"))
        .opt("--out", hcm.path("diagnosis"))
        .ok();
    let text = std::fs::read_to_string(hcm.path("diagnosis/diagnosis.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let diagnosis = &json["diagnosis"];
    // The catalogue was judged: one round, every wrench candidate that changes the
    // model scored (no law swaps: those need a fitted base).
    let candidates = diagnosis["rounds"][0]["candidates"].as_array().unwrap();
    assert!(candidates.len() >= 10, "{candidates:?}");
    assert!(candidates
        .iter()
        .all(|c| !c["name"].as_str().unwrap().starts_with("law:")));
    // The data are the model's own (each run's contact scattered by 2 %): nothing named.
    assert_eq!(
        diagnosis["named"].as_array().unwrap().len(),
        0,
        "{}",
        diagnosis["answer"]
    );
    assert!(diagnosis["answer"].as_str().unwrap().starts_with("none"));
}
