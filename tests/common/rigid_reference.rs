//! An independent reference solver for a rigid box falling on the fixed plane z = 0, to
//! check hcm's 3D simulator against (`scenarios/cube_drop.toml`).
//!
//! Independent on purpose: it uses only nalgebra and std — none of `hcm_core`'s laws,
//! geometry, rigid bodies or integrator — and a different formulation from the core's.
//! The core integrates a unit quaternion with the body-frame angular velocity ω by
//! adaptive Dormand–Prince 5(4); here the state is the position x, velocity v, the
//! rotation matrix R (body → world) and the world-frame angular momentum L, with
//! ω = R·I⁻¹·Rᵀ·L, advanced by fixed-step classical Runge–Kutta 4 and R projected back
//! onto the rotations after every step.
//!
//! Contacts: every vertex of the box below the plane, indentation δ = −z of the vertex,
//! indentation rate δ̇ = −ż of the vertex (v + ω × r), the force acting at the vertex.
//! Normal force by the IMPACT law (Eq 8–9), friction by the velocity-based STEP law
//! (Eq 10–11) on the tangential slip of the vertex.

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

/// The IMPACT normal law (MSC ADAMS, Eq 8–9):
/// f_n = max(0, k·δ^e + step(δ, 0, 0, d, c_max)·δ̇).
#[derive(Clone, Copy, Debug)]
pub struct Impact {
    /// Stiffness k (N/m^e).
    pub stiffness: f64,
    /// Force exponent e (–).
    pub exponent: f64,
    /// Damping coefficient c_max reached at full depth (N·s/m).
    pub max_damping: f64,
    /// Indentation d at which the damping reaches c_max (m).
    pub full_damping_depth: f64,
}

/// The velocity-based STEP friction law (Eq 10–11).
#[derive(Clone, Copy, Debug)]
pub struct StepFriction {
    /// Static friction coefficient μ_s (–).
    pub mu_static: f64,
    /// Slip speed v_s at which μ_s is reached (m/s).
    pub v_static: f64,
    /// Dynamic friction coefficient μ_d (–).
    pub mu_dynamic: f64,
    /// Slip speed v_d from which μ_d holds (m/s).
    pub v_dynamic: f64,
}

/// One box falling on the plane z = 0: body, initial state, contact laws and run length.
#[derive(Clone, Copy, Debug)]
pub struct Case {
    /// Half extents of the box along its body axes (m).
    pub half_extents: Vector3<f64>,
    /// Mass m (kg).
    pub mass: f64,
    /// Inertia tensor about the centre of mass, body frame (kg·m²).
    pub inertia: Matrix3<f64>,
    /// Initial position of the centre of mass, world frame (m).
    pub position: Vector3<f64>,
    /// Initial orientation, body → world (–).
    pub rotation: Matrix3<f64>,
    /// Initial velocity of the centre of mass, world frame (m/s).
    pub velocity: Vector3<f64>,
    /// Initial angular velocity, world frame (rad/s).
    pub angular_velocity: Vector3<f64>,
    /// Normal law at each touching vertex.
    pub impact: Impact,
    /// Friction law at each touching vertex.
    pub friction: StepFriction,
    /// Gravitational acceleration, world frame (m/s²).
    pub gravity: Vector3<f64>,
    /// Length of the run (s).
    pub end_time: f64,
    /// Time between recorded samples (s); a whole number of solver steps.
    pub sample_period: f64,
}

