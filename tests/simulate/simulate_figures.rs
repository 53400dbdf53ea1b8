//! `hcm simulate --figures DIR`: the side view of a 3D run and its contact force and
//! torque, written as SVG and PNG; refused for a 1D scenario.

use hcm_host::dataset::Dataset;
use hcm_tests::cli::Hcm;
use std::fs;
use std::path::Path;

/// The figures every 3D run writes.
const STEMS: [&str; 3] = ["trajectory", "contact_force", "contact_torque"];
/// The grey of the touch-down marks.
const MARK: &str = "#999999";

/// A 18 mm square peg falling, 2 mm off centre and tilted by 0.05 rad, into a 20 mm
/// square hole 30 mm deep in a fixed block (four walls and a bottom, top at z = 0.04 m).
const PEG_IN_HOLE: &str = r#"
name = "peg_test"
gravity = [0.0, 0.0, -9.81]

[[body]]
name = "peg"
mass = 0.05
shape = { box = { half_extents = [0.009, 0.009, 0.02] } }
inertia = [7.0e-6, 7.0e-6, 2.7e-6]
position = [0.002, 0.0, 0.065]
orientation = { roll_pitch_yaw = [0.0, 0.05, 0.0] }
velocity = [0.0, 0.0, -0.5]

[[body]]
name = "block"
fixed = true
position = [0.0, 0.0, 0.0]
shape = { compound = { parts = [
    { half_extents = [0.02, 0.02, 0.005], position = [0.0, 0.0, 0.005] },
    { half_extents = [0.005, 0.02, 0.015], position = [-0.015, 0.0, 0.025] },
    { half_extents = [0.005, 0.02, 0.015], position = [0.015, 0.0, 0.025] },
    { half_extents = [0.01, 0.005, 0.015], position = [0.0, -0.015, 0.025] },
    { half_extents = [0.01, 0.005, 0.015], position = [0.0, 0.015, 0.025] },
] } }

[[contact]]
bodies = ["peg", "block"]
law = "impact"
parameters = { stiffness = 1e7, exponent = 1.5, max_damping = 20.0, full_damping_depth = 1e-4 }
friction = { mu_static = 0.3, mu_dynamic = 0.2, v_static = 1e-3, v_dynamic = 1e-2 }

[simulation]
end_time = 0.1
relative_tolerance = 1e-8
absolute_tolerance = 1e-10
max_step = 1e-3
max_steps = 2000000

[record]
contact_sample_period = 1e-3
flight_sample_period = 1e-3
contact_margin = 0.0
bodies = ["peg"]
"#;

/// The `points` attribute of every polyline of `svg`, as point counts, in order.
fn polylines(svg: &str) -> Vec<(String, usize)> {
    svg.lines()
        .filter(|l| l.starts_with("<polyline"))
        .map(|l| {
            let stroke = l.split("stroke=\"").nth(1).unwrap_or("")[..7].to_owned();
            let points = l.split("points=\"").nth(1).unwrap_or("");
            let points = points.split('"').next().unwrap_or("");
            (stroke, points.split_whitespace().count())
        })
        .collect()
}

/// Checks that DIR holds each figure as an SVG document and a PNG image of the figures'
/// size; returns the SVGs.
fn read_figures(dir: &Path) -> Vec<String> {
    STEMS
        .iter()
        .map(|stem| {
            let png = fs::read(dir.join(format!("{stem}.png"))).expect("the PNG");
            assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{stem}.png: PNG signature");
            assert_eq!(&png[12..16], b"IHDR");
            let size = |at: usize| u32::from_be_bytes(png[at..at + 4].try_into().unwrap());
            assert_eq!((size(16), size(20)), (720, 440), "{stem}.png size");
            let svg = fs::read_to_string(dir.join(format!("{stem}.svg"))).expect("the SVG");
            assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
            assert!(svg.trim_end().ends_with("</svg>"), "{stem}.svg is complete");
            svg
        })
        .collect()
}

/// Rows of the printed event table: the number of touch-downs.
fn touch_downs(stdout: &str, pair: &str) -> usize {
    stdout
        .lines()
        .filter(|l| l.starts_with(&format!("| {pair} |")))
        .count()
}

#[test]
fn cube_drop_figures_show_every_sample_and_every_touch_down() {
    let hcm = Hcm::new();
    let out = hcm.path("cube.csv");
    let stdout = hcm
        .run("simulate")
        .opt("--scenario", hcm_tests::scenario("cube_drop.toml"))
        .opt("--out", &out)
        .opt("--figures", hcm.path("figures/cube"))
        .ok();
    let svgs = read_figures(&hcm.path("figures/cube"));
    let samples = Dataset::read(&out).unwrap().runs[0].bodies[0].samples.len();
    let trajectory = polylines(&svgs[0]);
    // The first curve is the centre of mass's path: one point per recorded sample.
    assert_eq!(trajectory[0].1, samples);
    // Then the ground (a line), then the cube at the start, at each touch-down, at the
    // end: each a closed convex outline of 4 to 6 corners.
    let events = touch_downs(&stdout, "cube–ground");
    assert!(events >= 2, "{stdout}");
    assert_eq!(trajectory[1].1, 2);
    let outlines = &trajectory[2..];
    assert_eq!(outlines.len(), 2 + events.min(6));
    assert!(
        outlines.iter().all(|o| (5..=7).contains(&o.1)),
        "{outlines:?}"
    );
    // The force and torque figures mark each touch-down and draw one sample per point.
    for svg in &svgs[1..] {
        let curves = polylines(svg);
        let marks = curves.iter().filter(|c| c.0 == MARK).count();
        assert_eq!(marks, events);
        assert_eq!(curves.last().unwrap().1, samples);
    }
}

#[test]
fn a_peg_falling_into_a_hole_is_drawn_with_every_part_of_the_block() {
    let hcm = Hcm::new();
    let scenario = hcm.path("peg.toml");
    fs::write(&scenario, PEG_IN_HOLE).unwrap();
    let stdout = hcm
        .run("simulate")
        .opt("--scenario", &scenario)
        .opt("--out", hcm.path("peg.csv"))
        .opt("--figures", hcm.path("figures"))
        .ok();
    let svgs = read_figures(&hcm.path("figures"));
    let trajectory = polylines(&svgs[0]);
    // Path, the block's five parts (rectangles: four corners and back), the peg at the
    // start, its touch-downs and the end.
    let events = touch_downs(&stdout, "peg–block");
    assert!(events >= 1, "{stdout}");
    assert_eq!(trajectory.len(), 1 + 5 + 2 + events.min(6));
    let fixed = trajectory.iter().filter(|c| c.0 == "#555555").count();
    assert_eq!(fixed, 5);
    assert!(trajectory[1..6].iter().all(|c| c.1 == 5), "{trajectory:?}");
}

#[test]
fn a_1d_scenario_is_refused_figures_naming_why() {
    let hcm = Hcm::new();
    let stderr = hcm
        .run("simulate")
        .opt("--scenario", hcm_tests::scenario("bouncing_ball.toml"))
        .opt("--out", hcm.path("ball.csv"))
        .opt("--figures", hcm.path("figures"))
        .fails();
    assert!(
        stderr.contains("--figures") && stderr.contains("1D"),
        "{stderr}"
    );
    assert!(!hcm.path("figures").exists() && !hcm.path("ball.csv").exists());
}
