//! The 3D simulator's contact on properties any correct one has: a box dropped flat on
//! a frictionless elastic (Hertz) contact bounces back to its release height, and a box
//! dropped on an edge, mirror-symmetric about the plane x = 0, keeps its corners'
//! forces pairwise equal and its motion in that plane.
//!
//! Run with `--nocapture` to see the measured figures.

use hcm_host::scenario::Scenario;
use hcm_host::simulate::simulate;
use hcm_host::simulate::{RigidLayout, RigidSystem};
use std::path::Path;

/// A 0.1 m × 0.06 m × 0.04 m box of 0.5 kg above the plane z = 0, in `orientation`
/// (TOML), released at rest with its centre at `height` (m); `contact` the TOML of the
/// contact's law.
fn box_scenario(height: f64, orientation: &str, contact: &str, end: f64) -> Scenario {
    let text = format!(
        r#"
name = "box_drop"
gravity = [0.0, 0.0, -9.81]
[[body]]
name = "box"
mass = 0.5
shape = {{ box = {{ half_extents = [0.05, 0.03, 0.02] }} }}
position = [0.0, 0.0, {height}]
orientation = {orientation}
[[body]]
name = "ground"
fixed = true
shape = {{ plane = {{ normal = [0.0, 0.0, 1.0] }} }}
position = [0.0, 0.0, 0.0]
[[contact]]
bodies = ["box", "ground"]
{contact}
[simulation]
end_time = {end}
relative_tolerance = 1e-12
absolute_tolerance = 1e-14
max_step = 1e-3
[record]
contact_sample_period = 1e-5
flight_sample_period = 1e-4
contact_margin = 0.0
"#
    );
    Scenario::parse(Path::new("box_drop.toml"), &text, &[]).unwrap()
}

#[test]
fn a_box_dropped_flat_on_an_elastic_contact_bounces_back_to_its_release_height() {
    let drop = 0.05; // m between the bottom face and the plane
    let start = 0.02 + drop;
    let law = r#"law = "hertz"
parameters = { stiffness = 1e9, exponent = 1.5 }"#;
    // Falls 0.101 s, bounces, rises for as long: the apex is near 0.2 s.
    let scenario = box_scenario(start, "{ quaternion = [1.0, 0.0, 0.0, 0.0] }", law, 0.25);
    let model = scenario.resolve(Path::new("box_drop.toml")).unwrap();
    assert!(model.is_rigid());
    let simulation = simulate(&model).unwrap();
    let event = &simulation.events[0];
    let lift_off = event.lift_off.expect("it bounces off");
    assert_eq!(event.max_points, 4, "flat: the four bottom corners");
    // The apex from every free-flight sample after lift-off: z + v_z²/(2g).
    let samples = &simulation.run.bodies[0].samples;
    let after: Vec<f64> = samples
        .iter()
        .filter(|s| s.time > lift_off)
        .map(|s| s.position[2] + s.velocity[2].powi(2) / (2.0 * 9.81))
        .collect();
    assert!(after.len() > 100, "{} flight samples", after.len());
    let worst = after
        .iter()
        .map(|apex| ((apex - start) / drop).abs())
        .fold(0.0, f64::max);
    println!(
        "flat Hertz drop from {drop} m: contact {:.3e} s, apex off the release height by {worst:.2e} of the drop ({} samples)",
        lift_off - event.touch_down,
        after.len()
    );
    assert!(worst < 1e-6, "{worst}");
    // No rotation from a symmetric impact.
    let last = samples.last().unwrap();
    assert!(
        last.angular_velocity.iter().all(|w| w.abs() < 1e-9),
        "{last:?}"
    );
}

#[test]
fn a_box_dropped_on_an_edge_loads_mirrored_corners_equally() {
    // Turned 0.3 rad about x: the lowest edge runs along x, its two corners mirrored in
    // the plane x = 0, as are the other two bottom corners that touch later.
    let law = r#"law = "impact"
parameters = { stiffness = 1e8, exponent = 1.5, max_damping = 100.0, full_damping_depth = 1e-4 }
friction = { mu_static = 0.3, mu_dynamic = 0.2, v_static = 1e-3, v_dynamic = 1e-2 }"#;
    let scenario = box_scenario(0.08, "{ roll_pitch_yaw = [0.3, 0.0, 0.0] }", law, 1.0);
    let model = scenario.resolve(Path::new("box_drop.toml")).unwrap();
    let simulation = simulate(&model).unwrap();
    let layout = RigidLayout::new(&model);
    let system = RigidSystem::new(&model, &layout);
    let samples = &simulation.run.bodies[0].samples;
    let (mut pairs, mut worst, mut most) = (0, 0.0_f64, 0_usize);
    let mut largest_asymmetry = 0.0_f64;
    for s in samples {
        // The state vector of the sample: p, q, v, ω in the body frame, then integrals.
        let mut y = vec![0.0; 19];
        y[0..3].copy_from_slice(&s.position);
        y[3..7].copy_from_slice(&s.orientation);
        y[7..10].copy_from_slice(&s.velocity);
        let [w, x, yq, z] = s.orientation;
        let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, yq, z));
        let body_omega = q.inverse_transform_vector(&nalgebra::Vector3::from(s.angular_velocity));
        y[10..13].copy_from_slice(body_omega.as_slice());
        let pair = system.manifold(&y, 0);
        most = most.max(pair.points.len());
        // Vertex i and i ^ 1 differ only in the sign of their x coordinate.
        for (a, &fa) in pair.points.iter().zip(&pair.features) {
            for (b, &fb) in pair.points.iter().zip(&pair.features) {
                if fb != (fa ^ 1) || fa > fb {
                    continue;
                }
                let force = |p| model.contacts[0].model.point_force(p);
                let (ga, gb) = (force(a), force(b));
                let scale = ga.normal_force.abs().max(1e-12);
                worst = worst.max((ga.normal_force - gb.normal_force).abs() / scale);
                worst = worst.max((ga.friction - gb.friction).norm() / scale);
                pairs += 1;
            }
        }
        largest_asymmetry = largest_asymmetry
            .max(s.position[0].abs())
            .max(s.angular_velocity[1].abs())
            .max(s.angular_velocity[2].abs());
    }
    println!(
        "edge drop: {pairs} mirrored corner pairs over {} samples (up to {most} corners at once), \
         largest relative force difference {worst:.2e}; |x|, |ω_y|, |ω_z| ≤ {largest_asymmetry:.2e}",
        samples.len()
    );
    assert!(pairs > 100, "the corners touched in pairs");
    assert_eq!(most, 4, "both edges come down: four corners");
    assert!(worst < 1e-9, "{worst}");
    assert!(largest_asymmetry < 1e-9, "{largest_asymmetry}");
}