/// The shipped cube drop (`scenarios/cube_drop.toml`): a 0.1 m cube of 0.37 kg dropped
/// tilted and spinning onto the plane, simulated for 0.4 s and sampled every 1 ms.
pub fn cube_drop() -> Case {
    let (mass, side) = (0.37, 0.1);
    let rotation = Rotation3::from_axis_angle(&Vector3::z_axis(), 0.1)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), -0.26)
        * Rotation3::from_axis_angle(&Vector3::x_axis(), 0.35);
    Case {
        half_extents: Vector3::repeat(side / 2.0),
        mass,
        inertia: Matrix3::identity() * (mass * side * side / 6.0),
        position: Vector3::new(0.0, 0.0, 0.15),
        rotation: rotation.into_inner(),
        velocity: Vector3::new(0.5, 0.0, -1.0),
        angular_velocity: Vector3::new(2.0, -3.0, 1.0),
        impact: Impact {
            stiffness: 1e7,
            exponent: 1.5,
            max_damping: 50.0,
            full_damping_depth: 1e-4,
        },
        friction: StepFriction {
            mu_static: 0.3,
            v_static: 1e-3,
            mu_dynamic: 0.2,
            v_dynamic: 1e-2,
        },
        gravity: Vector3::new(0.0, 0.0, -9.81),
        end_time: 0.4,
        sample_period: 1e-3,
    }
}

/// Another body and parameter set, as an unseen check will bring: a flat box
/// with a full (non-diagonal) inertia tensor, thrown harder onto softer, more damped and
/// more frictional contact.
pub fn tossed_plate() -> Case {
    let mut case = cube_drop();
    let mass = 0.8;
    let principal = Matrix3::from_diagonal(&Vector3::new(8e-4, 2e-3, 2.6e-3));
    let axes = Rotation3::from_euler_angles(0.3, -0.2, 0.7);
    case.half_extents = Vector3::new(0.08, 0.05, 0.02);
    case.mass = mass;
    case.inertia = axes.matrix() * principal * axes.matrix().transpose();
    case.rotation = Rotation3::from_euler_angles(-0.6, 0.4, 1.1).into_inner();
    case.position = Vector3::new(0.1, -0.05, 0.2);
    case.velocity = Vector3::new(-0.8, 1.2, -0.5);
    case.angular_velocity = Vector3::new(-4.0, 6.0, 9.0);
    case.impact.stiffness = 3e6;
    case.impact.max_damping = 300.0;
    case.friction.mu_static = 0.5;
    case.friction.mu_dynamic = 0.4;
    case
}

/// The recorded state of the box at one instant.
#[derive(Clone, Copy, Debug)]
pub struct Sample {
    /// Time (s).
    pub time: f64,
    /// Position of the centre of mass, world frame (m).
    pub position: Vector3<f64>,
    /// Orientation, body → world (–).
    pub rotation: Matrix3<f64>,
    /// Velocity of the centre of mass, world frame (m/s).
    pub velocity: Vector3<f64>,
    /// Angular velocity, world frame (rad/s).
    pub angular_velocity: Vector3<f64>,
    /// Contact force on the box (N) and torque about its centre (N·m), world frame,
    /// summed over the vertices below the plane: what a sensor in the box reads.
    pub wrench: (Vector3<f64>, Vector3<f64>),
}

impl Sample {
    /// The orientation as a unit quaternion (body → world).
    pub fn quaternion(&self) -> UnitQuaternion<f64> {
        UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(self.rotation))
    }
}

/// A run of the reference solver.
#[derive(Clone, Debug)]
pub struct Trajectory {
    /// Samples every `sample_period`, from t = 0 to `end_time` inclusive.
    pub samples: Vec<Sample>,
    /// End of the first step after which a vertex is below the plane (s); the true
    /// touch-down lies within one step before it. `None` if the box never touches.
    pub touch_down: Option<f64>,
    /// Number of RK4 steps taken (–).
    pub steps: usize,
}

/// The cubic STEP of Eq 9: h0 below x0, h1 above x1, h0 + (h1 − h0)·Δ²·(3 − 2Δ) between,
/// Δ = (x − x0)/(x1 − x0).
pub fn step(x: f64, x0: f64, h0: f64, x1: f64, h1: f64) -> f64 {
    let delta = ((x - x0) / (x1 - x0)).clamp(0.0, 1.0);
    h0 + (h1 - h0) * delta * delta * (3.0 - 2.0 * delta)
}

