//! `hcm reproduce` writes `results.json` beside `report.md`: every table of the report
//! for programs. On the ball, the HCM's error is below PM2's on each indicator.

use hcm_tests::cli::hcm_exe;
use serde_json::Value;
use std::path::Path;
use std::process::Command;

/// The indicator keys of a model row, in the report's order.
const INDICATORS: [&str; 4] = ["max_force", "impulse", "energy_loss", "duration"];

/// The indicators' row labels in the report's tables, in [`INDICATORS`] order.
const LABELS: [&str; 4] = [
    "maximum contact force",
    "contact impulse",
    "contact energy loss",
    "contact duration",
];

/// The cell of the report's S2 table (the table headed `| indicator | S2 mean |`) in
/// the row labelled `label` and the column headed `model`.
fn cell<'a>(report: &'a str, label: &str, model: &str) -> &'a str {
    let cells = |line: &'a str| -> Vec<&'a str> {
        let inner = line.trim().trim_start_matches('|').trim_end_matches('|');
        inner.split('|').map(str::trim).collect()
    };
    let mut lines = report
        .lines()
        .skip_while(|l| !l.starts_with("| indicator | S2 mean |"));
    let header = cells(
        lines
            .next()
            .unwrap_or_else(|| panic!("no S2 table:\n{report}")),
    );
    let column = (header.iter().position(|h| *h == model))
        .unwrap_or_else(|| panic!("no column `{model}` in {header:?}"));
    let row = (lines.take_while(|l| l.starts_with('|')).map(cells))
        .find(|row| row[0] == label)
        .unwrap_or_else(|| panic!("no row `{label}` in the S2 table:\n{report}"));
    row[column]
}

/// A printed quantity such as `8.67294 mJ` or `2924.31 N`, in SI units.
fn si(printed: &str) -> f64 {
    let (number, unit) = printed
        .split_once(' ')
        .unwrap_or_else(|| panic!("`{printed}` is not `number unit`"));
    let number: f64 = number.parse().unwrap_or_else(|_| panic!("`{printed}`"));
    let factor = match unit {
        "N" | "N·s" | "J" | "s" => 1.0,
        "kN" => 1e3,
        "mN·s" | "mJ" | "ms" => 1e-3,
        "µJ" | "µs" => 1e-6,
        other => panic!("unit `{other}` of `{printed}`"),
    };
    number * factor
}

/// `hcm reproduce bouncing-ball` with `args`, into `out`: its results.json and report.md.
fn reproduce(out: &Path, args: &[&str]) -> (Value, String) {
    let run = Command::new(hcm_exe())
        .args(["reproduce", "bouncing-ball", "--out", out.to_str().unwrap()])
        .args(args)
        .output()
        .expect("hcm runs");
    assert!(
        run.status.success(),
        "hcm reproduce failed:\n{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let json = std::fs::read_to_string(out.join("results.json")).unwrap();
    let report = std::fs::read_to_string(out.join("report.md")).unwrap();
    (serde_json::from_str(&json).unwrap(), report)
}

/// The row of `model` in the S2 table.
fn row<'a>(results: &'a Value, model: &str) -> &'a Value {
    results["validation"]["models"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["model"] == model)
        .unwrap_or_else(|| panic!("no row `{model}` in {}", results["validation"]))
}

/// `key` of `values` (an indicators or errors object) as a number.
fn number(values: &Value, key: &str) -> f64 {
    values[key]
        .as_f64()
        .unwrap_or_else(|| panic!("`{key}` is no number in {values}"))
}

#[test]
fn on_the_ball_the_hcm_beats_pm2_on_every_indicator() {
    // The ball without the run-to-run parameter scatter (Eq 18) but with the sensor
    // noise (Eq 19, σ = 15 N), and half the runs in S2. With the scatter, each run's
    // true max force and duration move by ≈ 0.7 %, so a CI-sized S2 (5–50 runs) is
    // off by more than PM2's own error there (0.1–0.3 %) and HCM < PM2 is a coin toss
    // on those two (the paper's 100-run S2 settles it). Measured in release, seeds
    // 1–20: HCM < PM2 on all four every time, HCM/PM2 at most 0.51 (duration), 0.32
    // (max force), 0.22 (impulse), 0.34 (energy loss).
    let dir = tempfile::tempdir().unwrap();
    for seed in ["1", "2", "3"] {
        let args = [
            "--seed",
            seed,
            "--runs",
            "100",
            "--method",
            "lsq",
            "--set",
            "contact.0.noise={}",
            "--set",
            "experiment.holdout_fraction=0.5",
        ];
        let (results, report) = reproduce(&dir.path().join(seed), &args);
        assert_eq!(
            results["validation"]["runs"], 50,
            "half of the 100 runs in S2"
        );
        hcm_below_pm2(&results, seed);
        same_table(&results, &report);
        reads_on_its_own(&results, &report);
    }
}

