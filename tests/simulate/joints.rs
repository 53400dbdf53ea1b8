//! Revolute joints (`[[joint]]`, `hcm-host/src/simulate/joints.rs`) against solutions
//! found independently: a compound pendulum's period at 0.5 rad (the exact elliptic
//! integral), a free-flying two-link chain's momentum, angular momentum and energy, and
//! a double pendulum against its Lagrangian equations integrated here by RK4; a joint
//! whose bodies do not meet in the initial state is refused by name.
//!
//! Run with `--nocapture` to see the measured figures.

use hcm_host::scenario::Scenario;
use hcm_host::simulate::simulate;
use nalgebra::{UnitQuaternion, Vector3};
use std::path::Path;

const G: f64 = 9.81;

/// A scene of `bodies` (TOML `[[body]]` tables) and `joints`, with a fixed plane far
/// below that one inert contact needs, simulated for `end` s at tight tolerances.
fn scene(gravity: f64, bodies: &str, joints: &str, end: f64) -> String {
    format!(
        r#"
name = "jointed"
gravity = [0.0, 0.0, {gravity}]
{bodies}
[[body]]
name = "world"
fixed = true
shape = {{ plane = {{ normal = [0.0, 0.0, 1.0] }} }}
position = [0.0, 0.0, -10.0]
[[contact]]
bodies = ["link_1", "world"]
law = "hertz"
parameters = {{ stiffness = 1e9, exponent = 1.5 }}
{joints}
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

/// A box link `name` of mass 1 kg and half extents (0.01, 0.01, `half`) m at `position`
/// turned by `q`, moving at `v` and `w` (world frame).
fn link(
    name: &str,
    half: f64,
    position: Vector3<f64>,
    q: UnitQuaternion<f64>,
    v: Vector3<f64>,
    w: Vector3<f64>,
) -> String {
    let inertia = link_inertia(half);
    let (ix, iz) = (inertia[(0, 0)], inertia[(2, 2)]);
    let q = q.quaternion();
    format!(
        r#"
[[body]]
name = "{name}"
mass = 1.0
shape = {{ box = {{ half_extents = [0.01, 0.01, {half:e}] }} }}
inertia = [{ix:e}, {ix:e}, {iz:e}]
position = [{:e}, {:e}, {:e}]
orientation = {{ quaternion = [{:e}, {:e}, {:e}, {:e}] }}
velocity = [{:e}, {:e}, {:e}]
angular_velocity = [{:e}, {:e}, {:e}]
"#,
        position.x, position.y, position.z, q.w, q.i, q.j, q.k, v.x, v.y, v.z, w.x, w.y, w.z
    )
}

/// The body-frame inertia (kg·m²) of a [`link`] of half length `half` (m).
fn link_inertia(half: f64) -> nalgebra::Matrix3<f64> {
    let across = (0.02f64.powi(2) + (2.0 * half).powi(2)) / 12.0;
    nalgebra::Matrix3::from_diagonal(&Vector3::new(across, across, 2.0 * 0.02f64.powi(2) / 12.0))
}

/// A recorded sample's orientation (body → world).
fn orientation(s: &hcm_host::dataset::Sample) -> UnitQuaternion<f64> {
    let [w, x, y, z] = s.orientation;
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(w, x, y, z))
}

fn joint(bodies: [&str; 2], anchors: [Vector3<f64>; 2]) -> String {
    joint_with(bodies, anchors, "{}")
}

/// [`joint`] with its `law` table (TOML).
fn joint_with(bodies: [&str; 2], anchors: [Vector3<f64>; 2], law: &str) -> String {
    let [a, b] = anchors;
    format!(
        "[[joint]]\nbodies = [\"{}\", \"{}\"]\nanchors = [[{:e}, {:e}, {:e}], [{:e}, {:e}, {:e}]]\naxis = [0.0, 1.0, 0.0]\nlaw = {law}\n",
        bodies[0], bodies[1], a.x, a.y, a.z, b.x, b.y, b.z
    )
}

fn run(text: &str) -> hcm_host::simulate::Simulation {
    let path = Path::new("jointed.toml");
    let model = Scenario::parse(path, text, &[])
        .and_then(|s| s.resolve(path))
        .unwrap();
    simulate(&model).unwrap()
}

/// The angle (rad) about y of each recorded orientation of `body`, with its time.
fn swing(simulation: &hcm_host::simulate::Simulation, body: &str) -> Vec<(f64, f64)> {
    let track = simulation.run.body(body).unwrap();
    (track.samples.iter())
        .map(|s| {
            let [w, _, y, _] = s.orientation;
            (s.time, 2.0 * y.atan2(w))
        })
        .collect()
}

fn about_y(angle: f64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::y_axis(), angle)
}

