//! The joints' constraint forces: each revolute joint holds its two anchors together
//! (3 rows) and its two bodies' axes parallel (2 rows), in the moving bodies' own
//! coordinates (each body keeps its 13 components; the joint adds none).
//!
//! Why constraints and not reduced coordinates: every body of a scene keeps the state,
//! contacts and records it has without joints, so a jointed scene runs through the same
//! integrator, contact model and replay as any other, and a scene without joints pays
//! nothing. The price is drift, held by Baumgarte's stabilisation (1972, *Stabilization
//! of constraints and integrals of motion in dynamical systems*, Comput. Methods Appl.
//! Mech. Eng. 1): the rows are enforced on the acceleration,
//!
//!   J·u̇ = −J̇·u − 2·ω_c·Ċ − ω_c²·C,
//!
//! with C the rows' error (m, –) and Ċ its rate, so that an error the integrator leaves
//! decays critically damped at ω_c instead of growing. The multipliers λ solve
//! (J·M⁻¹·Jᵀ)·λ = −J̇·u − 2·ω_c·Ċ − ω_c²·C − J·u̇_free, u̇_free the accelerations without
//! the joints (gravity, contacts, drag, the gyroscopic terms); Jᵀ·λ is each body's
//! constraint force and torque. A joint's own law (spring, friction) is a torque about
//! its axis, added before.

use nalgebra::{DMatrix, DVector, Matrix3, SMatrix, SVector, UnitQuaternion, Vector3};

use crate::scenario::{Joint, JointKind, Model, Pose};

/// ω_c of Baumgarte's stabilisation (rad/s): an error decays with a 20 ms time constant,
/// slow beside the contacts' milliseconds (the step size never has to follow it) and
/// fast beside a toss's second.
pub const STABILISATION: f64 = 50.0;

/// Rows a revolute joint holds (–).
const ROWS: usize = 5;

/// What the solve needs of one moving or fixed body at this instant.
#[derive(Clone, Copy, Debug)]
pub struct BodyMotion {
    /// Pose and velocities (world frame).
    pub pose: Pose,
    /// Its acceleration (m/s²) and angular acceleration (rad/s², world frame) without
    /// the joints; 0 for a fixed body.
    pub free: (Vector3<f64>, Vector3<f64>),
    /// 1/m (1/kg) and the world-frame inverse inertia (1/(kg·m²)); 0 for a fixed body.
    pub inverse: (f64, Matrix3<f64>),
}

/// One row: its coefficients on each body's velocity and angular velocity (world
/// frame), and its right-hand side.
struct Row {
    bodies: [usize; 2],
    linear: [Vector3<f64>; 2],
    angular: [Vector3<f64>; 2],
    /// −J̇·u − 2·ω_c·Ċ − ω_c²·C.
    bias: f64,
}

/// The rows of `joint` with its bodies in `motion`, added to `out`: a hinge's 5 (the
/// anchors together, the axes parallel), a slide's 5 (the anchors together off the axis,
/// no turn), a fixed joint's 6 (the anchors together, no turn).
fn push_rows(joint: &Joint, motion: &[BodyMotion], out: &mut Vec<Row>) {
    let [x, y, z, t1, t2] = rows(joint, motion);
    let point = [x, y, z];
    match joint.kind {
        JointKind::Revolute => out.extend(point.into_iter().chain([t1, t2])),
        JointKind::Prismatic => {
            out.extend(slide_rows(joint, motion));
            out.extend([t1, t2, lock_row(joint, motion)]);
        }
        JointKind::Fixed => {
            out.extend(point.into_iter().chain([t1, t2, lock_row(joint, motion)]));
        }
    }
}

/// The row that stops body 2 turning about the axis relative to body 1: C = −θ,
/// J·u = a·(ω₁ − ω₂), J̇·u = (ω₁ × a)·(ω₁ − ω₂), a the axis as body 1 carries it.
fn lock_row(joint: &Joint, motion: &[BodyMotion]) -> Row {
    let [i, j] = joint.bodies;
    let (a, b) = (&motion[i].pose, &motion[j].pose);
    let axis = a.orientation * joint.axis.into_inner();
    let (wa, wb) = (a.angular_velocity, b.angular_velocity);
    let angle = joint.angle(&a.orientation, &b.orientation);
    Row {
        bodies: [i, j],
        linear: [Vector3::zeros(), Vector3::zeros()],
        angular: [axis, -axis],
        bias: bias(
            -angle,
            axis.dot(&(wa - wb)),
            wa.cross(&axis).dot(&(wa - wb)),
        ),
    }
}

