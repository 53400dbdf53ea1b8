//! The firmware's fixed table of evaluations, compiled twice: into the firmware (for
//! `thumbv7em-none-eabihf`, printed over semihosting) and into the host test
//! `tests/controller/firmware.rs` (`#[path]`), which evaluates the same inputs in f32 on the host
//! and requires every printed bit pattern to match.
//!
//! It depends on `hcm-core` and `nalgebra` only, allocates nothing, and reports each
//! result through `emit(group, item, bits)`: the raw `f32::to_bits` of every number
//! (a flag or count as a plain `u32`), so the comparison is exact.

pub mod ball;
pub mod table;

use hcm_core::effect::{ContactMemory, ExtendedLaw};
use hcm_core::law::{AnyNormalLaw, Indentation, LawKind, NormalLaw};
use hcm_core::model::{ContactModel, Evaluated, Residual};
use hcm_core::residual::{decode, BlobError, Int8Weights, Mlp};
use hcm_core::wrench::ContactWrench;
use table::{MEMORY, STATES};

/// The ball's residual network with f32 weights: 3 inputs [δ (m), δ̇ (m/s), δ̇0 (m/s)],
/// two hidden layers of 16, one output (normal-force correction, N).
pub type BallResidual = Mlp<3, 16, 1, 2>;
/// The same network with int8 hidden → hidden weights.
pub type BallResidualInt8 = Mlp<3, 16, 1, 2, Int8Weights>;

/// Where results go: group (`law`, `hcm`, …), item (`hertz`, `f32`, …), raw bits.
pub type Emit<'a> = &'a mut dyn FnMut(&str, &str, &[u32]);

/// Everything decoded once at start-up: the two residuals and the ball's HCMs.
pub struct Fixture {
    /// The ball's HCM: its PM2 plus the f32 residual.
    pub hcm_f32: ContactModel<f32, BallResidual>,
    /// The ball's HCM with the int8 residual.
    pub hcm_int8: ContactModel<f32, BallResidualInt8>,
}

impl Fixture {
    /// Decodes the embedded blobs; fails only if a blob is not a valid 3-16-16-1 blob.
    pub fn decode() -> Result<Self, BlobError> {
        let f32_residual: BallResidual = decode(table::BALL_F32_BLOB)?;
        let int8_residual: BallResidualInt8 = decode(table::BALL_INT8_BLOB)?;
        let physics = ContactModel::physics(AnyNormalLaw::from(table::ball_pm2()));
        Ok(Fixture {
            hcm_f32: physics.clone().with_residual(f32_residual),
            hcm_int8: physics.with_residual(int8_residual),
        })
    }

    /// The HCM's inputs [δ (m), δ̇ (m/s), δ̇0 (m/s)]: four inside the f32 residual's
    /// training envelope (at fractions of its δ and δ̇ ranges, δ̇0 at the training
    /// value), one apart (0 N) and one whose δ̇0 is 10 % off, well beyond the envelope's
    /// tolerance for this input constant in training (0.03 m/s): physics only.
    pub fn hcm_inputs(&self) -> [[f32; 3]; 6] {
        let envelope = &self.hcm_f32.residual.envelope;
        let at = |i: usize, fraction: f32| {
            envelope.min[i] + (envelope.max[i] - envelope.min[i]) * fraction
        };
        let approach = envelope.min[2];
        [
            [at(0, 0.1), at(1, 0.9), approach],
            [at(0, 0.5), at(1, 0.5), approach],
            [at(0, 0.9), at(1, 0.55), approach],
            [at(0, 0.3), at(1, 0.05), approach],
            [-1e-6, at(1, 0.5), approach],
            [at(0, 0.5), at(1, 0.5), approach * 1.1],
        ]
    }
}

/// One HCM evaluation: the force (N) and whether the residual took part.
#[inline]
pub fn hcm_force<R: Residual<f32>>(model: &ContactModel<f32, R>, input: &[f32; 3]) -> (f32, bool) {
    let indentation = Indentation {
        depth: input[0],
        rate: input[1],
        approach_speed: input[2],
    };
    let (force, evaluated) = model.normal_force(&indentation, &ContactMemory::touch_down(), input);
    (force, evaluated == Evaluated::PhysicsAndResidual)
}

