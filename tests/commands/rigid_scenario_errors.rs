//! What a user meets when a 3D scenario is wrong: each mistake in the keys of boxes,
//! compound bodies, orientation, inertia and friction is answered with the field at
//! fault, what was expected and, where there is one, the fix — before anything runs.

use hcm_tests::cli::Hcm;

/// `hcm simulate` on the shipped cube drop with `sets` applied: its error message.
fn refused(sets: &[&str]) -> String {
    Hcm::new().simulate_refused(&hcm_tests::scenario("cube_drop.toml"), sets)
}

fn assert_says(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(message.contains(part), "missing `{part}` in: {message}");
    }
}

#[test]
fn a_box_starting_inside_the_ground_is_told_where_to_move() {
    let message = refused(&["body.cube.position=[0, 0, 0.04]"]);
    assert_says(
        &message,
        &[
            "body.cube.position",
            "starts 0.0348",
            "inside `ground`",
            "position = [0, 0, 0.0748",
        ],
    );
}

#[test]
fn an_inertia_no_rigid_body_has_is_refused() {
    assert_says(
        &refused(&["body.cube.inertia=[1e-3, 1e-3, 3e-3]"]),
        &["body `cube` (#0) inertia", "I1 + I2 ≥ I3"],
    );
    assert_says(
        &refused(&["body.cube.inertia=[[1e-3, 5e-4, 0], [0, 1e-3, 0], [0, 0, 1e-3]]"]),
        &["inertia", "symmetric"],
    );
}

#[test]
fn friction_and_orientation_errors_name_the_scenario_keys() {
    assert_says(
        &refused(&["contact.0.friction.v_dynamic=1e-4"]),
        &["contact #0", "friction", "v_dynamic", "v_static"],
    );
    assert_says(
        &refused(&["body.cube.orientation={ euler = [1, 2, 3] }"]),
        &["body.cube.orientation", "quaternion", "roll_pitch_yaw"],
    );
    assert_says(
        &refused(&["body.cube.orientation={ quaternion = [0, 0, 0, 0] }"]),
        &["orientation", "non-zero"],
    );
}

/// STEP friction falls from μ_s at v_s to μ_d at v_d: the keys in the other order, or
/// a step of no width, are a user's mistake, named.
#[test]
fn friction_out_of_step_order_is_refused() {
    assert_says(
        &refused(&["contact.0.friction.mu_dynamic=0.5"]),
        &[
            "contact #0",
            "mu_dynamic 0.5 is above mu_static 0.3",
            "swapped",
        ],
    );
    assert_says(
        &refused(&["contact.0.friction.v_dynamic=1e-3"]),
        &[
            "contact #0",
            "v_dynamic 0.001 equals v_static",
            "give v_dynamic above",
        ],
    );
}

#[test]
fn a_law_that_needs_a_radius_asks_for_its_stiffness_on_a_box() {
    assert_says(
        &refused(&["contact.0.law=\"hertz\"", "contact.0.parameters={}"]),
        &["hertz", "radius of curvature", "give `stiffness`"],
    );
}

#[test]
fn unsupported_pairs_and_moving_compounds_are_refused() {
    assert_says(
        &refused(&["contact.0.bodies=[\"ground\", \"cube\"]"]),
        &["not a supported pair", "swap the bodies"],
    );
    assert_says(
        &refused(&[
            "body.cube.shape={ compound = { parts = [{ half_extents = [0.05, 0.05, 0.05] }] } }",
        ]),
        &["compound body must be fixed"],
    );
}