impl Impact {
    /// Normal force f_n (N) at indentation δ (m, > 0 in contact) and indentation rate
    /// δ̇ (m/s, > 0 approaching), Eq 8.
    pub fn normal_force(&self, indentation: f64, indentation_rate: f64) -> f64 {
        if indentation <= 0.0 {
            return 0.0;
        }
        let damping = step(
            indentation,
            0.0,
            0.0,
            self.full_damping_depth,
            self.max_damping,
        );
        (self.stiffness * indentation.powf(self.exponent) + damping * indentation_rate).max(0.0)
    }

    /// Elastic energy k·δ^(e+1)/(e+1) stored at indentation δ (m), in J: the potential of
    /// the spring term, so that the total energy can only decrease.
    pub fn elastic_energy(&self, indentation: f64) -> f64 {
        if indentation <= 0.0 {
            return 0.0;
        }
        self.stiffness * indentation.powf(self.exponent + 1.0) / (self.exponent + 1.0)
    }
}

impl StepFriction {
    /// Friction coefficient μ(v) (–) at slip speed v (m/s), Eq 11.
    pub fn coefficient(&self, slip_speed: f64) -> f64 {
        if slip_speed < self.v_static {
            step(slip_speed, 0.0, 0.0, self.v_static, self.mu_static)
        } else if slip_speed <= self.v_dynamic {
            let (v_s, v_d) = (self.v_static, self.v_dynamic);
            step(slip_speed, v_s, self.mu_static, v_d, self.mu_dynamic)
        } else {
            self.mu_dynamic
        }
    }

    /// Friction force (N) for the tangential slip velocity `slip` (m/s) under the normal
    /// force f_n (N), Eq 10: −μ(|v|)·f_n·v/|v|, zero without slip.
    pub fn force(&self, slip: &Vector3<f64>, normal_force: f64) -> Vector3<f64> {
        let speed = slip.norm();
        if speed == 0.0 {
            return Vector3::zeros();
        }
        slip * (-self.coefficient(speed) * normal_force / speed)
    }
}

/// The eight vertices of the box in the world frame (m) for a pose (x, R).
pub fn vertices(
    half_extents: &Vector3<f64>,
    position: &Vector3<f64>,
    rotation: &Matrix3<f64>,
) -> [Vector3<f64>; 8] {
    core::array::from_fn(|i| {
        let sign = |bit: usize| if i & (1 << bit) == 0 { -1.0 } else { 1.0 };
        let corner = Vector3::new(sign(0), sign(1), sign(2)).component_mul(half_extents);
        position + rotation * corner
    })
}

/// Total energy (J) of a sample: kinetic (½·m·v² + ½·ω·L), gravitational (−m·g·x) and the
/// elastic energy stored at the vertices below the plane. The contact is dissipative, so
/// this can only decrease along an exact solution.
pub fn energy(case: &Case, sample: &Sample) -> f64 {
    let momentum = angular_momentum(case, &sample.rotation, &sample.angular_velocity);
    let kinetic = 0.5 * case.mass * sample.velocity.norm_squared()
        + 0.5 * sample.angular_velocity.dot(&momentum);
    let gravitational = -case.mass * case.gravity.dot(&sample.position);
    let elastic: f64 = vertices(&case.half_extents, &sample.position, &sample.rotation)
        .iter()
        .map(|vertex| case.impact.elastic_energy(-vertex.z))
        .sum();
    kinetic + gravitational + elastic
}

/// World-frame angular momentum L = R·I·Rᵀ·ω (kg·m²/s).
pub fn angular_momentum(
    case: &Case,
    rotation: &Matrix3<f64>,
    angular_velocity: &Vector3<f64>,
) -> Vector3<f64> {
    rotation * case.inertia * rotation.transpose() * angular_velocity
}

/// The integrated state, and (as a rate) its time derivative: ẋ = v, v̇ = F/m + g,
/// Ṙ = [ω]×·R, L̇ = T.
#[derive(Clone, Copy)]
struct State {
    position: Vector3<f64>,
    velocity: Vector3<f64>,
    rotation: Matrix3<f64>,
    momentum: Vector3<f64>,
}

