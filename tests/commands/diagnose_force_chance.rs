//! `hcm diagnose --chance` on force data: 60 runs of the ball, its surface loading
//! scattered by 10 % from run to run (Eq 18), against a physics file of the law they
//! were generated with. The scatter it names reaches every output: the answer, the report's
//! section 5, diagnosis.json's `chance`, and extended.toml's `noise`, which a physics
//! file carries back into every command.

use hcm_tests::cli::Hcm;

/// The ball's own law, written by hand (no fit record: the base as given).
const GIVEN: &str = r#"[[contact]]
bodies = ["ball", "ground"]
law = "variable_stiffness"

[contact.parameters]
surface_loading = 2.0
damping = 987.9
"#;

#[test]
fn a_named_scatter_reaches_the_report_the_json_and_the_extended_physics() {
    let hcm = Hcm::new();
    let scenario = hcm_tests::scenario("bouncing_ball.toml");
    hcm.run("generate")
        .opt("--scenario", &scenario)
        .opt("--runs", "60")
        .opt("--set", "contact.0.noise={surface_loading=0.1}")
        .opt("--out", hcm.path("gen"))
        .ok();
    std::fs::write(hcm.path("given.toml"), GIVEN).unwrap();
    let printed = hcm
        .run("diagnose")
        .opt("--scenario", &scenario)
        .opt("--data", hcm.path("gen"))
        .opt("--physics", hcm.path("given.toml"))
        .opt("--out", hcm.path("diagnosis"))
        .arg("--chance")
        .ok();
    assert!(
        printed.contains("## 5. Chance (held-out runs)"),
        "{printed}"
    );
    let text = std::fs::read_to_string(hcm.path("diagnosis/diagnosis.json")).unwrap();
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let named = json["chance"]["named"].as_array().unwrap();
    assert_eq!(named[0]["effect"], "surface_loading_scatter", "{named:?}");
    assert!(json["answer"]
        .as_str()
        .unwrap()
        .contains("surface_loading_scatter"));
    let sigma = named[0]["value"].as_f64().unwrap();
    // extended.toml carries the scatter as the contact's noise, σ as named.
    let extended = std::fs::read_to_string(hcm.path("diagnosis/extended.toml")).unwrap();
    let physics: toml::Table = toml::from_str(&extended).unwrap();
    let noise = &physics["contact"].as_array().unwrap()[0]["noise"];
    assert_eq!(
        noise["surface_loading"].as_float(),
        Some(sigma),
        "{extended}"
    );
    // Without --chance: no section 5, no noise.
    hcm.run("diagnose")
        .opt("--scenario", &scenario)
        .opt("--data", hcm.path("gen"))
        .opt("--physics", hcm.path("given.toml"))
        .opt("--out", hcm.path("plain"))
        .ok();
    let plain = std::fs::read_to_string(hcm.path("plain/report.md")).unwrap();
    assert!(!plain.contains("## 5. Chance"));
    let extended = std::fs::read_to_string(hcm.path("plain/extended.toml")).unwrap();
    assert!(!extended.contains("noise"), "{extended}");
}
