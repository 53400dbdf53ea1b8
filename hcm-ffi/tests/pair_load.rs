//! `hcm_pair_load` — the contact model of one body pair through the C ABI — against
//! the core's `ContactModel::pair_load`, **bit for bit**, on the peg-in-hole's states
//! with its f32 and int8 blobs; and its answers to a caller's mistakes.
//!
//! The peg's HCM is built exactly as the firmware builds it: the module
//! `hcm-firmware/src/peg` is compiled into this test (as `tests/controller/firmware.rs` does), so
//! its states (`states.rs`: rows of the S1 data set), its PM2 (IMPACT + STEP friction),
//! its manifold geometry and its `peg_load` are the firmware's own.

#[allow(dead_code)] // the firmware's printing helpers are not used here
#[path = "../../hcm-firmware/src/peg/mod.rs"]
mod peg;

use hcm_core::model::{ContactModel, ContactPoint, Evaluated, PairLoad, Residual};
use hcm_core::residual::{decode, F32Weights, Int8Weights};
use hcm_core::rigid::RigidState;
use hcm_ffi::*;
use nalgebra::Vector3;
use peg::{PegResidual, PegWeights, PEG_STATES, STATE_NAMES};
use std::ptr::{null, null_mut};

/// The peg's HCM with `Q` weights, as the firmware's host test builds it.
struct PegFixture<Q: PegWeights> {
    /// PM2 + friction + the residual.
    hcm: ContactModel<f32, PegResidual<Q>>,
}

impl<Q: PegWeights> PegFixture<Q> {
    /// The model with the shipped blob of `Q`.
    fn decode() -> Result<Self, hcm_core::residual::BlobError> {
        Ok(PegFixture {
            hcm: peg::peg_hcm(peg::decode_network::<Q>()?),
        })
    }
}

/// The peg's PM2 as C writes it: IMPACT (k, e, d_max, δ_max) and STEP friction
/// (μ_s, μ_d, v_s, v_d), the firmware's f32 values.
fn peg_physics() -> HcmPairPhysics {
    let law = peg::peg_pm2();
    let friction = peg::peg_friction();
    HcmPairPhysics {
        normal: HcmExtendedLaw {
            base: HcmLaw {
                kind: HCM_LAW_IMPACT,
                parameters: [
                    law.stiffness,
                    law.exponent,
                    law.max_damping,
                    law.full_damping_depth,
                    0.0,
                ],
            },
            effect_count: 0,
            effects: [HcmEffect {
                kind: 0,
                parameters: [0.0; HCM_MAX_PARAMETERS],
            }; HCM_MAX_EFFECTS],
        },
        friction: HcmFriction {
            kind: HCM_FRICTION_STEP,
            parameters: [
                friction.static_coefficient,
                friction.dynamic_coefficient,
                friction.stiction_speed,
                friction.dynamic_speed,
                0.0,
            ],
        },
    }
}

/// A core contact point as C passes it.
fn c_point(point: &ContactPoint<f32>) -> HcmContactPoint {
    HcmContactPoint {
        contact: HcmContact {
            depth: point.indentation.depth,
            rate: point.indentation.rate,
            approach_speed: point.indentation.approach_speed,
            max_depth: point.memory.max_depth,
        },
        normal: point.normal.into(),
        position: point.position.into(),
        relative_velocity: point.relative_velocity.into(),
        relative_angular_velocity: point.relative_angular_velocity.into(),
    }
}

fn zeroed_residual() -> Box<HcmWrenchResidual> {
    Box::new(HcmWrenchResidual {
        storage: [0; HCM_WRENCH_RESIDUAL_SIZE],
    })
}

/// `Q`'s peg blob decoded through the C ABI.
fn decoded<Q: PegWeights>() -> Box<HcmWrenchResidual> {
    let mut residual = zeroed_residual();
    // SAFETY: a live blob and an exclusive, aligned `HcmWrenchResidual`.
    let status =
        unsafe { hcm_wrench_residual_decode(Q::BLOB.as_ptr(), Q::BLOB.len(), &mut *residual) };
    assert_eq!(status, HcmStatus::Ok, "{}", Q::NAME);
    residual
}

/// `hcm_pair_load` on `points`, its status and result (NaN-filled if not written).
fn c_pair_load(
    physics: &HcmPairPhysics,
    residual: &HcmWrenchResidual,
    points: &[HcmContactPoint],
    reference: &[f32; 3],
    input: &[f32; HCM_WRENCH_RESIDUAL_INPUTS],
) -> (HcmStatus, HcmPairLoad) {
    let mut out = HcmPairLoad {
        force: [f32::NAN; 3],
        torque: [f32::NAN; 3],
        normal_force: f32::NAN,
        points_used: u32::MAX,
        residual_used: false,
        outside_envelope: u32::MAX,
    };
    // SAFETY: every pointer is to a live, aligned value of the documented length.
    let status = unsafe {
        hcm_pair_load(
            physics,
            residual,
            points.as_ptr(),
            points.len(),
            reference.as_ptr(),
            input.as_ptr(),
            &mut out,
        )
    };
    (status, out)
}