/// A slide's two rows: the anchors' gap e = (p₁ + r₁) − (p₂ + r₂) off the axis, along
/// the normals m as body 1 carries them, C = m·e, held at 0 (its rate and curvature
/// differentiated with m turning with body 1).
fn slide_rows(joint: &Joint, motion: &[BodyMotion]) -> [Row; 2] {
    let g = Anchors::of(joint, motion);
    let [i, j] = g.bodies;
    let (a, wa) = (&motion[i].pose, g.spin[0]);
    joint.normals.map(|n| {
        let m = a.orientation * n;
        let turning = wa.cross(&m);
        let j_dot_u =
            wa.cross(&turning).dot(&g.gap) + 2.0 * turning.dot(&g.rate) + m.dot(&g.curvature);
        Row {
            bodies: [i, j],
            linear: [m, -m],
            angular: [m.cross(&g.gap) + g.arms[0].cross(&m), -g.arms[1].cross(&m)],
            bias: bias(m.dot(&g.gap), turning.dot(&g.gap) + m.dot(&g.rate), j_dot_u),
        }
    })
}

/// A joint's two anchors as its bodies in `motion` carry them (world frame).
struct Anchors {
    /// Body 1 and body 2.
    bodies: [usize; 2],
    /// Each anchor from its body's centre of mass (m).
    arms: [Vector3<f64>; 2],
    /// Each body's angular velocity (rad/s).
    spin: [Vector3<f64>; 2],
    /// Anchor 1 minus anchor 2 (m).
    gap: Vector3<f64>,
    /// Its rate (m/s).
    rate: Vector3<f64>,
    /// The part of its second derivative the accelerations do not give,
    /// ω₁×(ω₁×r₁) − ω₂×(ω₂×r₂) (m/s²).
    curvature: Vector3<f64>,
}

impl Anchors {
    fn of(joint: &Joint, motion: &[BodyMotion]) -> Anchors {
        let [i, j] = joint.bodies;
        let (a, b) = (&motion[i].pose, &motion[j].pose);
        let (ra, rb) = (
            a.orientation * joint.anchors[0],
            b.orientation * joint.anchors[1],
        );
        let (wa, wb) = (a.angular_velocity, b.angular_velocity);
        Anchors {
            bodies: [i, j],
            arms: [ra, rb],
            spin: [wa, wb],
            gap: (a.position + ra) - (b.position + rb),
            rate: (a.velocity + wa.cross(&ra)) - (b.velocity + wb.cross(&rb)),
            curvature: wa.cross(&wa.cross(&ra)) - wb.cross(&wb.cross(&rb)),
        }
    }
}

/// −J̇·u − 2·ω_c·Ċ − ω_c²·C: a row's right-hand side from its error `c`, its rate
/// `c_dot` and `j_dot_u`.
fn bias(c: f64, c_dot: f64, j_dot_u: f64) -> f64 {
    -j_dot_u - 2.0 * STABILISATION * c_dot - STABILISATION * STABILISATION * c
}

/// The rows of a hinge with its bodies in `motion`.
fn rows(joint: &Joint, motion: &[BodyMotion]) -> [Row; ROWS] {
    let g = Anchors::of(joint, motion);
    let [i, j] = g.bodies;
    let (a, b) = (&motion[i].pose, &motion[j].pose);
    let ([ra, rb], [wa, wb]) = (g.arms, g.spin);
    let (error, rate, curvature) = (g.gap, g.rate, g.curvature);
    let point = |k: usize| {
        let e = Vector3::ith(k, 1.0);
        Row {
            bodies: [i, j],
            linear: [e, -e],
            angular: [ra.cross(&e), -rb.cross(&e)],
            bias: bias(error[k], rate[k], curvature[k]),
        }
    };
    let axis = a.orientation * joint.axis.into_inner();
    let [n1, n2] = joint.normals;
    let turn = |n: Vector3<f64>| {
        let normal = b.orientation * n;
        let lever = axis.cross(&normal);
        // d/dt of (ω_a − ω_b)·(a × n) with ȧ = ω_a × a and ṅ = ω_b × n.
        let j_dot_u =
            (wa - wb).dot(&(wa.cross(&axis).cross(&normal) + axis.cross(&wb.cross(&normal))));
        Row {
            bodies: [i, j],
            linear: [Vector3::zeros(), Vector3::zeros()],
            angular: [lever, -lever],
            bias: bias(axis.dot(&normal), (wa - wb).dot(&lever), j_dot_u),
        }
    };
    [point(0), point(1), point(2), turn(n1), turn(n2)]
}