impl State {
    /// `self + h·rate`.
    fn advanced(&self, rate: &State, h: f64) -> State {
        State {
            position: self.position + rate.position * h,
            velocity: self.velocity + rate.velocity * h,
            rotation: self.rotation + rate.rotation * h,
            momentum: self.momentum + rate.momentum * h,
        }
    }
}

/// The solver: the case with its inverse inertia precomputed.
struct Solver<'a> {
    case: &'a Case,
    inverse_inertia: Matrix3<f64>,
}

impl Solver<'_> {
    /// ω = R·I⁻¹·Rᵀ·L (rad/s, world frame).
    fn angular_velocity(&self, state: &State) -> Vector3<f64> {
        state.rotation * self.inverse_inertia * state.rotation.transpose() * state.momentum
    }

    /// Contact force (N) and torque about the centre of mass (N·m), world frame, summed
    /// over the vertices below the plane.
    fn contact_wrench(&self, state: &State, omega: &Vector3<f64>) -> (Vector3<f64>, Vector3<f64>) {
        let case = self.case;
        let (mut force, mut torque) = (Vector3::zeros(), Vector3::zeros());
        for vertex in vertices(&case.half_extents, &state.position, &state.rotation) {
            let indentation = -vertex.z;
            if indentation <= 0.0 {
                continue;
            }
            let arm = vertex - state.position;
            let vertex_velocity = state.velocity + omega.cross(&arm);
            let normal = case.impact.normal_force(indentation, -vertex_velocity.z);
            let slip = Vector3::new(vertex_velocity.x, vertex_velocity.y, 0.0);
            let at_vertex = case.friction.force(&slip, normal) + Vector3::z() * normal;
            force += at_vertex;
            torque += arm.cross(&at_vertex);
        }
        (force, torque)
    }

    /// The time derivative of the state under gravity and the contacts.
    fn rate(&self, state: &State) -> State {
        let omega = self.angular_velocity(state);
        let (force, torque) = self.contact_wrench(state, &omega);
        State {
            position: state.velocity,
            velocity: force / self.case.mass + self.case.gravity,
            rotation: omega.cross_matrix() * state.rotation,
            momentum: torque,
        }
    }

    /// One classical RK4 step of length h (s), R projected back onto the rotations.
    fn step(&self, state: &State, h: f64) -> State {
        let k1 = self.rate(state);
        let k2 = self.rate(&state.advanced(&k1, h / 2.0));
        let k3 = self.rate(&state.advanced(&k2, h / 2.0));
        let k4 = self.rate(&state.advanced(&k3, h));
        let mut next = *state;
        for (k, weight) in [(k1, 1.0), (k2, 2.0), (k3, 2.0), (k4, 1.0)] {
            next = next.advanced(&k, h * weight / 6.0);
        }
        next.rotation = orthonormalised(&next.rotation);
        next
    }

    fn sample(&self, time: f64, state: &State) -> Sample {
        let omega = self.angular_velocity(state);
        Sample {
            time,
            position: state.position,
            rotation: state.rotation,
            velocity: state.velocity,
            angular_velocity: omega,
            wrench: self.contact_wrench(state, &omega),
        }
    }
}

/// The nearest rotation to a nearly orthogonal matrix (its polar factor), by the Newton–
/// Schulz iteration R ← ½·R·(3·1 − RᵀR): symmetric in the columns, unlike Gram–Schmidt,
/// and quadratically convergent, so two rounds reach rounding from an RK4 step's drift.
fn orthonormalised(rotation: &Matrix3<f64>) -> Matrix3<f64> {
    let mut r = *rotation;
    for _ in 0..2 {
        r = r * (Matrix3::identity() * 3.0 - r.transpose() * r) * 0.5;
    }
    r
}