/// The complete elliptic integral of the first kind K(k) by the arithmetic-geometric mean.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0, (1.0 - k * k).sqrt());
    for _ in 0..30 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// A 0.3 m box hung from its top end swings at 0.5 rad with the period
/// 4·√(I_p/(m·g·c))·K(sin(θ₀/2)), I_p = I + m·c² about the pivot, c = 0.15 m.
#[test]
fn a_compound_pendulum_swings_with_the_exact_period() {
    let (half, theta) = PENDULUM;
    let (bodies, anchors) = released_pendulum();
    let joints = joint(["world", "link_1"], anchors);
    let simulation = run(&scene(-G, &bodies, &joints, 3.0));
    let angles = swing(&simulation, "link_1");
    // Upward zero crossings, linearly interpolated.
    let crossings: Vec<f64> = (angles.windows(2))
        .filter(|w| w[0].1 < 0.0 && w[1].1 >= 0.0)
        .map(|w| w[0].0 + (w[1].0 - w[0].0) * (-w[0].1) / (w[1].1 - w[0].1))
        .collect();
    let periods: Vec<f64> = crossings.windows(2).map(|w| w[1] - w[0]).collect();
    let measured = periods.iter().sum::<f64>() / periods.len() as f64;
    let i_y = (0.02f64.powi(2) + (2.0 * half).powi(2)) / 12.0;
    let pivot = i_y + half * half;
    let exact = 4.0 * (pivot / (G * half)).sqrt() * elliptic_k((theta / 2.0).sin());
    println!(
        "period: measured {measured:.9} s over {} swings, exact {exact:.9} s",
        periods.len()
    );
    assert!(periods.len() >= 2, "{crossings:?}");
    assert!(
        (measured / exact - 1.0).abs() < 1e-5,
        "{measured} vs {exact}"
    );
    let amplitude = angles.iter().map(|a| a.1.abs()).fold(0.0, f64::max);
    assert!((amplitude - theta).abs() < 1e-6, "amplitude {amplitude}");
}

/// Two links joined end to end, thrown spinning without gravity: their momentum,
/// angular momentum about the origin and kinetic energy stay as they start, and the
/// joint holds.
#[test]
fn a_free_two_link_chain_keeps_its_momentum_and_energy() {
    let half = 0.05;
    let q1 = about_y(0.3);
    let q2 = about_y(-0.4);
    let (v1, w1) = (Vector3::new(0.3, -0.1, 0.2), Vector3::new(0.5, 2.0, -0.3));
    let w2 = w1 + q1 * Vector3::new(0.0, 3.0, 0.0);
    let (a1, a2) = (Vector3::new(0.0, 0.0, -half), Vector3::new(0.0, 0.0, half));
    let (r1, r2) = (q1 * a1, q2 * a2);
    let p1 = Vector3::new(0.0, 0.0, 1.0);
    let p2 = p1 + r1 - r2;
    let v2 = v1 + w1.cross(&r1) - w2.cross(&r2);
    let bodies = link("link_1", half, p1, q1, v1, w1) + &link("link_2", half, p2, q2, v2, w2);
    let joints = joint(["link_1", "link_2"], [a1, a2]);
    let simulation = run(&scene(0.0, &bodies, &joints, 2.0));
    let inertia = link_inertia(half);
    let state = |k: usize| {
        let mut momentum = Vector3::zeros();
        let mut angular = Vector3::zeros();
        let mut energy = 0.0;
        let mut ends = Vec::new();
        for (name, anchor) in [("link_1", a1), ("link_2", a2)] {
            let s = &simulation.run.body(name).unwrap().samples[k];
            let p = Vector3::from(s.position);
            let v = Vector3::from(s.velocity);
            let w = Vector3::from(s.angular_velocity);
            let q = orientation(s);
            let world = q.to_rotation_matrix() * inertia * q.to_rotation_matrix().transpose();
            momentum += v;
            angular += p.cross(&v) + world * w;
            energy += 0.5 * v.norm_squared() + 0.5 * w.dot(&(world * w));
            ends.push(p + q * anchor);
        }
        (momentum, angular, energy, (ends[0] - ends[1]).norm())
    };
    let (p0, l0, e0, _) = state(0);
    let last = simulation.run.body("link_1").unwrap().samples.len() - 1;
    let (p, l, e, gap) = state(last);
    println!(
        "after {:.2} s: momentum {:.2e}, angular momentum {:.2e}, energy {:.2e} relative; joint gap {gap:.2e} m",
        simulation.end_time,
        (p - p0).norm() / p0.norm(),
        (l - l0).norm() / l0.norm(),
        (e - e0).abs() / e0
    );
    assert!((p - p0).norm() < 1e-8 * p0.norm());
    assert!((l - l0).norm() < 1e-6 * l0.norm());
    assert!((e - e0).abs() < 1e-6 * e0);
    assert!(gap < 1e-9, "{gap}");
}

