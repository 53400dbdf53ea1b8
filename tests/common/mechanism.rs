//! Throwing a two-body mechanism (the elbow): its scenario's start turned and lifted as
//! one rigid piece, its joint opened or closed, and its links moving together as one
//! rigid motion plus a turn about the joint — every draw kept on the joint (the anchors
//! together, the axes parallel, their velocities alike), so the simulator starts
//! assembled.

use hcm_host::scenario::Model;
use nalgebra::{UnitQuaternion, Vector3};
use rand::RngExt;

/// `model` (two moving bodies held by its first joint) thrown from seeded draws:
/// the pair turned by a random yaw and ±0.5 rad of tilt about its centre of mass, which
/// starts 0.15–0.25 m above the origin; the joint turned by ±0.8 rad from the
/// scenario's; the pair moving at 0.8–1.6 m/s sideways and 0.5 m/s down, spinning at
/// up to 6 rad/s (3 about the vertical), the child turning about the joint at ±5 rad/s
/// more (a hinge's; a slide or a bolt thrown as one rigid piece).
pub fn throw_mechanism(model: &mut Model, rng: &mut impl RngExt) {
    let joint = model.joints[0].clone();
    let [parent, child] = joint.bodies;
    let anchor = |m: &Model| {
        let p = &m.bodies[parent];
        (
            p.position + p.orientation * joint.anchors[0],
            p.orientation * joint.axis,
        )
    };
    // The joint opened by Δθ: the child turned about the axis through the anchor.
    // A hinge only: a slide or a bolt keeps its links' relative turn (the draws are
    // made all the same, so that a hinge's throws do not depend on it).
    let hinge = joint.kind == hcm_host::scenario::JointKind::Revolute;
    let (point, axis) = anchor(model);
    let opening = rng.random_range(-0.8..0.8);
    let open = UnitQuaternion::from_axis_angle(&axis, if hinge { opening } else { 0.0 });
    let c = &mut model.bodies[child];
    c.position = point + open * (c.position - point);
    c.orientation = open * c.orientation;
    // The pair turned about its centre of mass and lifted.
    let mass = model.bodies[parent].mass + model.bodies[child].mass;
    let centre = (model.bodies[parent].position * model.bodies[parent].mass
        + model.bodies[child].position * model.bodies[child].mass)
        / mass;
    let turn = UnitQuaternion::from_euler_angles(
        rng.random_range(-0.5..0.5),
        rng.random_range(-0.5..0.5),
        rng.random_range(0.0..std::f64::consts::TAU),
    );
    let lifted = Vector3::new(0.0, 0.0, rng.random_range(0.15..0.25));
    for b in [parent, child] {
        let body = &mut model.bodies[b];
        body.position = lifted + turn * (body.position - centre);
        body.orientation = turn * body.orientation;
    }
    // One rigid motion, then the child's turn about the joint.
    let angle = rng.random_range(0.0..std::f64::consts::TAU);
    let speed = rng.random_range(0.8..1.6);
    let velocity = Vector3::new(speed * angle.cos(), speed * angle.sin(), -0.5);
    let spin = Vector3::new(
        rng.random_range(-6.0..6.0),
        rng.random_range(-6.0..6.0),
        rng.random_range(-3.0..3.0),
    );
    let rate = rng.random_range(-5.0..5.0) * if hinge { 1.0 } else { 0.0 };
    for b in [parent, child] {
        let body = &mut model.bodies[b];
        body.velocity = velocity + spin.cross(&(body.position - lifted));
        body.angular_velocity = spin;
    }
    let (point, axis) = anchor(model);
    let c = &mut model.bodies[child];
    c.angular_velocity += axis.into_inner() * rate;
    c.velocity += (axis.into_inner() * rate).cross(&(c.position - point));
}

/// `count` throws of `model` ([`throw_mechanism`]) simulated, run ids `toss_000`…, with
/// every state the simulator records (filmed by [`crate::filmed_poses`]).
pub fn thrown_mechanisms(model: &Model, count: usize, seed: u64) -> hcm_host::dataset::Dataset {
    use rand::SeedableRng;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let mut data = hcm_host::dataset::Dataset::default();
    for k in 0..count {
        let mut toss = model.clone();
        throw_mechanism(&mut toss, &mut rng);
        let mut run = hcm_host::simulate::simulate(&toss)
            .expect("a thrown mechanism simulates")
            .run;
        run.id = format!("toss_{k:03}");
        data.runs.push(run);
    }
    data
}