/// Evaluates the whole table and emits every result, in a fixed order.
pub fn evaluate_all(fixture: &Fixture, emit: Emit<'_>) {
    laws(emit);
    effects(emit);
    friction_and_wrench(emit);
    hcm(fixture, emit);
    ball::emit_run(&fixture.hcm_f32, emit);
}

/// Every catalogued normal law at every state: f_n (N).
fn laws(emit: Emit<'_>) {
    for kind in LawKind::ALL {
        let law = table::law(kind);
        emit(
            "law",
            kind.name(),
            &STATES.map(|s| law.normal_force(&s).to_bits()),
        );
    }
}

/// Every catalogued effect added alone to the ball's PM2, at every state: f_n (N);
/// then air drag, −c·|v|·v (N) for each velocity.
fn effects(emit: Emit<'_>) {
    for effect in table::effects() {
        let mut extended = ExtendedLaw::new(table::ball_pm2().into());
        // Capacity MAX_EFFECTS ≥ 1: the push cannot fail.
        let _ = extended.effects.push(effect);
        let forces = STATES.map(|s| extended.normal_force(&s, &MEMORY).to_bits());
        emit("effect", effect.name(), &forces);
    }
    let (drag, velocities) = table::air_drag();
    let mut bits = [0_u32; 6];
    for (out, velocity) in bits.chunks_exact_mut(3).zip(&velocities) {
        write_vector(out, &drag.force(velocity));
    }
    emit("effect", drag.name(), &bits);
}

/// STEP friction (Eq 10–11) for each slip case: f_f (N, 3 components); and the
/// Eq 1 wrench from it: F1, T1, F2, T2 (N, N·m, 12 components).
fn friction_and_wrench(emit: Emit<'_>) {
    let law = table::friction();
    let mut friction_bits = [0_u32; 12];
    let mut wrench_bits = [0_u32; 48];
    let cases = table::slip_cases();
    for (i, case) in cases.iter().enumerate() {
        let f = law.force(&case.relative_velocity, &case.normal, case.normal_force);
        write_vector(&mut friction_bits[3 * i..], &f);
        let wrench = ContactWrench::assemble(
            case.normal_force,
            &case.normal,
            &f,
            &case.arm_1,
            &case.arm_2,
        );
        let out = &mut wrench_bits[12 * i..];
        write_vector(&mut out[0..], &wrench.force_1);
        write_vector(&mut out[3..], &wrench.torque_1);
        write_vector(&mut out[6..], &wrench.force_2);
        write_vector(&mut out[9..], &wrench.torque_2);
    }
    emit("friction", "step", &friction_bits);
    emit("wrench", "eq1", &wrench_bits);
}

/// The HCM (PM2 + residual) with f32 and int8 weights: per input the force (N) and
/// 1 if the residual took part (0 if not); and the residual's raw output (N).
fn hcm(fixture: &Fixture, emit: Emit<'_>) {
    let inputs = fixture.hcm_inputs();
    emit(
        "input",
        "hcm",
        inputs.map(|x| x.map(f32::to_bits)).as_flattened(),
    );
    emit(
        "hcm",
        "f32",
        inputs
            .map(|x| force_bits(&fixture.hcm_f32, &x))
            .as_flattened(),
    );
    emit(
        "hcm",
        "int8",
        inputs
            .map(|x| force_bits(&fixture.hcm_int8, &x))
            .as_flattened(),
    );
    let raw_f32 = inputs.map(|x| fixture.hcm_f32.residual.evaluate(&x)[0].to_bits());
    let raw_int8 = inputs.map(|x| fixture.hcm_int8.residual.evaluate(&x)[0].to_bits());
    emit("residual", "f32", &raw_f32);
    emit("residual", "int8", &raw_int8);
}

fn force_bits<R: Residual<f32>>(model: &ContactModel<f32, R>, input: &[f32; 3]) -> [u32; 2] {
    let (force, residual_on) = hcm_force(model, input);
    [force.to_bits(), u32::from(residual_on)]
}

fn write_vector(out: &mut [u32], v: &nalgebra::Vector3<f32>) {
    for (slot, x) in out.iter_mut().zip(v.iter()) {
        *slot = x.to_bits();
    }
}