/// The constraint force and torque (N, N·m about the centre of mass, world frame) on
/// every body of `model` that keeps its joints, the bodies in `motion`; added into
/// `loads`. Where the rows cannot be solved (joints that fight each other) nothing is
/// added: the bodies then move as if unjoined and the run's drift says so.
pub fn add_constraint_loads(
    model: &Model,
    motion: &[BodyMotion],
    loads: &mut [(Vector3<f64>, Vector3<f64>)],
) {
    let mut rows: Vec<Row> = Vec::with_capacity(6 * model.joints.len());
    for joint in &model.joints {
        push_rows(joint, motion, &mut rows);
    }
    let n = rows.len();
    // M⁻¹ times each row's coefficients on each of its two bodies, once per row.
    let inverse: Vec<[(Vector3<f64>, Vector3<f64>); 2]> = (rows.iter())
        .map(|r| {
            std::array::from_fn(|side| {
                let (m, i) = motion[r.bodies[side]].inverse;
                (r.linear[side] * m, i * r.angular[side])
            })
        })
        .collect();
    let entry = |p: usize, q: usize| {
        let (r, s) = (&rows[p], &rows[q]);
        let mut sum = 0.0;
        for (side, (linear, angular)) in inverse[p].iter().enumerate() {
            for other in 0..2 {
                if s.bodies[other] == r.bodies[side] {
                    sum += linear.dot(&s.linear[other]) + angular.dot(&s.angular[other]);
                }
            }
        }
        sum
    };
    let rhs = |p: usize| {
        let r = &rows[p];
        let free: f64 = (0..2)
            .map(|side| {
                let (a, alpha) = motion[r.bodies[side]].free;
                r.linear[side].dot(&a) + r.angular[side].dot(&alpha)
            })
            .sum();
        r.bias - free
    };
    let Some(lambda) = solve(n, entry, rhs) else {
        return;
    };
    for (r, l) in rows.iter().zip(lambda.iter()) {
        for side in 0..2 {
            let load = &mut loads[r.bodies[side]];
            load.0 += r.linear[side] * *l;
            load.1 += r.angular[side] * *l;
        }
    }
}

/// λ of (J·M⁻¹·Jᵀ)·λ = rhs, the matrix's entries from `entry`: Cholesky, LU where the
/// matrix is not positive definite (joints that constrain the same motion twice), None
/// where neither solves. One joint's 5 rows in fixed-size matrices on the stack (the
/// elbow's hinge solves at every evaluation of a jointed scene's derivative and its
/// Jacobian: measured by `benches/ball_simulation.rs`'s elbow toss), more in heap ones.
fn solve(
    n: usize,
    entry: impl Fn(usize, usize) -> f64,
    rhs: impl Fn(usize) -> f64,
) -> Option<Vec<f64>> {
    if n == ROWS {
        let matrix = SMatrix::<f64, ROWS, ROWS>::from_fn(&entry);
        let rhs = SVector::<f64, ROWS>::from_fn(|p, _| rhs(p));
        let lambda = (matrix.cholesky().map(|c| c.solve(&rhs))).or_else(|| matrix.lu().solve(&rhs));
        return lambda.map(|l| l.iter().copied().collect());
    }
    let matrix = DMatrix::from_fn(n, n, &entry);
    let rhs = DVector::from_fn(n, |p, _| rhs(p));
    let lambda =
        (matrix.clone().cholesky().map(|c| c.solve(&rhs))).or_else(|| matrix.lu().solve(&rhs));
    lambda.map(|l| l.iter().copied().collect())
}

