//! The fixed inputs: contact states, law and effect parameters, the ball's PM2 and
//! its residual blobs. Plausible values for a steel ball on concrete (the bouncing
//! ball of the paper's Section 5.1), in f32 as a controller holds them.

use hcm_core::effect::{
    Adhesion, AirDrag, ContactEffect, ContactMemory, HysteresisDamping, Plasticity,
    StiffnessExponent, ViscousDamping,
};
use hcm_core::friction::VelocityStepFriction;
use hcm_core::law::{
    AnyNormalLaw, Flores, Hertz, HuntCrossley, Impact, Indentation, LankaraniNikravesh, LawKind,
    VariableStiffness,
};
use nalgebra::Vector3;

/// The bouncing ball's exported residual, f32 weights (`hcm export`).
pub static BALL_F32_BLOB: &[u8] = include_bytes!("../../../examples/blobs/bouncing_ball.f32.hcm");
/// Its int8 twin.
pub static BALL_INT8_BLOB: &[u8] = include_bytes!("../../../examples/blobs/bouncing_ball.int8.hcm");

/// The ball's mass m (kg), scenarios/bouncing_ball.toml.
pub const BALL_MASS: f32 = 0.06693;
/// Gravity g (m/s²), scenarios/bouncing_ball.toml.
pub const GRAVITY: f32 = 9.81;
/// The gap (m) the ball is dropped from, scenarios/bouncing_ball.toml.
pub const DROP_GAP: f32 = 0.1;

/// A contact state: indentation δ (m), rate δ̇ (m/s), approach speed δ̇0 (m/s).
const fn state(depth: f32, rate: f32, approach_speed: f32) -> Indentation<f32> {
    Indentation {
        depth,
        rate,
        approach_speed,
    }
}

/// The states every normal law and extended law is evaluated at: loading, near the
/// deepest point, unloading, barely touching, apart (exactly 0 N) and deep.
pub const STATES: [Indentation<f32>; 6] = [
    state(10e-6, 1.4, 1.4),
    state(25e-6, 0.3, 1.4),
    state(15e-6, -0.9, 1.4),
    state(1e-9, 0.01, 0.5),
    state(-1e-6, 1.0, 1.4),
    state(2e-4, 2.0, 2.0),
];

/// What the contact remembers in every state above: δ_max = 30 µm, so that the
/// unloading states are below it (plasticity acts there).
pub const MEMORY: ContactMemory<f32> = ContactMemory { max_depth: 30e-6 };

/// The ball's PM2, Lankarani–Nikravesh, copied from examples/blobs/bouncing_ball.pm2.toml
/// (the firmware parses nothing at run time): k (N/m^n), n (-), c_e (-).
pub fn ball_pm2() -> LankaraniNikravesh<f32> {
    LankaraniNikravesh {
        stiffness: 6909559489.48986_f64 as f32,
        exponent: 1.4894618532836206_f64 as f32,
        restitution: 0.9289993736609472_f64 as f32,
    }
}

/// Law `kind` with steel-on-concrete parameters (k in N/m^n; the ball's radius and
/// mass; E* (Pa) of steel on concrete).
pub fn law(kind: LawKind) -> AnyNormalLaw<f32> {
    match kind {
        LawKind::Hertz => Hertz {
            stiffness: 6.9e9,
            exponent: 1.5,
        }
        .into(),
        LawKind::LankaraniNikravesh => ball_pm2().into(),
        LawKind::VariableStiffness => VariableStiffness {
            surface_loading: 2.0,
            effective_modulus: 2.402e10,
            radius: 0.0127,
            damping: 987.9,
            effective_mass: BALL_MASS,
        }
        .into(),
        LawKind::Impact => Impact {
            stiffness: 6.9e9,
            exponent: 1.5,
            max_damping: 1.0e4,
            full_damping_depth: 1.0e-5,
        }
        .into(),
        LawKind::HuntCrossley => HuntCrossley {
            stiffness: 6.9e9,
            exponent: 1.5,
            damping: 0.08,
        }
        .into(),
        LawKind::Flores => Flores {
            stiffness: 6.9e9,
            exponent: 1.5,
            restitution: 0.93,
        }
        .into(),
    }
}

/// Every catalogued contact effect, each added alone to the ball's PM2.
pub fn effects() -> [ContactEffect<f32>; 5] {
    [
        ViscousDamping { coefficient: 150.0 }.into(),
        HysteresisDamping {
            coefficient: 2.0e8,
            exponent: 1.5,
        }
        .into(),
        StiffnessExponent {
            exponent_change: 0.05,
            reference_depth: 1.0e-5,
        }
        .into(),
        Adhesion {
            pull_off_force: 0.5,
        }
        .into(),
        Plasticity {
            permanent_ratio: 0.2,
        }
        .into(),
    ]
}

/// Air drag (a body effect, not a contact term) and the velocities (m/s) it sees.
pub fn air_drag() -> (AirDrag<f32>, [Vector3<f32>; 2]) {
    let drag = AirDrag {
        coefficient: 2.5e-4,
    };
    (
        drag,
        [Vector3::new(0.0, 0.0, -1.4), Vector3::new(0.3, -0.2, 1.3)],
    )
}

/// STEP friction (Eq 10–11): μ_s, μ_d (-), v_s, v_d (m/s).
pub fn friction() -> VelocityStepFriction<f32> {
    VelocityStepFriction {
        static_coefficient: 0.6,
        dynamic_coefficient: 0.4,
        stiction_speed: 1.0e-3,
        dynamic_speed: 1.0e-2,
    }
}

/// Slip cases for friction and the wrench: relative velocity (m/s), unit normal,
/// normal force f_n (N), arms l1, l2 (m). Stiction, transition, sliding and no slip.
pub struct SlipCase {
    /// Velocity of body 1's contact point relative to body 2's (m/s).
    pub relative_velocity: Vector3<f32>,
    /// Unit normal from body 2 to body 1 (-).
    pub normal: Vector3<f32>,
    /// Normal force f_n (N).
    pub normal_force: f32,
    /// Arm from body 1's reference point to the contact (m).
    pub arm_1: Vector3<f32>,
    /// Arm from body 2's reference point to the contact (m).
    pub arm_2: Vector3<f32>,
}

/// The slip cases (see [`SlipCase`]).
pub fn slip_cases() -> [SlipCase; 4] {
    let normal = Vector3::new(0.0, 0.6, 0.8);
    let case = |v: Vector3<f32>, f: f32| SlipCase {
        relative_velocity: v,
        normal,
        normal_force: f,
        arm_1: Vector3::new(0.01, -0.0127, 0.002),
        arm_2: Vector3::new(-0.3, 0.2, 0.0),
    };
    [
        case(Vector3::new(4e-4, 0.0, 0.0), 12.5),
        case(Vector3::new(3e-3, 1e-3, -2e-3), 40.0),
        case(Vector3::new(-0.7, 0.25, 0.1), 250.0),
        case(Vector3::new(0.0, 0.3, 0.4), 5.0),
    ]
}
