//! A bad 3D data set is answered with what is wrong — the file, the column
//! or line, and what to do — before any fit runs: a channel missing, a body named
//! otherwise than in the scenario, frames out of order, a sensor on a body the
//! scenario lacks.

use hcm_tests::cli::Hcm;

/// `hcm generate` on the shipped cube drop (4 runs); the S1 file's rows.
fn cube_rows(hcm: &Hcm) -> Vec<Vec<String>> {
    hcm.run("generate")
        .opt("--scenario", hcm_tests::scenario("cube_drop.toml"))
        .opt("--runs", "4")
        .opt("--out", hcm.path("gen"))
        .ok();
    let text = std::fs::read_to_string(hcm.path("gen.s1.csv")).unwrap();
    text.lines()
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect()
}

/// `hcm identify` and `hcm diagnose` on `rows` written as a file: both must fail, each
/// message holding every one of `parts`, and write nothing.
fn refused(hcm: &Hcm, rows: &[Vec<String>], parts: &[&str]) {
    let text: Vec<String> = rows.iter().map(|r| r.join(",")).collect();
    std::fs::write(hcm.path("bad.csv"), text.join("\n") + "\n").unwrap();
    let scenario = hcm_tests::scenario("cube_drop.toml");
    let identify = hcm
        .run("identify")
        .opt("--scenario", &scenario)
        .opt("--data", hcm.path("bad.csv"))
        .opt("--law", "impact")
        .opt("--out", hcm.path("pm2.toml"))
        .fails();
    assert!(!hcm.path("pm2.toml").exists(), "nothing written");
    for part in parts {
        assert!(identify.contains(part), "missing `{part}` in: {identify}");
    }
}

#[test]
fn each_bad_3d_data_set_is_told_what_is_wrong() {
    let hcm = Hcm::new();
    let rows = cube_rows(&hcm);
    let header = rows[0].clone();
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    // The force channel left empty on every row.
    let mut no_force = rows.clone();
    for row in no_force.iter_mut().skip(1) {
        for name in ["fx", "fy", "fz"] {
            row[column(name)].clear();
        }
    }
    refused(
        &hcm,
        &no_force,
        &["bad.csv", "`fx`", "force channel", "never fills it"],
    );
    // The moving body named otherwise.
    let mut renamed = rows.clone();
    for row in renamed.iter_mut().skip(1) {
        row[1] = "box".to_owned();
    }
    refused(
        &hcm,
        &renamed,
        &["column `body`", "`box`", "does not have", "`cube`"],
    );
    // Two frames swapped.
    let mut swapped = rows.clone();
    swapped.swap(5, 6);
    refused(&hcm, &swapped, &["line 7", "`time`", "increase strictly"]);
    // A sensor's rows on a body the scenario lacks.
    let mut plate = rows.clone();
    let extra: Vec<Vec<String>> = (rows[1..20].iter())
        .map(|r| {
            let mut r = r.clone();
            r[1] = "force_plate".to_owned();
            r
        })
        .collect();
    plate.extend(extra);
    refused(
        &hcm,
        &plate,
        &["`force_plate`", "does not have", "add the body"],
    );
}

/// Too few runs to judge on held-out ones: the diagnosis says how many it needs, and
/// leaves no output directory behind.
#[test]
fn a_diagnosis_on_too_few_runs_says_how_many_it_needs() {
    let hcm = Hcm::new();
    cube_rows(&hcm);
    let scenario = hcm_tests::scenario("cube_drop.toml");
    hcm.run("identify")
        .opt("--scenario", &scenario)
        .opt("--data", hcm.path("gen.s1.csv"))
        .opt("--law", "impact")
        .opt("--out", hcm.path("pm2.toml"))
        .ok();
    let message = hcm
        .run("diagnose")
        .opt("--scenario", &scenario)
        .opt("--data", hcm.path("gen.s1.csv"))
        .opt("--physics", hcm.path("pm2.toml"))
        .opt("--out", hcm.path("diagnosis"))
        .fails();
    assert!(message.contains("needs at least 6 runs"), "{message}");
    assert!(!hcm.path("diagnosis").exists(), "no directory left behind");
}
