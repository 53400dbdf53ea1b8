//! A box with rounded edges and corners (`shape = { box = { half_extents, rounding } }`;
//! real cubes are not knife-edged): dropped without spin, a rounded cube
//! touches the ground exactly when its lowest corner sphere reaches it — later than
//! the sharp cube, by the geometry — and the keys a rounded box cannot take are
//! refused, naming the field.

use hcm_host::scenario::Scenario;
use hcm_tests::cli::Hcm;
use nalgebra::{UnitQuaternion, Vector3};

/// The shipped cube drop released at rest with `rounding` (m): the first recorded
/// time (s) with a contact force, and the free-fall time (s) at which the lowest point
/// of the rounded cube reaches the ground.
fn touch_down(rounding: f64) -> (f64, f64) {
    let sets = [
        format!("body.cube.shape.box.rounding={rounding}"),
        "body.cube.velocity=[0, 0, 0]".to_owned(),
        "body.cube.angular_velocity=[0, 0, 0]".to_owned(),
        "simulation.end_time=0.2".to_owned(),
        "record.contact_sample_period=1e-4".to_owned(),
        "record.flight_sample_period=1e-4".to_owned(),
    ];
    let model = Scenario::load(&hcm_tests::scenario("cube_drop.toml"), &sets)
        .unwrap()
        .model()
        .unwrap();
    let run = hcm_host::simulate::simulate(&model).unwrap().run;
    let track = run.body("cube").unwrap();
    let first = (track.samples.iter())
        .find(|s| s.force[2] > 0.0)
        .map_or(f64::NAN, |s| s.time);
    let cube = &model.bodies[0];
    let tilt = UnitQuaternion::from_euler_angles(0.35, -0.26, 0.1);
    let core = 0.05 - rounding;
    let lowest = (0..8)
        .map(|i| {
            let sign = |bit: usize| if i & bit != 0 { core } else { -core };
            (tilt * Vector3::new(sign(1), sign(2), sign(4))).z
        })
        .fold(f64::INFINITY, f64::min);
    let gap = cube.position.z + lowest - rounding;
    (first, (2.0 * gap / 9.81).sqrt())
}

#[test]
fn a_rounded_cube_touches_down_when_its_corner_sphere_reaches_the_ground() {
    let (sharp, sharp_expected) = touch_down(0.0);
    let (rounded, rounded_expected) = touch_down(0.01);
    println!("touch-down (s): sharp {sharp} (free fall {sharp_expected}), rounded 10 mm {rounded} (free fall {rounded_expected})");
    for (got, expected) in [(sharp, sharp_expected), (rounded, rounded_expected)] {
        assert!(
            got >= expected - 1e-9 && got <= expected + 1.01e-4,
            "first force at {got} s, the geometry says {expected} s"
        );
    }
    assert!(
        rounded - sharp > 2e-3,
        "rounded {rounded} s vs sharp {sharp} s"
    );
}

/// `hcm simulate` of `scenario` with `sets`: its error message (nothing written).
fn refused(scenario: &std::path::Path, sets: &[&str]) -> String {
    Hcm::new().simulate_refused(scenario, sets)
}

#[test]
fn a_rounding_a_box_cannot_have_is_refused_naming_the_field() {
    let drop = hcm_tests::scenario("cube_drop.toml");
    for bad in ["0.05", "-0.001", "nan"] {
        let message = refused(&drop, &[&format!("body.cube.shape.box.rounding={bad}")]);
        for part in ["shape.box.rounding", "smallest half extent 0.05"] {
            assert!(
                message.contains(part),
                "`{part}` missing for {bad}: {message}"
            );
        }
    }
    let blocks = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/common/scenes/block_on_block.toml");
    let message = refused(&blocks, &["body.block.shape.box.rounding=0.002"]);
    for part in ["`block` has rounded edges", "against a plane or a sphere"] {
        assert!(message.contains(part), "`{part}` missing: {message}");
    }
}
