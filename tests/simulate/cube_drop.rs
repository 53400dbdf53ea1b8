//! `hcm simulate --scenario scenarios/cube_drop.toml` against the independent reference
//! solver (`hcm_tests::rigid_reference`: rotation matrix and world angular momentum,
//! fixed-step RK4 — nothing shared with hcm's quaternion Dormand–Prince, manifold or
//! laws): within 1 mm in position and 1° in orientation over the whole 0.4 s, and
//! converged: halving the solver's tolerances moves the final pose by < 0.1 mm.
//!
//! Run with `--nocapture` to see the measured differences.

use hcm_host::dataset::{Dataset, Sample};
use hcm_tests::cli::Hcm;
use hcm_tests::rigid_reference::{compare, cube_drop, simulate, tossed_plate, Case};
use nalgebra::{Quaternion, UnitQuaternion, Vector3};

/// The reference's fixed step (s); its own tests show it converged to 6e-5°.
const REFERENCE_STEP: f64 = 2.5e-6;

/// The cube's samples of `hcm simulate` on the shipped scenario with `sets` applied.
fn hcm_cube(hcm: &Hcm, name: &str, sets: &[&str]) -> Vec<Sample> {
    let out = hcm.path(name);
    let mut call = hcm
        .run("simulate")
        .opt("--scenario", hcm_tests::scenario("cube_drop.toml"))
        .opt("--out", &out);
    for set in sets {
        call = call.opt("--set", set);
    }
    println!("{}", call.ok());
    let data = Dataset::read(&out).unwrap();
    data.runs[0].body("cube").unwrap().samples.clone()
}

/// `case` written as a scenario with the README's keys for boxes: half extents, full
/// inertia tensor, orientation quaternion, angular velocity (world frame), IMPACT and
/// friction parameters.
fn scenario_text(case: &Case) -> String {
    let q = UnitQuaternion::from_matrix(&case.rotation);
    let v = |x: &Vector3<f64>| format!("[{:e}, {:e}, {:e}]", x.x, x.y, x.z);
    let rows: Vec<String> = (0..3)
        .map(|i| v(&case.inertia.row(i).transpose().into_owned()))
        .collect();
    let (impact, friction) = (&case.impact, &case.friction);
    format!(
        r#"
name = "box_toss"
gravity = {gravity}
[[body]]
name = "cube"
mass = {mass:e}
shape = {{ box = {{ half_extents = {half} }} }}
inertia = [{rows}]
position = {position}
orientation = {{ quaternion = [{w:e}, {x:e}, {y:e}, {z:e}] }}
velocity = {velocity}
angular_velocity = {omega}
[[body]]
name = "ground"
fixed = true
shape = {{ plane = {{ normal = [0.0, 0.0, 1.0] }} }}
position = [0.0, 0.0, 0.0]
[[contact]]
bodies = ["cube", "ground"]
law = "impact"
parameters = {{ stiffness = {k:e}, exponent = {e:e}, max_damping = {d:e}, full_damping_depth = {depth:e} }}
friction = {{ mu_static = {ms:e}, mu_dynamic = {md:e}, v_static = {vs:e}, v_dynamic = {vd:e} }}
[simulation]
end_time = {end:e}
relative_tolerance = 1e-9
absolute_tolerance = 1e-10
max_step = 1e-3
max_steps = 2000000
[record]
contact_sample_period = {period:e}
flight_sample_period = {period:e}
contact_margin = 0.0
bodies = ["cube"]
"#,
        gravity = v(&case.gravity),
        mass = case.mass,
        half = v(&case.half_extents),
        rows = rows.join(", "),
        position = v(&case.position),
        w = q.w,
        x = q.i,
        y = q.j,
        z = q.k,
        velocity = v(&case.velocity),
        omega = v(&case.angular_velocity),
        k = impact.stiffness,
        e = impact.exponent,
        d = impact.max_damping,
        depth = impact.full_damping_depth,
        ms = friction.mu_static,
        md = friction.mu_dynamic,
        vs = friction.v_static,
        vd = friction.v_dynamic,
        end = case.end_time,
        period = case.sample_period,
    )
}