/// Each joint's own torque (its law at its angle and rate) added into `loads`: on body 2
/// about the axis, the opposite on body 1; the bodies at `poses`.
pub fn add_law_torques(model: &Model, poses: &[Pose], loads: &mut [(Vector3<f64>, Vector3<f64>)]) {
    for joint in (model.joints.iter()).filter(|j| !j.law.is_zero() || j.residual.is_some()) {
        let [b1, b2] = joint.bodies;
        let (p1, p2) = (&poses[b1], &poses[b2]);
        let axis = p1.orientation * joint.axis.into_inner();
        match joint.kind {
            JointKind::Revolute => {
                let angle = joint.angle(&p1.orientation, &p2.orientation);
                let rate = (p2.angular_velocity - p1.angular_velocity).dot(&axis);
                let torque = axis * joint_torque(joint, angle, rate);
                loads[b2].1 += torque;
                loads[b1].1 -= torque;
            }
            JointKind::Prismatic => {
                // s: body 2's anchor from body 1's along the axis (m), ṡ its rate with
                // the axis turning with body 1; the force on body 2 at its anchor, its
                // opposite on body 1 at the same point.
                let (r1, r2) = (
                    p1.orientation * joint.anchors[0],
                    p2.orientation * joint.anchors[1],
                );
                let gap = (p2.position + r2) - (p1.position + r1);
                let slip = (p2.velocity + p2.angular_velocity.cross(&r2))
                    - (p1.velocity + p1.angular_velocity.cross(&r1));
                let rate = p1.angular_velocity.cross(&axis).dot(&gap) + axis.dot(&slip);
                let force = axis * joint_torque(joint, gap.dot(&axis), rate);
                loads[b2].0 += force;
                loads[b2].1 += r2.cross(&force);
                loads[b1].0 -= force;
                loads[b1].1 -= (r1 + gap).cross(&force);
            }
            JointKind::Fixed => {}
        }
    }
}

/// A joint's torque on body 2 (N·m; a slide's force, N) at its angle (rad; m) and rate
/// (rad/s; m/s): its law's, plus its residual's where one is attached and on (the core's
/// hybrid sum, [`hcm_core::joint::hybrid_torque`]).
fn joint_torque(joint: &Joint, angle: f64, rate: f64) -> f64 {
    match &joint.residual {
        Some(residual) => residual.torque(&joint.law, angle, rate),
        None => joint.law.torque(angle, rate),
    }
}

/// World-frame inverse inertia R·I⁻¹·Rᵀ (1/(kg·m²)) of a body of body-frame inverse
/// inertia `inverse` turned by `q`.
pub fn world_inverse_inertia(inverse: &Matrix3<f64>, q: &UnitQuaternion<f64>) -> Matrix3<f64> {
    let r = q.to_rotation_matrix();
    r.matrix() * inverse * r.matrix().transpose()
}

/// Joint `j`'s compliance (1/(kg·m²)): the relative angular acceleration about its axis
/// (rad/s²) that a unit torque pair — +1 N·m on body 2 about the axis, −1 N·m on body 1
/// — gives the bodies at `poses` (their velocities ignored) while every joint of `model`
/// holds them and nothing else acts: 1/I of the joint's turn, the inverse of the
/// effective inertia a torque on the joint meets (for two free links, between their
/// inertias about their own centres and about the joint). What a joint's residual
/// torque turns the joint by (`crate::train::joint_samples`).
pub(crate) fn joint_compliance(model: &Model, j: usize, poses: &[Pose]) -> f64 {
    let joint = &model.joints[j];
    let axis = poses[joint.bodies[0]].orientation * joint.axis.into_inner();
    let still: Vec<Pose> = (poses.iter())
        .map(|p| Pose {
            velocity: Vector3::zeros(),
            angular_velocity: Vector3::zeros(),
            ..*p
        })
        .collect();
    let turn = |torque: f64| {
        let mut loads = vec![(Vector3::zeros(), Vector3::zeros()); model.bodies.len()];
        loads[joint.bodies[1]].1 += axis * torque;
        loads[joint.bodies[0]].1 -= axis * torque;
        let inverse: Vec<(f64, Matrix3<f64>)> = (model.bodies.iter().zip(&still))
            .map(|(body, pose)| match body.fixed {
                true => (0.0, Matrix3::zeros()),
                false => {
                    let inverse = body.inertia.try_inverse().unwrap_or_else(Matrix3::zeros);
                    let world = world_inverse_inertia(&inverse, &pose.orientation);
                    (1.0 / body.mass, world)
                }
            })
            .collect();
        let motion: Vec<BodyMotion> = (still.iter().zip(&inverse).zip(&loads))
            .map(|((pose, inverse), load)| BodyMotion {
                pose: *pose,
                free: (load.0 * inverse.0, inverse.1 * load.1),
                inverse: *inverse,
            })
            .collect();
        add_constraint_loads(model, &motion, &mut loads);
        let spin = |b: usize| inverse[b].1 * loads[b].1;
        (spin(joint.bodies[1]) - spin(joint.bodies[0])).dot(&axis)
    };
    // Less the response without the torque: the stabilisation's pull on the rows'
    // error at these poses.
    turn(1.0) - turn(0.0)
}