/// The double pendulum of two 0.3 m box links (pivot at link 1's top end, the joint at
/// its bottom end and link 2's top end), released at rest from (0.8, −0.3) rad, against
/// its Lagrangian equations integrated by RK4 at 10 µs: the absolute angles agree over
/// 1 s.
#[test]
fn a_double_pendulum_follows_its_lagrangian_equations() {
    let (half, (phi_1, phi_2)) = (0.15, (0.8, -0.3));
    let (q1, q2) = (about_y(phi_1), about_y(phi_2));
    let down = Vector3::new(0.0, 0.0, -half);
    let c1 = q1 * down;
    let c2 = 2.0 * c1 + q2 * down;
    let zero = Vector3::zeros();
    let bodies =
        link("link_1", half, c1, q1, zero, zero) + &link("link_2", half, c2, q2, zero, zero);
    let top = Vector3::new(0.0, 0.0, half);
    let joints = joint(["world", "link_1"], [Vector3::new(0.0, 0.0, 10.0), top])
        + &joint(["link_1", "link_2"], [-top, top]);
    let simulation = run(&scene(-G, &bodies, &joints, 1.0));
    let (first, second) = (swing(&simulation, "link_1"), swing(&simulation, "link_2"));

    // The reference: M(φ)·φ̈ = f(φ, φ̇) for two compound links (mass 1, centre c from
    // their top, inertia i about the centre, link 1 of length l).
    let (c, l, i) = (
        half,
        2.0 * half,
        (0.02f64.powi(2) + (2.0 * half).powi(2)) / 12.0,
    );
    let accelerations = |s: [f64; 4]| {
        let [a, b, da, db] = s;
        let (m11, m12, m22) = (i + c * c + l * l, l * c * (a - b).cos(), i + c * c);
        let f1 = -l * c * (a - b).sin() * db * db - (c + l) * G * a.sin();
        let f2 = l * c * (a - b).sin() * da * da - c * G * b.sin();
        let det = m11 * m22 - m12 * m12;
        [
            da,
            db,
            (m22 * f1 - m12 * f2) / det,
            (m11 * f2 - m12 * f1) / det,
        ]
    };
    let h = 1e-5;
    let mut s = [phi_1, phi_2, 0.0, 0.0];
    let mut worst: f64 = 0.0;
    let mut steps = 0usize;
    for k in 0..first.len() {
        // Whole steps of h to the sample's time (summing h would drift by a step).
        while (steps as f64) * h < first[k].0 - 0.5 * h {
            let add = |s: [f64; 4], d: [f64; 4], f: f64| std::array::from_fn(|j| s[j] + f * d[j]);
            let k1 = accelerations(s);
            let k2 = accelerations(add(s, k1, h / 2.0));
            let k3 = accelerations(add(s, k2, h / 2.0));
            let k4 = accelerations(add(s, k3, h));
            s = std::array::from_fn(|j| {
                s[j] + h / 6.0 * (k1[j] + 2.0 * k2[j] + 2.0 * k3[j] + k4[j])
            });
            steps += 1;
        }
        worst = worst
            .max((first[k].1 - s[0]).abs())
            .max((second[k].1 - s[1]).abs());
    }
    let t = steps as f64 * h;
    println!("double pendulum: largest angle difference over {t:.2} s: {worst:.2e} rad");
    assert!(worst < 1e-8, "{worst}");
}

