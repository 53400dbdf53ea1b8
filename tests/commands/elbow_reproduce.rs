//! `hcm reproduce elbow-toss` on the first 24 real elbow tosses, fits tiny and no
//! diagnosis: a mechanism's run end to end — both links' contacts fitted as one (the
//! physics file lists both, alike), both links' inertia among its `--set`s, every toss
//! scored by a fold that never saw it, and the physics file with `hcm predict` giving
//! each held-out toss's links' mean scores and the predicted file back.

use hcm_tests::cli::Hcm;
use serde_json::Value;
use std::path::{Path, PathBuf};

fn tosses_csv() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data/contactnets-elbow/tosses.csv")
}

#[test]
fn a_mechanism_s_reproduction_fits_both_links_and_its_physics_file_predicts_the_same() {
    let hcm = Hcm::new();
    hcm.run("reproduce")
        .arg("elbow-toss")
        .opt("--data", tosses_csv())
        .opt("--first", "24")
        .opt("--population", "3")
        .opt("--generations", "1")
        .opt("--polish", "2")
        .arg("--no-diagnosis")
        .opt("--out", "elbow")
        .ok();
    let out = hcm.path("elbow");
    let text = std::fs::read_to_string(out.join("results.json")).unwrap();
    let results: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(results["name"], "elbow-toss");
    assert_eq!(results["fit_stride"], 4);
    let cross = (results["scores"].as_array().unwrap().iter())
        .find(|r| r["part"] == "cross-validated" && r["model"] == "fitted")
        .unwrap();
    assert_eq!(cross["position"]["count"], 24, "{cross}");
    let physics = std::fs::read_to_string(out.join("physics.toml")).unwrap();
    let contacts = physics.split("[fit]").next().unwrap();
    let contacts: Vec<&str> = contacts.split("[[contact]]").skip(1).collect();
    assert_eq!(contacts.len(), 2, "{physics}");
    let body = |c: &str| c.replacen("\"elbow_2\"", "\"elbow_1\"", 1);
    assert_eq!(
        body(contacts[0]),
        body(contacts[1]),
        "the links' contacts alike"
    );
    let sets: Vec<&str> = (results["sets"].as_array().unwrap().iter())
        .map(|s| s.as_str().unwrap())
        .collect();
    for link in ["body.elbow_1.inertia=", "body.elbow_2.inertia="] {
        assert!(sets.iter().any(|s| s.starts_with(link)), "{sets:?}");
    }
    hcm.run("predict")
        .opt("--scenario", hcm_tests::scenario("elbow_toss.toml"))
        .opt("--physics", out.join("physics.toml"))
        .opt("--data", out.join("held_out.csv"))
        .opt("--out", "predicted.csv")
        .opt("--scores", "scores.csv")
        .ok();
    let scores = std::fs::read_to_string(hcm.path("scores.csv")).unwrap();
    let means: Vec<Vec<&str>> = (scores.lines().skip(1))
        .map(|l| l.split(',').collect::<Vec<_>>())
        .filter(|cells| cells[1] == "all")
        .collect();
    let tosses = results["held_out"].as_array().unwrap();
    assert_eq!(means.len(), tosses.len());
    for (cells, toss) in means.iter().zip(tosses) {
        assert_eq!(cells[0], toss["run"].as_str().unwrap());
        for (cell, expected) in [(5, &toss["fitted"][0]), (6, &toss["fitted"][1])] {
            let (got, expected): (f64, f64) =
                (cells[cell].parse().unwrap(), expected.as_f64().unwrap());
            assert!(
                (got - expected).abs() <= 1e-9 * expected.abs().max(1.0),
                "{got} vs {expected}"
            );
        }
    }
    assert_eq!(
        std::fs::read(hcm.path("predicted.csv")).unwrap(),
        std::fs::read(out.join("predicted_held_out.csv")).unwrap()
    );
}
