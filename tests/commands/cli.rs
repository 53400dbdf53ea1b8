//! The `hcm` binary end to end: simulate → CSV → indicators, and bad input.

use hcm_tests::cli::Hcm;
use hcm_tests::scenario;
use std::path::Path;

/// The keys of a model row's indicators and errors (`evaluate --json`, diagnosis.json).
const INDICATORS: [&str; 4] = ["max_force", "impulse", "energy_loss", "duration"];

#[test]
fn simulate_then_indicators_json_round_trip() {
    let hcm = Hcm::new();
    let out = hcm.path("ball.csv");
    let ball = scenario("bouncing_ball.toml");
    let stdout = hcm
        .run("simulate")
        .opt("--scenario", &ball)
        .opt("--out", &out)
        .ok();
    assert!(stdout.contains("ball–ground"), "{stdout}");
    let stdout = hcm
        .run("indicators")
        .opt("--data", &out)
        .opt("--scenario", &ball)
        .arg("--json")
        .ok();
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let summary = &json["summary"][0];
    assert_eq!(summary["runs"], 1);
    let max_force = summary["max_force"]["mean"].as_f64().unwrap();
    assert!((max_force / 2923.6 - 1.0).abs() < 1e-3, "{max_force}");
    assert_eq!(json["runs_without_contact"].as_array().unwrap().len(), 0);
}

#[test]
fn a_bad_override_names_the_field_and_writes_nothing() {
    let hcm = Hcm::new();
    let out = hcm.path("never.csv");
    let stderr = hcm
        .run("simulate")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--set", "body.ball.mass=-1")
        .opt("--out", &out)
        .fails();
    assert!(
        stderr.contains("ball") && stderr.contains("mass"),
        "{stderr}"
    );
    assert!(!out.exists());
    assert_eq!(
        std::fs::read_dir(hcm.dir()).unwrap().count(),
        0,
        "something was left behind"
    );
}

#[test]
fn an_unknown_scenario_key_is_an_error_with_its_line() {
    let hcm = Hcm::new();
    let text = std::fs::read_to_string(scenario("bouncing_ball.toml"))
        .unwrap()
        .replace("end_time", "end_tme");
    let path = hcm.path("typo.toml");
    std::fs::write(&path, text).unwrap();
    let out = hcm.path("x.csv");
    let stderr = hcm
        .run("simulate")
        .opt("--scenario", &path)
        .opt("--out", &out)
        .fails();
    assert!(
        stderr.contains("end_tme") && stderr.contains("typo.toml") && stderr.contains("line"),
        "{stderr}"
    );
    assert!(!out.exists());
}

#[test]
fn indicators_name_the_bad_line_of_a_data_file() {
    let hcm = Hcm::new();
    let out = hcm.path("ball.csv");
    let ball = scenario("bouncing_ball.toml");
    hcm.run("simulate")
        .opt("--scenario", &ball)
        .opt("--out", &out)
        .ok();
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    lines[5] = lines[5].replacen("0.0,", "NaN,", 1);
    std::fs::write(&out, lines.join("\n")).unwrap();
    let stderr = hcm
        .run("indicators")
        .opt("--data", &out)
        .opt("--scenario", &ball)
        .fails();
    assert!(
        stderr.contains("line 6") && stderr.contains("NaN"),
        "{stderr}"
    );
}