/// A joint whose anchors are apart in the initial state is refused, naming it.
#[test]
fn a_joint_not_assembled_is_refused_by_name() {
    let zero = Vector3::zeros();
    let bodies = link(
        "link_1",
        0.1,
        Vector3::new(0.0, 0.0, -0.1),
        UnitQuaternion::identity(),
        zero,
        zero,
    );
    let joints = joint(
        ["world", "link_1"],
        [Vector3::new(0.0, 0.0, 10.0), Vector3::new(0.0, 0.0, 0.11)],
    );
    let path = Path::new("jointed.toml");
    let text = scene(-G, &bodies, &joints, 0.1);
    let message = match Scenario::parse(path, &text, &[]).and_then(|s| s.resolve(path)) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        message.contains("joint #0") && message.contains("not assembled"),
        "{message}"
    );
    assert!(message.contains("1.000e-2 m apart"), "{message}");

    // A law out of its domain is refused naming the field.
    let law = "{ viscous = { damping = -1.0 } }";
    let anchors = [Vector3::new(0.0, 0.0, 10.0), Vector3::new(0.0, 0.0, 0.1)];
    let text = scene(
        -G,
        &bodies,
        &joint_with(["world", "link_1"], anchors, law),
        0.1,
    );
    let message = match Scenario::parse(path, &text, &[]).and_then(|s| s.resolve(path)) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    };
    assert!(
        message.contains("law") && message.contains("damping"),
        "{message}"
    );
}

/// The shipped elbow toss (two links on a hinge, each link's vertices on the table):
/// the hinge holds through the landing's impacts, and both links reach the table.
#[test]
fn the_elbow_toss_keeps_its_hinge_through_the_landing() {
    let path = hcm_tests::scenario("elbow_toss.toml");
    let model = Scenario::load(&path, &[]).unwrap().resolve(&path).unwrap();
    let simulation = simulate(&model).unwrap();
    let joint = &model.joints[0];
    let track = |name: &str| simulation.run.body(name).unwrap().samples.clone();
    let (first, second) = (track("elbow_1"), track("elbow_2"));
    let pose = |s: &hcm_host::dataset::Sample| (Vector3::from(s.position), orientation(s));
    let worst = (first.iter().zip(&second))
        .map(|(a, b)| {
            let ((p1, q1), (p2, q2)) = (pose(a), pose(b));
            joint.misfit((&p1, &q1), (&p2, &q2)).0
        })
        .fold(0.0, f64::max);
    println!(
        "elbow toss: {} frames, largest hinge gap {worst:.2e} m",
        first.len()
    );
    assert!(worst < 1e-6, "{worst}");
    for name in ["elbow_1", "elbow_2"] {
        let touched = (simulation.events.iter())
            .any(|e| model.contacts[e.contact].body_1 == model.body_index(name).unwrap());
        assert!(touched, "{name} never touched the table");
    }
}

/// The pendulum's half length (m) and release angle (rad).
const PENDULUM: (f64, f64) = (0.15, 0.5);

/// The 0.3 m link released at 0.5 rad from the vertical, hung by its top end from a
/// point 10 m above the world's plane: its body and the hinge's anchors (world, link).
fn released_pendulum() -> (String, [Vector3<f64>; 2]) {
    let (half, theta) = PENDULUM;
    let q = about_y(theta);
    let centre = -(q * Vector3::new(0.0, 0.0, half));
    let zero = Vector3::zeros();
    let bodies = link("link_1", half, centre, q, zero, zero);
    (
        bodies,
        [Vector3::new(0.0, 0.0, 10.0), Vector3::new(0.0, 0.0, half)],
    )
}

/// The compound pendulum with viscous and Coulomb friction in its hinge: the energy it
/// loses is the work the joint's torque does on the swing, −∫ τ(θ̇)·θ̇ dt (the core's
/// law along the recorded rate, by the trapezoid rule at 1 ms).
#[test]
fn joint_friction_takes_the_energy_its_torque_works() {
    use hcm_core::joint::{JointCoulomb, JointLaw, JointViscous};
    let (half, _) = PENDULUM;
    let (bodies, anchors) = released_pendulum();
    let text =
        "{ viscous = { damping = 0.01 }, coulomb = { torque = 0.02, smoothing_rate = 0.01 } }";
    let joints = joint_with(["world", "link_1"], anchors, text);
    let simulation = run(&scene(-G, &bodies, &joints, 2.0));
    let law = JointLaw {
        viscous: Some(JointViscous { damping: 0.01 }),
        coulomb: Some(JointCoulomb {
            torque: 0.02,
            smoothing_rate: 0.01,
        }),
        ..JointLaw::ZERO
    };
    let i_y = (0.02f64.powi(2) + (2.0 * half).powi(2)) / 12.0;
    let samples = &simulation.run.body("link_1").unwrap().samples;
    let energy = |s: &hcm_host::dataset::Sample| {
        let (v, w) = (Vector3::from(s.velocity), Vector3::from(s.angular_velocity));
        0.5 * v.norm_squared() + 0.5 * i_y * w.y * w.y + G * s.position[2]
    };
    let power = |s: &hcm_host::dataset::Sample| {
        let rate = s.angular_velocity[1];
        -law.torque(0.0, rate) * rate
    };
    let worked: f64 = (samples.windows(2))
        .map(|w| 0.5 * (w[1].time - w[0].time) * (power(&w[0]) + power(&w[1])))
        .sum();
    let lost = energy(&samples[0]) - energy(samples.last().unwrap());
    println!("energy lost {lost:.6e} J, the joint's work {worked:.6e} J");
    assert!(lost > 0.01 * energy(&samples[0]).abs().max(1e-3), "{lost}");
    assert!((lost - worked).abs() < 1e-5 * worked, "{lost} vs {worked}");
}

