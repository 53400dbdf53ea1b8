//! `hcm diagnose --from-poses --out DIR`: a directory like the force diagnosis' —
//! diagnosis.json and report.md always; where a chance is named, the held-out tosses'
//! forecast by the extended model (its report section and figures) and extended.toml,
//! the physics file with the chance, which `hcm predict --members` draws from.

use hcm_tests::cli::Hcm;
use std::path::{Path, PathBuf};

fn tosses_csv() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data/contactnets-cube/tosses.csv")
}

fn physics() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/results/cube-toss/physics.toml")
}

fn diagnose(hcm: &Hcm, first: usize, chance: bool, out: &Path) -> String {
    let mut call = hcm
        .run("diagnose")
        .arg("--from-poses")
        .opt("--scenario", hcm_tests::scenario("cube_toss.toml"))
        .opt("--physics", physics())
        .opt("--data", tosses_csv())
        .opt("--first", first.to_string())
        .opt("--out", out);
    if chance {
        call = call.arg("--chance");
    }
    call.ok()
}

#[test]
fn a_directory_gets_the_report_and_the_json_and_no_extended_model_for_nothing_named() {
    let hcm = Hcm::new();
    let out = hcm.path("diag");
    let printed = diagnose(&hcm, 8, false, &out);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("diagnosis.json")).unwrap())
            .unwrap();
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    let answer = json["answer"].as_str().unwrap();
    assert!(printed.contains(answer), "{printed}");
    // The report holds the answer and every candidate of every round.
    assert!(report.contains(answer), "{report}");
    for round in json["rounds"].as_array().unwrap() {
        for candidate in round["candidates"].as_array().unwrap() {
            let name = candidate["name"].as_str().unwrap();
            assert!(
                report.contains(&format!("| {name} |")),
                "{name} missing:\n{report}"
            );
        }
    }
    if json["named"].as_array().unwrap().is_empty() {
        assert!(!out.join("extended.toml").exists());
        assert!(!out.join("forecast_calibration.svg").exists());
    }
    // A `.json` --out is still the diagnosis alone, the same one.
    let alone = hcm.path("alone.json");
    diagnose(&hcm, 8, false, &alone);
    assert_eq!(
        std::fs::read_to_string(&alone).unwrap(),
        std::fs::read_to_string(out.join("diagnosis.json")).unwrap()
    );
}

#[test]
#[ignore = "study, over 12 s on 2 cores: cargo test -- --include-ignored"]
fn a_named_chance_is_forecast_drawn_and_written_as_physics() {
    let hcm = Hcm::new();
    let out = hcm.path("diag");
    diagnose(&hcm, 80, true, &out);
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("diagnosis.json")).unwrap())
            .unwrap();
    let named = json["named"].as_array().unwrap();
    assert_eq!(named.len(), 1, "{json}");
    let (name, sigma) = (
        named[0][0].as_str().unwrap(),
        named[0][1][0][1].as_f64().unwrap(),
    );
    assert!(
        [
            "fixed_tilt",
            "contact_scatter",
            "fixed_height",
            "start_uncertainty"
        ]
        .contains(&name),
        "{name}"
    );
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        report.contains("## Forecast by the named chance"),
        "{report}"
    );
    for figure in ["forecast_calibration", "forecast_bands"] {
        for ext in ["svg", "png"] {
            let file = out.join(format!("{figure}.{ext}"));
            assert!(std::fs::metadata(&file).unwrap().len() > 1000, "{file:?}");
        }
    }
    // extended.toml carries the named spread where a forecast reads it.
    let extended = std::fs::read_to_string(out.join("extended.toml")).unwrap();
    let carried = match name {
        "contact_scatter" => extended.contains("noise"),
        other => extended.contains(&format!(
            "variation.{}=",
            other.replace("_uncertainty", "_state")
        )),
    };
    assert!(carried, "{name} = {sigma} not in:\n{extended}");
    // And `hcm predict --physics extended.toml --members` draws from it: its ensemble
    // spreads: on most frames the members differ.
    let members = hcm.path("members.csv");
    hcm.run("predict")
        .opt("--scenario", hcm_tests::scenario("cube_toss.toml"))
        .opt("--physics", out.join("extended.toml"))
        .opt("--data", tosses_csv())
        .opt("--first", "6")
        .opt("--members", "4")
        .opt("--out", &members)
        .ok();
    let text = std::fs::read_to_string(&members).unwrap();
    let rows: Vec<&str> = text.lines().skip(1).collect();
    let run = rows[0].split(',').next().unwrap();
    // Per frame time of the first toss: the members' rows (member column dropped).
    let mut frames: std::collections::BTreeMap<&str, std::collections::BTreeSet<&str>> =
        Default::default();
    for row in rows.iter().filter(|r| r.split(',').next() == Some(run)) {
        let time = row.split(',').nth(2).unwrap();
        let (state, _member) = row.rsplit_once(',').unwrap();
        frames.entry(time).or_default().insert(state);
    }
    let spread = frames.values().filter(|states| states.len() > 1).count();
    assert!(
        spread * 2 > frames.len(),
        "{spread} of {} frames differ",
        frames.len()
    );
}