#[test]
fn generate_identify_evaluate_through_the_binary() {
    let hcm = Hcm::new();
    let data = hcm.path("data.csv");
    let pm2 = hcm.path("pm2.toml");
    let ball = scenario("bouncing_ball.toml");
    hcm.run("generate")
        .opt("--scenario", &ball)
        .opt("--runs", "10")
        .opt("--seed", "3")
        .opt("--out", &data)
        .ok();
    let (s1, s2) = (hcm.path("data.s1.csv"), hcm.path("data.s2.csv"));
    assert!(s1.exists() && s2.exists());
    hcm.run("identify")
        .opt("--scenario", &ball)
        .opt("--data", &s1)
        .opt("--law", "lankarani_nikravesh")
        .opt("--method", "lsq")
        .opt("--out", &pm2)
        .ok();
    let physics: toml::Table = std::fs::read_to_string(&pm2).unwrap().parse().unwrap();
    let k = physics["contact"][0]["parameters"]["stiffness"]
        .as_float()
        .unwrap();
    assert!(
        (1e9..1e10).contains(&k),
        "stiffness {k} outside the scenario's bounds"
    );
    let stdout = hcm
        .run("evaluate")
        .opt("--scenario", &ball)
        .opt("--data", &s2)
        .opt("--physics", &pm2)
        .arg("--json")
        .ok();
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    let errors = json[0]["models"][0]["errors"].as_object().unwrap();
    assert_eq!(errors.len(), 4);
    assert!(
        INDICATORS
            .iter()
            .all(|&k| errors[k].as_f64().unwrap() < 0.2),
        "{errors:?}"
    );

    // --members: the same table under `conditions`, and each condition's forecast; PM2
    // carries no `noise`, so its members are its replay.
    let stdout = hcm
        .run("evaluate")
        .opt("--scenario", &ball)
        .opt("--data", &s2)
        .opt("--physics", &pm2)
        .opt("--members", "4")
        .arg("--json")
        .ok();
    let with: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(with["conditions"], json);
    let forecast = &with["forecast"][0];
    assert_eq!(forecast["members"], 4);
    for (e, r) in (forecast["crps"].as_array().unwrap().iter())
        .zip(forecast["replay_crps"].as_array().unwrap())
    {
        let (e, r) = (e.as_f64().unwrap(), r.as_f64().unwrap());
        assert!((e - r).abs() <= 1e-12 * r, "{forecast}");
    }

    // train → export (f32 and int8) → evaluate with the residual: the HCM column.
    let trained = hcm.path("residual.json");
    hcm.run("train")
        .opt("--scenario", &ball)
        .opt("--data", &s1)
        .opt("--physics", &pm2)
        .opt("--epochs", "20")
        .opt("--int8-epochs", "2")
        .opt("--out", &trained)
        .ok();
    for weights in ["f32", "int8"] {
        let blob = hcm.path(&format!("residual.{weights}.bin"));
        hcm.run("export")
            .opt("--residual", &trained)
            .opt("--weights", weights)
            .opt("--out", &blob)
            .ok();
        let stdout = hcm
            .run("evaluate")
            .opt("--scenario", &ball)
            .opt("--data", &s2)
            .opt("--physics", &pm2)
            .opt("--residual", &blob)
            .arg("--json")
            .ok();
        let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
        let models = json[0]["models"].as_array().unwrap();
        assert_eq!(models.len(), 2, "{weights}: PM2 and HCM columns");
        assert_eq!(models[1]["model"], "HCM");
        assert_eq!(models[1]["errors"].as_object().unwrap().len(), 4);
    }
    // A missing or foreign trained-residual file is named, and no blob appears.
    let blob = hcm.path("never.bin");
    let stderr = hcm
        .run("export")
        .opt("--residual", &pm2)
        .opt("--out", &blob)
        .fails();
    assert!(stderr.contains("pm2.toml"));
    assert!(!blob.exists());
}

#[test]
fn identify_names_an_empty_data_file() {
    let hcm = Hcm::new();
    let empty = hcm.path("empty.csv");
    std::fs::write(&empty, "").unwrap();
    let out = hcm.path("pm2.toml");
    let stderr = hcm
        .run("identify")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--data", &empty)
        .opt("--law", "hertz")
        .opt("--out", &out)
        .fails();
    assert!(stderr.contains("empty.csv"), "{stderr}");
    assert!(!out.exists());
}

#[test]
fn reproduce_writes_the_report_blobs_and_figures() {
    let hcm = Hcm::new();
    let out = hcm.path("ball");
    hcm.run("reproduce")
        .arg("bouncing-ball")
        .opt("--runs", "12")
        .opt("--method", "lsq")
        .opt("--seed", "4")
        .opt("--scenario", scenario("bouncing_ball.toml"))
        .opt("--out", &out)
        .ok();
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    for needle in [
        "error of PM2",
        "error of HCM",
        "PM2 error (paper)",
        "| identify PM2 |",
    ] {
        assert!(report.contains(needle), "report lacks {needle}:\n{report}");
    }
    for figure in ["contact_force.svg", "force_error.svg"] {
        let svg = std::fs::read_to_string(out.join(figure)).unwrap();
        assert!(svg.matches("<polyline").count() >= 2, "{figure}");
        let png = std::fs::read(out.join(figure.replace(".svg", ".png"))).unwrap();
        assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"), "{figure} as PNG");
    }
    // The trained network and its int8 twin, for `hcm export`.
    assert!(hcm_host::train::TrainedResidual::read(&out.join("residual.json")).is_ok());
    let blob = std::fs::read(out.join("residual.bin")).unwrap();
    assert!(hcm_host::residual::ContactResidual::decode(&blob).is_ok());
}

/// `hcm diagnose` of the flat shot on `data` against the physics file `base`, writing
/// `out`, with extra scenario overrides; its diagnosis.json.
fn diagnose_flat(
    hcm: &Hcm,
    data: &Path,
    base: &Path,
    out: &Path,
    set: &[&str],
) -> serde_json::Value {
    let mut diagnose = hcm
        .run("diagnose")
        .opt("--scenario", scenario("flat_shot.toml"));
    for s in set {
        diagnose = diagnose.opt("--set", s);
    }
    diagnose
        .opt("--data", data)
        .opt("--physics", base)
        .opt("--out", out)
        .ok();
    serde_json::from_str(&std::fs::read_to_string(out.join("diagnosis.json")).unwrap()).unwrap()
}