/// The real elbow tosses replayed (`hcm predict`'s path): each link's start fitted to its
/// own free-flight frames, then assembled onto the hinge (`replay/assembly.rs`) — the
/// first predicted frame of every toss holds the hinge to rounding, and every frame after
/// it within 1e-6 m.
#[test]
fn the_elbow_tosses_replay_from_starts_the_hinge_allows() {
    use hcm_host::dataset::Dataset;
    use hcm_host::replay::{evaluate_tosses, predicted_dataset};
    let path = hcm_tests::scenario("elbow_toss.toml");
    let model = Scenario::load(&path, &[]).unwrap().resolve(&path).unwrap();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/contactnets-elbow/tosses.csv");
    let mut data = Dataset::read(&file).unwrap();
    data.runs.truncate(6);
    let evaluations = evaluate_tosses(&model, &data, || {}).unwrap();
    // Each link scored on its own (% of its 0.1 m, °), the toss's scores their means.
    for e in &evaluations {
        let s = &e.score;
        let names: Vec<&str> = s.bodies.iter().map(|b| b.body.as_str()).collect();
        assert_eq!(names, ["elbow_1", "elbow_2"], "{}", s.run);
        let mean =
            |f: fn(&hcm_host::replay::BodyScore) -> f64| s.bodies.iter().map(f).sum::<f64>() / 2.0;
        assert!(
            (mean(|b| b.position_error) - s.position_error).abs() < 1e-12,
            "{s:?}"
        );
        assert!(
            (mean(|b| b.rotation_error) - s.rotation_error).abs() < 1e-12,
            "{s:?}"
        );
    }
    let predicted = predicted_dataset(&evaluations, "elbow_1");
    let joint = &model.joints[0];
    let pose = |s: &hcm_host::dataset::Sample| (Vector3::from(s.position), orientation(s));
    let (mut first, mut worst) = (0.0f64, 0.0f64);
    for run in &predicted.runs {
        let (a, b) = (run.body("elbow_1").unwrap(), run.body("elbow_2").unwrap());
        assert_eq!(a.samples.len(), b.samples.len(), "{}", run.id);
        for (k, (s1, s2)) in a.samples.iter().zip(&b.samples).enumerate() {
            let ((p1, q1), (p2, q2)) = (pose(s1), pose(s2));
            let gap = joint.misfit((&p1, &q1), (&p2, &q2)).0;
            if k == 0 {
                first = first.max(gap);
            }
            worst = worst.max(gap);
        }
    }
    println!("elbow replays: hinge gap at the start {first:.2e} m, over the window {worst:.2e} m");
    assert!(first < 1e-12, "{first}");
    assert!(worst < 1e-6, "{worst}");
}

/// What does not follow a mechanism yet says so: the final face's forecast (a lone box's)
/// and a contact's residual trained from poses (its samples move one body; the joint's
/// own residual is learned, `tests/train/joint_residual.rs`). Slides and bolts replay
/// (below).
#[test]
fn what_does_not_follow_a_mechanism_yet_is_refused() {
    use hcm_host::dataset::Dataset;
    use hcm_host::replay::{forecast_tosses, Spread};
    let path = hcm_tests::scenario("elbow_toss.toml");
    let model = Scenario::load(&path, &[]).unwrap().resolve(&path).unwrap();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/contactnets-elbow/tosses.csv");
    let mut data = Dataset::read(&file).unwrap();
    data.runs.truncate(2);
    let faces = match forecast_tosses(&model, &data, Spread::of_model(4, 1), true, || {}) {
        Ok(_) => panic!("faces forecast for a mechanism"),
        Err(e) => e.to_string(),
    };
    assert!(
        faces.contains("joint `hinge`") && faces.contains("face"),
        "{faces}"
    );
    let train = match hcm_host::train::motion_rows(&model, &data, 0, 8) {
        Ok(_) => panic!("trained from a mechanism's poses"),
        Err(e) => e.to_string(),
    };
    assert!(
        train.contains("joint `hinge`") && train.contains("trained"),
        "{train}"
    );
}