/// The C result equals the core's `load`, every float bit for bit.
fn assert_same(c: &HcmPairLoad, core: &PairLoad<f32>, what: &str) {
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let w = &core.wrench;
    assert_eq!(bits(&c.force), bits(w.force_1.as_slice()), "{what}: force");
    assert_eq!(
        bits(&c.torque),
        bits(w.torque_1.as_slice()),
        "{what}: torque"
    );
    assert_eq!(
        c.normal_force.to_bits(),
        core.normal_force.to_bits(),
        "{what}: normal force"
    );
    assert_eq!(
        c.residual_used,
        core.evaluated == Evaluated::PhysicsAndResidual,
        "{what}: residual used"
    );
}

/// Every peg state through the C ABI against the firmware's `peg_load` (the core's
/// `pair_load`); (states with the residual on, states with ≥ 2 points).
fn check_peg_states<Q: PegWeights>() -> (usize, usize) {
    let fixture = PegFixture::<Q>::decode().unwrap();
    let residual = decoded::<Q>();
    let physics = peg_physics();
    let (mut used, mut several) = (0, 0);
    for (components, name) in PEG_STATES.iter().zip(STATE_NAMES) {
        let state = RigidState {
            components: *components,
        };
        let manifold = peg::manifold(&state);
        let points: Vec<HcmContactPoint> = manifold.iter().map(c_point).collect();
        let reference: [f32; 3] = state.position().into();
        let (status, c) = c_pair_load(&physics, &residual, &points, &reference, components);
        assert_eq!(status, HcmStatus::Ok, "{name}");
        let what = format!("{} {name}", Q::NAME);
        assert_same(&c, &peg::peg_load(&fixture.hcm, &state), &what);
        assert_eq!(c.points_used as usize, manifold.len(), "{what}");
        let inside = fixture.hcm.residual.excursion(components).is_none();
        assert_eq!(c.outside_envelope == 0, inside, "{what}");
        used += usize::from(c.residual_used);
        several += usize::from(manifold.len() >= 2);
        if c.residual_used {
            // The residual's wrench is in the result: without it, it differs.
            let physics_only = ContactModel::physics(fixture.hcm.normal.clone())
                .with_friction(fixture.hcm.friction.unwrap());
            let plain =
                physics_only.pair_load(&manifold, &reference.into(), &Vector3::zeros(), &[]);
            assert_ne!(c.force, <[f32; 3]>::from(plain.wrench.force_1), "{what}");
        }
    }
    (used, several)
}

#[test]
fn peg_states_match_pair_load_bit_for_bit_f32_and_int8() {
    for (used, several) in [
        check_peg_states::<F32Weights>(),
        check_peg_states::<Int8Weights>(),
    ] {
        // Four wall states run the residual; flight (no point) and the fast state
        // (outside the envelope) do not.
        assert_eq!(used, 4);
        assert!(several >= 1, "some state touches at two points or more");
    }
}

fn check_eight_points<Q: PegWeights>() {
    let fixture = PegFixture::<Q>::decode().unwrap();
    let residual = decoded::<Q>();
    let state = RigidState {
        components: PEG_STATES[1],
    };
    let mut points = peg::eight_points(&state);
    assert_eq!(points.len(), HCM_MAX_POINTS, "the state touches the block");
    // One point apart (δ < 0), one with a NaN depth: the core's rules, through C.
    points[6].indentation.depth = -1e-6;
    let reference = state.position();
    for nan_depth in [false, true] {
        if nan_depth {
            points[7].indentation.depth = f32::NAN;
        }
        let c_points: Vec<HcmContactPoint> = points.iter().map(c_point).collect();
        let (status, c) = c_pair_load(
            &peg_physics(),
            &residual,
            &c_points,
            &reference.into(),
            &state.components,
        );
        assert_eq!(status, HcmStatus::Ok);
        let core = fixture
            .hcm
            .pair_load(&points, &reference, &Vector3::zeros(), &state.components);
        assert_same(&c, &core, Q::NAME);
        assert_eq!(c.points_used, 7, "δ < 0 does not count, NaN does");
        assert!(c.residual_used);
        assert_eq!(c.force[0].is_nan(), nan_depth);
    }
}