/// Simulates `case` with fixed RK4 steps of `step` seconds; `case.sample_period` must be
/// a whole number of steps.
pub fn simulate(case: &Case, step: f64) -> Trajectory {
    let per_sample = (case.sample_period / step).round() as usize;
    assert!(
        per_sample >= 1 && (per_sample as f64 * step - case.sample_period).abs() < 1e-9 * step,
        "the sample period {} s is not a whole number of steps of {step} s",
        case.sample_period
    );
    let sample_count = (case.end_time / case.sample_period).round() as usize;
    let solver = Solver {
        case,
        inverse_inertia: case.inertia.try_inverse().expect("an invertible inertia"),
    };
    let mut state = State {
        position: case.position,
        velocity: case.velocity,
        rotation: case.rotation,
        momentum: angular_momentum(case, &case.rotation, &case.angular_velocity),
    };
    let mut samples = vec![solver.sample(0.0, &state)];
    let (mut steps, mut touch_down) = (0, None);
    for k in 1..=sample_count {
        for _ in 0..per_sample {
            state = solver.step(&state, step);
            steps += 1;
            let touching = vertices(&case.half_extents, &state.position, &state.rotation)
                .iter()
                .any(|vertex| vertex.z < 0.0);
            if touching && touch_down.is_none() {
                touch_down = Some(steps as f64 * step);
            }
        }
        samples.push(solver.sample(k as f64 * case.sample_period, &state));
    }
    Trajectory {
        samples,
        touch_down,
        steps,
    }
}

/// Times (s) closer than this to a reference sample use that sample as it is.
const SAME_TIME: f64 = 1e-9;

/// The largest position error (m) and orientation error (rad) of a trajectory, given at
/// `times` (s) as centre positions (m, world frame) and body → world unit quaternions
/// in the CSV's column order `[qw, qx, qy, qz]` (either sign; normalised here), against
/// the `reference` samples.
///
/// A time on the reference's sample grid (within 1 ns) is compared with that sample.
/// Between samples the reference is interpolated: the position by the cubic Hermite
/// curve through both samples' positions and velocities, the orientation along the
/// geodesic between them. Panics on a time outside the reference's span or on slices of
/// unequal lengths.
pub fn compare(
    reference: &[Sample],
    times: &[f64],
    positions: &[[f64; 3]],
    quaternions: &[[f64; 4]],
) -> (f64, f64) {
    assert!(
        times.len() == positions.len() && times.len() == quaternions.len(),
        "times, positions and quaternions differ in length: {}, {}, {}",
        times.len(),
        positions.len(),
        quaternions.len()
    );
    let (mut position_error, mut angle_error) = (0.0_f64, 0.0_f64);
    for ((&time, position), &[w, x, y, z]) in times.iter().zip(positions).zip(quaternions) {
        let (reference_position, reference_orientation) = interpolated(reference, time);
        position_error = position_error.max((Vector3::from(*position) - reference_position).norm());
        let orientation = nalgebra::Quaternion::new(w, x, y, z);
        let difference = reference_orientation.conjugate() * orientation;
        let angle = 2.0 * difference.vector().norm().atan2(difference.w.abs());
        angle_error = angle_error.max(angle);
    }
    (position_error, angle_error)
}

/// The reference position (m) and orientation at `time` (s); see [`compare`].
fn interpolated(reference: &[Sample], time: f64) -> (Vector3<f64>, nalgebra::Quaternion<f64>) {
    let after = reference.partition_point(|sample| sample.time < time - SAME_TIME);
    assert!(
        after < reference.len() && (after > 0 || reference[0].time - time <= SAME_TIME),
        "time {time} s lies outside the reference's span"
    );
    let b = &reference[after];
    if (b.time - time).abs() <= SAME_TIME {
        return (b.position, b.quaternion().into_inner());
    }
    let a = &reference[after - 1];
    let span = b.time - a.time;
    let s = (time - a.time) / span;
    let (s2, s3) = (s * s, s * s * s);
    let position = a.position * (2.0 * s3 - 3.0 * s2 + 1.0)
        + a.velocity * (span * (s3 - 2.0 * s2 + s))
        + b.position * (3.0 * s2 - 2.0 * s3)
        + b.velocity * (span * (s3 - s2));
    let (qa, qb) = (a.quaternion(), b.quaternion());
    let between = (qa.inverse() * qb).scaled_axis();
    let orientation = qa * UnitQuaternion::from_scaled_axis(between * s);
    (position, orientation.into_inner())
}
