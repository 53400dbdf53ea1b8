//! `hcm predict` on a mechanism (the shipped elbow toss, two links on a hinge): the
//! scores file holds a `body` column, per toss one row per link with its own scores and
//! start state, then an `all` row with their means; the links' start states hold the
//! hinge.

use hcm_tests::cli::Hcm;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use std::path::Path;

#[test]
fn a_mechanisms_scores_have_a_row_per_link_and_their_mean() {
    let hcm = Hcm::new();
    let tosses = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/contactnets-elbow/tosses.csv");
    let text = std::fs::read_to_string(tosses).unwrap();
    let kept: Vec<&str> = (text.lines().enumerate())
        .filter(|(i, l)| *i == 0 || l.starts_with("toss_000,") || l.starts_with("toss_001,"))
        .map(|(_, l)| l)
        .collect();
    std::fs::write(hcm.path("two.csv"), kept.join("\n") + "\n").unwrap();
    hcm.run("predict")
        .opt("--scenario", hcm_tests::scenario("elbow_toss.toml"))
        .opt("--data", "two.csv")
        .opt("--out", "predicted.csv")
        .opt("--scores", "scores.csv")
        .ok();
    let mut reader = csv::Reader::from_path(hcm.path("scores.csv")).unwrap();
    let header: Vec<String> = reader
        .headers()
        .unwrap()
        .iter()
        .map(str::to_owned)
        .collect();
    let at = |name: &str| header.iter().position(|h| h == name).unwrap();
    assert_eq!(&header[..2], ["run", "body"]);
    let rows: Vec<Vec<String>> = (reader.records())
        .map(|r| r.unwrap().iter().map(str::to_owned).collect())
        .collect();
    let bodies: Vec<&str> = rows.iter().map(|r| r[1].as_str()).collect();
    assert_eq!(
        bodies,
        ["elbow_1", "elbow_2", "all", "elbow_1", "elbow_2", "all"]
    );
    let number = |r: &[String], name: &str| r[at(name)].parse::<f64>().unwrap();
    for toss in rows.chunks(3) {
        for column in ["position_error", "rotation_error", "frozen_position_error"] {
            let mean = 0.5 * (number(&toss[0], column) + number(&toss[1], column));
            assert!(
                (mean - number(&toss[2], column)).abs() < 1e-9,
                "{column}: {toss:?}"
            );
        }
        assert_eq!(toss[2][at("p0x")], "", "the `all` row has no start state");
        // The hinge at (−0.035, 0.06, 0) m in elbow_1's frame, (−0.035, 0, 0) in elbow_2's.
        let pose = |r: &[String]| {
            let v = |k: &str| number(r, k);
            let q = Quaternion::new(v("q0w"), v("q0x"), v("q0y"), v("q0z"));
            (
                Vector3::new(v("p0x"), v("p0y"), v("p0z")),
                UnitQuaternion::from_quaternion(q),
            )
        };
        let ((p1, q1), (p2, q2)) = (pose(&toss[0]), pose(&toss[1]));
        let gap = (p1 + q1 * Vector3::new(-0.035, 0.06, 0.0))
            - (p2 + q2 * Vector3::new(-0.035, 0.0, 0.0));
        assert!(
            gap.norm() < 1e-9,
            "hinge {:e} m apart at the start",
            gap.norm()
        );
    }
}
