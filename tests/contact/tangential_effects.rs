//! The contact's tangential effects (`hcm_core::friction::TangentialEffects`)
//! in the 3D simulator against closed forms: a box resting flat and spinning on a
//! frictionless plane is stopped by torsional resistance at the rate a_t·m·g / I_zz;
//! one sliding on it slows under viscous friction as v₀·exp(−4·c_v·t/m) (four
//! corners); a solid sphere rolling on a plane with friction is slowed by rolling
//! resistance at (5/7)·a_r·g/r; and a scenario's `tangential` table is checked field
//! by field.
//!
//! Run with `--nocapture` to see the measured figures.

use hcm_host::scenario::Scenario;
use hcm_host::simulate::simulate;
use std::path::Path;

/// Box: 0.1 m × 0.06 m × 0.04 m, 0.5 kg (kg·m², about z: m·(a² + b²)/12).
const MASS: f64 = 0.5;
const I_ZZ: f64 = MASS * (0.1 * 0.1 + 0.06 * 0.06) / 12.0;
/// IMPACT stiffness (N/m^1.5) and exponent of the contact.
const STIFFNESS: f64 = 1e8;
const EXPONENT: f64 = 1.5;

/// The box resting flat at its static indentation (each corner carrying m·g/4), with
/// `velocity` (m/s) and `angular_velocity` (rad/s, world), on a frictionless plane with
/// the `tangential` table (TOML), simulated for `end` s.
fn resting_box(velocity: &str, angular_velocity: &str, tangential: &str, end: f64) -> String {
    let depth = (MASS * 9.81 / 4.0 / STIFFNESS).powf(1.0 / EXPONENT);
    let z = 0.02 - depth;
    format!(
        r#"
name = "resting_box"
gravity = [0.0, 0.0, -9.81]
[[body]]
name = "box"
mass = {MASS}
shape = {{ box = {{ half_extents = [0.05, 0.03, 0.02] }} }}
position = [0.0, 0.0, {z:e}]
velocity = {velocity}
angular_velocity = {angular_velocity}
[[body]]
name = "ground"
fixed = true
shape = {{ plane = {{ normal = [0.0, 0.0, 1.0] }} }}
position = [0.0, 0.0, 0.0]
[[contact]]
bodies = ["box", "ground"]
law = "impact"
parameters = {{ stiffness = {STIFFNESS:e}, exponent = {EXPONENT}, max_damping = 20.0, full_damping_depth = 1e-4 }}
tangential = {tangential}
[simulation]
end_time = {end}
relative_tolerance = 1e-10
absolute_tolerance = 1e-12
max_step = 1e-3
[record]
contact_sample_period = 1e-3
flight_sample_period = 1e-3
contact_margin = 0.0
"#
    )
}

fn run(text: &str) -> hcm_host::simulate::Simulation {
    let path = Path::new("tangential.toml");
    let model = Scenario::parse(path, text, &[])
        .and_then(|s| s.resolve(path))
        .unwrap();
    assert!(model.is_rigid());
    simulate(&model).unwrap()
}

#[test]
fn torsional_resistance_stops_a_spinning_box_at_the_closed_form_rate() {
    let (arm, omega_0) = (1e-3, 2.0); // m, rad/s
    let tangential = format!("{{ torsional_resistance = {{ arm = {arm}, spin_rate = 1e-3 }} }}");
    let text = resting_box("[0.0, 0.0, 0.0]", "[0.0, 0.0, 2.0]", &tangential, 0.2);
    let simulation = run(&text);
    // While it spins well above ω_t the couple is a_t·Σf_n = a_t·m·g: ω falls linearly.
    let rate = arm * MASS * 9.81 / I_ZZ;
    let samples = &simulation.run.bodies[0].samples;
    let mut worst: f64 = 0.0;
    for s in samples.iter().filter(|s| s.time <= 0.15) {
        let expected = omega_0 - rate * s.time;
        worst = worst.max((s.angular_velocity[2] - expected).abs() / omega_0);
    }
    println!(
        "torsional: ω falls at {rate:.4} rad/s²; the simulation within {worst:.2e} of ω₀ over 0.15 s"
    );
    assert!(worst < 1e-5, "{worst}");
    // Without the effect the frictionless box keeps spinning.
    let free = run(&resting_box(
        "[0.0, 0.0, 0.0]",
        "[0.0, 0.0, 2.0]",
        "{}",
        0.2,
    ));
    let last = free.run.bodies[0].samples.last().unwrap();
    assert!(
        (last.angular_velocity[2] - omega_0).abs() < 1e-6,
        "{last:?}"
    );
}

