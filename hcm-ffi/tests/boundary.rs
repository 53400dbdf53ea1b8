//! The C API's answers to a caller's mistakes — null and misaligned pointers, unknown
//! kinds, parameters out of their domain, a residual never decoded, an impossible
//! length — and, for correct calls, the core's own results bit for bit.

use hcm_core::effect::{Adhesion, ExtendedLaw, ViscousDamping};
use hcm_core::law::{AnyNormalLaw, LankaraniNikravesh, NormalLaw};
use hcm_core::model::{ContactModel, Evaluated};
use hcm_core::residual::{decode, F32Weights, Mlp};
use hcm_ffi::*;
use std::ptr::{null, null_mut};

const LN: HcmLaw = HcmLaw {
    kind: HCM_LAW_LANKARANI_NIKRAVESH,
    parameters: [6.9e9, 1.49, 0.929, 0.0, 0.0],
};
const NO_EFFECT: HcmEffect = HcmEffect {
    kind: HCM_EFFECT_VISCOUS_DAMPING,
    parameters: [0.0; HCM_MAX_PARAMETERS],
};
const CONTACT: HcmContact = HcmContact {
    depth: 2e-5,
    rate: 0.5,
    approach_speed: 1.2,
    max_depth: 2e-5,
};

fn extended(effects: &[HcmEffect]) -> HcmExtendedLaw {
    let mut law = HcmExtendedLaw {
        base: LN,
        effect_count: effects.len() as u32,
        effects: [NO_EFFECT; HCM_MAX_EFFECTS],
    };
    law.effects[..effects.len()].copy_from_slice(effects);
    law
}