/// Every law of the catalogue, with parameters for a 0.5 kg box (TOML).
const LAWS: [(&str, &str); 6] = [
    ("hertz", "stiffness = 1e9, exponent = 1.5"),
    ("lankarani_nikravesh", "stiffness = 1e9, exponent = 1.5, restitution = 0.8"),
    (
        "variable_stiffness",
        "surface_loading = 2.0, effective_modulus = 1e10, radius = 0.01, damping = 500.0, effective_mass = 0.125",
    ),
    (
        "impact",
        "stiffness = 1e9, exponent = 1.5, max_damping = 200.0, full_damping_depth = 1e-5",
    ),
    ("hunt_crossley", "stiffness = 1e9, exponent = 1.5, damping = 0.2"),
    ("flores", "stiffness = 1e9, exponent = 1.5, restitution = 0.8"),
];

/// The same law in 1D: a sphere of a quarter of the box's mass dropped the same gap
/// onto the plane. (restitution δ̇_out/δ̇_in, peak force (N)).
fn quarter_mass_sphere(law: &str, parameters: &str, drop: f64) -> (f64, f64) {
    let radius = 0.01;
    let text = format!(
        r#"
name = "quarter"
gravity = [0.0, 0.0, -9.81]
[[body]]
name = "ball"
mass = 0.125
shape = {{ sphere = {{ radius = {radius} }} }}
position = [0.0, 0.0, {}]
[[body]]
name = "ground"
fixed = true
shape = {{ plane = {{ normal = [0.0, 0.0, 1.0] }} }}
position = [0.0, 0.0, 0.0]
[[contact]]
bodies = ["ball", "ground"]
law = "{law}"
parameters = {{ {parameters} }}
[simulation]
end_time = 0.2
stop_after_contacts = 1
relative_tolerance = 1e-12
absolute_tolerance = 1e-14
[record]
contact_sample_period = 1e-4
flight_sample_period = 1e-3
contact_margin = 0.0
"#,
        radius + drop
    );
    let path = Path::new("quarter.toml");
    let model = Scenario::parse(path, &text, &[])
        .unwrap()
        .resolve(path)
        .unwrap();
    assert!(!model.is_rigid());
    let simulation = simulate(&model).unwrap();
    let event = &simulation.events[0];
    (
        event.separation_speed / event.approach_speed,
        event.max_force,
    )
}

#[test]
fn every_law_acts_at_each_corner_of_a_flat_box_as_on_a_quarter_of_its_mass() {
    // Dropped flat, each of the four corners carries a quarter of the box along the
    // same δ(t): the restitution must be the 1D law's for m/4, the peak force four
    // times its peak. For Lankarani–Nikravesh and Flores this checks that every corner
    // latches its own approach speed δ̇0 at its touch-down.
    let drop = 0.05;
    for (law, parameters) in LAWS {
        let contact = format!("law = \"{law}\"\nparameters = {{ {parameters} }}");
        let scenario = box_scenario(
            0.02 + drop,
            "{ quaternion = [1.0, 0.0, 0.0, 0.0] }",
            &contact,
            0.25,
        );
        let model = scenario.resolve(Path::new("box_drop.toml")).unwrap();
        let simulation = simulate(&model).unwrap();
        let event = &simulation.events[0];
        let lift_off = event.lift_off.expect("it bounces off");
        // Approach and separation speeds from free flight: v² = 2·g·h before, and the
        // apex after (z + v_z²/2g).
        let samples = &simulation.run.bodies[0].samples;
        let after = samples.iter().find(|s| s.time > lift_off + 1e-3).unwrap();
        let apex = after.position[2] + after.velocity[2].powi(2) / (2.0 * 9.81) - 0.02;
        let restitution = (apex / drop).sqrt();
        let (expected, peak) = quarter_mass_sphere(law, parameters, drop);
        println!(
            "{law}: box restitution {restitution:.9}, quarter-mass sphere {expected:.9}; peak {:.6e} N vs 4 × {peak:.6e} N",
            event.max_force
        );
        assert!((restitution - expected).abs() < 1e-6, "{law}");
        assert!((event.max_force / (4.0 * peak) - 1.0).abs() < 1e-4, "{law}");
    }
}