/// Slides and bolts replay as hinges do (`replay/assembly.rs`): the elbow's links joined
/// by a slide along the hinge's axis, then bolted, thrown onto the table and recorded;
/// each toss replayed from its links' own free-flight fits assembled onto the joint — its
/// first predicted frame holds the joint to rounding and every frame after it within
/// 1e-6 m, and the replay follows the recorded tosses far closer than the frozen pose.
#[test]
fn slides_and_bolts_replay_from_starts_they_allow() {
    use hcm_host::replay::{evaluate_tosses, predicted_dataset, summarize};
    use hcm_host::scenario::JointKind;
    let path = hcm_tests::scenario("elbow_toss.toml");
    let hinged = Scenario::load(&path, &[]).unwrap().resolve(&path).unwrap();
    for kind in [JointKind::Prismatic, JointKind::Fixed] {
        // elbow_2 turned as elbow_1 and placed on its anchor: a start the joint allows.
        let mut model = hinged.clone();
        let joint = model.joints[0].clone();
        let (b1, b2) = (model.bodies[0].clone(), &mut model.bodies[1]);
        b2.orientation = b1.orientation;
        b2.angular_velocity = b1.angular_velocity;
        let arm = b1.orientation * (joint.anchors[0] - joint.anchors[1]);
        b2.position = b1.position + arm;
        b2.velocity = b1.velocity + b1.angular_velocity.cross(&arm);
        model.joints[0].kind = kind;
        let data = hcm_tests::mechanism::thrown_mechanisms(&model, 4, 11);
        let evaluations = evaluate_tosses(&model, &data, || {}).unwrap();
        let predicted = predicted_dataset(&evaluations, "elbow_1");
        let pose = |s: &hcm_host::dataset::Sample| (Vector3::from(s.position), orientation(s));
        let (mut first, mut worst) = (0.0f64, 0.0f64);
        for run in &predicted.runs {
            let (a, b) = (run.body("elbow_1").unwrap(), run.body("elbow_2").unwrap());
            for (k, (s1, s2)) in a.samples.iter().zip(&b.samples).enumerate() {
                let ((p1, q1), (p2, q2)) = (pose(s1), pose(s2));
                let (gap, turn) = joint_of_kind(&joint, kind).misfit((&p1, &q1), (&p2, &q2));
                let misfit = gap.max(turn);
                if k == 0 {
                    first = first.max(misfit);
                }
                worst = worst.max(misfit);
            }
        }
        let summary = summarize(&evaluations);
        println!(
            "{}: start misfit {first:.2e}, worst {worst:.2e}; replays {:.3} % and {:.3}° \
             (frozen pose {:.3} % and {:.3}°)",
            kind.name(),
            summary.position.mean,
            summary.rotation.mean,
            summary.baseline_position.mean,
            summary.baseline_rotation.mean
        );
        assert!(first < 1e-12, "{first}");
        assert!(worst < 1e-6, "{worst}");
        // Far closer than the frozen pose: a tenth of its position error, a fifth of its
        // rotation's.
        assert!(
            summary.position.mean < 0.1 * summary.baseline_position.mean
                && summary.rotation.mean < 0.2 * summary.baseline_rotation.mean,
            "{summary:?}"
        );
    }
}

/// `joint` as a joint of `kind`.
fn joint_of_kind(
    joint: &hcm_host::scenario::Joint,
    kind: hcm_host::scenario::JointKind,
) -> hcm_host::scenario::Joint {
    hcm_host::scenario::Joint {
        kind,
        ..joint.clone()
    }
}

/// A `kind` joint between `bodies` with `anchors`, `axis` (in body 1's frame) and `law`.
fn joint_of(
    kind: &str,
    bodies: [&str; 2],
    anchors: [Vector3<f64>; 2],
    axis: Vector3<f64>,
    law: &str,
) -> String {
    let [a, b] = anchors;
    format!(
        "[[joint]]\nkind = \"{kind}\"\nbodies = [\"{}\", \"{}\"]\nanchors = [[{:e}, {:e}, {:e}], [{:e}, {:e}, {:e}]]\naxis = [{:e}, {:e}, {:e}]\nlaw = {law}\n",
        bodies[0], bodies[1], a.x, a.y, a.z, b.x, b.y, b.z, axis.x, axis.y, axis.z
    )
}