#[test]
fn eight_points_match_pair_load_bit_for_bit() {
    check_eight_points::<F32Weights>();
    check_eight_points::<Int8Weights>();
}

#[test]
fn non_finite_residual_inputs_switch_the_residual_off_as_in_the_core() {
    let fixture = PegFixture::<F32Weights>::decode().unwrap();
    let residual = decoded::<F32Weights>();
    let state = RigidState {
        components: PEG_STATES[1],
    };
    let manifold = peg::manifold(&state);
    let points: Vec<HcmContactPoint> = manifold.iter().map(c_point).collect();
    for (at, value) in [(9, f32::NAN), (0, f32::INFINITY), (12, f32::NEG_INFINITY)] {
        let mut input = state.components;
        input[at] = value;
        let reference = state.position();
        let (status, c) = c_pair_load(
            &peg_physics(),
            &residual,
            &points,
            &reference.into(),
            &input,
        );
        assert_eq!(status, HcmStatus::Ok);
        let core = fixture
            .hcm
            .pair_load(&manifold, &reference, &Vector3::zeros(), &input);
        assert_same(&c, &core, "non-finite input");
        assert!(!c.residual_used);
        assert_eq!(c.outside_envelope, 1 << at, "input {at}");
    }
}

#[test]
fn the_info_is_the_blobs() {
    let residual = decoded::<Int8Weights>();
    let mlp: PegResidual<Int8Weights> = decode(Int8Weights::BLOB).unwrap();
    let mut info = std::mem::MaybeUninit::<HcmWrenchResidualInfo>::uninit();
    // SAFETY: live, aligned values.
    let info = unsafe {
        assert_eq!(
            hcm_wrench_residual_info(&*residual, info.as_mut_ptr()),
            HcmStatus::Ok
        );
        info.assume_init()
    };
    assert_eq!(
        (
            info.quantisation,
            info.inputs,
            info.width,
            info.hidden_layers,
            info.outputs
        ),
        (1, 13, 32, 2, 6)
    );
    assert_eq!(info.envelope_min, mlp.envelope.min);
    assert_eq!(info.envelope_max, mlp.envelope.max);
}

#[test]
fn mistakes_are_answered_with_their_code() {
    let residual = decoded::<F32Weights>();
    let physics = peg_physics();
    let state = RigidState {
        components: PEG_STATES[1],
    };
    let points: Vec<HcmContactPoint> = peg::eight_points(&state).iter().map(c_point).collect();
    let reference: [f32; 3] = state.position().into();
    let input = state.components;
    let (p, r, x) = (points.as_ptr(), reference.as_ptr(), input.as_ptr());
    let mut out = std::mem::MaybeUninit::<HcmPairLoad>::zeroed();
    let o = out.as_mut_ptr();
    let nine = [points[0]; HCM_MAX_POINTS + 1];
    let zeroed = zeroed_residual();
    // SAFETY: every non-null pointer is to a live, aligned value of the documented
    // length; null, misaligned and too long are refused before any access.
    let statuses = unsafe {
        let odd = |pointer: *const f32| pointer.cast::<u8>().wrapping_add(1).cast::<f32>();
        [
            hcm_pair_load(null(), &*residual, p, 8, r, x, o),
            hcm_pair_load(&physics, null(), p, 8, r, x, o),
            hcm_pair_load(&physics, &*residual, null(), 8, r, x, o),
            hcm_pair_load(&physics, &*residual, p, 8, null(), x, o),
            hcm_pair_load(&physics, &*residual, p, 8, r, null(), o),
            hcm_pair_load(&physics, &*residual, p, 8, r, x, null_mut()),
            hcm_pair_load(&physics, &*residual, nine.as_ptr(), 9, r, x, o),
            hcm_pair_load(&physics, &*residual, p, usize::MAX, r, x, o),
            hcm_pair_load(&physics, &*zeroed, p, 8, r, x, o),
            hcm_pair_load(&physics, &*residual, p, 8, odd(r), x, o),
            hcm_pair_load(&physics, &*residual, p, 8, r, odd(x), o),
            hcm_wrench_residual_info(&*zeroed, &mut std::mem::zeroed()),
        ]
    };
    use HcmStatus::{BadParameter, Misaligned, NotDecoded, NullPointer};
    let expected = [
        NullPointer,
        NullPointer,
        NullPointer,
        NullPointer,
        NullPointer,
        NullPointer,
        BadParameter,
        BadParameter,
        NotDecoded,
        Misaligned,
        Misaligned,
        NotDecoded,
    ];
    for (i, (status, expected)) in statuses.into_iter().zip(expected).enumerate() {
        assert_eq!(status, expected, "call {i}");
    }
    // SAFETY: `out` was zeroed, and every call above failed before writing it.
    let out = unsafe { out.assume_init() };
    assert_eq!(out.points_used, 0, "nothing written");
}

