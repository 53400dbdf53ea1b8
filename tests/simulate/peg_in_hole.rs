//! The shipped peg-in-hole (`scenarios/peg_in_hole.toml`): `hcm simulate`
//! and `hcm indicators` both find two wall contacts before the bottom contact, each with
//! the four 3D indicators, and the indicators read back from the recorded data agree
//! with the simulator's own.
//!
//! Run with `--nocapture` to see the tables.

use hcm_tests::cli::Hcm;
use serde_json::Value;

#[test]
fn the_peg_touches_a_wall_twice_before_the_bottom() {
    let hcm = Hcm::new();
    let scenario = hcm_tests::scenario("peg_in_hole.toml");
    let out = hcm.path("peg.csv");
    let table = hcm
        .run("simulate")
        .opt("--scenario", &scenario)
        .opt("--out", &out)
        .ok();
    println!("{table}");
    let json = hcm
        .run("indicators")
        .opt("--scenario", &scenario)
        .opt("--data", &out)
        .arg("--json")
        .ok();
    let parsed: Value = serde_json::from_str(&json).unwrap();
    let events = parsed["events"].as_array().unwrap();
    assert_eq!(events.len(), 3, "{json}");
    for (i, event) in events.iter().enumerate() {
        let indicators = &event["indicators"];
        let linear: Vec<f64> = indicators["linear_impulse_vector"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        // A wall pushes the peg sideways (the hole's walls are normal to x or y), the
        // bottom pushes it up.
        let (sideways, up) = (linear[0].hypot(linear[1]), linear[2]);
        if i < 2 {
            assert!(
                sideways > up.abs(),
                "event {i} is a wall contact: {linear:?}"
            );
        } else {
            assert!(up > 3.0 * sideways, "event {i} is the bottom: {linear:?}");
        }
        for key in [
            "max_force",
            "max_torque",
            "linear_impulse",
            "angular_impulse",
            "duration",
        ] {
            let value = indicators[key].as_f64().unwrap();
            assert!(
                value > 0.0 && value.is_finite(),
                "event {i} {key} = {value}"
            );
        }
        // The simulator's row of the same event (from the printed table).
        let row = table
            .lines()
            .filter(|l| l.starts_with("| peg–block"))
            .nth(i)
            .unwrap();
        let cells: Vec<f64> = row
            .split('|')
            .skip(3)
            .take(4)
            .map(|c| c.trim().parse().unwrap())
            .collect();
        let keys = [
            "max_force",
            "max_torque",
            "linear_impulse",
            "angular_impulse",
        ];
        for (key, simulated) in keys.iter().zip(&cells) {
            let read = indicators[key].as_f64().unwrap();
            let relative = (read - simulated).abs() / simulated;
            println!(
                "event {i} {key}: simulated {simulated:.6e}, from data {read:.6e} ({relative:.1e})"
            );
            // 10 µs samples of a ~1 ms contact: the peaks and the trapezoid impulses
            // agree to a few per cent.
            assert!(relative < 0.05, "event {i} {key}: {simulated} vs {read}");
        }
    }
}
