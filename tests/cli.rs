//! The `hcm` binary end to end: simulate → CSV → indicators, and bad input.

use std::path::{Path, PathBuf};
use std::process::Command;

fn hcm(args: &[&str]) -> std::process::Output {
    Command::new(hcm_tests::cli::hcm_exe())
        .args(args)
        .output()
        .expect("hcm runs")
}

/// Runs `hcm` and asserts it succeeded, showing its standard error otherwise.
fn hcm_ok(args: &[&str]) -> std::process::Output {
    let run = hcm(args);
    assert!(
        run.status.success(),
        "hcm {args:?} failed:\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    run
}

fn scenario(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenarios")
        .join(name)
        .display()
        .to_string()
}

#[test]
fn simulate_then_indicators_json_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let out: PathBuf = dir.path().join("ball.csv");
    let ball = scenario("bouncing_ball.toml");
    let run = hcm_ok(&[
        "simulate",
        "--scenario",
        &ball,
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(stdout.contains("ball–ground"), "{stdout}");
    let run = hcm_ok(&[
        "indicators",
        "--data",
        out.to_str().unwrap(),
        "--scenario",
        &ball,
        "--json",
    ]);
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let summary = &json["summary"][0];
    assert_eq!(summary["runs"], 1);
    let max_force = summary["max_force"]["mean"].as_f64().unwrap();
    assert!((max_force / 2923.6 - 1.0).abs() < 1e-3, "{max_force}");
    assert_eq!(json["runs_without_contact"].as_array().unwrap().len(), 0);
}

#[test]
fn a_bad_override_names_the_field_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("never.csv");
    let ball = scenario("bouncing_ball.toml");
    let run = hcm(&[
        "simulate",
        "--scenario",
        &ball,
        "--set",
        "body.ball.mass=-1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("ball") && stderr.contains("mass"),
        "{stderr}"
    );
    assert!(!out.exists());
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "something was left behind"
    );
}

#[test]
fn an_unknown_scenario_key_is_an_error_with_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(scenario("bouncing_ball.toml"))
        .unwrap()
        .replace("end_time", "end_tme");
    let path = dir.path().join("typo.toml");
    std::fs::write(&path, text).unwrap();
    let out = dir.path().join("x.csv");
    let run = hcm(&[
        "simulate",
        "--scenario",
        path.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("end_tme") && stderr.contains("typo.toml") && stderr.contains("line"),
        "{stderr}"
    );
    assert!(!out.exists());
}

#[test]
fn indicators_name_the_bad_line_of_a_data_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ball.csv");
    let ball = scenario("bouncing_ball.toml");
    hcm_ok(&[
        "simulate",
        "--scenario",
        &ball,
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&out).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    lines[5] = lines[5].replacen("0.0,", "NaN,", 1);
    std::fs::write(&out, lines.join("\n")).unwrap();
    let run = hcm(&[
        "indicators",
        "--data",
        out.to_str().unwrap(),
        "--scenario",
        &ball,
    ]);
    assert!(!run.status.success());
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("line 6") && stderr.contains("NaN"),
        "{stderr}"
    );
}

#[test]
fn generate_identify_evaluate_through_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data.csv");
    let pm2 = dir.path().join("pm2.toml");
    let ball = scenario("bouncing_ball.toml");
    hcm_ok(&[
        "generate",
        "--scenario",
        &ball,
        "--runs",
        "10",
        "--seed",
        "3",
        "--out",
        data.to_str().unwrap(),
    ]);
    let (s1, s2) = (
        dir.path().join("data.s1.csv"),
        dir.path().join("data.s2.csv"),
    );
    assert!(s1.exists() && s2.exists());
    hcm_ok(&[
        "identify",
        "--scenario",
        &ball,
        "--data",
        s1.to_str().unwrap(),
        "--law",
        "lankarani_nikravesh",
        "--method",
        "lsq",
        "--out",
        pm2.to_str().unwrap(),
    ]);
    let physics: toml::Table = std::fs::read_to_string(&pm2).unwrap().parse().unwrap();
    let k = physics["contact"][0]["parameters"]["stiffness"]
        .as_float()
        .unwrap();
    assert!(
        (1e9..1e10).contains(&k),
        "stiffness {k} outside the scenario's bounds"
    );
    let run = hcm_ok(&[
        "evaluate",
        "--scenario",
        &ball,
        "--data",
        s2.to_str().unwrap(),
        "--physics",
        pm2.to_str().unwrap(),
        "--json",
    ]);
    let json: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    let errors = json[0]["models"][0]["errors"].as_array().unwrap();
    assert_eq!(errors.len(), 4);
    assert!(
        errors.iter().all(|e| e.as_f64().unwrap() < 0.2),
        "{errors:?}"
    );

    // train → export (f32 and int8) → evaluate with the residual: the HCM column.
    let trained = dir.path().join("residual.json");
    hcm_ok(&[
        "train",
        "--scenario",
        &ball,
        "--data",
        s1.to_str().unwrap(),
        "--physics",
        pm2.to_str().unwrap(),
        "--epochs",
        "20",
        "--int8-epochs",
        "2",
        "--out",
        trained.to_str().unwrap(),
    ]);
    for weights in ["f32", "int8"] {
        let blob = dir.path().join(format!("residual.{weights}.bin"));
        hcm_ok(&[
            "export",
            "--residual",
            trained.to_str().unwrap(),
            "--weights",
            weights,
            "--out",
            blob.to_str().unwrap(),
        ]);
        let run = hcm_ok(&[
            "evaluate",
            "--scenario",
            &ball,
            "--data",
            s2.to_str().unwrap(),
            "--physics",
            pm2.to_str().unwrap(),
            "--residual",
            blob.to_str().unwrap(),
            "--json",
        ]);
        let json: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
        let models = json[0]["models"].as_array().unwrap();
        assert_eq!(models.len(), 2, "{weights}: PM2 and HCM columns");
        assert_eq!(models[1]["errors"].as_array().unwrap().len(), 4);
    }
    // A missing or foreign trained-residual file is named, and no blob appears.
    let blob = dir.path().join("never.bin");
    let run = hcm(&[
        "export",
        "--residual",
        pm2.to_str().unwrap(),
        "--out",
        blob.to_str().unwrap(),
    ]);
    assert!(!run.status.success());
    assert!(String::from_utf8_lossy(&run.stderr).contains("pm2.toml"));
    assert!(!blob.exists());
}

