//! `hcm predict --members`: the ensemble's file read and scored again by a scorer
//! written here from the documented format alone (the measured-data columns and
//! `member` last; per toss and member, the window's frames; the width 0.1048 m), which
//! must give back the energy scores, CRPS and band coverage `hcm predict --scores`
//! reports; the same bytes on one thread and on the machine's; a physics file carrying
//! the contact's scatter and the start state's draws the same members as the options
//! that set them; and one member of a model without variation is the replay.

use hcm_tests::cli::Hcm;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

fn tosses_csv() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("data/contactnets-cube/tosses.csv")
}

/// The cube's width (m), as the scores' unit.
const WIDTH: f64 = 0.1048;

/// A CSV file as a header and rows of text.
fn table(path: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut reader = csv::Reader::from_path(path).unwrap();
    let header = reader
        .headers()
        .unwrap()
        .iter()
        .map(str::to_owned)
        .collect();
    let rows = (reader.records())
        .map(|r| r.unwrap().iter().map(str::to_owned).collect())
        .collect();
    (header, rows)
}

fn column(header: &[String], name: &str) -> usize {
    header.iter().position(|h| h == name).unwrap()
}

/// Per run, per member, the (time, centre) rows of the members file.
type Members = BTreeMap<String, BTreeMap<usize, Vec<(f64, [f64; 3])>>>;

fn members(path: &Path) -> Members {
    let (header, rows) = table(path);
    let at = |name| column(&header, name);
    let (run, member, time) = (at("run"), at("member"), at("time"));
    let centre = [at("px"), at("py"), at("pz")];
    let mut out = Members::new();
    for row in rows {
        let number = |i: usize| row[i].parse::<f64>().unwrap();
        (out.entry(row[run].clone()).or_default())
            .entry(row[member].parse().unwrap())
            .or_default()
            .push((number(time), centre.map(number)));
    }
    out
}

/// Per run, (time, centre) of the recorded cube.
fn recorded(path: &Path) -> BTreeMap<String, Vec<(f64, [f64; 3])>> {
    let (header, rows) = table(path);
    let at = |name| column(&header, name);
    let (run, time, centre) = (at("run"), at("time"), [at("px"), at("py"), at("pz")]);
    let mut out: BTreeMap<String, Vec<(f64, [f64; 3])>> = BTreeMap::new();
    for row in rows {
        let number = |i: usize| row[i].parse::<f64>().unwrap();
        (out.entry(row[run].clone()).or_default()).push((number(time), centre.map(number)));
    }
    out
}

fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    (0..3).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt()
}

/// The energy score E‖X − y‖ − ½ E‖X − X′‖ of `xs` for `y`.
fn energy(xs: &[[f64; 3]], y: &[f64; 3]) -> f64 {
    let m = xs.len() as f64;
    let near = xs.iter().map(|x| distance(x, y)).sum::<f64>() / m;
    let spread = (xs.iter())
        .flat_map(|a| xs.iter().map(move |b| distance(a, b)))
        .sum::<f64>()
        / (m * m);
    near - 0.5 * spread
}

/// The CRPS of the ensemble `xs` for `y`, in its energy form.
fn crps(xs: &[f64], y: f64) -> f64 {
    let m = xs.len() as f64;
    let near = xs.iter().map(|x| (x - y).abs()).sum::<f64>() / m;
    let spread = (xs.iter())
        .flat_map(|a| xs.iter().map(move |b| (a - b).abs()))
        .sum::<f64>()
        / (m * m);
    near - 0.5 * spread
}