fn ball_blob() -> Vec<u8> {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../examples/blobs/bouncing_ball.f32.hcm"
    );
    std::fs::read(path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

fn decoded(blob: &[u8]) -> Box<HcmResidual> {
    let mut residual = Box::new(HcmResidual {
        storage: [0; HCM_RESIDUAL_SIZE],
    });
    // SAFETY: a live blob and an exclusive, aligned `HcmResidual`.
    let status = unsafe { hcm_residual_decode(blob.as_ptr(), blob.len(), &mut *residual) };
    assert_eq!(status, HcmStatus::Ok);
    residual
}

/// A pointer one byte past `value`: non-null, misaligned for any `T` aligned > 1.
fn misaligned<T>(value: &mut T) -> *mut T {
    (value as *mut T).cast::<u8>().wrapping_add(1).cast()
}

#[test]
fn null_pointers_are_answered_with_their_code() {
    let blob = ball_blob();
    let residual = decoded(&blob);
    let law = extended(&[]);
    let mut force = 0.0_f32;
    let mut hybrid = HcmHybridForce {
        force: 0.0,
        physics: 0.0,
        residual_used: false,
        outside_envelope: 0,
    };
    let mut out = HcmResidual {
        storage: [0; HCM_RESIDUAL_SIZE],
    };
    // SAFETY: every non-null pointer is to a live, aligned value; null is what the
    // functions are documented to refuse.
    let statuses = unsafe {
        [
            hcm_residual_decode(null(), blob.len(), &mut out),
            hcm_residual_decode(blob.as_ptr(), blob.len(), null_mut()),
            hcm_residual_info(null(), &mut std::mem::zeroed()),
            hcm_residual_info(&*residual, null_mut()),
            hcm_law_force(null(), CONTACT, &mut force),
            hcm_law_force(&LN, CONTACT, null_mut()),
            hcm_extended_law_force(null(), CONTACT, &mut force),
            hcm_extended_law_force(&law, CONTACT, null_mut()),
            hcm_law_validate(null()),
            hcm_extended_law_validate(null()),
            hcm_hybrid_force(null(), &*residual, CONTACT, &mut hybrid),
            hcm_hybrid_force(&law, null(), CONTACT, &mut hybrid),
            hcm_hybrid_force(&law, &*residual, CONTACT, null_mut()),
        ]
    };
    for (i, status) in statuses.into_iter().enumerate() {
        assert_eq!(status, HcmStatus::NullPointer, "call {i}");
    }
    assert_eq!(force, 0.0, "nothing written on an error");
    assert_eq!(hybrid.force, 0.0, "nothing written on an error");
}

#[test]
fn misaligned_pointers_are_answered_with_their_code() {
    let blob = ball_blob();
    let residual = decoded(&blob);
    let mut storage = vec![0_u64; 2 * HCM_RESIDUAL_SIZE / 8];
    // 8-aligned but not 16-aligned: the `HcmResidual` a careless `malloc` could give.
    let base = storage.as_mut_ptr();
    let at = usize::from((base as usize).is_multiple_of(16));
    let out = base.wrapping_add(at).cast::<HcmResidual>();
    let mut law = extended(&[]);
    let mut force = [0.0_f32; 2];
    let mut info = std::mem::MaybeUninit::<HcmResidualInfo>::uninit();
    let mut copy = decoded(&blob);
    // SAFETY: the misaligned pointers are refused before any access; the others are
    // to live, aligned values.
    let statuses = unsafe {
        [
            hcm_residual_decode(blob.as_ptr(), blob.len(), out),
            hcm_residual_info(misaligned(&mut *copy), info.as_mut_ptr()),
            hcm_residual_info(&*residual, misaligned(&mut *info.as_mut_ptr())),
            hcm_law_force(misaligned(&mut law.base), CONTACT, &mut force[0]),
            hcm_law_force(&LN, CONTACT, misaligned(&mut force[0])),
            hcm_extended_law_force(misaligned(&mut law), CONTACT, &mut force[0]),
            hcm_law_validate(misaligned(&mut law.base)),
            hcm_extended_law_validate(misaligned(&mut law)),
            hcm_hybrid_force(&law, misaligned(&mut *copy), CONTACT, null_mut()),
        ]
    };
    for (i, status) in statuses.into_iter().enumerate() {
        assert_eq!(status, HcmStatus::Misaligned, "call {i}");
    }
    assert!(storage.iter().all(|word| *word == 0), "nothing written");
}

#[test]
fn unknown_kinds_domains_lengths_and_undecoded_residuals() {
    let blob = ball_blob();
    let mut force = 0.0_f32;
    let bad_kind = HcmLaw { kind: 6, ..LN };
    let bad_effect = HcmEffect {
        kind: 99,
        ..NO_EFFECT
    };
    let too_many = HcmExtendedLaw {
        effect_count: 5,
        ..extended(&[])
    };
    let negative = HcmLaw {
        parameters: [-1.0, 1.5, 0.9, 0.0, 0.0],
        ..LN
    };
    let twice = extended(&[NO_EFFECT, NO_EFFECT]);
    let zeroed = HcmResidual {
        storage: [0; HCM_RESIDUAL_SIZE],
    };
    let mut out = HcmResidual {
        storage: [0; HCM_RESIDUAL_SIZE],
    };
    // SAFETY: every pointer is to a live, aligned value; the impossible length is
    // refused before the blob is read.
    unsafe {
        assert_eq!(
            hcm_law_force(&bad_kind, CONTACT, &mut force),
            HcmStatus::BadParameter
        );
        let law = extended(&[bad_effect]);
        assert_eq!(
            hcm_extended_law_force(&law, CONTACT, &mut force),
            HcmStatus::BadParameter
        );
        let status = hcm_extended_law_force(&too_many, CONTACT, &mut force);
        assert_eq!(status, HcmStatus::BadParameter);
        assert_eq!(hcm_law_validate(&LN), HcmStatus::Ok);
        assert_eq!(hcm_law_validate(&negative), HcmStatus::OutOfDomain);
        assert_eq!(hcm_extended_law_validate(&twice), HcmStatus::OutOfDomain);
        let mut hybrid = std::mem::zeroed();
        let status = hcm_hybrid_force(&extended(&[]), &zeroed, CONTACT, &mut hybrid);
        assert_eq!(status, HcmStatus::NotDecoded);
        let status = hcm_residual_decode(blob.as_ptr(), usize::MAX, &mut out);
        assert_eq!(status, HcmStatus::BadLength);
    }
    assert_eq!(force, 0.0, "nothing written on an error");
}

#[test]
fn results_are_the_cores_bit_for_bit() {
    let blob = ball_blob();
    let residual = decoded(&blob);
    let mlp: Mlp<3, 16, 1, 2, F32Weights> = decode(&blob).unwrap();
    let core_law: AnyNormalLaw<f32> = LankaraniNikravesh::from_array([6.9e9, 1.49, 0.929]).into();
    let mut core_extended = ExtendedLaw::new(core_law);
    core_extended
        .effects
        .push(ViscousDamping { coefficient: 40.0 }.into())
        .unwrap();
    core_extended
        .effects
        .push(
            Adhesion {
                pull_off_force: 3.0,
            }
            .into(),
        )
        .unwrap();
    let viscous = HcmEffect {
        kind: HCM_EFFECT_VISCOUS_DAMPING,
        parameters: [40.0, 0.0, 0.0, 0.0, 0.0],
    };
    let adhesion = HcmEffect {
        kind: HCM_EFFECT_ADHESION,
        parameters: [3.0, 0.0, 0.0, 0.0, 0.0],
    };
    let law = extended(&[viscous, adhesion]);
    // Inside the envelope in every input (its δ̇0 range may be a single value), then
    // outside it in δ̇0, then out of contact.
    let middle = |i: usize| 0.5 * (mlp.envelope.min[i] + mlp.envelope.max[i]);
    let inside = [middle(0), middle(1), middle(2)];
    let far = [inside[0], inside[1], 3.0 * inside[2] + 1.0];
    let apart = [-1e-6, inside[1], inside[2]];
    assert!(
        mlp.envelope.min[0] >= 0.0,
        "the envelope's δ lies in contact"
    );
    let cases = [
        (inside, true, 0),
        (far, false, 0b100),
        (apart, false, 0b001),
    ];
    for (input, used, outside) in cases {
        let contact = HcmContact {
            depth: input[0],
            rate: input[1],
            approach_speed: input[2],
            max_depth: input[0].max(0.0),
        };
        let (state, memory) = (contact.indentation(), contact.memory());
        let (mut force, mut hybrid) = (f32::NAN, unsafe { std::mem::zeroed::<HcmHybridForce>() });
        // SAFETY: every pointer is to a live, aligned value.
        unsafe {
            assert_eq!(hcm_law_force(&LN, contact, &mut force), HcmStatus::Ok);
            assert_eq!(force.to_bits(), core_law.normal_force(&state).to_bits());
            assert_eq!(
                hcm_extended_law_force(&law, contact, &mut force),
                HcmStatus::Ok
            );
            let physics = ContactModel::physics(core_extended.clone());
            let expected = physics.physics_normal_force(&state, &memory);
            assert_eq!(force.to_bits(), expected.to_bits());
            assert_eq!(
                hcm_hybrid_force(&law, &*residual, contact, &mut hybrid),
                HcmStatus::Ok
            );
        }
        let hcm = ContactModel::physics(core_extended.clone()).with_residual(&mlp);
        let (expected, evaluated) = hcm.normal_force(&state, &memory, &input);
        assert_eq!(hybrid.force.to_bits(), expected.to_bits(), "{input:?}");
        assert_eq!(
            hybrid.residual_used,
            evaluated == Evaluated::PhysicsAndResidual
        );
        assert_eq!(hybrid.residual_used, used, "{input:?}");
        assert_eq!(hybrid.outside_envelope, outside, "{input:?}");
        if used {
            assert_ne!(
                hybrid.force, hybrid.physics,
                "the residual corrects the physics"
            );
        }
    }
}