#[test]
fn identify_names_an_empty_data_file() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty.csv");
    std::fs::write(&empty, "").unwrap();
    let out = dir.path().join("pm2.toml");
    let ball = scenario("bouncing_ball.toml");
    let run = hcm(&[
        "identify",
        "--scenario",
        &ball,
        "--data",
        empty.to_str().unwrap(),
        "--law",
        "hertz",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(!run.status.success());
    assert!(
        String::from_utf8_lossy(&run.stderr).contains("empty.csv"),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(!out.exists());
}

#[test]
fn reproduce_writes_the_report_blobs_and_figures() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("ball");
    let ball = scenario("bouncing_ball.toml");
    hcm_ok(&[
        "reproduce",
        "bouncing-ball",
        "--runs",
        "12",
        "--method",
        "lsq",
        "--seed",
        "4",
        "--scenario",
        &ball,
        "--out",
        out.to_str().unwrap(),
    ]);
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
fn diagnose_flat(data: &Path, base: &Path, out: &Path, set: &[&str]) -> serde_json::Value {
    let flat = scenario("flat_shot.toml");
    let mut args = vec!["diagnose", "--scenario", &flat];
    for s in set {
        args.extend(["--set", s]);
    }
    args.extend([
        "--data",
        data.to_str().unwrap(),
        "--physics",
        base.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    hcm_ok(&args);
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
    let dir = tempfile::tempdir().unwrap();
    let (data, base, out) = (
        dir.path().join("data.csv"),
        dir.path().join("base.toml"),
        dir.path().join("diagnosis"),
    );
    let flat = scenario("flat_shot.toml");
    hcm_ok(&[
        "generate",
        "--scenario",
        &flat,
        "--set",
        "contact.0.noise={}",
        "--runs",
        "4",
        "--seed",
        "3",
        "--out",
        data.to_str().unwrap(),
    ]);
    hcm_ok(&[
        "identify",
        "--scenario",
        &flat,
        "--data",
        data.to_str().unwrap(),
        "--law",
        "lankarani_nikravesh",
        "--method",
        "lsq",
        "--out",
        base.to_str().unwrap(),
    ]);
    let json = diagnose_flat(&data, &base, &out, &[]);
    let causes = json["causes"].as_array().unwrap();
    assert_eq!(causes.len(), 1, "{causes:?}");
    assert_eq!(causes[0]["effect"], "hysteresis_damping");
    let p = causes[0]["parameters"]["exponent"].as_f64().unwrap();
    assert!((1.0..1.5).contains(&p), "exponent {p}");
    // The held-out speeds: v0.95 (the scenario's S2) and, outside the fitted range, v1.0.
    // The paper's LN fit misses v0.95's energy loss by 33 %; ours (lsq on the force
    // curves of the other nine speeds) by about half that, still far outside the noise.
    // The HCM's network is off outside its training envelope (it is the base there);
    // the named physics carries over.
    let beyond = diagnose_flat(
        &data,
        &base,
        &dir.path().join("beyond"),
        &["experiment.holdout_conditions=[\"v1.0\"]"],
    );
    assert_eq!(beyond["answer"], "hysteresis_damping");
    for (json, speed) in [(&json, "v0.95"), (&beyond, "v1.0")] {
        let table = group(json, &format!("condition {speed}"));
        let energy = |model: &str| row(table, model, "errors")[2].as_f64().unwrap();
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
    hcm_ok(&[
        "evaluate",
        "--scenario",
        &flat,
        "--data",
        data.to_str().unwrap(),
        "--physics",
        extended.to_str().unwrap(),
    ]);
    for file in ["report.md", "residual_vs_time.svg", "residual_vs_time.png"] {
        assert!(out.join(file).exists(), "{file}");
    }
}