/// The largest position (m) and orientation (rad) differences of hcm's run of `case`
/// against the reference solver's.
fn against_reference(hcm: &Hcm, name: &str, case: &Case) -> (f64, f64) {
    let scenario = hcm.path(&format!("{name}.toml"));
    std::fs::write(&scenario, scenario_text(case)).unwrap();
    let out = hcm.path(&format!("{name}.csv"));
    println!(
        "{}",
        hcm.run("simulate")
            .opt("--scenario", &scenario)
            .opt("--out", &out)
            .ok()
    );
    let samples = Dataset::read(&out).unwrap().runs[0]
        .body("cube")
        .unwrap()
        .samples
        .clone();
    let reference = simulate(case, REFERENCE_STEP);
    let times: Vec<f64> = samples.iter().map(|s| s.time).collect();
    let positions: Vec<[f64; 3]> = samples.iter().map(|s| s.position).collect();
    let quaternions: Vec<[f64; 4]> = samples.iter().map(|s| s.orientation).collect();
    compare(&reference.samples, &times, &positions, &quaternions)
}

#[test]
fn another_box_and_parameter_set_written_with_the_readme_keys_agrees_too() {
    // A flat 160 × 100 × 40 mm plate of 0.8 kg with a full inertia tensor, thrown
    // spinning onto a softer, more damped, more frictional contact.
    let hcm = Hcm::new();
    let plate = tossed_plate();
    let (position_error, angle_error) = against_reference(&hcm, "plate", &plate);
    println!(
        "tossed plate against the reference over {} s: max position error {position_error:.3e} m, \
         max orientation error {:.3e}°",
        plate.end_time,
        angle_error.to_degrees()
    );
    assert!(position_error < 1e-3, "{position_error} m");
    assert!(
        angle_error.to_degrees() < 1.0,
        "{}°",
        angle_error.to_degrees()
    );
    // The shipped scenario, written from the reference's case the same way.
    let (p, a) = against_reference(&hcm, "cube", &cube_drop());
    println!(
        "cube drop written from the case: {p:.3e} m, {:.3e}°",
        a.to_degrees()
    );
    assert!(p < 1e-3 && a.to_degrees() < 1.0);
}

fn orientation(s: &Sample) -> UnitQuaternion<f64> {
    let [w, x, y, z] = s.orientation;
    UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z))
}

#[test]
fn the_cube_drop_agrees_with_an_independent_solver_and_is_converged() {
    let hcm = Hcm::new();
    let samples = hcm_cube(&hcm, "cube.csv", &[]);
    assert_eq!(samples.len(), 401, "every 1 ms over 0.4 s");
    assert!((samples.last().unwrap().time - 0.4).abs() < 1e-12);
    let reference = simulate(&cube_drop(), REFERENCE_STEP);
    let times: Vec<f64> = samples.iter().map(|s| s.time).collect();
    let positions: Vec<[f64; 3]> = samples.iter().map(|s| s.position).collect();
    let quaternions: Vec<[f64; 4]> = samples.iter().map(|s| s.orientation).collect();
    let (position_error, angle_error) =
        compare(&reference.samples, &times, &positions, &quaternions);
    println!(
        "against the reference over 0.4 s: max position error {:.3e} m, max orientation error {:.3e}°",
        position_error,
        angle_error.to_degrees()
    );
    assert!(position_error < 1e-3, "{position_error} m");
    assert!(
        angle_error.to_degrees() < 1.0,
        "{}°",
        angle_error.to_degrees()
    );

    let halved = hcm_cube(
        &hcm,
        "halved.csv",
        &[
            "simulation.relative_tolerance=5e-10",
            "simulation.absolute_tolerance=5e-11",
        ],
    );
    let (a, b) = (samples.last().unwrap(), halved.last().unwrap());
    let moved = (Vector3::from(a.position) - Vector3::from(b.position)).norm();
    let turned = orientation(a).angle_to(&orientation(b)).to_degrees();
    println!("halving the tolerances moves the final pose by {moved:.3e} m and {turned:.3e}°");
    assert!(moved < 1e-4, "{moved} m");
}