/// Whether `y` lies in the central `level` band of `xs` (type-6 quantiles, NumPy's
/// "weibull": the k-th smallest of M is the k/(M + 1) quantile, held within the range).
fn inside(xs: &[f64], y: f64, level: f64) -> bool {
    let mut s = xs.to_vec();
    s.sort_by(f64::total_cmp);
    let quantile = |p: f64| {
        let h = ((s.len() + 1) as f64 * p).clamp(1.0, s.len() as f64) - 1.0;
        let (lo, hi) = (h.floor() as usize, h.ceil() as usize);
        s[lo] + (h - lo as f64) * (s[hi] - s[lo])
    };
    quantile((1.0 - level) / 2.0) <= y && y <= quantile((1.0 + level) / 2.0)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn the_members_file_scored_again_gives_the_reported_scores() {
    let hcm = Hcm::new();
    let scenario = hcm_tests::scenario("cube_toss.toml");
    let predict = |out: &str, scores: &str| {
        hcm.run("predict")
            .opt("--scenario", &scenario)
            .opt("--data", tosses_csv())
            .opt("--first", "6")
            .opt("--members", "5")
            .opt("--scatter", "0.3")
            .opt("--start-spread", "1")
            .opt("--seed", "3")
            .opt("--out", out)
            .opt("--scores", scores)
    };
    let printed = predict("members.csv", "scores.csv").ok();
    assert!(printed.contains("ensemble of 5"), "{printed}");
    let (header, _) = table(&hcm.path("members.csv"));
    let format = hcm_host::dataset::csv_header();
    let expected: Vec<&str> = (format.split(',')).chain(["member"]).collect();
    assert_eq!(header, expected);

    let forecast = members(&hcm.path("members.csv"));
    let truth = recorded(&tosses_csv());
    let (header, rows) = table(&hcm.path("scores.csv"));
    assert_eq!(rows.len(), 6);
    for row in &rows {
        let value = |name: &str| row[column(&header, name)].parse::<f64>().unwrap();
        let run = &row[column(&header, "run")];
        let members = &forecast[run];
        assert_eq!(members.keys().copied().collect::<Vec<_>>(), [0, 1, 2, 3, 4]);
        // The window: the recorded frames from the window start to the last, each
        // member's rows at exactly those times.
        let start = value("window_start");
        let frames: Vec<&(f64, [f64; 3])> = truth[run]
            .iter()
            .filter(|(t, _)| *t >= start - 1e-9)
            .collect();
        assert_eq!(frames.len() as f64, value("frames"));
        let (mut es, mut cx, mut inside_50, mut inside_90) = (0.0, 0.0, 0, 0);
        for (i, (time, y)) in frames.iter().enumerate() {
            let xs: Vec<[f64; 3]> = (members.values())
                .map(|rows| {
                    assert_eq!(rows.len(), frames.len());
                    assert!((rows[i].0 - time).abs() < 1e-9);
                    rows[i].1
                })
                .collect();
            es += energy(&xs, y);
            cx += crps(&xs.iter().map(|x| x[0]).collect::<Vec<_>>(), y[0]);
            for k in 0..3 {
                let coordinate: Vec<f64> = xs.iter().map(|x| x[k]).collect();
                inside_50 += usize::from(inside(&coordinate, y[k], 0.5));
                inside_90 += usize::from(inside(&coordinate, y[k], 0.9));
            }
        }
        let n = frames.len() as f64;
        let percent = |sum: f64| 100.0 * sum / n / WIDTH;
        assert!(close(percent(es), value("energy_position")), "{run}");
        assert!(close(percent(cx), value("crps_x")), "{run}");
        assert!(
            close(inside_50 as f64 / (3.0 * n), value("inside_50")),
            "{run}"
        );
        assert!(
            close(inside_90 as f64 / (3.0 * n), value("inside_90")),
            "{run}"
        );
        assert_eq!(value("members"), 5.0);
    }

    // One thread, the same bytes.
    predict("one.csv", "one_scores.csv")
        .env("RAYON_NUM_THREADS", "1")
        .ok();
    let bytes = |name: &str| std::fs::read(hcm.path(name)).unwrap();
    assert_eq!(bytes("one.csv"), bytes("members.csv"));
    assert_eq!(bytes("one_scores.csv"), bytes("scores.csv"));
}

#[test]
fn a_physics_file_carries_the_scatter_the_members_draw() {
    let hcm = Hcm::new();
    let scenario = hcm_tests::scenario("cube_toss.toml");
    std::fs::write(
        hcm.path("scattered.toml"),
        r#"sets = ["variation.start_state=1.0"]

[[contact]]
bodies = ["cube", "table"]
law = "impact"
parameters = { stiffness = 1e7, exponent = 1.5, max_damping = 280.0, full_damping_depth = 1e-4 }
noise = { stiffness = 0.3, max_damping = 0.3, mu = 0.3 }
friction = { mu_static = 0.18, mu_dynamic = 0.18, v_static = 1e-3, v_dynamic = 1e-2 }
"#,
    )
    .unwrap();
    let predict = |out: &str| {
        hcm.run("predict")
            .opt("--scenario", &scenario)
            .opt("--data", tosses_csv())
            .opt("--first", "3")
            .opt("--members", "4")
            .opt("--out", out)
    };
    predict("from_file.csv")
        .opt("--physics", "scattered.toml")
        .ok();
    predict("from_options.csv")
        .opt("--scatter", "0.3")
        .opt("--start-spread", "1")
        .ok();
    let bytes = |name: &str| std::fs::read(hcm.path(name)).unwrap();
    assert_eq!(bytes("from_file.csv"), bytes("from_options.csv"));
    let forecast = members(&hcm.path("from_file.csv"));
    let first = forecast.values().next().unwrap();
    assert_ne!(first[&0], first[&1], "the members differ");

    // `hcm evaluate --members` draws the same members from the same file and scores
    // them as `hcm predict` does: the same ensemble row.
    let tosses = std::fs::read_to_string(tosses_csv()).unwrap();
    let kept: Vec<&str> = (tosses.lines().enumerate())
        .filter(|(i, l)| *i == 0 || forecast.contains_key(l.split(',').next().unwrap()))
        .map(|(_, l)| l)
        .collect();
    std::fs::write(hcm.path("three.csv"), kept.join("\n") + "\n").unwrap();
    let ensemble_row = |stdout: String| {
        (stdout.lines())
            .find(|l| l.starts_with("| ensemble of 4 |"))
            .unwrap_or_else(|| panic!("no ensemble row in {stdout}"))
            .to_owned()
    };
    let evaluated = hcm
        .run("evaluate")
        .opt("--scenario", &scenario)
        .opt("--physics", "scattered.toml")
        .opt("--data", "three.csv")
        .opt("--members", "4")
        .ok();
    let predicted = predict("again.csv").opt("--physics", "scattered.toml").ok();
    assert_eq!(ensemble_row(evaluated), ensemble_row(predicted));

    // One member of the scenario as it is (no variation): the replay's file, each row
    // with `,0` added.
    let replay = |out: &str| {
        hcm.run("predict")
            .opt("--scenario", &scenario)
            .opt("--data", tosses_csv())
            .opt("--first", "3")
            .opt("--out", out)
    };
    replay("one.csv").opt("--members", "1").ok();
    replay("replay.csv").ok();
    let text = |name: &str| std::fs::read_to_string(hcm.path(name)).unwrap();
    let replay: Vec<String> = (text("replay.csv").lines())
        .enumerate()
        .map(|(i, line)| format!("{line},{}", if i == 0 { "member" } else { "0" }))
        .collect();
    assert_eq!(text("one.csv").lines().collect::<Vec<_>>(), replay);
}