/// A block on a slide to the fixed world, its axis 0.5 rad below the horizontal, with
/// viscous friction c = 0.5 N·s/m: it slides as m·s̈ = m·g·sin β − c·ṡ gives, s(t) =
/// (m·g·sin β/c)·(t − (m/c)·(1 − e^(−c·t/m))), without turning or leaving the axis.
#[test]
fn a_block_on_a_slide_follows_its_equation_of_motion() {
    let (beta, c) = (0.5_f64, 0.5);
    let axis = Vector3::new(beta.cos(), 0.0, -beta.sin());
    let start = Vector3::new(0.0, 0.0, 1.0);
    let body = link(
        "link_1",
        0.05,
        start,
        UnitQuaternion::identity(),
        Vector3::zeros(),
        Vector3::zeros(),
    );
    let world_anchor = start - Vector3::new(0.0, 0.0, -10.0);
    let law = format!("{{ viscous = {{ damping = {c} }} }}");
    let slide = joint_of(
        "prismatic",
        ["world", "link_1"],
        [world_anchor, Vector3::zeros()],
        axis,
        &law,
    );
    let simulation = run(&scene(-G, &body, &slide, 1.0));
    let (mut worst, mut off, mut turn) = (0.0_f64, 0.0_f64, 0.0_f64);
    for s in &simulation.run.body("link_1").unwrap().samples {
        let t = s.time;
        let exact = (G * beta.sin() / c) * (t - (1.0 - (-c * t).exp()) / c);
        let moved = Vector3::from(s.position) - start;
        worst = worst.max((moved.dot(&axis) - exact).abs());
        off = off.max((moved - axis * moved.dot(&axis)).norm());
        let [w, x, y, z] = s.orientation;
        turn = turn.max(2.0 * (x * x + y * y + z * z).sqrt().atan2(w.abs()));
    }
    println!("slide: s off by {worst:.2e} m, off the axis {off:.2e} m, turned {turn:.2e} rad");
    assert!(
        worst < 1e-8 && off < 1e-9 && turn < 1e-9,
        "{worst} {off} {turn}"
    );
}

/// Half length (m) of the links of [`thrown_pair`].
const PAIR_HALF: f64 = 0.05;

/// Two aligned links end to end (link 1 turned 0.3 rad about y), thrown without gravity
/// as one rigid body spinning, link 2 sliding at `slide` (m/s) along link 1's long axis
/// besides: the bodies' TOML and the anchors of the ends that meet (m, each link's frame).
fn thrown_pair(slide: f64) -> (String, [Vector3<f64>; 2]) {
    let half = PAIR_HALF;
    let q = about_y(0.3);
    let (v1, w) = (Vector3::new(0.3, -0.1, 0.2), Vector3::new(0.5, 2.0, -0.3));
    let (a1, a2) = (Vector3::new(0.0, 0.0, -half), Vector3::new(0.0, 0.0, half));
    let p1 = Vector3::new(0.0, 0.0, 1.0);
    let p2 = p1 + q * a1 - q * a2;
    let v2 = v1 + w.cross(&(p2 - p1)) + q * Vector3::z() * slide;
    let bodies = link("link_1", half, p1, q, v1, w) + &link("link_2", half, p2, q, v2, w);
    (bodies, [a1, a2])
}

/// Two links bolted together (a fixed joint) thrown spinning without gravity move as one
/// rigid body: their relative pose stays as it started, momentum and energy are kept.
#[test]
fn two_links_bolted_together_move_as_one_body() {
    let (bodies, [a1, a2]) = thrown_pair(0.0);
    let bolt = joint_of("fixed", ["link_1", "link_2"], [a1, a2], Vector3::y(), "{}");
    let simulation = run(&scene(0.0, &bodies, &bolt, 2.0));
    let pose = |name: &str, k: usize| {
        let s = &simulation.run.body(name).unwrap().samples[k];
        let q = orientation(s);
        (Vector3::from(s.position), q, Vector3::from(s.velocity))
    };
    let samples = simulation.run.body("link_1").unwrap().samples.len();
    let (mut gap, mut turn) = (0.0_f64, 0.0_f64);
    for k in 0..samples {
        let ((p1, q1, _), (p2, q2, _)) = (pose("link_1", k), pose("link_2", k));
        gap = gap.max(((p1 + q1 * a1) - (p2 + q2 * a2)).norm());
        turn = turn.max((q1.inverse() * q2).angle());
    }
    let momentum = |k: usize| pose("link_1", k).2 + pose("link_2", k).2;
    let drift = (momentum(samples - 1) - momentum(0)).norm() / momentum(0).norm();
    println!("bolted: anchors {gap:.2e} m apart, turned {turn:.2e} rad, momentum {drift:.2e}");
    assert!(
        gap < 1e-9 && turn < 1e-9 && drift < 1e-8,
        "{gap} {turn} {drift}"
    );
}