#[test]
fn viscous_friction_slows_a_sliding_box_exponentially() {
    let (c, v_0) = (0.5, 0.5); // N·s/m per corner, m/s
    let tangential = format!("{{ viscous_friction = {{ coefficient = {c} }} }}");
    let text = resting_box("[0.5, 0.0, 0.0]", "[0.0, 0.0, 0.0]", &tangential, 0.3);
    let simulation = run(&text);
    let samples = &simulation.run.bodies[0].samples;
    let mut worst: f64 = 0.0;
    for s in samples {
        let expected = v_0 * (-4.0 * c * s.time / MASS).exp();
        worst = worst.max((s.velocity[0] - expected).abs() / v_0);
    }
    let last = samples.last().unwrap();
    println!(
        "viscous: v(0.3 s) = {:.6} m/s vs {:.6}; worst {worst:.2e} of v₀",
        last.velocity[0],
        v_0 * (-4.0 * c * 0.3 / MASS).exp()
    );
    assert!(worst < 2e-5, "{worst}");
}

#[test]
fn rolling_resistance_slows_a_rolling_sphere_at_the_closed_form_rate() {
    // A solid sphere (r, m, I = 2/5·m·r²) rolling without slipping (STEP friction
    // holds the contact point), couple a_r·m·g against the rolling: m·v̇ = F,
    // I·ω̇ = −r·F − a_r·m·g, v̇ = r·ω̇ ⇒ v̇ = −(5/7)·a_r·g/r.
    let (r, m, arm, v_0) = (0.02, 0.1, 1e-3, 0.5);
    let inertia = 0.4 * m * r * r;
    let depth = (m * 9.81 / STIFFNESS).powf(1.0 / EXPONENT);
    let text = format!(
        r#"
name = "rolling_sphere"
gravity = [0.0, 0.0, -9.81]
[[body]]
name = "ball"
mass = {m}
shape = {{ sphere = {{ radius = {r} }} }}
inertia = [{inertia:e}, {inertia:e}, {inertia:e}]
position = [0.0, 0.0, {z:e}]
velocity = [{v_0}, 0.0, 0.0]
angular_velocity = [0.0, {w:e}, 0.0]
[[body]]
name = "ground"
fixed = true
shape = {{ plane = {{ normal = [0.0, 0.0, 1.0] }} }}
position = [0.0, 0.0, 0.0]
[[contact]]
bodies = ["ball", "ground"]
law = "impact"
parameters = {{ stiffness = {STIFFNESS:e}, exponent = {EXPONENT}, max_damping = 5.0, full_damping_depth = 1e-4 }}
friction = {{ mu_static = 0.6, mu_dynamic = 0.5, v_static = 1e-4, v_dynamic = 1e-3 }}
tangential = {{ rolling_resistance = {{ arm = {arm}, roll_rate = 1e-3 }} }}
[simulation]
end_time = 0.3
relative_tolerance = 1e-10
absolute_tolerance = 1e-12
max_step = 1e-3
[record]
contact_sample_period = 1e-3
flight_sample_period = 1e-3
contact_margin = 0.0
"#,
        z = r - depth,
        w = v_0 / (r - depth),
    );
    let simulation = run(&text);
    let rate = 5.0 / 7.0 * arm * 9.81 / r;
    let samples = &simulation.run.bodies[0].samples;
    let mut worst: f64 = 0.0;
    for s in samples.iter().filter(|s| s.time >= 0.01) {
        let expected = v_0 - rate * s.time;
        worst = worst.max((s.velocity[0] - expected).abs() / (rate * s.time));
    }
    let last = samples.last().unwrap();
    println!(
        "rolling: v(0.3 s) = {:.6} m/s vs {:.6} (v̇ = {rate:.4} m/s²); worst {worst:.2e} of the loss",
        last.velocity[0],
        v_0 - rate * 0.3
    );
    assert!(worst < 0.01, "{worst}");
}

#[test]
fn a_bad_tangential_table_is_refused_with_its_field() {
    let path = Path::new("resting_box.toml");
    for (table, needle) in [
        (
            "{ torsional_resistance = { arm = 1e-3, spin_rate = 0.0 } }",
            "torsional_resistance.spin_rate",
        ),
        (
            "{ viscous_friction = { coefficient = -1.0 } }",
            "viscous_friction.coefficient",
        ),
        ("{ rolling = { arm = 1e-3 } }", "rolling"),
    ] {
        let text = resting_box("[0.0, 0.0, 0.0]", "[0.0, 0.0, 0.0]", table, 0.1);
        let message = match Scenario::parse(path, &text, &[]).and_then(|s| s.resolve(path)) {
            Ok(_) => panic!("{table} was accepted"),
            Err(e) => e.to_string(),
        };
        assert!(message.contains(needle), "{table}: {message}");
        assert!(message.contains("tangential"), "{table}: {message}");
    }
}