/// HCM < PM2 on each indicator, each error being Eq 20's of the row's indicator
/// against the S2 mean.
fn hcm_below_pm2(results: &Value, seed: &str) {
    let validation = &results["validation"];
    let (pm2, hcm) = (row(results, "PM2"), row(results, "HCM"));
    for key in INDICATORS {
        let (pm2_error, hcm_error) = (number(&pm2["errors"], key), number(&hcm["errors"], key));
        println!(
            "seed {seed} {key}: PM2 {:.3} %, HCM {:.3} %",
            100.0 * pm2_error,
            100.0 * hcm_error
        );
        assert!(
            hcm_error < pm2_error,
            "seed {seed} {key}: PM2 {pm2} HCM {hcm}"
        );
        let measured = number(&validation["measured"], key);
        for model in [pm2, hcm] {
            let value = number(&model["indicators"], key);
            let eq20 = ((measured - value) / measured).abs();
            assert!(
                (number(&model["errors"], key) - eq20).abs() <= 1e-12,
                "{key}: {model}"
            );
        }
    }
}

/// The report shows the numbers of results.json: every model's indicators, the
/// paper's figures (as fractions in the JSON) and every stage's time.
fn same_table(results: &Value, report: &str) {
    assert_eq!(results["example"], "bouncing-ball");
    for model in ["PM2", "HCM", "HCM int8"] {
        for (key, label) in INDICATORS.iter().zip(LABELS) {
            let value = number(&row(results, model)["indicators"], key);
            let printed = cell(report, label, model);
            // Six significant digits, as many as `{:.5e}` shows: a rounding error of at
            // most half a unit in the sixth digit.
            let shown = si(printed);
            assert!(
                (shown - value).abs() <= 5.000_001e-6 * value.abs(),
                "{model} {key}: {value} printed as {printed}:\n{report}"
            );
        }
    }
    assert_eq!(results["paper"]["pm2"]["energy_loss"], 0.0805);
    assert!(report.contains("| contact energy loss | ") && report.contains(" | 8.05 % | "));
    let stages: Vec<&str> = results["timings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["stage"].as_str().unwrap())
        .collect();
    assert_eq!(
        stages,
        [
            "generate + split",
            "identify PM2",
            "train (+ int8 twin)",
            "export",
            "evaluate + figures",
            "write files"
        ]
    );
    for stage in stages {
        assert!(report.contains(&format!("| {stage} | ")), "{stage}");
    }
}

/// The report reads without the paper: the setup in a sentence from the scenario's
/// bodies, every term glossed, numbers in plain notation, the example by its
/// command-line name, and each figure embedded with a caption.
fn reads_on_its_own(results: &Value, report: &str) {
    assert!(
        report.contains("**Setup.** `ball` (a steel sphere, radius 12.7 mm, mass 66.93 g) starts at rest 100 mm above `ground`"),
        "{report}"
    );
    assert!(report.contains("hits it at 1.401 m/s"), "{report}");
    assert!(report.contains("bouncing-ball") && !report.contains("BouncingBall"));
    let glossary = report
        .split("## What the words mean")
        .nth(1)
        .and_then(|rest| rest.split("\n## ").next())
        .unwrap_or_else(|| panic!("no glossary:\n{report}"));
    for term in [
        "**PM1**",
        "**S1**",
        "**S2**",
        "**PM2**",
        "**HCM**",
        "**HCM int8**",
        "**Error** (the paper's Eq 20)",
        "*envelope*",
        "*residual*",
    ] {
        assert!(
            glossary.contains(term),
            "{term} is not glossed:\n{glossary}"
        );
    }
    // No number in scientific notation such as 2.91186e3 or 4.0e-7.
    let bytes = report.as_bytes();
    for (i, window) in bytes.windows(3).enumerate() {
        let exponent = window[0].is_ascii_digit()
            && (window[1] == b'e' || window[1] == b'E')
            && (window[2].is_ascii_digit() || window[2] == b'-' || window[2] == b'+');
        assert!(
            !exponent,
            "scientific notation at {}",
            &report[i.saturating_sub(20)..(i + 10).min(report.len())]
        );
    }
    for png in results["figures"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(Value::as_str)
        .filter(|f| f.ends_with(".png"))
    {
        let embedded = report
            .split(&format!("]({png})\n\n"))
            .nth(1)
            .unwrap_or_else(|| panic!("{png} is not embedded:\n{report}"));
        assert!(
            embedded.starts_with('*') && embedded.lines().next().unwrap().len() > 40,
            "{png} has no caption"
        );
    }
    // A takeaway per table, computed from its numbers.
    assert_eq!(report.matches("**Takeaway:**").count(), 3, "{report}");
}