/// Two links on a free slide along link 1's long axis, thrown spinning and sliding
/// apart without gravity: the slide turns with link 1 (the curvature terms of its rows),
/// and momentum and energy are kept while link 2 never leaves the axis nor turns.
#[test]
fn a_spinning_slide_keeps_its_axis_momentum_and_energy() {
    let half = PAIR_HALF;
    let (bodies, [a1, a2]) = thrown_pair(-0.4);
    let slide = joint_of(
        "prismatic",
        ["link_1", "link_2"],
        [a1, a2],
        Vector3::z(),
        "{}",
    );
    let simulation = run(&scene(0.0, &bodies, &slide, 1.0));
    let inertia = link_inertia(half);
    let samples = simulation.run.body("link_1").unwrap().samples.len();
    let state = |k: usize| {
        let (mut momentum, mut energy) = (Vector3::zeros(), 0.0);
        let mut poses = Vec::new();
        for name in ["link_1", "link_2"] {
            let s = &simulation.run.body(name).unwrap().samples[k];
            let q = orientation(s);
            let (v, w) = (Vector3::from(s.velocity), Vector3::from(s.angular_velocity));
            let world = q.to_rotation_matrix() * inertia * q.to_rotation_matrix().transpose();
            momentum += v;
            energy += 0.5 * v.norm_squared() + 0.5 * w.dot(&(world * w));
            poses.push((Vector3::from(s.position), q));
        }
        let ((p1, q1), (p2, q2)) = (poses[0], poses[1]);
        let gap = (p1 + q1 * a1) - (p2 + q2 * a2);
        let axis = q1 * Vector3::z();
        let off = (gap - axis * gap.dot(&axis)).norm();
        (
            momentum,
            energy,
            off,
            (q1.inverse() * q2).angle(),
            gap.dot(&axis),
        )
    };
    let (p0, e0, ..) = state(0);
    let (mut off, mut turn) = (0.0_f64, 0.0_f64);
    for k in 0..samples {
        let (_, _, o, t, _) = state(k);
        (off, turn) = (off.max(o), turn.max(t));
    }
    let (p, e, _, _, slid) = state(samples - 1);
    let (dp, de) = ((p - p0).norm() / p0.norm(), (e - e0).abs() / e0);
    println!("spinning slide: slid {slid:.3} m, off the axis {off:.2e} m, turned {turn:.2e} rad, momentum {dp:.2e}, energy {de:.2e}");
    assert!(slid.abs() > 0.1, "it slides: {slid}");
    assert!(
        off < 1e-9 && turn < 1e-9 && dp < 1e-8 && de < 1e-6,
        "{off} {turn} {dp} {de}"
    );
}

/// The pendulum released at 0.5 rad with a stop at −0.3 rad (k = 500 N·m/rad, c = 0.5
/// N·m·s/rad): it swings into the stop, is pushed back within the depth its energy there
/// allows (½·k·δ² = m·g·c·(cos 0.3 − cos 0.5), δ = 0.0214 rad, gravity's pull adding a
/// little), and returns below its release angle, the stop's damper having taken energy.
#[test]
fn a_hinge_stop_turns_the_pendulum_back() {
    let (half, theta) = PENDULUM;
    let (bodies, anchors) = released_pendulum();
    let stop = "{ limit = { lower = -0.3, upper = 0.6, stiffness = 500.0, damping = 0.5 } }";
    let joints = joint_with(["world", "link_1"], anchors, stop);
    let simulation = run(&scene(-G, &bodies, &joints, 1.0));
    let angles = swing(&simulation, "link_1");
    let lowest = angles.iter().map(|a| a.1).fold(f64::INFINITY, f64::min);
    let turned = angles.iter().position(|a| a.1 == lowest).unwrap();
    let back = angles[turned..]
        .iter()
        .map(|a| a.1)
        .fold(f64::NEG_INFINITY, f64::max);
    let depth = (2.0 * G * half * (0.3f64.cos() - 0.5f64.cos()) / 500.0).sqrt();
    println!("stop: lowest {lowest:.4} rad (free depth {depth:.4}), back to {back:.4} rad");
    assert!(lowest < -0.3 && lowest > -0.3 - 1.5 * depth, "{lowest}");
    assert!(back > 0.0 && back < theta - 1e-3, "{back}");
}