#[test]
fn an_unknown_friction_is_refused_and_no_points_give_no_load() {
    let residual = decoded::<F32Weights>();
    let physics = peg_physics();
    let state = RigidState {
        components: PEG_STATES[1],
    };
    let points: Vec<HcmContactPoint> = peg::manifold(&state).iter().map(c_point).collect();
    let reference: [f32; 3] = state.position().into();
    let input = state.components;
    let unknown = HcmPairPhysics {
        friction: HcmFriction {
            kind: 7,
            ..physics.friction
        },
        ..physics
    };
    let (status, _) = c_pair_load(&unknown, &residual, &points, &reference, &input);
    assert_eq!(status, HcmStatus::BadParameter);
    // No points at all: zero loads, physics only.
    let (status, empty) = c_pair_load(&physics, &residual, &[], &reference, &input);
    assert_eq!(status, HcmStatus::Ok);
    assert_eq!(
        (empty.force, empty.torque, empty.points_used),
        ([0.0; 3], [0.0; 3], 0)
    );
    assert!(!empty.residual_used);
}

#[test]
fn a_blob_of_the_other_shape_or_storage_is_not_a_wrench_residual() {
    let ball = std::fs::read(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/blobs/bouncing_ball.f32.hcm"
    ))
    .unwrap();
    let mut wrench = decoded::<F32Weights>();
    // SAFETY: live blobs and exclusive, aligned outputs.
    unsafe {
        let status = hcm_wrench_residual_decode(ball.as_ptr(), ball.len(), &mut *wrench);
        assert_eq!(status, HcmStatus::BlobWrongShape);
        // The failed decode marked the storage: it answers "not decoded".
        let mut info = std::mem::zeroed();
        assert_eq!(
            hcm_wrench_residual_info(&*wrench, &mut info),
            HcmStatus::NotDecoded
        );
        let peg = F32Weights::BLOB;
        let mut small = Box::new(HcmResidual {
            storage: [0; HCM_RESIDUAL_SIZE],
        });
        let status = hcm_residual_decode(peg.as_ptr(), peg.len(), &mut *small);
        assert_eq!(status, HcmStatus::BlobWrongShape);
        // A decoded 1D residual's bytes copied into wrench storage are not taken for a
        // wrench network: each storage has its own marker.
        let status = hcm_residual_decode(ball.as_ptr(), ball.len(), &mut *small);
        assert_eq!(status, HcmStatus::Ok);
        wrench.storage[..HCM_RESIDUAL_SIZE].copy_from_slice(&small.storage);
        let mut info = std::mem::zeroed();
        assert_eq!(
            hcm_wrench_residual_info(&*wrench, &mut info),
            HcmStatus::NotDecoded
        );
        let status = hcm_wrench_residual_decode(peg.as_ptr(), peg.len() - 1, &mut *wrench);
        assert_eq!(status, HcmStatus::BlobTruncated);
    }
}

#[test]
fn physics_is_validated_with_friction() {
    let physics = peg_physics();
    let mut negative = physics;
    negative.friction.parameters[0] = -0.1;
    let mut unknown = physics;
    unknown.friction.kind = 2;
    let mut none = physics;
    none.friction.kind = HCM_FRICTION_NONE;
    // SAFETY: live, aligned values.
    unsafe {
        assert_eq!(hcm_pair_physics_validate(&physics), HcmStatus::Ok);
        assert_eq!(hcm_pair_physics_validate(&none), HcmStatus::Ok);
        assert_eq!(hcm_pair_physics_validate(&negative), HcmStatus::OutOfDomain);
        assert_eq!(hcm_pair_physics_validate(&unknown), HcmStatus::BadParameter);
        assert_eq!(hcm_pair_physics_validate(null()), HcmStatus::NullPointer);
    }
}

/// The C structs hold what the core's do: a point converts back to itself.
#[test]
fn a_point_round_trips() {
    let state = RigidState {
        components: PEG_STATES[2],
    };
    for point in peg::manifold(&state) {
        assert_eq!(c_point(&point).to_core(), point);
    }
}

/// The firmware's residual wrench is the one C applies (same model, same input).
#[test]
fn the_residual_is_the_firmwares() {
    let fixture = PegFixture::<F32Weights>::decode().unwrap();
    let mlp: PegResidual<F32Weights> = decode(F32Weights::BLOB).unwrap();
    assert_eq!(fixture.hcm.residual, mlp);
    assert!(fixture.hcm.residual.correction(&PEG_STATES[1]).is_some());
}