/// Field `key` of `model`'s row in a gain table of diagnosis.json.
fn row<'a>(table: &'a serde_json::Value, model: &str, key: &str) -> &'a serde_json::Value {
    &table["rows"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["model"] == model)
        .unwrap()[key]
}

/// The gain table of diagnosis.json for `group`.
fn group<'a>(json: &'a serde_json::Value, group: &str) -> &'a serde_json::Value {
    json["gain"]
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["group"] == group)
        .unwrap_or_else(|| panic!("no gain table `{group}` in {}", json["gain"]))
}

#[test]
fn diagnose_names_the_variable_stiffness_damping_missing_from_lankarani_nikravesh() {
    // Flat shot, 10 speeds × 4 runs, data from the variable-stiffness law (PM1) without
    // parameter noise, base = Lankarani–Nikravesh fitted by lsq. The VS damping
    // 2λ·√(k(δ)·m_e)·δ·δ̇ grows like δ^1.25·δ̇ and does not scale with 1/δ̇0.
    let hcm = Hcm::new();
    let (data, base, out) = (
        hcm.path("data.csv"),
        hcm.path("base.toml"),
        hcm.path("diagnosis"),
    );
    let flat = scenario("flat_shot.toml");
    hcm.run("generate")
        .opt("--scenario", &flat)
        .opt("--set", "contact.0.noise={}")
        .opt("--runs", "4")
        .opt("--seed", "3")
        .opt("--out", &data)
        .ok();
    hcm.run("identify")
        .opt("--scenario", &flat)
        .opt("--data", &data)
        .opt("--law", "lankarani_nikravesh")
        .opt("--method", "lsq")
        .opt("--out", &base)
        .ok();
    let json = diagnose_flat(&hcm, &data, &base, &out, &[]);
    let causes = json["causes"].as_array().unwrap();
    assert_eq!(causes.len(), 1, "{causes:?}");
    // The flat shot's runs start in contact: no flight before the event to weigh the
    // momentum against, so no gain (null), rather than a guess.
    assert!(json["sensor_gain"].is_null(), "{}", json["sensor_gain"]);
    assert_eq!(causes[0]["effect"], "hysteresis_damping");
    let p = causes[0]["parameters"]["exponent"].as_f64().unwrap();
    assert!((1.0..1.5).contains(&p), "exponent {p}");
    // The held-out speeds: v0.95 (the scenario's S2) and, outside the fitted range, v1.0.
    // The paper's LN fit misses v0.95's energy loss by 33 %; ours (lsq on the force
    // curves of the other nine speeds) by about half that, still far outside the noise.
    // The HCM's network is off outside its training envelope (it is the base there);
    // the named physics carries over.
    let beyond = diagnose_flat(
        &hcm,
        &data,
        &base,
        &hcm.path("beyond"),
        &["experiment.holdout_conditions=[\"v1.0\"]"],
    );
    assert_eq!(beyond["answer"], "hysteresis_damping");
    // The report's answer line: the cause with its values and intervals, and the shares.
    let report = std::fs::read_to_string(hcm.path("beyond").join("report.md")).unwrap();
    let line = report
        .lines()
        .find(|l| l.starts_with("**Answer: "))
        .unwrap();
    for part in [
        "hysteresis_damping (coefficient = ",
        "exponent = ",
        "% left unexplained",
    ] {
        assert!(line.contains(part), "no `{part}` in {line}");
    }
    for (json, speed) in [(&json, "v0.95"), (&beyond, "v1.0")] {
        let table = group(json, &format!("condition {speed}"));
        let energy = |model: &str| row(table, model, "errors")["energy_loss"].as_f64().unwrap();
        println!(
            "{speed} energy-loss error: base {:.2} %, extended {:.2} %, HCM {:.2} %",
            100.0 * energy("base"),
            100.0 * energy("extended"),
            100.0 * energy("HCM")
        );
        assert!(energy("base") > 0.1, "{table}");
        assert!(energy("extended") < 0.25 * energy("base"), "{table}");
    }
    // Where it was fitted, too, the extension removes most of the base's force error.
    let fitted = &json["in_sample"];
    assert_eq!(fitted["group"], "training runs");
    let excess = |model: &str| row(fitted, model, "excess_rmse").as_f64().unwrap();
    assert!(excess("extended") < 0.5 * excess("base"), "{fitted}");
    // And the extended model is a physics file the other commands read.
    let extended = out.join("extended.toml");
    hcm.run("evaluate")
        .opt("--scenario", &flat)
        .opt("--data", &data)
        .opt("--physics", &extended)
        .ok();
    for file in ["report.md", "residual_vs_time.svg", "residual_vs_time.png"] {
        assert!(out.join(file).exists(), "{file}");
    }
}
